/* SPDX-License-Identifier: MIT */
#include <stdio.h>
#include <string.h>

#include "np_common.h"
#include "np_cmd.h"
#include "np_unit.h"

int np_cmd_units(int argc, char **argv)
{
    if (argc > 1 && (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0)) {
        puts("usage: noisepipe units\n\nLists every unit with its default configuration, fields, accuracy contract and\nconfiguration keys (name, range, default, meaning).");
        return NP_EXIT_OK;
    }
    if (argc > 1) {
        np_err("units", "unexpected argument '%s'", argv[1]);
        return NP_EXIT_USAGE;
    }
    const np_unit *u;
    for (size_t i = 0; (u = np_unit_at(i)) != NULL; i++) {
        np_unit_cfg cfg;
        char buf[256];
        np_unit_fields f;
        np_unit_cfg_default(u, &cfg);
        np_unit_cfg_format(u, &cfg, buf, sizeof buf);
        u->fields(&cfg, &f);
        printf("%s: %s\n  default configuration: %s\n  inputs: ", u->name, u->summary, buf);
        for (unsigned k = 0; k < f.n_in; k++)
            printf("%s%s (%s)", k ? ", " : "", f.in[k].name, f.in[k].format);
        printf("\n  outputs: ");
        for (unsigned k = 0; k < f.n_out; k++)
            printf("%s%s (%s)", k ? ", " : "", f.out[k].name, f.out[k].format);
        printf("\n  accuracy: |output - float reference| <= %g LSB required, %.4f LSB guaranteed by the error argument\n",
               u->tolerance_lsb, u->error_bound_lsb(&cfg));
        printf("  keys (name, range, default, meaning; a derived default follows the other keys):\n");
        for (const np_unit_key *k = u->keys; k && k->name; k++) {
            char range[128], def[112];
            np_unit_key_range(k, range, sizeof range);
            np_unit_key_text(k, &cfg, def, sizeof def);
            if (k->derive)
                snprintf(def + strlen(def), sizeof def - strlen(def), " derived");
            printf("    %-12s %-17s %-11s %s\n", k->name, range, def, k->meaning);
        }
    }
    return NP_EXIT_OK;
}
