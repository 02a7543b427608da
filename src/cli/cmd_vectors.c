/* SPDX-License-Identifier: MIT */
/* noisepipe vectors - write golden test vectors (the generator of TestFloat's testfloat_gen). */
#include <stdio.h>
#include <string.h>

#include "np_common.h"
#include "np_cmd.h"
#include "np_vec.h"

static const char usage[] =
    "usage: noisepipe vectors --unit U [--config k=v,...] [--seed S] [--level 1|2] [-n N]\n"
    "                         [--format text|readmemh|coe] [-o FILE]\n"
    "\n"
    "Writes golden test vectors for unit U: its hand-annotated boundary cases (level 2 adds\n"
    "their +-1 neighbours), bit patterns per input field (walking ones and zeros, all ones,\n"
    "all zeros, alternating), and weighted random inputs from a seeded xoshiro256**. Each\n"
    "line holds the inputs, the bit-exact model's outputs and the float reference, as\n"
    "fixed-width hex (format: docs/vectors.md). Same unit, config, seed, level and -n give a\n"
    "byte-identical file.\n"
    "\n"
    "  --unit U        the unit (noisepipe units lists them)\n"
    "  --config k=v,.. its configuration (default: the unit's default)\n"
    "  --seed S        seed of the random cases (default 1)\n"
    "  --level 1|2     1: a few thousand vectors (default); 2: far more, with 10^6 random\n"
    "  -n N            number of random cases (default 1024 at level 1, 1000000 at level 2)\n"
    "  --format F      text (default), readmemh ($readmemh words {1'b1, inputs, outputs}),\n"
    "                  coe (the same words as a Xilinx .coe)\n"
    "  -o FILE         write FILE (atomically: complete or not at all); default stdout\n";

int np_cmd_vectors(int argc, char **argv)
{
    const char *cmd = "vectors", *unit = NULL, *spec = NULL, *path = NULL, *v;
    uint64_t seed = 1, level = 1, n_random = UINT64_MAX;
    np_vec_format fmt = NP_VEC_TEXT;
    for (int i = 1; i < argc; i++) {
        int r;
        if (np_vec_is_help(argv[i])) {
            fputs(usage, stdout);
            return NP_EXIT_OK;
        } else if ((r = np_vec_opt(cmd, argc, argv, &i, "--unit", &v)) != 0) {
            unit = v;
        } else if ((r = np_vec_opt(cmd, argc, argv, &i, "--config", &v)) != 0) {
            spec = v;
        } else if ((r = np_vec_opt(cmd, argc, argv, &i, "--seed", &v)) != 0) {
            if (r > 0 && np_vec_opt_u64(cmd, "--seed", v, 0, UINT64_MAX, &seed) != 0)
                return NP_EXIT_USAGE;
        } else if ((r = np_vec_opt(cmd, argc, argv, &i, "--level", &v)) != 0) {
            if (r > 0 && np_vec_opt_u64(cmd, "--level", v, 1, 2, &level) != 0)
                return NP_EXIT_USAGE;
        } else if ((r = np_vec_opt(cmd, argc, argv, &i, "-n", &v)) != 0) {
            if (r > 0 && np_vec_opt_u64(cmd, "-n", v, 0, UINT64_MAX - 1u, &n_random) != 0)
                return NP_EXIT_USAGE;
        } else if ((r = np_vec_opt(cmd, argc, argv, &i, "--format", &v)) != 0) {
            if (r > 0 && (np_vec_format_parse(v, &fmt) != 0 || fmt == NP_VEC_RESULTS)) {
                np_err(cmd, "--format '%s': expected text, readmemh or coe", v);
                return NP_EXIT_USAGE;
            }
        } else if ((r = np_vec_opt(cmd, argc, argv, &i, "-o", &v)) != 0) {
            path = v;
        } else {
            np_err(cmd, "unexpected argument '%s' (see noisepipe vectors --help)", argv[i]);
            return NP_EXIT_USAGE;
        }
        if (r < 0)
            return NP_EXIT_USAGE;
    }
    np_vec_header h;
    char err[NP_VEC_ERRLEN];
    if (np_vec_opt_header(cmd, unit, spec, &h) != 0)
        return NP_EXIT_USAGE;
    np_vec_output out = { path, fmt };
    if (np_vec_generate(&h, (unsigned)level, seed, n_random, &out, 1, err, sizeof err) != 0) {
        np_err(cmd, "%s", err);
        return NP_EXIT_USAGE;
    }
    return NP_EXIT_OK;
}
