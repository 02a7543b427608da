/* SPDX-License-Identifier: MIT */
/*
 * noisepipe render --aa: the options of the adaptive supersampling report
 * of seed 001 (np_report_aa.h, docs/aacount.md) and the scene's "aa"
 * section they override; the report itself is src/report/report_aa.c.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "np_common.h"
#include "np_report_aa.h"
#include "np_unit.h"
#include "render_cli.h"

static const char *const CMD = "render --aa";

typedef struct aa_opts {
    unsigned ms[3], n_m;
    int have[8];
    double v[8]; /* c_d c_n c_s t_min t_edge luma_taps tile (scene overrides) */
    const char *out;
    const char *scene;
    unsigned gt_q;
    int sweep;
} aa_opts;

static const char *const keys[] = { "c_d", "c_n", "c_s", "t_min", "t_edge", "luma_taps", "tile", NULL };

/*
 * Defaults where the scene's "aa" section gives no constants (marble,
 * wood): all three metrics, constants from the sweep in docs/aacount.md
 * (c_d per world^2).
 */
enum { DEF_KEYS = 3 };
static const double def_c[DEF_KEYS] = { 1.0e4, 8.0, 32.0 };

static int parse_spec(const char *spec, aa_opts *o)
{
    char buf[512];
    snprintf(buf, sizeof buf, "%s", spec);
    int in_m = 0;
    for (char *tok = strtok(buf, ","); tok; tok = strtok(NULL, ",")) {
        char *eq = strchr(tok, '=');
        const char *key = NULL, *val = tok;
        if (eq) {
            *eq = '\0';
            key = tok;
            val = eq + 1;
            in_m = strcmp(key, "m") == 0;
        } else if (!in_m) {
            np_err(CMD, "--aa %s: expected KEY=VALUE (m=2|3|4, c_d, c_n, c_s, t_min, t_edge, luma_taps, tile)", spec);
            return -1;
        }
        if (!key || strcmp(key, "m") == 0) {
            unsigned m;
            if (np_unit_parse_uint(val, 2, 4, &m) != 0 || o->n_m >= 3) {
                np_err(CMD, "--aa m=%s: expected 2, 3 or 4 (at most three)", val);
                return -1;
            }
            o->ms[o->n_m++] = m;
            continue;
        }
        int k = 0;
        while (keys[k] && strcmp(keys[k], key) != 0)
            k++;
        char *end;
        double v = strtod(val, &end);
        if (!keys[k] || *val == '\0' || *end != '\0' || !(v >= 0.0) || !isfinite(v)) {
            np_err(CMD, "--aa %s=%s: unknown key or not a number >= 0", key, val);
            return -1;
        }
        o->have[k] = 1;
        o->v[k] = v;
    }
    if (o->n_m == 0) {
        np_err(CMD, "--aa %s: no m given (m=2|3|4)", spec);
        return -1;
    }
    return 0;
}

static void usage(FILE *f)
{
    fputs("usage: noisepipe render --aa m=2|3|4[,m...][,KEY=VALUE...] [-o DIR] [--gt Q] [--sweep] SCENE.json\n"
          "The adaptive supersampling of seed 001 on the G-buffer: S (one sample a pixel), the unit\n"
          "aacount per pixel, the chosen samples shaded on texel, the unit's resolve; per m the % of\n"
          "samples over covered pixels, MSE (x 1e-5, [0,1] scale) and PSNR both ways (the paper's\n"
          "10 log10(255^2/MSE) and the consistent 10 log10(1/MSE)) against full m x m and against\n"
          "the Q x Q ground truth (default 16; 0: none), and the cycles of the unit, the shading and\n"
          "the resolve, beside the paper's Table 1 (Sponza).\n"
          "  KEY: c_d (per world^2), c_n, c_s, t_min, t_edge (0..1), luma_taps (4|5), tile (0|6):\n"
          "       over the scene's \"aa\" section; a scene without constants gets c_d=1e4,c_n=8,c_s=32\n"
          "  -o DIR   the adaptive images and the sample-density images per metric (Fig. 8), PNG\n"
          "  --sweep  with -o: error against samples over a scale of the constants, t_min and t_edge\n"
          "           (DIR/aacount-sweep-SCENE.{svg,md})\n",
          f);
}

/* The scene's aa over the command's overrides and the defaults. */
static void scene_aa(np_scene *sc, const aa_opts *o)
{
    np_scene_aa *a = &sc->aa;
    int any = a->have_cd || a->have_cn || a->have_cs;
    int *have[3] = { &a->have_cd, &a->have_cn, &a->have_cs };
    double *val[3] = { &a->c_d, &a->c_n, &a->c_s };
    for (int k = 0; k < DEF_KEYS; k++) {
        if (!any) {
            *have[k] = 1;
            *val[k] = def_c[k];
        }
        if (o->have[k]) {
            *have[k] = 1;
            *val[k] = o->v[k];
        }
    }
    if (!a->present) {
        a->t_min = 16.0 / 255.0;
        a->t_edge = 0.125;
        a->luma_taps = 4;
    }
    if (o->have[3])
        a->t_min = o->v[3];
    if (o->have[4])
        a->t_edge = o->v[4];
    if (o->have[5])
        a->luma_taps = (unsigned)o->v[5];
    if (o->have[6])
        a->tile = (unsigned)o->v[6];
}

int np_render_aa_main(int argc, char **argv)
{
    aa_opts o;
    memset(&o, 0, sizeof o);
    o.gt_q = 16;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
            usage(stdout);
            return NP_EXIT_OK;
        } else if (strcmp(argv[i], "--aa") == 0 && i + 1 < argc) {
            if (parse_spec(argv[++i], &o))
                return NP_EXIT_USAGE;
        } else if ((strcmp(argv[i], "-o") == 0 || strcmp(argv[i], "--out") == 0) && i + 1 < argc) {
            o.out = argv[++i];
        } else if (strcmp(argv[i], "--gt") == 0 && i + 1 < argc) {
            if (np_unit_parse_uint(argv[++i], 0, 64, &o.gt_q)) {
                np_err(CMD, "--gt %s: expected 0..64", argv[i]);
                return NP_EXIT_USAGE;
            }
        } else if (strcmp(argv[i], "--sweep") == 0) {
            o.sweep = 1;
        } else if (argv[i][0] == '-') {
            np_err(CMD, "unknown option '%s' (noisepipe render --aa --help)", argv[i]);
            return NP_EXIT_USAGE;
        } else if (!o.scene) {
            o.scene = argv[i];
        } else {
            np_err(CMD, "one scene at a time ('%s' and '%s')", o.scene, argv[i]);
            return NP_EXIT_USAGE;
        }
    }
    if (!o.scene) {
        np_err(CMD, "no scene (noisepipe render --aa m=3 SCENE.json)");
        return NP_EXIT_USAGE;
    }
    if (o.sweep && !o.out) {
        np_err(CMD, "--sweep needs -o DIR");
        return NP_EXIT_USAGE;
    }
    char err[1024];
    np_scene sc;
    if (np_scene_load(o.scene, &sc, err, sizeof err)) {
        np_err(CMD, "%s", err);
        return NP_EXIT_USAGE;
    }
    scene_aa(&sc, &o);
    int rc = np_report_aa(&sc, o.ms, o.n_m, o.gt_q, o.out, o.sweep, o.scene, CMD);
    np_scene_free(&sc);
    return rc;
}
