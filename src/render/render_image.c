/* SPDX-License-Identifier: MIT */
/* Image files of a render: the units' images, the reference, error heat maps (np_render.h). */
#include "np_render.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "np_image.h"

/* --- Image files --- */

static int write_float_rgb(const char *base, unsigned w, unsigned h, const float *planes, char *err, size_t errlen)
{
    static const char *const names[3] = { "R", "G", "B" };
    char path[4096];
    snprintf(path, sizeof path, "%s.exr", base);
    return np_image_write_exr(path, w, h, 3, names, planes, err, errlen);
}

static int write_png(const char *base, unsigned w, unsigned h, const uint8_t *rgb, char *err, size_t errlen)
{
    char path[4096];
    snprintf(path, sizeof path, "%s.png", base);
    return np_image_write_png(path, w, h, rgb, err, errlen);
}

int np_render_write_rgb8(const char *base, unsigned w, unsigned h, const uint8_t *rgb, char *err, size_t errlen)
{
    size_t n = (size_t)w * h;
    float *pl = malloc(3 * n * sizeof *pl);
    if (!pl) {
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    for (size_t i = 0; i < n; i++)
        for (size_t ch = 0; ch < 3; ch++)
            pl[ch * n + i] = (float)rgb[3 * i + ch] / 255.0f;
    int rc = write_float_rgb(base, w, h, pl, err, errlen) || write_png(base, w, h, rgb, err, errlen) ? -1 : 0;
    free(pl);
    return rc;
}

int np_render_write_ref(const char *base, const np_render_frame *fr, char *err, size_t errlen)
{
    unsigned w = fr->sc->width, h = fr->sc->height;
    size_t n = (size_t)w * h;
    float *pl = malloc(3 * n * sizeof *pl);
    uint8_t *rgb = malloc(3 * n);
    int rc = -1;
    if (!pl || !rgb) {
        snprintf(err, errlen, "out of memory");
        goto out;
    }
    for (size_t i = 0; i < n; i++)
        for (size_t ch = 0; ch < 3; ch++)
            pl[ch * n + i] = (float)(fr->ref[3 * i + ch] / 255.0);
    np_render_ref_rgb8(fr, rgb);
    rc = write_float_rgb(base, w, h, pl, err, errlen) || write_png(base, w, h, rgb, err, errlen) ? -1 : 0;
out:
    free(pl);
    free(rgb);
    return rc;
}

/* The heat map of np_render_write_error: stops every 0.5 LSB. */
static void heat(double e, uint8_t c[3])
{
    static const double stops[5][3] = { { 0, 0, 0 }, { 0, 0, 255 }, { 0, 255, 0 }, { 255, 255, 0 }, { 255, 0, 0 } };
    double t = e / 0.5;
    if (t >= 4.0) {
        memcpy(c, (uint8_t[3]){ 255, 0, 0 }, 3);
        return;
    }
    int k = (int)floor(t);
    double w = t - k;
    for (int ch = 0; ch < 3; ch++)
        c[ch] = (uint8_t)floor(stops[k][ch] + w * (stops[k + 1][ch] - stops[k][ch]) + 0.5);
}

int np_render_write_error(const char *base, const np_render_frame *fr, const uint8_t *rgb, char *err,
                          size_t errlen)
{
    unsigned w = fr->sc->width, h = fr->sc->height;
    size_t n = (size_t)w * h;
    float *pl = calloc(3 * n, sizeof *pl);
    uint8_t *hm = malloc(3 * n);
    int rc = -1;
    if (!pl || !hm) {
        snprintf(err, errlen, "out of memory");
        goto out;
    }
    for (size_t i = 0; i < n; i++) {
        if (!fr->mask[i]) {
            memset(hm + 3 * i, 40, 3);
            continue;
        }
        double m = 0;
        for (size_t ch = 0; ch < 3; ch++) {
            double d = (double)rgb[3 * i + ch] - fr->ref[3 * i + ch];
            pl[ch * n + i] = (float)d;
            m = fmax(m, fabs(d));
        }
        heat(m, hm + 3 * i);
    }
    rc = write_float_rgb(base, w, h, pl, err, errlen) || write_png(base, w, h, hm, err, errlen) ? -1 : 0;
out:
    free(pl);
    free(hm);
    return rc;
}

