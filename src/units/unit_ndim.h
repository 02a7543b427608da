/* SPDX-License-Identifier: MIT */
/* What the n-D noise units (unit_simplexn.c, unit_classicn.c) share. */
#ifndef UNIT_NDIM_H
#define UNIT_NDIM_H

#include <stddef.h>
#include <stdint.h>

#include "np_unit.h"

/* Input field names of axis 0..4: x, y, z, w, v. */
extern const char *const np_ndim_axis_names[5];

/*
 * The hand-annotated boundary inputs of an n-input noise unit (the classes
 * are annotated in unit_simplexn.c): writes up to max rows of n words,
 * returns the full count.
 */
size_t np_ndim_boundary(unsigned n, uint64_t (*in)[NP_UNIT_MAX_FIELDS], size_t max);

/*
 * cfg_scene of an n-D unit called name (u: the unit, for its defaults): 1
 * with cfg at the defaults when scene sc's texture reads this unit
 * (np_unit_scene.noise_unit: a 4-D texture in a scene), else 0. So the
 * scene's gate report (`report gates --scene`) names the noise unit it uses.
 */
int np_ndim_cfg_scene(const np_unit *u, void *cfg, const np_unit_scene *sc);

/* The n-D simplex datapath at n = 3 as a unit, not registered (unit_simplexn.c): the dims report's 3-D row. */
extern const np_unit np_unit_simplexn3;

#endif /* UNIT_NDIM_H */
