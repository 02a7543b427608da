/* SPDX-License-Identifier: MIT */
/*
 * np_scene.h - scenes for the reference renderer and the scanline texturing
 * units, read from JSON (the .json files in vectors/scenes, format in docs/render.md)
 * with cJSON. A malformed scene is refused with a message that names the
 * file, the field and what was expected.
 */
#ifndef NP_SCENE_H
#define NP_SCENE_H

#include <stddef.h>
#include <stdint.h>

#include "np_ref.h"
#include "np_unit.h"
#include "unit_aacount.h"
#include "unit_hatch.h"

/*
 * No cap on polygons: explicit polygons are a growing array, meshes are
 * stored as shared vertices and index triangles (np_scene_mesh). Polygon ids
 * (np_scene_poly_get) run over the explicit polygons, then each mesh's
 * triangles, below NP_SCENE_MAX_PRIMS (ids fit a u32 with room for the
 * G-buffer's "none").
 */
enum { NP_SCENE_MAX_VERTS = 8, NP_SCENE_MAX_SIZE = 4096, NP_SCENE_MAX_PRIMS = 1 << 24 };

/* A convex polygon: object-space vertices and their texture coordinates. */
typedef struct np_scene_poly {
    unsigned n;                          /* 3..8 vertices */
    double p[NP_SCENE_MAX_VERTS][3];
    double t[NP_SCENE_MAX_VERTS][3];
    int cull;                            /* drop it when it faces away from the camera */
} np_scene_poly;

typedef struct np_scene_camera {
    int perspective;                     /* 0: orthographic */
    double eye[3], target[3], up[3];
    double height;                       /* orthographic: world units across the image height */
    double focal;                        /* perspective: image-plane distance, in half image heights */
    /*
     * "depth_range": [near, far], the view depths the G-buffer's u24 depth
     * spans (np_gbuf.h); have_depth_range 0: the range of the drawn polygons.
     */
    int have_depth_range;
    double depth_range[2];
} np_scene_camera;

/*
 * A procedural mesh (geometry "sphere"): shared vertices with texture
 * coordinates, counter-clockwise triangles seen from outside. Its triangles
 * are polygons (np_scene_poly_get) with the ids first_id ...
 */
typedef struct np_scene_mesh {
    uint32_t n_vert, n_tri;
    double (*p)[3];                      /* n_vert positions */
    double (*t)[3];                      /* n_vert texture coordinates */
    uint32_t (*tri)[3];                  /* n_tri vertex triples */
    uint32_t first_id;
    int cull;
} np_scene_mesh;

/* "aa": the unit aacount's section, in the unit's own type (unit_aacount.h). */
typedef np_aacount_scene np_scene_aa;

/* "hatch": the unit hatch's section, in the unit's own type (unit_hatch.h). */
typedef np_hatch_scene np_scene_hatch;

/*
 * "texture.noise": the texture's octaves read a 4-D noise unit instead of
 * the span units' trilinear value noise, time its fourth axis (a
 * time-varying solid texture; docs/noise-nd.md, "A 4-D texture in a scene").
 * The w register of frame f is u16 Q8.8, (w0 + f dw) mod 2^16: w0 and dw
 * are lattice units, multiples of 1/256 in [0, 256) (exact in the register).
 */
typedef struct np_scene_noise {
    int present;                         /* the texture has a "noise" section */
    char unit[16];                       /* "unit": "simplex4" or "classic4" */
    uint16_t w0, dw;                     /* "w0", "dw": u16 Q8.8 registers */
    unsigned frames;                     /* "frames": 1..100 (default 8) */
} np_scene_noise;

typedef struct np_scene {
    char name[64];
    char path[512];
    unsigned width, height;
    double background[3];                /* 0..255 */
    np_scene_camera cam;
    unsigned n_poly;                     /* explicit polygons (cubes' faces, "polygon") */
    np_scene_poly *poly;
    unsigned n_mesh;
    np_scene_mesh *mesh;
    uint32_t n_prims;                    /* every polygon id: n_poly + the meshes' triangles */
    np_ref_texture tex;
    np_scene_noise noise;                /* tex's octaves through a 4-D noise unit (absent: value noise) */
    unsigned probe_row;                  /* scanline of the noise-difference plot */
    int allow_empty;                     /* "allow_empty": true: an image that covers no pixel is not an error */
    /*
     * Not from the file: set by a tool (render --sized, report gates --scene):
     * the span units' cfg_scene sizes their registers to the scene
     * (np_su_cfg_scene) instead of keeping the default widths.
     */
    int size_registers;
    /*
     * "light": one directional light for the shaded views (NAME_*_lit.png),
     * never for the units' outputs or the hashed images. light_dir is the unit
     * vector from a surface towards the light (world space); a view pixel is
     * colour * (ambient + (1 - ambient) max(0, n . light_dir)). Default, when
     * the scene has no "light": ambient 0.3 and the direction
     * -2 forward + up - right of the camera, normalised (from over the viewer's
     * left shoulder).
     */
    double light_dir[3];
    double ambient;
    /*
     * "light.image": true - the light also shades the rendered images (the
     * G-buffer renderer's shading, np_gbuf.h "Lighting", units and reference
     * alike, so hashed); false (default) - only the _lit views, as above.
     */
    int light_image;
    np_scene_aa aa;
    np_scene_hatch hatch;
} np_scene;

/*
 * Polygon id (0 .. n_prims - 1): an explicit polygon (returned in place) or a
 * mesh triangle (copied into tmp, returned). NULL past the last id.
 */
const np_scene_poly *np_scene_poly_get(const np_scene *s, uint32_t id, np_scene_poly *tmp);

/*
 * 0, or -1 with "FILE: field 'a.b[2]': expected ..." in err. A path
 * "embedded:NAME" reads the copy of vectors/scenes/NAME.json built into the
 * program (np_scenes_embedded), so the seed scenes need no files at run time.
 */
int np_scene_load(const char *path, np_scene *s, char *err, size_t errlen);

typedef struct np_scene_embedded {
    const char *name; /* "wood", "marble" */
    const char *json;
} np_scene_embedded;
extern const np_scene_embedded np_scenes_embedded[]; /* terminated by name == NULL */
/* The same from a JSON text; name is used in messages in place of the file. */
int np_scene_parse(const char *json, const char *name, np_scene *s, char *err, size_t errlen);
void np_scene_free(np_scene *s);

/*
 * The scene as the units see it (np_unit_scene, np_unit.h): its name, width,
 * texture and the box of its explicit polygons' texture coordinates, the 4-D
 * noise unit its texture reads, its "aa" and "hatch" sections when present.
 * us points into s, which must outlive it.
 */
void np_scene_for_units(const np_scene *s, np_unit_scene *us);
/* u->cfg_scene on scene s adapted by np_scene_for_units: 1, 0 or -1 as np_unit.cfg_scene; 0 without a hook. */
int np_scene_cfg_unit(const np_unit *u, void *cfg, const np_scene *s, char *err, size_t errlen);

#endif /* NP_SCENE_H */
