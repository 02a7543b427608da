/* SPDX-License-Identifier: MIT */
/*
 * render_view.h - internal to the renderer: the camera, the projection, back
 * faces and the scan conversion of one polygon row (render_raster.c), shared
 * by the span renderer (np_render.h) and the G-buffer renderer (np_gbuf.h).
 */
#ifndef RENDER_VIEW_H
#define RENDER_VIEW_H

#include "np_render.h"

typedef struct np_rview {
    double eye[3], f[3], r[3], u[3];
    double w, h;
    const np_scene_camera *cam;
} np_rview;

static inline double np_rdot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

void np_rview_init(const np_scene *sc, np_rview *v);
/* Screen position (x right, y down, pixel centres at +1/2) of P; -1 when P is not in front of the eye. */
int np_rview_project(const np_rview *v, const double P[3], double *sx, double *sy);
/* View depth of P: its distance along the viewing direction from the eye. */
double np_rview_depth(const np_rview *v, const double P[3]);
/* Newell normal of p (not normalised). */
void np_rpoly_normal(const np_scene_poly *p, double n[3]);
/* Does the polygon face the camera? (Newell normal; counter-clockwise seen from the front.) */
int np_rview_facing(const np_rview *v, const np_scene_poly *p);

typedef struct np_rproj {
    unsigned n;
    double x[NP_SCENE_MAX_VERTS], y[NP_SCENE_MAX_VERTS];
    const np_scene_poly *p;
    unsigned id;
    double ymin, ymax, xmin, xmax;
} np_rproj;

/* Project polygon p (id) into q; -1 when a vertex is not in front of the eye. */
int np_rproj_init(const np_rview *v, const np_scene_poly *p, unsigned id, np_rproj *q);

/*
 * The span of projected polygon pp on pixel row j with the sample point at
 * (ox, oy) inside the pixel (1/2, 1/2: the centre): the pixels i with
 * x_left <= i + ox < x_right on the line y = j + oy, edges half-open in y;
 * out->s0 is the texture coordinate at pixel x0's sample point, ds the step
 * per pixel. 1 when it has pixels, 0 when none, -1 on a range error (err).
 */
int np_rrow_span(const np_scene *sc, const np_rproj *pp, unsigned j, double ox, double oy, np_rspan *out, char *err,
                 size_t errlen);

#endif /* RENDER_VIEW_H */
