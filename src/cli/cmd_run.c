/* SPDX-License-Identifier: MIT */
/*
 * noisepipe run - the main job, on the embedded defaults:
 *   1. "classic3 golden vectors": level-1 vectors for the classic unit,
 *      exported as text, $readmemh and .coe, then verified on the
 *      cycle-accurate model with random bubbles and stalls;
 *   2. the seed's wood scene (built into the program) rendered with the float
 *      reference and both scanline texturing units, with their error summary
 *      (noisepipe render).
 */
#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "np_common.h"
#include "np_cmd.h"
#include "np_vec.h"

static const char usage[] =
    "usage: noisepipe run [-o DIR] [--seed S]\n"
    "\n"
    "The main job, on the embedded defaults:\n"
    "1. \"classic3 golden vectors\": writes level-1 golden vectors for the classic noise unit\n"
    "   (default configuration) into DIR as text (.vec), $readmemh (.memh) and Xilinx .coe,\n"
    "   verifies them on the cycle-accurate model with random input bubbles and output\n"
    "   stalls, and prints the latency, the error against the float reference (max |error|,\n"
    "   % correctly rounded, histogram) and the verdict;\n"
    "2. renders the seed's wood scene (built in) with the float reference and both scanline\n"
    "   texturing units into DIR/render (OpenEXR + PNG) and prints their error summary\n"
    "   (the same as noisepipe render -o DIR/render).\n"
    "\n"
    "  -o DIR     output directory (default ./noisepipe-out; created if needed)\n"
    "  --seed S   seed of the random vectors (default 1)\n"
    "\n"
    "Exit status: 0 no errors, 1 errors found, 2 bad usage or an I/O problem.\n";

static const char scene_unit[] = "classic3";

/* mkdir -p: 0, or -1 with errno. */
static int make_dirs(const char *dir)
{
    char p[4096];
    if (snprintf(p, sizeof p, "%s", dir) >= (int)sizeof p) {
        errno = ENAMETOOLONG;
        return -1;
    }
    for (char *s = p + 1; *s; s++) {
        if (*s != '/')
            continue;
        *s = '\0';
        if (mkdir(p, 0777) != 0 && errno != EEXIST)
            return -1;
        *s = '/';
    }
    if (mkdir(p, 0777) != 0 && errno != EEXIST)
        return -1;
    return 0;
}

int np_cmd_run(int argc, char **argv)
{
    const char *cmd = "run", *dir = "noisepipe-out", *v;
    uint64_t seed = 1;
    for (int i = 1; i < argc; i++) {
        int r;
        if (np_vec_is_help(argv[i])) {
            fputs(usage, stdout);
            return NP_EXIT_OK;
        } else if ((r = np_vec_opt(cmd, argc, argv, &i, "-o", &v)) != 0) {
            dir = v;
        } else if ((r = np_vec_opt(cmd, argc, argv, &i, "--seed", &v)) != 0) {
            if (r > 0 && np_vec_opt_u64(cmd, "--seed", v, 0, UINT64_MAX, &seed) != 0)
                return NP_EXIT_USAGE;
        } else {
            np_err(cmd, "unexpected argument '%s' (see noisepipe run --help)", argv[i]);
            return NP_EXIT_USAGE;
        }
        if (r < 0)
            return NP_EXIT_USAGE;
    }
    if (make_dirs(dir) != 0) {
        np_err(cmd, "cannot create directory %s: %s", dir, strerror(errno));
        return NP_EXIT_USAGE;
    }
    static const struct {
        np_vec_format fmt;
        const char *ext;
    } kinds[] = { { NP_VEC_TEXT, "vec" }, { NP_VEC_READMEMH, "memh" }, { NP_VEC_COE, "coe" } };
    enum { N_KINDS = sizeof kinds / sizeof kinds[0] };
    char path[N_KINDS][4200], err[NP_VEC_ERRLEN];
    np_vec_output outs[N_KINDS];
    np_vec_header h;
    if (np_vec_opt_header(cmd, scene_unit, NULL, &h) != 0)
        return NP_EXIT_USAGE;
    printf("scene \"classic3 golden vectors\": unit %s (%s), level 1, seed %llu\n", h.unit->name,
           h.cfg_text, (unsigned long long)seed);
    for (unsigned k = 0; k < N_KINDS; k++) {
        snprintf(path[k], sizeof path[k], "%s/%s-l1-seed%llu.%s", dir, scene_unit,
                 (unsigned long long)seed, kinds[k].ext);
        outs[k] = (np_vec_output){ path[k], kinds[k].fmt };
    }
    if (np_vec_generate(&h, 1, seed, UINT64_MAX, outs, N_KINDS, err, sizeof err) != 0) {
        np_err(cmd, "%s", err);
        return NP_EXIT_USAGE;
    }
    printf("wrote %s (%llu vectors: %s), %s, %s\n", path[0], (unsigned long long)h.count, h.sources,
           path[1], path[2]);
    fflush(stdout);
    np_verify_opts o = { .cmd = cmd, .max_errors = 20, .tolerance = -1.0, .traffic = 1, .seed = 1 };
    int rc = np_verify(path[0], &o, stdout);
    if (rc == NP_EXIT_USAGE)
        return rc;
    char render_dir[4200];
    snprintf(render_dir, sizeof render_dir, "%s/render", dir);
    printf("\nscene \"wood\" (Kameya & Hart, equation 23; embedded copy of vectors/scenes/wood.json)\n");
    fflush(stdout);
    char *args[] = { (char *)"render", (char *)"-o", render_dir, (char *)"embedded:wood", NULL };
    int rc2 = np_cmd_render(4, args);
    return rc != NP_EXIT_OK ? rc : rc2;
}
