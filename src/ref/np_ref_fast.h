/* SPDX-License-Identifier: MIT */
/*
 * np_ref_fast.h - branch-free forms of the float references' gradient
 * pieces, for the per-input references (np_ref_classic3, np_ref_simplex3).
 *
 * np_ref_grad (ref_classic.c) is Appendix B transcribed: three selects of
 * x, y, z by b = h & 3, three conditional negations and a sum whose shape
 * depends on b and bit 2. Those branches depend on the hash, so they are
 * mispredicted about half the time. np_ref_grad_fast does the same
 * operations on the same operands, with the selects done by indexing:
 *  - p, q, r: x, y, z rotated so that p is axis (b + 2) mod 3 (b = 1: x,
 *    2: y, 0 and 3: z), q the next axis and r the one after, as Appendix B
 *    picks them;
 *  - each negation as a multiplication by -1.0 or +1.0, which gives the
 *    negation's bits exactly (signed zeros included);
 *  - the sum p + (q + r), p + q or p + r, with all three candidates formed
 *    (no side effects: IEEE operations on finite doubles, no traps enabled)
 *    and one taken by index.
 * So the result is np_ref_grad's double bit for bit, -0.0 included; test
 * fast.ref_grad_fast checks every h on points with signed zeros and halves.
 */
#ifndef NP_REF_FAST_H
#define NP_REF_FAST_H

static inline double np_ref_grad_fast(unsigned h, double x, double y, double z)
{
    static const double sign[2] = { 1.0, -1.0 };
    const double v[3] = { x, y, z };
    unsigned b5 = h >> 5 & 1u, b4 = h >> 4 & 1u, b3 = h >> 3 & 1u, b2 = h >> 2 & 1u, b = h & 3u;
    unsigned pa = (b + 2u) % 3u, qa = (pa + 1u) % 3u, ra = (pa + 2u) % 3u;
    double p = sign[b5 == b3] * v[pa];
    double q = sign[b5 == b4] * v[qa];
    double r = sign[b5 != (b4 ^ b3)] * v[ra];
    const double tail[3] = { q + r, q, r }; /* b == 0; b2 == 0; else */
    unsigned mode = b == 0u ? 0u : 1u + b2;
    return p + tail[mode];
}

/*
 * The coefficients (G_x, G_y, G_z) of Appendix B's gradient of index h (the
 * partial derivatives of np_ref_grad in x, y, z): +-1.0 on the axes the
 * gradient uses, +0.0 on the one it does not (np_ref_simplex3's grad_coef),
 * as a table built by the compiler from the same rules.
 */
#define NP_REF_GC_P(h) (((h) & 3u) + 2u) % 3u
#define NP_REF_GC_SP(h) (((h) >> 5 & 1u) == ((h) >> 3 & 1u) ? -1.0 : 1.0)
#define NP_REF_GC_SQ(h) (((h) >> 5 & 1u) == ((h) >> 4 & 1u) ? -1.0 : 1.0)
#define NP_REF_GC_SR(h) (((h) >> 5 & 1u) != (((h) >> 4 & 1u) ^ ((h) >> 3 & 1u)) ? -1.0 : 1.0)
#define NP_REF_GC_USEQ(h) (((h) & 3u) == 0u || ((h) >> 2 & 1u) == 0u)
#define NP_REF_GC_USER(h) (((h) & 3u) == 0u || ((h) >> 2 & 1u) != 0u)
#define NP_REF_GC(h, a)                                                                                         \
    ((a) == NP_REF_GC_P(h)                 ? NP_REF_GC_SP(h)                                                    \
     : (a) == (NP_REF_GC_P(h) + 1u) % 3u ? (NP_REF_GC_USEQ(h) ? NP_REF_GC_SQ(h) : 0.0)                         \
                                           : (NP_REF_GC_USER(h) ? NP_REF_GC_SR(h) : 0.0))
#define NP_REF_GC_ROW(h) { NP_REF_GC(h, 0u), NP_REF_GC(h, 1u), NP_REF_GC(h, 2u) }
#define NP_REF_GC_8(h)                                                                                          \
    NP_REF_GC_ROW((h) + 0u), NP_REF_GC_ROW((h) + 1u), NP_REF_GC_ROW((h) + 2u), NP_REF_GC_ROW((h) + 3u),         \
        NP_REF_GC_ROW((h) + 4u), NP_REF_GC_ROW((h) + 5u), NP_REF_GC_ROW((h) + 6u), NP_REF_GC_ROW((h) + 7u)
#if defined(__GNUC__)
#define NP_REF_UNUSED __attribute__((unused))
#else
#define NP_REF_UNUSED
#endif
static const double np_ref_grad_coef[64][3] NP_REF_UNUSED = {
    NP_REF_GC_8(0u), NP_REF_GC_8(8u), NP_REF_GC_8(16u), NP_REF_GC_8(24u),
    NP_REF_GC_8(32u), NP_REF_GC_8(40u), NP_REF_GC_8(48u), NP_REF_GC_8(56u)
};

#endif
