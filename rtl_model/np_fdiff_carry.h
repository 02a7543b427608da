/* SPDX-License-Identifier: MIT */
/*
 * np_fdiff_carry.h - the multiplier-free cell set-up of the forward-
 * difference unit (issue 26; docs/fdiff.md, "A multiplier-free set-up").
 *
 * The multiplier set-up (np_fdiff.h) computes, at a cell's first pixel k_c,
 * the exact forward differences Y_j = a' Delta^j n(k_c) (116 fraction bits,
 * modulo 2^128) of the cell's trilinear polynomial
 *
 *   n = a + bU + cV + dW + eUV + fVW + gWU + hUVW,   U = fu + (k - k_c) du, ...
 *
 * and rounds each once. Y_j is linear in a..h:
 *
 *   Y_j = sum_m c_m a' Delta^j[m](k_c),   m in {1, U, V, W, UV, VW, WU, UVW},
 *
 * so a unit that holds the seven monomials' forward differences (times a')
 * at the current pixel needs, at a crossing, only the 20 products of a..h
 * (s10 Q3.6) by them. Every monomial is a polynomial of degree <= 3 in k, so
 * it is carried from pixel to pixel by additions (Delta^3 constant), and a
 * cell crossing, which shifts a fraction by an integer (U -> U - j_u, j_u =
 * the integer part of frac + du, in [-128, 128]), transforms the monomials
 * linearly: UV -> UV - j_v U - j_u V + j_u j_v, and so on. All of it is ring
 * arithmetic on exact integers, so the carried Y_j are the multiplier
 * set-up's Y_j bit for bit (modulo 2^128), and the rounded differences are
 * the same: no drift, same images.
 *
 * --- Carried state per octave (this model: every value modulo 2^128 at
 *     the common scale Q.110 of a' UVW; the hardware's widths: docs/fdiff.md) ---
 *   amp          a'                     Q17.14 (Delta^0 only)
 *   lin[a][t]    a' U_a, a' du_a         Q.46   t = 0, 1 (Delta^2 = 0)
 *   quad[p][t]   a' UV, a' VW, a' WU     Q.78   t = 0, 1, 2 (Delta^2 = 2 a' du dv)
 *   cub[t]       a' UVW                  Q.110  t = 0..3 (Delta^3 = 6 a' du dv dw)
 * (axis pairs p: 0 = (U, V), 1 = (V, W), 2 = (W, U)).
 *
 * --- Operations ---
 *   init (span start): from the front end's fractions and steps: products
 *     (the span set-up; np_fdiff_carry_init);
 *   step (every pixel): x_t += x_{t+1} for every carried vector, 9 additions
 *     per octave (np_fdiff_carry_step);
 *   rebase (a crossing, integer shifts j): additions and products by the
 *     small integers j (|j| <= 1 for |du| < 1: additions only)
 *     (np_fdiff_carry_rebase);
 *   set-up (a crossing, or the re-set-up interval): Y_j by the 20 products
 *     of a..h, then one rounding per difference (np_fdiff_carry_setup).
 */
#ifndef NP_FDIFF_CARRY_H
#define NP_FDIFF_CARRY_H

#include <stdint.h>

#include "np_fixed.h"
#include "np_texture.h"

#ifdef __cplusplus
extern "C" {
#endif

enum {
    NP_FDIFF_CARRY_FRAC = 3 * NP_TEX_FC + NP_TEX_AMP_FRAC /* 110: the common scale of the carried values */
};

typedef struct np_fdiff_carry {
    np_s128 amp;
    np_s128 lin[3][2];
    np_s128 quad[3][3];
    np_s128 cub[4];
} np_fdiff_carry;

/* The seed's trilinear coefficients a..h (s10 Q3.6, exact) of the cell of coordinate u (u40 Q8.32). */
void np_fdiff_cell_coef(const uint64_t u[3], int64_t co[8]);

/* Span start: the monomials of octave oct's cell at coordinate u (u40 Q8.32) with step du (s40 Q7.32). */
void np_fdiff_carry_init(np_fdiff_carry *c, const np_tex_regs *r, unsigned oct, const uint64_t u[3],
                         const int64_t du[3]);
/* One pixel: every carried difference vector by one step (additions). */
void np_fdiff_carry_step(np_fdiff_carry *c);
/*
 * A crossing: the fractions shift by the integers j (U -> U - j[0], ...):
 * j[a] = floor(frac(u_a) + du_a) of the step that crossed, in [-128, 128].
 */
void np_fdiff_carry_rebase(np_fdiff_carry *c, const int32_t j[3]);
/*
 * The integer shifts of the step from coordinate u (before the DDA step)
 * with step du: the integer part of frac(u) + du per axis (the carry out of
 * the fraction adder, with the step's integer part).
 */
void np_fdiff_carry_shift(const uint64_t u[3], const int64_t du[3], int32_t j[3]);
/*
 * The cell set-up from the carried monomials: the four differences d[0..3]
 * (s(W) QI.F, F fraction bits) of the cell of coordinate u (for its lattice
 * values), and, if exact is not NULL, Y_0..Y_3 (116 fraction bits, modulo
 * 2^128): equal to np_fdiff_cell_setup's for the same u and du.
 */
void np_fdiff_carry_setup(const np_fdiff_carry *c, const uint64_t u[3], unsigned F, unsigned W, np_s128 d[4],
                          np_s128 exact[4]);

/*
 * The hardware's widths: keep every carried value modulo 2^bits at the
 * common scale Q.110 (a' U modulo 2^(bits-64) at Q.46, a' UV.. modulo
 * 2^(bits-32) at Q.78, a' UVW modulo 2^bits), bits = the window the
 * rounding reads (np_fdiff_y_window, 117 + I). Every operation is a ring
 * operation, so the rounded differences are unchanged (test
 * fdiff.carry_seed_scenes and carry_adversarial check it).
 */
void np_fdiff_carry_wrap(np_fdiff_carry *c, unsigned bits);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* NP_FDIFF_CARRY_H */
