/* SPDX-License-Identifier: MIT */
#include "np_classic.h"

#include <stddef.h>
#include <string.h>

/* The hand-vectorised batch kernel: GCC or Clang on x86-64 (chosen at run time by the CPU). */
#if (defined(__GNUC__) || defined(__clang__)) && defined(__x86_64__)
#define NP_CLASSIC_HAVE_AVX2 1
#else
#define NP_CLASSIC_HAVE_AVX2 0
#endif

/*
 * Input word ruler (each of x, y, z):
 *   15            8 7             0
 *  +---------------+---------------+
 *  |  cell (u8)    | fraction u8   |
 *  +---------------+---------------+
 */
enum { POS_IN_FRAC = 0, SIZE_IN_FRAC = 8, POS_IN_CELL = 8, SIZE_IN_CELL = 8 };

static uint8_t in_cell(uint16_t x) { return (uint8_t)((x >> POS_IN_CELL) & NP_MASK(SIZE_IN_CELL)); }
static uint8_t in_frac(uint16_t x) { return (uint8_t)((x >> POS_IN_FRAC) & NP_MASK(SIZE_IN_FRAC)); }

np_classic_cfg np_classic_cfg_default(unsigned out_bits)
{
    np_classic_cfg c;
    c.out_bits = out_bits;
    c.s_frac = out_bits - 2u + 6u;
    if (c.s_frac > NP_CLASSIC_WS_MAX)
        c.s_frac = NP_CLASSIC_WS_MAX;
    c.lerp_frac = out_bits - 2u + 5u;
    return c;
}

const char *np_classic_cfg_check(const np_classic_cfg *cfg)
{
    if (cfg->out_bits < NP_CLASSIC_OUT_MIN || cfg->out_bits > NP_CLASSIC_OUT_MAX)
        return "out_bits must be 2..16";
    if (cfg->s_frac < NP_CLASSIC_WS_MIN || cfg->s_frac > NP_CLASSIC_WS_MAX)
        return "s_frac must be 1..24";
    if (cfg->lerp_frac < np_classic_out_frac(cfg) || cfg->lerp_frac > NP_CLASSIC_WL_MAX)
        return "lerp_frac must be out_bits-2..30";
    return NULL;
}


double np_classic_error_bound_lsb(const np_classic_cfg *cfg)
{
    int f = (int)np_classic_out_frac(cfg);
    double es = cfg->s_frac >= NP_CLASSIC_SNUM_BITS ? 0.0 : 3.0 * np_pow2i(f - (int)cfg->s_frac);
    double el = np_pow2i(f - (int)cfg->lerp_frac - 1);
    return 0.5 + 3.0 * (es + el);
}

void np_classic_cell_setup(uint8_t i, uint8_t j, uint8_t k, np_classic_cell *cell)
{
    for (unsigned c = 0; c < 8; c++) {
        uint8_t ci = (uint8_t)(i + (c & 1u)), cj = (uint8_t)(j + ((c >> 1) & 1u)),
                ck = (uint8_t)(k + ((c >> 2) & 1u)); /* wrap mod 256 */
        cell->g[c] = np_grad_fast(np_hash6_fast(ci, cj, ck));
    }
}

int32_t np_classic_eval(const np_classic_cfg *cfg, uint16_t x, uint16_t y, uint16_t z)
{
    np_classic_cell cell;
    np_classic_cell_setup(in_cell(x), in_cell(y), in_cell(z), &cell);
    return np_classic_eval_in_cell(cfg, &cell, in_frac(x), in_frac(y), in_frac(z));
}

/*
 * --- The batch model's specialised path: the default widths N = 8, WS = 12,
 * WL = 11 (F = 6) in int32. The same operations as np_classic_eval_in_cell
 * with the widths as constants; every intermediate fits 32 bits:
 *   s            u13 Q1.12   (u^2 (768 - 2u) + 2^11) >> 12 <= 4096
 *   g            s11 Q2.8    |g| <= 768
 *   level 1      g0 2^12 + s (g1 - g0)   Q.20, |.| <= 768 2^12 + 4096 * 1536 < 2^24
 *                l1 = round to Q.11 (drop 9 bits), |l1| <= 2.5 2^11 + 1
 *   levels 2, 3  l 2^12 + s (l' - l)     Q.23, |.| <= 2.5 2^23 + 4096 * 5 2^11 + ... < 2^26
 *                rounded to Q.11 (drop 12 bits)
 *   out          round Q.11 to Q.6 (drop 5 bits), saturate to s8
 * (the level bounds are np_classic_datapath's range argument; the sums have
 * 5 bits of headroom below 2^31). Rounding is np_shr_round_half_up's: add
 * half, then an arithmetic shift, written with unsigned operations.
 */
enum {
    D_WS = 12, D_WL = 11, D_N = 8, D_F = D_N - 2, D_SNUM_DROP = NP_CLASSIC_SNUM_BITS - D_WS,
    D_DROP1 = NP_CLASSIC_FRAC_IN + D_WS - D_WL, /* level 1: Q.20 to Q.11 */
    D_DROP2 = D_WS,                             /* levels 2, 3: Q.23 to Q.11 */
    D_DROP_OUT = D_WL - D_F,                    /* out: Q.11 to Q.6 */
    D_OUT_MAX = (1 << (D_N - 1)) - 1, D_OUT_MIN = -D_OUT_MAX - 1
};

static inline int32_t asr32(int32_t v, unsigned sh)
{
    uint32_t u = (uint32_t)v;
    uint32_t sign = 0u - (u >> 31);
    return (int32_t)((u >> sh) | (sign & ~(~0u >> sh)));
}
static inline int32_t round32(int32_t v, unsigned sh) { return asr32(v + (1 << (sh - 1u)), sh); }

/* One lerp level in int32: round(a 2^WS + s (b - a)) dropping `drop` bits. */
static inline int32_t lerp32(int32_t s, int32_t a, int32_t b, unsigned drop)
{
    return round32(a * (1 << D_WS) + s * (b - a), drop);
}

static inline int32_t scurve32(int32_t u)
{
    return round32(u * u * (768 - 2 * u), D_SNUM_DROP);
}

/* Gradient contribution of the corner (ci, cj, ck) (u8 each) at offset (dx, dy, dz), s11. */
static inline int32_t grad32(uint32_t ci, uint32_t cj, uint32_t ck, int32_t dx, int32_t dy, int32_t dz)
{
    uint32_t g = np_grad_packed32[np_hash6_fast32(ci & 255u, cj & 255u, ck & 255u)];
    return np_grad_unpack(g, 0) * dx + np_grad_unpack(g, 1) * dy + np_grad_unpack(g, 2) * dz;
}

/* The portable int32 loop (any CPU; the AVX2 kernel's tail). */
static void eval_n_int32(const uint16_t *restrict xs, const uint16_t *restrict ys,
                         const uint16_t *restrict zs, int32_t *restrict out, size_t count)
{
    for (size_t n = 0; n < count; n++) {
        uint32_t x = xs[n], y = ys[n], z = zs[n];
        uint32_t i = x >> POS_IN_CELL, j = y >> POS_IN_CELL, k = z >> POS_IN_CELL;
        int32_t u = (int32_t)(x & NP_MASK(SIZE_IN_FRAC)), v = (int32_t)(y & NP_MASK(SIZE_IN_FRAC)),
                w = (int32_t)(z & NP_MASK(SIZE_IN_FRAC));
        int32_t u1 = u - 256, v1 = v - 256, w1 = w - 256;
        int32_t g0 = grad32(i, j, k, u, v, w);
        int32_t g1 = grad32(i + 1u, j, k, u1, v, w);
        int32_t g2 = grad32(i, j + 1u, k, u, v1, w);
        int32_t g3 = grad32(i + 1u, j + 1u, k, u1, v1, w);
        int32_t g4 = grad32(i, j, k + 1u, u, v, w1);
        int32_t g5 = grad32(i + 1u, j, k + 1u, u1, v, w1);
        int32_t g6 = grad32(i, j + 1u, k + 1u, u, v1, w1);
        int32_t g7 = grad32(i + 1u, j + 1u, k + 1u, u1, v1, w1);
        int32_t sx = scurve32(u), sy = scurve32(v), sz = scurve32(w);
        int32_t a = lerp32(sx, g0, g1, D_DROP1), b = lerp32(sx, g2, g3, D_DROP1);
        int32_t c = lerp32(sx, g4, g5, D_DROP1), d = lerp32(sx, g6, g7, D_DROP1);
        int32_t e = lerp32(sy, a, b, D_DROP2), f = lerp32(sy, c, d, D_DROP2);
        int32_t r = round32(lerp32(sz, e, f, D_DROP2), D_DROP_OUT);
        out[n] = r > D_OUT_MAX ? D_OUT_MAX : r < D_OUT_MIN ? D_OUT_MIN : r;
    }
}

#if NP_CLASSIC_HAVE_AVX2
/*
 * The same loop by hand for AVX2, eight inputs a step (issue 13: GCC 12
 * vectorises eval_n_int32 but, tuned for generic x86-64, emulates its table
 * loads with scalar inserts and extracts, about 0.9x stb_perlin_noise3; the
 * hardware gathers here give 2x and more, docs/sweep.md). Every operation is
 * eval_n_int32's on 32-bit lanes, same order, same widths:
 *   - the 24 table loads per input (two hash nibble tables and the packed
 *     gradient of each corner) are vpgatherdd;
 *   - c * d for a coefficient c in {-1, 0, +1} is vpsignd(d, c), exactly;
 *   - the products s (b - a) are vpmulld (low 32 bits; they fit, see above);
 *   - rounding is add half, then vpsrad: an arithmetic shift, as asr32.
 */
#include <immintrin.h>

#define AVX2_FN __attribute__((target("avx2")))
#define V8(c) _mm256_set1_epi32(c)

AVX2_FN static inline __m256i round8(__m256i v, int sh)
{
    return _mm256_srai_epi32(_mm256_add_epi32(v, V8(1 << (sh - 1))), sh);
}
/* round(a 2^WS + s (b - a)) dropping `drop` bits (lerp32). */
AVX2_FN static inline __m256i lerp8(__m256i s, __m256i a, __m256i b, int drop)
{
    return round8(_mm256_add_epi32(_mm256_slli_epi32(a, D_WS), _mm256_mullo_epi32(s, _mm256_sub_epi32(b, a))),
                  drop);
}
/* Gradient coefficient of axis a from np_grad_packed32 words: -1, 0 or +1 (np_grad_unpack). */
AVX2_FN static inline __m256i unpack8(__m256i g, int a)
{
    return _mm256_sub_epi32(_mm256_and_si256(_mm256_srli_epi32(g, 2 * a), V8(3)), V8(1));
}
AVX2_FN static inline __m256i load8(const uint16_t *p)
{
    return _mm256_cvtepu16_epi32(_mm_loadu_si128((const __m128i *)(const void *)p));
}

AVX2_FN static void eval_n_avx2(const uint16_t *restrict xs, const uint16_t *restrict ys,
                                const uint16_t *restrict zs, int32_t *restrict out, size_t count)
{
    const int *lo_t = (const int *)np_hash6_lo32, *hi_t = (const int *)np_hash6_hi32,
              *grad_t = (const int *)np_grad_packed32;
    const __m256i cell_mask = V8(NP_MASK(SIZE_IN_CELL)), frac_mask = V8(NP_MASK(SIZE_IN_FRAC)),
                  nib = V8(15), one = V8(1);
    size_t n = 0;
    for (; n + 8u <= count; n += 8u) {
        __m256i in[3] = { load8(xs + n), load8(ys + n), load8(zs + n) };
        /*
         * Per axis a and corner side e (0: the cell, 1: the cell + 1 mod 256):
         * the offset d[e][a] (s9 Q1.8) and the axis's part of the two nibble
         * tables' indices, lo/hi[e][a] = nibble << (4 (2 - a)) (np_hash6_fast32).
         */
        __m256i d[2][3], lo[2][3], hi[2][3];
        for (int a = 0; a < 3; a++) {
            __m256i cell[2];
            cell[0] = _mm256_srli_epi32(in[a], POS_IN_CELL);
            cell[1] = _mm256_and_si256(_mm256_add_epi32(cell[0], one), cell_mask);
            d[0][a] = _mm256_and_si256(in[a], frac_mask);
            d[1][a] = _mm256_sub_epi32(d[0][a], V8(256));
            for (int e = 0; e < 2; e++) {
                lo[e][a] = _mm256_slli_epi32(_mm256_and_si256(cell[e], nib), 4 * (2 - a));
                hi[e][a] = _mm256_slli_epi32(_mm256_srli_epi32(cell[e], 4), 4 * (2 - a));
            }
        }
        __m256i g[8];
        for (int c = 0; c < 8; c++) {
            int ex = c & 1, ey = (c >> 1) & 1, ez = (c >> 2) & 1;
            __m256i li = _mm256_or_si256(_mm256_or_si256(lo[ex][0], lo[ey][1]), lo[ez][2]);
            __m256i hj = _mm256_or_si256(_mm256_or_si256(hi[ex][0], hi[ey][1]), hi[ez][2]);
            __m256i h = _mm256_and_si256(
                _mm256_add_epi32(_mm256_i32gather_epi32(lo_t, li, 4), _mm256_i32gather_epi32(hi_t, hj, 4)),
                V8(63));
            __m256i gp = _mm256_i32gather_epi32(grad_t, h, 4);
            g[c] = _mm256_add_epi32(_mm256_add_epi32(_mm256_sign_epi32(d[ex][0], unpack8(gp, 0)),
                                                     _mm256_sign_epi32(d[ey][1], unpack8(gp, 1))),
                                    _mm256_sign_epi32(d[ez][2], unpack8(gp, 2)));
        }
        __m256i s[3];
        for (int a = 0; a < 3; a++) {
            __m256i u = d[0][a];
            __m256i num = _mm256_mullo_epi32(_mm256_mullo_epi32(u, u), _mm256_sub_epi32(V8(768), _mm256_add_epi32(u, u)));
            s[a] = round8(num, D_SNUM_DROP);
        }
        __m256i l1a = lerp8(s[0], g[0], g[1], D_DROP1), l1b = lerp8(s[0], g[2], g[3], D_DROP1);
        __m256i l1c = lerp8(s[0], g[4], g[5], D_DROP1), l1d = lerp8(s[0], g[6], g[7], D_DROP1);
        __m256i l2a = lerp8(s[1], l1a, l1b, D_DROP2), l2b = lerp8(s[1], l1c, l1d, D_DROP2);
        __m256i r = round8(lerp8(s[2], l2a, l2b, D_DROP2), D_DROP_OUT);
        r = _mm256_min_epi32(_mm256_max_epi32(r, V8(D_OUT_MIN)), V8(D_OUT_MAX));
        _mm256_storeu_si256((__m256i *)(void *)(out + n), r);
    }
    eval_n_int32(xs + n, ys + n, zs + n, out + n, count - n);
}
#endif /* NP_CLASSIC_HAVE_AVX2 */

static int is_default_cfg(const np_classic_cfg *cfg)
{
    return cfg->out_bits == D_N && cfg->s_frac == D_WS && cfg->lerp_frac == D_WL;
}

static int have_avx2(void)
{
#if NP_CLASSIC_HAVE_AVX2
    return __builtin_cpu_supports("avx2");
#else
    return 0;
#endif
}

int np_classic_eval_n_path(unsigned path, const np_classic_cfg *cfg, const uint16_t *x,
                           const uint16_t *y, const uint16_t *z, int32_t *out, size_t count)
{
    switch (path) {
    case NP_CLASSIC_BATCH_GENERIC: {
        const np_classic_cfg c = *cfg;
        for (size_t n = 0; n < count; n++)
            out[n] = np_classic_eval(&c, x[n], y[n], z[n]);
        return 0;
    }
    case NP_CLASSIC_BATCH_INT32:
        if (!is_default_cfg(cfg))
            return -1;
        eval_n_int32(x, y, z, out, count);
        return 0;
    case NP_CLASSIC_BATCH_AVX2:
        if (!is_default_cfg(cfg) || !have_avx2())
            return -1;
#if NP_CLASSIC_HAVE_AVX2
        eval_n_avx2(x, y, z, out, count);
#endif
        return 0;
    default:
        return -1;
    }
}

void np_classic_eval_n(const np_classic_cfg *cfg, const uint16_t *x, const uint16_t *y,
                       const uint16_t *z, int32_t *out, size_t count)
{
    static const unsigned order[] = { NP_CLASSIC_BATCH_AVX2, NP_CLASSIC_BATCH_INT32 };
    for (unsigned k = 0; k < sizeof order / sizeof order[0]; k++)
        if (np_classic_eval_n_path(order[k], cfg, x, y, z, out, count) == 0)
            return;
    np_classic_eval_n_path(NP_CLASSIC_BATCH_GENERIC, cfg, x, y, z, out, count);
}

/* --- Pipeline stages: the same primitives, split at the register banks. --- */

static np_classic_sig *sig_of(void *s) { return (np_classic_sig *)s; }

/* L: corner hashes; S first half: squares of the fractions. */
static void stage_l(const void *cfgv, void *sv)
{
    (void)cfgv;
    np_classic_sig *s = sig_of(sv);
    uint8_t i = in_cell(s->x), j = in_cell(s->y), k = in_cell(s->z);
    for (unsigned c = 0; c < 8; c++)
        s->h[c] = np_hash6_fast((uint8_t)(i + (c & 1u)), (uint8_t)(j + ((c >> 1) & 1u)),
                           (uint8_t)(k + ((c >> 2) & 1u)));
    const uint16_t in[3] = { s->x, s->y, s->z };
    for (unsigned a = 0; a < 3; a++) {
        uint32_t f = in_frac(in[a]);
        s->s2[a] = f * f;
    }
}

/* H: gradient decode and contribution; S second half: the s-curve. */
static void stage_h(const void *cfgv, void *sv)
{
    const np_classic_cfg *cfg = cfgv;
    np_classic_sig *s = sig_of(sv);
    const uint16_t in[3] = { s->x, s->y, s->z };
    int16_t d[2][3];
    for (unsigned a = 0; a < 3; a++) {
        d[0][a] = (int16_t)in_frac(in[a]);
        d[1][a] = (int16_t)(in_frac(in[a]) - 256);
        uint32_t num = s->s2[a] * (uint32_t)(768u - 2u * in_frac(in[a]));
        s->s[a] = (uint32_t)np_shr_round_half_up_u(num, NP_CLASSIC_SNUM_BITS - cfg->s_frac);
    }
    for (unsigned c = 0; c < 8; c++)
        s->g[c] = np_grad_apply_q8(np_grad_fast(s->h[c]), d[c & 1u][0], d[(c >> 1) & 1u][1],
                                   d[(c >> 2) & 1u][2]);
}

static void stage_i1m(const void *cfgv, void *sv)
{
    (void)cfgv;
    np_classic_sig *s = sig_of(sv);
    for (unsigned p = 0; p < 4; p++)
        s->prod[p] = np_classic_lerp_mul(s->s[0], s->g[2 * p], s->g[2 * p + 1]);
}

static void stage_i1a(const void *cfgv, void *sv)
{
    np_classic_sig *s = sig_of(sv);
    for (unsigned p = 0; p < 4; p++)
        s->l1[p] = np_classic_lerp_add(cfgv, s->g[2 * p], NP_CLASSIC_FRAC_IN, s->prod[p]);
}

static void stage_i2m(const void *cfgv, void *sv)
{
    (void)cfgv;
    np_classic_sig *s = sig_of(sv);
    for (unsigned p = 0; p < 2; p++)
        s->prod[p] = np_classic_lerp_mul(s->s[1], s->l1[2 * p], s->l1[2 * p + 1]);
}

static void stage_i2a(const void *cfgv, void *sv)
{
    const np_classic_cfg *cfg = cfgv;
    np_classic_sig *s = sig_of(sv);
    for (unsigned p = 0; p < 2; p++)
        s->l2[p] = np_classic_lerp_add(cfg, s->l1[2 * p], cfg->lerp_frac, s->prod[p]);
}

static void stage_i3m(const void *cfgv, void *sv)
{
    (void)cfgv;
    np_classic_sig *s = sig_of(sv);
    s->prod[0] = np_classic_lerp_mul(s->s[2], s->l2[0], s->l2[1]);
}

static void stage_i3a(const void *cfgv, void *sv)
{
    const np_classic_cfg *cfg = cfgv;
    np_classic_sig *s = sig_of(sv);
    s->l3 = np_classic_lerp_add(cfg, s->l2[0], cfg->lerp_frac, s->prod[0]);
}

static void stage_o(const void *cfgv, void *sv)
{
    np_classic_sig *s = sig_of(sv);
    s->out = np_classic_output(cfgv, s->l3);
}

const np_stage_desc np_classic_stages[NP_CLASSIC_STAGES] = {
    { "L", stage_l },     { "H", stage_h },     { "I1m", stage_i1m },
    { "I1a", stage_i1a }, { "I2m", stage_i2m }, { "I2a", stage_i2a },
    { "I3m", stage_i3m }, { "I3a", stage_i3a }, { "O", stage_o },
};

int np_classic_pipe_init(np_pipe *p, const np_classic_cfg *cfg)
{
    return np_pipe_init(p, np_classic_stages, NP_CLASSIC_STAGES, sizeof(np_classic_sig), cfg);
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

size_t np_classic_datapath(const np_classic_cfg *cfg, np_op *ops, size_t max)
{
    size_t n = 0;
    unsigned ws = cfg->s_frac, wl = cfg->lerp_frac, nb = cfg->out_bits, f = nb - 2u;
    unsigned sw = ws + 1u;   /* s: u(WS+1) Q1.WS */
    /* L: cell + 1 (three 8-bit incrementers), 64 pattern lookups, an adder tree per corner. */
    OP("L", NULL, NP_OP_INC, 3, 8, 0, 0, 0, 0);
    OP("L", NULL, NP_OP_LUT, 64, 3, 6, 0, 0, 1);
    OP("L", NULL, NP_OP_ADD, 32, 6, 0, 0, 0, 2);
    OP("L", NULL, NP_OP_ADD, 16, 6, 0, 0, 0, 3);
    OP("L", "h", NP_OP_ADD, 8, 6, 0, 6, 0, 4);
    OP("L", "s2", NP_OP_SQR, 3, 8, 0, 16, 0, 0); /* u * u: a squarer */
    OP("L", NULL, NP_OP_REG, 1, 3 * 8 + 8 * 6 + 3 * 16 + 1, 0, 0, 0, 0); /* u,v,w; h; squares; valid */
    /* H: select p, q, r (3:1 muxes of s9 offsets), conditional negates, two additions. */
    OP("H", NULL, NP_OP_MUX, 24, 9, 3, 0, 0, 0);
    /* -(-256) = 256 needs s10: the conditional negates are 10 bits wide (np_classic3.v). */
    OP("H", NULL, NP_OP_NEG, 24, 10, 0, 0, 0, 1);
    OP("H", NULL, NP_OP_ADD, 8, 10, 0, 0, 0, 2);
    OP("H", "g", NP_OP_ADD, 8, NP_CLASSIC_G_BITS, 0, NP_CLASSIC_G_BITS, 1, 3);
    /* S second half, in parallel: 768 - 2u, the 16 x 10 product, rounding to WS bits. */
    OP("H", NULL, NP_OP_INC, 3, 10, 0, 0, 0, 0); /* 768 - 2u: a constant minus x */
    OP("H", "snum", NP_OP_MUL, 3, 16, 10, NP_CLASSIC_SNUM_BITS, 0, 1);
    if (ws < NP_CLASSIC_SNUM_BITS)
        OP("H", "s", NP_OP_INC, 3, sw, 0, sw, 0, 2); /* + half an LSB */
    OP("H", NULL, NP_OP_REG, 1, 8 * NP_CLASSIC_G_BITS + 3 * sw + 1, 0, 0, 0, 0);
    /* I: three levels of (difference, product | sum, rounding). */
    static const char *const names[3][4] = { { "diff1", "prod1", "sum1", "l1" },
                                             { "diff2", "prod2", "sum2", "l2" },
                                             { "diff3", "prod3", "sum3", "l3" } };
    static const char *const mstage[3] = { "I1m", "I2m", "I3m" };
    static const char *const astage[3] = { "I1a", "I2a", "I3a" };
    /*
     * Range of each level (same argument as the 1.5 bound of the function,
     * np_classic.h): a level-n value interpolates along n axes, each of which
     * contributes at most max_t (1 - s)t + s(1 - t) = 1/2, while the other
     * axes contribute at most 1 each. So |l1| <= 2.5, |l2| <= 2, |l3| <= 1.5,
     * |g| <= 3, and a difference b - a is at most twice the operands' bound.
     * Integer bits (besides the sign) of each signal follow:
     *   level  operand  |b-a|  diff   value
     *   1      g  Q2    6      Q3     l1 Q2 (2.5)
     *   2      l1 Q2    5      Q3     l2 Q2 (2, reachable)
     *   3      l2 Q2    4      Q3     l3 Q1 (1.5)
     * The product s (b - a) has |s| <= 1, so it needs no bit beyond the
     * difference's: pw = dw + WS.
     */
    static const unsigned val_int[3] = { 2, 2, 1 };
    /*
     * Constant-zero low bits: when level 1 widens (8 + WS < WL), l1 = (the
     * exact sum) << (WL - 8 - WS) ends in that many 0 bits, and they pass on
     * (a level drops WS of them). Hardware (and synthesis) keeps no zero bit,
     * so each level is priced at its effective widths: operand fraction
     * af - zin, result fraction WL - zout. The traced widths (out) stay the
     * words' full widths.
     */
    unsigned zin = 0;
    for (unsigned lvl = 0; lvl < 3; lvl++) {
        unsigned cnt = 4u >> lvl;                         /* 4, 2, 1 interpolators */
        unsigned af = lvl == 0 ? NP_CLASSIC_FRAC_IN : wl; /* operand fraction bits */
        unsigned dw = af + 4u;                            /* b - a: s(af+4) Q3.af */
        unsigned pw = dw + ws;                            /* s (b - a): Q3.(af+WS) */
        unsigned sumw = af + ws + 1u + val_int[lvl];      /* a + s (b - a), exact */
        unsigned vw = wl + 1u + val_int[lvl];             /* rounded level value */
        unsigned later = (lvl < 1 ? sw : 0u) + (lvl < 2 ? sw : 0u); /* sy, sz still needed */
        unsigned zout = lvl == 0 ? (wl > af + ws ? wl - af - ws : 0u) : (zin > ws ? zin - ws : 0u);
        unsigned afe = af - zin, wle = wl - zout;         /* effective fraction bits */
        unsigned dwe = afe + 4u, pwe = dwe + ws, sumwe = afe + ws + 1u + val_int[lvl], vwe = wle + 1u + val_int[lvl];
        /*
         * The rounding below drops sh = af + WS - WL bits (0: it widens): of
         * prod's low bits it reads only bit sh - 1 (the carry of its half LSB),
         * and none of the WS bits under a 2^WS when sh > WS, so the bank
         * keeps prod without its dead low bits.
         */
        unsigned sh = afe + ws > wle ? afe + ws - wle : 0u;
        unsigned dead = sh == 0u ? 0u : (sh - 1u < ws ? sh - 1u : ws);
        OP(mstage[lvl], names[lvl][0], NP_OP_ADD, cnt, dwe, 0, dw, 1, 0);
        OP(mstage[lvl], names[lvl][1], NP_OP_MUL, cnt, sw, dwe, pw, 1, 1);
        OP(mstage[lvl], NULL, NP_OP_REG, 1, cnt * (pwe - dead + afe + 3u) + later + 1, 0, 0, 0, 0);
        /*
         * a 2^WS + prod: the low WS bits are prod's (a 2^WS has none there), so
         * the adder spans only the sumw - WS bits above them. The rounding
         * drops sh bits: its half LSB meets only prod's bits when sh <= WS,
         * so it is an incrementer of bits sh..WS-1 whose carry enters the
         * adder (sh == WS: the adder's carry-in); when sh > WS it lands on
         * the adder's sum: an incrementer over the kept bits and the round
         * bit after it. l3: O reads only the bits from its own round bit
         * (WL - F - 1) up; under them the adder only carries (a comparator's
         * chain).
         */
        unsigned unread = lvl == 2u && wl > f + 1u + zout ? wl - f - 1u - zout : 0u;
        OP(astage[lvl], names[lvl][2], NP_OP_ADD, cnt, sumwe - ws - unread, 0, sumw, 1, 0);
        if (unread > 0u)
            OP(astage[lvl], NULL, NP_OP_CMP, cnt, unread, 0, 0, 0, 0);
        if (sh > 0u && sh < ws)
            OP(astage[lvl], names[lvl][3], NP_OP_INC, cnt, ws - sh + 1u, 0, vw, 1, 1);
        else if (sh > ws)
            OP(astage[lvl], names[lvl][3], NP_OP_INC, cnt, vwe + 1u, 0, vw, 1, 1);
        else
            OP(astage[lvl], names[lvl][3], NP_OP_REG, 0, 0, 0, vw, 1, 1); /* wiring, or the adder's carry-in */
        OP(astage[lvl], NULL, NP_OP_REG, 1, cnt * (vwe - unread) + later + 1, 0, 0, 0, 0);
        zin = zout;
    }
    /* O: round to Q2.F, saturate to N bits (two comparisons, a 3:1 mux). */
    /*
     * Round to Q2.F (adding half an LSB: an incrementer over the kept bits
     * and the round bit) and saturate to sN. Since |l3| <= 1.5 < 2, the
     * rounded word leaves sN only by the rounding's carry into +2.0, whose
     * low N bits (the minimum) are the saturated maximum inverted: the clamp
     * is that carry and one gate per bit, which synthesis folds into the
     * incrementer (report gates --synth: O is the incrementer and the bank).
     * Without rounding (wl == f) l3 is already sN Q2.F: wiring.
     */
    if (wl > f)
        OP("O", "f", NP_OP_INC, 1, f + 3u, 0, nb, 1, 0);
    else
        OP("O", "f", NP_OP_REG, 0, 0, 0, nb, 1, 0); /* wiring only */
    OP("O", NULL, NP_OP_REG, 1, nb + 1, 0, 0, 0, 0);
    return n;
}

static void trace(np_trace *t, size_t n, const char *name, int64_t v)
{
    for (size_t i = 0; i < n; i++)
        if (t[i].signal && strcmp(t[i].signal, name) == 0)
            np_trace_add(&t[i], v);
}

void np_classic_trace(const np_classic_cfg *cfg, unsigned k, const np_classic_sig *s, np_trace *t,
                      size_t n)
{
    const uint16_t in[3] = { s->x, s->y, s->z };
    switch (k) {
    case 0:
        for (unsigned c = 0; c < 8; c++)
            trace(t, n, "h", s->h[c]);
        for (unsigned a = 0; a < 3; a++)
            trace(t, n, "s2", s->s2[a]);
        break;
    case 1:
        for (unsigned c = 0; c < 8; c++)
            trace(t, n, "g", s->g[c]);
        for (unsigned a = 0; a < 3; a++) {
            trace(t, n, "snum", (int64_t)s->s2[a] * (768 - 2 * (int64_t)in_frac(in[a])));
            trace(t, n, "s", s->s[a]);
        }
        break;
    case 2: case 4: case 6: {
        unsigned lvl = (k - 2u) / 2u, cnt = 4u >> lvl;
        static const char *const dn[3] = { "diff1", "diff2", "diff3" };
        static const char *const pn[3] = { "prod1", "prod2", "prod3" };
        for (unsigned p = 0; p < cnt; p++) {
            int64_t a = lvl == 0 ? s->g[2 * p] : lvl == 1 ? s->l1[2 * p] : s->l2[0];
            int64_t b = lvl == 0 ? s->g[2 * p + 1] : lvl == 1 ? s->l1[2 * p + 1] : s->l2[1];
            trace(t, n, dn[lvl], b - a);
            trace(t, n, pn[lvl], s->prod[p]);
        }
        break;
    }
    case 3: case 5: case 7: {
        unsigned lvl = (k - 3u) / 2u, cnt = 4u >> lvl;
        static const char *const sn[3] = { "sum1", "sum2", "sum3" };
        static const char *const ln[3] = { "l1", "l2", "l3" };
        for (unsigned p = 0; p < cnt; p++) {
            int64_t a = lvl == 0 ? s->g[2 * p] : lvl == 1 ? s->l1[2 * p] : s->l2[0];
            trace(t, n, sn[lvl], np_shl(a, cfg->s_frac) + s->prod[p]);
            trace(t, n, ln[lvl], lvl == 0 ? s->l1[p] : lvl == 1 ? s->l2[p] : s->l3);
        }
        break;
    }
    default:
        trace(t, n, "f", s->out);
        break;
    }
}
