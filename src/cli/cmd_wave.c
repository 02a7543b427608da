/* SPDX-License-Identifier: MIT */
/*
 * noisepipe wave - the Gerstner wave unit on a scene and its figures
 * (docs/wave.md):
 *   wave SCENE.json [--frames N] [--first T] [--grid N] [--budget C] [-o DIR]
 *        frames of the scene through the bit-exact model: cycles, boxes
 *        visible, height statistics; with -o, a PNG of each frame's height.
 *   wave check [--size N] [--frames N] [--trains N] [--regs S]
 *        the model against the double reference from the same registers on
 *        N x N points at F frames spread over 0 .. 2^32 - 1 (the last ones
 *        next to 2^32): max error and the histogram.
 *   wave bench SCENARIO1 SCENARIO2 [-o DIR]
 *        cycles and model time from 64^2 to 512^2, the culling structure, the
 *        effects' costs, the budget curve (a plot with -o).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "np_common.h"
#include "np_cmd.h"
#include "np_gbuf.h"
#include "np_image.h"
#include "np_render.h"
#include "np_scene.h"
#include "np_plot.h"
#include "np_report.h"
#include "np_unit.h"
#include "np_wave_json.h"
#include "np_wave_ref.h"

static const char *const USAGE =
    "usage: noisepipe wave SCENE.json [--frames N] [--first T] [--grid N] [--budget CYCLES] [-o DIR [--render TEMPLATE]]\n"
    "       noisepipe wave check [--size N] [--frames N] [--trains N] [--regs S]\n"
    "       noisepipe wave bench SCENARIO1.json SCENARIO2.json [-o DIR]\n"
    "\n"
    "SCENE: frames of a wave scene (docs/wave.md, \"Scenes\") through the bit-exact model of the wave unit:\n"
    "  per frame the cycles, the boxes visible and the height's range; -o DIR writes DIR/NAME-fNNNNNN.png;\n"
    "  --render TEMPLATE also renders it lit through the G-buffer renderer (the template's image, camera,\n"
    "  light and colour map): DIR/NAME-lit-fNNNNNN.png.\n"
    "  A scene whose surface may fold (1.3 sum k (A + a) > 1) is refused (exit 2) unless it sets allow_fold.\n"
    "check: the model against the double reference from the same registers: N^2 points (default 512) at\n"
    "  F frames (default 1000) from 0 to 2^32 - 1, the last third next to 2^32; exit 1 over 1 LSB.\n"
    "bench: scenario 1's cycles and model time from 64^2 to 512^2, scenario 2's culling, the effects'\n"
    "  costs and the time-budget curve (-o DIR: DIR/wave_budget.svg).\n";

static int parse_u(const char *opt, const char *v, uint64_t lo, uint64_t hi, uint64_t *out)
{
    if (!v || np_parse_u64(v, lo, hi, out) != 0) {
        np_err("wave", "%s: expected a whole number in %llu..%llu, not '%s'", opt, (unsigned long long)lo,
               (unsigned long long)hi, v ? v : "(nothing)");
        return -1;
    }
    return 0;
}

/* --- check --- */

static int cmd_check(int argc, char **argv)
{
    uint64_t size = 512, frames = 1000, trains = 2, regs = 1;
    for (int i = 1; i < argc; i++) {
        uint64_t *dst = strcmp(argv[i], "--size") == 0     ? &size
                        : strcmp(argv[i], "--frames") == 0 ? &frames
                        : strcmp(argv[i], "--trains") == 0 ? &trains
                        : strcmp(argv[i], "--regs") == 0   ? &regs
                                                           : NULL;
        if (!dst) {
            np_err("wave", "check: unknown option '%s'", argv[i]);
            return NP_EXIT_USAGE;
        }
        uint64_t hi = dst == &size ? 4096 : dst == &frames ? 1000000 : dst == &trains ? NP_WAVE_MAX_TRAINS : 65535;
        if (parse_u(argv[i], i + 1 < argc ? argv[i + 1] : NULL, dst == &regs ? 0 : 1, hi, dst) != 0)
            return NP_EXIT_USAGE;
        i++;
    }
    np_wave_unit u;
    memset(&u, 0, sizeof u);
    u.c = np_wave_cfg_default();
    u.c.trains = (unsigned)trains;
    np_wave_regs_test(regs, (unsigned)trains, &u.r);
    double bound = np_wave_error_bound_lsb(&u), worst = 0.0;
    uint64_t hist[9] = { 0 }, n = 0;
    uint32_t worst_t = 0;
    np_progress pr;
    np_progress_start(&pr, "wave check", frames);
    for (uint64_t f = 0; f < frames; f++) {
        /* Two thirds spread over [0, 2^32), the last third the frames just below 2^32. */
        uint64_t third = frames - frames / 3u;
        uint32_t t = f < third ? (uint32_t)(f * (UINT64_C(4294967296) / third)) : (uint32_t)(UINT64_C(4294967296) - (frames - f));
        for (unsigned j = 0; j < size; j++)
            for (unsigned i = 0; i < size; i++) {
                np_wave_in in = { (uint16_t)i, (uint16_t)j, t, 0, (uint16_t)i, (uint16_t)(j + 8u), (uint8_t)(i * 31u ^ j),
                                  16384 };
                np_wave_out o;
                double r[3];
                np_wave_eval(&u, &in, &o);
                np_ref_wave(&u, &in, r);
                const int16_t got[3] = { o.y, o.dx, o.dz };
                for (unsigned k = 0; k < 3; k++) {
                    double d = fabs((double)got[k] - r[k] * 1024.0);
                    if (d > worst) {
                        worst = d;
                        worst_t = t;
                    }
                    unsigned b = (unsigned)(d * 8.0);
                    hist[b > 8 ? 8 : b]++;
                    n++;
                }
            }
        np_progress_update(&pr, f + 1);
    }
    np_progress_end(&pr);
    printf("wave check: %llu^2 points x %llu frames (0 .. 2^32 - 1), trains=%llu regs=%llu: %llu outputs\n",
           (unsigned long long)size, (unsigned long long)frames, (unsigned long long)trains, (unsigned long long)regs,
           (unsigned long long)n);
    printf("|model - reference| in 1/8 LSB bins:");
    for (unsigned b = 0; b < 9; b++)
        printf(" %llu", (unsigned long long)hist[b]);
    printf("\nmax %.4f LSB (at frame %u); bound %.4f; %s\n", worst, worst_t, bound,
           worst <= 1.0 ? "every output within 1 LSB" : "OVER 1 LSB");
    return worst <= 1.0 ? NP_EXIT_OK : NP_EXIT_FAIL;
}

/* --- scenes --- */

static int load(const char *path, np_wave_scene *s, unsigned frames[3], unsigned grid)
{
    char err[512] = "";
    unsigned dropped = 0;
    if (np_wave_scene_read(path, s, frames, err, sizeof err) != 0) {
        np_err("wave", "%s", err);
        return -1;
    }
    if (grid)
        s->grid = grid;
    if (np_wave_scene_prepare(s, &dropped, err, sizeof err) != 0) {
        np_err("wave", "%s: %s", path, err);
        np_wave_scene_free(s);
        return -1;
    }
    if (dropped)
        fprintf(stderr, "noisepipe wave: %s: %u train(s) above the grid's Nyquist limit left out\n", path, dropped);
    return 0;
}

static double rms_diff(const int32_t *a, const int32_t *b, size_t n)
{
    double s = 0.0;
    for (size_t q = 0; q < n; q++) {
        double d = (double)(a[q] - b[q]) / 1024.0;
        s += d * d;
    }
    return sqrt(s / (double)n);
}

static int write_png(const char *dir, const char *name, uint32_t t, const np_wave_scene *s, const int32_t *y)
{
    size_t n2 = (size_t)s->grid * s->grid;
    uint8_t *rgb = malloc(n2 * 3);
    if (!rgb)
        return -1;
    double hm = 0.0;
    for (unsigned k = 0; k < s->nbox; k++)
        hm = s->box[k].hmax > hm ? s->box[k].hmax : hm;
    hm = hm > 0.0 ? hm : 1.0;
    for (unsigned j = 0; j < s->grid; j++)
        for (unsigned i = 0; i < s->grid; i++) {
            size_t q = (size_t)j * s->grid + i, o = ((size_t)(s->grid - 1u - j) * s->grid + i) * 3;
            if (s->depth[q] <= 0.0f) {
                double h = -(double)s->depth[q] / (s->isl_height > 0.0 ? s->isl_height : 1.0);
                h = h > 1.0 ? 1.0 : h;
                rgb[o] = (uint8_t)(110 + 80 * h);
                rgb[o + 1] = (uint8_t)(150 + 60 * h);
                rgb[o + 2] = (uint8_t)(80 + 60 * h);
            } else {
                double v = 0.5 + (double)y[q] / 1024.0 / (2.0 * hm);
                v = v < 0.0 ? 0.0 : v > 1.0 ? 1.0 : v;
                rgb[o] = (uint8_t)(20 + 120 * v);
                rgb[o + 1] = (uint8_t)(60 + 150 * v);
                rgb[o + 2] = (uint8_t)(120 + 135 * v);
            }
        }
    char path[1024], err[256];
    snprintf(path, sizeof path, "%s/%s-f%010u.png", dir, name, t);
    int rc = np_image_write_png(path, s->grid, s->grid, rgb, err, sizeof err);
    if (rc != 0)
        np_err("wave", "%s", err);
    free(rgb);
    return rc;
}

/*
 * The frame rendered lit through the G-buffer renderer (np_gbuf.h, issue 15):
 * the template scene tpl (image, camera, light, texture) with two meshes
 * added, the displaced water grid (p0 + (dx, y, dz)) and the terrain where it
 * rises above -2 m; texture coordinate T = y / hm on the water (in [-1, 1])
 * and 2 + h / island height on land, so the template's colour map colours
 * both. Shaded on the texel unit, one sample a pixel. 0, or -1.
 */
static int render_lit(const char *tpl, const char *dir, const char *name, uint32_t t, const np_wave_scene *s,
                      const int32_t *y, const int32_t *dx, const int32_t *dz)
{
    static np_scene sc;
    char err[512];
    if (np_scene_load(tpl, &sc, err, sizeof err) != 0) {
        np_err("wave", "%s", err);
        return -1;
    }
    unsigned n = s->grid;
    double hm = 0.0;
    for (unsigned k = 0; k < s->nbox; k++)
        hm = s->box[k].hmax > hm ? s->box[k].hmax : hm;
    hm = hm > 0.0 ? hm : 1.0;
    np_scene_mesh *m = realloc(sc.mesh, (sc.n_mesh + 2u) * sizeof *m);
    if (!m) {
        np_scene_free(&sc);
        return -1;
    }
    sc.mesh = m;
    int rc = -1;
    for (unsigned w = 0; w < 2; w++) {
        np_scene_mesh *me = &sc.mesh[sc.n_mesh];
        memset(me, 0, sizeof *me);
        me->n_vert = n * n;
        me->p = malloc((size_t)me->n_vert * sizeof *me->p);
        me->t = malloc((size_t)me->n_vert * sizeof *me->t);
        me->tri = malloc((size_t)2 * (n - 1u) * (n - 1u) * sizeof *me->tri);
        sc.n_mesh++;
        if (!me->p || !me->t || !me->tri)
            goto done;
        for (unsigned j = 0; j < n; j++)
            for (unsigned i = 0; i < n; i++) {
                size_t q = (size_t)j * n + i;
                double x = i * s->spacing, z = j * s->spacing, h = -(double)s->depth[q];
                if (w == 0) {
                    me->p[q][0] = x + dx[q] / 1024.0;
                    me->p[q][1] = y[q] / 1024.0;
                    me->p[q][2] = z + dz[q] / 1024.0;
                    me->t[q][0] = x;
                    me->t[q][1] = y[q] / 1024.0 / hm;
                    me->t[q][2] = z;
                } else {
                    me->p[q][0] = x;
                    me->p[q][1] = h;
                    me->p[q][2] = z;
                    me->t[q][0] = x;
                    me->t[q][1] = 2.0 + (h > 0.0 ? h : 0.0) / (s->isl_height > 0.0 ? s->isl_height : 1.0);
                    me->t[q][2] = z;
                }
            }
        for (unsigned j = 0; j + 1u < n; j++)
            for (unsigned i = 0; i + 1u < n; i++) {
                uint32_t a = j * n + i, b = a + 1u, c = a + n, d = c + 1u;
                if (w == 1 && s->depth[a] > 2.0f && s->depth[b] > 2.0f && s->depth[c] > 2.0f && s->depth[d] > 2.0f)
                    continue; /* terrain well under water: hidden by the water */
                uint32_t(*tr)[3] = &me->tri[me->n_tri];
                tr[0][0] = a, tr[0][1] = c, tr[0][2] = b;
                tr[1][0] = b, tr[1][1] = c, tr[1][2] = d;
                me->n_tri += 2;
            }
        me->first_id = sc.n_prims;
        sc.n_prims += me->n_tri;
    }
    np_render_unit_cfg us[NP_RENDER_MAX_UNITS];
    int nu = np_render_units(&sc, NULL, NULL, us, err, sizeof err), k;
    for (k = 0; k < nu && strcmp(us[k].u->name, "texel") != 0; k++)
        ;
    if (nu < 0 || k == nu) {
        np_err("wave", "%s: %s", tpl, nu < 0 ? err : "the texel unit does not render it");
        goto done;
    }
    np_gbuf g;
    if (np_gbuf_build(&sc, 1, &g, err, sizeof err) != 0) {
        np_err("wave", "%s: %s", tpl, err);
        goto done;
    }
    uint8_t *rgb = malloc((size_t)sc.width * sc.height * 3);
    np_gbuf_cost cost;
    if (rgb && np_gbuf_shade_first(&g, us[k].u, us[k].cfg.bytes, rgb, &cost) == 0) {
        char path[1024];
        snprintf(path, sizeof path, "%s/%s-lit-f%010u.png", dir, name, t);
        rc = np_image_write_png(path, sc.width, sc.height, rgb, err, sizeof err);
        if (rc != 0)
            np_err("wave", "%s", err);
        else {
            /* The image's SHA-256 as a binary PPM (np_image_hash, as vectors/images/ keeps them): wave.lit_hashes. */
            char hex[65];
            np_image_hash(sc.width, sc.height, rgb, hex);
            printf("    lit: %s (%u triangles, %llu shading cycles on texel) sha256 %s\n", path, sc.n_prims,
                   (unsigned long long)cost.cycles, hex);
        }
    }
    free(rgb);
    np_gbuf_free(&g);
done:
    np_scene_free(&sc);
    return rc;
}

static const char *base_name(const char *path, char *buf, size_t n)
{
    const char *b = strrchr(path, '/');
    snprintf(buf, n, "%s", b ? b + 1 : path);
    char *dot = strrchr(buf, '.');
    if (dot)
        *dot = '\0';
    return buf;
}

static int cmd_scene(int argc, char **argv)
{
    const char *path = NULL, *dir = NULL, *tpl = NULL;
    uint64_t frames = 0, first = 0, grid = 0, budget = 0;
    int have_frames = 0, have_first = 0;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "-o") == 0 && i + 1 < argc) {
            dir = argv[++i];
            continue;
        }
        if (strcmp(argv[i], "--render") == 0 && i + 1 < argc) {
            tpl = argv[++i];
            continue;
        }
        uint64_t *dst = strcmp(argv[i], "--frames") == 0   ? &frames
                        : strcmp(argv[i], "--first") == 0  ? &first
                        : strcmp(argv[i], "--grid") == 0   ? &grid
                        : strcmp(argv[i], "--budget") == 0 ? &budget
                                                           : NULL;
        if (dst) {
            uint64_t hi = dst == &grid ? 4096 : dst == &frames ? 100000 : UINT32_MAX;
            uint64_t lo = dst == &grid ? 8 : dst == &frames ? 1 : 0;
            if (parse_u(argv[i], i + 1 < argc ? argv[i + 1] : NULL, lo, dst == &budget ? UINT64_MAX / 2 : hi, dst) != 0)
                return NP_EXIT_USAGE;
            have_frames |= dst == &frames;
            have_first |= dst == &first;
            i++;
        } else if (argv[i][0] == '-' || path) {
            np_err("wave", "unexpected argument '%s'\n%s", argv[i], USAGE);
            return NP_EXIT_USAGE;
        } else
            path = argv[i];
    }
    if (!path) {
        np_err("wave", "no scene\n%s", USAGE);
        return NP_EXIT_USAGE;
    }
    static np_wave_scene s;
    unsigned fr[3] = { 1, 0, 1 };
    if (load(path, &s, fr, (unsigned)grid) != 0)
        return NP_EXIT_USAGE;
    if (have_frames)
        fr[0] = (unsigned)frames;
    if (have_first)
        fr[1] = (unsigned)first;
    if (dir)
        mkdir(dir, 0777);
    size_t n2 = (size_t)s.grid * s.grid;
    int32_t *y = malloc(n2 * 4), *dx = malloc(n2 * 4), *dz = malloc(n2 * 4), *yf = malloc(n2 * 4);
    if (!y || !dx || !dz || !yf) {
        np_err("wave", "out of memory");
        return NP_EXIT_FAIL;
    }
    np_wave_plan full, plan;
    np_wave_plan_full(&s, &full);
    uint64_t full_cycles = np_wave_plan_cycles(&s, &full);
    if (budget)
        np_wave_plan_budget(&s, budget, &plan);
    else
        plan = full;
    size_t pts = 0;
    unsigned vis = 0;
    for (unsigned k = 0; k < s.nbox; k++) {
        pts += s.box[k].npts;
        vis += (unsigned)full.visible[k];
    }
    char name[256];
    base_name(path, name, sizeof name);
    printf("%s: %u^2 grid of %.4g m, %u boxes (%zu box points), %u visible; full frame %llu cycles%s\n", name, s.grid,
           s.spacing, s.nbox, pts, vis, (unsigned long long)full_cycles, budget ? "" : "");
    int rc = NP_EXIT_OK;
    for (unsigned f = 0; f < fr[0]; f++) {
        uint32_t t = fr[1] + f * fr[2];
        uint64_t cyc = np_wave_frame(&s, &plan, t, y, dx, dz);
        int32_t lo = 0, hi = 0;
        for (size_t q = 0; q < n2; q++) {
            lo = y[q] < lo ? y[q] : lo;
            hi = y[q] > hi ? y[q] : hi;
        }
        printf("  frame %u: %llu cycles, y in [%.3f, %.3f] m", t, (unsigned long long)cyc, lo / 1024.0, hi / 1024.0);
        if (budget) {
            np_wave_frame(&s, &full, t, yf, dx, dz);
            printf(", budget %llu: RMS height error against the full field %.4f m", (unsigned long long)budget,
                   rms_diff(y, yf, n2));
            if (cyc > budget) {
                printf(" (OVER BUDGET)");
                rc = NP_EXIT_FAIL;
            }
        }
        printf("\n");
        if (dir && write_png(dir, name, t, &s, y) != 0)
            rc = NP_EXIT_FAIL;
        if (dir && tpl && render_lit(tpl, dir, name, t, &s, y, dx, dz) != 0)
            rc = NP_EXIT_FAIL;
    }
    free(y);
    free(dx);
    free(dz);
    free(yf);
    np_wave_scene_free(&s);
    return rc;
}

/* --- bench --- */

/* NAND2 equivalents of the registry's wave unit in configuration spec (its test register set); -1 on error. */
static double unit_gates(const char *spec)
{
    const np_unit *u = np_unit_find("wave");
    static np_unit_cfg cfg;
    static np_unit_cost c;
    char err[256];
    if (!u || np_unit_configure(u, &cfg, spec, err, sizeof err) != 0 ||
        np_unit_cost_compute(u, &cfg, &np_cost_default, &c, err, sizeof err) != 0)
        return -1.0;
    return c.total;
}

/* The thread's CPU seconds: the machine may be shared, and the model runs on one thread. */
static double cpu_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

static double time_frame(const np_wave_scene *s, const np_wave_plan *p, int32_t *y, int32_t *dx, int32_t *dz, unsigned reps)
{
    double best = 1e30;
    for (unsigned r = 0; r < reps; r++) {
        double t0 = cpu_now();
        np_wave_frame(s, p, 1000u + r, y, dx, dz);
        double e = cpu_now() - t0;
        best = e < best ? e : best;
    }
    return best;
}

/*
 * The model's CPU time a frame for the linearity: best of reps runs of k
 * frames each (k frames of a small grid are about as much work as one frame
 * of 512^2). Each frame starts with cold caches, as a 512^2 frame does (its
 * points and grids are larger than the caches): an untimed write over 32 MB
 * before each, so a small grid repeated is not timed from a warm cache.
 */
static double time_frames(const np_wave_scene *s, const np_wave_plan *p, int32_t *y, int32_t *dx, int32_t *dz,
                          unsigned k, unsigned reps)
{
    enum { FLUSH = 32u << 20 };
    static unsigned char *junk;
    if (!junk)
        junk = malloc(FLUSH);
    double best = 1e30;
    for (unsigned r = 0; r < reps; r++) {
        double e = 0.0;
        for (unsigned f = 0; f < k; f++) {
            if (junk)
                memset(junk, (int)(f + r) & 0xff, FLUSH);
            double t0 = cpu_now();
            np_wave_frame(s, p, 1000u + f, y, dx, dz);
            e += cpu_now() - t0;
        }
        best = e < best ? e : best;
    }
    return best / k;
}

static int cmd_bench(int argc, char **argv)
{
    const char *sc[2] = { NULL, NULL }, *dir = NULL;
    unsigned ns = 0;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "-o") == 0 && i + 1 < argc)
            dir = argv[++i];
        else if (argv[i][0] != '-' && ns < 2)
            sc[ns++] = argv[i];
        else {
            np_err("wave", "bench: unexpected argument '%s'\n%s", argv[i], USAGE);
            return NP_EXIT_USAGE;
        }
    }
    if (ns != 2) {
        np_err("wave", "bench: two scenes (scenario 1, scenario 2)\n%s", USAGE);
        return NP_EXIT_USAGE;
    }
    static np_wave_scene s;
    const size_t nmax = (size_t)512 * 512;
    int32_t *y = malloc(nmax * 4), *dx = malloc(nmax * 4), *dz = malloc(nmax * 4), *yf = malloc(nmax * 4);
    if (!y || !dx || !dz || !yf)
        return NP_EXIT_FAIL;
    static const double paper_wc[4] = { 3.20, 12.2, 49.9, 199.0 };
    printf("Scenario 1 (%s): cycles and model time against points x trains (paper's Table 1: WC)\n", sc[0]);
    printf("| grid | points x trains | cycles | cycles / (points x trains) | model ms | ns / (point x train) | paper WC ms |\n");
    printf("| --- | ---: | ---: | ---: | ---: | ---: | ---: |\n");
    double nspt[4];
    for (unsigned g = 64, q = 0; g <= 512; g *= 2, q++) {
        if (load(sc[0], &s, NULL, g) != 0)
            return NP_EXIT_USAGE;
        np_wave_plan p;
        np_wave_plan_full(&s, &p);
        uint64_t pt = 0;
        for (unsigned k = 0; k < s.nbox; k++)
            pt += (uint64_t)s.box[k].npts * s.box[k].unit.r.n;
        uint64_t cyc = np_wave_plan_cycles(&s, &p);
        double ms = time_frames(&s, &p, y, dx, dz, (512u / g) * (512u / g), 5) * 1e3;
        nspt[q] = ms * 1e6 / (double)pt;
        printf("| %u^2 | %llu | %llu | %.4f | %.2f | %.1f | %.2f |\n", g, (unsigned long long)pt, (unsigned long long)cyc,
               (double)cyc / (double)pt, ms, nspt[q], paper_wc[q]);
        if (g == 512)
            printf("512^2: the bit-exact model takes %.2f ms a frame, %.1fx faster than the paper's 199 ms\n", ms, 199.0 / ms);
        np_wave_scene_free(&s);
    }
    /* Model time linear in points x trains: each grid's ns a point and train against their mean. */
    double mean = (nspt[0] + nspt[1] + nspt[2] + nspt[3]) / 4.0, dev = 0.0;
    for (unsigned q = 0; q < 4; q++)
        dev = fmax(dev, fabs(nspt[q] / mean - 1.0));
    printf("model time linearity, 64^2 .. 512^2 (thread CPU time, best of 5 runs of 64, 16, 4, 1 frames, each from "
           "cold caches): "
           "%.1f %.1f %.1f %.1f ns a point and train, mean %.1f; largest deviation %+.1f %%: %s\n",
           nspt[0], nspt[1], nspt[2], nspt[3], mean, 100.0 * dev, dev <= 0.10 ? "within +-10 %" : "NOT within +-10 %");
    /* Scenario 2: all visible against none visible; the saving per culled box. */
    if (load(sc[1], &s, NULL, 256) != 0)
        return NP_EXIT_USAGE;
    np_wave_plan all, none;
    np_wave_plan_full(&s, &all);
    for (unsigned k = 0; k < s.nbox; k++)
        all.visible[k] = 1, all.sel[k] = (1u << s.box[k].unit.r.n) - 1u;
    memset(&none, 0, sizeof none);
    none.noise = all.noise;
    uint64_t ca = np_wave_plan_cycles(&s, &all), cn = np_wave_plan_cycles(&s, &none);
    double ta = time_frame(&s, &all, y, dx, dz, 3) * 1e3, tn = time_frame(&s, &none, y, dx, dz, 3) * 1e3;
    printf("\nScenario 2 (%s, 256^2, %u boxes): all visible %llu cycles (model %.2f ms), none visible %llu cycles "
           "(%.3f ms): ratio %.1f (paper 57.7 / 0.6 ms = %.1f)\n",
           sc[1], s.nbox, (unsigned long long)ca, ta, (unsigned long long)cn, tn, (double)ca / (double)cn, 57.7 / 0.6);
    printf("saving per culled box (cycles; paper 3-10 ms at 256^2):");
    for (unsigned k = 0; k < s.nbox; k++) {
        np_wave_plan p = all;
        p.visible[k] = 0;
        p.sel[k] = 0;
        printf(" %llu", (unsigned long long)(ca - np_wave_plan_cycles(&s, &p)));
    }
    printf("\n");
    /* The effects' costs: model time with each effect alone on top of basic Gerstner, and the unit's gates. */
    printf("\nEffects on scenario 2, 256^2 (paper's Table 2 at 256^2: round waves 0.5, refraction 1.2, noise 3, "
           "irregular height 9.5 ms)\n| effect | model ms a frame (over basic) | cycles (over basic) | unit gates, one lane (over basic) | paper ms |\n"
           "| --- | ---: | ---: | ---: | ---: |\n");
    static const char *const fx_cfg[4] = { NULL, NULL, "trains=1,irr=0,cap=1", "trains=1,irr=1,cap=0" };
    double g0 = unit_gates("trains=1,irr=0,cap=0");
    static const unsigned fx[4] = { NP_WAVE_FX_ROUND, NP_WAVE_FX_REFRACTION, NP_WAVE_FX_NOISE, NP_WAVE_FX_IRREGULAR };
    static const char *const fxn[4] = { "round waves", "depth refraction", "noise", "irregular height" };
    static const double paper_fx[4] = { 0.5, 1.2, 3.0, 9.5 };
    double base_ms = 0.0;
    uint64_t base_cyc = 0;
    for (int e = -1; e < 4; e++) {
        np_wave_scene_free(&s);
        char err[512];
        unsigned d = 0;
        if (np_wave_scene_read(sc[1], &s, NULL, err, sizeof err) != 0) {
            np_err("wave", "%s", err);
            return NP_EXIT_USAGE;
        }
        s.grid = 256;
        s.effects = e < 0 ? 0u : fx[e];
        /* Host work per effect (the ray walk) is a set-up of the box: timed with the frame. */
        double t0 = cpu_now();
        if (np_wave_scene_prepare(&s, &d, err, sizeof err) != 0) {
            np_err("wave", "%s", err);
            return NP_EXIT_USAGE;
        }
        double prep = cpu_now() - t0;
        np_wave_plan p;
        np_wave_plan_full(&s, &p);
        for (unsigned k = 0; k < s.nbox; k++)
            p.visible[k] = 1, p.sel[k] = (1u << s.box[k].unit.r.n) - 1u;
        double ms = time_frame(&s, &p, y, dx, dz, 9) * 1e3;
        uint64_t cyc = np_wave_plan_cycles(&s, &p);
        if (e < 0) {
            base_ms = ms;
            base_cyc = cyc;
            printf("| basic Gerstner | %.2f (host set-up %.1f) | %llu | %.0f | 57.7 in all |\n", ms, prep * 1e3,
                   (unsigned long long)cyc, g0);
        } else
            printf("| %s | %+.2f (host set-up %.1f) | %+lld | %+.0f%s | %.1f |\n", fxn[e], ms - base_ms, prep * 1e3,
                   (long long)cyc - (long long)base_cyc, fx_cfg[e] ? unit_gates(fx_cfg[e]) - g0 : 0.0,
                   fx_cfg[e] ? "" : " (a per-ray phase: host)", paper_fx[e]);
    }
    /* The time budget: RMS height error against the full field as the budget grows. */
    np_wave_scene_free(&s);
    if (load(sc[1], &s, NULL, 256) != 0)
        return NP_EXIT_USAGE;
    np_wave_plan full;
    np_wave_plan_full(&s, &full);
    uint64_t fc = np_wave_plan_cycles(&s, &full);
    enum { NB = 21 };
    double bx[NB], by[NB];
    np_wave_frame(&s, &full, 600, yf, dx, dz);
    const uint64_t floor_c = (uint64_t)NP_WAVE_CYC_CULL * s.nbox; /* the culling: no budget below it can be met */
    printf("\nTime budget on scenario 2 (256^2, frame 600; PIN trains by descending A; from the culling's %llu cycles): "
           "budget fraction, cycles used / budget, RMS height error (m)\n",
           (unsigned long long)floor_c);
    for (unsigned q = 0; q < NB; q++) {
        uint64_t b = floor_c + (fc - floor_c) * q / (NB - 1u);
        np_wave_plan p;
        np_wave_plan_budget(&s, b, &p);
        uint64_t cyc = np_wave_frame(&s, &p, 600, y, dx, dz);
        bx[q] = (double)q / (NB - 1u);
        by[q] = rms_diff(y, yf, (size_t)s.grid * s.grid);
        printf("  %.2f  %9llu / %9llu  %.4f%s\n", bx[q], (unsigned long long)cyc, (unsigned long long)b, by[q],
               cyc > b ? "  OVER" : "");
    }
    if (dir) {
        mkdir(dir, 0777);
        char path[1024];
        snprintf(path, sizeof path, "%s/wave_budget.svg", dir);
        FILE *f = fopen(path, "w");
        if (f) {
            np_plot pl = { "wave: RMS height error against the budget (scenario 2, 256^2)", "budget / full frame's cycles",
                           "RMS height error (m)", 0, 1, 0, 0, 0, NAN, NAN, NULL, NULL };
            np_plot_series se = { "trains by descending A", "#1f77b4", bx, by, NB, 1, 1 };
            np_plot_svg(f, &pl, &se, 1);
            fclose(f);
            printf("wrote %s\n", path);
        }
    }
    np_wave_scene_free(&s);
    free(y);
    free(dx);
    free(dz);
    free(yf);
    return NP_EXIT_OK;
}

int np_cmd_wave(int argc, char **argv)
{
    if (argc < 2 || strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0) {
        fputs(USAGE, argc < 2 ? stderr : stdout);
        return argc < 2 ? NP_EXIT_USAGE : NP_EXIT_OK;
    }
    if (strcmp(argv[1], "check") == 0)
        return cmd_check(argc - 1, argv + 1);
    if (strcmp(argv[1], "bench") == 0)
        return cmd_bench(argc - 1, argv + 1);
    return cmd_scene(argc, argv);
}
