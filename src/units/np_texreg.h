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
