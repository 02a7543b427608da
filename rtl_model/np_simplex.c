/* SPDX-License-Identifier: MIT */
#include "np_simplex.h"

#include <stddef.h>
#include <string.h>

#include "np_simplex32.h"

/* The hand-vectorised batch path: GCC or Clang on x86-64 (chosen at run time by the CPU). */
#if (defined(__GNUC__) || defined(__clang__)) && defined(__x86_64__)
#define NP_SIMPLEX_HAVE_AVX2 1
#include <immintrin.h>
#else
#define NP_SIMPLEX_HAVE_AVX2 0
#endif
_Static_assert(sizeof(np_simplex_out) == 4 * sizeof(int32_t), "np_simplex_out is {f, df[3]}, no padding");

static unsigned umax(unsigned a, unsigned b) { return a > b ? a : b; }

np_simplex_cfg np_simplex_cfg_default(unsigned out_bits, unsigned dout_bits, unsigned deriv)
{
    np_simplex_cfg c;
    unsigned fd = dout_bits >= 2u ? dout_bits - 2u : 0u;
    c.out_bits = out_bits;
    c.dout_bits = dout_bits;
    c.deriv = deriv ? 1u : 0u;
    c.t_frac = out_bits + 7u;
    c.p_frac = out_bits + 4u;
    c.k_frac = out_bits + 6u;
    if (c.deriv) {
        c.t_frac = umax(c.t_frac, fd + 10u);
        c.p_frac = umax(c.p_frac, fd + 8u);
        c.k_frac = umax(c.k_frac, fd + 7u);
    }
    if (c.t_frac > NP_SIMPLEX_WT_MAX)
        c.t_frac = NP_SIMPLEX_WT_MAX;
    if (c.p_frac > NP_SIMPLEX_WP_MAX)
        c.p_frac = NP_SIMPLEX_WP_MAX;
    if (c.k_frac > NP_SIMPLEX_WK_MAX)
        c.k_frac = NP_SIMPLEX_WK_MAX;
    return c;
}

const char *np_simplex_cfg_check(const np_simplex_cfg *cfg)
{
    if (cfg->out_bits < NP_SIMPLEX_OUT_MIN || cfg->out_bits > NP_SIMPLEX_OUT_MAX)
        return "out_bits must be 4..20";
    if (cfg->dout_bits < NP_SIMPLEX_DOUT_MIN || cfg->dout_bits > NP_SIMPLEX_OUT_MAX)
        return "dout_bits must be 5..20";
    if (cfg->deriv > 1u)
        return "deriv must be 0 or 1";
    if (cfg->t_frac < 1u || cfg->t_frac > NP_SIMPLEX_WT_MAX)
        return "t_frac must be 1..30";
    if (cfg->p_frac < 1u || cfg->p_frac > NP_SIMPLEX_WP_MAX)
        return "p_frac must be 1..32";
    if (cfg->k_frac < 1u || cfg->k_frac > NP_SIMPLEX_WK_MAX)
        return "k_frac must be 1..26";
    return NULL;
}


/* Constants of the argument in np_simplex.h (upper bounds, rounded up). */
#define BOUND_TAU_MAX 0.84375       /* tau(0) */
#define BOUND_GD_MAX 4.0249224      /* sqrt(3 * 5.4) >= |G . d'| in the support */
#define BOUND_S_MAX 1.6981          /* |S| <= 4 * 0.42451 */
#define BOUND_Q_MAX 3.7093          /* |Q_a| <= 4 * 0.92731 */
#define BOUND_M_E 11.6913           /* 5/4 sqrt(3) * 5.4: e-coefficient of m_a */
#define BOUND_M_P 4.9047            /* 5/4 * 2.32379 + 1 (m rounding) + 1 (e_a rounding) */
#define BOUND_KF 0.68189671         /* 2^23 / 12301875, rounded up */
#define BOUND_KD 2.04569011         /* 2^23 / 4100625, rounded up */

double np_simplex_error_bound_lsb(const np_simplex_cfg *cfg, int deriv_field)
{
    double e = np_pow2i(-(int)cfg->t_frac - 1), p = np_pow2i(-(int)cfg->p_frac - 1),
           k = np_pow2i(-(int)cfg->k_frac - 1);
    double e4 = e * (2.0 * BOUND_TAU_MAX * BOUND_TAU_MAX + e) + e;
    if (!deriv_field) {
        double ef = 4.0 * (e4 * BOUND_GD_MAX + p);
        return 0.5 + np_pow2i((int)np_simplex_f_frac(cfg)) * (BOUND_KF * ef + k * (BOUND_S_MAX + ef));
    }
    double ed = 4.0 * (e4 + BOUND_M_E * e + BOUND_M_P * p);
    return 0.5 + np_pow2i((int)np_simplex_d_frac(cfg)) * (BOUND_KD * ed + k * (BOUND_Q_MAX + ed));
}

/*
 * Input word ruler (each of x, y, z), as the skew sees it:
 *   15            8 7             0
 *  +---------------+---------------+
 *  |  integer (u8) | fraction (u8) |     value = word / 256
 *  +---------------+---------------+
 * The skewed cell is not the high byte: it is floor((4x + y + z) / 768).
 */

/*
 * The model for one input, inlined into np_simplex_eval and into the batch
 * loops below, where a constant cfg folds every width (one definition of
 * the arithmetic).
 */
#if defined(__GNUC__)
#define ALWAYS_INLINE static inline __attribute__((always_inline))
#else
#define ALWAYS_INLINE static inline
#endif
ALWAYS_INLINE void eval_one(const np_simplex_cfg *cfg, int64_t kf, int64_t kd, uint16_t x, uint16_t y,
                            uint16_t z, np_simplex_out *out)
{
    const uint16_t in[3] = { x, y, z };
    uint32_t cell[3];
    int32_t off[3];
    for (unsigned a = 0; a < 3; a++)
        cell[a] = np_simplex_cell(np_simplex_skew(in[a], in[(a + 1u) % 3u], in[(a + 2u) % 3u]));
    uint32_t n = cell[0] + cell[1] + cell[2];
    for (unsigned a = 0; a < 3; a++)
        off[a] = np_simplex_offset(in[a], cell[a], n);
    uint8_t hi, lo;
    np_simplex_rank(off[0], off[1], off[2], &hi, &lo);

    int64_t s = 0, qs[3] = { 0, 0, 0 };
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC unroll 4
#endif
    for (unsigned c = 0; c < 4; c++) {
        unsigned mask = np_simplex_corner_mask(hi, lo, c);
        int32_t d[3];
        for (unsigned a = 0; a < 3; a++)
            d[a] = np_simplex_corner_d(off[a], mask >> a & 1u, c);
        /* np_simplex_corner_hash and np_grad_decode, through the 32-bit tables (vector gathers) */
        uint32_t gp = np_grad_packed32[np_hash6_fast32((cell[0] + (mask & 1u)) & NP_MASK(NP_SIMPLEX_HASH_BITS),
                                                       (cell[1] + (mask >> 1 & 1u)) & NP_MASK(NP_SIMPLEX_HASH_BITS),
                                                       (cell[2] + (mask >> 2 & 1u)) & NP_MASK(NP_SIMPLEX_HASH_BITS))];
        np_grad g = { (int8_t)np_grad_unpack(gp, 0), (int8_t)np_grad_unpack(gp, 1), (int8_t)np_grad_unpack(gp, 2) };
        int32_t gd = np_simplex_gdot(g, d);
        uint32_t t = np_simplex_kernel_t(np_simplex_r2(d));
        uint32_t tau2 = np_simplex_tau2(cfg, t);
        uint32_t tau4 = np_simplex_tau4(cfg, tau2);
        s += np_simplex_fterm(cfg, tau4, gd);
        if (cfg->deriv) {
            int64_t q = np_simplex_qterm(cfg, np_simplex_tau3(tau2, t), gd);
            const int coef[3] = { g.cx, g.cy, g.cz };
            for (unsigned a = 0; a < 3; a++)
                qs[a] += np_simplex_eterm(cfg, tau4, coef[a]) - np_simplex_mterm(q, d[a]);
        }
    }
    out->f = np_simplex_out_f(cfg, kf, s);
    for (unsigned a = 0; a < 3; a++)
        out->df[a] = cfg->deriv ? np_simplex_out_d(cfg, kd, qs[a]) : 0;
}

void np_simplex_eval(const np_simplex_cfg *cfg, uint16_t x, uint16_t y, uint16_t z,
                     np_simplex_out *out)
{
    eval_one(cfg, np_simplex_kf(cfg), np_simplex_kd(cfg), x, y, z, out);
}

/*
 * Batch: the default configurations (N = ND = 16, with and without the
 * derivative) with the widths as compile-time constants (WIDTHS); any other
 * runs eval_one with the configuration read once (GENERIC). Same bits either
 * way.
 */
static const np_simplex_cfg default_d = { 16, 16, 1, 24, 22, 22 };
static const np_simplex_cfg default_f = { 16, 16, 0, 23, 20, 22 };

static int same_cfg(const np_simplex_cfg *a, const np_simplex_cfg *b)
{
    return a->out_bits == b->out_bits && a->dout_bits == b->dout_bits && a->deriv == b->deriv &&
           a->t_frac == b->t_frac && a->p_frac == b->p_frac && a->k_frac == b->k_frac;
}

NP_BATCH_CLONES static void eval_n_default_d(const uint16_t *x, const uint16_t *y, const uint16_t *z,
                                             np_simplex_out *out, size_t count)
{
    const int64_t kf = np_simplex_kf(&default_d), kd = np_simplex_kd(&default_d);
    for (size_t n = 0; n < count; n++)
        eval_one(&default_d, kf, kd, x[n], y[n], z[n], &out[n]);
}

NP_BATCH_CLONES static void eval_n_default_f(const uint16_t *x, const uint16_t *y, const uint16_t *z,
                                             np_simplex_out *out, size_t count)
{
    const int64_t kf = np_simplex_kf(&default_f), kd = np_simplex_kd(&default_f);
    for (size_t n = 0; n < count; n++)
        eval_one(&default_f, kf, kd, x[n], y[n], z[n], &out[n]);
}

/*
 * --- INT32: the two defaults in int32 arithmetic. ---
 * eval_one's operations at WT = 24, WP = 22, WK = 22 (and, value only, at
 * WT = 23, WP = 20, WK = 22: |S| < 2^25.2, Kf' S below 2^48, rounded by 26
 * bits) with every signal in an int32 (np_simplex32.h gives the ranges: all
 * below 2^31) and the rounded products that exceed 32 bits formed from
 * 32-bit partial products (m32_tau2, ...: exact identities). Only Kf' S and
 * Kd' Q_a are 64-bit:
 * Kf' = 2860110 < 2^22, Kd' = 8580330 < 2^24 (np_simplex_kf, np_simplex_kd
 * at WK = 22), |S| < 2^27.2, |Q_a| < 2^29.7, so each product is below 2^54
 * and its rounded word below 2^23: the out words are those of
 * np_simplex_out_f and np_simplex_out_d (rounding by WK + WP - 16 = 28 and
 * WK + WP - 14 = 30 bits, saturation to s16).
 */
enum {
    D32_F_DROP = 22 + 22 - 16, /* Kf' S: Q.44 to Q.16 */
    D32_D_DROP = 22 + 22 - 14, /* Kd' Q_a: Q.44 to Q.14 */
    D32_FV_DROP = 22 + 20 - 16, /* value only (WP = 20): Kf' S from Q.42 to Q.16 */
    D32_OUT_MAX = 32767,
    D32_OUT_MIN = -32768
};

static int32_t out32(int32_t v, int64_t k, unsigned drop)
{
    int64_t r = np_shr_round_half_up((int64_t)v * k, drop);
    return (int32_t)(r > D32_OUT_MAX ? D32_OUT_MAX : r < D32_OUT_MIN ? D32_OUT_MIN : r);
}

/*
 * Both defaults (deriv: WT = 24, WP = 22; value only: WT = 23, WP = 20,
 * the _23 and rq12 products), WK = 22.
 */
ALWAYS_INLINE void eval_int32(const int deriv, const uint16_t *restrict xs, const uint16_t *restrict ys,
                              const uint16_t *restrict zs, np_simplex_out *restrict out, size_t count)
{
    const np_simplex_cfg *cfg = deriv ? &default_d : &default_f;
    const int64_t kf = np_simplex_kf(cfg), kd = np_simplex_kd(cfg);
    for (size_t n = 0; n < count; n++) {
        const uint16_t in[3] = { xs[n], ys[n], zs[n] };
        uint32_t cell[3];
        int32_t off[3];
        for (unsigned a = 0; a < 3; a++)
            cell[a] = np_simplex_cell(np_simplex_skew(in[a], in[(a + 1u) % 3u], in[(a + 2u) % 3u]));
        uint32_t nn = cell[0] + cell[1] + cell[2];
        for (unsigned a = 0; a < 3; a++)
            off[a] = np_simplex_offset(in[a], cell[a], nn);
        uint8_t hi, lo;
        np_simplex_rank(off[0], off[1], off[2], &hi, &lo);
        int32_t s = 0, qs[3] = { 0, 0, 0 };
        for (unsigned c = 0; c < 4; c++) {
            unsigned mask = np_simplex_corner_mask(hi, lo, c);
            int32_t d[3], g[3];
            for (unsigned a = 0; a < 3; a++)
                d[a] = np_simplex_corner_d(off[a], mask >> a & 1u, c);
            uint32_t gp = np_grad_packed32[np_hash6_fast32((cell[0] + (mask & 1u)) & NP_MASK(NP_SIMPLEX_HASH_BITS),
                                                           (cell[1] + (mask >> 1 & 1u)) & NP_MASK(NP_SIMPLEX_HASH_BITS),
                                                           (cell[2] + (mask >> 2 & 1u)) & NP_MASK(NP_SIMPLEX_HASH_BITS))];
            for (unsigned a = 0; a < 3; a++)
                g[a] = np_grad_unpack(gp, a);
            int32_t gd = g[0] * d[0] + g[1] * d[1] + g[2] * d[2];            /* np_simplex_gdot */
            int32_t td = NP_SIMPLEX_T_VERTEX - NP_SIMPLEX_R2_SCALE * (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            int32_t t = td > 0 ? td : 0;                                     /* np_simplex_kernel_t */
            if (!deriv) {
                s += m32_mul_rq12(m32_tau4_23(m32_tau2_23(t)), gd);          /* np_simplex_fterm */
                continue;
            }
            int32_t tau2 = m32_tau2(t), tau4 = m32_tau4(tau2), tau3 = m32_tau3(tau2, t);
            s += m32_mul_rq11(tau4, gd);                                     /* np_simplex_fterm */
            int32_t q = m32_mul_rq11(tau3, gd);                              /* np_simplex_qterm */
            int32_t q5 = 4 * q + q;                                          /* np_simplex_mterm's 5q */
            for (unsigned a = 0; a < 3; a++)
                qs[a] += m32_eterm(g[a], tau4) - m32_mul_rq11(q5, d[a]);     /* e_a - m_a */
        }
        out[n].f = out32(s, kf, deriv ? D32_F_DROP : D32_FV_DROP);
        for (unsigned a = 0; a < 3; a++)
            out[n].df[a] = deriv ? out32(qs[a], kd, D32_D_DROP) : 0;
    }
}

static void eval_n_int32(const uint16_t *xs, const uint16_t *ys, const uint16_t *zs, np_simplex_out *out,
                         size_t count)
{
    eval_int32(1, xs, ys, zs, out, count);
}

static void eval_n_int32_f(const uint16_t *xs, const uint16_t *ys, const uint16_t *zs, np_simplex_out *out,
                           size_t count)
{
    eval_int32(0, xs, ys, zs, out, count);
}

#if NP_SIMPLEX_HAVE_AVX2
/*
 * --- AVX2 and AVX-512: eval_n_int32 8 and 16 inputs a step, by hand. ---
 * GCC's vector extension (v8i, v16i: int32 lanes) carries the arithmetic,
 * so the rounded products are np_simplex32.h's text itself (v8_tau2, ...)
 * and the rest of the corner loop is np_simplex_lanes.inc's, one text for
 * both widths; the intrinsics do what the extension cannot say:
 *   - the hash's nibble tables (np_hash6_fast32) are read by vpgatherdd;
 *     the packed gradient (64 words) by vpgatherdd (AVX2) or by two
 *     vpermt2d, 32 words each, and a blend on bit 5 of h (AVX-512);
 *   - G_a D for a coefficient G_a in {-1, 0, +1} is vpsignd(D, G_a)
 *     (AVX2) or vpmulld (AVX-512, which has no vpsignd): exactly G_a D;
 *   - Kf' S and Kd' Q_a are vpmuldq (signed 32 x 32 -> 64 bits) on the even
 *     and the odd lanes, rounded in 64 bits (out8, out16);
 *   - the outputs are transposed to np_simplex_out's {f, df[3]} by unpacks
 *     and lane shuffles.
 * GCC and Clang define >> of a negative lane as arithmetic (V_ASR), and
 * the lane operations wrap like the int32 ones, which never overflow here.
 */
typedef int32_t v8i __attribute__((vector_size(32)));
typedef int32_t v16i __attribute__((vector_size(64)));
#define V_ASR(v, sh) ((v) >> (sh))

#define AVX2_FN __attribute__((target("avx2")))
AVX2_FN static inline v8i v8_mulc(v8i d, v8i c) { return (v8i)_mm256_sign_epi32((__m256i)d, (__m256i)c); }
NP_SIMPLEX32_PRODUCTS(v8_, v8i, V_ASR, v8_mulc, AVX2_FN)

AVX2_FN static inline v8i load8(const uint16_t *p)
{
    return (v8i)_mm256_cvtepu16_epi32(_mm_loadu_si128((const __m128i *)(const void *)p));
}
AVX2_FN static inline v8i gather8(const uint32_t *table, v8i idx)
{
    return (v8i)_mm256_i32gather_epi32((const int *)(const void *)table, (__m256i)idx, 4);
}
AVX2_FN static inline v8i v8_grad(v8i lo, v8i hi)
{
    return gather8(np_grad_packed32, (gather8(np_hash6_lo32, lo) + gather8(np_hash6_hi32, hi)) & 63);
}

#define LANE_T v8i
#define LANE(name) v8_##name
#define LANE_FN AVX2_FN
#include "np_simplex_lanes.inc"
#undef LANE_T
#undef LANE
#undef LANE_FN

/* out32 on eight lanes: sat16(floor((v k + 2^(drop-1)) / 2^drop)), 0 < k < 2^31. */
AVX2_FN static inline __m256i out8(v8i v, int32_t k, int drop)
{
    const __m256i kk = _mm256_set1_epi32(k), half = _mm256_set1_epi64x(1LL << (drop - 1));
    __m256i even = _mm256_add_epi64(_mm256_mul_epi32((__m256i)v, kk), half);
    __m256i odd = _mm256_add_epi64(_mm256_mul_epi32(_mm256_srli_epi64((__m256i)v, 32), kk), half);
    /*
     * The rounded word fits 32 bits (see INT32) and drop <= 32, so the low 32
     * bits of a logical 64-bit shift are those of the arithmetic one.
     */
    __m256i r = _mm256_blend_epi32(_mm256_srli_epi64(even, drop), _mm256_slli_epi64(_mm256_srli_epi64(odd, drop), 32),
                                   0xaa);
    return _mm256_min_epi32(_mm256_max_epi32(r, _mm256_set1_epi32(D32_OUT_MIN)), _mm256_set1_epi32(D32_OUT_MAX));
}

/* Four 8-lane words to eight {f, dx, dy, dz} outputs: a 4 x 8 transpose. */
AVX2_FN static inline void store8x4(np_simplex_out *out, __m256i f, __m256i dx, __m256i dy, __m256i dz)
{
    __m256i a0 = _mm256_unpacklo_epi32(f, dx), a1 = _mm256_unpacklo_epi32(dy, dz);
    __m256i a2 = _mm256_unpackhi_epi32(f, dx), a3 = _mm256_unpackhi_epi32(dy, dz);
    __m256i r0 = _mm256_unpacklo_epi64(a0, a1), r1 = _mm256_unpackhi_epi64(a0, a1); /* inputs 0|4, 1|5 */
    __m256i r2 = _mm256_unpacklo_epi64(a2, a3), r3 = _mm256_unpackhi_epi64(a2, a3); /* inputs 2|6, 3|7 */
    __m256i *o = (__m256i *)(void *)out;
    _mm256_storeu_si256(o, _mm256_permute2x128_si256(r0, r1, 0x20));
    _mm256_storeu_si256(o + 1, _mm256_permute2x128_si256(r2, r3, 0x20));
    _mm256_storeu_si256(o + 2, _mm256_permute2x128_si256(r0, r1, 0x31));
    _mm256_storeu_si256(o + 3, _mm256_permute2x128_si256(r2, r3, 0x31));
}

AVX2_FN static void eval_n_avx2(const uint16_t *restrict xs, const uint16_t *restrict ys,
                                const uint16_t *restrict zs, np_simplex_out *restrict out, size_t count)
{
    const int32_t kf = (int32_t)np_simplex_kf(&default_d), kd = (int32_t)np_simplex_kd(&default_d);
    size_t n = 0;
    for (; n + 8u <= count; n += 8u) {
        const v8i in[3] = { load8(xs + n), load8(ys + n), load8(zs + n) };
        v8i s, qs[3];
        v8_core(in, &s, qs);
        __m256i f = out8(s, kf, D32_F_DROP), dx = out8(qs[0], kd, D32_D_DROP), dy = out8(qs[1], kd, D32_D_DROP),
                dz = out8(qs[2], kd, D32_D_DROP);
        store8x4(out + n, f, dx, dy, dz);
    }
    eval_n_int32(xs + n, ys + n, zs + n, out + n, count - n);
}

AVX2_FN static void eval_n_avx2_f(const uint16_t *restrict xs, const uint16_t *restrict ys,
                                  const uint16_t *restrict zs, np_simplex_out *restrict out, size_t count)
{
    const int32_t kf = (int32_t)np_simplex_kf(&default_f);
    const __m256i zero = _mm256_setzero_si256();
    size_t n = 0;
    for (; n + 8u <= count; n += 8u) {
        const v8i in[3] = { load8(xs + n), load8(ys + n), load8(zs + n) };
        __m256i f = out8(v8_core_f(in), kf, D32_FV_DROP);
        store8x4(out + n, f, zero, zero, zero);
    }
    eval_n_int32_f(xs + n, ys + n, zs + n, out + n, count - n);
}

#define AVX512_FN __attribute__((target("avx512f")))
AVX512_FN static inline v16i v16_mulc(v16i d, v16i c) { return c * d; }
NP_SIMPLEX32_PRODUCTS(v16_, v16i, V_ASR, v16_mulc, AVX512_FN)

AVX512_FN static inline v16i load16(const uint16_t *p)
{
    return (v16i)_mm512_cvtepu16_epi32(_mm256_loadu_si256((const __m256i *)(const void *)p));
}
/*
 * Without optimisation GCC 12's header makes _mm512_i32gather_epi32 a macro
 * whose all-ones mask, (__mmask16)0xFFFF, converts to the builtin's signed
 * parameter: a -Wsign-conversion warning in the header's text, not ours.
 */
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wsign-conversion"
AVX512_FN static inline v16i gather16(const uint32_t *table, v16i idx)
{
    return (v16i)_mm512_i32gather_epi32((__m512i)idx, (const void *)table, 4);
}
#pragma GCC diagnostic pop
/* np_grad_packed32[h]: words 0..31 and 32..63 each by one two-table permute, then bit 5 of h picks. */
AVX512_FN static inline v16i v16_grad(v16i lo, v16i hi)
{
    const __m512i *t = (const __m512i *)(const void *)np_grad_packed32;
    __m512i h = (__m512i)((gather16(np_hash6_lo32, lo) + gather16(np_hash6_hi32, hi)) & 63);
    __m512i g0 = _mm512_permutex2var_epi32(_mm512_loadu_si512(t), h, _mm512_loadu_si512(t + 1));
    __m512i g1 = _mm512_permutex2var_epi32(_mm512_loadu_si512(t + 2), h, _mm512_loadu_si512(t + 3));
    return (v16i)_mm512_mask_blend_epi32(_mm512_test_epi32_mask(h, _mm512_set1_epi32(32)), g0, g1);
}

#define LANE_T v16i
#define LANE(name) v16_##name
#define LANE_FN AVX512_FN
#include "np_simplex_lanes.inc"
#undef LANE_T
#undef LANE
#undef LANE_FN

/* out32 on sixteen lanes (out8's argument). */
AVX512_FN static inline __m512i out16(v16i v, int32_t k, unsigned drop)
{
    const __m512i kk = _mm512_set1_epi32(k), half = _mm512_set1_epi64(1LL << (drop - 1u));
    __m512i even = _mm512_add_epi64(_mm512_mul_epi32((__m512i)v, kk), half);
    __m512i odd = _mm512_add_epi64(_mm512_mul_epi32(_mm512_srli_epi64((__m512i)v, 32), kk), half);
    __m512i r = _mm512_mask_blend_epi32(0xaaaa, _mm512_srli_epi64(even, drop),
                                        _mm512_slli_epi64(_mm512_srli_epi64(odd, drop), 32));
    return _mm512_min_epi32(_mm512_max_epi32(r, _mm512_set1_epi32(D32_OUT_MIN)), _mm512_set1_epi32(D32_OUT_MAX));
}

/* store8x4 on sixteen lanes: in 128-bit lane L, r_m holds input 4 L + m. */
AVX512_FN static inline void store16x4(np_simplex_out *out, __m512i f, __m512i dx, __m512i dy, __m512i dz)
{
    __m512i a0 = _mm512_unpacklo_epi32(f, dx), a1 = _mm512_unpacklo_epi32(dy, dz);
    __m512i a2 = _mm512_unpackhi_epi32(f, dx), a3 = _mm512_unpackhi_epi32(dy, dz);
    __m512i r0 = _mm512_unpacklo_epi64(a0, a1), r1 = _mm512_unpackhi_epi64(a0, a1);
    __m512i r2 = _mm512_unpacklo_epi64(a2, a3), r3 = _mm512_unpackhi_epi64(a2, a3);
    __m512i t0 = _mm512_shuffle_i32x4(r0, r1, 0x44), t1 = _mm512_shuffle_i32x4(r2, r3, 0x44); /* lanes 0, 1 */
    __m512i t2 = _mm512_shuffle_i32x4(r0, r1, 0xee), t3 = _mm512_shuffle_i32x4(r2, r3, 0xee); /* lanes 2, 3 */
    char *o = (char *)(void *)out;
    _mm512_storeu_si512(o, _mm512_shuffle_i32x4(t0, t1, 0x88));       /* inputs 0..3 */
    _mm512_storeu_si512(o + 64, _mm512_shuffle_i32x4(t0, t1, 0xdd));  /* 4..7 */
    _mm512_storeu_si512(o + 128, _mm512_shuffle_i32x4(t2, t3, 0x88)); /* 8..11 */
    _mm512_storeu_si512(o + 192, _mm512_shuffle_i32x4(t2, t3, 0xdd)); /* 12..15 */
}

AVX512_FN static void eval_n_avx512(const uint16_t *restrict xs, const uint16_t *restrict ys,
                                    const uint16_t *restrict zs, np_simplex_out *restrict out, size_t count)
{
    const int32_t kf = (int32_t)np_simplex_kf(&default_d), kd = (int32_t)np_simplex_kd(&default_d);
    size_t n = 0;
    for (; n + 16u <= count; n += 16u) {
        const v16i in[3] = { load16(xs + n), load16(ys + n), load16(zs + n) };
        v16i s, qs[3];
        v16_core(in, &s, qs);
        __m512i f = out16(s, kf, D32_F_DROP), dx = out16(qs[0], kd, D32_D_DROP),
                dy = out16(qs[1], kd, D32_D_DROP), dz = out16(qs[2], kd, D32_D_DROP);
        store16x4(out + n, f, dx, dy, dz);
    }
    eval_n_avx2(xs + n, ys + n, zs + n, out + n, count - n);
}

AVX512_FN static void eval_n_avx512_f(const uint16_t *restrict xs, const uint16_t *restrict ys,
                                      const uint16_t *restrict zs, np_simplex_out *restrict out, size_t count)
{
    const int32_t kf = (int32_t)np_simplex_kf(&default_f);
    const __m512i zero = _mm512_setzero_si512();
    size_t n = 0;
    for (; n + 16u <= count; n += 16u) {
        const v16i in[3] = { load16(xs + n), load16(ys + n), load16(zs + n) };
        __m512i f = out16(v16_core_f(in), kf, D32_FV_DROP);
        store16x4(out + n, f, zero, zero, zero);
    }
    eval_n_avx2_f(xs + n, ys + n, zs + n, out + n, count - n);
}
#endif /* NP_SIMPLEX_HAVE_AVX2 */

static int have_avx512(void)
{
#if NP_SIMPLEX_HAVE_AVX2
    return __builtin_cpu_supports("avx512f");
#else
    return 0;
#endif
}

static int have_avx2(void)
{
#if NP_SIMPLEX_HAVE_AVX2
    return __builtin_cpu_supports("avx2");
#else
    return 0;
#endif
}

int np_simplex_eval_n_path(unsigned path, const np_simplex_cfg *cfg, const uint16_t *x, const uint16_t *y,
                           const uint16_t *z, np_simplex_out *out, size_t count)
{
    switch (path) {
    case NP_SIMPLEX_BATCH_GENERIC: {
        const np_simplex_cfg c = *cfg;
        const int64_t kf = np_simplex_kf(&c), kd = np_simplex_kd(&c);
        for (size_t n = 0; n < count; n++)
            eval_one(&c, kf, kd, x[n], y[n], z[n], &out[n]);
        return 0;
    }
    case NP_SIMPLEX_BATCH_WIDTHS:
        if (same_cfg(cfg, &default_d))
            eval_n_default_d(x, y, z, out, count);
        else if (same_cfg(cfg, &default_f))
            eval_n_default_f(x, y, z, out, count);
        else
            return -1;
        return 0;
    case NP_SIMPLEX_BATCH_INT32:
        if (same_cfg(cfg, &default_d))
            eval_n_int32(x, y, z, out, count);
        else if (same_cfg(cfg, &default_f))
            eval_n_int32_f(x, y, z, out, count);
        else
            return -1;
        return 0;
    case NP_SIMPLEX_BATCH_AVX2:
        if (!(same_cfg(cfg, &default_d) || same_cfg(cfg, &default_f)) || !have_avx2())
            return -1;
#if NP_SIMPLEX_HAVE_AVX2
        if (cfg->deriv)
            eval_n_avx2(x, y, z, out, count);
        else
            eval_n_avx2_f(x, y, z, out, count);
#endif
        return 0;
    case NP_SIMPLEX_BATCH_AVX512:
        if (!(same_cfg(cfg, &default_d) || same_cfg(cfg, &default_f)) || !have_avx512() || !have_avx2())
            return -1;
#if NP_SIMPLEX_HAVE_AVX2
        if (cfg->deriv)
            eval_n_avx512(x, y, z, out, count);
        else
            eval_n_avx512_f(x, y, z, out, count);
#endif
        return 0;
    default:
        return -1;
    }
}

void np_simplex_eval_n(const np_simplex_cfg *cfg, const uint16_t *x, const uint16_t *y,
                       const uint16_t *z, np_simplex_out *out, size_t count)
{
    static const unsigned order[] = { NP_SIMPLEX_BATCH_AVX512, NP_SIMPLEX_BATCH_AVX2, NP_SIMPLEX_BATCH_WIDTHS };
    for (unsigned k = 0; k < sizeof order / sizeof order[0]; k++)
        if (np_simplex_eval_n_path(order[k], cfg, x, y, z, out, count) == 0)
            return;
    np_simplex_eval_n_path(NP_SIMPLEX_BATCH_GENERIC, cfg, x, y, z, out, count);
}

/* --- Pipeline stages: the same primitives, split at the register banks. --- */

static np_simplex_sig *sig_of(void *s) { return (np_simplex_sig *)s; }

/* SK: skewed numerators and the skewed cell. */
static void stage_sk(const void *cfgv, void *sv)
{
    (void)cfgv;
    np_simplex_sig *s = sig_of(sv);
    const uint16_t in[3] = { s->x, s->y, s->z };
    for (unsigned a = 0; a < 3; a++) {
        s->sk[a] = np_simplex_skew(in[a], in[(a + 1u) % 3u], in[(a + 2u) % 3u]);
        s->cell[a] = np_simplex_cell(s->sk[a]);
    }
}

/* RK: exact unskewed offsets and the ranking (three comparators). */
static void stage_rk(const void *cfgv, void *sv)
{
    (void)cfgv;
    np_simplex_sig *s = sig_of(sv);
    const uint16_t in[3] = { s->x, s->y, s->z };
    uint32_t n = s->cell[0] + s->cell[1] + s->cell[2];
    for (unsigned a = 0; a < 3; a++)
        s->off[a] = np_simplex_offset(in[a], s->cell[a], n);
    np_simplex_rank(s->off[0], s->off[1], s->off[2], &s->hi, &s->lo);
}

/* CH: the four corners: offsets, hashes, gradients, G . D. */
static void stage_ch(const void *cfgv, void *sv)
{
    (void)cfgv;
    np_simplex_sig *s = sig_of(sv);
    for (unsigned c = 0; c < 4; c++) {
        unsigned mask = np_simplex_corner_mask(s->hi, s->lo, c);
        for (unsigned a = 0; a < 3; a++)
            s->d[c][a] = np_simplex_corner_d(s->off[a], mask >> a & 1u, c);
        s->h[c] = np_simplex_corner_hash(s->cell, mask);
        s->g[c] = np_grad_fast(s->h[c]);
        s->gd[c] = np_simplex_gdot(s->g[c], s->d[c]);
    }
}

/* KT: squared length and the kernel variable T (support decided here, exactly). */
static void stage_kt(const void *cfgv, void *sv)
{
    (void)cfgv;
    np_simplex_sig *s = sig_of(sv);
    for (unsigned c = 0; c < 4; c++) {
        s->r2[c] = np_simplex_r2(s->d[c]);
        s->t[c] = np_simplex_kernel_t(s->r2[c]);
    }
}

/* P2: tau^2. */
static void stage_p2(const void *cfgv, void *sv)
{
    np_simplex_sig *s = sig_of(sv);
    for (unsigned c = 0; c < 4; c++)
        s->tau2[c] = np_simplex_tau2(cfgv, s->t[c]);
}

/* P4: tau^4 and (derivative) tau^3. */
static void stage_p4(const void *cfgv, void *sv)
{
    const np_simplex_cfg *cfg = cfgv;
    np_simplex_sig *s = sig_of(sv);
    for (unsigned c = 0; c < 4; c++) {
        s->tau4[c] = np_simplex_tau4(cfg, s->tau2[c]);
        s->tau3[c] = cfg->deriv ? np_simplex_tau3(s->tau2[c], s->t[c]) : 0u;
    }
}

/* M: the f terms; (derivative) q and the G_a tau^4 terms. */
static void stage_m(const void *cfgv, void *sv)
{
    const np_simplex_cfg *cfg = cfgv;
    np_simplex_sig *s = sig_of(sv);
    for (unsigned c = 0; c < 4; c++) {
        s->fc[c] = np_simplex_fterm(cfg, s->tau4[c], s->gd[c]);
        if (cfg->deriv) {
            const int coef[3] = { s->g[c].cx, s->g[c].cy, s->g[c].cz };
            s->q[c] = np_simplex_qterm(cfg, s->tau3[c], s->gd[c]);
            for (unsigned a = 0; a < 3; a++)
                s->e[c][a] = np_simplex_eterm(cfg, s->tau4[c], coef[a]);
        }
    }
}

/* M2 (derivative only): m_a = 5/4 q d'_a. */
static void stage_m2(const void *cfgv, void *sv)
{
    (void)cfgv;
    np_simplex_sig *s = sig_of(sv);
    for (unsigned c = 0; c < 4; c++)
        for (unsigned a = 0; a < 3; a++)
            s->m[c][a] = np_simplex_mterm(s->q[c], s->d[c][a]);
}

/* A: the sums over the four corners. */
static void stage_a(const void *cfgv, void *sv)
{
    const np_simplex_cfg *cfg = cfgv;
    np_simplex_sig *s = sig_of(sv);
    s->s = s->fc[0] + s->fc[1] + s->fc[2] + s->fc[3];
    for (unsigned a = 0; a < 3; a++) {
        s->qs[a] = 0;
        if (cfg->deriv)
            for (unsigned c = 0; c < 4; c++)
                s->qs[a] += s->e[c][a] - s->m[c][a];
    }
}

/* O: constant multiply, round, saturate. */
static void stage_o(const void *cfgv, void *sv)
{
    const np_simplex_cfg *cfg = cfgv;
    np_simplex_sig *s = sig_of(sv);
    s->f = np_simplex_out_f(cfg, np_simplex_kf(cfg), s->s);
    int64_t kd = np_simplex_kd(cfg);
    for (unsigned a = 0; a < 3; a++)
        s->df[a] = cfg->deriv ? np_simplex_out_d(cfg, kd, s->qs[a]) : 0;
}

const np_stage_desc np_simplex_stages_d[NP_SIMPLEX_STAGES_D] = {
    { "SK", stage_sk }, { "RK", stage_rk }, { "CH", stage_ch }, { "KT", stage_kt },
    { "P2", stage_p2 }, { "P4", stage_p4 }, { "M", stage_m },   { "M2", stage_m2 },
    { "A", stage_a },   { "O", stage_o },
};

const np_stage_desc np_simplex_stages_f[NP_SIMPLEX_STAGES_F] = {
    { "SK", stage_sk }, { "RK", stage_rk }, { "CH", stage_ch }, { "KT", stage_kt },
    { "P2", stage_p2 }, { "P4", stage_p4 }, { "M", stage_m },   { "A", stage_a },
    { "O", stage_o },
};

int np_simplex_pipe_init(np_pipe *p, const np_simplex_cfg *cfg)
{
    return np_pipe_init(p, np_simplex_stage_table(cfg), np_simplex_stage_count(cfg),
                        sizeof(np_simplex_sig), cfg);
}

/* --- Datapath declaration --- */

/* Append one op (when there is room) and count it. */
static void put(np_op *ops, size_t max, size_t *n, np_op op)
{
    if (*n < max)
        ops[*n] = op;
    (*n)++;
}

#define OP(stage, sig, kind, count, a, b, out, sgn, level) \
    put(ops, max, &n, (np_op){ stage, sig, kind, count, a, b, out, sgn, level })

/*
 * Range constants (upper bounds, rounded up). Per corner, the maxima over
 * s = |d'|^2 in [0, 5.4) with tau = 5 (5.4 - s) / 32 of np_simplex.h; the
 * sums from OUTPUT RANGE (the output bounds that simplex.max_magnitude
 * recomputes over every local configuration) divided by the constants.
 */
#define RANGE_FC 0.42451  /* tau^4 |G.d'| */
#define RANGE_Q 0.57546   /* tau^3 |G.d'| */
#define RANGE_M 0.74068   /* 5/4 tau^3 |G.d'| |d'_a| */
#define RANGE_EM 0.92731  /* |tau^4 G_a - 5/4 tau^3 (G.d') d'_a| */
#define RANGE_S 0.50952   /* |S| = |f| / Kf <= 0.347438 / Kf */
#define RANGE_QS 0.85095  /* |Q_a| = |df_a| / Kd <= 1.740774 / Kd */
#define TAU3_E 1.84375    /* |tau3' - tau^3| <= (tau + 1) e */
#define M_P_PRE 2.9047    /* p-coefficient of the m_a error before m's own rounding */
enum {
    GD_MAX = 2660,        /* |gd| <= |D|_1 <= sqrt(3) |D| <= sqrt(3) 1536 = 2660.4 (|d| <= 1) */
    GD_BITS = 13,         /* so gd is s13 */
    CELL_LIVE = 8,        /* the bits of a cell index read after SK (the hash reads it mod 256) */
    IN_LIVE = 11,         /* the bits of an input word read after SK: 6a mod 2^12 needs a mod 2^11 */
    GRAD_BITS = 6,        /* a corner's gradient index h */
    /*
     * Bits that are constant or shared, which the hardware (Yosys's
     * synthesis of the RTL, docs/cost-model.md) neither stores twice nor
     * computes: U = 6a - 1536 i + 256 n is even, and so are every corner's
     * D = U - 1536 A + 256 c and G . D, so bit 0 of each is 0; R2 = sum D_a^2
     * is then a multiple of 4, and so is T = 27 * 2^18 - 5 R2. Hence the live
     * widths below: U, D s12 -> 11 bits; |D_a| = 2 |D_a / 2|, an 11-bit
     * negate and a 10-bit squarer; R2, 5 R2, T two bits narrower; G . D s13
     * -> 12 bits (so T^2 is a 21-bit squarer and the products with G . D
     * and D one bit narrower).
     */
    OFF_LIVE = NP_SIMPLEX_OFF_BITS - 1,
    GD_LIVE = GD_BITS - 1,
    T_LIVE = NP_SIMPLEX_T_BITS - 2,
    /*
     * The four corners' offsets D held in a bank: D_c differs from U only
     * from bit 8 on, so D[7:0] = U[7:0] at every corner and one register
     * holds its 7 live bits for the four (Yosys merges the RTL's identical
     * flip-flops): 3 x 7 + 12 x 4 = 69 bits, not 12 x 12.
     */
    D_LOW = 8,
    D_REG_BITS = 3 * (D_LOW - 1) + 4 * 3 * (NP_SIMPLEX_OFF_BITS - D_LOW)
};

/* Widths of an unsigned / a signed (symmetric) word of magnitude at most v. */
static unsigned ubits(uint64_t v) { return np_bits_for_range(0, (int64_t)v, 0); }
static unsigned sbits(uint64_t v) { return np_bits_for_range(-(int64_t)v, (int64_t)v, 1); }
static uint64_t umin64(uint64_t a, uint64_t b) { return a < b ? a : b; }

/* ceil(v 2^f) for v >= 0: a real bound as a word bound in Q.f. */
static uint64_t word_bound(double v, unsigned f)
{
    double x = v * np_pow2i((int)f);
    uint64_t u = (uint64_t)x;
    return (double)u < x ? u + 1u : u;
}

/*
 * A bound on |np_simplex_requant(v, from, to)| from a bound b on |v|: the
 * rounding is monotone, and for x >= 0, -requant(x) <= requant(-x).
 */
static uint64_t requant_bound(uint64_t b, unsigned from, unsigned to)
{
    return from >= to ? np_shr_round_half_up_u(b, from - to) : b << (to - from);
}

/* Widths of the rounded datapath for cfg (the range argument of each is at its use). */
typedef struct sx_widths {
    unsigned tsq, tau2, t4p, tau4, t3p, tau3;                 /* unsigned */
    unsigned fcp, fc, qp, q, e, q5, mp, m, em, s, qs;         /* signed */
    unsigned fprod, fr, dprod, dr;                            /* signed */
    uint64_t smax, qsmax;                                     /* word bounds of S, Q_a */
} sx_widths;

static void widths_of(const np_simplex_cfg *cfg, sx_widths *w)
{
    unsigned wt = cfg->t_frac, wp = cfg->p_frac, wk = cfg->k_frac;
    double e = np_pow2i(-(int)wt - 1), p = np_pow2i(-(int)wp - 1);
    double e4 = e * (2.0 * BOUND_TAU_MAX * BOUND_TAU_MAX + e) + e;
    /*
     * tau2, tau4 and tau3 are monotone in T (every rounding is), and
     * T <= T_VERTEX (|d| = 0; reached at the origin): their largest words
     * are exactly those at T_VERTEX.
     */
    uint64_t tv = NP_SIMPLEX_T_VERTEX;
    uint64_t t2 = np_simplex_tau2(cfg, (uint32_t)tv);
    uint64_t t4 = np_simplex_tau4(cfg, (uint32_t)t2);
    uint64_t t3 = np_simplex_tau3((uint32_t)t2, (uint32_t)tv);
    w->tsq = ubits(tv * tv);
    w->tau2 = ubits(t2);
    w->t4p = ubits(t2 * t2);
    w->tau4 = ubits(t4);
    w->t3p = ubits(t2 * tv);
    w->tau3 = ubits(t3);
    /*
     * The terms: the per-corner maximum of the real function plus the
     * rounding errors of the ERROR BOUND argument (tau4' <= tau^4 + e4,
     * tau3' <= tau^3 + (tau + 1) e, |G.d'| <= 4.0249 where T > 0), and never
     * more than the largest power times GD_MAX (what counts when WT is so
     * small that e4 is large). fc, q, e in Q.WP; the products in Q.(WT+9).
     */
    uint64_t fcp = umin64(word_bound(RANGE_FC + BOUND_GD_MAX * e4, wt + NP_SIMPLEX_GD_FRAC), t4 * GD_MAX);
    uint64_t fc = requant_bound(fcp, wt + NP_SIMPLEX_GD_FRAC, wp);
    uint64_t qp = umin64(word_bound(RANGE_Q + BOUND_GD_MAX * TAU3_E * e, wt + NP_SIMPLEX_GD_FRAC), t3 * GD_MAX);
    uint64_t q = requant_bound(qp, wt + NP_SIMPLEX_GD_FRAC, wp);
    uint64_t ev = requant_bound(t4, wt, wp);
    uint64_t q5 = 5u * q;
    /* 5 q D in Q.(WP+11): 5/4 |q' d'_a| <= RANGE_M + (error of m before its rounding) */
    uint64_t mp = umin64(word_bound(RANGE_M + BOUND_M_E * e + M_P_PRE * p, wp + NP_SIMPLEX_GD_FRAC + NP_SIMPLEX_M_SHIFT),
                         q5 * NP_SIMPLEX_UNIT);
    uint64_t m = np_shr_round_half_up_u(mp, NP_SIMPLEX_GD_FRAC + NP_SIMPLEX_M_SHIFT);
    uint64_t em = umin64(word_bound(RANGE_EM + e4 + p + BOUND_M_E * e + (M_P_PRE + 1.0) * p, wp), ev + m);
    /* The sums: the output bounds over Kf, Kd plus E_f, E_d; never more than four terms. */
    uint64_t sm = umin64(word_bound(RANGE_S + 4.0 * (e4 * BOUND_GD_MAX + p), wp), 4u * fc);
    uint64_t qs = umin64(word_bound(RANGE_QS + 4.0 * (e4 + BOUND_M_E * e + BOUND_M_P * p), wp), 4u * em);
    uint64_t fprod = (uint64_t)np_simplex_kf(cfg) * sm, dprod = (uint64_t)np_simplex_kd(cfg) * qs;
    w->fcp = sbits(fcp);
    w->fc = sbits(fc);
    w->qp = sbits(qp);
    w->q = sbits(q);
    w->e = sbits(ev);
    w->q5 = sbits(q5);
    w->mp = sbits(mp);
    w->m = sbits(m);
    w->em = sbits(em);
    w->s = sbits(sm);
    w->qs = sbits(qs);
    w->smax = sm;
    w->qsmax = qs;
    w->fprod = sbits(fprod);
    w->fr = sbits(requant_bound(fprod, wk + wp, np_simplex_f_frac(cfg)));
    w->dprod = sbits(dprod);
    w->dr = sbits(requant_bound(dprod, wk + wp, np_simplex_d_frac(cfg)));
}

/*
 * O: count multipliers by the constant k as shift-adds. The operands are
 * the operand (|v| <= vmax) shifted to each non-zero digit of k's canonical
 * signed-digit form, summed pairwise, lowest digits first, in a tree. An
 * adder of two partial sums whose lowest set bits are l1 < l2 spans the
 * result's bits from l2 up (the bits below l2 are the first operand's:
 * wiring); a partial sum of the terms T is bounded by vmax * sum 2^s over T,
 * the whole product by k vmax (width bits, named sig, traced at `traced`
 * bits: the range argument's, where the RTL holds wider words). The
 * rounding after it drops the product's drop low bits, so the last adder's
 * bits under the round bit only carry (`carry`); the operand's zero low
 * bits (0 when WP is finer than the products) add nothing. Returns the tree's depth
 * in levels.
 */
static unsigned const_mul(np_op *ops, size_t max, size_t *n, unsigned count, uint64_t k, uint64_t vmax,
                          unsigned width, unsigned traced, unsigned drop, unsigned zero, const char *sig)
{
    enum { MAX_DIGITS = 40 };
    unsigned low[MAX_DIGITS], terms = 0, lvl = 0;
    uint64_t mag[MAX_DIGITS];
    for (unsigned pos = 0; k && terms < MAX_DIGITS; pos++, k >>= 1)
        if (k & 1u) {
            low[terms] = pos;
            mag[terms++] = vmax << pos;
            k = (k & 2u) ? k + 1u : k - 1u; /* digit -1 or +1 */
        }
    if (terms <= 1u) { /* a power of two (or 0): wiring */
        put(ops, max, n, (np_op){ "O", sig, NP_OP_REG, 0, 0, 0, traced, 1, 0 });
        return 0;
    }
    while (terms > 1u) {
        unsigned next = 0, w[MAX_DIGITS / 2], nw = 0;
        for (unsigned i = 0; i + 1u < terms; i += 2u) {
            uint64_t m = mag[i] + mag[i + 1u];
            unsigned rw = terms == 2u ? width : sbits(m);
            w[nw++] = rw > low[i + 1u] + zero ? rw - low[i + 1u] - zero : 1u;
            low[next] = low[i];
            mag[next++] = m;
        }
        if (terms & 1u) {
            low[next] = low[terms - 1u];
            mag[next++] = mag[terms - 1u];
        }
        if (next == 1u && drop > low[1] + zero + 1u && w[0] > 1u) {
            /*
             * The last adder: the rounding reads its bits from drop - 1 (the
             * round bit) up; below, only its carry (from bit low[1] on).
             */
            unsigned c = drop - 1u - low[1] - zero < w[0] ? drop - 1u - low[1] - zero : w[0] - 1u;
            put(ops, max, n, (np_op){ "O", NULL, NP_OP_CARRY, count, c, 0, 0, 0, lvl });
            w[0] -= c;
        }
        for (unsigned i = 0; i < nw;) { /* one op per run of equal widths */
            unsigned j = i;
            while (j < nw && w[j] == w[i])
                j++;
            put(ops, max, n, (np_op){ "O", next == 1u ? sig : NULL, NP_OP_ADD, count * (j - i), w[i], 0,
                                      next == 1u ? traced : 0u, 1, lvl });
            i = j;
        }
        terms = next;
        lvl++;
    }
    return lvl;
}

/*
 * O: round the product (kept bits plus the round bit) to the output width
 * and saturate, unless the range argument shows the rounded word already
 * fits (then the saturation can never act and is left out, bits unchanged)
 * and the RTL leaves it out too (force_sat = 0: its TIGHT widths).
 */
static void out_round(np_op *ops, size_t max, size_t *n, unsigned count, unsigned drop, unsigned rw,
                      unsigned ow, int force_sat, const char *sig, unsigned lvl)
{
    int sat = force_sat || rw > ow;
    if (drop > 0u)
        put(ops, max, n, (np_op){ "O", sat ? NULL : sig, NP_OP_INC, count, rw + 1u, 0, sat ? 0u : ow, 1, lvl });
    else if (!sat)
        put(ops, max, n, (np_op){ "O", sig, NP_OP_REG, 0, 0, 0, ow, 1, lvl }); /* wiring only */
    if (sat) {
        /*
         * Out of range when the bits from ow - 1 up are not all the sign:
         * one check of rw - ow + 1 bits; the saturated word is the sign and
         * its complement (wiring and an inverter), picked by a 2:1 select.
         */
        put(ops, max, n, (np_op){ "O", NULL, NP_OP_CMPK, count, rw >= ow ? rw - ow + 1u : 1u, 0, 0, 0, lvl + 1u });
        put(ops, max, n, (np_op){ "O", sig, NP_OP_MUX, count, ow, 2, ow, 1, lvl + 2u });
    }
}

/*
 * A rounding that drops sh bits to a word held in pw bits (traced at vw):
 * adding half an LSB over the kept bits plus the round bit, or wiring.
 */
#define ROUND(stage, sig, count, sh, pw, vw, level)                     \
    do {                                                                \
        if ((sh) > 0)                                                   \
            OP(stage, sig, NP_OP_INC, count, (pw) + 1u, 0, vw, 1, level); \
        else                                                            \
            OP(stage, sig, NP_OP_REG, 0, 0, 0, vw, 1, level);           \
    } while (0)

size_t np_simplex_datapath(const np_simplex_cfg *cfg, np_op *ops, size_t max)
{
    size_t n = 0;
    sx_widths w, h;
    widths_of(cfg, &w);
    unsigned dv = cfg->deriv, wt = cfg->t_frac, wp = cfg->p_frac, wk = cfg->k_frac;
    /*
     * h: the widths the hardware holds from M on. The reference RTL
     * (np_simplex3.v) holds w's when TIGHT (WT >= 9 and WP >= 9) and leaves
     * O's saturation out; otherwise it holds every word wide enough never to
     * wrap at any configuration (fc, q WP+6; 5q WP+9; m WP+8; e WP+2; e_a - m_a
     * WP+9; S, Q_a WP+10) and saturates both outputs, so those are priced.
     * The traced signals keep w's widths (the range argument's).
     */
    int tight = wt >= 9 && wp >= 9;
    h = w;
    if (!tight) {
        h.fc = wp + 6u;
        h.q = wp + 6u;
        h.q5 = wp + 9u;
        h.m = wp + 8u;
        h.e = wp + 2u;
        h.em = wp + 9u;
        h.s = h.qs = wp + 10u;
        h.smax = h.qsmax = ((uint64_t)1 << (wp + 9u)) - 1u;
        /* |K S| < 2^(bits(K) + WP + 9): exact while that fits 63 bits, else that bound's width */
        uint64_t kf = (uint64_t)np_simplex_kf(cfg), kd = (uint64_t)np_simplex_kd(cfg);
        unsigned ff = np_simplex_f_frac(cfg), fd = np_simplex_d_frac(cfg), sh = wk + wp;
        if (ubits(kd) + wp + 9u <= 62u) {
            h.fprod = sbits(kf * h.smax);
            h.fr = sbits(requant_bound(kf * h.smax, sh, ff));
            h.dprod = sbits(kd * h.qsmax);
            h.dr = sbits(requant_bound(kd * h.qsmax, sh, fd));
        } else {
            h.fprod = ubits(kf) + wp + 10u;
            h.fr = sh > ff ? h.fprod - (sh - ff) + 1u : h.fprod + (ff - sh);
            h.dprod = ubits(kd) + wp + 10u;
            h.dr = sh > fd ? h.dprod - (sh - fd) + 1u : h.dprod + (fd - sh);
        }
    }
    unsigned nb = cfg->out_bits, nd = cfg->dout_bits, ob = NP_SIMPLEX_OFF_BITS;
    /* Carried for the derivative only: D to M2, each corner's gradient index to M (e_a). */
    unsigned d_live = dv ? (unsigned)D_REG_BITS : 0u, h_live = dv ? 4u * GRAD_BITS : 0u;

    /*
     * SK. SX = 4a + (b + c): b + c <= 2 * 65535 (u17), SX <= 6 * 65535 = 393210
     * < 2^19 (u19). Then i = floor(SX / 768) = (683 nn) >> 11 with
     * nn = SX >> 8 <= 1535 (u11), 683 nn = 2 (32 - 1)(2 (4 + 1) + 1) nn + nn
     * as four shift-adds in series: 5 nn <= 7675 (u13), 11 nn <= 16885 (u15),
     * 341 nn <= 523435 < 2^19 (u19), 683 nn <= 1048405 < 2^20 (u20).
     * Each shift-add (X << s) + Y is priced by its bit positions: below s
     * Y's bits (wiring), where both operands have bits a full adder, above
     * Y's top bit an incrementer of X's bits (the carry), and where only the
     * carry out of a position is read (SX below bit 8, 683 nn below bit 11:
     * the cell reads SX[18:8] and (683 nn)[19:11]) a carry chain (`carry`,
     * a majority chain: cheaper than a comparator, carry10 in cost_calib.v):
     *   bc = b + c: 16 full adders;  SX = (a << 2) + bc: bits 2..7 carry,
     *   8..16 full, 17..18 increment;  5 nn = (nn << 2) + nn: 2..10 full,
     *   11..12 increment;  11 nn = (5 nn << 1) + nn: 1..10 full, 11..14
     *   increment;  341 nn = (11 nn << 5) - 11 nn: 0..4 the borrow of
     *   -11 nn (increment), 5..14 full, 15..19 increment;  683 nn =
     *   (341 nn << 1) + nn: 1..10 carry, 11..19 increment.
     * The RTL (np_simplex3.v, cell_of) writes the same chain.
     */
    OP("SK", "bc", NP_OP_ADD, 3, 16, 0, 17, 0, 0);
    OP("SK", "sk", NP_OP_ADD, 3, 9, 0, NP_SIMPLEX_SKEW_BITS, 0, 1);
    OP("SK", NULL, NP_OP_CARRY, 3, 6, 0, 0, 0, 1);
    OP("SK", NULL, NP_OP_INC, 3, 2, 0, 0, 0, 1);
    OP("SK", "n5", NP_OP_ADD, 3, 9, 0, 13, 0, 2);
    OP("SK", NULL, NP_OP_INC, 3, 2, 0, 0, 0, 2);
    OP("SK", "n11", NP_OP_ADD, 3, 10, 0, 15, 0, 3);
    OP("SK", NULL, NP_OP_INC, 3, 4, 0, 0, 0, 3);
    OP("SK", "n341", NP_OP_ADD, 3, 10, 0, 19, 0, 4);
    OP("SK", NULL, NP_OP_INC, 3, 10, 0, 0, 0, 4);
    OP("SK", NULL, NP_OP_CARRY, 3, 10, 0, 0, 0, 5);
    OP("SK", "n683", NP_OP_INC, 3, 9, 0, 20, 0, 6);
    /*
     * Live after SK: each input word mod 2^11 (all that U mod 2^12 reads) and
     * each cell mod 256 (bit 8 is never read: the hash takes the cell mod 256,
     * U its residues mod 8 and mod 16).
     */
    OP("SK", NULL, NP_OP_REG, 1, 3 * IN_LIVE + 3 * CELL_LIVE + 1, 0, 0, 0, 0);

    /*
     * RK. U = 6a - 1536 i + 256 n lies in (-512, 1280) (u in (-1/3, 5/6)), so
     * s12 holds it and it is computed mod 2^12 exactly: U[7:0] = (6a)[7:0],
     * U[11:8] = (6a)[11:8] + (n - 2 (3i mod 8)) mod 16, with 6a mod 2^12 =
     * 2 ((2a + a) mod 2^11), 3i mod 8 = (2i + i) mod 8, n mod 16 =
     * (i + j + k) mod 16. Each adder spans only the bits where both
     * operands have bits (bit 0 of 2a + a is a's, of 2i + i is i's, of n - 6i
     * is n's: wiring), and none has a carry out (all are modular).
     */
    OP("RK", NULL, NP_OP_ADD, 3, 10, 0, 0, 0, 0);             /* (2a + a) mod 2^11: bits 1..10 */
    OP("RK", NULL, NP_OP_ADD, 3, 2, 0, 0, 0, 0);              /* 3i mod 8: bits 1..2 */
    OP("RK", NULL, NP_OP_ADD, 1, 4, 0, 0, 0, 0);              /* (i + j) mod 16 */
    OP("RK", NULL, NP_OP_ADD, 1, 4, 0, 0, 0, 1);              /* n mod 16 */
    OP("RK", NULL, NP_OP_ADD, 3, 3, 0, 0, 0, 2);              /* (n - 6i) mod 16: bits 1..3 */
    OP("RK", "off", NP_OP_ADD, 3, 4, 0, ob, 1, 3);            /* U[11:8] */
    /*
     * Appendix B's ranking: three comparators, encoded as the axes of the
     * largest and the smallest offset (2 bits each; the RTL's hi and lo).
     */
    OP("RK", NULL, NP_OP_CMP, 3, OFF_LIVE, 0, 0, 0, 4);
    OP("RK", NULL, NP_OP_LUT, 1, 3, 4, 0, 0, 5);
    OP("RK", NULL, NP_OP_REG, 1, 3 * OFF_LIVE + 4 + 3 * CELL_LIVE + 1, 0, 0, 0, 0); /* U; hi, lo; cell */

    /*
     * CH. D_c = U - 1536 A + 256 c for corners 1..3 (corner 0's is U): |D| <= 1536
     * (|d| <= 1, the longest simplex edge), s12, so D[7:0] = U[7:0] and
     * D[11:8] = U[11:8] + (c - 6 A_a) mod 16, the constant picked by the mask
     * bit. The corner masks of corners 1 and 2 decoded from hi, lo. Hash: the
     * corner cells, cell + mask bit (mod 256: an incrementer whose carry-in
     * is the mask bit; cell + 1 at corner 3, the cell itself at corner 0),
     * then per corner 8 lookups 3 -> 6 and 7 six-bit adders (4, 2, 1), as in
     * classic3. G . D: -D formed beside the hash, then per axis a 3:1 select of
     * D_a, -D_a or 0 by the gradient coefficient (np_grad_decode's bit logic,
     * not counted, as in classic3), and two additions:
     * |D_x c_x + D_y c_y| <= sqrt(2) 1536 = 2172 (s13), |gd| <= 2660 (s13).
     */
    OP("CH", NULL, NP_OP_LUT, 1, 4, 6, 0, 0, 0);
    OP("CH", NULL, NP_OP_INC, 9, CELL_LIVE, 0, 0, 0, 0);
    OP("CH", "d", NP_OP_ADD, 9, 4, 0, ob, 1, 0);
    OP("CH", NULL, NP_OP_LUT, 32, 3, 6, 0, 0, 1);
    OP("CH", NULL, NP_OP_ADD, 16, 6, 0, 0, 0, 2);
    OP("CH", NULL, NP_OP_NEG, 12, OFF_LIVE, 0, 0, 0, 2);
    OP("CH", NULL, NP_OP_ADD, 8, 6, 0, 0, 0, 3);
    OP("CH", "h", NP_OP_ADD, 4, 6, 0, 6, 0, 4);
    OP("CH", NULL, NP_OP_MUX, 12, OFF_LIVE, 3, 0, 0, 5);
    OP("CH", "gd2", NP_OP_ADD, 4, GD_LIVE, 0, GD_BITS, 1, 6);
    OP("CH", "gd", NP_OP_ADD, 4, GD_LIVE, 0, GD_BITS, 1, 7);
    OP("CH", NULL, NP_OP_REG, 1, D_REG_BITS + 4 * GD_LIVE + h_live + 1, 0, 0, 0, 0); /* D; gd; (h) */

    /*
     * KT. |D_a| <= 1536 (u11: a conditional negate of the s12 word, then an
     * 11-bit squarer), D_a^2 <= 1536^2 = 2359296 < 2^22 (u22); R2 and
     * its partial sum <= 1536^2 (u22);
     * 5 R2 = 4 R2 + R2 <= 11796480 < 2^24 (u24); 7077888 - 5 R2 in
     * [-4718592, 7077888] (s24); T = the clamp at 0 by the sign bit (u23).
     * Priced at the live widths (D even, R2 and T multiples of 4, above).
     */
    OP("KT", NULL, NP_OP_NEG, 12, OFF_LIVE, 0, 0, 0, 0);
    OP("KT", "dsq", NP_OP_SQR, 12, ob - 2u, 0, NP_SIMPLEX_R2_BITS, 0, 1);
    OP("KT", "r2p", NP_OP_ADD, 4, NP_SIMPLEX_R2_BITS - 2u, 0, NP_SIMPLEX_R2_BITS, 0, 2);
    OP("KT", "r2", NP_OP_ADD, 4, NP_SIMPLEX_R2_BITS - 2u, 0, NP_SIMPLEX_R2_BITS, 0, 3);
    OP("KT", "r2x5", NP_OP_ADD, 4, NP_SIMPLEX_TD_BITS - 2u, 0, NP_SIMPLEX_TD_BITS, 0, 4);
    OP("KT", "td", NP_OP_INC, 4, NP_SIMPLEX_TD_BITS - 2u, 0, NP_SIMPLEX_TD_BITS, 1, 5); /* a constant minus 5 R2 */
    OP("KT", "t", NP_OP_MUX, 4, T_LIVE, 2, NP_SIMPLEX_T_BITS, 0, 6);
    OP("KT", NULL, NP_OP_REG, 1, 4 * T_LIVE + 4 * GD_LIVE + d_live + h_live + 1, 0, 0, 0, 0);

    /*
     * P2, P4. T^2 <= 7077888^2 < 2^46 (u46). The powers' largest words are
     * those at T = 7077888 (widths_of): tau2 ~ 0.7119, tau4 ~ 0.5068,
     * tau3 ~ 0.6007, each u(WT); the products tau2^2 and tau2 T at their
     * exact maxima. Each rounding drops at least one bit (46 - WT, WT, 23).
     * T's two low bits are 0: T^2 = 16 (T / 4)^2, a 21-bit squarer.
     */
    OP("P2", "tsq", NP_OP_SQR, 4, T_LIVE, 0, w.tsq, 0, 0);
    OP("P2", "tau2", NP_OP_INC, 4, w.tau2 + 1u, 0, w.tau2, 0, 1);
    OP("P2", NULL, NP_OP_REG, 1,
       4 * w.tau2 + 4 * GD_LIVE + (dv ? 4u * T_LIVE : 0u) + d_live + h_live + 1, 0, 0, 0, 0);
    OP("P4", "tau4p", NP_OP_SQR, 4, w.tau2, 0, w.t4p, 0, 0);
    OP("P4", "tau4", NP_OP_INC, 4, w.tau4 + 1u, 0, w.tau4, 0, 1);
    if (dv) {
        OP("P4", "tau3p", NP_OP_MUL, 4, w.tau2, T_LIVE, w.t3p, 0, 0);
        OP("P4", "tau3", NP_OP_INC, 4, w.tau3 + 1u, 0, w.tau3, 0, 1);
    }
    OP("P4", NULL, NP_OP_REG, 1, 4 * w.tau4 + 4 * GD_LIVE + (dv ? 4u * w.tau3 : 0u) + d_live + h_live + 1, 0, 0,
       0, 0);

    /*
     * M. fc = round(tau4 gd): product and fc from widths_of (|tau4' G.d'| <=
     * 0.4245 + 4.0249 e4, so fc is sWP when that is < 1/2). Derivative:
     * q = round(tau3 gd) alike (<= 0.5755 + ...: s(WP+1)); e_a = G_a tau4 as a
     * 3:1 select of round(tau4), round(-tau4) and 0 (two roundings per corner,
     * shared by the three axes; |e| <= round(max tau4) ~ 0.5068: s(WP+1)).
     */
    unsigned shp = wt + NP_SIMPLEX_GD_FRAC > wp ? wt + NP_SIMPLEX_GD_FRAC - wp : 0u;
    /*
     * Low bits that are 0 when WP is finer than the products (the requant
     * shifts left): zf of fc, q, S and 5q (WP > WT + 9), ze of e (WP > WT),
     * zm of m (5 q D has zf + 0 zero bits, m drops 11 of them), zq of e - m
     * and Q_a. Nothing stores or adds them (Yosys drops constant flip-flops).
     */
    unsigned zf = wp > wt + NP_SIMPLEX_GD_FRAC ? wp - wt - NP_SIMPLEX_GD_FRAC : 0u;
    unsigned ze = wp > wt ? wp - wt : 0u;
    unsigned zm = zf > NP_SIMPLEX_M_SHIFT + NP_SIMPLEX_GD_FRAC ? zf - NP_SIMPLEX_M_SHIFT - NP_SIMPLEX_GD_FRAC : 0u;
    unsigned zq = ze < zm ? ze : zm;
#define LIVE(width, z) ((width) > (z) ? (width) - (z) : 1u)
    OP("M", "fcp", NP_OP_MUL, 4, w.tau4, GD_LIVE, w.fcp, 1, 0);
    ROUND("M", "fc", 4, shp, h.fc, w.fc, 1);
    if (dv) {
        OP("M", "qp", NP_OP_MUL, 4, w.tau3, GD_LIVE, w.qp, 1, 0);
        ROUND("M", "q", 4, shp, h.q, w.q, 1);
        OP("M", NULL, NP_OP_NEG, 4, w.tau4 + 1u, 0, 0, 0, 0);
        if (wt > wp)
            OP("M", NULL, NP_OP_INC, 8, h.e + 1u, 0, 0, 0, 1);
        OP("M", "e", NP_OP_MUX, 12, LIVE(h.e, ze), 3, w.e, 1, 2);
    }
    OP("M", NULL, NP_OP_REG, 1, 4 * LIVE(h.fc, zf) + (dv ? 4u * LIVE(h.q, zf) + 12u * LIVE(h.e, ze) : 0u) + d_live + 1,
       0, 0, 0, 0);

    /*
     * M2 (derivative only). 5q = 4q + q (|5q| <= 5 max |q|); 5 q D in
     * Q.(WP+11): 5/4 |q' d'_a| <= 0.7407 + 11.6913 e + 2.9047 p; m = that
     * rounded by 11 bits (s(WP+1)).
     */
    if (dv) {
        OP("M2", "q5", NP_OP_ADD, 4, LIVE(h.q5, zf + NP_SIMPLEX_M_SHIFT), 0, w.q5, 1, 0);
        OP("M2", "mp", NP_OP_MUL, 12, LIVE(h.q5, zf), OFF_LIVE, w.mp, 1, 1);
        if (zf < NP_SIMPLEX_M_SHIFT + NP_SIMPLEX_GD_FRAC) /* else the dropped bits are 0: exact */
            OP("M2", "m", NP_OP_INC, 12, h.m + 1u, 0, w.m, 1, 2);
        else
            OP("M2", "m", NP_OP_REG, 0, 0, 0, w.m, 1, 2);
        OP("M2", NULL, NP_OP_REG, 1, 4 * LIVE(h.fc, zf) + 12 * LIVE(h.e, ze) + 12 * LIVE(h.m, zm) + 1, 0, 0, 0, 0);
    }

    /*
     * A. S = sum of 4 fc: |S| <= 0.5095 + E_f (s(WP+1) while that is < 1);
     * Q_a = sum of 4 (e_a - m_a): |e_a - m_a| <= 0.9273 + errors,
     * |Q_a| <= 0.8510 + E_d (s(WP+1)). Each tree adds mod 2^width: partial
     * sums may wrap, the final one fits, so it is exact.
     */
    OP("A", NULL, NP_OP_ADD, 2, LIVE(h.s, zf), 0, 0, 0, 0);
    OP("A", "s", NP_OP_ADD, 1, LIVE(h.s, zf), 0, w.s, 1, 1);
    if (dv) {
        /* e_a - m_a: below e's zero bits it is -m_a, whose inversion and carry-in the tree takes */
        OP("A", "em", NP_OP_ADD, 12, LIVE(h.em, ze), 0, w.em, 1, 0);
        OP("A", NULL, NP_OP_ADD, 6, LIVE(h.qs, zq), 0, 0, 0, 1);
        OP("A", "qs", NP_OP_ADD, 3, LIVE(h.qs, zq), 0, w.qs, 1, 2);
    }
    OP("A", NULL, NP_OP_REG, 1, LIVE(h.s, zf) + (dv ? 3u * LIVE(h.qs, zq) : 0u) + 1, 0, 0, 0, 0);

    /*
     * O. Kf' S and (derivative) Kd' Q_a as shift-adds of the constants' CSD
     * digits: |Kf' S| <= Kf' max |S|, |Kd' Q| <= Kd' max |Q|; then rounding
     * by WK + WP - F bits (F = N, ND - 2); the rounded words' bounds give
     * the saturation's need.
     */
    unsigned ff = np_simplex_f_frac(cfg), fd = np_simplex_d_frac(cfg);
    unsigned lf = const_mul(ops, max, &n, 1, (uint64_t)np_simplex_kf(cfg), h.smax, h.fprod, w.fprod,
                            wk + wp > ff ? wk + wp - ff : 0u, zf, "fprod");
    unsigned ld = dv ? const_mul(ops, max, &n, 3, (uint64_t)np_simplex_kd(cfg), h.qsmax, h.dprod, w.dprod,
                                 wk + wp > fd ? wk + wp - fd : 0u, zq, "dprod")
                     : 0u;
    unsigned lr = lf > ld ? lf : ld;
    out_round(ops, max, &n, 1, wk + wp > ff ? wk + wp - ff : 0u, h.fr, nb, !tight, "f", lr);
    if (dv)
        out_round(ops, max, &n, 3, wk + wp > fd ? wk + wp - fd : 0u, h.dr, nd, !tight, "df", lr);
    OP("O", NULL, NP_OP_REG, 1, nb + (dv ? 3u * nd : 0u) + 1, 0, 0, 0, 0);
    return n;
}

static void trace(np_trace *t, size_t n, const char *name, int64_t v)
{
    for (size_t i = 0; i < n; i++)
        if (t[i].signal && strcmp(t[i].signal, name) == 0)
            np_trace_add(&t[i], v);
}

void np_simplex_trace(const np_simplex_cfg *cfg, unsigned k, const np_simplex_sig *s, np_trace *t,
                      size_t n)
{
    if (k >= np_simplex_stage_count(cfg))
        return;
    const char *st = np_simplex_stage_table(cfg)[k].name;
    const uint16_t in[3] = { s->x, s->y, s->z };
    if (strcmp(st, "SK") == 0) {
        for (unsigned a = 0; a < 3; a++) {
            int64_t nn = s->sk[a] >> NP_SIMPLEX_FRAC_IN;
            trace(t, n, "bc", (int64_t)in[(a + 1u) % 3u] + in[(a + 2u) % 3u]);
            trace(t, n, "sk", s->sk[a]);
            trace(t, n, "n5", 5 * nn);
            trace(t, n, "n11", 11 * nn);
            trace(t, n, "n341", 341 * nn);
            trace(t, n, "n683", 683 * nn);
        }
    } else if (strcmp(st, "RK") == 0) {
        for (unsigned a = 0; a < 3; a++)
            trace(t, n, "off", s->off[a]);
    } else if (strcmp(st, "CH") == 0) {
        for (unsigned c = 0; c < 4; c++) {
            for (unsigned a = 0; a < 3; a++)
                trace(t, n, "d", s->d[c][a]);
            trace(t, n, "h", s->h[c]);
            trace(t, n, "gd2", (int64_t)s->g[c].cx * s->d[c][0] + (int64_t)s->g[c].cy * s->d[c][1]);
            trace(t, n, "gd", s->gd[c]);
        }
    } else if (strcmp(st, "KT") == 0) {
        for (unsigned c = 0; c < 4; c++) {
            for (unsigned a = 0; a < 3; a++)
                trace(t, n, "dsq", (int64_t)s->d[c][a] * s->d[c][a]);
            trace(t, n, "r2p", (int64_t)s->d[c][0] * s->d[c][0] + (int64_t)s->d[c][1] * s->d[c][1]);
            trace(t, n, "r2", s->r2[c]);
            trace(t, n, "r2x5", (int64_t)NP_SIMPLEX_R2_SCALE * s->r2[c]);
            trace(t, n, "td", (int64_t)NP_SIMPLEX_T_VERTEX - (int64_t)NP_SIMPLEX_R2_SCALE * s->r2[c]);
            trace(t, n, "t", s->t[c]);
        }
    } else if (strcmp(st, "P2") == 0) {
        for (unsigned c = 0; c < 4; c++) {
            trace(t, n, "tsq", (int64_t)((uint64_t)s->t[c] * s->t[c]));
            trace(t, n, "tau2", s->tau2[c]);
        }
    } else if (strcmp(st, "P4") == 0) {
        for (unsigned c = 0; c < 4; c++) {
            trace(t, n, "tau4p", (int64_t)((uint64_t)s->tau2[c] * s->tau2[c]));
            trace(t, n, "tau4", s->tau4[c]);
            if (cfg->deriv) {
                trace(t, n, "tau3p", (int64_t)((uint64_t)s->tau2[c] * s->t[c]));
                trace(t, n, "tau3", s->tau3[c]);
            }
        }
    } else if (strcmp(st, "M") == 0) {
        for (unsigned c = 0; c < 4; c++) {
            trace(t, n, "fcp", (int64_t)s->tau4[c] * s->gd[c]);
            trace(t, n, "fc", s->fc[c]);
            if (cfg->deriv) {
                trace(t, n, "qp", (int64_t)s->tau3[c] * s->gd[c]);
                trace(t, n, "q", s->q[c]);
                for (unsigned a = 0; a < 3; a++)
                    trace(t, n, "e", s->e[c][a]);
            }
        }
    } else if (strcmp(st, "M2") == 0) {
        for (unsigned c = 0; c < 4; c++) {
            int64_t q5 = np_shl(s->q[c], NP_SIMPLEX_M_SHIFT) + s->q[c];
            trace(t, n, "q5", q5);
            for (unsigned a = 0; a < 3; a++) {
                trace(t, n, "mp", q5 * s->d[c][a]);
                trace(t, n, "m", s->m[c][a]);
            }
        }
    } else if (strcmp(st, "A") == 0) {
        trace(t, n, "s", s->s);
        if (cfg->deriv) {
            for (unsigned c = 0; c < 4; c++)
                for (unsigned a = 0; a < 3; a++)
                    trace(t, n, "em", s->e[c][a] - s->m[c][a]);
            for (unsigned a = 0; a < 3; a++)
                trace(t, n, "qs", s->qs[a]);
        }
    } else { /* O */
        trace(t, n, "fprod", np_simplex_kf(cfg) * s->s);
        trace(t, n, "f", s->f);
        if (cfg->deriv)
            for (unsigned a = 0; a < 3; a++) {
                trace(t, n, "dprod", np_simplex_kd(cfg) * s->qs[a]);
                trace(t, n, "df", s->df[a]);
            }
    }
}
