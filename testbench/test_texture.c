/* SPDX-License-Identifier: MIT */
/*
 * What the span units share (rtl_model/np_texture.h, np_span.h): the colour
 * stage against the float colour map, the span front end's rounding, the
 * distribution of the lattice values derived from np_hash6, and the
 * validation of configurations, registers and descriptors.
 * (CTest names: fdiff.colour_stage, ... as before the split.)
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "np_fdiff.h"
#include "np_ref.h"
#include "np_rng.h"
#include "np_test.h"
#include "np_texel.h"
#include "np_texreg.h"
#include "span_test.h"

static int colour_stage(void)
{
    /* The colour stage against the float colour map at the same index: error <= 1/2 + slope 2^-(Fw+1). */
    np_rng g;
    np_rng_seed(&g, 41);
    double worst = 0;
    for (int mode = 0; mode < 2; mode++) {
        np_tex_regs r = span_multi_regs(&g, 1);
        np_ref_colormap c;
        memset(&c, 0, sizeof c);
        r.cmap_repeat = mode == 0;
        c.repeat = r.cmap_repeat;
        c.n = r.cmap_n;
        c.f0 = 0;
        c.f1 = 1;
        for (unsigned k = 0; k < c.n; k++)
            for (int ch = 0; ch < 3; ch++)
                c.c[k][ch] = r.cmap[k][ch];
        double S = c.repeat ? (double)c.n : (double)(c.n - 1u);
        unsigned F = 40, fw = 12, W = 1 + 10 + F;
        double bound = 0.5 + np_tex_colour_slope(&r) * ldexp(1.0, -(int)fw - 1);
        for (unsigned it = 0; it < 200000; it++) {
            np_s128 x = np_wrap_s128(np_asr128((np_s128)(int64_t)np_rng_next(&g), (unsigned)np_rng_below(&g, 12) + 2u), W);
            uint8_t rgb[3];
            double ref[3];
            np_tex_colour(&r, x, F, fw, rgb);
            np_ref_colour(&c, ldexp((double)x, -(int)F) / S, ref);
            for (int ch = 0; ch < 3; ch++) {
                double e = fabs((double)rgb[ch] - ref[ch]);
                worst = fmax(worst, e / bound);
            }
        }
    }
    printf("colour stage: worst error / bound (1/2 + slope 2^-(Fw+1)) = %.4f over 400,000 indices\n", worst);
    NP_CHECK(worst <= 1.0, "colour stage exceeds its bound: %.4f", worst);
    return 0;
}

static int front_end_rounding(void)
{
    /* u0 and du against the exact M s + o and M ds (integers at 48 fraction bits): |error| <= 2^-33 mod 256. */
    np_rng g;
    np_rng_seed(&g, 42);
    np_s128 worst = 0;
    const unsigned sh = NP_TEX_M_FRAC, wu = NP_TEX_U_BITS + NP_TEX_M_FRAC;
    for (unsigned it = 0; it < 100000; it++) {
        np_tex_regs r = span_multi_regs(&g, 1);
        np_span sp = span_rand(&g);
        np_tex_oct_span os;
        np_tex_octave_span(&r, 0, sp.s, sp.ds, &os);
        for (int a = 0; a < 3; a++) {
            np_s128 u = (np_s128)r.oct[0].o[a] * ((np_s128)1 << sh), du = 0;
            for (int b = 0; b < 3; b++) {
                u += (np_s128)r.oct[0].m[a][b] * sp.s[b];
                du += (np_s128)r.oct[0].m[a][b] * sp.ds[b];
            }
            np_s128 eu = np_wrap_s128((np_s128)os.u[a] * ((np_s128)1 << sh) - u, wu);
            np_s128 ed = np_wrap_s128((np_s128)os.du[a] * ((np_s128)1 << sh) - du, wu);
            eu = eu < 0 ? -eu : eu;
            ed = ed < 0 ? -ed : ed;
            worst = eu > worst ? eu : worst;
            worst = ed > worst ? ed : worst;
        }
    }
    printf("front end: worst |u0 - exact|, |du - exact| = %.4f x 2^-33 (bound 1), modulo 256, exact integer check\n",
           ldexp((double)worst, -(int)sh + 1));
    NP_CHECK(worst <= ((np_s128)1 << (sh - 1u)), "front-end rounding beyond 2^-33");
    return 0;
}

static int lattice_distribution(void)
{
    /*
     * The lattice values n = np_hash6 / 64 over the whole tile (2^24 points):
     * the histogram, its moments against a uniform 6-bit value, chi-square.
     */
    static uint64_t hist[64];
    memset(hist, 0, sizeof hist);
    for (unsigned i = 0; i < 256; i++)
        for (unsigned j = 0; j < 256; j++)
            for (unsigned k = 0; k < 256; k++)
                hist[np_hash6((uint8_t)i, (uint8_t)j, (uint8_t)k)]++;
    const double N = 16777216.0, E = N / 64.0;
    double mean = 0, m2 = 0, chi = 0, ent = 0;
    uint64_t lo = UINT64_MAX, hi = 0, tot = 0, zero = 0;
    for (unsigned h = 0; h < 64; h++) {
        double p = (double)hist[h] / N, v = h / 64.0;
        mean += p * v;
        m2 += p * v * v;
        chi += ((double)hist[h] - E) * ((double)hist[h] - E) / E;
        if (hist[h])
            ent -= p * log2(p);
        lo = hist[h] < lo ? hist[h] : lo;
        hi = hist[h] > hi ? hist[h] : hi;
        tot += hist[h];
        zero += hist[h] == 0;
    }
    double var = m2 - mean * mean;
    printf("lattice values n = np_hash6 / 64 over 2^24 lattice points:\n");
    for (unsigned h = 0; h < 64; h += 8) {
        printf("  ");
        for (unsigned k = h; k < h + 8; k++)
            printf("%2u:%7llu ", k, (unsigned long long)hist[k]);
        printf("\n");
    }
    printf("  counts min %llu max %llu (uniform %.0f), values never hit %llu\n", (unsigned long long)lo,
           (unsigned long long)hi, E, (unsigned long long)zero);
    printf("  mean %.6f (uniform 6-bit: %.6f), std %.6f (uniform: %.6f), entropy %.4f bits (uniform 6), "
           "chi-square %.0f on 63 degrees of freedom\n",
           mean, 31.5 / 64.0, sqrt(var), sqrt((64.0 * 64.0 - 1.0) / 12.0) / 64.0, ent, chi);
    NP_CHECK(tot == 16777216u, "histogram total %llu", (unsigned long long)tot);
    /* Pinned: the distribution is a property of the shared hash; a change here is a change of every texture. */
    NP_CHECK(hist[0] != hist[1] || hist[1] != hist[2], "unexpectedly uniform");
    return 0;
}

static int cfg_validation(void)
{
    np_fdiff_cfg c = np_fdiff_cfg_default();
    NP_CHECK(np_fdiff_cfg_check(&c) == NULL, "default invalid: %s", np_fdiff_cfg_check(&c));
    NP_CHECK(np_fdiff_width(&c) == 1 + 10 + 12 + 44, "default width %u", np_fdiff_width(&c));
    c.idx_int = 12;
    NP_CHECK(np_fdiff_cfg_check(&c) != NULL, "idx_int 12 accepted");
    c = np_fdiff_cfg_default();
    c.guard = 105;
    NP_CHECK(np_fdiff_cfg_check(&c) != NULL, "width > 127 accepted");
    c = np_fdiff_cfg_default();
    c.setup_mults = 0;
    NP_CHECK(np_fdiff_cfg_check(&c) != NULL, "0 multipliers accepted");
    np_texel_cfg t = np_texel_cfg_default();
    NP_CHECK(np_texel_cfg_check(&t) == NULL, "texel default invalid");
    t.weight_frac = 33;
    NP_CHECK(np_texel_cfg_check(&t) != NULL, "WT 33 accepted");
    np_tex_regs r = span_ramp_regs();
    NP_CHECK(np_tex_regs_check(&r) == NULL, "ramp regs invalid");
    r.cmap_n = 6;
    r.cmap_repeat = 1;
    NP_CHECK(np_tex_regs_check(&r) != NULL, "repeat map of 6 entries accepted");
    r = span_ramp_regs();
    r.oct[0].m[0][0] = 1 << 23;
    NP_CHECK(np_tex_regs_check(&r) != NULL, "matrix entry 128 accepted");
    np_span sp = span_mk(0, 65000, 600, (double[3]){ 0, 0, 0 }, (double[3]){ 0, 0, 0 });
    NP_CHECK(np_span_check(&sp) != NULL, "span past pixel 65535 accepted");
    sp = span_mk(0, 0, 200, (double[3]){ 30000, 0, 0 }, (double[3]){ 200, 0, 0 });
    NP_CHECK(np_span_check(&sp) != NULL, "span leaving s48 accepted");
    return 0;
}

/*
 * Register rounding inside the bound (np_texreg.h): a texture whose
 * registers do round (scale 0.1 in s24 Q7.16, amplitude 0.3, quadric
 * A = 1e-5 in Q23.24, offset 1/3) on the steepest clamped map, over the box
 * [90, 100]^3: the predicted bound (the unit's own plus the registers') must
 * cover every pixel of random spans through both units' bit-exact models
 * against the float texture, and the registers' part must matter (> 0.05
 * LSB here). The scenes that go over are refused (render.*_refuses_*).
 */
static int register_bound(void)
{
    np_ref_texture t;
    memset(&t, 0, sizeof t);
    t.quad[0] = 1e-5;
    t.n_oct = 1;
    for (int a = 0; a < 3; a++) {
        t.oct[0].m[a][a] = 0.1;
        t.oct[0].o[a] = 1.0 / 3.0;
    }
    t.oct[0].amp = 0.3;
    t.cmap.n = 2;
    t.cmap.repeat = 0;
    t.cmap.f0 = 0;
    t.cmap.f1 = 1.2;
    for (int ch = 0; ch < 3; ch++)
        t.cmap.c[1][ch] = 255;
    np_tex_regs r;
    char err[256];
    NP_CHECK(np_texreg_compile(&t, &r, err, sizeof err) == 0, "%s", err);
    const double lo[3] = { 90, 90, 90 }, hi[3] = { 100, 100, 100 };
    np_texreg_scene_bound b;
    np_texreg_scene_bound_compute(&t, &r, lo, hi, 512, &b);
    np_fdiff_cfg fc = np_fdiff_cfg_default();
    np_texel_cfg tc = np_texel_cfg_default();
    const double slope = (double)np_tex_colour_slope(&r);
    /* The units' own bounds over spans of at most 512 pixels (np_fdiff.h, np_texel.h). */
    const double own_fd = 0.5 + slope * (np_fdiff_drift_bound_noise(np_fdiff_frac(&fc), 511) +
                                          np_fdiff_drift_bound_quad(np_fdiff_frac(&fc), 511) +
                                          ldexp(1.0, -(int)fc.w_frac - 1));
    const double own_tx = 0.5 + slope * (np_texel_error_bound_index(&tc, &r) + ldexp(1.0, -(int)tc.w_frac - 1));
    np_rng g;
    np_rng_seed(&g, 77);
    double worst_fd = 0, worst_tx = 0;
    uint64_t px = 0;
    np_tex_pixel *out = calloc(512, sizeof *out);
    for (unsigned it = 0; it < 400; it++) {
        double s0[3], ds[3];
        uint32_t n = 1u + (uint32_t)np_rng_below(&g, 512);
        for (int a = 0; a < 3; a++) {
            ds[a] = ldexp((double)np_rng_below(&g, 1u << 20) - (double)(1u << 19), -32);
            double end = ds[a] * (double)(n - 1u);
            double a0 = lo[a] + fmax(0, -end), a1 = hi[a] - fmax(0, end);
            s0[a] = a0 + (a1 - a0) * ldexp((double)np_rng_below(&g, 1u << 30), -30);
            s0[a] = ldexp(floor(ldexp(s0[a], 32)), -32);
        }
        np_span sp = span_mk(0, 0, n, s0, ds);
        for (int unit = 0; unit < 2; unit++) {
            if (unit == 0)
                np_fdiff_span(&fc, &r, &sp, out, NULL, NULL);
            else
                np_texel_span(&tc, &r, &sp, out, NULL, NULL);
            for (uint32_t k = 0; k < n; k++) {
                double st[3], rgb[3];
                for (int a = 0; a < 3; a++)
                    st[a] = ldexp((double)sp.s[a], -32) + (double)k * ldexp((double)sp.ds[a], -32);
                np_ref_colour(&t.cmap, np_ref_texture_f(&t, st, NULL), rgb);
                for (int ch = 0; ch < 3; ch++) {
                    double e = fabs((double)out[k].rgb[ch] - rgb[ch]);
                    double *w = unit == 0 ? &worst_fd : &worst_tx;
                    if (e > *w)
                        *w = e;
                }
            }
            px += n;
        }
    }
    free(out);
    printf("registers: %.4f LSB (worst field %s, %.4f LSB; the formats guarantee %.4f); index up to %.4g\n",
           b.reg_lsb, b.worst, b.worst_lsb, b.reg_lsb_bound, b.index_max);
    printf("fdiff: measured %.4f LSB <= predicted %.4f (own %.4f); texel: measured %.4f <= %.4f (own %.4f); %llu "
           "pixels\n",
           worst_fd, own_fd + b.reg_lsb, own_fd, worst_tx, own_tx + b.reg_lsb, own_tx, (unsigned long long)px);
    NP_CHECK(b.reg_lsb > 0.05, "the registers' rounding should matter here (%.4f)", b.reg_lsb);
    NP_CHECK(b.reg_lsb <= b.reg_lsb_bound, "actual %.4g above what the formats guarantee %.4g", b.reg_lsb,
             b.reg_lsb_bound);
    NP_CHECK(worst_fd <= own_fd + b.reg_lsb && worst_tx <= own_tx + b.reg_lsb, "measured over the predicted bound");
    NP_CHECK(np_texreg_scene_check("t", &b, own_fd, fc.idx_int, 11, err, sizeof err) == 0, "%s", err);
    return 0;
}

/* The registers' bound of texture t in formats f over lo..hi (spans of max_span pixels). */
static double reg_bound_at(const np_ref_texture *t, np_texreg_fmt f, const double lo[3], const double hi[3],
                           unsigned max_span)
{
    np_tex_regs r;
    np_texreg_scene_bound b;
    char err[256];
    if (np_texreg_compile_fmt(t, &f, &r, err, sizeof err) != 0)
        return (double)INFINITY;
    np_texreg_scene_bound_compute(t, &r, lo, hi, max_span, &b);
    return b.reg_lsb;
}

/*
 * Registers sized by the scene (np_texreg_size), the fewest both ways: on
 * the issue-10 textures the chosen transform fraction is the fewest whose
 * registers' bound is <= the budget with the quadric at its widest (one bit
 * fewer exceeds it), the chosen quadric fraction the fewest at that
 * transform, and the chosen formats meet the budget; the seed textures'
 * dyadic values need no fraction bits.
 */
static int sized_fewest(void)
{
    const double B = NP_TEXREG_SIZE_BUDGET;
    struct {
        const char *name;
        double scale, quad_a, lo, hi;
        int repeat;
        unsigned span;
    } cs[] = { { "scale 0.1 near 1000", 0.1, 0, 990, 1000, 0, 64 },
               { "scale 1e-6", 1e-6, 0, 0, 20000, 0, 512 },
               { "quadric A = 1e-6", 1, 1e-6, 0, 20000, 1, 512 },
               { "dyadic (wood-like)", 5, 10, 0, 1, 1, 256 } };
    for (size_t i = 0; i < sizeof cs / sizeof cs[0]; i++) {
        np_ref_texture t;
        memset(&t, 0, sizeof t);
        t.quad[0] = cs[i].quad_a;
        t.n_oct = 1;
        for (int a = 0; a < 3; a++)
            t.oct[0].m[a][a] = cs[i].scale;
        t.oct[0].amp = 1;
        t.cmap.n = 2;
        t.cmap.repeat = cs[i].repeat;
        t.cmap.f0 = 0;
        t.cmap.f1 = 1;
        for (int ch = 0; ch < 3; ch++)
            t.cmap.c[1][ch] = 255;
        const double lo[3] = { cs[i].lo, cs[i].lo, cs[i].lo }, hi[3] = { cs[i].hi, cs[i].hi, cs[i].hi };
        np_texreg_fmt f;
        np_tex_regs r;
        np_texreg_scene_bound b;
        char err[256];
        NP_CHECK(np_texreg_size(&t, lo, hi, cs[i].span, B, &f, &r, &b, err, sizeof err) == 0, "%s: %s", cs[i].name, err);
        /* The quadric at its widest: the same integer bits, 48 fraction bits. */
        np_texreg_fmt wide = f;
        wide.k_bits = f.k_bits - f.k_frac + NP_TEX_K_FRAC_MAX;
        wide.k_frac = NP_TEX_K_FRAC_MAX;
        np_texreg_fmt m1 = wide, k1 = f;
        m1.m_frac--;
        m1.m_bits--;
        k1.k_frac--;
        k1.k_bits--;
        const double at = b.reg_lsb, at_m1 = f.m_frac ? reg_bound_at(&t, m1, lo, hi, cs[i].span) : (double)NAN,
                     at_k1 = f.k_frac ? reg_bound_at(&t, k1, lo, hi, cs[i].span) : (double)NAN;
        printf("%-20s quadric s%u Q.%u, transform s%u Q.%u: registers %.4g LSB <= %.3g; one transform bit fewer "
               "%.4g, one quadric bit fewer %.4g\n",
               cs[i].name, f.k_bits, f.k_frac, f.m_bits, f.m_frac, at, B, at_m1, at_k1);
        NP_CHECK(at <= B, "%s: %.4g over the budget", cs[i].name, at);
        NP_CHECK(f.m_frac == 0 || at_m1 > B, "%s: transform Q.%u is not the fewest", cs[i].name, f.m_frac);
        NP_CHECK(f.k_frac == 0 || at_k1 > B, "%s: quadric Q.%u is not the fewest", cs[i].name, f.k_frac);
        if (i == 3)
            NP_CHECK(f.m_frac == 0 && f.k_frac == 0, "dyadic values need no fraction bits (Q.%u, Q.%u)", f.k_frac,
                     f.m_frac);
        else
            NP_CHECK(f.m_frac > NP_TEX_M_FRAC || f.k_frac > NP_TEX_K_FRAC, "%s: wider than the defaults expected",
                     cs[i].name);
    }
    return 0;
}

static const np_test_case cases[] = {
    { "colour_stage", colour_stage },
    { "front_end_rounding", front_end_rounding },
    { "lattice_distribution", lattice_distribution },
    { "cfg_validation", cfg_validation },
    { "register_bound", register_bound },
    { "sized_fewest", sized_fewest },
    { NULL, NULL },
};

NP_TEST_MAIN(cases)
