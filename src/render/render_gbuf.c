/* SPDX-License-Identifier: MIT */
/* The G-buffer renderer: scan conversion at m x m samples, deferred shading, resolve, lighting (np_gbuf.h). */
#include "np_gbuf.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "np_common.h"
#include "np_texreg.h"
#include "render_view.h"

/*
 * The paper's index matrices and the resolve's reciprocal ROM are the unit's,
 * through the registry (np_unit.samples, kept in np_gbuf.samples): one
 * definition, the hardware's.
 */

/* Round half up to 8 bits (the units' colour stage, np_tex_colour_round). */
static uint8_t round8(double v) { return (uint8_t)floor(v + 0.5); }

/* --- Lighting (fixed point; formats in np_gbuf.h) --- */

static int32_t q_signed(double v, unsigned frac, int32_t lim)
{
    double r = floor(ldexp(v, (int)frac) + 0.5);
    if (r > lim)
        r = lim;
    if (r < -lim)
        r = -lim;
    return (int32_t)r;
}

void np_gbuf_light_setup(const np_scene *sc, np_gbuf_lightq *q)
{
    memset(q, 0, sizeof *q);
    q->on = sc->light_image;
    for (int a = 0; a < 3; a++)
        q->l[a] = q_signed(sc->light_dir[a] * 128.0 / (double)NP_GBUF_NORMAL_ONE, NP_GBUF_LIGHT_FRAC, 1 << 16);
    q->a = (uint32_t)floor(ldexp(sc->ambient, NP_GBUF_L_FRAC) + 0.5);
}

uint32_t np_gbuf_light_factor(const np_gbuf_lightq *q, const int8_t n[3])
{
    const unsigned one = 1u << NP_GBUF_L_FRAC;
    /* dot: s25 Q0.22 (|n_i| <= 127, |l_i| <= 33026: |dot| < 2^24), exact. */
    int32_t dot = (int32_t)n[0] * q->l[0] + (int32_t)n[1] * q->l[1] + (int32_t)n[2] * q->l[2];
    const int32_t dfrac = NP_GBUF_NORMAL_FRAC + NP_GBUF_LIGHT_FRAC, shift = dfrac - NP_GBUF_L_FRAC;
    if (dot < 0)
        dot = 0;
    if (dot > (1 << dfrac))
        dot = 1 << dfrac;
    uint32_t lam = ((uint32_t)dot + (1u << (shift - 1))) >> shift; /* u17 Q1.16, <= 2^16 */
    uint64_t L = (uint64_t)q->a * one + (uint64_t)(one - q->a) * lam; /* Q2.32, <= 2^32 */
    return (uint32_t)((L + (1u << (NP_GBUF_L_FRAC - 1))) >> NP_GBUF_L_FRAC);
}

void np_gbuf_light(const np_gbuf_lightq *q, const int8_t n[3], uint8_t rgb[3])
{
    if (!q->on)
        return;
    uint32_t L = np_gbuf_light_factor(q, n);
    for (int c = 0; c < 3; c++)
        rgb[c] = (uint8_t)(((uint64_t)rgb[c] * L + (1u << (NP_GBUF_L_FRAC - 1))) >> NP_GBUF_L_FRAC);
}

/* --- Scan conversion --- */

/* The G-buffer's normal code: round_half_up(127 n_i) (np_gbuf.h). */
static void normal_code(const double n[3], int8_t nq[3])
{
    for (int a = 0; a < 3; a++)
        nq[a] = (int8_t)q_signed(n[a] * (double)NP_GBUF_NORMAL_ONE, 0, NP_GBUF_NORMAL_ONE);
}

void np_gbuf_normal_decode(const int8_t nq[3], double n[3])
{
    for (int a = 0; a < 3; a++)
        n[a] = (double)nq[a] / (double)NP_GBUF_NORMAL_ONE;
}

/* The unit normal of p turned towards the camera (world space). */
static void facing_normal(const np_rview *v, const np_scene_poly *p, double n[3])
{
    np_rpoly_normal(p, n);
    double l = sqrt(np_rdot3(n, n));
    if (!(l > 0)) {
        n[0] = n[1] = n[2] = 0;
        return;
    }
    for (int a = 0; a < 3; a++)
        n[a] /= l;
    double side;
    if (v->cam->perspective) {
        double d[3] = { p->p[0][0] - v->eye[0], p->p[0][1] - v->eye[1], p->p[0][2] - v->eye[2] };
        side = np_rdot3(n, d);
    } else {
        side = np_rdot3(n, v->f);
    }
    if (side > 0)
        for (int a = 0; a < 3; a++)
            n[a] = -n[a];
}

/* The polygon's plane for the depth of a screen point: z = plane_depth(pl, sx, sy). */
typedef struct plane {
    double A, nr, nu, nf;
    const np_rview *v;
} plane;

static void plane_init(const np_rview *v, const np_scene_poly *p, plane *pl)
{
    double n[3];
    np_rpoly_normal(p, n);
    double d[3] = { v->eye[0] - p->p[0][0], v->eye[1] - p->p[0][1], v->eye[2] - p->p[0][2] };
    pl->A = np_rdot3(n, d);
    pl->nr = np_rdot3(n, v->r);
    pl->nu = np_rdot3(n, v->u);
    pl->nf = np_rdot3(n, v->f);
    pl->v = v;
}

/* View depth of the polygon's plane under screen point (sx, sy): the ray's exact intersection. */
static double plane_depth(const plane *pl, double sx, double sy)
{
    const np_rview *v = pl->v;
    if (v->cam->perspective) {
        double k = v->cam->focal * v->h / 2.0;
        double xd = (sx - v->w / 2.0) / k, yd = (v->h / 2.0 - sy) / k;
        return -pl->A / (xd * pl->nr + yd * pl->nu + pl->nf);
    }
    double k = v->h / v->cam->height;
    double xw = (sx - v->w / 2.0) / k, yw = (v->h / 2.0 - sy) / k;
    return -(pl->A + xw * pl->nr + yw * pl->nu) / pl->nf;
}

static uint32_t depth_code(double z, double z0, double z1)
{
    if (!(z1 > z0))
        return 0;
    double d = floor((z - z0) / (z1 - z0) * (double)NP_GBUF_DEPTH_FAR + 0.5);
    if (!(d > 0)) /* NaN too */
        return d != d ? NP_GBUF_DEPTH_FAR : 0;
    return d >= (double)NP_GBUF_DEPTH_FAR ? NP_GBUF_DEPTH_FAR : (uint32_t)d;
}

double np_gbuf_depth_f(const np_gbuf *g, uint32_t d)
{
    return g->z_near + (g->z_far - g->z_near) * (double)d / (double)NP_GBUF_DEPTH_FAR;
}

/* The texture axes that vary on the face: drop the one with the smallest range (ties: the highest). */
static void uv_axes(const np_scene_poly *p, uint8_t uv[2])
{
    double range[3];
    for (int a = 0; a < 3; a++) {
        double lo = p->t[0][a], hi = p->t[0][a];
        for (unsigned k = 1; k < p->n; k++) {
            lo = fmin(lo, p->t[k][a]);
            hi = fmax(hi, p->t[k][a]);
        }
        range[a] = hi - lo;
    }
    int drop = 2;
    for (int a = 1; a >= 0; a--)
        if (range[a] < range[drop])
            drop = a;
    uv[0] = (uint8_t)(drop == 0 ? 1 : 0);
    uv[1] = (uint8_t)(drop == 2 ? 1 : 2);
}

/* d s / d y on the screen: the affine map through the projected polygon's largest-area vertex triangle. */
static void screen_dsdy(const np_rproj *pp, double dsdy[3])
{
    double best = 0;
    unsigned bi = 1;
    for (unsigned i = 1; i + 1 < pp->n; i++) {
        double a = fabs((pp->x[i] - pp->x[0]) * (pp->y[i + 1] - pp->y[0]) -
                        (pp->x[i + 1] - pp->x[0]) * (pp->y[i] - pp->y[0]));
        if (a > best) {
            best = a;
            bi = i;
        }
    }
    const double dx1 = pp->x[bi] - pp->x[0], dy1 = pp->y[bi] - pp->y[0];
    const double dx2 = pp->x[bi + 1] - pp->x[0], dy2 = pp->y[bi + 1] - pp->y[0];
    const double det = dx1 * dy2 - dx2 * dy1;
    for (int a = 0; a < 3; a++) {
        const double dt1 = pp->p->t[bi][a] - pp->p->t[0][a], dt2 = pp->p->t[bi + 1][a] - pp->p->t[0][a];
        dsdy[a] = det != 0 ? (dx1 * dt2 - dx2 * dt1) / det : 0.0;
    }
}

/* The depth range: the scene's, or [min, max] of the view depth over the drawn polygons' vertices. */
static void depth_range(const np_scene *sc, const np_rview *v, double *z0, double *z1)
{
    if (sc->cam.have_depth_range) {
        *z0 = sc->cam.depth_range[0];
        *z1 = sc->cam.depth_range[1];
        return;
    }
    double lo = HUGE_VAL, hi = -HUGE_VAL;
    np_scene_poly tmp;
    for (uint32_t id = 0; id < sc->n_prims; id++) {
        const np_scene_poly *p = np_scene_poly_get(sc, id, &tmp);
        if (p->cull && !np_rview_facing(v, p))
            continue;
        for (unsigned k = 0; k < p->n; k++) {
            double z = np_rview_depth(v, p->p[k]);
            lo = fmin(lo, z);
            hi = fmax(hi, z);
        }
    }
    *z0 = lo < hi ? lo : 0;
    *z1 = lo < hi ? hi : 0;
}

static int push_gspan(np_gbuf *g, size_t *cap, const np_gbuf_span *s)
{
    if (g->n_spans == *cap) {
        size_t nc = *cap ? *cap * 2 : 1024;
        np_gbuf_span *ns = realloc(g->spans, nc * sizeof *ns);
        if (!ns)
            return -1;
        g->spans = ns;
        *cap = nc;
    }
    g->spans[g->n_spans++] = *s;
    return 0;
}

void np_gbuf_free(np_gbuf *g)
{
    free(g->spans);
    free(g->depth);
    free(g->normal);
    free(g->poly);
    free(g->span);
    free(g->k);
    free(g->hits);
    free(g->cover);
    memset(g, 0, sizeof *g);
}

/* Drop the sub-spans no sample refers to (wholly hidden ones), renumbering the samples' references. */
static int compact_spans(np_gbuf *g, size_t nsamp)
{
    uint32_t *map = malloc((g->n_spans ? g->n_spans : 1) * sizeof *map);
    if (!map)
        return -1;
    for (size_t i = 0; i < g->n_spans; i++)
        map[i] = NP_GBUF_NONE;
    for (size_t i = 0; i < nsamp; i++)
        if (g->span[i] != NP_GBUF_NONE)
            map[g->span[i]] = 0;
    size_t n = 0;
    for (size_t i = 0; i < g->n_spans; i++)
        if (map[i] == 0) {
            g->spans[n] = g->spans[i];
            map[i] = (uint32_t)n++;
        }
    for (size_t i = 0; i < nsamp; i++)
        if (g->span[i] != NP_GBUF_NONE)
            g->span[i] = map[g->span[i]];
    g->n_spans = n;
    free(map);
    return 0;
}

int np_gbuf_build(const np_scene *sc, unsigned m, np_gbuf *g, char *err, size_t errlen)
{
    memset(g, 0, sizeof *g);
    if (m < 1 || m > NP_GBUF_M_MAX) {
        snprintf(err, errlen, "G-buffer: m = %u samples per pixel side: expected 1..%d", m, NP_GBUF_M_MAX);
        return -1;
    }
    for (size_t i = 0; !g->samples && np_unit_at(i); i++)
        g->samples = np_unit_at(i)->samples;
    if (!g->samples) {
        snprintf(err, errlen, "G-buffer: no unit of the registry gives a sample order and resolve (np_unit.samples)");
        return -1;
    }
    g->sc = sc;
    g->m = m;
    g->n = m * m;
    g->w = sc->width;
    g->h = sc->height;
    char why[256];
    if (np_texreg_compile(&sc->tex, &g->regs, why, sizeof why)) {
        snprintf(err, errlen, "%s: texture: %s", sc->path, why);
        return -1;
    }
    double t0 = np_now();
    np_rview v;
    np_rview_init(sc, &v);
    depth_range(sc, &v, &g->z_near, &g->z_far);
    const size_t npx = (size_t)g->w * g->h, ns = npx * g->n;
    g->depth = malloc(ns * sizeof *g->depth);
    g->normal = calloc(ns, sizeof *g->normal);
    g->poly = malloc(ns * sizeof *g->poly);
    g->span = malloc(ns * sizeof *g->span);
    g->k = calloc(ns, sizeof *g->k);
    g->hits = calloc(ns, 1);
    g->cover = calloc(npx, 1);
    if (!g->depth || !g->normal || !g->poly || !g->span || !g->k || !g->hits || !g->cover)
        goto oom;
    for (size_t i = 0; i < ns; i++) {
        g->depth[i] = NP_GBUF_DEPTH_FAR;
        g->poly[i] = NP_GBUF_NONE;
        g->span[i] = NP_GBUF_NONE;
    }
    size_t cap = 0, live_mark = (size_t)1 << 20;
    np_progress pr;
    np_progress_start(&pr, "render: G-buffer, polygons", sc->n_prims);
    np_scene_poly tmp;
    for (uint32_t id = 0; id < sc->n_prims; id++) {
        if ((id & 1023u) == 0)
            np_progress_update(&pr, id);
        const np_scene_poly *p = np_scene_poly_get(sc, id, &tmp);
        if (p->cull && !np_rview_facing(&v, p))
            continue;
        np_rproj pp;
        if (np_rproj_init(&v, p, id, &pp)) {
            np_progress_end(&pr);
            snprintf(err, errlen, "%s: polygon %u is not wholly in front of the camera (no near clipping)", sc->path,
                     id);
            np_gbuf_free(g);
            return -1;
        }
        g->polys_drawn++;
        /* Bounding box: rows whose sample lines can cross it, nothing when it is off the image. */
        if (!(pp.xmax > 0) || !(pp.xmin < (double)g->w) || !(pp.ymax > 0) || !(pp.ymin < (double)g->h))
            continue;
        double nf[3];
        facing_normal(&v, p, nf);
        int8_t nq[3];
        normal_code(nf, nq);
        plane pl;
        plane_init(&v, p, &pl);
        np_gbuf_span gs;
        memset(&gs, 0, sizeof gs);
        uv_axes(p, gs.uv);
        screen_dsdy(&pp, gs.dsdy);
        double jlo = floor(pp.ymin - 1.0), jhi = ceil(pp.ymax);
        unsigned j0 = jlo < 0 ? 0u : (unsigned)jlo, j1 = jhi > (double)g->h ? g->h : (unsigned)jhi;
        for (unsigned b = 0; b < m; b++) {
            const double oy = ((double)b + 0.5) / (double)m;
            for (unsigned a = 0; a < m; a++) {
                const double ox = ((double)a + 0.5) / (double)m;
                for (unsigned j = j0; j < j1; j++) {
                    int rc = np_rrow_span(sc, &pp, j, ox, oy, &gs.r, err, errlen);
                    if (rc < 0) {
                        np_progress_end(&pr);
                        np_gbuf_free(g);
                        return -1;
                    }
                    if (rc == 0)
                        continue;
                    gs.a = (uint8_t)a;
                    gs.b = (uint8_t)b;
                    if (g->n_spans == cap && cap >= live_mark) {
                        /* Keep the sub-spans to about the live ones: drop the wholly hidden. */
                        if (compact_spans(g, ns))
                            goto oom_pr;
                        if (g->n_spans > live_mark / 2)
                            live_mark *= 2;
                    }
                    if (push_gspan(g, &cap, &gs))
                        goto oom_pr;
                    const uint32_t si = (uint32_t)(g->n_spans - 1);
                    const double sy = (double)j + oy;
                    for (uint32_t k = 0; k < gs.r.hw.n; k++) {
                        const unsigned x = gs.r.hw.x0 + k;
                        const size_t i = np_gbuf_index(g, x, j, a, b);
                        const uint32_t d = depth_code(plane_depth(&pl, (double)x + ox, sy), g->z_near, g->z_far);
                        if (g->hits[i] < 255)
                            g->hits[i]++;
                        if (d > g->depth[i])
                            continue;
                        g->depth[i] = d;
                        g->poly[i] = id;
                        g->span[i] = si;
                        g->k[i] = (uint16_t)k;
                        memcpy(g->normal[i], nq, 3);
                    }
                }
            }
        }
    }
    np_progress_end(&pr);
    if (compact_spans(g, ns))
        goto oom;
    for (size_t p = 0; p < npx; p++) {
        unsigned c = 0;
        for (unsigned j = 0; j < g->n; j++)
            c += g->poly[p * g->n + j] != NP_GBUF_NONE;
        g->cover[p] = (uint8_t)c;
        g->covered_samples += c;
        g->covered_pixels += c > 0;
    }
    g->raster_seconds = np_now() - t0;
    if (g->covered_samples == 0 && !sc->allow_empty) {
        np_gbuf_free(g);
        snprintf(err, errlen,
                 "the scene covers no pixel: every polygon faces away from the camera, is behind it or "
                 "is off the image (is camera.eye inside the geometry?); set \"allow_empty\": true to "
                 "render an empty image");
        return -1;
    }
    return 0;
oom_pr:
    np_progress_end(&pr);
oom:
    np_gbuf_free(g);
    snprintf(err, errlen, "out of memory");
    return -1;
}

/* --- Sample accessors --- */

void np_gbuf_position(const np_gbuf *g, size_t i, double *sx, double *sy)
{
    size_t p = i / g->n;
    unsigned j = (unsigned)(i % g->n);
    *sx = (double)(p % g->w) + ((double)(j % g->m) + 0.5) / (double)g->m;
    *sy = (double)(p / g->w) + ((double)(j / g->m) + 0.5) / (double)g->m;
}

void np_gbuf_texcoord(const np_gbuf *g, size_t i, int64_t s[3])
{
    const np_span *sp = &g->spans[g->span[i]].r.hw;
    for (int a = 0; a < 3; a++)
        s[a] = sp->s[a] + (int64_t)g->k[i] * sp->ds[a];
}

void np_gbuf_texcoord_f(const np_gbuf *g, size_t i, double s[3])
{
    const np_rspan *sp = &g->spans[g->span[i]].r;
    for (int a = 0; a < 3; a++)
        s[a] = sp->s0[a] + (double)g->k[i] * sp->ds[a];
}

void np_gbuf_uv(const np_gbuf *g, size_t i, int64_t uv[2])
{
    int64_t s[3];
    np_gbuf_texcoord(g, i, s);
    const np_gbuf_span *sp = &g->spans[g->span[i]];
    uv[0] = s[sp->uv[0]];
    uv[1] = s[sp->uv[1]];
}

void np_gbuf_uv_f(const np_gbuf *g, size_t i, double uv[2])
{
    double s[3];
    np_gbuf_texcoord_f(g, i, s);
    const np_gbuf_span *sp = &g->spans[g->span[i]];
    uv[0] = s[sp->uv[0]];
    uv[1] = s[sp->uv[1]];
}

/* --- Deferred shading --- */

static int selected(const np_gbuf *g, const uint16_t *mask, uint32_t si, size_t i)
{
    if (g->span[i] != si)
        return 0;
    return !mask || (((unsigned)mask[i / g->n] >> (i % g->n)) & 1u);
}

int np_gbuf_shade(const np_gbuf *g, const np_unit *u, const void *cfg, const uint16_t *mask, uint8_t *rgb,
                  np_gbuf_cost *cost)
{
    if (!u->span)
        return -1;
    const np_span_engine *e = u->span->engine;
    const void *ecfg = np_unit_span_cfg(u->span, cfg);
    void *core = malloc(e->core_size), *sig = malloc(e->sig_size);
    if (!core || !sig) {
        free(core);
        free(sig);
        return -1;
    }
    np_gbuf_cost c;
    memset(&c, 0, sizeof c);
    np_gbuf_lightq lq;
    np_gbuf_light_setup(g->sc, &lq);
    e->init(core, ecfg, &g->regs);
    const unsigned seek = e->seek && u->span->seek_cycles ? u->span->seek_cycles(ecfg, &g->regs) : 0;
    /* The runs as the sequencer sees them (timing only; cycles below). */
    size_t n_tim = 0, cap_tim = 0;
    np_span *tim = NULL;
    np_span_counts cnt;
    memset(&cnt, 0, sizeof cnt);
    /* Uncovered samples in the mask: the background, no unit work. */
    uint8_t bg[3];
    for (int ch = 0; ch < 3; ch++)
        bg[ch] = round8(g->sc->background[ch]);
    const size_t ns = (size_t)g->w * g->h * g->n;
    for (size_t i = 0; i < ns; i++)
        if (g->span[i] == NP_GBUF_NONE && (!mask || (((unsigned)mask[i / g->n] >> (i % g->n)) & 1u)))
            memcpy(rgb + 3 * i, bg, 3);
    for (uint32_t si = 0; si < g->n_spans; si++) {
        const np_gbuf_span *gs = &g->spans[si];
        const np_span *sp = &gs->r.hw;
        uint32_t k = 0;
        while (k < sp->n) {
            if (!selected(g, mask, si, np_gbuf_index(g, sp->x0 + k, sp->y, gs->a, gs->b))) {
                k++;
                continue;
            }
            uint32_t k1 = k + 1;
            while (k1 < sp->n && selected(g, mask, si, np_gbuf_index(g, sp->x0 + k1, sp->y, gs->a, gs->b)))
                k1++;
            /* One run: the descriptor, placed at pixel k, pixels k .. k1 - 1. */
            if (n_tim == cap_tim) {
                cap_tim = cap_tim ? 2 * cap_tim : 256;
                np_span *t = realloc(tim, cap_tim * sizeof *t);
                if (!t) {
                    free(tim);
                    free(core);
                    free(sig);
                    return -1;
                }
                tim = t;
            }
            /*
             * What the sequencer times: a seeking engine's run is a span of
             * k1 - k pixels (its pixels cost the same wherever they start)
             * plus the seek's clocks; a sequential engine steps from pixel 0,
             * so its run is the span's first k1 pixels.
             */
            tim[n_tim] = *sp;
            tim[n_tim++].n = e->seek ? k1 - k : k1;
            (void)e->begin(core, sp, &cnt);
            if (k > 0) {
                if (e->seek) {
                    e->seek(core, sp, k);
                    c.seek += seek;
                } else {
                    for (uint32_t s = 0; s < k; s++)
                        (void)e->advance(core, &cnt);
                    c.skipped += k;
                }
            }
            c.runs++;
            for (; k < k1; k++) {
                memset(sig, 0, e->sig_size);
                e->issue(core, sig);
                np_span_sig *h = sig;
                h->pix.x = (uint16_t)(sp->x0 + k);
                h->pix.y = sp->y;
                for (unsigned st = 0; st < e->n_stages; st++)
                    e->stages[st].fn(np_span_ctx_of(core), sig);
                const size_t i = np_gbuf_index(g, sp->x0 + k, sp->y, gs->a, gs->b);
                memcpy(rgb + 3 * i, h->pix.rgb, 3);
                np_gbuf_light(&lq, g->normal[i], rgb + 3 * i);
                c.samples++;
                (void)e->advance(core, &cnt);
            }
        }
    }
    free(core);
    free(sig);
    /* The cycles: the engine's cycle-accurate sequencer fed the runs back to back, plus the seeks. */
    if (n_tim) {
        np_span_sim sim;
        if (np_span_sim_init(&sim, e, ecfg, &g->regs)) {
            free(tim);
            return -1;
        }
        size_t next = 0;
        while (next < n_tim || !np_span_sim_idle(&sim)) {
            np_span_port p;
            memset(&p, 0, sizeof p);
            p.in_valid = next < n_tim;
            p.in = p.in_valid ? &tim[next] : NULL;
            p.out_ready = 1;
            np_span_sim_eval(&sim, &p);
            if (p.in_valid && p.in_ready)
                next++;
            np_span_sim_clock(&sim, &p);
        }
        c.setup = sim.stats.setup_stalls + c.seek;
        c.cycles = sim.stats.cycles + c.seek;
        np_span_sim_free(&sim);
    }
    free(tim);
    if (cost)
        *cost = c;
    return 0;
}

int np_gbuf_shade_first(const np_gbuf *g, const np_unit *u, const void *cfg, uint8_t *rgb1, np_gbuf_cost *cost)
{
    const size_t npx = (size_t)g->w * g->h;
    uint16_t *mask = calloc(npx ? npx : 1, sizeof *mask);
    uint8_t *all = malloc(npx * g->n * 3 + 1);
    if (!mask || !all) {
        free(mask);
        free(all);
        return -1;
    }
    const uint16_t first = g->samples->mask(g->m, 1);
    unsigned j0 = 0;
    while (!((first >> j0) & 1u))
        j0++;
    for (size_t p = 0; p < npx; p++)
        mask[p] = first;
    int rc = np_gbuf_shade(g, u, cfg, mask, all, cost);
    if (rc == 0)
        for (size_t p = 0; p < npx; p++)
            memcpy(rgb1 + 3 * p, all + 3 * (p * g->n + j0), 3);
    free(mask);
    free(all);
    return rc;
}

void np_gbuf_resolve(const np_gbuf *g, const uint16_t *mask, const uint8_t *rgb, uint8_t *out)
{
    const size_t npx = (size_t)g->w * g->h;
    for (size_t p = 0; p < npx; p++) {
        const unsigned mk = mask ? (unsigned)mask[p] : (1u << g->n) - 1u;
        uint32_t sum[3] = { 0, 0, 0 };
        unsigned s = 0;
        for (unsigned j = 0; j < g->n; j++)
            if ((mk >> j) & 1u) {
                for (int ch = 0; ch < 3; ch++)
                    sum[ch] += rgb[3 * (p * g->n + j) + (size_t)ch];
                s++;
            }
        for (int ch = 0; ch < 3; ch++)
            out[3 * p + (size_t)ch] = s ? g->samples->resolve(sum[ch], s) : round8(g->sc->background[ch]);
    }
}

/* --- Float references --- */

void np_gbuf_poly_normal(const np_scene *sc, uint32_t id, double n[3], int8_t nq[3])
{
    np_rview v;
    np_rview_init(sc, &v);
    np_scene_poly tmp;
    facing_normal(&v, np_scene_poly_get(sc, id, &tmp), n);
    if (nq)
        normal_code(n, nq);
}

double np_gbuf_light_ref(const np_scene *sc, const double n[3])
{
    if (!sc->light_image)
        return 1.0;
    return sc->ambient + (1.0 - sc->ambient) * fmax(0.0, np_rdot3(n, sc->light_dir));
}

/* The reference's lighting factor of polygon id (exact normal), 1 when the scene does not light the image. */
static double light_f(const np_scene *sc, const np_rview *v, uint32_t id)
{
    if (!sc->light_image)
        return 1.0;
    np_scene_poly tmp;
    double n[3];
    facing_normal(v, np_scene_poly_get(sc, id, &tmp), n);
    return np_gbuf_light_ref(sc, n);
}

int np_gbuf_reference_samples(const np_gbuf *g, double *out)
{
    const np_scene *sc = g->sc;
    const size_t ns = (size_t)g->w * g->h * g->n;
    for (size_t i = 0; i < ns; i++) {
        double *o = out + 3 * i;
        if (g->span[i] == NP_GBUF_NONE) {
            for (int ch = 0; ch < 3; ch++)
                o[ch] = sc->background[ch];
            continue;
        }
        double st[3];
        np_gbuf_texcoord_f(g, i, st);
        np_ref_colour(&sc->tex.cmap, np_ref_texture_f(&sc->tex, st, NULL), o);
        if (sc->light_image) {
            double n[3];
            np_gbuf_normal_decode(g->normal[i], n);
            const double lf = np_gbuf_light_ref(sc, n);
            for (int ch = 0; ch < 3; ch++)
                o[ch] *= lf;
        }
    }
    return 0;
}

int np_gbuf_reference_ssaa(const np_gbuf *g, double *out)
{
    const size_t npx = (size_t)g->w * g->h;
    double *s = malloc(npx * g->n * 3 * sizeof *s);
    if (!s)
        return -1;
    np_gbuf_reference_samples(g, s);
    for (size_t p = 0; p < npx; p++)
        for (int ch = 0; ch < 3; ch++) {
            double sum = 0;
            for (unsigned j = 0; j < g->n; j++)
                sum += s[3 * (p * g->n + j) + (size_t)ch];
            out[3 * p + (size_t)ch] = sum / (double)g->n;
        }
    free(s);
    return 0;
}

int np_gbuf_ground_truth(const np_scene *sc, unsigned q, double *out, char *err, size_t errlen)
{
    if (q < 1 || q > 64) {
        snprintf(err, errlen, "ground truth: q = %u samples per pixel side: expected 1..64", q);
        return -1;
    }
    np_rview v;
    np_rview_init(sc, &v);
    const unsigned w = sc->width, h = sc->height, n = q * q;
    /* Each drawn polygon in the lists of the rows its bounding box touches. */
    size_t *first = calloc((size_t)h + 1, sizeof *first), total = 0;
    uint32_t *ids = NULL;
    double *z = malloc((size_t)w * n * sizeof *z), *st = malloc((size_t)w * n * 3 * sizeof *st);
    uint32_t *pid = malloc((size_t)w * n * sizeof *pid);
    if (!first || !z || !st || !pid)
        goto oom;
    np_scene_poly tmp;
    for (int pass = 0; pass < 2; pass++) {
        if (pass == 1) {
            for (unsigned j = 0; j < h; j++)
                first[j + 1] += first[j];
            total = first[h];
            ids = malloc((total ? total : 1) * sizeof *ids);
            if (!ids)
                goto oom;
        }
        for (uint32_t id = 0; id < sc->n_prims; id++) {
            const np_scene_poly *p = np_scene_poly_get(sc, id, &tmp);
            np_rproj pp;
            if ((p->cull && !np_rview_facing(&v, p)) || np_rproj_init(&v, p, id, &pp))
                continue;
            double jlo = floor(pp.ymin - 1.0), jhi = ceil(pp.ymax);
            unsigned j0 = jlo < 0 ? 0u : (unsigned)fmin(jlo, (double)h), j1 = jhi > (double)h ? h : (unsigned)fmax(jhi, 0);
            for (unsigned j = j0; j < j1; j++) {
                if (pass == 0)
                    first[j + 1]++;
                else
                    ids[first[j]++] = id;
            }
        }
        if (pass == 1) {
            for (unsigned j = h; j > 0; j--)
                first[j] = first[j - 1];
            first[0] = 0;
        }
    }
    np_progress pr;
    np_progress_start(&pr, "render: ground truth, rows", h);
    for (unsigned j = 0; j < h; j++) {
        np_progress_update(&pr, j + 1u);
        for (size_t i = 0; i < (size_t)w * n; i++) {
            z[i] = HUGE_VAL;
            pid[i] = NP_GBUF_NONE;
        }
        for (size_t e = first[j]; e < first[j + 1]; e++) {
            const uint32_t id = ids[e];
            const np_scene_poly *p = np_scene_poly_get(sc, id, &tmp);
            np_rproj pp;
            np_rproj_init(&v, p, id, &pp);
            plane pl;
            plane_init(&v, p, &pl);
            for (unsigned b = 0; b < q; b++)
                for (unsigned a = 0; a < q; a++) {
                    const double ox = ((double)a + 0.5) / (double)q, oy = ((double)b + 0.5) / (double)q;
                    np_rspan rs;
                    int rc = np_rrow_span(sc, &pp, j, ox, oy, &rs, err, errlen);
                    if (rc < 0) {
                        np_progress_end(&pr);
                        goto fail;
                    }
                    for (uint32_t k = 0; rc > 0 && k < rs.hw.n; k++) {
                        const unsigned x = rs.hw.x0 + k;
                        const size_t i = (size_t)x * n + (size_t)b * q + a;
                        double zz = plane_depth(&pl, (double)x + ox, (double)j + oy);
                        if (zz > z[i])
                            continue;
                        z[i] = zz;
                        pid[i] = id;
                        for (int c = 0; c < 3; c++)
                            st[3 * i + (size_t)c] = rs.s0[c] + (double)k * rs.ds[c];
                    }
                }
        }
        uint32_t last = NP_GBUF_NONE;
        double lf = 1.0;
        for (unsigned x = 0; x < w; x++) {
            double sum[3] = { 0, 0, 0 };
            for (unsigned s = 0; s < n; s++) {
                const size_t i = (size_t)x * n + s;
                double c[3];
                if (pid[i] == NP_GBUF_NONE) {
                    memcpy(c, sc->background, sizeof c);
                } else {
                    np_ref_colour(&sc->tex.cmap, np_ref_texture_f(&sc->tex, st + 3 * i, NULL), c);
                    if (pid[i] != last) {
                        last = pid[i];
                        lf = light_f(sc, &v, last);
                    }
                    for (int ch = 0; ch < 3; ch++)
                        c[ch] *= lf;
                }
                for (int ch = 0; ch < 3; ch++)
                    sum[ch] += c[ch];
            }
            for (int ch = 0; ch < 3; ch++)
                out[3 * ((size_t)j * w + x) + (size_t)ch] = sum[ch] / (double)n;
        }
    }
    np_progress_end(&pr);
    free(first);
    free(ids);
    free(z);
    free(st);
    free(pid);
    return 0;
oom:
    snprintf(err, errlen, "out of memory");
fail:
    free(first);
    free(ids);
    free(z);
    free(st);
    free(pid);
    return -1;
}

/* --- Error measures --- */

/* Sum of squared differences on [0, 1] over the masked pixels: a is a8 (8-bit) or af (double). */
static double mse_of(const uint8_t *a8, const double *af, const double *b, const uint8_t *mask, size_t pixels)
{
    double sum = 0;
    size_t cnt = 0;
    for (size_t p = 0; p < pixels; p++) {
        if (mask && !mask[p])
            continue;
        for (size_t i = 3 * p; i < 3 * p + 3; i++) {
            double d = ((a8 ? (double)a8[i] : af[i]) - b[i]) / 255.0;
            sum += d * d;
        }
        cnt += 3;
    }
    return cnt ? sum / (double)cnt : 0.0;
}

double np_gbuf_mse(const uint8_t *a, const double *b, const uint8_t *mask, size_t pixels)
{
    return mse_of(a, NULL, b, mask, pixels);
}

double np_gbuf_mse_f(const double *a, const double *b, const uint8_t *mask, size_t pixels)
{
    return mse_of(NULL, a, b, mask, pixels);
}

double np_gbuf_psnr_paper(double mse) { return mse > 0 ? 10.0 * log10(255.0 * 255.0 / mse) : HUGE_VAL; }
double np_gbuf_psnr(double mse) { return mse > 0 ? 10.0 * log10(1.0 / mse) : HUGE_VAL; }
