/* SPDX-License-Identifier: MIT */
/* One scanline's noise, forward differences against per pixel (np_report_scan.h; the seed's figures 10 and 11). */
#include "np_report_scan.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "np_texel.h"
#include "np_texreg.h"

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
