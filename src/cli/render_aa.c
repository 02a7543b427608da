/* SPDX-License-Identifier: MIT */
/*
 * noisepipe render --aa: the adaptive supersampling report of seed 001
 * (np_render_aa.h, docs/aacount.md), per m a row shaped like the paper's
 * Table 1 beside the paper's numbers.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "np_common.h"
#include "np_outfile.h"
#include "np_image.h"
#include "np_plot.h"
#include "np_render_aa.h"
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

/* The paper's Table 1 (Sponza, adaptive against full): samples %, MSE x1e-5, PSNR as printed. */
static const double paper[5][3] = { { 0, 0, 0 }, { 0, 0, 0 }, { 57.8, 5.0, 91.14 }, { 53.40, 3.08, 93.24 },
                                    { 53.14, 3.79, 92.34 } };

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

static double psnr_paper(double mse) { return np_gbuf_psnr_paper(mse); }
static double psnr(double mse) { return np_gbuf_psnr(mse); }

/* "MSE x 1e5 | paper / consistent PSNR" of mse, or "- | -" without one (no ground truth). */
static const char *mse_cells(char *buf, size_t len, double mse)
{
    if (isnan(mse))
        snprintf(buf, len, "- | -");
    else
        snprintf(buf, len, "%.3f | %.2f / %.2f", mse * 1e5, psnr_paper(mse), psnr(mse));
    return buf;
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

/* A count image: s / n as a grey ramp (white = n), background dark blue. */
static int write_density(const char *path, const np_aa_frame *f, const uint8_t *s, char *err, size_t errlen)
{
    const size_t npx = (size_t)f->g.w * f->g.h;
    uint8_t *img = malloc(npx * 3);
    if (!img)
        return np_errf(err, errlen, "out of memory");
    for (size_t p = 0; p < npx; p++) {
        if (!f->covered[p]) {
            img[3 * p] = 16;
            img[3 * p + 1] = 16;
            img[3 * p + 2] = 48;
            continue;
        }
        unsigned v = s[p] ? (255u * s[p] + f->g.n / 2u) / f->g.n : 0u;
        img[3 * p] = img[3 * p + 1] = img[3 * p + 2] = (uint8_t)v;
    }
    int rc = np_image_write_png(path, f->g.w, f->g.h, img, err, errlen);
    free(img);
    return rc;
}

/* Error against samples over the constants (scale), t_min and t_edge: an SVG and a Markdown table. */
static int sweep(const aa_opts *o, const np_aa_frame *f, const np_aacount_cfg *base, char *err, size_t errlen)
{
    enum { NS = 13 };
    static const double scale[NS] = { 0, 0.0625, 0.125, 0.25, 0.5, 1, 2, 4, 8, 16, 32, 64, 128 };
    static const unsigned tmins[6] = { 0, 8, 16, 32, 64, 128 };
    static const unsigned tedges[6] = { 0, 16, 32, 64, 128, 255 };
    double x[3][NS], y[3][NS];
    size_t nx[3] = { 0, 0, 0 };
    char path[4096];
    snprintf(path, sizeof path, "%s/aacount-sweep-%s-m%u.md", o->out, f->sc->name, f->g.m);
    FILE *md = fopen(path, "w");
    if (!md)
        return np_errf(err, errlen, "cannot write %s", path);
    fprintf(md, "# aacount: error against samples, %s, m = %u\n\nGenerated by `noisepipe render --aa m=%u --sweep -o DIR %s`."
                " Base: c_d=%u c_n=%u/4 c_s=%u/16 t_min=%u t_edge=%u/256 (unit keys).\n\n"
                "| series | value | samples %% | MSE vs full (x1e-5) | MSE vs GT (x1e-5) |\n| --- | ---: | ---: | ---: | ---: |\n",
            f->sc->name, f->g.m, f->g.m, o->scene, base->c_d, base->c_n, base->c_s, base->t_min, base->t_edge);
    for (int series = 0; series < 3; series++) {
        unsigned cnt = series == 0 ? NS : 6u;
        for (unsigned i = 0; i < cnt; i++) {
            np_aacount_cfg c = *base;
            double val;
            if (series == 0) {
                val = scale[i];
                c.c_d = (uint32_t)fmin(4294967295.0, floor((double)base->c_d * val + 0.5));
                c.c_n = (uint8_t)fmin(255.0, floor((double)base->c_n * val + 0.5));
                c.c_s = (uint16_t)fmin(65535.0, floor((double)base->c_s * val + 0.5));
            } else if (series == 1) {
                val = tmins[i];
                c.t_min = (uint8_t)tmins[i];
            } else {
                val = tedges[i];
                c.t_edge = (uint8_t)tedges[i];
            }
            np_aa_result r;
            if (np_aa_run(f, &c, NULL, 0, &r))
                return np_errf(err, errlen, "out of memory");
            x[series][nx[series]] = r.pct;
            y[series][nx[series]] = fmax(r.mse_full, 1e-9) * 1e5;
            nx[series]++;
            fprintf(md, "| %s | %g | %.2f | %.3f | %.3f |\n",
                    series == 0 ? "scale of c_d, c_n, c_s" : series == 1 ? "t_min (luma codes)" : "t_edge (/256)", val,
                    r.pct, r.mse_full * 1e5, r.mse_gt * 1e5);
            np_aa_result_free(&r);
        }
    }
    fclose(md);
    snprintf(path, sizeof path, "%s/aacount-sweep-%s-m%u.svg", o->out, f->sc->name, f->g.m);
    FILE *svg = fopen(path, "w");
    if (!svg)
        return np_errf(err, errlen, "cannot write %s", path);
    char title[128];
    snprintf(title, sizeof title, "aacount on %s, m = %u: error against samples", f->sc->name, f->g.m);
    np_plot p = { title, "samples shaded, % of full", "MSE against full m x m (x 1e-5, [0,1] scale)", 0, 100, 0, 0, 1,
                  60.0, 5.0, "60 %", "MSE 5e-5" };
    np_plot_series s[3] = {
        { "scale of c_d, c_n, c_s (0 .. 128)", "#1f77b4", x[0], y[0], nx[0], 1, 1 },
        { "t_min 0 .. 128", "#d62728", x[1], y[1], nx[1], 1, 1 },
        { "t_edge 0 .. 255/256", "#2ca02c", x[2], y[2], nx[2], 1, 1 },
    };
    np_plot_svg(svg, &p, s, 3);
    fclose(svg);
    return 0;
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
    np_render_unit_cfg us[NP_RENDER_MAX_UNITS];
    int nu = np_render_units(&sc, NULL, NULL, us, err, sizeof err);
    const np_render_unit_cfg *tex = NULL, *fd = NULL;
    for (int i = 0; i < nu; i++) {
        if (strcmp(us[i].u->name, "texel") == 0)
            tex = &us[i];
        if (strcmp(us[i].u->name, "fdiff") == 0)
            fd = &us[i];
    }
    if (!tex) {
        np_err(CMD, "%s: the unit texel does not render this scene%s%s", o.scene, nu < 0 ? ": " : "", nu < 0 ? err : "");
        np_scene_free(&sc);
        return NP_EXIT_USAGE;
    }
    if (o.out && np_mkdir_p(o.out)) {
        np_err(CMD, "-o %s: cannot create the folder", o.out);
        np_scene_free(&sc);
        return NP_EXIT_USAGE;
    }
    int rc = NP_EXIT_OK;
    double *gt = NULL;
    if (o.gt_q) {
        gt = malloc((size_t)sc.width * sc.height * 3 * sizeof *gt);
        if (!gt || np_gbuf_ground_truth(&sc, o.gt_q, gt, err, sizeof err)) {
            np_err(CMD, "ground truth: %s", gt ? err : "out of memory");
            free(gt);
            np_scene_free(&sc);
            return NP_EXIT_FAIL;
        }
    }
    if (o.gt_q)
        printf("scene %s (%ux%u), shading on texel (%s), ground truth %ux%u\n", sc.name, sc.width, sc.height, tex->text,
               o.gt_q, o.gt_q);
    else
        printf("scene %s (%ux%u), shading on texel (%s), no ground truth (--gt 0)\n", sc.name, sc.width, sc.height,
               tex->text);
    printf("samples %%: shaded samples over m^2 x covered pixels. MSE on the [0, 1] scale x 1e-5, covered pixels,\n"
           "against full m x m (the paper's reference) and against the ground truth. PSNR paper = 10 log10(255^2 /\n"
           "MSE) (the paper's Table 1 column), consistent = 10 log10(1 / MSE). Cycles: the unit aacount over every\n"
           "window (parallel pipe / serial schedule), shading of the chosen samples on texel (S's included), the\n"
           "resolve. Last column: the paper's Table 1 row for this m (samples %%, MSE x 1e-5 against full, PSNR paper).\n\n");
    char gth[32] = "no truth";
    if (o.gt_q)
        snprintf(gth, sizeof gth, "%ux%u truth", o.gt_q, o.gt_q);
    printf("| rate | method | samples %% | MSE vs full (1e-5) | PSNR paper / consistent | MSE vs %s (1e-5) | PSNR paper /"
           " consistent | unit cycles (parallel / serial) | shading cycles | resolve cycles | paper: samples %%, MSE, PSNR |\n"
           "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | --- |\n",
           gth);
    /* The acceptance "adaptive 4x4 at <= 9 samples a pixel beats full 3x3 against the truth", and why not. */
    double full3_gt = (double)NAN, ad4_gt = (double)NAN, ad4_spp = 0, or4_gt = (double)NAN, or4_spp = 0;
    for (unsigned k = 0; k < o.n_m && rc == NP_EXIT_OK; k++) {
        unsigned m = o.ms[k];
        np_aa_frame f;
        if (np_aa_frame_build(&sc, m, tex, gt, &f, err, sizeof err)) {
            np_err(CMD, "m=%u: %s", m, err);
            rc = NP_EXIT_FAIL;
            break;
        }
        np_aacount_cfg c;
        np_aa_cfg_from_scene(&sc, m, f.g.z_near, f.g.z_far, &c);
        np_aa_result r;
        if (np_aa_run(&f, &c, NULL, 1, &r)) {
            np_err(CMD, "m=%u: out of memory", m);
            np_aa_frame_free(&f);
            rc = NP_EXIT_FAIL;
            break;
        }
        const size_t npx = (size_t)f.g.w * f.g.h;
        double full_gt = gt ? np_gbuf_mse(f.img_full, gt, f.covered, npx) : (double)NAN;
        double s_gt = gt ? np_gbuf_mse(f.img_s, gt, f.covered, npx) : (double)NAN;
        double s_full = np_gbuf_mse(f.img_s, f.img_full_d, f.covered, npx);
        uint64_t fd_cycles = 0;
        double fd_mse = (double)NAN;
        if (fd) {
            /* fdiff cannot skip samples inside a span: full supersampling only; its image against texel's */
            uint8_t *tmp = malloc(npx * f.g.n * 3), *img = malloc(npx * 3);
            np_gbuf_cost fc;
            if (tmp && img && np_gbuf_shade(&f.g, fd->u, fd->cfg.bytes, NULL, tmp, &fc) == 0) {
                fd_cycles = fc.cycles;
                np_gbuf_resolve(&f.g, NULL, tmp, img);
                fd_mse = np_gbuf_mse(img, f.img_full_d, f.covered, npx);
            }
            free(tmp);
            free(img);
        }
        char c1[64], c2[64];
        printf("| %ux%u | 1 sample (S) | %.2f | %s | %s | - | %llu | - | |\n", m, m, 100.0 / (double)f.g.n,
               mse_cells(c1, sizeof c1, s_full), mse_cells(c2, sizeof c2, s_gt), (unsigned long long)f.cost_s.cycles);
        printf("| %ux%u | full, texel | 100 | - | - | %s | - | %llu | %llu | 100 |\n", m, m,
               mse_cells(c2, sizeof c2, full_gt), (unsigned long long)f.cost_full.cycles,
               (unsigned long long)f.resolve_full_cycles);
        if (fd)
            printf("| %ux%u | full, fdiff | 100 | %.4f (against texel's) | | | | - | %llu | %llu | |\n", m, m,
                   fd_mse * 1e5, (unsigned long long)fd_cycles, (unsigned long long)f.resolve_full_cycles);
        printf("| %ux%u | adaptive, texel | %.2f | %s | %s | %llu / %llu | %llu |"
               " %llu | %.2f %%, %.2f, %.2f dB |\n",
               m, m, r.pct, mse_cells(c1, sizeof c1, r.mse_full), mse_cells(c2, sizeof c2, r.mse_gt),
               (unsigned long long)r.unit_cycles,
               (unsigned long long)r.unit_cycles_serial, (unsigned long long)r.shade_cycles,
               (unsigned long long)r.resolve_cycles, paper[m][0], paper[m][1], paper[m][2]);
        double P = (double)r.covered_pixels * f.g.n;
        printf("|  | metrics alone | depth %.2f %%, normal %.2f %%, luma %.2f %% | unit keys c_d=%u c_n=%u c_s=%u t_min=%u"
               " t_edge=%u luma_taps=%u tile=%u | covered pixels %llu%s | | | | | | |\n",
               c.depth ? 100.0 * (double)r.samples_d / P : 0.0, c.normal ? 100.0 * (double)r.samples_n / P : 0.0,
               c.luma ? 100.0 * (double)r.samples_s / P : 0.0, c.c_d, c.c_n, c.c_s, c.t_min, c.t_edge, c.luma_taps,
               c.tile, (unsigned long long)r.covered_pixels, r.pipe_mismatch ? "; CYCLE MODEL DIFFERS" : "");
        if (r.pipe_mismatch)
            rc = NP_EXIT_FAIL;
        if (gt && m == 3)
            full3_gt = full_gt;
        if (gt && m == 4) {
            ad4_gt = r.mse_gt;
            ad4_spp = r.pct * 16.0 / 100.0;
            if (np_aa_colour_oracle(&f, 9.0, &or4_gt, &or4_spp))
                or4_spp = 0;
        }
        if (o.out) {
            char path[4096];
            const char *nm[5] = { "adaptive", "s", "sd", "sn", "ss" };
            const uint8_t *im[5] = { r.img, r.s, r.sd, r.sn, r.ss };
            for (int q = 0; q < 5 && rc == NP_EXIT_OK; q++) {
                snprintf(path, sizeof path, "%s/%s_aa%u_%s.png", o.out, sc.name, m, nm[q]);
                int e = q == 0 ? np_image_write_png(path, f.g.w, f.g.h, im[q], err, sizeof err)
                               : write_density(path, &f, im[q], err, sizeof err);
                if (e) {
                    np_err(CMD, "%s", err);
                    rc = NP_EXIT_FAIL;
                }
            }
            if (rc == NP_EXIT_OK && o.sweep && sweep(&o, &f, &c, err, sizeof err)) {
                np_err(CMD, "%s", err);
                rc = NP_EXIT_FAIL;
            }
        }
        np_aa_result_free(&r);
        np_aa_frame_free(&f);
    }
    if (rc == NP_EXIT_OK && gt && ad4_spp > 0) {
        const int ok9 = ad4_spp <= 9.0, known3 = !isnan(full3_gt), beats = ok9 && known3 && ad4_gt < full3_gt;
        printf("\nadaptive 4x4: %.2f samples a pixel (%s 9), MSE %.3fe-5 against the %ux%u truth", ad4_spp,
               ok9 ? "<=" : "over", ad4_gt * 1e5, o.gt_q, o.gt_q);
        if (known3)
            printf("; full 3x3 %.3fe-5: %s\n", full3_gt * 1e5,
                   beats ? "beats full 3x3" : ok9 ? "does NOT beat full 3x3" : "over the 9-sample budget");
        else
            printf(" (add m=3 to compare with full 3x3)\n");
        if (!beats && or4_spp > 0)
            printf("why: the three metrics read depth, normals and the lumas of S (one sample a pixel); texture\n"
                   "detail inside a pixel moves none of them, so the samples go to edges, not to the texture. A count\n"
                   "that saw every sample's colour (np_aa_colour_oracle, not the unit) reaches %.3fe-5 at %.2f samples\n"
                   "a pixel. The search of the PIN knobs and constants: docs/aacount.md (aa_render.boxes_knobs).\n",
                   or4_gt * 1e5, or4_spp);
    }
    free(gt);
    np_scene_free(&sc);
    return rc;
}
