/* SPDX-License-Identifier: MIT */
/*
 * unit_tex.h - internal: what the registry entries of the two scanline
 * texturing units (unit_fdiff.c, unit_texel.c) share.
 *
 * A vector transaction is one pixel (np_stream.h): the span descriptor's
 * texture fields and length, then the pixel index k; out the pixel's colour.
 * (The descriptor's y and x0 only tag the pixels; they are not in vectors.)
 *
 *   in   s, t, r     s48 Q15.32   texture coordinate at pixel 0
 *        ds, dt, dr  s41 Q8.32    step per pixel
 *        n           u17          pixels of the span (0..65536)
 *        k           u16          the pixel (0..65535); defined for any k,
 *                                 also k >= n (the span continued)
 *   out  cr, cg, cb  u8           colour, 8-bit
 *
 * The texture is configuration: texture=wood|marble|ramp (np_texreg.h).
 */
#ifndef UNIT_TEX_H
#define UNIT_TEX_H

#include <stddef.h>
#include <stdint.h>

#include "np_ref.h"
#include "np_rng.h"
#include "np_stream.h"
#include "np_texture.h"
#include "np_unit.h"

extern const np_unit np_unit_fdiff, np_unit_texel;

enum { UT_S, UT_T, UT_R, UT_DS, UT_DT, UT_DR, UT_N, UT_K, UT_NIN, UT_NDESC = UT_K };

void np_ut_fields(np_unit_fields *f);
/* Words of a descriptor (UT_NDESC fields) into a span at y = 0, x0 = 0. */
void np_ut_span(const uint64_t *in, np_span *sp);
/* The registers of built-in texture number tex (compiled once, thread-safe). */
const np_tex_regs *np_ut_regs(unsigned tex);
/* The name of texture number tex; NULL past the last one defined. */
const char *np_ut_texture_name(unsigned tex);
/*
 * A scene's texture as a named texture of the registry (after the built-in
 * ones): compiled into registers, then "texture=NAME" selects it in every
 * tool. The same name again redefines that texture (same number). 0 with *tex,
 * or -1 with err (it does not fit the registers, or the slots are full).
 * Call before any thread uses the texture.
 */
int np_ut_texture_add(const char *name, const np_ref_texture *t, unsigned *tex, char *err, size_t errlen);
/* The units' cfg_scene: register the scene's texture and select it (returns 1: the scene uses the unit). */
int np_ut_cfg_scene(const struct np_scene *sc, unsigned *tex, char *err, size_t errlen);
/*
 * The units' texture key (an enumeration: np_ut_texture_name's words, the
 * built-in textures then the scenes' "scene:NAME"), over member of type.
 */
#define UT_TEXTURE_KEY(type, member)                                                                     \
    NP_UNIT_KEY_WORDS("texture", type, member, 0, 2, 0,                                                  \
                      "texture in the registers: a built-in one, or a scene's (scene:NAME, added by a render)", \
                      np_ut_texture_name, NP_UNIT_KEY_SCENE)
/*
 * The model's configuration inside the registry's block of fdiff / texel:
 * the renderer calls the models (np_render_fdiff, np_render_texel) with it.
 */
const struct np_fdiff_cfg *np_ut_fdiff_cfg(const void *cfg);
const struct np_texel_cfg *np_ut_texel_cfg(const void *cfg);
/* The float reference's colour of pixel k (8-bit units). */
void np_ut_ref(unsigned tex, const uint64_t *in, double *out);
/* Annotated descriptors (the stiff cases) and random ones. */
size_t np_ut_descriptors(uint64_t (*desc)[NP_UNIT_MAX_FIELDS], size_t max);
void np_ut_random_desc(np_rng *rng, uint64_t *desc);
/* The unit's boundary table for the generic generator: every pixel of the short annotated spans. */
size_t np_ut_boundary(uint64_t (*in)[NP_UNIT_MAX_FIELDS], size_t max);
uint64_t np_ut_beats(const void *cfg, const uint64_t *desc);
void np_ut_set_field(np_field *f, const char *name, unsigned bits, int sgn, unsigned frac, const char *fmt);

#endif /* UNIT_TEX_H */
