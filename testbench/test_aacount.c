/* SPDX-License-Identifier: MIT */
/*
 * The sample-count unit aacount: bit-exact model against the exact rational
 * reference, the host's threshold registers, the stiff and extreme cases of
 * issue 15, the resolve exhaustively, the serial cycle model.
 */
#include <inttypes.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "np_aacount.h"
#include "np_ref.h"
#include "np_rng.h"
#include "np_test.h"
#include "np_unit.h"

typedef __int128 i128;

static int same(const np_aacount_out *o, const np_ref_aacount_counts *r)
{
    return o->s == r->s && o->mask == r->mask && o->sd == r->sd && o->sn == r->sn && o->ss == r->ss;
}

static uint64_t checked, mismatches;

/* Model against reference on one window; prints the first mismatches. */
static void cmp1(const np_aacount_cfg *c, const np_aacount_win *w, const char *what)
{
    np_aacount_out o;
    np_ref_aacount_counts r;
    np_aacount_eval(c, w, &o);
    np_ref_aacount(c, w, &r);
    checked++;
    if (!same(&o, &r)) {
        mismatches++;
        NP_CHECK(0, "%s m=%u c_d=%u c_n=%u c_s=%u: model s=%u sd=%u sn=%u ss=%u mask=%04x, reference s=%u sd=%u sn=%u ss=%u mask=%04x",
                 what, c->m, c->c_d, c->c_n, c->c_s, o.s, o.sd, o.sn, o.ss, o.mask, r.s, r.sd, r.sn, r.ss, r.mask);
    }
}

/* A plausible window: depths around a base with a spread, normals around a direction, lumas. */
static void rand_win(np_rng *g, unsigned n, np_aacount_win *w)
{
    memset(w, 0, sizeof *w);
    uint32_t base = (uint32_t)(np_rng_next(g) >> 40);
    unsigned spread_bits = (unsigned)np_rng_below(g, 25);
    int nb[3];
    for (unsigned k = 0; k < 3; k++)
        nb[k] = (int)np_rng_below(g, 256) - 128;
    unsigned nspread = (unsigned)np_rng_below(g, 9);
    for (unsigned i = 0; i < n; i++) {
        uint64_t off = spread_bits ? np_rng_next(g) >> (64u - spread_bits) : 0u;
        uint64_t d = base + off;
        w->d[i] = (uint32_t)(d > 0xffffffu ? 0xffffffu : d);
        for (unsigned k = 0; k < 3; k++) {
            int e = nb[k] + (nspread ? (int)np_rng_below(g, 1u << nspread) - (int)(1u << nspread) / 2 : 0);
            w->nrm[i][k] = (int8_t)(e < -128 ? -128 : e > 127 ? 127 : e);
        }
        if (np_rng_below(g, 16) == 0)
            memset(w->nrm[i], 0, 3); /* background sample */
    }
    unsigned lb = (unsigned)np_rng_below(g, 256), ls = (unsigned)np_rng_below(g, 9);
    for (unsigned k = 0; k < 5; k++) {
        unsigned l = lb + (ls ? (unsigned)np_rng_below(g, 1u << ls) : 0u);
        w->luma[k] = (uint8_t)(l > 255 ? 255 : l);
    }
}

static void rand_cfg(np_rng *g, np_aacount_cfg *c)
{
    *c = np_aacount_cfg_default();
    c->m = (uint8_t)(1 + np_rng_below(g, 4));
    unsigned metrics = (unsigned)np_rng_below(g, 8);
    c->depth = metrics & 1u;
    c->normal = metrics >> 1 & 1u;
    c->luma = metrics >> 2 & 1u;
    c->luma_taps = (uint8_t)(4 + np_rng_below(g, 2));
    c->c_d = (uint32_t)(np_rng_next(g) >> (32 + np_rng_below(g, 32)));
    c->c_n = (uint8_t)np_rng_below(g, 256);
    c->c_s = (uint16_t)(np_rng_next(g) >> (48 + np_rng_below(g, 16)));
    c->t_min = (uint8_t)np_rng_below(g, 64);
    c->t_edge = (uint8_t)np_rng_below(g, 256);
}

static int kat(void)
{
    static const struct {
        uint64_t w0, w1, w2, w3, w4, w5, w6, w7;
        unsigned s, mask, sd, sn, ss;
    } k[] = {
#include "aacount_kat.inc"
    };
    const np_unit *u = np_unit_find("aacount");
    NP_CHECK(u != NULL, "aacount not in the registry");
    if (!u)
        return 1;
    np_unit_cfg cfg;
    np_unit_cfg_default(u, &cfg);
    unsigned n = sizeof k / sizeof k[0];
    for (unsigned i = 0; i < n; i++) {
        uint64_t out[NP_UNIT_MAX_FIELDS];
        const uint64_t in[8] = { k[i].w0, k[i].w1, k[i].w2, k[i].w3, k[i].w4, k[i].w5, k[i].w6, k[i].w7 };
        u->eval(&cfg, in, out);
        NP_CHECK(out[0] == k[i].s && out[1] == k[i].mask && out[2] == k[i].sd && out[3] == k[i].sn &&
                     out[4] == k[i].ss,
                 "row %u: s=%" PRIu64 " mask=%" PRIx64 ", want %u %x", i, out[0], out[1], k[i].s, k[i].mask);
    }
    printf("%u pinned windows match\n", n);
    return 0;
}

/* 100 % agreement with the exact rational reference over random configurations and windows. */
static int ref_random(void)
{
    np_rng g;
    np_rng_seed(&g, 15);
    checked = mismatches = 0;
    for (unsigned t = 0; t < 200000; t++) {
        np_aacount_cfg c;
        np_aacount_win w;
        rand_cfg(&g, &c);
        rand_win(&g, (unsigned)c.m * c.m, &w);
        cmp1(&c, &w, "random");
    }
    printf("%" PRIu64 " random windows over random configurations: %" PRIu64 " differ from the rational reference\n",
           checked, mismatches);
    return 0;
}

/*
 * At the thresholds: for random windows, the constants at which each metric's
 * k crosses each integer j, and one either side. Depth: c_d* = j n^2 2^48 / V,
 * tried at floor, ceil and +-1. Luma: every C_s in 0..4095 over windows with
 * r at t_min - 1, t_min, t_min + 1 and at 8 r = lmax +- 1. Normals: every
 * C = 4 c_n in 0..255 (every normal register value) on windows of nearly
 * parallel normals, where p/q sits closest to the thresholds.
 */
static int ref_thresholds(void)
{
    np_rng g;
    np_rng_seed(&g, 1515);
    checked = mismatches = 0;
    uint64_t at_equal = 0;
    for (unsigned t = 0; t < 3000; t++) {
        np_aacount_cfg c = np_aacount_cfg_default();
        c.m = (uint8_t)(2 + t % 3);
        c.normal = c.luma = 0;
        unsigned n = (unsigned)c.m * c.m;
        np_aacount_win w;
        rand_win(&g, n, &w);
        i128 S = 0;
        for (unsigned i = 0; i < n; i++)
            for (unsigned j = i + 1; j < n; j++)
                S += ((i128)w.d[i] - w.d[j]) * ((i128)w.d[i] - w.d[j]);
        if (S == 0)
            continue;
        for (unsigned j = 1; j < n; j++) {
            i128 num = (i128)j * n * n * ((i128)1 << 48), cs = num / S;
            for (int dlt = -1; dlt <= 2; dlt++) {
                i128 cd = cs + dlt;
                if (cd < 0 || cd > 0xffffffffu)
                    continue;
                c.c_d = (uint32_t)cd;
                at_equal += cd * S == num;
                cmp1(&c, &w, "depth threshold");
            }
        }
    }
    /*
     * Exactly at k_d = j: one sample 2^k above the rest gives S = (n - 1) 4^k,
     * and c_d = n^2 2^(48 - 2k) puts k_d = n - 1 exactly (c_d = that -+ 1 either side).
     */
    for (unsigned m = 2; m <= 4; m++)
        for (unsigned k = 13; k < 24; k++) {
            unsigned n = m * m;
            np_aacount_cfg c = np_aacount_cfg_default();
            c.m = (uint8_t)m;
            c.normal = c.luma = 0;
            np_aacount_win w;
            memset(&w, 0, sizeof w);
            w.d[n / 2] = 1u << k;
            uint64_t cd = (uint64_t)n * n << (48u - 2u * k);
            if (cd > 0xffffffffu)
                continue;
            for (int dlt = -1; dlt <= 1; dlt++) {
                c.c_d = (uint32_t)((int64_t)cd + dlt);
                at_equal += dlt == 0;
                cmp1(&c, &w, "depth exactly at k_d = n - 1");
                np_aacount_out o;
                np_aacount_eval(&c, &w, &o);
                NP_CHECK(o.sd == (dlt > 0 ? n : n - 1u), "m=%u k=%u c_d=%u: sd=%u", m, k, c.c_d, o.sd);
            }
        }
    for (unsigned t = 0; t < 600; t++) {
        np_aacount_cfg c = np_aacount_cfg_default();
        c.m = (uint8_t)(2 + t % 3);
        c.depth = c.normal = 0;
        c.luma_taps = (uint8_t)(4 + t % 2);
        c.t_min = (uint8_t)np_rng_below(&g, 64);
        np_aacount_win w;
        memset(&w, 0, sizeof w);
        unsigned lmax = 64 + (unsigned)np_rng_below(&g, 192);
        /* r = t_min - 1, t_min, t_min + 1 and r = lmax/8 - 1 .. lmax/8 + 1 */
        int rs[6] = { c.t_min - 1, c.t_min, c.t_min + 1, (int)lmax / 8 - 1, (int)lmax / 8, (int)lmax / 8 + 1 };
        for (unsigned q = 0; q < 6; q++) {
            if (rs[q] < 0 || rs[q] > (int)lmax)
                continue;
            w.luma[0] = (uint8_t)lmax;
            w.luma[1] = (uint8_t)lmax;
            w.luma[2] = (uint8_t)(lmax - (unsigned)rs[q]);
            w.luma[3] = (uint8_t)(lmax - (unsigned)rs[q] / 2u);
            w.luma[4] = (uint8_t)lmax;
            for (unsigned cs = 0; cs < 4096; cs += 1u + (unsigned)np_rng_below(&g, 3)) {
                c.c_s = (uint16_t)cs;
                cmp1(&c, &w, "luma threshold");
            }
        }
    }
    for (unsigned t = 0; t < 400; t++) {
        np_aacount_cfg c = np_aacount_cfg_default();
        c.m = (uint8_t)(2 + t % 3);
        c.depth = c.luma = 0;
        unsigned n = (unsigned)c.m * c.m;
        np_aacount_win w;
        memset(&w, 0, sizeof w);
        int base[3] = { (int)np_rng_below(&g, 200) - 100, (int)np_rng_below(&g, 200) - 100, 100 };
        unsigned sp = 1 + (unsigned)np_rng_below(&g, 40);
        for (unsigned i = 0; i < n; i++)
            for (unsigned k = 0; k < 3; k++)
                w.nrm[i][k] = (int8_t)(base[k] + (int)np_rng_below(&g, sp) - (int)sp / 2);
        for (unsigned cn = 0; cn < 256; cn++) {
            c.c_n = (uint8_t)cn;
            cmp1(&c, &w, "normal threshold");
        }
    }
    printf("%" PRIu64 " windows at the thresholds (depth c_d at floor/ceil/+-1 of each crossing, %" PRIu64
           " exactly at k_d = j; luma r at t_min +-1 and lmax/8 +-1 over C_s; normals over every C): %" PRIu64
           " differ from the rational reference\n",
           checked, at_equal, mismatches);
    NP_CHECK(at_equal > 0, "no window met a depth threshold exactly");
    return 0;
}

/*
 * The host's registers against their definition: vd[j] is the least v with
 * c_d v > j n^2 2^48; rs[j] the least r with C_s r > 4080 j; na_on[j] iff
 * C^2 > 16 j^2 (a_j > 0).
 */
static int host_registers(void)
{
    np_rng g;
    np_rng_seed(&g, 77);
    unsigned checks = 0;
    for (unsigned t = 0; t < 20000; t++) {
        np_aacount_cfg c;
        rand_cfg(&g, &c);
        if (t < 4)
            c.c_d = t; /* 0 never fires; 1..3 never below 2^56 */
        np_aacount_regs r;
        np_aacount_regs_compute(&c, &r);
        unsigned n = (unsigned)c.m * c.m;
        for (unsigned j = 1; j < n; j++) {
            i128 num = (i128)j * n * n * ((i128)1 << 48);
            if (r.vd[j] < NP_AAC_VD_NEVER) {
                NP_CHECK((i128)c.c_d * r.vd[j] > num && (i128)c.c_d * (r.vd[j] - 1) <= num, "vd[%u]=%" PRIu64, j,
                         r.vd[j]);
            } else {
                NP_CHECK((i128)c.c_d * (NP_AAC_VD_NEVER - 1) <= num, "vd[%u] never but c_d=%u fires below 2^56", j,
                         c.c_d);
            }
            if (r.rs[j] < 256)
                NP_CHECK((uint32_t)c.c_s * r.rs[j] > 4080u * j && (uint32_t)c.c_s * (r.rs[j] - 1u) <= 4080u * j,
                         "rs[%u]=%u C_s=%u", j, r.rs[j], c.c_s);
            else
                NP_CHECK((uint32_t)c.c_s * 255u <= 4080u * j, "rs[%u] never but C_s=%u fires", j, c.c_s);
            uint64_t C2 = (uint64_t)c.c_n * c.c_n;
            NP_CHECK(r.na_on[j] == (C2 > 16u * j * j), "na_on[%u] C=%u", j, c.c_n);
            if (r.na_on[j])
                NP_CHECK(r.na[j] == (C2 - 16u * j * j) * (C2 - 16u * j * j), "na[%u]", j);
            checks++;
        }
        NP_CHECK(r.nd == (uint32_t)((uint64_t)c.c_n * c.c_n * c.c_n * c.c_n), "nd");
    }
    printf("%u threshold registers equal their definitions\n", checks);
    return 0;
}

/*
 * Depths near 2^24 - 1 differing by one LSB: v = n - 1 exactly. In single
 * precision, E[d^2] - E[d]^2 of the same depths (on [0, 1)) is not n - 1 / n^2
 * 2^-48; it comes out 0 or negative (a GPU's variance).
 */
static int depth_near_max_1lsb(void)
{
    for (unsigned m = 2; m <= 4; m++) {
        unsigned n = m * m;
        np_aacount_cfg c = np_aacount_cfg_default();
        c.m = (uint8_t)m;
        c.normal = c.luma = 0;
        c.c_d = 0xffffffffu;
        np_aacount_win w;
        memset(&w, 0, sizeof w);
        for (unsigned i = 0; i < n; i++)
            w.d[i] = 0xffffffu;
        w.d[0] = 0xfffffeu;
        np_aacount_sig s;
        np_aacount_sig_in(&s, &w);
        np_pipe p;
        /* v by the bit-exact stages: run the model and read v through the trace of stage V */
        np_aacount_out o;
        np_aacount_eval(&c, &w, &o);
        uint64_t sd = 0, sd2 = 0;
        for (unsigned i = 0; i < n; i++) {
            sd += w.d[i];
            sd2 += (uint64_t)w.d[i] * w.d[i];
        }
        uint64_t v = (uint64_t)n * sd2 - sd * sd;
        NP_CHECK(v == n - 1u, "m=%u: v=%" PRIu64 ", want %u", m, v, n - 1u);
        float fs = 0.0f, fs2 = 0.0f;
        for (unsigned i = 0; i < n; i++) {
            float d = (float)w.d[i] / 16777216.0f;
            fs += d;
            fs2 += d * d;
        }
        float fvar = fs2 / (float)n - (fs / (float)n) * (fs / (float)n);
        double exact = (double)(n - 1u) / ((double)n * n) / 281474976710656.0;
        printf("m=%u: exact v = %" PRIu64 " (Var = %.3e of the range^2); float32 E[d^2]-E[d]^2 = %.3e%s; s = %u\n", m,
               v, exact, (double)fvar, fvar < 0.0f ? " (negative)" : fvar == 0.0f ? " (zero)" : "", o.s);
        NP_CHECK(fvar <= 0.0f || fabs((double)fvar - exact) > exact, "m=%u: float32 variance %.3e is not wrong", m,
                 (double)fvar);
        /* every split of the window between 2^24 - 1 and 2^24 - 2: the float32 variance's least value */
        float fmin = 1.0f;
        for (unsigned kk = 1; kk < n; kk++) {
            float a = 0.0f, a2 = 0.0f;
            for (unsigned i = 0; i < n; i++) {
                float d = (float)(i < kk ? 0xfffffeu : 0xffffffu) / 16777216.0f;
                a += d;
                a2 += d * d;
            }
            float fv = a2 / (float)n - (a / (float)n) * (a / (float)n);
            fmin = fv < fmin ? fv : fmin;
        }
        printf("     over every split of the window between 2^24 - 2 and 2^24 - 1: least float32 variance %.3e%s\n",
               (double)fmin, fmin < 0.0f ? " (negative)" : "");
        /* c_d = 2^32 - 1: k_d = c_d (n - 1) / (n^2 2^48) << 1: one sample */
        NP_CHECK(o.sd == 1, "m=%u: sd=%u", m, o.sd);
        (void)p;
        (void)s;
    }
    return 0;
}

/*
 * The seed cube (vectors/scenes/marble.json: orthographic, eye (3.5,-2.5,3.5)
 * to (0.5,0.5,0.5), height 1.8 over 256 pixels): each of the three visible
 * faces has |N.v| = 1/sqrt(3), a depth slope tan = sqrt(2) along its steepest
 * screen direction, so an m x m window of sample spacing h = 1.8/(256 m)
 * holds a ramp of Var = 2 h^2 (m^2 - 1) / 12 world^2 (7.72e-6 at m = 4) > 0
 * on every window. With depth over the cube's extent along the view (sqrt 3,
 * u24), the windows of every face at every sub-pixel offset are quantised
 * and the least v found: every window fires (k_d > 1) iff
 * c_d > n^2 2^48 / v_min.
 */
static int slanted_cube_faces(void)
{
    const double R = sqrt(3.0), pix = 1.8 / 256.0;
    /* screen basis: view v = (-1,1,-1)/sqrt3, up (1,1,1) orthogonalised, right = v x up */
    double v[3] = { -1 / sqrt(3.0), 1 / sqrt(3.0), -1 / sqrt(3.0) };
    double up[3] = { 1, 1, 1 }, dvu = up[0] * v[0] + up[1] * v[1] + up[2] * v[2];
    for (unsigned k = 0; k < 3; k++)
        up[k] -= dvu * v[k];
    double ul = sqrt(up[0] * up[0] + up[1] * up[1] + up[2] * up[2]);
    for (unsigned k = 0; k < 3; k++)
        up[k] /= ul;
    double rt[3] = { v[1] * up[2] - v[2] * up[1], v[2] * up[0] - v[0] * up[2], v[0] * up[1] - v[1] * up[0] };
    static const double normals[3][3] = { { 1, 0, 0 }, { 0, -1, 0 }, { 0, 0, 1 } };
    for (unsigned m = 2; m <= 4; m++) {
        unsigned n = m * m;
        double h = pix / m, gr = 0, worst_var = 1e30;
        uint64_t vmin = UINT64_MAX;
        for (unsigned f = 0; f < 3; f++) {
            const double *N = normals[f];
            double nv = N[0] * v[0] + N[1] * v[1] + N[2] * v[2];
            /* depth z along v on the plane: dz/dx_screen = -(N.rt)/(N.v) */
            double gx = -(N[0] * rt[0] + N[1] * rt[1] + N[2] * rt[2]) / nv;
            double gy = -(N[0] * up[0] + N[1] * up[1] + N[2] * up[2]) / nv;
            gr = sqrt(gx * gx + gy * gy);
            double var = (gx * gx + gy * gy) * h * h * ((double)n - 1.0) / 12.0;
            worst_var = var < worst_var ? var : worst_var;
            for (unsigned off = 0; off < 4096; off++) {
                double z0 = 0.25 + 0.5 * (double)off / 4096.0, dx = (double)(off * 7u % 64u) / 64.0;
                uint64_t sd = 0, sd2 = 0;
                for (unsigned b = 0; b < m; b++)
                    for (unsigned a = 0; a < m; a++) {
                        double z = z0 + gx * h * (a + dx) + gy * h * b;
                        uint64_t d = (uint64_t)llround(z / R * 16777216.0);
                        sd += d;
                        sd2 += d * d;
                    }
                uint64_t vv = (uint64_t)n * sd2 - sd * sd;
                vmin = vv < vmin ? vv : vmin;
            }
        }
        NP_CHECK(vmin > 0, "m=%u: a slanted window with v = 0", m);
        i128 num = (i128)n * n * ((i128)1 << 48);
        uint64_t cstar = (uint64_t)(num / vmin); /* c_d > cstar fires on every window */
        double world = 1.0 / worst_var;
        printf("m=%u: depth slope %.4f, window Var %.3e world^2, least quantised v = %" PRIu64
               ": every face fires for c_d > %" PRIu64 " (per range^2; %.4g per world^2, 1/Var = %.4g)\n",
               m, gr, worst_var, vmin, cstar, (double)cstar / (R * R), world);
        NP_CHECK(fabs((double)cstar / (R * R) / world - 1.0) < 0.02, "m=%u: c_d* %.4g far from 1/Var %.4g", m,
                 (double)cstar / (R * R), world);
        np_aacount_cfg c = np_aacount_cfg_default();
        c.m = (uint8_t)m;
        c.normal = c.luma = 0;
        c.c_d = (uint32_t)(cstar + 1u);
        np_aacount_regs r;
        np_aacount_regs_compute(&c, &r);
        NP_CHECK(r.vd[1] <= vmin, "m=%u: c_d = c* + 1 does not fire on v_min", m);
        c.c_d = (uint32_t)cstar;
        np_aacount_regs_compute(&c, &r);
        NP_CHECK(r.vd[1] >= vmin || (i128)cstar * vmin > num, "m=%u: c_d = c* fires on v_min", m);
    }
    return 0;
}

/* nbar = 0 with surfaces: sn = n; every normal zero: sn = 1; c_n = 0: sn = 1. */
static int nbar_zero(void)
{
    for (unsigned m = 2; m <= 4; m++) {
        unsigned n = m * m;
        np_aacount_cfg c = np_aacount_cfg_default();
        c.m = (uint8_t)m;
        c.depth = c.luma = 0;
        np_aacount_win w;
        memset(&w, 0, sizeof w);
        for (unsigned i = 0; i + 1 < n; i += 2) {
            w.nrm[i][0] = 90;
            w.nrm[i][1] = -90;
            w.nrm[i + 1][0] = -90;
            w.nrm[i + 1][1] = 90;
        }
        np_aacount_out o;
        np_aacount_eval(&c, &w, &o);
        NP_CHECK(o.sn == n && o.s == n, "m=%u: cancelling normals sn=%u, want %u", m, o.sn, n);
        cmp1(&c, &w, "nbar = 0");
        c.c_n = 0;
        np_aacount_eval(&c, &w, &o);
        NP_CHECK(o.sn == 1, "m=%u: c_n = 0 gives sn=%u", m, o.sn);
        memset(&w, 0, sizeof w);
        c.c_n = 32;
        np_aacount_eval(&c, &w, &o);
        NP_CHECK(o.sn == 1, "m=%u: no surface gives sn=%u", m, o.sn);
        printf("m=%u: normals that cancel: sn = %u; c_n = 0 or no surface: sn = 1\n", m, n);
    }
    return 0;
}

/*
 * Identical quantised normals with |n| != 1: p = q exactly, so min|cos| = 1
 * and k_n = 0 (sn = 1) at every c_n. A GPU's normalised dot of such normals
 * can exceed 1, and sqrt(1 - x) is then NaN.
 */
static int identical_normals(void)
{
    np_rng g;
    np_rng_seed(&g, 6);
    unsigned nan_seen = 0, tried = 0;
    for (unsigned t = 0; t < 20000; t++) {
        np_aacount_cfg c = np_aacount_cfg_default();
        c.m = (uint8_t)(2 + t % 3);
        c.depth = c.luma = 0;
        c.c_n = (uint8_t)(1 + np_rng_below(&g, 255));
        np_aacount_win w;
        memset(&w, 0, sizeof w);
        int8_t e[3];
        do {
            for (unsigned k = 0; k < 3; k++)
                e[k] = (int8_t)((int)np_rng_below(&g, 256) - 128);
        } while (e[0] == 0 && e[1] == 0 && e[2] == 0);
        unsigned n = (unsigned)c.m * c.m;
        for (unsigned i = 0; i < n; i++)
            memcpy(w.nrm[i], e, 3);
        np_aacount_out o;
        np_aacount_eval(&c, &w, &o);
        NP_CHECK(o.sn == 1, "normal (%d,%d,%d): sn=%u", e[0], e[1], e[2], o.sn);
        /* float32 as a shader does it: normalise each, mean, normalise, dot */
        float nn = sqrtf((float)(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]));
        float u[3] = { e[0] / nn, e[1] / nn, e[2] / nn }, mb[3] = { 0, 0, 0 };
        for (unsigned i = 0; i < n; i++)
            for (unsigned k = 0; k < 3; k++)
                mb[k] += u[k] * 0.1f;
        float ml = sqrtf(mb[0] * mb[0] + mb[1] * mb[1] + mb[2] * mb[2]);
        float x = fabsf((mb[0] * u[0] + mb[1] * u[1] + mb[2] * u[2]) / ml);
        float kn = sqrtf(1.0f - x);
        nan_seen += isnan(kn) ? 1u : 0u;
        tried++;
    }
    printf("%u windows of identical normals: sn = 1 on all; float32 sqrt(1 - |cos|) is NaN on %u of them\n", tried,
           nan_seen);
    NP_CHECK(nan_seen > 0, "the float32 path never went NaN: the case shows nothing");
    return 0;
}

/* The luma gate with r exactly at t_min and at lmax t_edge, both sides; and the l_max >> 3 pitfall. */
static int luma_at_threshold(void)
{
    np_aacount_cfg c = np_aacount_cfg_default();
    c.depth = c.normal = 0;
    c.c_s = 16u * 255u; /* k_s = r: counts beyond 1 once the gate opens */
    struct {
        uint8_t l[5];
        unsigned want;
        const char *why;
    } k[] = {
        { { 0, 100, 116, 110, 108 }, 9, "r = 16 = t_min, 8 r = 128 >= 116: fires, k_s = 16 > n" },
        { { 0, 101, 116, 110, 108 }, 1, "r = 15 < t_min: gated" },
        { { 0, 200, 224, 210, 220 }, 9, "r = 24 > t_min, 8 r = 192 < 224: gated by t_edge? no: 192 < 224 gates" },
        { { 0, 196, 224, 210, 220 }, 9, "r = 28, 8 r = 224 = lmax: not below: fires" },
        { { 0, 197, 224, 210, 220 }, 1, "r = 27, 8 r = 216 < 224: gated by t_edge" },
        { { 0, 0, 9, 5, 5 }, 1, "lmax = 9, r = 9 < t_min: gated" },
    };
    k[2].want = 1;
    k[2].why = "r = 24 > t_min, 8 r = 192 < lmax 224: gated by t_edge";
    for (unsigned i = 0; i < sizeof k / sizeof k[0]; i++) {
        np_aacount_win w;
        memset(&w, 0, sizeof w);
        memcpy(w.luma, k[i].l, 5);
        np_aacount_out o;
        np_aacount_eval(&c, &w, &o);
        NP_CHECK(o.ss == k[i].want, "%s: ss=%u, want %u", k[i].why, o.ss, k[i].want);
        cmp1(&c, &w, k[i].why);
        printf("%-60s ss = %u\n", k[i].why, o.ss);
    }
    /* t_min = 0: lmax = 9, r = 1: the paper's r < 9/8 gates; floor(9/8) = 1 would not */
    c.t_min = 0;
    np_aacount_win w;
    memset(&w, 0, sizeof w);
    w.luma[1] = 8;
    w.luma[2] = 9;
    w.luma[3] = 9;
    w.luma[4] = 9;
    np_aacount_out o;
    np_aacount_eval(&c, &w, &o);
    NP_CHECK(o.ss == 1, "lmax = 9, r = 1, t_min = 0: ss=%u (r < 9/8 gates)", o.ss);
    cmp1(&c, &w, "lmax 9 r 1");
    printf("t_min = 0, lmax = 9, r = 1: gated (8 r = 8 < 9); a compare with lmax >> 3 = 1 would fire\n");
    return 0;
}

/* k far above n (every metric): s = n, the mask full. */
static int k_over_n(void)
{
    for (unsigned m = 1; m <= 4; m++) {
        np_aacount_cfg c = np_aacount_cfg_default();
        c.m = (uint8_t)m;
        c.c_d = 0xffffffffu;
        c.c_n = 255;
        c.c_s = 0xffff;
        if (m == 4)
            c.normal = 0; /* the registry's bus; the model itself takes both (below) */
        unsigned n = m * m;
        np_aacount_win w;
        memset(&w, 0, sizeof w);
        for (unsigned i = 0; i < n; i++)
            w.d[i] = i & 1u ? 0xffffffu : 0u;
        w.luma[2] = 255;
        np_aacount_out o;
        np_aacount_eval(&c, &w, &o);
        NP_CHECK(o.s == n && o.mask == (uint16_t)((1u << n) - 1u), "m=%u: s=%u mask=%04x", m, o.s, o.mask);
        c.normal = 1;
        np_aacount_eval(&c, &w, &o);
        NP_CHECK(o.s == n, "m=%u with normals: s=%u", m, o.s);
        cmp1(&c, &w, "k > n");
        printf("m=%u: k_d = %.3g, k_s = %.3g >> n: s = %u, mask %04x\n", m,
               (double)c.c_d * (n * n / 4) / (double)(n * n) * 0.25, 4095.9 * 255 / 255, o.s, o.mask);
    }
    return 0;
}

/* All thresholds 0 (the registers): every pixel shades n; every constant 0: s = 1 (S alone). */
static int thresholds_zero_and_c_zero(void)
{
    np_rng g;
    np_rng_seed(&g, 9);
    for (unsigned t = 0; t < 20000; t++) {
        np_aacount_cfg c;
        rand_cfg(&g, &c);
        c.depth = 1;
        if (c.m == 4)
            c.normal = 0;
        np_aacount_win w;
        rand_win(&g, (unsigned)c.m * c.m, &w);
        np_aacount_regs r;
        np_aacount_regs_compute(&c, &r);
        memset(r.vd, 0, sizeof r.vd);
        np_aacount_out o;
        np_aacount_eval_regs(&c, &r, &w, &o);
        unsigned n = (unsigned)c.m * c.m;
        NP_CHECK(o.s == n, "depth registers 0: s=%u, want %u", o.s, n);
        c.c_d = 0;
        c.c_n = 0;
        c.c_s = 0;
        np_aacount_eval(&c, &w, &o);
        NP_CHECK(o.s == 1 && o.mask == np_aacount_mask(c.m, 1), "c = 0: s=%u", o.s);
    }
    printf("20000 windows: depth registers 0 give s = n; c_d = c_n = c_s = 0 give s = 1 (mask = B_m index 0)\n");
    return 0;
}

/* The paper's matrices: permutations of 0..n-1; B3's 0 at the centre; B4 is Bayer's with 0 and 1 swapped. */
static int bayer_matrices(void)
{
    static const unsigned bayer4_std[4][4] = { { 0, 8, 2, 10 }, { 12, 4, 14, 6 }, { 3, 11, 1, 9 }, { 15, 7, 13, 5 } };
    for (unsigned m = 2; m <= 4; m++) {
        unsigned seen = 0;
        for (unsigned b = 0; b < m; b++)
            for (unsigned a = 0; a < m; a++)
                seen |= 1u << np_aacount_bayer(m, a, b);
        NP_CHECK(seen == (1u << (m * m)) - 1u, "B%u is not a permutation", m);
        for (unsigned s = 1; s <= m * m; s++) {
            uint16_t mk = np_aacount_mask(m, s);
            NP_CHECK((unsigned)__builtin_popcount(mk) == s, "B%u mask of %u has %d bits", m, s, __builtin_popcount(mk));
            NP_CHECK((np_aacount_mask(m, s - 1) & ~mk) == 0, "B%u: masks not nested at %u", m, s);
        }
    }
    NP_CHECK(np_aacount_bayer(1, 0, 0) == 0 && np_aacount_mask(1, 1) == 1, "B1 = [[0]]");
    NP_CHECK(np_aacount_bayer(2, 1, 0) == 2 && np_aacount_bayer(2, 0, 1) == 3, "B2 = [[0,2],[3,1]]");
    NP_CHECK(np_aacount_bayer(3, 1, 1) == 0, "B3's 0 is not the centre");
    unsigned diff = 0;
    for (unsigned b = 0; b < 4; b++)
        for (unsigned a = 0; a < 4; a++)
            diff += np_aacount_bayer(4, a, b) != bayer4_std[b][a];
    NP_CHECK(diff == 2, "B4 differs from Bayer's standard matrix in %u places, want 2 (0 and 1 swapped)", diff);
    printf("B2, B3, B4 are permutations; B3[1][1] = 0 (centre); B4 = Bayer's with 0 and 1 swapped; mask(s) has s bits, "
           "the masks nested\n");
    return 0;
}

/* Every (s, sum) pair: out = round-half-up(sum / s) exactly. */
static int resolve_exhaustive(void)
{
    unsigned pairs = 0;
    for (unsigned s = 1; s <= NP_AAC_N_MAX; s++) {
        NP_CHECK(np_aacount_rom(s) < (1u << NP_AAC_ROM_BITS), "rom[%u] = %u exceeds u18", s, np_aacount_rom(s));
        for (uint32_t sum = 0; sum <= 255u * s; sum++, pairs++) {
            unsigned want = (2u * sum + s) / (2u * s);
            unsigned got = np_aacount_resolve(sum, s);
            NP_CHECK(got == want, "s=%u sum=%u: %u, want %u", s, sum, got, want);
        }
    }
    /* one bit less of ROM fraction fails somewhere: the 17 bits are needed */
    unsigned fail16 = 0;
    for (unsigned s = 1; s <= NP_AAC_N_MAX; s++) {
        uint64_t rom = ((1u << 16) + s - 1u) / s;
        for (uint32_t sum = 0; sum <= 255u * s; sum++)
            fail16 += (unsigned)(((sum * rom + (1u << 15)) >> 16) != (2u * sum + s) / (2u * s));
    }
    printf("resolve: %u (s, sum) pairs, every one round-half-up(sum / s) with rom[s] = ceil(2^17 / s) (16 x u18);"
           " with 16 fraction bits %u pairs fail\n",
           pairs, fail16);
    NP_CHECK(fail16 > 0, "16 bits would do: the ROM is wider than needed");
    return 0;
}

/* The 6 x 6 tile maximum, a partial tile at the border included. */
static int tile_max(void)
{
    uint8_t s[14 * 8];
    for (unsigned i = 0; i < sizeof s; i++)
        s[i] = 1;
    s[3 * 14 + 4] = 7;  /* tile (0,0) */
    s[7 * 14 + 13] = 5; /* tile (2,1), partial: columns 12..13, rows 6..7 */
    np_aacount_tile_max(s, 14, 8);
    unsigned total = 0;
    for (unsigned y = 0; y < 8; y++)
        for (unsigned x = 0; x < 14; x++) {
            unsigned want = (x < 6 && y < 6) ? 7u : (x >= 12 && y >= 6) ? 5u : 1u;
            NP_CHECK(s[y * 14 + x] == want, "(%u,%u) = %u, want %u", x, y, s[y * 14 + x], want);
            total += s[y * 14 + x];
        }
    printf("6x6 tile maximum over 14 x 8: 2 pixels of s > 1 become %u samples in all (from %u)\n", total,
           14u * 8u - 2u + 7u + 5u);
    return 0;
}

/* The window bus round-trips for every configuration shape. */
static int bus_roundtrip(void)
{
    np_rng g;
    np_rng_seed(&g, 3);
    for (unsigned t = 0; t < 5000; t++) {
        np_aacount_cfg c;
        rand_cfg(&g, &c);
        if (np_aacount_cfg_check(&c))
            continue;
        np_aacount_win w, w2;
        rand_win(&g, (unsigned)c.m * c.m, &w);
        /* the bus carries only what is built */
        if (!c.depth)
            memset(w.d, 0, sizeof w.d);
        if (!c.normal)
            memset(w.nrm, 0, sizeof w.nrm);
        if (!c.luma)
            memset(w.luma, 0, sizeof w.luma);
        for (unsigned i = (unsigned)c.m * c.m; i < NP_AAC_N_MAX; i++) {
            w.d[i] = 0;
            memset(w.nrm[i], 0, 3);
        }
        uint64_t words[8];
        np_aacount_bus_pack(&c, &w, words);
        np_aacount_bus_unpack(&c, words, &w2);
        NP_CHECK(memcmp(&w, &w2, sizeof w) == 0, "m=%u: bus round trip", c.m);
    }
    np_aacount_cfg c = np_aacount_cfg_default();
    c.m = 4;
    NP_CHECK(np_aacount_cfg_check(&c) != NULL, "m=4 with depth and normal (808 bits) accepted on the bus");
    printf("bus: 5000 windows round-trip; m=3 all metrics %u bits, m=4 with depth and normal %u bits (refused)\n",
           np_aacount_bus_bits(&(np_aacount_cfg){ .m = 3, .depth = 1, .normal = 1, .luma = 1 }),
           np_aacount_bus_bits(&c));
    return 0;
}

/* The serial variant: the bit-exact outputs, a window every n clocks, latency 2n. */
static int serial_model(void)
{
    np_rng g;
    np_rng_seed(&g, 21);
    for (unsigned m = 1; m <= 4; m++) {
        np_aacount_cfg c = np_aacount_cfg_default();
        c.m = (uint8_t)m;
        c.serial = 1;
        unsigned n = m * m, nwin = 200;
        np_aacount_win wins[200];
        for (unsigned i = 0; i < nwin; i++)
            rand_win(&g, n, &wins[i]);
        np_aacount_serial u;
        np_aacount_serial_init(&u, &c);
        unsigned sent = 0, got = 0, beat = 0;
        uint64_t first_clock = 0, first_out = 0, last_out = 0;
        for (uint64_t clk = 0; got < nwin && clk < 100000; clk++) {
            int valid = sent < nwin;
            int took = np_aacount_serial_clock(&u, valid, valid ? &wins[sent] : NULL);
            if (took) {
                if (sent == 0 && beat == 0)
                    first_clock = clk;
                if (++beat == n) {
                    beat = 0;
                    sent++;
                }
            }
            if (u.out_valid) {
                np_aacount_out o;
                np_aacount_eval(&c, &wins[got], &o);
                NP_CHECK(memcmp(&o, &u.out, sizeof o) == 0, "m=%u window %u: serial s=%u, bit-exact %u", m, got,
                         u.out.s, o.s);
                if (got == 0)
                    first_out = clk;
                last_out = clk;
                got++;
            }
        }
        NP_CHECK(got == nwin, "m=%u: %u of %u windows out", m, got, nwin);
        NP_CHECK(first_out - first_clock == np_aacount_serial_latency(&c), "m=%u: latency %" PRIu64 ", want %u", m,
                 first_out - first_clock, np_aacount_serial_latency(&c));
        NP_CHECK(last_out - first_out == (uint64_t)(nwin - 1u) * n, "m=%u: %" PRIu64 " clocks for %u windows", m,
                 last_out - first_out, nwin - 1u);
        printf("m=%u serial: %u windows bit-exact, latency %" PRIu64 " clocks, one window every %u clocks\n", m, got,
               first_out - first_clock, n);
    }
    return 0;
}

static const np_test_case cases[] = {
    { "kat", kat },
    { "ref_random", ref_random },
    { "ref_thresholds", ref_thresholds },
    { "host_registers", host_registers },
    { "depth_near_max_1lsb", depth_near_max_1lsb },
    { "slanted_cube_faces", slanted_cube_faces },
    { "nbar_zero", nbar_zero },
    { "identical_normals", identical_normals },
    { "luma_at_threshold", luma_at_threshold },
    { "k_over_n", k_over_n },
    { "thresholds_zero_and_c_zero", thresholds_zero_and_c_zero },
    { "bayer_matrices", bayer_matrices },
    { "resolve_exhaustive", resolve_exhaustive },
    { "tile_max", tile_max },
    { "bus_roundtrip", bus_roundtrip },
    { "serial_model", serial_model },
    { NULL, NULL },
};

NP_TEST_MAIN(cases)
