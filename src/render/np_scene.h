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

#include "np_ref.h"

enum { NP_SCENE_MAX_VERTS = 8, NP_SCENE_MAX_POLYS = 4096, NP_SCENE_MAX_SIZE = 4096 };

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
} np_scene_camera;

typedef struct np_scene {
    char name[64];
    char path[512];
    unsigned width, height;
    double background[3];                /* 0..255 */
    np_scene_camera cam;
    unsigned n_poly;
    np_scene_poly *poly;
    np_ref_texture tex;
    unsigned probe_row;                  /* scanline of the noise-difference plot */
    int allow_empty;                     /* "allow_empty": true: an image that covers no pixel is not an error */
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
} np_scene;

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

#endif /* NP_SCENE_H */
