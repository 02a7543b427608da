/* SPDX-License-Identifier: MIT */
/*
 * gen_kat - print the known-answer table of a registered unit (np_kat.h):
 *
 *   gen_kat UNIT [--config SPEC]... [--inputs FILE] [-n ROWS] [-o OUT]
 *
 * A relative --inputs path is taken from OUT's directory. With -o, the
 * table is written to OUT only when complete (it may be its own --inputs).
 * The conformance test regenerates every checked-in table the same way.
 */
#include <stdio.h>
#include <string.h>

#include "np_kat.h"

int main(int argc, char **argv)
{
    const char *out = NULL;
    char *args[64];
    int n = 0;
    for (int i = 1; i < argc && n < 64; i++) {
        if (strcmp(argv[i], "-o") == 0 && i + 1 < argc)
            out = argv[++i];
        else
            args[n++] = argv[i];
    }
    char dir[4096] = ".", err[512], tmp[4200];
    if (out)
        np_kat_dir_of(out, dir, sizeof dir);
    np_kat_spec s;
    if (n == 0 || np_kat_parse(n, args, dir, &s, err, sizeof err) != 0) {
        fprintf(stderr, "gen_kat: %s\nusage: gen_kat UNIT [--config SPEC]... [--inputs FILE] [-n ROWS] [-o OUT]\n",
                n ? err : "no unit named");
        return 2;
    }
    FILE *f = stdout;
    if (out) {
        snprintf(tmp, sizeof tmp, "%s.tmp", out);
        if (!(f = fopen(tmp, "w"))) {
            fprintf(stderr, "gen_kat: %s: cannot write\n", tmp);
            return 2;
        }
    }
    int rc = np_kat_write(&s, f, err, sizeof err);
    if (out && (fclose(f) != 0 || rc != 0 || rename(tmp, out) != 0)) {
        if (rc == 0)
            snprintf(err, sizeof err, "%s: cannot write", out);
        remove(tmp);
        rc = -1;
    }
    if (rc != 0) {
        fprintf(stderr, "gen_kat: %s\n", err);
        return 2;
    }
    return 0;
}
