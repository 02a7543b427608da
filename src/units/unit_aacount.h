/* SPDX-License-Identifier: MIT */
/* unit_aacount.h - the unit aacount configured from a scene (src/units/unit_aacount.c). */
#ifndef NP_UNIT_AACOUNT_H
#define NP_UNIT_AACOUNT_H

struct np_aacount_cfg;

/*
 * What the unit needs from a scene: its "aa" section (the adaptive
 * supersampling of seed 001, design/scene-pipeline.md, Seed 001), in the
 * unit's own type (np_unit_scene.aa; the scene reader fills it). A metric
 * whose constant the scene leaves out is off (left out of the unit's model,
 * vectors and gates).
 */
typedef struct np_aacount_scene {
    int present;                         /* the scene has an "aa" section */
    unsigned m;                          /* "m": 1..4 samples per pixel side (default 3) */
    int have_cd, have_cn, have_cs;       /* which metrics the scene enables */
    double c_d, c_n, c_s;                /* "c_d", "c_n", "c_s" >= 0: the metrics' constants */
    double t_min, t_edge;                /* "t_min" (default 16/255), "t_edge" (default 1/8), 0..1 */
    unsigned luma_taps;                  /* "luma_taps": 4 (default) or 5 (the centre too, as FXAA) */
    unsigned tile;                       /* "tile": 0 (default, off) or 6: the 6x6 tile maximum (Fig. 6c) */
} np_aacount_scene;

/*
 * The unit's keys for a scene's "aa" section a at m (1..4), from the unit's
 * defaults: the metrics the scene enables
 * (a constant it leaves out turns its metric off), luma_taps, tile, and the
 * host conversion of the constants (docs/aacount.md):
 *   c_d key = round(c_d R^2 2^48 / (2^24 - 1)^2)  (scene c_d per world^2, R the
 *             G-buffer's depth range z_far - z_near),
 *   c_n key = round(4 c_n), c_s key = round(16 c_s) (saturated to the key's range),
 *   t_min key = ceil(255 t_min - 1e-9), t_edge key = round(256 t_edge).
 * The registry's cfg_scene hook (report gates --scene) calls it with R = 1:
 * the depth range moves the c_d register's value, never the datapath.
 */
void np_aacount_cfg_scene(const np_aacount_scene *a, unsigned m, double depth_range, struct np_aacount_cfg *c);

#endif /* NP_UNIT_AACOUNT_H */
