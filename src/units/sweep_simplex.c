/* SPDX-License-Identifier: MIT */
/*
 * simplex3's sweep kernel (np_unit.sweep_rows): rows of 256 inputs at one
 * (y, z), the bit-exact model through its batch loop (np_simplex_eval_n,
 * vectorised across the row) and the float reference through a row form of
 * np_ref_simplex3 that gives the very same doubles (test
 * sweep.simplex_kernel_*), also vectorised across the row.
 *
 * The reference row. np_ref_simplex3 (src/ref/ref_simplex.c) per input, in
 * its order of operations, in two passes that GCC vectorises (-fopt-info-vec:
 * both loops in the x86-64-v4 and v3 clones; where AVX-512 is missing their
 * selects are done on bit patterns, pick()):
 *  - pass 1 (ref_pass1), per input: the skew, floor(x + s) as a double fi (an
 *    integer < 2^9, by floor_pos: the same double as floor(), no call), the
 *    unskew, (u, v, w), and a key = (cell, the three rank comparisons) as an
 *    exact integer-valued double;
 *  - a scalar scan cuts the row into runs of one key (one simplex: a row
 *    crosses a few cells and rank changes); per run, ref_corners finds the
 *    reference's four corners, hashes (np_hash6_fast == the bit loop,
 *    fast.hash_exhaustive) and Appendix B gradients (grad_coef, as in the
 *    reference) once;
 *  - pass 2 (ref_pass2) per input of the run: the corner loop with the run's
 *    constants. Appendix B's g = p + (q + r) (q or r unused for 48 of the 64
 *    gradients) is formed as X + (Y + Z) in the rotation whose first term is
 *    the p axis, X = G_x d_x etc. with G = 0.0 on an unused axis, and the
 *    rotation is taken by weights 1.0/0.0 (no select on a loop-invariant
 *    condition); a corner outside the kernel (t < 0) leaves f and df
 *    unchanged by a select instead of a `continue`.
 * None of this changes a nonzero double: X + (Y + 0*d) == X + Y whenever the
 * result is nonzero, and 1*g + 0*g' + 0*g'' == g when g != 0 (every
 * operand is finite). Only the sign of a zero g can differ, and it cannot
 * show: f and df start at +0.0 and only ever have terms added (df: 8 t^4 G_a
 * - 64 t^3 g d_a, itself +-0.0 when it is zero); under round-to-nearest
 * x + (+-0) == x for x != 0 and +0 + (+-0) == +0, so a sum that starts at
 * +0.0 is never -0.0 and a term's zero sign cannot show in it. Every other
 * operation is the reference's, in its order, with -ffp-contract=off (no
 * FMA) in every clone. Tests fast.simplex_kernel_block (2^24 inputs) and
 * fast.simplex_kernel_random compare every double's bits.
 */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "np_hash.h"
#include "np_simplex.h"
#include "np_unit_sweep.h"
#include "np_simplex32.h"

/* ---- The reference row, in segments ---- */

/*
 * floor(a) for 0 <= a < 2^51, the same double: a + 1.5 * 2^52 rounds a to a
 * nearest integer n (the sum lies in [2^52, 2^53), where doubles are the
 * integers), exactly; n - 1.5 * 2^52 is exact; n - 1 when n > a. A select,
 * not a call: GCC inlines floor() into a vector loop only with
 * -fno-trapping-math, which noisepipe does not use.
 */
/*
 * c ? a : b (c = 0 or 1): a or b unchanged either way. bits = 0: the `?:`,
 * which GCC 12 under -ftrapping-math if-converts only with AVX-512 masks
 * (the v4 clone: masked operations, the fastest there); bits = 1: the same
 * choice on the bit patterns (and, andnot, or), which the v3 and baseline
 * clones vectorise too (they ran the reference row scalar). ref_row_bits()
 * picks bits = 0 when the CPU has AVX-512F, else 1; both give the same
 * doubles (a or b, bit for bit; fast.simplex_kernel_random runs both).
 */
NP_SWEEP_INLINE double pick(const int bits, int c, double a, double b)
{
    if (!bits)
        return c ? a : b;
    uint64_t ia, ib, m = (uint64_t)0 - (uint64_t)c;
    memcpy(&ia, &a, sizeof ia);
    memcpy(&ib, &b, sizeof ib);
    ia = (ia & m) | (ib & ~m);
    memcpy(&a, &ia, sizeof a);
    return a;
}

NP_SWEEP_INLINE double floor_pos(const int bits, double a)
{
    double n = (a + 0x1.8p52) - 0x1.8p52, n1 = n - 1.0;
    return pick(bits, n > a, n1, n);
}

/*
 * Pass 1 of a row: per input the reference's skew, cell and unskewed offsets
 * (u, v, w) and a key naming its simplex: the cell and the three rank
 * comparisons. Only doubles: the loop vectorises.
 */
NP_SWEEP_INLINE void ref_pass1(const int bits, const double *restrict xs, double y, double z, double *restrict u,
                               double *restrict v, double *restrict w, double *restrict key)
{
    for (unsigned t = 0; t < NP_SWEEP_ROW; t++) {
        double x = xs[t];
        double s = (x + y + z) / 3;
        double fi = floor_pos(bits, x + s), fj = floor_pos(bits, y + s), fk = floor_pos(bits, z + s);
        s = (fi + fj + fk) / 6.;
        double uu = x - fi + s, vv = y - fj + s, ww = z - fk + s;
        /* the ranking reads u >= w, u >= v, v >= w (np_ref_simplex3's hi/lo rule) */
        double rank = (double)((uu >= ww) * 4 + (uu >= vv) * 2 + (vv >= ww)); /* 0..7, exact */
        u[t] = uu;
        v[t] = vv;
        w[t] = ww;
        /* fi, fj, fk < 2^9: the key is an exact integer < 2^33, one per (cell, rank) */
        key[t] = ((fi * 1024. + fj) * 1024. + fk) * 8. + rank;
    }
}

/* What a corner of one simplex contributes, constant over a segment of a row. */
typedef struct ref_corner {
    double a0, a1, a2, sa; /* the corner offset A and (A0 + A1 + A2) / 6 */
    double gx, gy, gz;     /* Appendix B's gradient coefficients on x, y, z (grad_coef) */
    double w1, w2, w0;     /* 1.0 for the gradient's p axis: x (h & 3 == 1), y (== 2), z (0, 3); others 0.0 */
} ref_corner;

/*
 * A corner's constants over one run, with what depends on v and w alone:
 * along a run only x (so u) changes; the cell, so fj, fk and the unskew
 * (fi + fj + fk) / 6, are the run's (pass 1's key names them), and
 * v = y - fj + s, w = z - fk + s are the same doubles for every input of it.
 * So d1, d2, d1 d1, d2 d2, Y = G_y d1, Z = G_z d2 and Y + Z are computed once
 * per run, by the same operations on the same operands: the same doubles.
 */
typedef struct ref_rcorner {
    ref_corner k;
    double d1, d2, d1s, d2s, Y, Z, YZ;
} ref_rcorner;

static ref_rcorner ref_run_corner(const ref_corner k, double v, double w)
{
    ref_rcorner r;
    r.k = k;
    r.d1 = v - k.a1 + k.sa;
    r.d2 = w - k.a2 + k.sa;
    r.d1s = r.d1 * r.d1;
    r.d2s = r.d2 * r.d2;
    r.Y = k.gy * r.d1;
    r.Z = k.gz * r.d2;
    r.YZ = r.Y + r.Z;
    return r;
}

/*
 * One corner of np_ref_simplex3's corner loop at (u, v, w), in its order: d,
 * t, the gradient p + (q + r), f += 8 t^4 g, df += 8 t^4 G - 64 t^3 g d; a
 * corner with t < 0 is skipped by a select. The three orders of the gradient
 * sum are all computed and the one of the p axis is taken by weights 1, 0, 0
 * (1 g + 0 g' + 0 g'' == g when g != 0, and a zero when g is one): no
 * operation is under a condition and no select has a loop-invariant
 * condition, so GCC can if-convert and vectorise the loop. v and w enter
 * through the run's constants (ref_run_corner).
 */
NP_SWEEP_INLINE void ref_corner_add(const int bits, const ref_rcorner r, double u, const int deriv, double *f, double *df0,
                                    double *df1, double *df2)
{
    const ref_corner k = r.k;
    double d0 = u - k.a0 + k.sa, d1 = r.d1, d2 = r.d2;
    double tt = .6 - d0 * d0 - r.d1s - r.d2s; /* .6 - d0 d0 - d1 d1 - d2 d2, left to right */
    double X = k.gx * d0, Y = r.Y, Z = r.Z;
    double g1 = X + r.YZ, g2 = Y + (Z + X), g0 = Z + (X + Y);
    double g = (k.w1 * g1 + k.w2 * g2) + k.w0 * g0; /* one weight 1.0, two 0.0: the selected sum, or a zero */
    double t2 = tt * tt;
    double nf = *f + 8 * t2 * t2 * g;
    *f = pick(bits, tt < 0, *f, nf);
    if (deriv) {
        double t3 = t2 * tt, t4 = t2 * t2;
        double n0 = *df0 + (8 * t4 * k.gx - 64 * t3 * g * d0);
        double n1 = *df1 + (8 * t4 * k.gy - 64 * t3 * g * d1);
        double n2 = *df2 + (8 * t4 * k.gz - 64 * t3 * g * d2);
        *df0 = pick(bits, tt < 0, *df0, n0);
        *df1 = pick(bits, tt < 0, *df1, n1);
        *df2 = pick(bits, tt < 0, *df2, n2);
    }
}

/*
 * Pass 2: the four corners of one simplex for the inputs [t0, t1) of a row
 * (v and w: the run's). Doubles only, in whole blocks of REF_LANES (one
 * AVX-512 vector): a run is 63 inputs on average and a remainder loop would
 * run scalar. The last block reads and writes up to REF_LANES - 1 inputs past
 * t1; ref_row gives every array that room, and the next run, or nothing,
 * overwrites them.
 */
enum { REF_LANES = 8 };
NP_SWEEP_INLINE void ref_pass2(const int bits, const ref_corner *restrict cn, unsigned t0, unsigned t1, const double *restrict u,
                               double v, double w, const int deriv, double *restrict rf, double *restrict rdx,
                               double *restrict rdy, double *restrict rdz)
{
    const ref_rcorner k0 = ref_run_corner(cn[0], v, w), k1 = ref_run_corner(cn[1], v, w),
                      k2 = ref_run_corner(cn[2], v, w), k3 = ref_run_corner(cn[3], v, w);
    for (unsigned b = t0; b < t1; b += REF_LANES)
        for (unsigned j = 0; j < REF_LANES; j++) {
            unsigned t = b + j;
            double f = 0.0, df0 = 0.0, df1 = 0.0, df2 = 0.0;
            ref_corner_add(bits, k0, u[t], deriv, &f, &df0, &df1, &df2);
            ref_corner_add(bits, k1, u[t], deriv, &f, &df0, &df1, &df2);
            ref_corner_add(bits, k2, u[t], deriv, &f, &df0, &df1, &df2);
            ref_corner_add(bits, k3, u[t], deriv, &f, &df0, &df1, &df2);
            rf[t] = f;
            if (deriv) {
                rdx[t] = df0;
                rdy[t] = df1;
                rdz[t] = df2;
            }
        }
}

/* Appendix B's gradient coefficients of index h on x, y, z (np_ref_simplex3's grad_coef). */
static void grad_coef(unsigned h, double gc[3])
{
    unsigned b5 = h >> 5 & 1u, b4 = h >> 4 & 1u, b3 = h >> 3 & 1u, b2 = h >> 2 & 1u, b = h & 3u;
    unsigned p = b == 1 ? 0u : b == 2 ? 1u : 2u, q = b == 1 ? 1u : b == 2 ? 2u : 0u, r = b == 1 ? 2u : b == 2 ? 0u : 1u;
    gc[0] = gc[1] = gc[2] = 0.0;
    gc[p] = b5 == b3 ? -1.0 : 1.0;
    if (b == 0 || b2 == 0)
        gc[q] = b5 == b4 ? -1.0 : 1.0;
    if (b == 0 || b2 != 0)
        gc[r] = b5 != (b4 ^ b3) ? -1.0 : 1.0;
}

/* The four corners of the simplex that pass 1's key names (cell and rank, as np_ref_simplex3 finds them). */
static void ref_corners(double key, ref_corner cn[4])
{
    uint64_t kk = (uint64_t)key;
    unsigned ra = (unsigned)(kk >> 2 & 1u), rb = (unsigned)(kk >> 1 & 1u), rc = (unsigned)(kk & 1u);
    uint32_t fk = (uint32_t)(kk >> 3 & 1023u), fj = (uint32_t)(kk >> 13 & 1023u), fi = (uint32_t)(kk >> 23);
    /* hi = u >= w ? u >= v ? 0 : 1 : v >= w ? 1 : 2; lo = u < w ? u < v ? 0 : 1 : v < w ? 1 : 2 */
    unsigned hi = ra ? (rb ? 0u : 1u) : (rc ? 1u : 2u);
    unsigned lo = !ra ? (!rb ? 0u : 1u) : (!rc ? 1u : 2u);
    const unsigned step[4] = { hi, 3u - hi - lo, lo, 0u };
    unsigned a[3] = { 0, 0, 0 };
    for (unsigned c = 0; c < 4; c++) {
        ref_corner *k = &cn[c];
        unsigned h = np_hash6_fast((uint8_t)((fi + a[0]) & 255u), (uint8_t)((fj + a[1]) & 255u),
                                   (uint8_t)((fk + a[2]) & 255u));
        double gc[3];
        grad_coef(h, gc);
        k->a0 = (double)a[0];
        k->a1 = (double)a[1];
        k->a2 = (double)a[2];
        k->sa = (double)(a[0] + a[1] + a[2]) / 6.;
        k->gx = gc[0];
        k->gy = gc[1];
        k->gz = gc[2];
        k->w1 = (h & 3u) == 1u ? 1.0 : 0.0;
        k->w2 = (h & 3u) == 2u ? 1.0 : 0.0;
        k->w0 = (h & 3u) == 0u || (h & 3u) == 3u ? 1.0 : 0.0;
        a[step[c]]++;
    }
}

/*
 * The corners of recent keys (rows next to each other cross the same
 * simplices): direct-mapped, REF_CACHE entries, one cache per thread that
 * lives across calls (a key's corners depend on the key alone: the reference
 * has no configuration); key -1 marks an empty entry.
 */
enum { REF_CACHE = 64 };
typedef struct ref_cache {
    double key[REF_CACHE];
    ref_corner cn[REF_CACHE][4];
} ref_cache;

static const ref_corner *ref_corners_cached(ref_cache *cache, double key)
{
    uint64_t kk = (uint64_t)key;
    unsigned e = (unsigned)((kk * 0x9e3779b97f4a7c15u) >> 58); /* 6 bits: REF_CACHE */
    if (cache->key[e] != key) {
        ref_corners(key, cache->cn[e]);
        cache->key[e] = key;
    }
    return cache->cn[e];
}

/*
 * The runs of one key in a row from brk[t] = (key[t] != key[t - 1]) for
 * 1 <= t < NP_SWEEP_ROW (a vector loop of the caller's; brk[0] unused):
 * start[k] the first input of run k, k < n, and start[n] = NP_SWEEP_ROW;
 * returns n. The flags are read eight at a time (a row has about four runs),
 * instead of a scalar compare loop over every input.
 */
static unsigned row_runs(unsigned char *brk, unsigned short *start)
{
    unsigned n = 0;
    brk[0] = 1;
    for (unsigned w = 0; w < NP_SWEEP_ROW; w += 8) {
        uint64_t word;
        memcpy(&word, brk + w, sizeof word);
        if (word == 0)
            continue;
        for (unsigned t = w; t < w + 8u; t++)
            if (brk[t])
                start[n++] = (unsigned short)t;
    }
    start[n] = NP_SWEEP_ROW;
    return n;
}

/* row_runs of a row of keys: reference (double) and model (uint32) keys; the flag loops vectorise. */
NP_SWEEP_INLINE unsigned runs_f64(const double *key, unsigned short *start)
{
    unsigned char brk[NP_SWEEP_ROW];
    for (unsigned t = 1; t < NP_SWEEP_ROW; t++)
        brk[t] = key[t] != key[t - 1];
    return row_runs(brk, start);
}

NP_SWEEP_INLINE unsigned runs_u32(const uint32_t *key, unsigned short *start)
{
    unsigned char brk[NP_SWEEP_ROW];
    for (unsigned t = 1; t < NP_SWEEP_ROW; t++)
        brk[t] = key[t] != key[t - 1];
    return row_runs(brk, start);
}

/* One row of np_ref_simplex3 at xs[t], y / 256, z / 256: pass 1, then pass 2 over each run of one simplex. */
NP_SWEEP_INLINE void ref_row(const int bits, ref_cache *cache, const double *restrict xs, uint16_t yw, uint16_t zw,
                             const int deriv, double *restrict rf, double *restrict rdx, double *restrict rdy,
                             double *restrict rdz)
{
    enum { PAD = NP_SWEEP_ROW + REF_LANES };
    double u[PAD], v[PAD], w[PAD], key[NP_SWEEP_ROW], of[PAD], ox[PAD], oy[PAD], oz[PAD];
    ref_pass1(bits, xs, (double)yw / 256.0, (double)zw / 256.0, u, v, w, key);
    for (unsigned t = NP_SWEEP_ROW; t < PAD; t++)
        u[t] = 0.0; /* a finite value for the spilled lanes */
    unsigned short start[NP_SWEEP_ROW + 1];
    unsigned runs = runs_f64(key, start);
    for (unsigned k = 0; k < runs; k++) {
        unsigned t0 = start[k], t1 = start[k + 1];
        ref_pass2(bits, ref_corners_cached(cache, key[t0]), t0, t1, u, v[t0], w[t0], deriv, of, ox, oy, oz);
    }
    memcpy(rf, of, NP_SWEEP_ROW * sizeof *rf);
    if (deriv) {
        memcpy(rdx, ox, NP_SWEEP_ROW * sizeof *rdx);
        memcpy(rdy, oy, NP_SWEEP_ROW * sizeof *rdy);
        memcpy(rdz, oz, NP_SWEEP_ROW * sizeof *rdz);
    }
}

/* The row with and without the derivative, each compiled without a branch on it (so it vectorises). */
NP_SWEEP_CLONES static void ref_row_d(int bits, ref_cache *cache, const double *xs, uint16_t y, uint16_t z,
                                      double *rf, double *rdx, double *rdy, double *rdz)
{
    if (bits)
        ref_row(1, cache, xs, y, z, 1, rf, rdx, rdy, rdz);
    else
        ref_row(0, cache, xs, y, z, 1, rf, rdx, rdy, rdz);
}

NP_SWEEP_CLONES static void ref_row_f(int bits, ref_cache *cache, const double *xs, uint16_t y, uint16_t z,
                                      double *rf)
{
    if (bits)
        ref_row(1, cache, xs, y, z, 0, rf, NULL, NULL, NULL);
    else
        ref_row(0, cache, xs, y, z, 0, rf, NULL, NULL, NULL);
}

/* -1: by the CPU (ref_row_bits); 0 or 1: forced (np_sweep_simplex3_force_bits, for the tests). */
static int ref_bits_forced = -1;

void np_sweep_simplex3_force_bits(int bits) { ref_bits_forced = bits < 0 ? -1 : bits != 0; }

/* The reference row's select form: masks (bits = 0) where AVX-512F is there, else bit patterns. */
static int ref_row_bits(void)
{
    if (ref_bits_forced >= 0)
        return ref_bits_forced;
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
    return !__builtin_cpu_supports("avx512f");
#else
    return 1;
#endif
}

/* ---- The model row, in segments (the default configurations) ---- */

/*
 * np_simplex_eval (eval_one in np_simplex.c) for a row, in two passes, the
 * same inline arithmetic of np_simplex.h with the hash and gradient decode
 * hoisted out of the per-input loop:
 *  - pass 1 per input: the skewed cells (SK), the offsets and the three rank
 *    comparisons (RK), and a key naming the simplex (cells and comparisons);
 *  - a scan cuts the row into runs of one key; per run the four corners'
 *    masks, hashes and gradients are found once (np_simplex_corner_mask,
 *    np_simplex_corner_hash, np_grad_fast: they depend on the cells and the
 *    rank alone);
 *  - pass 2 per input of the run: every corner's D, G.D, R2, T, tau powers
 *    and terms, and the outputs, through the same inline functions with the
 *    configuration a compile-time constant.
 * So the codes are eval_one's by construction; fast.simplex_kernel_block and
 * fast.simplex_kernel_random compare every code with np_simplex_eval.
 */
typedef struct mdl_corner {
    int32_t b0, b1, b2; /* the corner's mask bits */
    int32_t cx, cy, cz; /* its gradient */
} mdl_corner;

static const np_simplex_cfg mdl_default_d = { 16, 16, 1, 24, 22, 22 };
static const np_simplex_cfg mdl_default_f = { 16, 16, 0, 23, 20, 22 };

NP_SWEEP_INLINE void mdl_pass1(uint16_t x0, uint16_t yw, uint16_t zw, int32_t *restrict o0, int32_t *restrict o1,
                               int32_t *restrict o2, uint32_t *restrict key)
{
    for (unsigned t = 0; t < NP_SWEEP_ROW; t++) {
        uint16_t xw = (uint16_t)(x0 + t);
        uint32_t c0 = np_simplex_cell(np_simplex_skew(xw, yw, zw));
        uint32_t c1 = np_simplex_cell(np_simplex_skew(yw, zw, xw));
        uint32_t c2 = np_simplex_cell(np_simplex_skew(zw, xw, yw));
        uint32_t n = c0 + c1 + c2;
        int32_t u = np_simplex_offset(xw, c0, n), v = np_simplex_offset(yw, c1, n), w = np_simplex_offset(zw, c2, n);
        /* np_simplex_rank's three comparators */
        uint32_t rank = (uint32_t)(u >= w) << 2 | (uint32_t)(u >= v) << 1 | (uint32_t)(v >= w);
        o0[t] = u;
        o1[t] = v;
        o2[t] = w;
        key[t] = ((c0 << 9 | c1) << 9 | c2) << 3 | rank; /* cells u9 each */
    }
}

static void mdl_corners(uint32_t key, mdl_corner cn[4])
{
    uint32_t cell[3] = { key >> 21 & 511u, key >> 12 & 511u, key >> 3 & 511u };
    uint8_t hi, lo;
    /* the comparators' results as np_simplex_rank reads them (u >= w, u >= v, v >= w) */
    int32_t uw = (int32_t)(key >> 2 & 1u), uv = (int32_t)(key >> 1 & 1u), vw = (int32_t)(key & 1u);
    hi = (uint8_t)(uw ? (uv ? 0 : 1) : (vw ? 1 : 2));
    lo = (uint8_t)(!uw ? (!uv ? 0 : 1) : (!vw ? 1 : 2));
    for (unsigned c = 0; c < 4; c++) {
        unsigned mask = np_simplex_corner_mask(hi, lo, c);
        np_grad g = np_grad_fast(np_simplex_corner_hash(cell, mask));
        cn[c].b0 = (int32_t)(mask & 1u);
        cn[c].b1 = (int32_t)(mask >> 1 & 1u);
        cn[c].b2 = (int32_t)(mask >> 2 & 1u);
        cn[c].cx = g.cx;
        cn[c].cy = g.cy;
        cn[c].cz = g.cz;
    }
}

NP_SWEEP_INLINE void mdl_corner_add(const np_simplex_cfg *cfg, const mdl_corner k, unsigned c, int32_t u, int32_t v,
                                    int32_t w, int64_t *s, int64_t *q0, int64_t *q1, int64_t *q2)
{
    int32_t d[3] = { np_simplex_corner_d(u, (unsigned)k.b0, c), np_simplex_corner_d(v, (unsigned)k.b1, c),
                     np_simplex_corner_d(w, (unsigned)k.b2, c) };
    np_grad g = { (int8_t)k.cx, (int8_t)k.cy, (int8_t)k.cz };
    int32_t gd = np_simplex_gdot(g, d);
    uint32_t t = np_simplex_kernel_t(np_simplex_r2(d));
    uint32_t tau2 = np_simplex_tau2(cfg, t);
    uint32_t tau4 = np_simplex_tau4(cfg, tau2);
    *s += np_simplex_fterm(cfg, tau4, gd);
    if (cfg->deriv) {
        int64_t q = np_simplex_qterm(cfg, np_simplex_tau3(tau2, t), gd);
        *q0 += np_simplex_eterm(cfg, tau4, k.cx) - np_simplex_mterm(q, d[0]);
        *q1 += np_simplex_eterm(cfg, tau4, k.cy) - np_simplex_mterm(q, d[1]);
        *q2 += np_simplex_eterm(cfg, tau4, k.cz) - np_simplex_mterm(q, d[2]);
    }
}

NP_SWEEP_INLINE void mdl_pass2(const np_simplex_cfg *cfg, const mdl_corner *restrict cn, unsigned t0, unsigned t1,
                               const int32_t *restrict o0, const int32_t *restrict o1, const int32_t *restrict o2,
                               int32_t *restrict f, int32_t *restrict dx, int32_t *restrict dy,
                               int32_t *restrict dz)
{
    const int64_t kf = np_simplex_kf(cfg), kd = np_simplex_kd(cfg);
    const mdl_corner k0 = cn[0], k1 = cn[1], k2 = cn[2], k3 = cn[3];
    for (unsigned t = t0; t < t1; t++) {
        int64_t s = 0, q0 = 0, q1 = 0, q2 = 0;
        mdl_corner_add(cfg, k0, 0u, o0[t], o1[t], o2[t], &s, &q0, &q1, &q2);
        mdl_corner_add(cfg, k1, 1u, o0[t], o1[t], o2[t], &s, &q0, &q1, &q2);
        mdl_corner_add(cfg, k2, 2u, o0[t], o1[t], o2[t], &s, &q0, &q1, &q2);
        mdl_corner_add(cfg, k3, 3u, o0[t], o1[t], o2[t], &s, &q0, &q1, &q2);
        f[t] = np_simplex_out_f(cfg, kf, s);
        if (cfg->deriv) {
            dx[t] = np_simplex_out_d(cfg, kd, q0);
            dy[t] = np_simplex_out_d(cfg, kd, q1);
            dz[t] = np_simplex_out_d(cfg, kd, q2);
        }
    }
}


/*
 * One corner of pass 2 as mdl_corner_add with the default widths, in int32.
 * Along a run only the x offset changes: the cells and n are the run's, so
 * V = 6 Y - 1536 j + 256 n and W likewise are constant over it (pass 1's key
 * names the cells). m32_run_corner takes what depends on them alone once per
 * run: D1, D2, G1 D1 + G2 D2 and D1^2 + D2^2 (exact int32 sums, so
 * gd = G0 D0 + that and R2 = D0^2 + that are np_simplex_gdot's and
 * np_simplex_r2's values).
 */
typedef struct m32_corner {
    int32_t off0, cx, cy, cz; /* D0 = U + off0 (np_simplex_corner_d), the gradient */
    int32_t d1, d2, gd12, r212; /* D1, D2, G1 D1 + G2 D2, D1^2 + D2^2 */
} m32_corner;

static m32_corner m32_run_corner(const mdl_corner k, unsigned c, int32_t v, int32_t w)
{
    m32_corner m;
    m.off0 = np_simplex_corner_d(0, (unsigned)k.b0, c);
    m.cx = k.cx;
    m.cy = k.cy;
    m.cz = k.cz;
    m.d1 = np_simplex_corner_d(v, (unsigned)k.b1, c);
    m.d2 = np_simplex_corner_d(w, (unsigned)k.b2, c);
    m.gd12 = k.cy * m.d1 + k.cz * m.d2;
    m.r212 = m.d1 * m.d1 + m.d2 * m.d2;
    return m;
}

NP_SWEEP_INLINE void m32_corner_add(const m32_corner k, int32_t u, int32_t *s, int32_t *q0, int32_t *q1,
                                    int32_t *q2)
{
    int32_t d0 = u + k.off0;
    int32_t gd = k.cx * d0 + k.gd12;                           /* np_simplex_gdot */
    int32_t r2 = d0 * d0 + k.r212;                             /* np_simplex_r2 */
    int32_t td = NP_SIMPLEX_T_VERTEX - NP_SIMPLEX_R2_SCALE * r2; /* np_simplex_kernel_t */
    int32_t t = td > 0 ? td : 0;
    int32_t tau2 = m32_tau2(t), tau4 = m32_tau4(tau2), tau3 = m32_tau3(tau2, t);
    *s += m32_mul_rq11(tau4, gd);                              /* np_simplex_fterm: Q.33 -> Q.22 */
    int32_t q = m32_mul_rq11(tau3, gd);                        /* np_simplex_qterm */
    int32_t q5 = 4 * q + q;                                    /* np_simplex_mterm's 5q */
    /* np_simplex_eterm: G_a tau4 from Q.24 to Q.22, round half up; np_simplex_mterm: 5q D_a / 2^11 */
    *q0 += m32_eterm(k.cx, tau4) - m32_mul_rq11(q5, d0);
    *q1 += m32_eterm(k.cy, tau4) - m32_mul_rq11(q5, k.d1);
    *q2 += m32_eterm(k.cz, tau4) - m32_mul_rq11(q5, k.d2);
}

/*
 * Pass 2 over the inputs [t0, t1) of one run, in whole blocks of M32_LANES
 * (one AVX-512 vector of int32): a run is 63 inputs on average, and a
 * remainder loop would run scalar. The last block reads and writes up to
 * M32_LANES - 1 inputs past t1: o0 and the outputs have that much room
 * (m32_row), and the next run, or nothing, overwrites what it wrote. Those
 * spilled lanes pair another run's U (or 0) with this run's corners: still
 * |D| < 2^11 + 1536 + 768, so R2 < 2^26 and nothing overflows; and T > 0
 * only when every |D_a| < 1190, within the ranges of np_simplex32.h.
 */
enum { M32_LANES = 16 };
NP_SWEEP_INLINE void m32_pass2(const mdl_corner *restrict cn, unsigned t0, unsigned t1, const int32_t *restrict o0,
                               int32_t v, int32_t w, int32_t *restrict f, int32_t *restrict dx,
                               int32_t *restrict dy, int32_t *restrict dz)
{
    const int64_t kf = np_simplex_kf(&mdl_default_d), kd = np_simplex_kd(&mdl_default_d);
    const m32_corner k0 = m32_run_corner(cn[0], 0u, v, w), k1 = m32_run_corner(cn[1], 1u, v, w),
                     k2 = m32_run_corner(cn[2], 2u, v, w), k3 = m32_run_corner(cn[3], 3u, v, w);
    for (unsigned b = t0; b < t1; b += M32_LANES)
        for (unsigned j = 0; j < M32_LANES; j++) {
            unsigned t = b + j;
            int32_t s = 0, q0 = 0, q1 = 0, q2 = 0;
            m32_corner_add(k0, o0[t], &s, &q0, &q1, &q2);
            m32_corner_add(k1, o0[t], &s, &q0, &q1, &q2);
            m32_corner_add(k2, o0[t], &s, &q0, &q1, &q2);
            m32_corner_add(k3, o0[t], &s, &q0, &q1, &q2);
            f[t] = np_simplex_out_f(&mdl_default_d, kf, s);
            dx[t] = np_simplex_out_d(&mdl_default_d, kd, q0);
            dy[t] = np_simplex_out_d(&mdl_default_d, kd, q1);
            dz[t] = np_simplex_out_d(&mdl_default_d, kd, q2);
        }
}

/*
 * The corners of recent keys, one direct-mapped cache per thread that lives
 * across calls, as the reference row's (a key's corners depend on the cells
 * and the rank alone, not on the configuration); key ~0 (no key: cells are
 * u9) marks an empty entry.
 */
static const mdl_corner *mdl_corners_cached(uint32_t key)
{
    static _Thread_local uint32_t keys[REF_CACHE];
    static _Thread_local mdl_corner cns[REF_CACHE][4];
    static _Thread_local int ready;
    if (!ready) {
        for (unsigned e = 0; e < REF_CACHE; e++)
            keys[e] = ~0u;
        ready = 1;
    }
    unsigned e = (unsigned)(((uint64_t)key * 0x9e3779b97f4a7c15u) >> 58); /* 6 bits: REF_CACHE */
    if (keys[e] != key) {
        mdl_corners(key, cns[e]);
        keys[e] = key;
    }
    return cns[e];
}

NP_SWEEP_INLINE void mdl_row(const np_simplex_cfg *cfg, uint16_t x0, uint16_t y, uint16_t z, int32_t *f,
                             int32_t *dx, int32_t *dy, int32_t *dz)
{
    int32_t o0[NP_SWEEP_ROW], o1[NP_SWEEP_ROW], o2[NP_SWEEP_ROW];
    uint32_t key[NP_SWEEP_ROW];
    mdl_pass1(x0, y, z, o0, o1, o2, key);
    unsigned short start[NP_SWEEP_ROW + 1];
    unsigned runs = runs_u32(key, start);
    for (unsigned k = 0; k < runs; k++)
        mdl_pass2(cfg, mdl_corners_cached(key[start[k]]), start[k], start[k + 1], o0, o1, o2, f, dx, dy, dz);
}

/*
 * The model row for the default configuration with the derivative: pass 1,
 * then m32_pass2 per run into padded scratch (a run's last block spills past
 * its end), copied out.
 */
NP_SWEEP_INLINE void m32_row(uint16_t x0, uint16_t y, uint16_t z, int32_t *f, int32_t *dx, int32_t *dy, int32_t *dz)
{
    enum { PAD = NP_SWEEP_ROW + M32_LANES };
    int32_t o0[PAD], o1[PAD], o2[PAD], of[PAD], ox[PAD], oy[PAD], oz[PAD];
    uint32_t key[NP_SWEEP_ROW];
    mdl_pass1(x0, y, z, o0, o1, o2, key);
    for (unsigned t = NP_SWEEP_ROW; t < PAD; t++)
        o0[t] = 0; /* an offset: no overflow in the spilled lanes (m32_pass2) */
    unsigned short start[NP_SWEEP_ROW + 1];
    unsigned runs = runs_u32(key, start);
    for (unsigned k = 0; k < runs; k++) {
        unsigned t0 = start[k], t1 = start[k + 1];
        m32_pass2(mdl_corners_cached(key[t0]), t0, t1, o0, o1[t0], o2[t0], of, ox, oy, oz);
    }
    memcpy(f, of, NP_SWEEP_ROW * sizeof *f);
    memcpy(dx, ox, NP_SWEEP_ROW * sizeof *dx);
    memcpy(dy, oy, NP_SWEEP_ROW * sizeof *dy);
    memcpy(dz, oz, NP_SWEEP_ROW * sizeof *dz);
}

NP_SWEEP_CLONES static void mdl_row_d(uint16_t x0, uint16_t y, uint16_t z, int32_t *f, int32_t *dx, int32_t *dy,
                                      int32_t *dz)
{
    m32_row(x0, y, z, f, dx, dy, dz);
}

NP_SWEEP_CLONES static void mdl_row_f(uint16_t x0, uint16_t y, uint16_t z, int32_t *f)
{
    mdl_row(&mdl_default_f, x0, y, z, f, NULL, NULL, NULL);
}

static int mdl_same(const np_simplex_cfg *a, const np_simplex_cfg *b)
{
    return a->out_bits == b->out_bits && a->dout_bits == b->dout_bits && a->deriv == b->deriv &&
           a->t_frac == b->t_frac && a->p_frac == b->p_frac && a->k_frac == b->k_frac;
}

void np_sweep_simplex3_rows(const np_simplex_cfg *cfg, uint16_t x0, uint16_t y0, uint16_t z, unsigned rows,
                            unsigned what, int32_t *code, double *ref)
{
    unsigned nf = cfg->deriv ? 4u : 1u;
    const int bits = ref_row_bits();
    double xs_ref[NP_SWEEP_ROW]; /* the reference's x = word / 256, the same in every row */
    static _Thread_local ref_cache cache;
    static _Thread_local int cache_ready;
    if (!cache_ready) {
        for (unsigned e = 0; e < REF_CACHE; e++)
            cache.key[e] = -1.0;
        cache_ready = 1;
    }
    for (unsigned r = 0; r < rows; r++) {
        uint16_t y = (uint16_t)(y0 + r);
        int seg_d = mdl_same(cfg, &mdl_default_d), seg_f = mdl_same(cfg, &mdl_default_f);
        if ((what & NP_SWEEP_MODEL) && (seg_d || seg_f)) {
            size_t fs = (size_t)rows * NP_SWEEP_ROW;
            int32_t *c = code + (size_t)r * NP_SWEEP_ROW;
            if (seg_d)
                mdl_row_d(x0, y, z, c, c + fs, c + 2 * fs, c + 3 * fs);
            else
                mdl_row_f(x0, y, z, c);
        } else if (what & NP_SWEEP_MODEL) {
            uint16_t xs[NP_SWEEP_ROW], ys[NP_SWEEP_ROW], zs[NP_SWEEP_ROW];
            np_simplex_out o[NP_SWEEP_ROW];
            for (unsigned t = 0; t < NP_SWEEP_ROW; t++) {
                xs[t] = (uint16_t)(x0 + t);
                ys[t] = y;
                zs[t] = z;
            }
            np_simplex_eval_n(cfg, xs, ys, zs, o, NP_SWEEP_ROW);
            for (unsigned k = 0; k < nf; k++) {
                int32_t *dst = code + ((size_t)k * rows + r) * NP_SWEEP_ROW;
                for (unsigned t = 0; t < NP_SWEEP_ROW; t++)
                    dst[t] = k == 0 ? o[t].f : o[t].df[k - 1u];
            }
        }
        if (what & NP_SWEEP_REF) {
            if (r == 0)
                for (unsigned t = 0; t < NP_SWEEP_ROW; t++)
                    xs_ref[t] = (double)(uint16_t)(x0 + t) / 256.0;
            double *b = ref + (size_t)r * NP_SWEEP_ROW;
            size_t fs = (size_t)rows * NP_SWEEP_ROW;
            if (cfg->deriv)
                ref_row_d(bits, &cache, xs_ref, y, z, b, b + fs, b + 2 * fs, b + 3 * fs);
            else
                ref_row_f(bits, &cache, xs_ref, y, z, b);
        }
    }
}
