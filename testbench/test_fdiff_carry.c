/* SPDX-License-Identifier: MIT */
/*
 * The carried cell set-up of np_fdiff (rtl_model/np_fdiff_carry.h, issue
 * 26): the monomials carried by additions along a span and rebased at each
 * crossing give, at every set-up pixel, the multiplier set-up's exact
 * differences Y_0..Y_3 (all 128 bits) and so its rounded differences, bit
 * for bit; and the unit with carry=1 gives the same pixels as with carry=0.
 * On the seed scenes' spans and on adversarial ones: steps of many cells,
 * negative, near-zero and zero steps, 4096-pixel spans, crossings in
 * several axes at one pixel, cell edges on pixel centres, the wrap at 256.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "np_fdiff.h"
#include "np_golden.h"
#include "np_render.h"
#include "np_report.h"
#include "np_texel.h"
#include "np_rng.h"
#include "np_scene.h"
#include "np_test.h"
#include "span_test.h"

#ifndef NP_SOURCE_DIR
#define NP_SOURCE_DIR "."
#endif

typedef struct walk_stats {
    uint64_t setups, crossings, multi_axis, big_shift, mismatches;
    uint64_t narrow_mismatches; /* the carried values held in the windows: rounded differences */
    int32_t max_shift;
} walk_stats;

/*
 * Walk octave oct of registers r along n pixels from u with step du, the
 * carried monomials beside the DDA, and compare the carried set-up with
 * np_fdiff_cell_setup at every set-up pixel (pixel 0, every crossing, and
 * every K-th pixel when K is not 0).
 */
static void walk(const np_fdiff_cfg *cfg, const np_tex_regs *r, unsigned oct, const uint64_t u0[3],
                 const int64_t du[3], uint32_t n, uint32_t K, walk_stats *ws)
{
    const unsigned F = np_fdiff_frac(cfg), W = np_fdiff_width(cfg);
    uint64_t u[3];
    memcpy(u, u0, sizeof u);
    np_fdiff_carry cm, cw; /* cw: held in the hardware's windows (np_fdiff_carry_wrap) */
    const unsigned yw = np_fdiff_y_window(cfg);
    np_fdiff_carry_init(&cm, r, oct, u, du);
    cw = cm;
    np_fdiff_carry_wrap(&cw, yw);
    uint32_t steps = 0;
    for (uint32_t k = 0; k < n; k++) {
        int setup = k == 0;
        if (k > 0) {
            int32_t j[3];
            np_fdiff_carry_shift(u, du, j);
            np_fdiff_carry_step(&cm);
            np_fdiff_carry_rebase(&cm, j);
            np_fdiff_carry_step(&cw);
            np_fdiff_carry_wrap(&cw, yw);
            np_fdiff_carry_rebase(&cw, j);
            np_fdiff_carry_wrap(&cw, yw);
            unsigned axes = 0;
            for (unsigned a = 0; a < 3; a++) {
                const uint8_t c0 = np_tex_cell(u[a]);
                u[a] = np_tex_dda(u[a], du[a]);
                if (np_tex_cell(u[a]) != c0) {
                    axes++;
                    const int32_t m = j[a] < 0 ? -j[a] : j[a];
                    if (m > ws->max_shift)
                        ws->max_shift = m;
                    ws->big_shift += m > 1;
                }
                if ((np_tex_cell(u[a]) != c0) != (j[a] != 0))
                    ws->mismatches++; /* a shift must be exactly a cell change */
            }
            steps++;
            if (axes) {
                ws->crossings++;
                ws->multi_axis += axes > 1;
            }
            setup = axes || (K && steps >= K);
        }
        if (!setup)
            continue;
        steps = 0;
        np_s128 d0[4], y0[4], d1[4], y1[4], d2[4];
        np_fdiff_cell_setup(cfg, r, oct, u, du, d0, y0);
        np_fdiff_carry_setup(&cm, u, F, W, d1, y1);
        np_fdiff_carry_setup(&cw, u, F, W, d2, NULL);
        ws->setups++;
        for (unsigned t = 0; t < 4; t++) {
            ws->mismatches += d0[t] != d1[t] || y0[t] != y1[t];
            ws->narrow_mismatches += d0[t] != d2[t];
        }
    }
}

/* The unit with carry=1 against carry=0 on one span: every pixel's index and colour. */
static uint64_t span_pair(const np_fdiff_cfg *cfg0, const np_tex_regs *r, const np_span *sp, np_s128 *xa,
                          np_s128 *xb, np_tex_pixel *pa, np_tex_pixel *pb)
{
    np_fdiff_cfg cfg1 = *cfg0;
    cfg1.carry = 1;
    np_fdiff_probe p0 = { 0 }, p1 = { 0 };
    p0.x = xa;
    p1.x = xb;
    np_fdiff_span(cfg0, r, sp, pa, NULL, &p0);
    np_fdiff_span(&cfg1, r, sp, pb, NULL, &p1);
    uint64_t bad = 0;
    for (uint32_t k = 0; k < sp->n; k++)
        bad += xa[k] != xb[k] || memcmp(pa[k].rgb, pb[k].rgb, 3) != 0;
    return bad;
}

static void print_stats(const char *what, const walk_stats *ws)
{
    printf("%s: %llu set-ups (%llu crossings, %llu in several axes at once, %llu shifting a fraction by more than "
           "one cell, largest |j| %d): %llu mismatches; in the hardware's windows: %llu\n",
           what, (unsigned long long)ws->setups, (unsigned long long)ws->crossings,
           (unsigned long long)ws->multi_axis, (unsigned long long)ws->big_shift, ws->max_shift,
           (unsigned long long)ws->mismatches, (unsigned long long)ws->narrow_mismatches);
}

static int seed_scene(const char *name, uint64_t *pix_bad)
{
    char path[1024], err[1024];
    np_scene s;
    np_render_frame fr;
    np_golden_scene_path(NP_SOURCE_DIR, name, path, sizeof path);
    NP_CHECK(np_scene_load(path, &s, err, sizeof err) == 0, "%s", err);
    NP_CHECK(np_render_prepare(&s, &fr, err, sizeof err) == 0, "%s", err);
    const np_fdiff_cfg cfg = np_fdiff_cfg_default();
    walk_stats ws;
    memset(&ws, 0, sizeof ws);
    np_s128 *xa = malloc((fr.longest + 1u) * sizeof *xa), *xb = malloc((fr.longest + 1u) * sizeof *xb);
    np_tex_pixel *pa = malloc((fr.longest + 1u) * sizeof *pa), *pb = malloc((fr.longest + 1u) * sizeof *pb);
    NP_CHECK(xa && xb && pa && pb, "out of memory");
    uint64_t pixels = 0;
    *pix_bad = 0;
    for (size_t i = 0; i < fr.n_spans; i++) {
        const np_span *sp = &fr.spans[i].hw;
        for (unsigned o = 0; o < fr.regs.n_oct; o++) {
            np_tex_oct_span os;
            np_tex_octave_span(&fr.regs, o, sp->s, sp->ds, &os);
            walk(&cfg, &fr.regs, o, os.u, os.du, sp->n, 0, &ws);
        }
        *pix_bad += span_pair(&cfg, &fr.regs, sp, xa, xb, pa, pb);
        pixels += sp->n;
    }
    char what[160];
    snprintf(what, sizeof what, "%s (%zu spans, %u octave%s)", name, fr.n_spans, fr.regs.n_oct,
             fr.regs.n_oct == 1 ? "" : "s");
    print_stats(what, &ws);
    printf("%s: carry=1 against carry=0, %llu pixels: %llu differ (index or colour)\n", name,
           (unsigned long long)pixels, (unsigned long long)*pix_bad);
    free(xa);
    free(xb);
    free(pa);
    free(pb);
    np_render_frame_free(&fr);
    np_scene_free(&s);
    NP_CHECK(ws.mismatches == 0 && ws.narrow_mismatches == 0 && ws.setups > 0, "%s: %llu set-up mismatches", name,
             (unsigned long long)ws.mismatches);
    return 0;
}

static int carry_seed_scenes(void)
{
    uint64_t bw = 0, bm = 0;
    if (seed_scene("wood", &bw) || seed_scene("marble", &bm))
        return 1;
    NP_CHECK(bw == 0 && bm == 0, "pixels differ: wood %llu, marble %llu", (unsigned long long)bw,
             (unsigned long long)bm);
    return 0;
}

/* A step of class c: 0 random full s40 (many cells), 1 within one cell, 2 near zero (|du| <= 2 LSB), 3 zero. */
static int64_t rand_step(np_rng *g, unsigned c)
{
    switch (c) {
    case 0:
        return np_sext(np_rng_next(g), NP_TEX_DU_BITS);
    case 1:
        return np_asr(np_sext(np_rng_next(g), NP_TEX_DU_BITS), 7u + (unsigned)np_rng_below(g, 30));
    case 2:
        return (int64_t)np_rng_below(g, 5) - 2;
    default:
        return 0;
    }
}

static int carry_adversarial(void)
{
    np_fdiff_cfg cfg = np_fdiff_cfg_default();
    np_rng g;
    np_rng_seed(&g, 2601);
    walk_stats ws;
    int fails = 0;
    struct {
        const char *name;
        unsigned iters;
        uint32_t n;
    } cls[] = {
        { "steps of many cells (full s40, both signs), 4096 pixels", 40, 4096 },
        { "steps within a cell, negative and positive, 4096 pixels", 40, 4096 },
        { "near-zero steps (|du| <= 2 LSB) and zero steps, 4096 pixels", 40, 4096 },
        { "mixed axes: one huge, one small, one near zero, 4096 pixels", 40, 4096 },
        { "crossings in all three axes at one pixel (equal steps and fractions), 4096 pixels", 40, 4096 },
        { "cell edges on pixel centres (dyadic steps 2^-m, fraction 0), with K = 7", 40, 4096 },
        { "the wrap at 256: u near 255 up, near 0 down, steps +-(2^-8 .. 127.99)", 40, 4096 },
        { "largest steps: du = -128, 128 - 2^-32, fractions at the extremes", 8, 4096 },
    };
    const unsigned NC = sizeof cls / sizeof cls[0];
    for (unsigned c = 0; c < NC; c++) {
        memset(&ws, 0, sizeof ws);
        for (unsigned it = 0; it < cls[c].iters; it++) {
            np_tex_regs r = span_wide_regs(&g, 1, (int)(it & 1u));
            uint64_t u[3];
            int64_t du[3];
            uint32_t K = 0;
            for (unsigned a = 0; a < 3; a++)
                u[a] = np_rng_next(&g) & NP_MASK(NP_TEX_U_BITS);
            switch (c) {
            case 0:
            case 1:
                for (unsigned a = 0; a < 3; a++)
                    du[a] = rand_step(&g, c);
                break;
            case 2:
                for (unsigned a = 0; a < 3; a++)
                    du[a] = rand_step(&g, 2u + (unsigned)np_rng_below(&g, 2));
                u[0] = (u[0] | NP_MASK(NP_TEX_FC)) - (uint64_t)np_rng_below(&g, 4096); /* near a cell edge */
                break;
            case 3: {
                const unsigned p = (unsigned)np_rng_below(&g, 3);
                du[p] = rand_step(&g, 0);
                du[(p + 1u) % 3u] = rand_step(&g, 1);
                du[(p + 2u) % 3u] = rand_step(&g, 2);
                break;
            }
            case 4: {
                const int64_t d = rand_step(&g, (unsigned)np_rng_below(&g, 2));
                const uint64_t f = np_rng_next(&g) & NP_MASK(NP_TEX_FC);
                for (unsigned a = 0; a < 3; a++) {
                    du[a] = d;
                    u[a] = (u[a] & ~(uint64_t)NP_MASK(NP_TEX_FC)) | f;
                }
                break;
            }
            case 5:
                K = 7;
                for (unsigned a = 0; a < 3; a++) {
                    const int64_t m = (int64_t)1 << (NP_TEX_FC - 1u - (unsigned)np_rng_below(&g, 12));
                    du[a] = np_rng_below(&g, 2) ? m : -m;
                    u[a] &= ~(uint64_t)NP_MASK(NP_TEX_FC);
                }
                break;
            case 6:
                for (unsigned a = 0; a < 3; a++) {
                    const int up = (int)np_rng_below(&g, 2);
                    const int64_t m = np_asr((int64_t)np_rng_below(&g, (uint64_t)1 << 39), (unsigned)np_rng_below(&g, 16));
                    du[a] = up ? m : -m;
                    u[a] = ((uint64_t)(up ? 255u : 0u) << NP_TEX_FC) | (np_rng_next(&g) & NP_MASK(NP_TEX_FC));
                }
                break;
            default:
                for (unsigned a = 0; a < 3; a++) {
                    du[a] = (np_rng_below(&g, 2) ? -((int64_t)1 << 39) : ((int64_t)1 << 39) - 1);
                    u[a] = (u[a] & ~(uint64_t)NP_MASK(NP_TEX_FC)) | (it & 1u ? NP_MASK(NP_TEX_FC) : 0u);
                }
                break;
            }
            cfg.idx_int = 1u + it % 11u; /* the window 117 + I: 118 .. 128 bits */
            cfg.guard = (unsigned)np_rng_below(&g, 45);
            walk(&cfg, &r, 0, u, du, cls[c].n, K, &ws);
        }
        print_stats(cls[c].name, &ws);
        if (ws.mismatches || ws.narrow_mismatches || !ws.setups)
            fails++;
        if (c == 4 && !ws.multi_axis)
            fails++; /* the class must cross several axes at once */
        if (c == 0 && !ws.big_shift)
            fails++;
    }
    NP_CHECK(fails == 0, "%d classes failed", fails);
    return 0;
}

/*
 * Whole spans through the unit, carry=1 against carry=0: random spans over
 * registers drawn across their full formats (1..8 octaves, general
 * transforms, amplitudes to -2^31), with and without the re-set-up
 * interval, and 4096-pixel spans.
 */
static int carry_unit_spans(void)
{
    np_rng g;
    np_rng_seed(&g, 2602);
    enum { NMAX = 4096 };
    np_s128 *xa = malloc(NMAX * sizeof *xa), *xb = malloc(NMAX * sizeof *xb);
    np_tex_pixel *pa = malloc(NMAX * sizeof *pa), *pb = malloc(NMAX * sizeof *pb);
    NP_CHECK(xa && xb && pa && pb, "out of memory");
    uint64_t bad = 0, pixels = 0, spans = 0;
    for (unsigned it = 0; it < 600; it++) {
        np_fdiff_cfg cfg = np_fdiff_cfg_default();
        cfg.resetup = it % 3u == 0 ? 0u : (unsigned)(1u + np_rng_below(&g, 40));
        cfg.guard = (unsigned)np_rng_below(&g, 45);
        np_tex_regs r = span_wide_regs(&g, 1u + (unsigned)np_rng_below(&g, 8), (int)(it & 1u));
        np_span sp = span_rand(&g);
        if (it % 10u == 0) {
            sp.n = NMAX;
            sp.x0 = 0;
        }
        if (np_span_check(&sp) || np_tex_regs_check(&r))
            continue;
        bad += span_pair(&cfg, &r, &sp, xa, xb, pa, pb);
        pixels += sp.n;
        spans++;
    }
    printf("%llu spans, %llu pixels over full-format registers (1..8 octaves, K = 0 or 1..40, G = 0..44): carry=1 "
           "against carry=0: %llu pixels differ\n",
           (unsigned long long)spans, (unsigned long long)pixels, (unsigned long long)bad);
    free(xa);
    free(xb);
    free(pa);
    free(pb);
    NP_CHECK(bad == 0 && spans > 100, "%llu pixels differ", (unsigned long long)bad);
    return 0;
}

/*
 * How the renderer's span descriptors relate to each other (docs/fdiff.md,
 * "Span to span"): per polygon, are consecutive scanlines' steps ds the
 * same bits, and is the start s0 affine in (x0, y) in the Q.32 bits, i.e.
 * is D = s0(y+1) - s0(y) - (x0(y+1) - x0(y)) ds the same on every row?
 */
static int span_relations(const char *name)
{
    char path[1024], err[1024];
    np_scene s;
    np_render_frame fr;
    np_golden_scene_path(NP_SOURCE_DIR, name, path, sizeof path);
    NP_CHECK(np_scene_load(path, &s, err, sizeof err) == 0, "%s", err);
    NP_CHECK(np_render_prepare(&s, &fr, err, sizeof err) == 0, "%s", err);
    uint64_t pairs = 0, same_ds = 0, polys = 0;
    int64_t spread_max = 0;
    for (unsigned poly = 0; poly < 4096; poly++) {
        const np_span *prev = NULL;
        int64_t dmin[3] = { INT64_MAX, INT64_MAX, INT64_MAX }, dmax[3] = { INT64_MIN, INT64_MIN, INT64_MIN };
        int any = 0;
        for (size_t i = 0; i < fr.n_spans; i++) {
            if (fr.spans[i].poly != poly)
                continue;
            const np_span *sp = &fr.spans[i].hw;
            any = 1;
            if (prev && sp->y == prev->y + 1u) {
                pairs++;
                same_ds += memcmp(sp->ds, prev->ds, sizeof sp->ds) == 0;
                for (unsigned a = 0; a < 3; a++) {
                    const int64_t d = sp->s[a] - prev->s[a] - ((int64_t)sp->x0 - (int64_t)prev->x0) * prev->ds[a];
                    dmin[a] = d < dmin[a] ? d : dmin[a];
                    dmax[a] = d > dmax[a] ? d : dmax[a];
                }
            }
            prev = sp;
        }
        if (!any)
            continue;
        polys++;
        for (unsigned a = 0; a < 3; a++)
            if (dmax[a] >= dmin[a] && dmax[a] - dmin[a] > spread_max)
                spread_max = dmax[a] - dmin[a];
    }
    printf("%s: %llu polygons, %llu pairs of consecutive scanlines: ds the same bits in %llu; s0(y+1) - s0(y) - "
           "dx0 ds varies over a polygon's rows by up to %lld LSB of Q.32 (0 would be a plane in the units' bits)\n",
           name, (unsigned long long)polys, (unsigned long long)pairs, (unsigned long long)same_ds,
           (long long)spread_max);
    np_render_frame_free(&fr);
    np_scene_free(&s);
    NP_CHECK(pairs > 0, "no consecutive spans");
    return 0;
}

static int carry_span_relations(void) { return span_relations("wood") || span_relations("marble"); }

/* --- The estimate of docs/fdiff.md ("A multiplier-free set-up"): the cost model on the declarations --- */

enum { OPS_MAX = 256 };

/* Gates of ops[0..n) in stage (NULL: all stages). */
static double price(const np_op *ops, size_t n, const char *stage)
{
    double g = 0;
    for (size_t i = 0; i < n; i++)
        if (!stage || strcmp(ops[i].stage, stage) == 0)
            g += np_cost_op_gates(&np_cost_default, &ops[i]);
    return g;
}

static int price_scene(const char *name, unsigned size)
{
    char path[1024], err[1024];
    np_scene s;
    np_render_frame fr;
    np_golden_scene_path(NP_SOURCE_DIR, name, path, sizeof path);
    NP_CHECK(np_scene_load(path, &s, err, sizeof err) == 0, "%s", err);
    s.width = s.height = size;
    NP_CHECK(np_render_prepare(&s, &fr, err, sizeof err) == 0, "%s", err);
    NP_CHECK(np_render_reference(&fr) == 0, "reference"); /* the runs measure their error against it */
    const np_tex_regs *r = &fr.regs;
    np_fdiff_cfg fc = np_fdiff_cfg_default(), f1 = fc;
    f1.setup_mults = 1;
    np_texel_cfg tc = np_texel_cfg_default();
    np_op ops[OPS_MAX];
    size_t n = np_fdiff_datapath(&fc, r, ops, OPS_MAX);
    const double fd = price(ops, n, NULL), fd_su = price(ops, n, "SU");
    n = np_fdiff_datapath(&f1, r, ops, OPS_MAX);
    const double su1 = price(ops, n, "SU");
    n = np_texel_datapath(&tc, r, ops, OPS_MAX);
    const double tx = price(ops, n, NULL);
    np_render_run run;
    NP_CHECK(np_render_engine(&fr, &np_fdiff_engine, &fc, 1, &run) == 0, "fdiff run");
    const double fd_cyc = (double)run.cycles;
    const double setups = (double)(run.span_setups * r->n_oct + run.cell_setups + run.interval_setups);
    np_render_run_free(&run);
    NP_CHECK(np_render_engine(&fr, &np_fdiff_engine, &f1, 1, &run) == 0, "fdiff P=1 run");
    const double fd1_cyc = (double)run.cycles;
    np_render_run_free(&run);
    NP_CHECK(np_render_engine(&fr, &np_texel_engine, &tc, 1, &run) == 0, "texel run");
    const double tx_cyc = (double)run.cycles;
    np_render_run_free(&run);
    /* One pixel per clock, no stall: the least any span unit takes. */
    const double lower = (double)fr.pixels + (double)fr.n_spans + NP_FDIFF_TAIL_STAGES;
    const double tgc = tx * tx_cyc;
    printf("%s %u^2: texel %.0f gates x %.0f cycles = %.3g; fdiff today %.0f x %.0f = %.3g (%.2f of texel); "
           "%.0f cell set-ups, %.2f products per pixel carried\n",
           name, size, tx, tx_cyc, tgc, fd, fd_cyc, fd * fd_cyc, fd * fd_cyc / tgc, setups,
           setups * NP_FDIFF_CARRY_PRODUCTS / (double)fr.pixels);
    /* The span-to-span variant: every carried vector's y-differences (3 more), the quadric's 2-D ones. */
    const unsigned W = np_fdiff_width(&fc);
    double best = 0;
    for (unsigned pc = 1; pc <= 8; pc *= 2) {
        n = np_fdiff_carry_datapath(&fc, r, pc, ops, OPS_MAX);
        const double ca = price(ops, n, "CA"), cm = price(ops, n, "CM");
        const double g1 = fd - fd_su + su1 + ca + cm;
        const double mac_bound = setups * NP_FDIFF_CARRY_PRODUCTS / pc;
        const double c1 = lower > mac_bound ? lower : mac_bound;
        const unsigned yw = np_fdiff_y_window(&fc);
        const double bits = 3.0 * 2.0 * (yw - 2u * NP_TEX_FC) + 3.0 * 3.0 * (yw - NP_TEX_FC) + 4.0 * yw;
        const double ystep = np_cost_default.ff_bit * 3.0 * bits * r->n_oct;
        const double quad2d = np_cost_default.ff_bit * 4.0 * W + 2.0 * (np_cost_default.add_bit * W - np_cost_default.add_edge);
        const double g2 = fd - fd_su + ca + cm + ystep + quad2d;
        printf("  %u crossing MAC%s: carrier %.0f, MACs %.0f; within span (SU at P = 1 %.0f): %.0f gates x %.0f cycles "
               "(%s) = %.3g, %.2f of texel", pc, pc == 1 ? "" : "s", ca, cm, su1, g1, c1,
               c1 == lower ? "one pixel per clock" : "MAC-bound", g1 * c1, g1 * c1 / tgc);
        if (pc == 1)
            printf(" (%.2f at today's P = 1 cycles %.0f)", g1 * (fd1_cyc > c1 ? fd1_cyc : c1) / tgc, fd1_cyc);
        printf("; span to span too (y-differences %.0f): %.0f gates, %.2f of texel\n", ystep, g2, g2 * c1 / tgc);
        const double ratio = g1 * c1 / tgc;
        if (best == 0 || ratio < best)
            best = ratio;
    }
    printf("  best within-span variant: %.2f of texel's gates x cycles (acceptance: <= 0.5)\n", best);
    np_render_frame_free(&fr);
    np_scene_free(&s);
    NP_CHECK(best > 0 && fd > 0 && tx > 0, "no estimate");
    return 0;
}

static int carry_price(void)
{
    if (price_scene("wood", 256) || price_scene("marble", 256) || price_scene("wood", 1024) ||
        price_scene("marble", 1024))
        return 1;
    return 0;
}

static const np_test_case cases[] = {
    { "carry_seed_scenes", carry_seed_scenes },
    { "carry_adversarial", carry_adversarial },
    { "carry_unit_spans", carry_unit_spans },
    { "carry_price", carry_price },
    { "carry_span_relations", carry_span_relations },
    { NULL, NULL },
};

NP_TEST_MAIN(cases)
