/* SPDX-License-Identifier: MIT */
/* Camera, scan conversion into span descriptors, and the float reference image (np_render.h). */
#include "np_render.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "np_common.h"
#include "np_gbuf.h"
#include "np_texreg.h"
#include "render_view.h"

/* --- Camera and scan conversion (render_view.h) --- */

static void cross3(const double a[3], const double b[3], double o[3])
{
    o[0] = a[1] * b[2] - a[2] * b[1];
    o[1] = a[2] * b[0] - a[0] * b[2];
    o[2] = a[0] * b[1] - a[1] * b[0];
}

static void norm3(double v[3])
{
    double l = sqrt(np_rdot3(v, v));
    for (int a = 0; a < 3; a++)
        v[a] /= l;
}

void np_rview_init(const np_scene *sc, np_rview *v)
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

int np_rview_project(const np_rview *v, const double P[3], double *sx, double *sy)
{
    double d[3] = { P[0] - v->eye[0], P[1] - v->eye[1], P[2] - v->eye[2] };
    double xc = np_rdot3(d, v->r), yc = np_rdot3(d, v->u), zc = np_rdot3(d, v->f);
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

double np_rview_depth(const np_rview *v, const double P[3])
{
    double d[3] = { P[0] - v->eye[0], P[1] - v->eye[1], P[2] - v->eye[2] };
    return np_rdot3(d, v->f);
}

void np_rpoly_normal(const np_scene_poly *p, double n[3])
{
    n[0] = n[1] = n[2] = 0;
    for (unsigned i = 0; i < p->n; i++) {
        const double *a = p->p[i], *b = p->p[(i + 1) % p->n];
        n[0] += (a[1] - b[1]) * (a[2] + b[2]);
        n[1] += (a[2] - b[2]) * (a[0] + b[0]);
        n[2] += (a[0] - b[0]) * (a[1] + b[1]);
    }
}

int np_rview_facing(const np_rview *v, const np_scene_poly *p)
{
    double n[3];
    np_rpoly_normal(p, n);
    if (v->cam->perspective) {
        double d[3] = { p->p[0][0] - v->eye[0], p->p[0][1] - v->eye[1], p->p[0][2] - v->eye[2] };
        return np_rdot3(n, d) < 0;
    }
    return np_rdot3(n, v->f) < 0;
}

int np_rproj_init(const np_rview *v, const np_scene_poly *p, unsigned id, np_rproj *q)
{
    q->n = p->n;
    q->p = p;
    q->id = id;
    q->ymin = q->xmin = HUGE_VAL;
    q->ymax = q->xmax = -HUGE_VAL;
    int bad = 0;
    for (unsigned k = 0; k < p->n; k++) {
        bad |= np_rview_project(v, p->p[k], &q->x[k], &q->y[k]);
        q->ymin = fmin(q->ymin, q->y[k]);
        q->ymax = fmax(q->ymax, q->y[k]);
        q->xmin = fmin(q->xmin, q->x[k]);
        q->xmax = fmax(q->xmax, q->x[k]);
    }
    return bad ? -1 : 0;
}


int np_rrow_span(const np_scene *sc, const np_rproj *pp, unsigned j, double ox, double oy, np_rspan *out, char *err,
                 size_t errlen)
{
    double yc = (double)j + oy;
    double xs[2], ts[2][3];
    unsigned hits = 0;
    for (unsigned i = 0; i < pp->n && hits < 3; i++) {
        unsigned k = (i + 1) % pp->n;
        double y0 = pp->y[i], y1 = pp->y[k];
        /* Half-open in y: an edge covers [min y, max y), so a shared vertex counts once. */
        if (!((y0 <= yc && yc < y1) || (y1 <= yc && yc < y0)))
            continue;
        /*
         * From the upper end, whichever way the polygon runs along the edge:
         * two polygons sharing it compute the same crossing bit for bit, so
         * a sample exactly on it falls in exactly one (gbuf.shared_edges).
         */
        unsigned e0 = i, e1 = k;
        if (y0 > y1) {
            e0 = k;
            e1 = i;
        }
        double t = (yc - pp->y[e0]) / (pp->y[e1] - pp->y[e0]);
        if (hits < 2) {
            xs[hits] = pp->x[e0] + t * (pp->x[e1] - pp->x[e0]);
            for (int a = 0; a < 3; a++)
                ts[hits][a] = pp->p->t[e0][a] + t * (pp->p->t[e1][a] - pp->p->t[e0][a]);
        }
        hits++;
    }
    if (hits != 2)
        return 0; /* not on this row (or a degenerate polygon) */
    int l = xs[0] <= xs[1] ? 0 : 1, rr = 1 - l;
    double xl = xs[l], xr = xs[rr];
    if (!(xr > xl))
        return 0;
    /* Pixels i with xl <= i + ox < xr, clipped to the image. */
    double fi0 = ceil(xl - ox), fi1 = ceil(xr - ox);
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
    out->poly = pp->id;
    for (int a = 0; a < 3; a++) {
        out->ds[a] = (ts[rr][a] - ts[l][a]) / (xr - xl);
        out->s0[a] = ts[l][a] + (fi0 + ox - xl) * out->ds[a];
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

/* Frame order: by row, then polygon id (scene order), then x - the order the scan converter has always given. */
static int span_order(const void *pa, const void *pb)
{
    const np_rspan *a = pa, *b = pb;
    if (a->hw.y != b->hw.y)
        return a->hw.y < b->hw.y ? -1 : 1;
    if (a->poly != b->poly)
        return a->poly < b->poly ? -1 : 1;
    return a->hw.x0 < b->hw.x0 ? -1 : a->hw.x0 > b->hw.x0;
}

/*
 * The 1x1 frame is the G-buffer at m = 1 (np_gbuf.h): its spans are the
 * visible runs of the sub-spans (a whole sub-span unless a nearer polygon
 * hides part of it), so hidden surfaces are removed by depth and the units
 * shade only what is seen.
 */
int np_render_prepare(const np_scene *sc, np_render_frame *fr, char *err, size_t errlen)
{
    memset(fr, 0, sizeof *fr);
    fr->sc = sc;
    np_gbuf g;
    if (np_gbuf_build(sc, 1, &g, err, errlen))
        return -1;
    fr->regs = g.regs;
    size_t cap = 0;
    for (uint32_t si = 0; si < g.n_spans; si++) {
        const np_rspan *sp = &g.spans[si].r;
        uint32_t k = 0;
        while (k < sp->hw.n) {
            if (g.span[(size_t)sp->hw.y * g.w + sp->hw.x0 + k] != si) {
                k++;
                continue;
            }
            uint32_t k1 = k + 1;
            while (k1 < sp->hw.n && g.span[(size_t)sp->hw.y * g.w + sp->hw.x0 + k1] == si)
                k1++;
            np_rspan s = *sp;
            s.hw.x0 = (uint16_t)(sp->hw.x0 + k);
            s.hw.n = k1 - k;
            for (int a = 0; a < 3; a++) {
                s.hw.s[a] = sp->hw.s[a] + (int64_t)k * sp->hw.ds[a];
                s.s0[a] = sp->s0[a] + (double)k * sp->ds[a];
            }
            if (fr->n_spans == cap) {
                size_t nc = cap ? cap * 2 : 1024;
                np_rspan *ns = realloc(fr->spans, nc * sizeof *ns);
                if (!ns) {
                    np_gbuf_free(&g);
                    np_render_frame_free(fr);
                    snprintf(err, errlen, "out of memory");
                    return -1;
                }
                fr->spans = ns;
                cap = nc;
            }
            fr->spans[fr->n_spans++] = s;
            fr->pixels += s.hw.n;
            if (s.hw.n > fr->longest)
                fr->longest = s.hw.n;
            k = k1;
        }
    }
    np_gbuf_free(&g);
    if (fr->n_spans) /* an empty frame (allow_empty) has no span array: qsort must not see NULL */
        qsort(fr->spans, fr->n_spans, sizeof *fr->spans, span_order);
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
    np_progress pr;
    np_progress_start(&pr, "render: float reference, spans", fr->n_spans);
    double t0 = np_now();
    for (size_t i = 0; i < fr->n_spans; i++) {
        np_progress_update(&pr, i + 1u); /* counted as it starts: the last update is 100 % */
        const np_rspan *s = &fr->spans[i];
        double *row = fr->ref + ((size_t)s->hw.y * sc->width + s->hw.x0) * 3;
        double lf = 1.0; /* the scene's light on the image (light.image) */
        if (sc->light_image) {
            double n[3], nd[3];
            int8_t nq[3];
            np_gbuf_poly_normal(sc, s->poly, n, nq);
            np_gbuf_normal_decode(nq, nd); /* the G-buffer's normal, as the unit sees it */
            lf = np_gbuf_light_ref(sc, nd);
        }
        for (uint32_t k = 0; k < s->hw.n; k++) {
            /* Equation 14: s0 + k ds. */
            double st[3] = { s->s0[0] + (double)k * s->ds[0], s->s0[1] + (double)k * s->ds[1],
                             s->s0[2] + (double)k * s->ds[2] };
            np_ref_colour(&sc->tex.cmap, np_ref_texture_f(&sc->tex, st, NULL), row + 3 * (size_t)k);
            for (size_t ch = 0; ch < 3; ch++)
                row[3 * (size_t)k + ch] *= lf;
        }
    }
    fr->ref_seconds = np_now() - t0;
    np_progress_end(&pr);
    return 0;
}

