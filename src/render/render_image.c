/* SPDX-License-Identifier: MIT */
/*
 * Image files of a render (np_render.h): the units' images and the reference
 * (EXR linear with chromaticities, PNG as computed, a shaded PNG view), and
 * the error heat maps with their colour bar and scale.
 */
#include "np_render.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "np_image.h"

/* --- Colour images --- */

/*
 * The sRGB EOTF (IEC 61966-2-1): a display-referred code value v / 255 in
 * [0, 1] to linear light. EXR viewers expect linear values; writing the
 * display-referred value shows it washed out.
 */
static float srgb_to_linear(double v)
{
    return (float)(v <= 0.04045 ? v / 12.92 : pow((v + 0.055) / 1.055, 2.4));
}

/* base.exr: linear Rec. 709 R, G, B of the display-referred values v[3 i + c] / 255, with the chromaticities. */
static int write_linear_exr(const char *base, const np_render_frame *fr, const char *unit, const double *v8,
                            const uint8_t *c8, char *err, size_t errlen)
{
    static const char *const names[3] = { "R", "G", "B" };
    unsigned w = fr->sc->width, h = fr->sc->height;
    size_t n = (size_t)w * h;
    float *pl = malloc(3 * n * sizeof *pl);
    if (!pl) {
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    for (size_t i = 0; i < n; i++)
        for (size_t ch = 0; ch < 3; ch++)
            pl[ch * n + i] = srgb_to_linear((v8 ? v8[3 * i + ch] : (double)c8[3 * i + ch]) / 255.0);
    np_image_meta m = { .rec709 = 1 };
    np_image_meta_add(&m, "noisepipe:values",
                      v8 ? "linear light, Rec. 709 primaries, D65 white: the sRGB EOTF of the unrounded reference "
                           "value / 255"
                         : "linear light, Rec. 709 primaries, D65 white: the sRGB EOTF of the unit's 8-bit code / 255");
    np_image_meta_add(&m, "noisepipe:unit", unit);
    np_image_meta_add(&m, "noisepipe:scene", fr->sc->name);
    char path[4096];
    snprintf(path, sizeof path, "%s.exr", base);
    int rc = np_image_write_exr_meta(path, w, h, 3, names, pl, &m, err, errlen);
    free(pl);
    return rc;
}

/* base.png (the 8-bit image as computed) and base_lit.png (np_render_shade). */
static int write_views(const char *base, const np_render_frame *fr, const char *unit, const uint8_t *rgb, char *err,
                       size_t errlen)
{
    unsigned w = fr->sc->width, h = fr->sc->height;
    char path[4096];
    np_image_meta m = { 0 };
    np_image_meta_add(&m, "noisepipe:unit", unit);
    np_image_meta_add(&m, "noisepipe:scene", fr->sc->name);
    snprintf(path, sizeof path, "%s.png", base);
    if (np_image_write_png_meta(path, w, h, rgb, &m, err, errlen))
        return -1;
    uint8_t *lit = malloc((size_t)w * h * 3);
    if (!lit) {
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    np_render_shade(fr, rgb, lit);
    np_image_meta_add(&m, "noisepipe:view", "shaded for viewing (Lambert, the scene's light); not the unit's output");
    snprintf(path, sizeof path, "%s_lit.png", base);
    int rc = np_image_write_png_meta(path, w, h, lit, &m, err, errlen);
    free(lit);
    return rc;
}

int np_render_write_rgb8(const char *base, const np_render_frame *fr, const char *unit, const uint8_t *rgb,
                         char *err, size_t errlen)
{
    if (write_linear_exr(base, fr, unit, NULL, rgb, err, errlen))
        return -1;
    return write_views(base, fr, unit, rgb, err, errlen);
}

int np_render_write_ref(const char *base, const np_render_frame *fr, char *err, size_t errlen)
{
    size_t n = (size_t)fr->sc->width * fr->sc->height;
    uint8_t *rgb = malloc(3 * n);
    if (!rgb) {
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    np_render_ref_rgb8(fr, rgb);
    int rc = write_linear_exr(base, fr, "ref", fr->ref, NULL, err, errlen) ? -1
                                                                             : write_views(base, fr, "ref", rgb, err, errlen);
    free(rgb);
    return rc;
}

/* --- Shading --- */

/* Lambert factor of polygon p: ambient + (1 - ambient) max(0, n . light), n its Newell normal turned to the eye. */
static double lambert(const np_scene *sc, const np_scene_poly *p)
{
    double nv[3] = { 0, 0, 0 }, l2 = 0, side = 0;
    for (unsigned k = 0; k < p->n; k++) {
        const double *a = p->p[k], *b = p->p[(k + 1) % p->n];
        nv[0] += (a[1] - b[1]) * (a[2] + b[2]);
        nv[1] += (a[2] - b[2]) * (a[0] + b[0]);
        nv[2] += (a[0] - b[0]) * (a[1] + b[1]);
    }
    for (int a = 0; a < 3; a++) {
        l2 += nv[a] * nv[a];
        side += nv[a] * (sc->cam.eye[a] - p->p[0][a]);
    }
    if (!(l2 > 0))
        return sc->ambient;
    double d = (nv[0] * sc->light_dir[0] + nv[1] * sc->light_dir[1] + nv[2] * sc->light_dir[2]) / sqrt(l2);
    if (side < 0) /* seen from its back (a polygon with "cull": false) */
        d = -d;
    return sc->ambient + (1.0 - sc->ambient) * fmax(0.0, d);
}

int np_render_shade(const np_render_frame *fr, const uint8_t *rgb, uint8_t *out)
{
    const np_scene *sc = fr->sc;
    memcpy(out, rgb, (size_t)sc->width * sc->height * 3);
    if (sc->light_image)
        return 0; /* the image is lit already (light.image): the view is the image */
    double *k = malloc((sc->n_prims ? sc->n_prims : 1) * sizeof *k);
    if (!k)
        return -1;
    np_scene_poly tmp;
    for (uint32_t p = 0; p < sc->n_prims; p++)
        k[p] = lambert(sc, np_scene_poly_get(sc, p, &tmp));
    /* Spans in frame order (they do not overlap: hidden parts are removed by depth). */
    for (size_t i = 0; i < fr->n_spans; i++) {
        const np_rspan *s = &fr->spans[i];
        size_t at = ((size_t)s->hw.y * sc->width + s->hw.x0) * 3;
        for (size_t c = 0; c < (size_t)s->hw.n * 3; c++)
            out[at + c] = (uint8_t)floor((double)rgb[at + c] * k[s->poly] + 0.5);
    }
    free(k);
    return 0;
}

/* --- Error images --- */

void np_render_heat(double e, uint8_t c[3])
{
    static const double stops[5][3] = { { 0, 0, 0 }, { 0, 0, 255 }, { 0, 255, 0 }, { 255, 255, 0 }, { 255, 0, 0 } };
    double t = e / 0.5;
    if (!(t < 4.0)) {
        for (int ch = 0; ch < 3; ch++)
            c[ch] = (uint8_t)stops[4][ch];
        return;
    }
    if (t < 0)
        t = 0;
    int k = (int)floor(t);
    double w = t - k;
    for (int ch = 0; ch < 3; ch++)
        c[ch] = (uint8_t)floor(stops[k][ch] + w * (stops[k + 1][ch] - stops[k][ch]) + 0.5);
}

void np_render_legend_layout(unsigned w, np_render_legend *l)
{
    memset(l, 0, sizeof *l);
    if (w < NP_RENDER_LEGEND_MIN_WIDTH)
        return;
    unsigned s = w >= 192 ? 2u : 1u;
    l->scale = s;
    l->height = 20 * s;
    l->x0 = 4 * s;
    /* Room on the right for "2 LSB"; x1 - x0 a multiple of 4, so each tick is exactly 0.5 LSB. */
    l->x1 = l->x0 + (w - 1 - 20 * s - l->x0) / 4 * 4;
    l->y0 = 3 * s;
    l->y1 = 9 * s;
}

/* A 3 x 5 bitmap font: each row 3 bits, the leftmost the highest. */
static const uint8_t *glyph(char ch)
{
    static const struct { char c; uint8_t rows[5]; } font[] = {
        { '0', { 7, 5, 5, 5, 7 } }, { '1', { 2, 6, 2, 2, 7 } }, { '2', { 7, 1, 7, 4, 7 } },
        { '5', { 7, 4, 7, 1, 7 } }, { '.', { 0, 0, 0, 0, 2 } }, { 'L', { 4, 4, 4, 4, 7 } },
        { 'S', { 3, 4, 2, 1, 6 } }, { 'B', { 6, 5, 6, 5, 6 } },
    };
    for (size_t i = 0; i < sizeof font / sizeof font[0]; i++)
        if (font[i].c == ch)
            return font[i].rows;
    return NULL;
}

enum { LEGEND_INK = 220, LEGEND_PAPER = 40 };

/* Draw text with its top-left corner at (x, y) of img (width w), glyphs s x s pixels. */
static void draw_text(uint8_t *img, unsigned w, unsigned x, unsigned y, unsigned s, const char *t)
{
    for (; *t; t++, x += 4 * s) {
        const uint8_t *g = glyph(*t);
        for (unsigned r = 0; g && r < 5 * s; r++)
            for (unsigned c = 0; c < 3 * s; c++)
                if (((unsigned)g[r / s] >> (2u - c / s) & 1u) && x + c < w)
                    memset(img + ((size_t)(y + r) * w + x + c) * 3, LEGEND_INK, 3);
    }
}

static unsigned text_width(const char *t, unsigned s) { return (unsigned)strlen(t) * 4 * s - s; }

/*
 * The colour bar in the strip of l.height rows at the bottom of img (w x
 * rows): the heat map from 0 (x0) to NP_RENDER_HEAT_MAX LSB (x1), a tick and a
 * label every 0.5 LSB where the label fits, and "LSB" after the last.
 */
static void draw_legend(uint8_t *img, unsigned w, unsigned top, const np_render_legend *l)
{
    unsigned s = l->scale;
    memset(img + (size_t)top * w * 3, LEGEND_PAPER, (size_t)l->height * w * 3);
    for (unsigned x = l->x0; x <= l->x1; x++) {
        uint8_t c[3];
        np_render_heat(NP_RENDER_HEAT_MAX * (double)(x - l->x0) / (double)(l->x1 - l->x0), c);
        for (unsigned y = l->y0; y < l->y1; y++)
            memcpy(img + ((size_t)(top + y) * w + x) * 3, c, 3);
    }
    static const char *const label[5] = { "0", "0.5", "1", "1.5", "2" };
    unsigned free_x = 0; /* the first column a label may use */
    for (unsigned k = 0; k < 5; k++) {
        unsigned tx = l->x0 + (unsigned)((l->x1 - l->x0) * k / 4u);
        for (unsigned y = l->y1; y < l->y1 + 2 * s; y++)
            for (unsigned c = 0; c < s && tx + c < w; c++)
                memset(img + ((size_t)(top + y) * w + tx + c) * 3, LEGEND_INK, 3);
        unsigned tw = text_width(label[k], s), lx = tx + s / 2 >= tw / 2 ? tx + s / 2 - tw / 2 : 0;
        if (lx < free_x || lx + tw > w)
            continue;
        draw_text(img, w, lx, top + l->y1 + 3 * s, s, label[k]);
        free_x = lx + tw + 2 * s;
        if (k == 4 && free_x + 2 * s + text_width("LSB", s) <= w)
            draw_text(img, w, free_x + 2 * s, top + l->y1 + 3 * s, s, "LSB");
    }
}

int np_render_write_error(const char *base, const np_render_frame *fr, const char *unit, const uint8_t *rgb,
                          int rounded, char *err, size_t errlen)
{
    static const char *const names[3] = { "R", "G", "B" };
    unsigned w = fr->sc->width, h = fr->sc->height;
    size_t n = (size_t)w * h;
    np_render_legend lg;
    np_render_legend_layout(w, &lg);
    float *pl = calloc(3 * n, sizeof *pl);
    uint8_t *hm = malloc((n + (size_t)w * lg.height) * 3), *ref8 = rounded ? malloc(3 * n) : NULL;
    int rc = -1;
    if (!pl || !hm || (rounded && !ref8)) {
        snprintf(err, errlen, "out of memory");
        goto out;
    }
    if (rounded)
        np_render_ref_rgb8(fr, ref8);
    for (size_t i = 0; i < n; i++) {
        if (!fr->mask[i]) {
            memset(hm + 3 * i, LEGEND_PAPER, 3);
            continue;
        }
        double m = 0;
        for (size_t ch = 0; ch < 3; ch++) {
            double d = (double)rgb[3 * i + ch] - (rounded ? (double)ref8[3 * i + ch] : fr->ref[3 * i + ch]);
            pl[ch * n + i] = (float)d;
            m = fmax(m, fabs(d));
        }
        np_render_heat(m, hm + 3 * i);
    }
    if (lg.height)
        draw_legend(hm, w, h, &lg);
    const char *what = rounded ? "unit - reference correctly rounded to 8 bits (round half up, as the units' "
                                 "colour stage): the error beyond correct rounding"
                               : "unit - reference (unrounded)";
    char vals[256], scale[320], path[4096];
    snprintf(vals, sizeof vals, "error in 8-bit LSB (data, not colour), %s; 0 where no surface", what);
    snprintf(scale, sizeof scale,
             "0 .. %g LSB, heat map of the largest channel |error|: black 0, blue 0.5, green 1, yellow 1.5, "
             "red >= 2 LSB; dark grey: no surface; the colour bar is the bottom %u rows",
             NP_RENDER_HEAT_MAX, lg.height);
    np_image_meta m = { 0 };
    np_image_meta_add(&m, "noisepipe:values", vals);
    np_image_meta_add(&m, "noisepipe:unit", unit);
    np_image_meta_add(&m, "noisepipe:scene", fr->sc->name);
    snprintf(path, sizeof path, "%s.exr", base);
    if (np_image_write_exr_meta(path, w, h, 3, names, pl, &m, err, errlen))
        goto out;
    np_image_meta p = { 0 };
    np_image_meta_add(&p, "noisepipe:scale", scale);
    np_image_meta_add(&p, "noisepipe:error", what);
    np_image_meta_add(&p, "noisepipe:unit", unit);
    np_image_meta_add(&p, "noisepipe:scene", fr->sc->name);
    snprintf(path, sizeof path, "%s.png", base);
    rc = np_image_write_png_meta(path, w, h + lg.height, hm, &p, err, errlen);
out:
    free(pl);
    free(hm);
    free(ref8);
    return rc;
}
