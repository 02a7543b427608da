/* SPDX-License-Identifier: MIT */
/*
 * np_hatch_render.h - a scene hatched by the unit hatch (seed 003; docs/hatch.md,
 * "Scenes") through the G-buffer renderer (np_gbuf.h) at one sample a pixel.
 *
 * Per covered sample:
 *   colour  u8 x 3   the scene's texture on the texel unit (np_gbuf_shade), lit
 *                    by the scene's light (np_gbuf_light, the fixed-point
 *                    Lambert of np_gbuf.h, also when light.image is false: the
 *                    tone is taken from the lit colour).
 *   Y       u8       luma, (77 R + 150 G + 29 B + 128) >> 8 (PIN: BT.601
 *                    weights in 8 bits, summing to 256, so white stays 255).
 *   tone    u8       255 - Y (the design's PIN a = 1 - light lum(colour) / 255).
 *   x_uv    u128 Q32.96  the sample's UV (the G-buffer's s48 Q15.32, exactly
 *                    s + k ds of its sub-span, formed per span in 128 bits:
 *                    x_uv0 + k dx_uv) shifted up 64 (mod 2^32 in UV).
 *   xu, xv  u33 Q1.32    the unit's seed space (np_unit_strokes.xs(x_uv, level)).
 *   out     u8       the unit's colour (np_unit.eval, or the coverage unit's
 *                    np_unit_strokes.eval_cover with the host's lists),
 *                    written as grey (c, c, c).
 * The unit is the registry's "hatch", reached through np_unit.h only: its
 * configuration is an opaque np_unit_cfg, and what the renderer needs besides
 * eval, ref and the pipe is its np_unit.strokes.
 * Uncovered samples get the background.
 *
 * Level of detail, per polygon (the host's; affine mapping, so constant):
 * J = the sub-span's UV change per pixel right (r.ds) and down (dsdy) on the
 * face's two UV axes; L = sqrt(|det J|) tile_pixels (PIN: the isotropic
 * scale - the geometric mean of J's singular values - stands for the
 * paper's detail direction h, which differs per layer while x_s is one
 * point; tile_pixels = 1/F, the artist's seed density). M = log2 L,
 * level = floor(M), m = M - level, from frexp(L) = f 2^e exactly (level =
 * e - 1, 2^m = 2f), then in integers:
 *   X   u31 Q1.30   round(2f 2^30) (X = 2^31 moves to the next level, X = 2^30)
 *   pm  u17 Q1.16   round(2^46 / X) = 2^-m
 *   m16 u16 Q0.16   log2(X), 16 bits by repeated squaring (square rounded
 *                   half up in Q1.30; a bit is 1 when the square reaches 2,
 *                   which is then halved): truncated
 *   om  u17 Q1.16   2^16 - m16
 * The level is clamped to the unit's [-64, 31] (np_unit_strokes.xs), m to 0 there.
 */
#ifndef NP_HATCH_RENDER_H
#define NP_HATCH_RENDER_H

#include <stddef.h>
#include <stdint.h>

#include "np_fixed.h"
#include "np_gbuf.h"
#include "np_scene.h"
#include "np_unit.h"

/* A polygon's level of detail: level, 2^-m and 1 - m (formats above). */
typedef struct np_hatch_lod {
    int level;
    uint32_t pm, om;
} np_hatch_lod;

/* The level of detail for the scale L = sqrt(|det J|) tile_pixels (above). */
np_hatch_lod np_hatch_lod_of(double L);

/*
 * The unit's configuration for a scene's "hatch" section: the registry's
 * defaults (np_unit_configure) with set, layers, fade and lanes, then more
 * ("key=value,...", may be NULL). 0, or -1 with err.
 */
int np_hatch_render_cfg(const np_scene_hatch *h, const char *more, np_unit_cfg *cfg, char *err, size_t errlen);
/* The unit's configuration as text, "set=..,layers=..,fade=..,guard=..,lanes=.." (the hash list's column). */
void np_hatch_render_cfg_text(const np_unit_cfg *cfg, char *s, size_t n);

typedef struct np_hatch_frame {
    unsigned w, h;
    uint8_t *rgb;          /* w * h * 3: the hatched image */
    uint8_t *tone;         /* w * h: the tone fed to the unit (0 where uncovered) */
    uint8_t *covered;      /* w * h */
    np_hatch_lod *lod;     /* per polygon id (n_prims); level INT32_MIN where never drawn */
    np_u128 *uv[2];        /* w * h: each covered pixel's x_uv (Q32.96) */
    uint32_t *poly;        /* w * h: the polygon (NP_GBUF_NONE uncovered) */
    uint64_t samples;      /* covered samples hatched */
    int level_min, level_max;
    /* Cycles of an iterative unit with P lanes: brute force layers N / P a point; coverage sum of ceil(len / P). */
    uint64_t iter_cycles;
    unsigned brute_cycles; /* brute force's a point: layers N / P */
    /* Coverage lists at the samples: mean entries per layer and the longest (coverage mode). */
    double list_mean;
    unsigned list_max;
    /*
     * The unrolled cycle model (np_pipe), fed every covered sample back to back
     * (when asked): brute force's seed stages, or in coverage mode the coverage
     * unit's slot stages reading the host's lists (np_unit_strokes.cover_cfg).
     */
    unsigned pipe_depth;   /* its latency */
    uint64_t pipe_cycles;
    int pipe_mismatch;
    /* Against the float reference np_unit.ref (when asked): max |out - ref| in LSB, and > 1 LSB count. */
    double ref_max;
    uint64_t ref_over;
    double seconds;        /* the bit-exact model's time */
} np_hatch_frame;

enum { NP_HATCH_RENDER_PIPE = 1, NP_HATCH_RENDER_REF = 2 };

/*
 * Hatch scene sc (its "hatch" section, or h when not NULL) with unit
 * configuration cfg; coverage 1 uses the host's lists. flags: NP_HATCH_RENDER_*.
 * 0, or -1 with err (G-buffer, the texel unit, lists overflowing, memory).
 */
int np_hatch_render(const np_scene *sc, const np_unit_cfg *cfg, unsigned coverage, double tile_pixels,
                    unsigned flags, np_hatch_frame *out, char *err, size_t errlen);
void np_hatch_frame_free(np_hatch_frame *f);

/* The hatching unit ("hatch", with np_unit.strokes), or NULL. */
const np_unit *np_hatch_unit(void);

#endif /* NP_HATCH_RENDER_H */
