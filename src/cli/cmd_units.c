/* SPDX-License-Identifier: MIT */
#include <stdio.h>
#include <string.h>

#include "np_cli.h"
#include "np_cmd.h"
#include "np_unit.h"

int np_cmd_units(int argc, char **argv)
{
    if (argc > 1 && (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0)) {
        puts("usage: noisepipe units\n\nLists every unit with its default configuration, fields and accuracy contract.");
        return NP_EXIT_OK;
    }
    if (argc > 1) {
        np_err("units", "unexpected argument '%s'", argv[1]);
        return NP_EXIT_USAGE;
    }
    for (size_t i = 0; np_units[i]; i++) {
        const np_unit *u = np_units[i];
        np_unit_cfg cfg;
        char buf[256];
        np_unit_fields f;
        u->cfg_default(&cfg);
        u->cfg_format(&cfg, buf, sizeof buf);
        u->fields(&cfg, &f);
        printf("%s: %s\n  default configuration: %s\n  inputs: ", u->name, u->summary, buf);
        for (unsigned k = 0; k < f.n_in; k++)
            printf("%s%s (%s)", k ? ", " : "", f.in[k].name, f.in[k].format);
        printf("\n  outputs: ");
        for (unsigned k = 0; k < f.n_out; k++)
            printf("%s%s (%s)", k ? ", " : "", f.out[k].name, f.out[k].format);
        printf("\n  accuracy: |output - float reference| <= %g LSB required, %.4f LSB guaranteed by the error argument\n",
               u->tolerance_lsb, u->error_bound_lsb(&cfg));
    }
    return NP_EXIT_OK;
}
