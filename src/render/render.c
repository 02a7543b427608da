/* SPDX-License-Identifier: MIT */
/* Reference renderer and unit renders (np_render.h). */
#include "np_render.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "np_cli.h"
#include "np_image.h"
#include "np_texreg.h"

/* --- Camera and scan conversion --- */

typedef struct view {
    double eye[3], f[3], r[3], u[3];
    double w, h;
    const np_scene_camera *cam;
} view;

static double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static void cross3(const double a[3], const double b[3], double o[3])
{
    o[0] = a[1] * b[2] - a[2] * b[1];
    o[1] = a[2] * b[0] - a[0] * b[2];
    o[2] = a[0] * b[1] - a[1] * b[0];
}

static void norm3(double v[3])
{
    double l = sqrt(dot3(v, v));
    for (int a = 0; a < 3; a++)
        v[a] /= l;
}

static void view_init(const np_scene *sc, view *v)
{
    const np_scene_camera *c = &sc->cam;
    v->cam = c;
    for (int a = 0; a < 3; a++) {
        v->eye[a] = c->eye[a];
        v->f[a] = c->target[a] - c->eye[a];
    }
    norm3(v->f);
    cross3(v->f, c->up, v->r);
    norm3(v->r);
    cross3(v->r, v->f, v->u);
    v->w = (double)sc->width;
    v->h = (double)sc->height;
}

/* Screen position (x right, y down, pixel centres at +1/2) of P; -1 when P is not in front of the eye. */
static int project(const view *v, const double P[3], double *sx, double *sy)
{
    double d[3] = { P[0] - v->eye[0], P[1] - v->eye[1], P[2] - v->eye[2] };
    double xc = dot3(d, v->r), yc = dot3(d, v->u), zc = dot3(d, v->f);
    if (v->cam->perspective) {
        if (!(zc > 1e-9))
            return -1;
        double k = v->cam->focal * v->h / 2.0 / zc;
        *sx = v->w / 2.0 + xc * k;
        *sy = v->h / 2.0 - yc * k;
    } else {
        double k = v->h / v->cam->height;
        *sx = v->w / 2.0 + xc * k;
        *sy = v->h / 2.0 - yc * k;
    }
    return 0;
}

/* Does the polygon face the camera? (Newell normal; counter-clockwise seen from the front.) */
static int facing(const view *v, const np_scene_poly *p)
{
    double n[3] = { 0, 0, 0 };
    for (unsigned i = 0; i < p->n; i++) {
        const double *a = p->p[i], *b = p->p[(i + 1) % p->n];
        n[0] += (a[1] - b[1]) * (a[2] + b[2]);
        n[1] += (a[2] - b[2]) * (a[0] + b[0]);
        n[2] += (a[0] - b[0]) * (a[1] + b[1]);
    }
    if (v->cam->perspective) {
        double d[3] = { p->p[0][0] - v->eye[0], p->p[0][1] - v->eye[1], p->p[0][2] - v->eye[2] };
        return dot3(n, d) < 0;
    }
    return dot3(n, v->f) < 0;
}

typedef struct proj_poly {
    unsigned n;
    double x[NP_SCENE_MAX_VERTS], y[NP_SCENE_MAX_VERTS];
    const np_scene_poly *p;
    double ymin, ymax;
} proj_poly;

static int push_span(np_render_frame *fr, size_t *cap, const np_rspan *s)
{
    if (fr->n_spans == *cap) {
        size_t nc = *cap ? *cap * 2 : 1024;
        np_rspan *ns = realloc(fr->spans, nc * sizeof *ns);
        if (!ns)
            return -1;
        fr->spans = ns;
        *cap = nc;
    }
    fr->spans[fr->n_spans++] = *s;
    return 0;
}

/* The span of polygon pp on row j (centre yc); 1 when it has pixels, 0 when none, -1 on a range error. */
static int row_span(const np_scene *sc, const proj_poly *pp, unsigned j, np_rspan *out, char *err, size_t errlen)
{
    double yc = (double)j + 0.5;
    double xs[2], ts[2][3];
    unsigned hits = 0;
    for (unsigned i = 0; i < pp->n && hits < 3; i++) {
        unsigned k = (i + 1) % pp->n;
        double y0 = pp->y[i], y1 = pp->y[k];
        /* Half-open in y: an edge covers [min y, max y), so a shared vertex counts once. */
        if (!((y0 <= yc && yc < y1) || (y1 <= yc && yc < y0)))
            continue;
        double t = (yc - y0) / (y1 - y0);
        if (hits < 2) {
            xs[hits] = pp->x[i] + t * (pp->x[k] - pp->x[i]);
            for (int a = 0; a < 3; a++)
                ts[hits][a] = pp->p->t[i][a] + t * (pp->p->t[k][a] - pp->p->t[i][a]);
        }
        hits++;
    }
    if (hits != 2)
        return 0; /* not on this row (or a degenerate polygon) */
    int l = xs[0] <= xs[1] ? 0 : 1, rr = 1 - l;
    double xl = xs[l], xr = xs[rr];
    if (!(xr > xl))
        return 0;
    /* Pixels i with xl <= i + 1/2 < xr, clipped to the image. */
    double fi0 = ceil(xl - 0.5), fi1 = ceil(xr - 0.5);
    if (fi0 < 0)
        fi0 = 0;
    if (fi1 > (double)sc->width)
        fi1 = (double)sc->width;
    if (!(fi1 > fi0))
        return 0;
    memset(out, 0, sizeof *out);
    out->hw.y = (uint16_t)j;
    out->hw.x0 = (uint16_t)fi0;
    out->hw.n = (uint32_t)(fi1 - fi0);
    for (int a = 0; a < 3; a++) {
        out->ds[a] = (ts[rr][a] - ts[l][a]) / (xr - xl);
        out->s0[a] = ts[l][a] + (fi0 + 0.5 - xl) * out->ds[a];
        if (np_texreg_quantize(out->s0[a], NP_TEX_FC, NP_TEX_S_BITS, &out->hw.s[a]) ||
            np_texreg_quantize(out->ds[a], NP_TEX_FC, NP_TEX_DS_BITS, &out->hw.ds[a])) {
            snprintf(err, errlen, "%s: row %u: texture coordinate %g or its step %g per pixel is outside the "
                     "units' range (s48 Q15.32, s41 Q8.32)", sc->path, j, out->s0[a], out->ds[a]);
            return -1;
        }
    }
    const char *why = np_span_check(&out->hw);
    if (why) {
        snprintf(err, errlen, "%s: row %u: %s", sc->path, j, why);
        return -1;
    }
    return 1;
}

int np_render_prepare(const np_scene *sc, np_render_frame *fr, char *err, size_t errlen)
{
    memset(fr, 0, sizeof *fr);
    fr->sc = sc;
    char why[256];
    if (np_texreg_compile(&sc->tex, &fr->regs, why, sizeof why)) {
        snprintf(err, errlen, "%s: texture: %s", sc->path, why);
        return -1;
    }
    view v;
    view_init(sc, &v);
    proj_poly *pp = calloc(sc->n_poly ? sc->n_poly : 1, sizeof *pp);
    if (!pp) {
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    unsigned np = 0;
    for (unsigned i = 0; i < sc->n_poly; i++) {
        const np_scene_poly *p = &sc->poly[i];
        if (p->cull && !facing(&v, p))
            continue;
        proj_poly *q = &pp[np];
        q->n = p->n;
        q->p = p;
        q->ymin = HUGE_VAL;
        q->ymax = -HUGE_VAL;
        int bad = 0;
        for (unsigned k = 0; k < p->n; k++) {
            bad |= project(&v, p->p[k], &q->x[k], &q->y[k]);
            q->ymin = fmin(q->ymin, q->y[k]);
            q->ymax = fmax(q->ymax, q->y[k]);
        }
        if (bad) {
            free(pp);
            snprintf(err, errlen, "%s: polygon %u is not wholly in front of the camera (no near clipping)",
                     sc->path, i);
            return -1;
        }
        np++;
    }
    size_t cap = 0;
    for (unsigned j = 0; j < sc->height; j++) {
        double yc = (double)j + 0.5;
        for (unsigned i = 0; i < np; i++) {
            if (yc < pp[i].ymin || yc >= pp[i].ymax)
                continue;
            np_rspan s;
            int rc = row_span(sc, &pp[i], j, &s, err, errlen);
            if (rc < 0 || (rc > 0 && push_span(fr, &cap, &s))) {
                if (rc > 0)
                    snprintf(err, errlen, "out of memory");
                free(pp);
                np_render_frame_free(fr);
                return -1;
            }
            if (rc > 0) {
                fr->pixels += s.hw.n;
                if (s.hw.n > fr->longest)
                    fr->longest = s.hw.n;
            }
        }
    }
    free(pp);
    if (fr->pixels == 0 && !sc->allow_empty) {
        /* Nothing to measure: "0 of 0 samples, PSNR inf" would pass any check. */
        np_render_frame_free(fr);
        snprintf(err, errlen,
                 "the scene covers no pixel: every polygon faces away from the camera, is behind it or "
                 "is off the image (is camera.eye inside the geometry?); set \"allow_empty\": true to "
                 "render an empty image");
        return -1;
    }
    size_t npx = (size_t)sc->width * sc->height;
    fr->mask = calloc(npx, 1);
    if (!fr->mask) {
        np_render_frame_free(fr);
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    for (size_t i = 0; i < fr->n_spans; i++) {
        const np_span *s = &fr->spans[i].hw;
        memset(fr->mask + (size_t)s->y * sc->width + s->x0, 1, s->n);
    }
    return 0;
}

void np_render_frame_free(np_render_frame *fr)
{
    free(fr->spans);
    free(fr->ref);
    free(fr->mask);
    fr->spans = NULL;
    fr->ref = NULL;
    fr->mask = NULL;
}

/* --- Renders --- */

int np_render_reference(np_render_frame *fr)
{
    const np_scene *sc = fr->sc;
    size_t npx = (size_t)sc->width * sc->height;
    free(fr->ref);
    fr->ref = malloc(npx * 3 * sizeof *fr->ref);
    if (!fr->ref)
        return -1;
    for (size_t i = 0; i < npx; i++)
        for (int ch = 0; ch < 3; ch++)
            fr->ref[3 * i + (size_t)ch] = sc->background[ch];
    double t0 = np_now();
    for (size_t i = 0; i < fr->n_spans; i++) {
        const np_rspan *s = &fr->spans[i];
        double *row = fr->ref + ((size_t)s->hw.y * sc->width + s->hw.x0) * 3;
        for (uint32_t k = 0; k < s->hw.n; k++) {
            /* Equation 14: s0 + k ds. */
            double st[3] = { s->s0[0] + (double)k * s->ds[0], s->s0[1] + (double)k * s->ds[1],
                             s->s0[2] + (double)k * s->ds[2] };
            np_ref_colour(&sc->tex.cmap, np_ref_texture_f(&sc->tex, st, NULL), row + 3 * (size_t)k);
        }
    }
    fr->ref_seconds = np_now() - t0;
    return 0;
}

static uint8_t bg8(double v) { return (uint8_t)floor(v + 0.5); }

static int run_alloc(const np_render_frame *fr, np_render_run *run)
{
    const np_scene *sc = fr->sc;
    size_t npx = (size_t)sc->width * sc->height;
    memset(run, 0, sizeof *run);
    run->rgb = malloc(npx * 3);
    if (!run->rgb)
        return -1;
    for (size_t i = 0; i < npx; i++)
        for (int ch = 0; ch < 3; ch++)
            run->rgb[3 * i + (size_t)ch] = bg8(sc->background[ch]);
    return 0;
}

static void put_pixels(const np_scene *sc, uint8_t *img, const np_tex_pixel *px, uint32_t n)
{
    for (uint32_t k = 0; k < n; k++)
        memcpy(img + ((size_t)px[k].y * sc->width + px[k].x) * 3, px[k].rgb, 3);
}

/* Count pixels where a differs from b (covered pixels only). */
static uint64_t count_diff(const np_render_frame *fr, const uint8_t *a, const uint8_t *b)
{
    size_t npx = (size_t)fr->sc->width * fr->sc->height;
    uint64_t n = 0;
    for (size_t i = 0; i < npx; i++)
        if (fr->mask[i] && memcmp(a + 3 * i, b + 3 * i, 3) != 0)
            n++;
    return n;
}

enum { CYCLE_LIMIT_PER_PIXEL = 100000 };

int np_render_fdiff(const np_render_frame *fr, const np_fdiff_cfg *cfg, int cycles, np_render_run *run)
{
    if (run_alloc(fr, run))
        return -1;
    np_tex_pixel *px = malloc(((size_t)fr->longest + 1) * sizeof *px);
    if (!px)
        return -1;
    np_fdiff_counts cnt;
    memset(&cnt, 0, sizeof cnt);
    double t0 = np_now();
    for (size_t i = 0; i < fr->n_spans; i++) {
        np_fdiff_span(cfg, &fr->regs, &fr->spans[i].hw, px, &cnt, NULL);
        put_pixels(fr->sc, run->rgb, px, fr->spans[i].hw.n);
    }
    run->model_seconds = np_now() - t0;
    free(px);
    run->span_setups = cnt.span_setups;
    run->cell_setups = cnt.cell_setups;
    run->interval_setups = cnt.interval_setups;
    if (cycles) {
        np_fdiff_sim m;
        np_render_run c;
        if (run_alloc(fr, &c) || np_fdiff_sim_init(&m, cfg, &fr->regs)) {
            free(c.rgb);
            return -1;
        }
        size_t next = 0;
        uint64_t limit = (fr->pixels + fr->n_spans + 16u) * CYCLE_LIMIT_PER_PIXEL;
        t0 = np_now();
        while ((next < fr->n_spans || !np_fdiff_sim_idle(&m)) && m.stats.cycles < limit) {
            np_fdiff_port p;
            memset(&p, 0, sizeof p);
            p.in_valid = next < fr->n_spans;
            p.in = p.in_valid ? &fr->spans[next].hw : NULL;
            p.out_ready = 1;
            np_fdiff_sim_eval(&m, &p);
            if (p.out_valid)
                put_pixels(fr->sc, c.rgb, &p.out, 1);
            if (p.in_valid && p.in_ready)
                next++;
            np_fdiff_sim_clock(&m, &p);
        }
        run->cycle_seconds = np_now() - t0;
        run->have_cycles = 1;
        run->cycles = m.stats.cycles;
        run->setup_stalls = m.stats.setup_stalls;
        run->out_stalls = m.stats.out_stalls;
        run->cycle_mismatch = count_diff(fr, run->rgb, c.rgb) +
                              (m.stats.counts.pixels != fr->pixels ? 1u : 0u) +
                              (m.stats.counts.cell_setups != cnt.cell_setups ? 1u : 0u);
        np_fdiff_sim_free(&m);
        free(c.rgb);
    }
    np_render_error(fr, run->rgb, &run->err);
    return 0;
}

int np_render_texel(const np_render_frame *fr, const np_texel_cfg *cfg, int cycles, np_render_run *run)
{
    if (run_alloc(fr, run))
        return -1;
    np_tex_pixel *px = malloc(((size_t)fr->longest + 1) * sizeof *px);
    if (!px)
        return -1;
    np_texel_counts cnt;
    memset(&cnt, 0, sizeof cnt);
    double t0 = np_now();
    for (size_t i = 0; i < fr->n_spans; i++) {
        np_texel_span(cfg, &fr->regs, &fr->spans[i].hw, px, &cnt, NULL);
        put_pixels(fr->sc, run->rgb, px, fr->spans[i].hw.n);
    }
    run->model_seconds = np_now() - t0;
    free(px);
    run->span_setups = cnt.span_setups;
    if (cycles) {
        np_texel_sim m;
        np_render_run c;
        if (run_alloc(fr, &c) || np_texel_sim_init(&m, cfg, &fr->regs)) {
            free(c.rgb);
            return -1;
        }
        size_t next = 0;
        uint64_t limit = (fr->pixels + fr->n_spans + 16u) * CYCLE_LIMIT_PER_PIXEL;
        t0 = np_now();
        while ((next < fr->n_spans || !np_texel_sim_idle(&m)) && m.stats.cycles < limit) {
            np_texel_port p;
            memset(&p, 0, sizeof p);
            p.in_valid = next < fr->n_spans;
            p.in = p.in_valid ? &fr->spans[next].hw : NULL;
            p.out_ready = 1;
            np_texel_sim_eval(&m, &p);
            if (p.out_valid)
                put_pixels(fr->sc, c.rgb, &p.out, 1);
            if (p.in_valid && p.in_ready)
                next++;
            np_texel_sim_clock(&m, &p);
        }
        run->cycle_seconds = np_now() - t0;
        run->have_cycles = 1;
        run->cycles = m.stats.cycles;
        run->setup_stalls = m.stats.setup_stalls;
        run->out_stalls = m.stats.out_stalls;
        run->cycle_mismatch = count_diff(fr, run->rgb, c.rgb) + (m.stats.counts.pixels != fr->pixels ? 1u : 0u);
        np_texel_sim_free(&m);
        free(c.rgb);
    }
    np_render_error(fr, run->rgb, &run->err);
    return 0;
}

void np_render_run_free(np_render_run *run)
{
    free(run->rgb);
    run->rgb = NULL;
}

void np_render_error(const np_render_frame *fr, const uint8_t *rgb, np_render_err *e)
{
    const np_scene *sc = fr->sc;
    size_t npx = (size_t)sc->width * sc->height;
    double sum = 0, sum2 = 0;
    memset(e, 0, sizeof *e);
    for (size_t i = 0; i < npx; i++) {
        if (!fr->mask[i])
            continue;
        for (size_t ch = 0; ch < 3; ch++) {
            double d = (double)rgb[3 * i + ch] - fr->ref[3 * i + ch];
            double a = fabs(d);
            sum += d;
            sum2 += d * d;
            e->samples++;
            e->over_half += a > 0.5;
            e->over_one += a > 1.0;
            if (a > e->max_lsb) {
                e->max_lsb = a;
                e->max_x = (unsigned)(i % sc->width);
                e->max_y = (unsigned)(i / sc->width);
            }
        }
    }
    if (e->samples) {
        e->mean_lsb = sum / (double)e->samples;
        e->rms_lsb = sqrt(sum2 / (double)e->samples);
    }
    e->psnr_db = e->rms_lsb > 0 ? 20.0 * log10(255.0 / e->rms_lsb) : HUGE_VAL;
}

void np_render_ref_rgb8(const np_render_frame *fr, uint8_t *rgb)
{
    size_t n = (size_t)fr->sc->width * fr->sc->height * 3;
    for (size_t i = 0; i < n; i++)
        rgb[i] = (uint8_t)floor(fr->ref[i] + 0.5);
}

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

/* --- One scanline's noise (figures 10 and 11) --- */

static int grow(double **a, size_t n)
{
    double *p = realloc(*a, (n + 1) * sizeof **a);
    if (!p)
        return -1;
    *a = p;
    return 0;
}

static int scan_sort(np_render_scan *s);

int np_render_scanline(const np_render_frame *fr, const np_fdiff_cfg *cfg, unsigned y, np_render_scan *s)
{
    const np_tex_regs *r = &fr->regs;
    const unsigned F = np_fdiff_frac(cfg), last = r->n_oct ? r->n_oct - 1u : 0u;
    const double S = np_texreg_index_scale(&fr->sc->tex.cmap), one = ldexp(1.0, (int)F);
    np_texel_cfg tc = np_texel_cfg_default();
    tc.idx_int = cfg->idx_int;
    tc.w_frac = cfg->w_frac;
    tc.guard = cfg->guard;
    tc.weight_frac = NP_TEXEL_WT_MAX; /* exact weights: the per-pixel unit is the exact cubic, rounded once */
    memset(s, 0, sizeof *s);
    for (size_t i = 0; i < fr->n_spans; i++) {
        const np_rspan *sp = &fr->spans[i];
        if (sp->hw.y != y || r->n_oct == 0)
            continue;
        uint32_t n = sp->hw.n;
        np_tex_pixel *px = malloc(n * sizeof *px);
        np_s128 *fd[NP_TEX_MAX_OCTAVES] = { 0 }, *tx[NP_TEX_MAX_OCTAVES] = { 0 };
        uint16_t *set = malloc(n * sizeof *set);
        int bad = !px || !set;
        for (unsigned o = 0; o < r->n_oct; o++) {
            fd[o] = malloc(n * sizeof **fd);
            tx[o] = malloc(n * sizeof **tx);
            bad |= !fd[o] || !tx[o];
        }
        if (!bad) {
            np_fdiff_probe pf = { NULL, { 0 }, set };
            np_texel_probe pt = { NULL, { 0 } };
            for (unsigned o = 0; o < r->n_oct; o++) {
                pf.noise[o] = fd[o];
                pt.noise[o] = tx[o];
            }
            np_fdiff_span(cfg, r, &sp->hw, px, NULL, &pf);
            np_texel_span(&tc, r, &sp->hw, px, NULL, &pt);
            for (uint32_t k = 0; k < n && !bad; k++) {
                double d = 0, dl;
                for (unsigned o = 0; o < r->n_oct; o++)
                    d += (double)np_wrap_s128(np_add128(fd[o][k], -tx[o][k]), np_fdiff_width(cfg));
                dl = (double)np_wrap_s128(np_add128(fd[last][k], -tx[last][k]), np_fdiff_width(cfg));
                double st[3] = { sp->s0[0] + (double)k * sp->ds[0], sp->s0[1] + (double)k * sp->ds[1],
                                 sp->s0[2] + (double)k * sp->ds[2] };
                double nz[NP_REF_MAX_OCTAVES], refsum = 0;
                np_ref_texture_f(&fr->sc->tex, st, nz);
                for (unsigned o = 0; o < r->n_oct; o++)
                    refsum += fr->sc->tex.oct[o].amp * nz[o];
                if (grow(&s->x, s->n) || grow(&s->sum, s->n) || grow(&s->last, s->n) || grow(&s->ref_sum, s->n)) {
                    bad = 1;
                    break;
                }
                s->x[s->n] = (double)(sp->hw.x0 + k);
                s->sum[s->n] = d / one / S;
                s->last[s->n] = dl / one / ((double)r->oct[last].amp * 0x1p-14);
                s->ref_sum[s->n] = refsum;
                s->n++;
                if (set[k] & ((1u << r->n_oct) - 1u)) {
                    if (grow(&s->edge_any, s->n_edge_any)) {
                        bad = 1;
                        break;
                    }
                    s->edge_any[s->n_edge_any++] = (double)(sp->hw.x0 + k);
                }
                if (set[k] & (1u << last)) {
                    if (grow(&s->edge_last, s->n_edge_last)) {
                        bad = 1;
                        break;
                    }
                    s->edge_last[s->n_edge_last++] = (double)(sp->hw.x0 + k);
                }
            }
        }
        free(px);
        free(set);
        for (unsigned o = 0; o < r->n_oct; o++) {
            free(fd[o]);
            free(tx[o]);
        }
        if (bad) {
            np_render_scan_free(s);
            return -1;
        }
    }
    if (scan_sort(s)) {
        np_render_scan_free(s);
        return -1;
    }
    return 0;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* Order the samples by pixel x (the spans of a row come in polygon order). */
static int scan_sort(np_render_scan *s)
{
    double *t = malloc(4 * s->n * sizeof *t + 1);
    if (!t)
        return -1;
    for (size_t i = 0; i < s->n; i++) {
        t[4 * i] = s->x[i];
        t[4 * i + 1] = s->sum[i];
        t[4 * i + 2] = s->last[i];
        t[4 * i + 3] = s->ref_sum[i];
    }
    qsort(t, s->n, 4 * sizeof *t, cmp_double); /* x values are distinct: a stable order is not needed */
    for (size_t i = 0; i < s->n; i++) {
        s->x[i] = t[4 * i];
        s->sum[i] = t[4 * i + 1];
        s->last[i] = t[4 * i + 2];
        s->ref_sum[i] = t[4 * i + 3];
    }
    free(t);
    if (s->n_edge_any)
        qsort(s->edge_any, s->n_edge_any, sizeof *s->edge_any, cmp_double);
    if (s->n_edge_last)
        qsort(s->edge_last, s->n_edge_last, sizeof *s->edge_last, cmp_double);
    return 0;
}

void np_render_scan_free(np_render_scan *s)
{
    free(s->x);
    free(s->sum);
    free(s->last);
    free(s->ref_sum);
    free(s->edge_any);
    free(s->edge_last);
    memset(s, 0, sizeof *s);
}
