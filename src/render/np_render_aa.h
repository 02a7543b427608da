/* SPDX-License-Identifier: MIT */
/*
 * np_render_aa.h - the adaptive supersampling pipeline of seed 001
 * (Hollaender, Boubekeur, Eisemann; docs/aacount.md): on the G-buffer of a
 * scene at m x m samples (np_gbuf.h),
 *   1. shade S: each pixel's sample of B_m index 0 (np_gbuf_shade_first);
 *   2. lumas of S, Y = (77R + 150G + 29B + 128) >> 8, border-clamped;
 *   3. the sample-count unit (aacount) per pixel on its window: s and mask;
 *      the 6 x 6 tile maximum when the configuration asks;
 *   4. shade the chosen samples other than S's on the span unit (texel);
 *   5. resolve with the unit's resolve.
 * The count is the registry's (np_unit.samples: count, registers, cycle
 * model; the first unit that has one, np_aa_unit): a configuration and its
 * registers are opaque np_unit_cfg blocks here, read and set by key
 * (np_aa_key, np_aa_key_set).
 * Against full m x m supersampling (every sample shaded and resolved) and
 * the 16 x 16 ground truth (np_gbuf_ground_truth), with each step's cycles.
 */
#ifndef NP_RENDER_AA_H
#define NP_RENDER_AA_H

#include <stddef.h>
#include <stdint.h>

#include "np_gbuf.h"
#include "np_render.h"
#include "np_unit.h"

/* The sample-count unit (the registry's first with np_unit.samples->count), or NULL. */
const np_unit *np_aa_unit(void);
/* Key name of configuration c of np_aa_unit() (0 when there is no such key); set one (no check). */
unsigned np_aa_key(const np_unit_cfg *c, const char *name);
void np_aa_key_set(np_unit_cfg *c, const char *name, unsigned v);

/* What does not change with the unit's constants: built once per scene and m. */
typedef struct np_aa_frame {
    const np_scene *sc;
    const np_unit *unit;           /* the sample-count unit (np_aa_unit) */
    const np_render_unit_cfg *tex; /* the span unit that shades (texel) */
    np_gbuf g;
    uint8_t *rgb_full;   /* every sample shaded, w h n 3 */
    uint8_t *img_full;   /* full m x m resolved, w h 3 */
    double *img_full_d;  /* the same as doubles (np_gbuf_mse's reference argument) */
    uint8_t *img_s;      /* S, w h 3 */
    uint8_t *luma;       /* Y of S, w h */
    uint8_t *covered;    /* 1 where the pixel has a covered sample, w h */
    np_gbuf_cost cost_full, cost_s;
    uint64_t resolve_full_cycles;
    const double *gt;    /* the ground truth (w h 3, 0..255), or NULL */
} np_aa_frame;

/* One adaptive run. */
typedef struct np_aa_result {
    np_unit_cfg cfg;           /* the count's configuration, at the frame's m */
    uint8_t *s, *sd, *sn, *ss; /* per pixel (w h) */
    uint8_t *img;              /* the adaptive image, w h 3 */
    uint64_t covered_pixels;
    uint64_t samples;          /* sum of s over covered pixels */
    uint64_t samples_d, samples_n, samples_s; /* the same for each metric's own count */
    double pct;                /* samples / (n covered pixels), % */
    double mse_full;           /* against full m x m (8-bit), [0, 1] scale, covered pixels */
    double mse_gt;             /* against the ground truth (NaN without one) */
    uint64_t unit_cycles;      /* the parallel pipe's (np_pipe run over every window) */
    uint64_t unit_cycles_serial; /* the serial model's schedule: n per window + latency */
    np_gbuf_cost shade_extra;  /* the chosen samples besides S's (when shaded) */
    uint64_t shade_cycles;     /* S's + the extra ones */
    uint64_t resolve_cycles;
    int pipe_mismatch;         /* the cycle model's s differed from the bit-exact model's */
} np_aa_result;

/*
 * The unit's keys for scene sc at m, from its "aa" section (np_scene_aa) and
 * the G-buffer's depth range (z_near, z_far); a constant the scene leaves out
 * turns its metric off. Host conversion (docs/aacount.md):
 *   c_d key = round(c_d (z_far - z_near)^2 2^48 / (2^24 - 1)^2)  (scene c_d per world^2),
 *   c_n key = round(4 c_n), c_s key = round(16 c_s) (saturated to the key's range),
 *   t_min key = ceil(255 t_min - 1e-9), t_edge key = round(256 t_edge).
 */
void np_aa_cfg_from_scene(const np_scene *sc, unsigned m, double z_near, double z_far, np_unit_cfg *c);

/*
 * Build the frame of sc at m on span unit tex: G-buffer, every sample
 * shaded, full m x m, S and its lumas. gt (the ground truth, may be NULL) is
 * kept by reference. 0, or -1 with err (also when no unit counts).
 */
int np_aa_frame_build(const np_scene *sc, unsigned m, const np_render_unit_cfg *tex, const double *gt,
                      np_aa_frame *f, char *err, size_t errlen);
void np_aa_frame_free(np_aa_frame *f);

/*
 * The unit's window of pixel (x, y): its n G-buffer samples (depth u24,
 * normal 3 x s8; uncovered: 2^24 - 1 and (0,0,0)) and the lumas of S at the
 * pixel, left, right, up, down, each neighbour clamped to the image.
 */
void np_aa_window(const np_aa_frame *f, unsigned x, unsigned y, np_unit_window *w);

/*
 * Run the unit with configuration c (regs: its register block, NULL: from c) on
 * every pixel. shade != 0: shade the chosen samples on the span unit (their
 * cycles); 0: take their colours from rgb_full (the same bits: a sample's
 * colour does not depend on which others are shaded) and leave the shading
 * cost 0 (for sweeps). 0, or -1 (no memory).
 */
int np_aa_run(const np_aa_frame *f, const np_unit_cfg *c, const np_unit_cfg *regs, int shade, np_aa_result *r);
void np_aa_result_free(np_aa_result *r);

/*
 * What a count that saw every sample's colour could do (not the unit: a
 * yardstick for the metrics): per covered pixel the s minimising its error
 * against full m x m plus lambda s, the first s samples of B_m resolved, over
 * lambda in {0} and 1e-7 .. 1 (400 steps); of the counts with at most
 * budget_spp samples per covered pixel the one with the least MSE against
 * the ground truth f->gt: that MSE ([0, 1] scale) and its samples per
 * covered pixel. 0, or -1 (no ground truth, no memory, no count within the
 * budget).
 */
int np_aa_colour_oracle(const np_aa_frame *f, double budget_spp, double *mse_gt, double *spp);

#endif /* NP_RENDER_AA_H */
