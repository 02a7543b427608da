/* SPDX-License-Identifier: MIT */
/* A span unit's render of a frame (bit-exact and cycle-accurate) and its error against the reference (np_render.h). */
#include "np_render.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "np_common.h"
#include "np_gbuf.h"
#include "unit_span.h"

/* Round half up to 8 bits: the units' colour stage rounding (np_tex_colour_round). */
static uint8_t round8(double v) { return (uint8_t)floor(v + 0.5); }

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
            run->rgb[3 * i + (size_t)ch] = round8(sc->background[ch]);
    return 0;
}

static void put_pixels(const np_scene *sc, uint8_t *img, const np_tex_pixel *px, uint32_t n)
{
    for (uint32_t k = 0; k < n; k++)
        memcpy(img + ((size_t)px[k].y * sc->width + px[k].x) * 3, px[k].rgb, 3);
}

/*
 * The scene's light on a unit's image (np_gbuf.h "Lighting", scene key
 * light.image): each span's pixels lit with its polygon's quantised normal,
 * as the G-buffer renderer lights a sample. Nothing without light.image.
 */
static void light_frame(const np_render_frame *fr, uint8_t *rgb)
{
    np_gbuf_lightq q;
    np_gbuf_light_setup(fr->sc, &q);
    if (!q.on)
        return;
    uint32_t last = NP_GBUF_NONE;
    int8_t nq[3] = { 0, 0, 0 };
    for (size_t i = 0; i < fr->n_spans; i++) {
        const np_rspan *s = &fr->spans[i];
        if (s->poly != last) {
            double n[3];
            np_gbuf_poly_normal(fr->sc, s->poly, n, nq);
            last = s->poly;
        }
        uint8_t *px = rgb + ((size_t)s->hw.y * fr->sc->width + s->hw.x0) * 3;
        for (uint32_t k = 0; k < s->hw.n; k++)
            np_gbuf_light(&q, nq, px + 3 * (size_t)k);
    }
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

/* The frame's spans through the engine's cycle-accurate model (np_span_sim): its image into c, statistics into st. */
static int run_cycles(const np_render_frame *fr, const np_span_engine *e, const void *ecfg, np_render_run *c,
                      np_span_stats *st)
{
    np_span_sim m;
    if (np_span_sim_init(&m, e, ecfg, &fr->regs))
        return -1;
    size_t next = 0;
    uint64_t limit = (fr->pixels + fr->n_spans + 16u) * CYCLE_LIMIT_PER_PIXEL, shown = 0;
    char label[64];
    snprintf(label, sizeof label, "render: %s cycle model, spans", e->name);
    np_progress pr;
    np_progress_start(&pr, label, fr->n_spans);
    while ((next < fr->n_spans || !np_span_sim_idle(&m)) && m.stats.cycles < limit) {
        if (next != shown) {
            shown = next;
            np_progress_update(&pr, next);
        }
        np_span_port p;
        memset(&p, 0, sizeof p);
        p.in_valid = next < fr->n_spans;
        p.in = p.in_valid ? &fr->spans[next].hw : NULL;
        p.out_ready = 1;
        np_span_sim_eval(&m, &p);
        if (p.out_valid)
            put_pixels(fr->sc, c->rgb, &p.out, 1);
        if (p.in_valid && p.in_ready)
            next++;
        np_span_sim_clock(&m, &p);
    }
    np_progress_end(&pr);
    *st = m.stats;
    np_span_sim_free(&m);
    return 0;
}

int np_render_engine(const np_render_frame *fr, const np_span_engine *e, const void *ecfg, int cycles,
                     np_render_run *run)
{
    if (run_alloc(fr, run))
        return -1;
    np_tex_pixel *px = malloc(((size_t)fr->longest + 1) * sizeof *px);
    void *core = malloc(e->core_size), *sig = malloc(e->sig_size);
    if (!px || !core || !sig) {
        free(px);
        free(core);
        free(sig);
        return -1;
    }
    np_span_counts cnt;
    memset(&cnt, 0, sizeof cnt);
    e->init(core, ecfg, &fr->regs);
    char label[64];
    snprintf(label, sizeof label, "render: %s bit-exact model, spans", e->name);
    np_progress pr;
    np_progress_start(&pr, label, fr->n_spans);
    double t0 = np_now();
    for (size_t i = 0; i < fr->n_spans; i++) {
        np_span_run(e, core, sig, &fr->spans[i].hw, px, &cnt, NULL, NULL);
        put_pixels(fr->sc, run->rgb, px, fr->spans[i].hw.n);
        np_progress_update(&pr, i + 1u);
    }
    run->model_seconds = np_now() - t0;
    np_progress_end(&pr);
    light_frame(fr, run->rgb);
    free(px);
    free(core);
    free(sig);
    run->span_setups = cnt.span_setups;
    run->cell_setups = cnt.cell_setups;
    run->interval_setups = cnt.interval_setups;
    if (cycles) {
        np_render_run c;
        np_span_stats st;
        if (run_alloc(fr, &c))
            return -1;
        t0 = np_now();
        if (run_cycles(fr, e, ecfg, &c, &st)) {
            free(c.rgb);
            return -1;
        }
        run->cycle_seconds = np_now() - t0;
        light_frame(fr, c.rgb);
        run->have_cycles = 1;
        run->cycles = st.cycles;
        run->setup_stalls = st.setup_stalls;
        run->out_stalls = st.out_stalls;
        run->cycle_mismatch = count_diff(fr, run->rgb, c.rgb) + (st.counts.pixels != fr->pixels ? 1u : 0u) +
                              (st.counts.span_setups != cnt.span_setups || st.counts.cell_setups != cnt.cell_setups ||
                                       st.counts.interval_setups != cnt.interval_setups
                                   ? 1u
                                   : 0u);
        free(c.rgb);
    }
    np_render_error(fr, run->rgb, &run->err);
    return 0;
}

int np_render_unit(const np_render_frame *fr, const np_unit *u, const void *cfg, int cycles, np_render_run *run)
{
    if (!u->span)
        return -1;
    if (fr->sc->size_registers) {
        /* Registers sized by the scene: the unit's texture as its cfg_scene compiled it, not the frame's defaults. */
        np_render_frame f = *fr;
        f.regs = *np_ut_regs(np_su_texture(u->span, cfg));
        return np_render_engine(&f, u->span->engine, np_unit_span_cfg(u->span, cfg), cycles, run);
    }
    return np_render_engine(fr, u->span->engine, np_unit_span_cfg(u->span, cfg), cycles, run);
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
            int cr = abs((int)rgb[3 * i + ch] - (int)round8(fr->ref[3 * i + ch]));
            e->over_cr += cr != 0;
            if ((unsigned)cr > e->max_cr)
                e->max_cr = (unsigned)cr;
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
        rgb[i] = round8(fr->ref[i]);
}

