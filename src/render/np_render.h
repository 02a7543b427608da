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
 * Hidden surfaces: back-facing polygons are culled, the rest depth-tested
 * per pixel: the frame is the G-buffer at m = 1 (np_gbuf.h) and its spans are
 * the visible runs of the G-buffer's sub-spans, ordered by row, polygon id,
 * x (on convex objects: every polygon's whole row span, as before).
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

#include "np_scene.h"
#include "np_unit.h"
#include "np_unit_span.h"

typedef struct np_rspan {
    np_span hw;           /* what the units read */
    double s0[3], ds[3];  /* what the reference uses */
    unsigned poly;        /* the scene polygon id (np_scene_poly_get): its normal shades the views */
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
    uint64_t over_cr;                           /* samples that differ from the correctly rounded reference */
    unsigned max_cr;                            /* the largest such difference, LSB */
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

/*
 * A span unit's image of the frame: its engine's bit-exact model
 * (np_span_run), then (if cycles) its cycle-accurate model (np_span_sim),
 * from the frame's span descriptors and registers; every span engine alike.
 * 0, or -1 (no memory, or u has no span engine).
 */
int np_render_engine(const np_render_frame *fr, const np_span_engine *e, const void *ecfg, int cycles,
                     np_render_run *run);
/* The same for registry unit u with configuration block cfg (np_unit.span). */
int np_render_unit(const np_render_frame *fr, const np_unit *u, const void *cfg, int cycles, np_render_run *run);

/* A unit that renders a scene, configured for it. */
typedef struct np_render_unit_cfg {
    const np_unit *u;
    np_unit_cfg cfg;   /* what the unit renders with */
    np_unit_cfg scene; /* as the scene configured it (cfg_scene) */
    char spec[512];    /* the keys given over the defaults ("key=value,...") */
    char text[256];    /* cfg without the scene's keys, "key=value,key=value" (golden hash lists) */
} np_render_unit_cfg;

enum { NP_RENDER_MAX_UNITS = 8 };

/*
 * The units that render scene sc: every registry unit with a span engine
 * (np_unit.span) whose cfg_scene accepts sc, in registry order, configured
 * by spec(ctx, u) ("key=value,...", NULL for none) over the defaults and
 * by cfg_scene for the keys the scene sets (NP_UNIT_KEY_SCENE: the
 * texture; with sc->size_registers also the index and guard bits it sized,
 * unless spec gives them). Writes up to NP_RENDER_MAX_UNITS into us; the count, or -1 with err.
 */
int np_render_units(const np_scene *sc, const char *(*spec)(const void *ctx, const np_unit *u), const void *ctx,
                    np_render_unit_cfg *us, char *err, size_t errlen);
/* Configure c again from its spec and more ("key=value,..."; more's keys win over the spec's). 0, or -1. */
int np_render_unit_reconfigure(np_render_unit_cfg *c, const char *more, char *err, size_t errlen);
void np_render_run_free(np_render_run *run);

/* Error of an 8-bit image against the reference, over the covered pixels. */
void np_render_error(const np_render_frame *fr, const uint8_t *rgb, np_render_err *e);

/*
 * The reference correctly rounded to 8 bits: round half up, as the units'
 * colour stage rounds (np_tex_colour_round), background included.
 */
void np_render_ref_rgb8(const np_render_frame *fr, uint8_t *rgb);

/*
 * Colour images: base.exr, FLOAT R, G, B in linear light (the sRGB EOTF of
 * value / 255) with the chromaticities attribute (Rec. 709 primaries, D65
 * white) and string attributes noisepipe:values, :unit, :scene; base.png,
 * the 8-bit image as computed (the unit's output; the reference rounded
 * half up), with tEXt noisepipe:unit and :scene; and base_lit.png, the same
 * shaded for viewing (np_render_shade). 0, or -1 with err.
 */
int np_render_write_rgb8(const char *base, const np_render_frame *fr, const char *unit, const uint8_t *rgb,
                         char *err, size_t errlen);
/* The same for the reference (EXR: the unrounded value; unit "ref"). */
int np_render_write_ref(const char *base, const np_render_frame *fr, char *err, size_t errlen);

/*
 * A view of rgb (w * h * 3, the frame's) shaded with the scene's light
 * (np_scene.light_dir, ambient): each covered pixel's colour times
 * ambient + (1 - ambient) max(0, n . light), n the normal of its polygon
 * turned towards the camera, rounded half up; background unchanged. For
 * looking at only: never hashed, never compared. A scene whose light shades
 * the image itself (light.image, np_gbuf.h) gets the image unchanged. 0, or
 * -1 (out of memory).
 */
int np_render_shade(const np_render_frame *fr, const uint8_t *rgb, uint8_t *out);

/* The heat map of the error images: black 0, blue 0.5, green 1, yellow 1.5, red >= 2 LSB (linear between). */
#define NP_RENDER_HEAT_MAX 2.0
void np_render_heat(double lsb, uint8_t rgb[3]);

/*
 * The colour bar under every error PNG: a strip of `height` rows added below
 * the w x h image (none when w < NP_RENDER_LEGEND_MIN_WIDTH). Rows [y0, y1)
 * of the strip hold the heat map, column x0 = 0 LSB (black) to column x1 =
 * NP_RENDER_HEAT_MAX LSB (red), linear between; under it a tick every
 * 0.5 LSB and the labels 0, 0.5, 1, 1.5, 2 LSB (a 3 x 5 pixel font,
 * `scale` pixels per font pixel) where they fit.
 */
enum { NP_RENDER_LEGEND_MIN_WIDTH = 32 };
typedef struct np_render_legend {
    unsigned height, scale, x0, x1, y0, y1;
} np_render_legend;
void np_render_legend_layout(unsigned w, np_render_legend *l);

/*
 * Error images of unit's rgb against the reference: base.exr (FLOAT R, G,
 * B = the signed error in LSB, 0 where uncovered; data, not colour: no
 * chromaticities, noisepipe:values says what they are) and base.png, the
 * heat map of the largest channel |error| (uncovered pixels dark grey) with
 * the colour bar below it and tEXt noisepipe:scale, :error, :unit, :scene.
 * rounded = 0: against the unrounded reference (8-bit rounding alone is up to
 * 1/2 LSB); rounded = 1: against the reference correctly rounded to 8 bits
 * (np_render_ref_rgb8), i.e. the error beyond correct rounding, 0 where the
 * unit returns the correctly rounded value.
 */
int np_render_write_error(const char *base, const np_render_frame *fr, const char *unit, const uint8_t *rgb,
                          int rounded, char *err, size_t errlen);

#endif /* NP_RENDER_H */
