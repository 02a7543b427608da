/* SPDX-License-Identifier: MIT */
/* noisepipe verify - check vectors on the cycle model or a device's results (TestFloat's testfloat_ver). */
#include <stdio.h>
#include <string.h>

#include "np_common.h"
#include "np_cmd.h"
#include "np_vec.h"

static const char usage[] =
    "usage: noisepipe verify [--errors N] [--tolerance LSB] [--results FILE] [--seed S]\n"
    "                        [--no-stalls] VECTORS|-\n"
    "\n"
    "Reads a vector file (- = stdin), recomputes every expected output with the bit-exact\n"
    "model and the float reference, and checks the outputs under test:\n"
    "  - a device's results, from --results FILE (one line of output fields per vector, or a\n"
    "    $writememh file) or from one extra field per output on each vector line (as\n"
    "    `noisepipe device` writes them): bit for bit and against the reference;\n"
    "  - otherwise the cycle-accurate model's, driven with random input bubbles and output\n"
    "    stalls: bit for bit, in order, and each output exactly `latency` clocks after its\n"
    "    input when no stall came in between.\n"
    "Prints `inputs => got expected: want (reason)` per failing vector, an error summary\n"
    "(max |error|, % correctly rounded, histogram) and a one-line verdict.\n"
    "\n"
    "  --errors N       stop after N failing vectors (default 20; 0 = never)\n"
    "  --tolerance LSB  allowed |output - reference| (default: the unit's contract)\n"
    "  --results FILE   the device's results\n"
    "  --seed S         seed of the bubbles and stalls (default 1)\n"
    "  --no-stalls      stream one input per clock, output always ready\n"
    "\n"
    "Exit status: 0 no errors, 1 errors found, 2 bad usage or bad input.\n";

int np_cmd_verify(int argc, char **argv)
{
    const char *cmd = "verify", *path = NULL, *v;
    np_verify_opts o = { .cmd = cmd, .max_errors = 20, .tolerance = -1.0, .traffic = 1, .seed = 1 };
    for (int i = 1; i < argc; i++) {
        int r;
        if (np_vec_is_help(argv[i])) {
            fputs(usage, stdout);
            return NP_EXIT_OK;
        } else if ((r = np_vec_opt(cmd, argc, argv, &i, "--errors", &v)) != 0) {
            if (r > 0 && np_vec_opt_u64(cmd, "--errors", v, 0, UINT64_MAX, &o.max_errors) != 0)
                return NP_EXIT_USAGE;
        } else if ((r = np_vec_opt(cmd, argc, argv, &i, "--tolerance", &v)) != 0) {
            if (r > 0 && np_vec_opt_double(cmd, "--tolerance", v, &o.tolerance) != 0)
                return NP_EXIT_USAGE;
        } else if ((r = np_vec_opt(cmd, argc, argv, &i, "--results", &v)) != 0) {
            o.results = v;
        } else if ((r = np_vec_opt(cmd, argc, argv, &i, "--seed", &v)) != 0) {
            if (r > 0 && np_vec_opt_u64(cmd, "--seed", v, 0, UINT64_MAX, &o.seed) != 0)
                return NP_EXIT_USAGE;
        } else if (strcmp(argv[i], "--no-stalls") == 0) {
            o.traffic = 0;
            r = 1;
        } else if (argv[i][0] == '-' && argv[i][1] != '\0') {
            np_err(cmd, "unknown option '%s' (see noisepipe verify --help)", argv[i]);
            return NP_EXIT_USAGE;
        } else if (path) {
            np_err(cmd, "one vector file only ('%s' and '%s')", path, argv[i]);
            return NP_EXIT_USAGE;
        } else {
            path = argv[i];
            r = 1;
        }
        if (r < 0)
            return NP_EXIT_USAGE;
    }
    if (!path) {
        np_err(cmd, "which vector file? (a path, or - for stdin; see noisepipe verify --help)");
        return NP_EXIT_USAGE;
    }
    if (o.results && strcmp(o.results, "-") == 0 && strcmp(path, "-") == 0) {
        np_err(cmd, "the vectors and the results cannot both come from stdin");
        return NP_EXIT_USAGE;
    }
    return np_verify(path, &o, stdout);
}
