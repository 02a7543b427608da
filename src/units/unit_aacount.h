/* SPDX-License-Identifier: MIT */
/* unit_aacount.h - the unit aacount configured from a scene (src/units/unit_aacount.c). */
#ifndef NP_UNIT_AACOUNT_H
#define NP_UNIT_AACOUNT_H

#include "np_aacount.h"

struct np_scene;

/*
 * The unit's keys for scene sc at m (1..4) from its "aa" section
 * (np_scene_aa), from the unit's defaults: the metrics the scene enables
 * (a constant it leaves out turns its metric off), luma_taps, tile, and the
 * host conversion of the constants (docs/aacount.md):
 *   c_d key = round(c_d R^2 2^48 / (2^24 - 1)^2)  (scene c_d per world^2, R the
 *             G-buffer's depth range z_far - z_near),
 *   c_n key = round(4 c_n), c_s key = round(16 c_s) (saturated to the key's range),
 *   t_min key = ceil(255 t_min - 1e-9), t_edge key = round(256 t_edge).
 * The registry's cfg_scene hook (report gates --scene) calls it with R = 1:
 * the depth range moves the c_d register's value, never the datapath.
 */
void np_aacount_cfg_scene(const struct np_scene *sc, unsigned m, double depth_range, np_aacount_cfg *c);

#endif /* NP_UNIT_AACOUNT_H */
