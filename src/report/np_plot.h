/* SPDX-License-Identifier: MIT */
/*
 * np_plot.h - small, dependency-free SVG plots (scatter and polylines with
 * axes, ticks, labels and reference lines). Text output: deterministic, so
 * the copies in docs/ can be checked for freshness byte for byte.
 */
#ifndef NP_PLOT_H
#define NP_PLOT_H

#include <stddef.h>
#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct np_plot_series {
    const char *label;
    const char *color;  /* SVG colour */
    const double *x, *y;
    size_t n;
    int line;           /* 1: join the points in order; 0: markers only */
    int markers;
} np_plot_series;

typedef struct np_plot {
    const char *title, *xlabel, *ylabel;
    double xmin, xmax, ymin, ymax; /* equal min and max: fit the data */
    int ylog;                      /* logarithmic y axis (ymin > 0) */
    double vline, hline;           /* reference lines; NAN for none */
    const char *vlabel, *hlabel;
} np_plot;

/* Write an SVG document of 720 x 480 to f. */
void np_plot_svg(FILE *f, const np_plot *p, const np_plot_series *s, size_t ns);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* NP_PLOT_H */
