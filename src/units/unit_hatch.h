/* SPDX-License-Identifier: MIT */
/* unit_hatch.h - what the unit hatch (src/units/unit_hatch.c) needs from a scene. */
#ifndef NP_UNIT_HATCH_H
#define NP_UNIT_HATCH_H

/*
 * A scene's "hatch" section (seed 003; docs/hatch.md, "Scenes"), in the
 * unit's own type (np_unit_scene.hatch; the scene reader fills it): the
 * scene hatched by the unit, tone from the lit texture, level of detail per
 * polygon.
 */
typedef struct np_hatch_scene {
    int present;                         /* the scene has a "hatch" section */
    unsigned set;                        /* "set": index into np_hatch_sets (default best16) */
    unsigned layers;                     /* "layers": 1..4 (default 4) */
    unsigned fade;                       /* "fade": "smooth" (0, default) or "onebyone" (1) */
    unsigned coverage;                   /* "mode": "brute" (0) or "coverage" (1, default) */
    unsigned lanes;                      /* "lanes": P, 1..16 (default 1) */
    double tile_pixels;                  /* "tile_pixels": 1/F, a seed tile's size on screen (default 64) */
} np_hatch_scene;

#endif /* NP_UNIT_HATCH_H */
