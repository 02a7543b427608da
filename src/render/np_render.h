/* SPDX-License-Identifier: MIT */
/*
 * np_render.h - the reference renderer and the texture units' renders.
 *
 * A scene (np_scene.h) is scan-converted into spans: for each scanline,
 * top to bottom, each visible convex polygon in scene order gives at most
 * one span, the pixels whose centres (x + 1/2, y + 1/2) lie in
 * [x_left, x_right) on that scanline. Texture coordinates are linear along
 * each polygon edge and along each span in screen space (the seed's
 * equations 13 and 14; no perspective correction), so along a span
 *   s(k) = s0 + k ds,  k = 0 .. n - 1.
 * Hidden surfaces: back-facing polygons are culled; overlapping front faces
 * are drawn in scene order (the last wins) - enough for convex objects.
 *
 * The float reference evaluates f and the colour map in double at
 * s0 + k ds. The units read each span's descriptor (np_span): s0 and ds
 * rounded to Q15.32 (|error| <= 2^-33 each). Their images are compared
 * with the reference over the covered pixels, per channel, in 8-bit LSB.
 */
#ifndef NP_RENDER_H
#define NP_RENDER_H

#include <stddef.h>
#include <stdint.h>

#include "np_fdiff.h"
#include "np_scene.h"
#include "np_texel.h"

typedef struct np_rspan {
    np_span hw;           /* what the units read */
    double s0[3], ds[3];  /* what the reference uses */
} np_rspan;

typedef struct np_render_frame {
    const np_scene *sc;
    np_tex_regs regs;     /* the scene's texture, quantized (np_texreg_compile) */
    np_rspan *spans;
    size_t n_spans;
    uint64_t pixels;
    uint32_t longest;     /* longest span */
    double *ref;          /* w * h * 3, 8-bit units, not rounded; background where uncovered */
    unsigned char *mask;  /* w * h: 1 where covered */
    double ref_seconds;
} np_render_frame;

typedef struct np_render_err {
    uint64_t samples;     /* covered pixels x 3 channels */
    double max_lsb, rms_lsb, mean_lsb, psnr_db; /* psnr: 20 log10(255 / rms); +inf (HUGE_VAL) when rms = 0 */
    uint64_t over_half, over_one;               /* samples with |error| > 0.5, > 1 LSB */
    unsigned max_x, max_y;                      /* where the largest error is */
} np_render_err;

typedef struct np_render_run {
    uint8_t *rgb;         /* w * h * 3 */
    double model_seconds; /* the bit-exact model, whole frame */
    int have_cycles;
    double cycle_seconds; /* the cycle-accurate model, whole frame */
    uint64_t cycles, setup_stalls, out_stalls;
    uint64_t span_setups, cell_setups, interval_setups;
    uint64_t cycle_mismatch; /* pixels where the cycle model differs from the bit-exact one */
    np_render_err err;
} np_render_run;

/* Scan-convert the scene and compile its texture. 0, or -1 with err. */
int np_render_prepare(const np_scene *sc, np_render_frame *fr, char *err, size_t errlen);
void np_render_frame_free(np_render_frame *fr);

/* The float reference image (fills fr->ref, fr->ref_seconds). 0, or -1 when out of memory. */
int np_render_reference(np_render_frame *fr);

/* The units' images: bit-exact model, then (if cycles) the cycle-accurate model. 0, or -1 (no memory). */
int np_render_fdiff(const np_render_frame *fr, const np_fdiff_cfg *cfg, int cycles, np_render_run *run);
int np_render_texel(const np_render_frame *fr, const np_texel_cfg *cfg, int cycles, np_render_run *run);
void np_render_run_free(np_render_run *run);

/* Error of an 8-bit image against the reference, over the covered pixels. */
void np_render_error(const np_render_frame *fr, const uint8_t *rgb, np_render_err *e);

/* The reference rounded to 8 bits (round half up), background included. */
void np_render_ref_rgb8(const np_render_frame *fr, uint8_t *rgb);

/* Write base.exr (FLOAT R, G, B = value / 255) and base.png. 0, or -1 with err. */
int np_render_write_rgb8(const char *base, unsigned w, unsigned h, const uint8_t *rgb, char *err, size_t errlen);
int np_render_write_ref(const char *base, const np_render_frame *fr, char *err, size_t errlen);
/*
 * Error images of rgb against the reference: base.exr (FLOAT R, G, B = the
 * signed error in LSB, 0 where uncovered) and base.png, a heat map of the
 * largest channel error: black 0, blue 0.5, green 1, yellow 1.5, red >= 2 LSB;
 * uncovered pixels dark grey.
 */
int np_render_write_error(const char *base, const np_render_frame *fr, const uint8_t *rgb, char *err,
                          size_t errlen);

/*
 * The noise along one scanline (the seed's figures 10 and 11): for every
 * pixel of the spans on row y, the forward-difference unit's noise
 * accumulators against the per-pixel unit's (exact weights, WT = 32, the
 * same F), i.e. the forward differences' drift alone:
 *   sum[i]  = (sum_o N_fd - sum_o N_px) / (2^F S)   in units of f
 *   last[i] = (N_fd - N_px) of the last octave / (2^F a'), in noise units (0..1)
 * and the pixels where a set-up happened (any octave; the last octave).
 * Samples are ordered by x. Arrays are malloc'd; free with np_render_scan_free.
 */
typedef struct np_render_scan {
    size_t n;
    double *x, *sum, *last, *ref_sum; /* ref_sum: the reference's sum a_i n_i, for scale */
    size_t n_edge_any, n_edge_last;
    double *edge_any, *edge_last;
} np_render_scan;

int np_render_scanline(const np_render_frame *fr, const np_fdiff_cfg *cfg, unsigned y, np_render_scan *s);
void np_render_scan_free(np_render_scan *s);

#endif /* NP_RENDER_H */
