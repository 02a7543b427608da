/* SPDX-License-Identifier: MIT */
/*
 * np_noisetex.h - a time-varying solid texture through a 4-D noise unit, as
 * a scene of the scene pipeline (scene key texture.noise, np_scene.h;
 * docs/noise-nd.md, "A 4-D texture in a scene").
 *
 * The scene is scan-converted into the G-buffer (np_gbuf.h, one sample a
 * pixel); at shading time every covered sample's texture coordinate feeds
 * the scene's texture model with its octaves' noise read from the 4-D noise
 * unit (simplex4 or classic4, the registry's bit-exact model), time its
 * fourth input. Per frame f and sample (all integers, exact but where said):
 *
 *   S_a     s48 Q15.32   the texture coordinate (np_gbuf_texcoord)
 *   u_a     u40 Q8.32    octave i's coordinate round(M_i S + o_i) mod 256
 *                        (the span units' front end, np_tex_octave_span)
 *   X_a     u16 Q8.8     round_half_up(u_a / 2^24) mod 2^16: the unit's x, y, z
 *   W       u16 Q8.8     the w register, (w0 + f dw) mod 2^16 (the scene's)
 *   n_i     sN Q(I).(N-I)  the noise unit's output for (X, W)  (simplex4: s16
 *                        classic4: s16 Q3.13 at their defaults)
 *   P_i     s(32+N)      a'_i n_i, exact (a'_i: s32 Q17.14, the folded amplitude)
 *   x       s49 Q16.32   q'(S) (exact, np_tex_quadric_exact) + sum_i P_i,
 *                        rounded once (np_tex_to_index) to the index format
 *                        I = 16, F = 32 (the texture units' s(W) QI.F)
 *   rgb     3 x u8       the colour stages C1 C2 C3 (np_tex_colour) with
 *                        Fw = 12 weight bits; lit by np_gbuf_light when the
 *                        scene's light.image is set
 *
 * The float reference of a sample: f = q(s) + sum_i a_i n_ref(X_i, W) in
 * double (s the double texture coordinate, n_ref the unit's float reference
 * at the same input words: the coordinate's Q8.8 sampling is the scene's
 * choice, not the unit's error), then the colour map in double.
 */
#ifndef NP_NOISETEX_H
#define NP_NOISETEX_H

#include <stddef.h>
#include <stdint.h>

#include "np_gbuf.h"
#include "np_scene.h"
#include "np_unit.h"

enum { NP_NOISETEX_IDX_INT = 16, NP_NOISETEX_IDX_FRAC = 32, NP_NOISETEX_W_FRAC = 12 };

typedef struct np_noisetex {
    const np_scene *sc;
    const np_unit *u;      /* the 4-D noise unit */
    np_unit_cfg cfg;       /* at its defaults */
    unsigned out_frac;     /* fraction bits of its output field */
    double bound_lsb;      /* its error bound, output LSB */
} np_noisetex;

/* One frame's figures. */
typedef struct np_noisetex_stats {
    uint64_t samples, transactions; /* covered samples; noise transactions (samples x octaves) */
    double max_lsb;        /* largest |unit - reference| of the texture's colour (before the light) over
                              covered samples and channels, colour LSB */
    uint64_t over_one;     /* channels over 1 LSB (the same) */
    double max_lit_lsb;    /* the same after the light (light.image; np_gbuf.h bounds what it adds) */
    uint64_t cycles;       /* the noise unit's cycle model over the frame's transactions, back to back */
    uint64_t cycle_mismatch; /* its outputs that differ from the bit-exact model's */
    uint16_t w;            /* the frame's w register */
} np_noisetex_stats;

/* For a scene with texture.noise: the unit, configured cfg (NULL: its defaults). 0, or -1 with err. */
int np_noisetex_init(np_noisetex *t, const np_scene *sc, const np_unit_cfg *cfg, char *err, size_t errlen);

/*
 * Frame f of g (built from t->sc at m = 1): the unit's image rgb (w * h * 3),
 * optionally the reference ref (w * h * 3 doubles, 0..255, unrounded) and the
 * first octave's noise output code0 (w * h, sign-extended; 0 where
 * uncovered), and the stats; cycles: 1 runs the unit's cycle model too.
 * 0, or -1 with err (no memory; a clamped map's index out of its range).
 */
int np_noisetex_frame(const np_noisetex *t, const np_gbuf *g, unsigned f, int cycles, uint8_t *rgb, double *ref,
                      int32_t *code0, np_noisetex_stats *st, char *err, size_t errlen);

/*
 * The largest change of the noise unit's output between two frames at one
 * input point, in output LSB, for the scene's dw: L dw 2^N + 2 e, L the
 * unit's Lipschitz bound along w (simplex4: A (n + 1) |G|max 27/343 =
 * 6 * 5 * sqrt 3 * 27/343 = 4.090 per lattice unit, docs/noise-nd.md), e its
 * error bound; a negative value when the unit has no such bound here.
 */
double np_noisetex_step_bound_lsb(const np_noisetex *t);

#endif /* NP_NOISETEX_H */
