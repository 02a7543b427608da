/* SPDX-License-Identifier: MIT */
/*
 * np_texreg.h - the host side of the scanline texturing units (np_fdiff,
 * np_texel): a float texture (np_ref_texture, as a scene describes it)
 * rounded into the units' registers (np_tex_regs), and the built-in
 * textures the unit registry names in its configuration ("texture=wood").
 */
#ifndef NP_TEXREG_H
#define NP_TEXREG_H

#include <stddef.h>
#include <stdint.h>

#include "np_ref.h"
#include "np_texture.h"

#ifdef __cplusplus
extern "C" {
#endif

/*
 * Round v * 2^frac to the nearest integer, ties up (floor(x + 1/2), exact
 * for |x| < 2^52), into a signed field of bits bits: 0, or -1 when it does
 * not fit. The one rounding rule from doubles to register and descriptor
 * words; error <= 2^-(frac+1).
 */
int np_texreg_quantize(double v, int frac, unsigned bits, int64_t *out);

/* S of a colour map: table segments per unit of f (N / period repeating, (N - 1) / (f1 - f0) clamped). */
double np_texreg_index_scale(const np_ref_colormap *c);

/*
 * The texture as unit registers: S folded into the quadric (J' = S (J - f0))
 * and the amplitudes, every value rounded (np_texreg_quantize) into its
 * register format. 0, or -1 with a message naming the value that does not fit.
 */
int np_texreg_compile(const np_ref_texture *t, np_tex_regs *r, char *err, size_t errlen);

/* Register formats of a texture sized by a scene (np_tex_regs.k_frac ...; 0 bits: the default format). */
typedef struct np_texreg_fmt {
    unsigned k_frac, k_bits;   /* quadric: s(k_bits) Q(k_bits-1-k_frac).k_frac */
    unsigned m_frac, m_bits;   /* transform: s(m_bits) Q(m_bits-1-m_frac).m_frac */
} np_texreg_fmt;
/* np_texreg_compile into the formats fmt (NULL: the defaults). */
int np_texreg_compile_fmt(const np_ref_texture *t, const np_texreg_fmt *fmt, np_tex_regs *r, char *err, size_t errlen);

/*
 * What rounding the texture into registers costs over a scene, and whether
 * the units can render it within 1 LSB (issue 10: register quantisation
 * inside the bound). Over the box lo..hi of the scene's texture coordinates
 * (every pixel's coordinate is a convex combination of its polygon's
 * vertices' and lies in it) and spans of at most max_span pixels, the index
 * error the registers add against the float texture is at most
 *   sum_j |K'_j - S q_j| m_j(box)                  (quadric: the monomial's
 *                                                    largest magnitude m_j)
 * + sum_i (63/64) ( |a'_i - S a_i|
 *                   + |a'_i| sum_a ( sum_b |M_ab - m_ab| |s_b|max + |o_a - o_a'|
 *                                    + 2^-33 (1 + max_span) ) )
 * (the lattice noise is in [0, 63/64] and its slope per axis at most 63/64;
 * the front end rounds u0 and du to 2^-33 each and du's error grows with
 * the pixel), plus the descriptor's rounding (s and ds to Q.32 by the host,
 * 2^-33 (1 + max_span) per axis) through |M| and the quadric's gradient
 * over the box, and the colour error by slope times that (np_tex_colour_slope).
 * The index reaches at most |x| <= sum_j |K'_j| m_j + sum_i |a'_i| 63/64;
 * a clamped map needs it below 2^I.
 */
typedef struct np_texreg_scene_bound {
    double reg_index;       /* the registers' index error bound (index units) */
    double reg_lsb;         /* the same in colour LSB (slope times) */
    double reg_lsb_bound;   /* what the formats guarantee (every residual at its half LSB), colour LSB */
    double index_max;       /* the bound on |x| over the box (index units) */
    unsigned idx_int_need;  /* the fewest index integer bits that hold it (clamped maps; 1 for repeating ones) */
    char index_worst[64];   /* the field of the largest term of that bound */
    double index_worst_value;
    char worst[96];         /* the field whose rounding contributes most, as the scene names it */
    double worst_value;     /* its value in the scene (after the colour map's scale where it is folded in) */
    double worst_lsb;       /* its contribution in colour LSB */
    double worst_mult;      /* colour LSB per unit of its rounding residual */
    unsigned worst_frac;    /* its register's fraction bits */
    unsigned worst_bits;    /* its register's width */
} np_texreg_scene_bound;

void np_texreg_scene_bound_compute(const np_ref_texture *t, const np_tex_regs *r, const double lo[3],
                                   const double hi[3], unsigned max_span, np_texreg_scene_bound *b);
/*
 * The check a span unit applies to a scene: 0 when unit_lsb (the unit's own
 * bound) + the registers' reg_lsb <= 1 and, for a clamped map, the index
 * fits idx_int bits (idx_int_max: the most the unit has); else -1 with a
 * message naming the scene, the field, its value and the width it would
 * need (exit 2 by the callers).
 */
int np_texreg_scene_check(const char *scene, const np_texreg_scene_bound *b, double unit_lsb, unsigned idx_int,
                          unsigned idx_int_max, char *err, size_t errlen);

/*
 * Registers sized by the scene (issue 10): the fewest transform fraction
 * bits m_frac (0..40) and then the fewest quadric fraction bits k_frac
 * (0..48) whose registers' bound over the scene (np_texreg_scene_bound_compute
 * over lo..hi and spans of max_span pixels) is <= budget colour LSB - the
 * transform searched with the quadric at its widest, then the quadric at the
 * transform found - each register with the fewest integer bits that hold
 * the scene's values (the transform at most 7, |m| < 128; the quadric's
 * width at most 64, so a large coefficient leaves fewer fraction bits).
 * When even the widest formats exceed budget, the widest are chosen and the
 * caller's check (np_texreg_scene_check) decides. r: the texture compiled
 * in them, b: their bound, fmt: the formats. 0, or -1 with err (a value that
 * fits no format).
 */
int np_texreg_size(const np_ref_texture *t, const double lo[3], const double hi[3], unsigned max_span, double budget,
                   np_texreg_fmt *fmt, np_tex_regs *r, np_texreg_scene_bound *b, char *err, size_t errlen);
/* The share of the 1 LSB budget the scene-sized registers get (the unit's own rounding has the rest). */
#define NP_TEXREG_SIZE_BUDGET 0.125

/*
 * Built-in textures: "wood" and "marble" (the seed scenes' textures, the same
 * as vectors/scenes/wood.json and marble.json; a test compares them) and
 * "ramp" (one octave, x = n, a clamped black-to-white map: colour = 255 n,
 * the steepest map, used by the stiff cases). NULL for another name.
 */
const np_ref_texture *np_texreg_builtin(const char *name);
/* The i-th built-in texture's name; NULL past the last. */
const char *np_texreg_builtin_name(unsigned i);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* NP_TEXREG_H */
