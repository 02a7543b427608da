/* SPDX-License-Identifier: MIT */
/* A scene hatched by the unit hatch through the G-buffer renderer (np_hatch_render.h, docs/hatch.md "Scenes"). */
#include "np_hatch_render.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "np_ref.h"
#include "np_render.h"
#include "np_unit.h"

np_hatch_lod np_hatch_lod_of(double L)
{
    np_hatch_lod d = { 0, 0x10000u, 0x10000u };
    if (!(L > 0) || !isfinite(L)) { /* edge-on or degenerate: the finest level */
        d.level = -64;
        return d;
    }
    int e;
    double f = frexp(L, &e); /* L = f 2^e, f in [1/2, 1): level e - 1, 2^m = 2 f */
    int level = e - 1;
    uint64_t X = (uint64_t)floor(ldexp(f, 31) + 0.5); /* u31 Q1.30: 2 f */
    if (X >= (UINT64_C(1) << 31)) {
        X = UINT64_C(1) << 30;
        level++;
    }
    if (level < -64 || level > 31) {
        d.level = level < -64 ? -64 : 31;
        return d; /* clamped: m = 0 */
    }
    d.level = level;
    d.pm = (uint32_t)(((UINT64_C(1) << 46) + X / 2u) / X);
    /* log2(X / 2^30), 16 fraction bits by repeated squaring. */
    uint64_t y = X;
    uint32_t m16 = 0;
    for (int b = 15; b >= 0; b--) {
        y = (y * y + (UINT64_C(1) << 29)) >> 30;
        if (y >= (UINT64_C(1) << 31)) {
            m16 |= 1u << b;
            y >>= 1;
        }
    }
    d.om = 0x10000u - m16;
    return d;
}

const np_unit *np_hatch_unit(void)
{
    const np_unit *u = np_unit_find("hatch");
    return u && u->strokes ? u : NULL;
}

/* The text of key name of the hatching unit u in cfg ("" when it has none). */
static void key_text(const np_unit *u, const void *cfg, const char *name, char *buf, size_t len)
{
    const np_unit_key *k = np_unit_key_find(u, name);
    if (k)
        np_unit_key_text(k, cfg, buf, len);
    else
        snprintf(buf, len, "%s", "");
}

int np_hatch_render_cfg(const np_scene_hatch *h, const char *more, np_unit_cfg *cfg, char *err, size_t errlen)
{
    const np_unit *u = np_hatch_unit();
    const np_unit_key *ks = u ? np_unit_key_find(u, "set") : NULL;
    char spec[512];
    if (!u || !ks || !ks->word) {
        snprintf(err, errlen, "the unit hatch is not in the registry");
        return -1;
    }
    const char *set = ks->word(h->set);
    snprintf(spec, sizeof spec, "set=%s,layers=%u,fade=%s,lanes=%u%s%s", set ? set : "?", h->layers,
             h->fade ? "onebyone" : "smooth", h->lanes, more && *more ? "," : "", more ? more : "");
    return np_unit_configure(u, cfg->bytes, spec, err, errlen) != 0 ? -1 : 0;
}

void np_hatch_render_cfg_text(const np_unit_cfg *cfg, char *s, size_t n)
{
    static const char *const names[] = { "set", "layers", "fade", "guard", "lanes" };
    const np_unit *u = np_hatch_unit();
    size_t at = 0;
    s[0] = '\0';
    for (size_t i = 0; u && i < sizeof names / sizeof names[0] && at < n; i++) {
        char v[64];
        key_text(u, cfg->bytes, names[i], v, sizeof v);
        int w = snprintf(s + at, n - at, "%s%s=%s", i ? "," : "", names[i], v);
        if (w < 0)
            break;
        at += (size_t)w;
    }
}

void np_hatch_frame_free(np_hatch_frame *f)
{
    free(f->rgb);
    free(f->tone);
    free(f->covered);
    free(f->lod);
    free(f->uv[0]);
    free(f->uv[1]);
    free(f->poly);
    memset(f, 0, sizeof *f);
}

/* The per-polygon level of detail from a sub-span's Jacobian on its UV axes. */
static np_hatch_lod span_lod(const np_gbuf_span *sp, double tile_pixels)
{
    double a = sp->r.ds[sp->uv[0]], b = sp->dsdy[sp->uv[0]];
    double c = sp->r.ds[sp->uv[1]], d = sp->dsdy[sp->uv[1]];
    return np_hatch_lod_of(sqrt(fabs(a * d - b * c)) * tile_pixels);
}

/* The texel unit's lit colour of every sample (tone source). */
static int lit_texture(const np_gbuf *g, const np_scene *sc, uint8_t *rgb, char *err, size_t errlen)
{
    np_render_unit_cfg us[NP_RENDER_MAX_UNITS];
    int nu = np_render_units(sc, NULL, NULL, us, err, errlen);
    const np_render_unit_cfg *tx = NULL;
    for (int i = 0; i < nu; i++)
        if (strcmp(us[i].u->name, "texel") == 0)
            tx = &us[i];
    if (!tx) {
        if (nu >= 0)
            snprintf(err, errlen, "%s: the texel unit does not render the scene's texture (the tone's source)",
                     sc->name);
        return -1;
    }
    if (np_gbuf_shade(g, tx->u, &tx->cfg, NULL, rgb, NULL)) {
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    if (!sc->light_image) { /* the tone is the lit colour's, also when the images are unlit */
        np_gbuf_lightq q;
        np_gbuf_light_setup(sc, &q);
        q.on = 1;
        size_t ns = (size_t)g->w * g->h * g->n;
        for (size_t i = 0; i < ns; i++)
            if (g->poly[i] != NP_GBUF_NONE)
                np_gbuf_light(&q, g->normal[i], rgb + 3 * i);
    }
    return 0;
}

/* The unit's input words at pixel p of frame f with seed-space point (xu, xv): xu, xv, tone, pm, om. */
static void inputs(const np_hatch_frame *f, size_t p, uint64_t xu, uint64_t xv, uint64_t in[NP_UNIT_MAX_FIELDS])
{
    const np_hatch_lod *lod = &f->lod[f->poly[p]];
    memset(in, 0, NP_UNIT_MAX_FIELDS * sizeof *in);
    in[0] = xu;
    in[1] = xv;
    in[2] = f->tone[p];
    in[3] = lod->pm;
    in[4] = lod->om;
}

/* The unrolled cycle model fed every covered pixel back to back: its cycles; 1 in *bad when an output differs. */
static int run_pipe(const np_unit *u, const void *cfg, const np_hatch_frame *f, const uint64_t *xs, const size_t *pix,
                    size_t n, uint64_t *cycles, int *bad)
{
    np_pipe pipe;
    if (u->pipe_init(&pipe, cfg) != 0)
        return -1;
    void *in = calloc(1, pipe.sig_size);
    if (!in) {
        np_pipe_free(&pipe);
        return -1;
    }
    size_t a = 0, d = 0;
    while (d < n) {
        np_pipe_port port;
        memset(&port, 0, sizeof port);
        if (a < n) {
            uint64_t w[NP_UNIT_MAX_FIELDS];
            inputs(f, pix[a], xs[2 * a], xs[2 * a + 1], w);
            u->sig_set_in(in, w);
            port.in_valid = 1;
            port.in_sig = in;
        }
        port.out_ready = 1;
        np_pipe_eval(&pipe, &port);
        if (port.out_valid) {
            uint64_t o[NP_UNIT_MAX_FIELDS];
            u->sig_get_out(cfg, port.out_sig, o);
            *bad |= o[0] != f->rgb[3 * pix[d]];
            d++;
        }
        if (port.in_valid && port.in_ready)
            a++;
        np_pipe_clock(&pipe, &port);
    }
    *cycles = pipe.stats.cycles;
    np_pipe_free(&pipe);
    free(in);
    return 0;
}

int np_hatch_render(const np_scene *sc, const np_unit_cfg *cfgb, unsigned coverage, double tile_pixels,
                    unsigned flags, np_hatch_frame *f, char *err, size_t errlen)
{
    const np_unit *u = np_hatch_unit();
    const void *cfg = cfgb->bytes;
    np_gbuf g;
    void *cv = NULL;
    uint8_t *lit = NULL;
    uint64_t *xs = NULL;
    size_t *pix = NULL;
    int rc = -1;
    memset(f, 0, sizeof *f);
    if (!u) {
        snprintf(err, errlen, "the unit hatch is not in the registry");
        return -1;
    }
    const np_unit_strokes *st = u->strokes;
    const char *why = u->cfg_check ? u->cfg_check(cfg) : NULL;
    if (why) {
        snprintf(err, errlen, "hatch: %s", why);
        return -1;
    }
    np_unit_stroke_info info;
    st->info(cfg, &info);
    if (np_gbuf_build(sc, 1, &g, err, errlen))
        return -1;
    size_t npx = (size_t)g.w * g.h;
    f->w = g.w;
    f->h = g.h;
    f->rgb = malloc(npx * 3);
    f->tone = calloc(npx, 1);
    f->covered = calloc(npx, 1);
    f->lod = malloc((size_t)sc->n_prims * sizeof *f->lod);
    f->uv[0] = malloc(npx * sizeof(np_u128));
    f->uv[1] = malloc(npx * sizeof(np_u128));
    f->poly = malloc(npx * sizeof *f->poly);
    lit = malloc(npx * 3);
    xs = malloc(npx * 2 * sizeof *xs);
    pix = malloc(npx * sizeof *pix);
    if (!f->rgb || !f->tone || !f->covered || !f->lod || !f->uv[0] || !f->uv[1] || !f->poly || !lit || !xs || !pix) {
        snprintf(err, errlen, "out of memory");
        goto out;
    }
    if (lit_texture(&g, sc, lit, err, errlen))
        goto out;
    if (coverage && !(cv = st->cover_new(cfg, err, errlen)))
        goto out;
    for (uint32_t i = 0; i < sc->n_prims; i++)
        f->lod[i].level = INT32_MIN;
    f->level_min = INT32_MAX;
    f->level_max = INT32_MIN;
    for (size_t si = 0; si < g.n_spans; si++) {
        const np_gbuf_span *sp = &g.spans[si];
        np_hatch_lod *d = &f->lod[sp->r.poly];
        if (d->level == INT32_MIN)
            *d = span_lod(sp, tile_pixels);
    }
    uint8_t bg[3];
    for (int c = 0; c < 3; c++)
        bg[c] = (uint8_t)sc->background[c];
    f->brute_cycles = info.brute_cycles;
    uint64_t list_sum = 0;
    size_t n = 0;
    clock_t t0 = clock();
    for (size_t p = 0; p < npx; p++) {
        f->poly[p] = g.poly[p];
        if (g.poly[p] == NP_GBUF_NONE) {
            memcpy(f->rgb + 3 * p, bg, 3);
            continue;
        }
        const np_gbuf_span *sp = &g.spans[g.span[p]];
        const np_hatch_lod *d = &f->lod[g.poly[p]];
        const uint8_t *c = lit + 3 * p;
        uint32_t Y = (77u * c[0] + 150u * c[1] + 29u * c[2] + 128u) >> 8;
        uint32_t tone = 255u - Y;
        /* x_uv per span in 128 bits: x_uv0 + k dx_uv (Q32.96, UV mod 2^32). */
        uint64_t x[2];
        for (int a = 0; a < 2; a++) {
            np_u128 x0 = (np_u128)(np_s128)sp->r.hw.s[sp->uv[a]] << 64;
            np_u128 dx = (np_u128)(np_s128)sp->r.hw.ds[sp->uv[a]] << 64;
            np_u128 xu = x0 + (np_u128)g.k[p] * dx;
            f->uv[a][p] = xu;
            x[a] = st->xs(xu, d->level);
        }
        f->tone[p] = (uint8_t)tone;
        uint64_t in[NP_UNIT_MAX_FIELDS], out[NP_UNIT_MAX_FIELDS];
        inputs(f, p, x[0], x[1], in);
        if (cv) {
            unsigned cyc = 0, len[NP_UNIT_STROKE_LAYERS_MAX];
            out[0] = st->eval_cover(cfg, cv, in, &cyc, len);
            f->iter_cycles += cyc;
            for (unsigned l = 0; l < info.layers; l++) {
                list_sum += len[l];
                f->list_max = len[l] > f->list_max ? len[l] : f->list_max;
            }
        } else {
            u->eval(cfg, in, out);
            f->iter_cycles += info.brute_cycles;
        }
        if (flags & NP_HATCH_RENDER_REF) {
            double r, e;
            u->ref(cfg, in, &r);
            e = fabs((double)out[0] - r);
            f->ref_max = e > f->ref_max ? e : f->ref_max;
            f->ref_over += e > 1.0;
        }
        f->rgb[3 * p] = f->rgb[3 * p + 1] = f->rgb[3 * p + 2] = (uint8_t)out[0];
        f->covered[p] = 1;
        f->level_min = d->level < f->level_min ? d->level : f->level_min;
        f->level_max = d->level > f->level_max ? d->level : f->level_max;
        xs[2 * n] = x[0];
        xs[2 * n + 1] = x[1];
        pix[n++] = p;
    }
    f->seconds = (double)(clock() - t0) / CLOCKS_PER_SEC;
    f->samples = n;
    if (cv && n)
        f->list_mean = (double)list_sum / ((double)n * info.layers);
    /* The cycle model: brute force's, or the coverage unit's slots with the host's lists. */
    np_unit_cfg pc = *cfgb;
    np_unit_timing tm;
    if (cv)
        st->cover_cfg(pc.bytes, cv);
    if (!u->timing || u->timing(pc.bytes, &tm, err, errlen)) {
        if (!u->timing)
            snprintf(err, errlen, "hatch: the unit has no timing (its pipe's latency)");
        goto out;
    }
    f->pipe_depth = tm.latency;
    if ((flags & NP_HATCH_RENDER_PIPE) && run_pipe(u, pc.bytes, f, xs, pix, n, &f->pipe_cycles, &f->pipe_mismatch)) {
        snprintf(err, errlen, "out of memory");
        goto out;
    }
    rc = 0;
out:
    if (cv)
        st->cover_free(cv);
    free(lit);
    free(xs);
    free(pix);
    np_gbuf_free(&g);
    if (rc)
        np_hatch_frame_free(f);
    return rc;
}
