/* SPDX-License-Identifier: MIT */
/* The adaptive supersampling pipeline of seed 001 on the G-buffer (np_render_aa.h). */
#include "np_render_aa.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Y = (77 R + 150 G + 29 B + 128) >> 8 (u8; the weights sum to 256, so Y <= 255). */
static uint8_t luma_of(const uint8_t *rgb)
{
    return (uint8_t)((77u * rgb[0] + 150u * rgb[1] + 29u * rgb[2] + 128u) >> 8);
}

const np_unit *np_aa_unit(void)
{
    for (size_t i = 0; np_unit_at(i); i++) {
        const np_unit *u = np_unit_at(i);
        if (u->samples && u->samples->count)
            return u;
    }
    return NULL;
}

unsigned np_aa_key(const np_unit_cfg *c, const char *name)
{
    const np_unit *u = np_aa_unit();
    const np_unit_key *k = u ? np_unit_key_find(u, name) : NULL;
    return k ? np_unit_key_get(k, c->bytes) : 0u;
}

void np_aa_key_set(np_unit_cfg *c, const char *name, unsigned v)
{
    const np_unit *u = np_aa_unit();
    const np_unit_key *k = u ? np_unit_key_find(u, name) : NULL;
    if (k)
        np_unit_key_put(k, c->bytes, v);
}

void np_aa_cfg_from_scene(const np_scene *sc, unsigned m, double z_near, double z_far, np_unit_cfg *c)
{
    const np_unit *u = np_aa_unit();
    np_unit_scene us;
    memset(c, 0, sizeof *c);
    if (!u)
        return;
    np_scene_for_units(sc, &us);
    us.aa = &sc->aa; /* the section as the scene holds it, present or not (the tests set its constants) */
    u->samples->cfg_scene(c->bytes, &us, m, z_far - z_near);
}

void np_aa_frame_free(np_aa_frame *f)
{
    np_gbuf_free(&f->g);
    free(f->rgb_full);
    free(f->img_full);
    free(f->img_full_d);
    free(f->img_s);
    free(f->luma);
    free(f->covered);
    memset(f, 0, sizeof *f);
}

int np_aa_frame_build(const np_scene *sc, unsigned m, const np_render_unit_cfg *tex, const double *gt,
                      np_aa_frame *f, char *err, size_t errlen)
{
    memset(f, 0, sizeof *f);
    f->sc = sc;
    f->unit = np_aa_unit();
    f->tex = tex;
    if (!f->unit) {
        snprintf(err, errlen, "no unit of the registry counts samples (np_unit.samples->count)");
        return -1;
    }
    f->gt = gt;
    if (np_gbuf_build(sc, m, &f->g, err, errlen))
        return -1;
    const np_gbuf *g = &f->g;
    const size_t npx = (size_t)g->w * g->h;
    f->rgb_full = malloc(npx * g->n * 3);
    f->img_full = malloc(npx * 3);
    f->img_full_d = malloc(npx * 3 * sizeof *f->img_full_d);
    f->img_s = malloc(npx * 3);
    f->luma = malloc(npx);
    f->covered = malloc(npx);
    if (!f->rgb_full || !f->img_full || !f->img_full_d || !f->img_s || !f->luma || !f->covered) {
        snprintf(err, errlen, "out of memory");
        np_aa_frame_free(f);
        return -1;
    }
    if (np_gbuf_shade(g, tex->u, tex->cfg.bytes, NULL, f->rgb_full, &f->cost_full) ||
        np_gbuf_shade_first(g, tex->u, tex->cfg.bytes, f->img_s, &f->cost_s)) {
        snprintf(err, errlen, "shading on %s failed", tex->u->name);
        np_aa_frame_free(f);
        return -1;
    }
    np_gbuf_resolve(g, NULL, f->rgb_full, f->img_full);
    f->resolve_full_cycles = (uint64_t)npx * g->n + 2u; /* a sample a clock; the product and the add */
    for (size_t i = 0; i < npx * 3; i++)
        f->img_full_d[i] = f->img_full[i];
    for (size_t p = 0; p < npx; p++) {
        f->luma[p] = luma_of(&f->img_s[3 * p]);
        f->covered[p] = g->cover[p] > 0;
    }
    return 0;
}

void np_aa_result_free(np_aa_result *r)
{
    free(r->s);
    free(r->sd);
    free(r->sn);
    free(r->ss);
    free(r->img);
    memset(r, 0, sizeof *r);
}

/* The window of pixel (x, y): its n G-buffer samples and the five lumas, border-clamped. */
void np_aa_window(const np_aa_frame *f, unsigned x, unsigned y, np_unit_window *w)
{
    const np_gbuf *g = &f->g;
    const size_t p = (size_t)y * g->w + x;
    memset(w, 0, sizeof *w);
    for (unsigned j = 0; j < g->n; j++) {
        w->d[j] = f->g.depth[p * g->n + j];
        memcpy(w->nrm[j], f->g.normal[p * g->n + j], 3);
    }
    unsigned xl = x ? x - 1u : x, xr = x + 1u < g->w ? x + 1u : x;
    unsigned yu = y ? y - 1u : y, yd = y + 1u < g->h ? y + 1u : y;
    w->luma[0] = f->luma[p];
    w->luma[1] = f->luma[(size_t)y * g->w + xl];
    w->luma[2] = f->luma[(size_t)y * g->w + xr];
    w->luma[3] = f->luma[(size_t)yu * g->w + x];
    w->luma[4] = f->luma[(size_t)yd * g->w + x];
}

/* np_unit_samples.count_pipe's window source: window i in raster order. */
static void window_at(const void *ctx, size_t i, np_unit_window *w)
{
    const np_aa_frame *f = ctx;
    np_aa_window(f, (unsigned)(i % f->g.w), (unsigned)(i / f->g.w), w);
}

int np_aa_run(const np_aa_frame *f, const np_unit_cfg *c, const np_unit_cfg *regs, int shade, np_aa_result *r)
{
    const np_gbuf *g = &f->g;
    const np_unit_samples *u = f->unit->samples;
    const size_t npx = (size_t)g->w * g->h;
    memset(r, 0, sizeof *r);
    r->cfg = *c;
    u->set_m(r->cfg.bytes, g->m);
    np_unit_cfg rg;
    if (regs)
        rg = *regs;
    else
        u->regs(r->cfg.bytes, rg.bytes);
    r->s = malloc(npx);
    r->sd = malloc(npx);
    r->sn = malloc(npx);
    r->ss = malloc(npx);
    r->img = malloc(npx * 3);
    uint16_t *masks = malloc(npx * sizeof *masks);
    uint8_t *rgb = shade ? malloc(npx * g->n * 3) : NULL;
    if (!r->s || !r->sd || !r->sn || !r->ss || !r->img || !masks || (shade && !rgb)) {
        free(masks);
        free(rgb);
        np_aa_result_free(r);
        return -1;
    }
    /* 3. the unit, pixel by pixel in raster order */
    for (unsigned y = 0; y < g->h; y++)
        for (unsigned x = 0; x < g->w; x++) {
            np_unit_window w;
            np_unit_count o;
            np_aa_window(f, x, y, &w);
            u->count(r->cfg.bytes, rg.bytes, &w, &o);
            size_t p = (size_t)y * g->w + x;
            r->s[p] = o.s;
            r->sd[p] = o.sd;
            r->sn[p] = o.sn;
            r->ss[p] = o.ss;
        }
    /*
     * The parallel cycle model over the same windows (when the registers are
     * the keys'): its cycles, its s checked (no memory: no cycles, as before).
     */
    if (!regs)
        (void)u->count_pipe(r->cfg.bytes, window_at, f, npx, r->s, &r->unit_cycles, &r->pipe_mismatch);
    r->unit_cycles_serial = (uint64_t)npx * g->n + u->serial_latency(r->cfg.bytes);
    u->post(r->cfg.bytes, r->s, g->w, g->h);
    u->post(r->cfg.bytes, r->sd, g->w, g->h);
    u->post(r->cfg.bytes, r->sn, g->w, g->h);
    u->post(r->cfg.bytes, r->ss, g->w, g->h);
    const uint16_t first = u->mask(g->m, 1);
    for (size_t p = 0; p < npx; p++) {
        masks[p] = u->mask(g->m, r->s[p]);
        if (f->covered[p]) {
            r->covered_pixels++;
            r->samples += r->s[p];
            r->samples_d += r->sd[p];
            r->samples_n += r->sn[p];
            r->samples_s += r->ss[p];
        }
    }
    r->pct = r->covered_pixels ? 100.0 * (double)r->samples / ((double)g->n * (double)r->covered_pixels) : 0.0;
    /* 4. the chosen samples besides S's (S is shaded already), 5. the resolve */
    if (shade) {
        uint16_t *extra = malloc(npx * sizeof *extra);
        if (!extra) {
            free(masks);
            free(rgb);
            np_aa_result_free(r);
            return -1;
        }
        const unsigned j0 = (unsigned)__builtin_ctz(first);
        for (size_t p = 0; p < npx; p++) {
            extra[p] = (uint16_t)(masks[p] & ~first);
            memcpy(&rgb[3 * (p * g->n + j0)], &f->img_s[3 * p], 3);
        }
        int rc = np_gbuf_shade(g, f->tex->u, f->tex->cfg.bytes, extra, rgb, &r->shade_extra);
        free(extra);
        if (rc) {
            free(masks);
            free(rgb);
            np_aa_result_free(r);
            return -1;
        }
        r->shade_cycles = f->cost_s.cycles + r->shade_extra.cycles;
        np_gbuf_resolve(g, masks, rgb, r->img);
    } else {
        np_gbuf_resolve(g, masks, f->rgb_full, r->img);
    }
    r->resolve_cycles = 2u;
    for (size_t p = 0; p < npx; p++)
        r->resolve_cycles += r->s[p];
    r->mse_full = np_gbuf_mse(r->img, f->img_full_d, f->covered, npx);
    r->mse_gt = f->gt ? np_gbuf_mse(r->img, f->gt, f->covered, npx) : (double)NAN;
    free(masks);
    free(rgb);
    return 0;
}

int np_aa_colour_oracle(const np_aa_frame *f, double budget_spp, double *mse_gt, double *spp)
{
    const unsigned n = f->g.n;
    const size_t npx = (size_t)f->g.w * f->g.h;
    *mse_gt = (double)NAN;
    *spp = 0;
    if (!f->gt)
        return -1;
    double *e = malloc(npx * (n + 1) * sizeof *e), *ef = malloc(npx * (n + 1) * sizeof *ef);
    if (!e || !ef) {
        free(e);
        free(ef);
        return -1;
    }
    uint64_t cov = 0;
    for (size_t p = 0; p < npx; p++) {
        if (!f->covered[p])
            continue;
        cov++;
        for (unsigned s = 1; s <= n; s++) {
            const uint16_t mk = f->unit->samples->mask(f->g.m, s);
            double eg = 0, eo = 0;
            for (unsigned ch = 0; ch < 3; ch++) {
                uint32_t sum = 0;
                for (unsigned j = 0; j < n; j++)
                    if (((unsigned)mk >> j) & 1u)
                        sum += f->rgb_full[3 * (p * n + j) + ch];
                const double v = (double)f->unit->samples->resolve(sum, s);
                const double dg = (v - f->gt[3 * p + ch]) / 255.0, dfull = (v - (double)f->img_full[3 * p + ch]) / 255.0;
                eg += dg * dg;
                eo += dfull * dfull;
            }
            e[p * (n + 1) + s] = eg;
            ef[p * (n + 1) + s] = eo;
        }
    }
    for (int k = 0; cov && k <= 400; k++) {
        const double lambda = k == 0 ? 0.0 : 1e-7 * pow(10.0, (double)k / 50.0); /* 0, 1e-7 .. 1 */
        double sum_g = 0;
        uint64_t ssum = 0;
        for (size_t p = 0; p < npx; p++) {
            if (!f->covered[p])
                continue;
            const double *ep = ef + p * (n + 1);
            unsigned bs = 1;
            for (unsigned s = 2; s <= n; s++)
                if (ep[s] + lambda * s < ep[bs] + lambda * bs)
                    bs = s;
            sum_g += e[p * (n + 1) + bs];
            ssum += bs;
        }
        const double mse = sum_g / (3.0 * (double)cov), per = (double)ssum / (double)cov;
        if (per <= budget_spp && (*spp == 0 || mse < *mse_gt)) {
            *mse_gt = mse;
            *spp = per;
        }
    }
    free(e);
    free(ef);
    return *spp > 0 ? 0 : -1;
}
