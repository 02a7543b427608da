/* SPDX-License-Identifier: MIT */
/*
 * np_gbuf.h - the G-buffer renderer: a scene scan-converted at m x m samples
 * per pixel (m = 1..4, an ordered grid), texturing deferred to shading time
 * on a registry span unit, the resolve, and the float references
 * (seed 001, Hollander, Boubekeur, Eisemann; design/scene-pipeline.md).
 *
 * --- Samples ---
 * Sample (a, b) of pixel (x, y), a the column and b the row inside the
 * pixel, 0 <= a, b < m, lies at the screen point
 *     (x + (a + 1/2)/m, y + (b + 1/2)/m)     (x right, y down)
 * Its index inside the pixel is j = b m + a (row-major, the order of the
 * paper's index matrices B_m[b][a]); all per-sample arrays are pixel-major:
 *     sample i = (y w + x) n + j,   n = m^2.
 * A sample mask (u16) has bit j for sample j. For m = 1 and for m = 3, a = b
 * = 1, the sample is the pixel centre (x + 1/2, y + 1/2): the point the 1x1
 * renderer (np_render.h) samples, with the same span descriptors, so the
 * same bits.
 *
 * --- Scan conversion ---
 * For each sample offset (a, b) the scene is scan-converted exactly as the
 * 1x1 renderer does it with the pixel centre moved from (1/2, 1/2) to
 * ((a + 1/2)/m, (b + 1/2)/m): per polygon and pixel row, the pixels whose
 * sample point satisfies x_left <= x + (a + 1/2)/m < x_right on the line
 * y + (b + 1/2)/m, polygon edges half-open in y (a shared vertex or edge
 * counts once: no sample is covered twice by the faces of a closed mesh,
 * none is missed). Each such run is a sub-span (np_gbuf_span): a span
 * descriptor (np_span) whose pixel k is sample (a, b) of pixel x0 + k, with
 * pixel spacing 1. Only pixel rows in the polygon's bounding box are
 * visited (per-polygon bounding-box rasterisation).
 * Hidden surfaces: per sample, the depth test d_new <= d_old on the u24
 * depth below (ties: the later polygon in scene order wins, as the 1x1
 * renderer's "last wins"); back faces culled as there.
 *
 * --- Per-sample fields (the G-buffer) ---
 *   depth   u24   linear view depth z (distance along the viewing direction,
 *                 the exact plane intersection, also under perspective),
 *                 quantised over the scene's depth range [z_near, z_far]:
 *                   d = clamp(round_half_up((z - z_near) / (z_far - z_near)
 *                                           * (2^24 - 1)), 0, 2^24 - 1)
 *                 PIN: the range is camera.depth_range when the scene sets
 *                 it, else [min, max] of z over the vertices of every
 *                 polygon drawn (front-facing or not culled); a zero range
 *                 gives d = 0. Uncovered samples: NP_GBUF_DEPTH_FAR
 *                 (2^24 - 1, the far clear value).
 *   normal  3 x s8 Q0.7  the polygon's unit normal n (Newell, world space)
 *                 turned towards the camera, each component coded
 *                 round_half_up(127 n_i), |code| <= 127 (PIN: the design's
 *                 s8 Q0.7 word; coding 127 n rather than 128 n keeps 1.0
 *                 exact - the GPU's SNORM8 - so the word read as Q0.7 is
 *                 (127/128) n: one common scale, which the cone test of
 *                 aacount does not see (it is scale-free) and the light
 *                 register absorbs); uncovered: (0, 0, 0). Decoded: code / 127.
 *   poly    u32   the scene polygon id (np_scene_poly_get); the hardware
 *                 G-buffer channel is its low 8 bits (PIN: polygon id u8);
 *                 uncovered: NP_GBUF_NONE.
 *   span, k       the sub-span (index into spans) and the pixel of it:
 *                 the sample's texture coordinate is, exactly,
 *   texcoord 3 x s48 Q15.32  s = sp.s + k sp.ds  (np_gbuf_texcoord), the
 *                 value the span units' front end reaches at pixel k; the
 *                 reference's is s0 + k ds in double (np_gbuf_texcoord_f).
 *   uv      2 x s48 Q15.32  the two texture coordinates that vary on the
 *                 face: the sub-span's axes uv[0] < uv[1], PIN: the
 *                 polygon's texture axis with the smallest range over its
 *                 vertices is dropped (ties: the highest axis), so a cube
 *                 face keeps the two that are not constant.
 *   coverage      a sample is covered iff poly != NP_GBUF_NONE; per pixel,
 *                 cover[p] = the number of covered samples (0..n).
 *
 * --- Deferred shading (np_gbuf_shade) ---
 * Sample i's colour is what the span unit gives pixel k of its sub-span's
 * descriptor: the unit's transaction (descriptor, k), as in its vectors,
 * bit for bit; uncovered samples get the background (no unit work). With
 * the scene's light applied (np_scene.light_image), the colour is lit by
 * np_gbuf_light.
 * The shaded samples of one sub-span that are consecutive form a run; each
 * run is one descriptor transaction. Cycles: the engine's cycle-accurate
 * sequencer (np_span_sim, np_span.h "Timing": its descriptor buffer and
 * set-up overlap included) fed the runs back to back with no gaps and no
 * backpressure, so for whole sub-spans the count is exactly the cycle
 * model's (gbuf.shade_cycles checks it). A run that starts at k0 > 0:
 *   - an engine with a seek (texel) places pixel k0 directly: u0 + k0 du and
 *     s + k0 ds, one more dependency level of the set-up engine after du:
 *     the run is timed as a span of its own k1 - k0 pixels, plus
 *     seek = the unit's np_unit_span.seek_cycles (texel: (octaves + 1)
 *     (ceil(3 / P) + Lm - 1) clocks, P, Lm its setup_mults, mult_lat), added
 *     serially (not hidden behind the previous run: an upper bound); 0 for a
 *     unit that declares none;
 *   - an engine without (fdiff: forward differences cannot skip) steps
 *     from k = 0: the run is timed as the span's first k1 pixels, so the
 *     k0 skipped pixels cost a clock each (and any cell set-ups they need),
 *     counted in skipped.
 *
 * --- Resolve (np_gbuf_resolve) ---
 * A pixel's colour from its s shaded samples (1 <= s <= 16), per channel:
 *   S   u12       sum of the s u8 colours (<= 255 s <= 4080)
 *   R   u18       np_aacount_rom(s) = ceil(2^17 / s) (the reciprocal ROM)
 *   out u8        (S R + 2^16) >> 17
 * which equals round_half_up(S / s) for every s in 1..16 and S in
 * 0..255 s (gbuf.resolve_exhaustive, aacount.resolve_exhaustive). The
 * renderer calls the unit's resolve (np_gbuf.samples): one definition.
 *
 * --- Lighting (np_gbuf_light; scene key light.image, PIN) ---
 * Only when the scene's "light" section has "image": true (default false:
 * the light shades only the _lit views, and every existing image and hash
 * is unchanged). With the G-buffer normal code n (3 x s8, above), the light
 * register l (3 x s17 Q1.15: round_half_up(2^15 (128/127) l_i), l the unit
 * direction towards the light, so that n . l / 2^22 = (n/127) . l) and the
 * ambient register a (u17 Q1.16, round_half_up(2^16 ambient)):
 *   dot  s25 Q0.22   n . l, exact (|dot| < 3 * 127 * 33026 < 2^24)
 *   lam  u17 Q1.16   clamp(dot, 0, 2^22) >> 6, rounded half up (|err| <= 2^-17)
 *   L    u17 Q1.16   (a 2^16 + (2^16 - a) lam + 2^15) >> 16   (<= 1.0, |err| <= 2^-16)
 *   c'   u8          (c L + 2^15) >> 16 per channel, rounded half up
 * The float references light a sample with the decoded G-buffer normal
 * n_d = code / 127 (what the unit sees) and the exact light and ambient:
 * c_ref (ambient + (1 - ambient) max(0, n_d . l)); the 16x16 ground truth
 * with the exact normal. Bound against the former: L is within 2^-16 of its
 * formula on the registers (lam's and L's roundings), the registers move it
 * by at most 2^-17 (a) + sqrt(3) 2^-16 (l, |n_d|_1 <= sqrt 3), so
 * |L - L_ref| <= 3.3 2^-16; then |c' - c_ref L_ref| <= 1/2 (rounding) +
 * e_c (the unlit colour's error, times L <= 1) + 255 * 3.3 2^-16 (0.013):
 * 0.513 + e_c LSB, 1.024 LSB for the units' e_c <= 0.511; measured 0.947 on
 * boxes.json (gbuf.light). The normal's coding (|n_d - n|_i <= 1/254) moves
 * n . l by at most sqrt(3)/254, i.e. 1.74 (1 - ambient) LSB against the
 * exact normal.
 */
#ifndef NP_GBUF_H
#define NP_GBUF_H

#include <stddef.h>
#include <stdint.h>

#include "np_render.h"
#include "np_scene.h"
#include "np_unit.h"
#include "np_unit_span.h"

enum {
    NP_GBUF_M_MAX = 4,
    NP_GBUF_N_MAX = NP_GBUF_M_MAX * NP_GBUF_M_MAX,
    NP_GBUF_DEPTH_BITS = 24,
    NP_GBUF_DEPTH_FAR = (1 << NP_GBUF_DEPTH_BITS) - 1,
    NP_GBUF_NORMAL_FRAC = 7,  /* s8 Q0.7 */
    NP_GBUF_NORMAL_ONE = 127, /* the normal code of 1.0 */
    NP_GBUF_LIGHT_FRAC = 15,  /* light register s17 Q1.15 */
    NP_GBUF_L_FRAC = 16       /* ambient, lam, L: Q1.16 */
};
#define NP_GBUF_NONE UINT32_MAX

/*
 * The paper's index matrices (Figure 3) and the resolve's reciprocal ROM have
 * one definition, the unit's: the G-buffer takes them through the registry
 * (np_unit.samples of the first unit that has one, aacount's: np_gbuf.samples),
 * mask(m, s) the first-s mask (bit j = b m + a set iff B_m[b][a] < s; s >= n
 * gives all n), resolve(sum, s) the resolve (rtl_model/np_aacount.h:
 * np_aacount_mask, np_aacount_resolve, np_aacount_bayer(m, a, b) = B_m[b][a]).
 */

/* A sub-span: sample (a, b) of pixels x0 .. x0 + n - 1 on pixel row y of one polygon. */
typedef struct np_gbuf_span {
    np_rspan r;           /* r.hw: the descriptor (y, x0, n: pixels); r.s0, r.ds: the reference's doubles; r.poly */
    uint8_t a, b;         /* the sample offset in the pixel */
    uint8_t uv[2];        /* the texture axes that vary on the face (PIN above) */
    /*
     * The texture coordinate's change per pixel down the screen (r.ds is per
     * pixel right): the polygon's screen-space gradient, from the affine map
     * through its largest-area vertex triangle - exact for a triangle and for
     * any polygon under an orthographic camera; under perspective, where the
     * seed's edge interpolation is not one affine map on a polygon of more than
     * three vertices, an estimate. With r.ds it is the Jacobian a level of
     * detail (hatching) or an anisotropic filter reads.
     */
    double dsdy[3];
} np_gbuf_span;

typedef struct np_gbuf {
    const np_scene *sc;
    unsigned m, n;        /* n = m * m samples per pixel */
    unsigned w, h;
    np_tex_regs regs;     /* the scene's texture, quantised (np_texreg_compile) */
    double z_near, z_far; /* the depth range (PIN above) */
    np_gbuf_span *spans;  /* every sub-span drawn, by polygon, then sample offset, then row */
    size_t n_spans;
    /* Per sample, w * h * n (index above). */
    uint32_t *depth;      /* u24 */
    int8_t (*normal)[3];  /* s8 Q0.7 */
    uint32_t *poly;       /* NP_GBUF_NONE where uncovered */
    uint32_t *span;       /* the sub-span; NP_GBUF_NONE where uncovered */
    uint16_t *k;          /* the pixel of the sub-span */
    uint8_t *hits;        /* sub-spans (front faces drawn) containing the sample, saturating at 255: coverage
                             checks (a closed mesh: 1 inside its outline, 0 outside) */
    /* Per pixel, w * h. */
    uint8_t *cover;       /* covered samples, 0..n */
    uint64_t covered_pixels;  /* pixels with cover > 0 */
    uint64_t covered_samples;
    uint64_t polys_drawn;     /* polygons not culled */
    double raster_seconds;
    const np_unit_samples *samples; /* the sample order and resolve: the registry's (np_unit.samples) */
} np_gbuf;

/*
 * Scan-convert scene sc at m x m samples per pixel (1 <= m <= 4). 0, or -1
 * with err (texture out of the units' range, a polygon behind the camera,
 * out of memory, m out of range).
 */
int np_gbuf_build(const np_scene *sc, unsigned m, np_gbuf *g, char *err, size_t errlen);
void np_gbuf_free(np_gbuf *g);

static inline size_t np_gbuf_index(const np_gbuf *g, unsigned x, unsigned y, unsigned a, unsigned b)
{
    return ((size_t)y * g->w + x) * g->n + (size_t)b * g->m + a;
}
/* The sample's screen position (x + (a + 1/2)/m, y + (b + 1/2)/m). */
void np_gbuf_position(const np_gbuf *g, size_t i, double *sx, double *sy);
/* Texture coordinate of covered sample i: s48 Q15.32, exact (span units' bits), and the reference's double. */
void np_gbuf_texcoord(const np_gbuf *g, size_t i, int64_t s[3]);
void np_gbuf_texcoord_f(const np_gbuf *g, size_t i, double s[3]);
/* UV of covered sample i: the two varying texture coordinates (s48 Q15.32; double). */
void np_gbuf_uv(const np_gbuf *g, size_t i, int64_t uv[2]);
void np_gbuf_uv_f(const np_gbuf *g, size_t i, double uv[2]);
/* Linear view depth of a u24 depth code (the centre of its quantisation step). */
double np_gbuf_depth_f(const np_gbuf *g, uint32_t d);

/* What shading a set of samples cost (cost model above). */
typedef struct np_gbuf_cost {
    uint64_t samples;     /* covered samples shaded */
    uint64_t runs;        /* descriptor transactions */
    uint64_t setup;       /* set-up stall clocks (seeks and a sequential engine's set-ups while skipping included) */
    uint64_t seek;        /* of which seeks */
    uint64_t skipped;     /* pixels a sequential engine stepped over to reach a run's start (a clock each) */
    uint64_t cycles;      /* the total */
} np_gbuf_cost;

/*
 * Shade samples of g on registry span unit u (u->span != NULL) with
 * configuration cfg (np_render_units' cfg): the samples of pixel p whose bit
 * is set in mask[p] (w * h masks; NULL: every sample). rgb: w * h * n * 3,
 * per sample (index above); samples not in the mask are left untouched;
 * uncovered samples in the mask get the background. Lit when the scene asks
 * (light_image). cost may be NULL. 0, or -1 (no memory, no span engine).
 */
int np_gbuf_shade(const np_gbuf *g, const np_unit *u, const void *cfg, const uint16_t *mask, uint8_t *rgb,
                  np_gbuf_cost *cost);

/*
 * The S buffer (the paper's one sample per pixel): each pixel's sample with
 * B index 0 (samples->mask(m, 1)) shaded, into rgb1 (w * h * 3, one
 * pixel each; background where that sample is uncovered). For m = 3 and
 * m = 1 this is the 1x1 renderer's image of the unit, bit for bit.
 */
int np_gbuf_shade_first(const np_gbuf *g, const np_unit *u, const void *cfg, uint8_t *rgb1, np_gbuf_cost *cost);

/*
 * Resolve: each pixel the mean (samples->resolve) of its samples in mask[p]
 * (NULL: all n), from per-sample rgb (np_gbuf_shade), into out (w * h * 3).
 * A pixel with an empty mask gets the background.
 */
void np_gbuf_resolve(const np_gbuf *g, const uint16_t *mask, const uint8_t *rgb, uint8_t *out);

/*
 * The lit colour (formats above) of u8 colour c at normal n (s8 Q0.7) under
 * the scene's light: np_gbuf_light_setup once, then np_gbuf_light per sample.
 */
typedef struct np_gbuf_lightq {
    int on;               /* the scene's light.image */
    int32_t l[3];         /* s17 Q1.15, 2^15 (128/127) l */
    uint32_t a;           /* u17 Q1.16 */
} np_gbuf_lightq;
void np_gbuf_light_setup(const np_scene *sc, np_gbuf_lightq *q);
uint32_t np_gbuf_light_factor(const np_gbuf_lightq *q, const int8_t n[3]); /* L, u17 Q1.16 */
void np_gbuf_light(const np_gbuf_lightq *q, const int8_t n[3], uint8_t rgb[3]);

/*
 * Polygon id's unit normal turned towards the camera (world space, double)
 * and its G-buffer code (round_half_up(127 n_i)); nq may be NULL.
 */
void np_gbuf_poly_normal(const np_scene *sc, uint32_t id, double n[3], int8_t nq[3]);
/* A normal code decoded: code / 127. */
void np_gbuf_normal_decode(const int8_t nq[3], double n[3]);
/* The reference's light factor at normal n: ambient + (1 - ambient) max(0, n . l); 1 without light.image. */
double np_gbuf_light_ref(const np_scene *sc, const double n[3]);

/* --- Float references (double) --- */

/*
 * Per sample, the reference colour (0..255, unrounded; lit in double when
 * the scene asks; background where uncovered) of every sample of g: out is
 * w * h * n * 3. 0, or -1 (no memory).
 */
int np_gbuf_reference_samples(const np_gbuf *g, double *out);
/* Full m x m supersampling in double: each pixel the mean of its n reference samples, w * h * 3. */
int np_gbuf_reference_ssaa(const np_gbuf *g, double *out);
/*
 * The ground truth: the scene at q x q samples per pixel (q = 16: 256 per
 * pixel, the 16x16), every sample in double (the reference's
 * texture at the double texture coordinate, exact-plane depth test),
 * averaged: w * h * 3, 0..255. Built row by row (memory O(w q^2)). 0, or -1 with err.
 */
int np_gbuf_ground_truth(const np_scene *sc, unsigned q, double *out, char *err, size_t errlen);

/* --- Error measures for the reports --- */

/*
 * Mean squared error of image a (8-bit) against b (double, 0..255), on the
 * [0, 1] scale ((a - b) / 255 squared), over the pixels where mask is set
 * (NULL: all), all three channels.
 */
double np_gbuf_mse(const uint8_t *a, const double *b, const uint8_t *mask, size_t pixels);
double np_gbuf_mse_f(const double *a, const double *b, const uint8_t *mask, size_t pixels);
/* The paper's PSNR as printed: 10 log10(255^2 / MSE), MSE on [0, 1]; HUGE_VAL for MSE 0. */
double np_gbuf_psnr_paper(double mse);
/* The consistent PSNR: 10 log10(1 / MSE), MSE on [0, 1] (peak 1 on the same scale). */
double np_gbuf_psnr(double mse);

#endif /* NP_GBUF_H */
