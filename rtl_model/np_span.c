/* SPDX-License-Identifier: MIT */
/* The span sequencer and the colour stages every span unit shares (np_span.h). */
#include "np_span.h"

#include <stdlib.h>
#include <string.h>

/* --- Colour stages --- */

static np_span_sig *head(void *sig) { return (np_span_sig *)sig; }

void np_span_stage_c1(const void *cv, void *sv)
{
    const np_span_ctx *c = cv;
    np_span_sig *s = head(sv);
    np_tex_colour_split(c->r, s->x, c->F, c->fw, &s->seg, &s->cw);
}

void np_span_stage_c2(const void *cv, void *sv)
{
    const np_span_ctx *c = cv;
    np_span_sig *s = head(sv);
    np_tex_colour_mix(c->r, s->seg, s->cw, c->fw, s->prod);
}

void np_span_stage_c3(const void *cv, void *sv)
{
    const np_span_ctx *c = cv;
    np_span_sig *s = head(sv);
    np_tex_colour_round(s->prod, c->fw, s->pix.rgb);
}

const np_stage_desc np_span_colour_stages[NP_SPAN_COLOUR_STAGES] = {
    { "C1", np_span_stage_c1 }, { "C2", np_span_stage_c2 }, { "C3", np_span_stage_c3 },
};

/* Pixel k of span sp into a cleared bundle. */
static void issue(const np_span_engine *e, const void *core, void *sig, const np_span *sp, uint32_t k)
{
    memset(sig, 0, e->sig_size);
    e->issue(core, sig);
    head(sig)->pix.x = (uint16_t)(sp->x0 + k);
    head(sig)->pix.y = sp->y;
}

/* --- Bit-exact model --- */

void np_span_run(const np_span_engine *e, void *core, void *sig, const np_span *sp, np_tex_pixel *out,
                 np_span_counts *cnt, np_span_probe_fn probe, const void *pctx)
{
    const np_span_ctx *ctx = np_span_ctx_of(core);
    np_span_counts dummy;
    if (!cnt) {
        memset(&dummy, 0, sizeof dummy);
        cnt = &dummy;
    }
    /* The span run alone: accepted at clock 0, pixel k issued at clock t. */
    np_span_ctx *clk = (np_span_ctx *)core;
    clk->now = 0;
    uint64_t t = 1u + e->begin(core, sp, cnt);
    for (uint32_t k = 0; k < sp->n; k++) {
        issue(e, core, sig, sp, k);
        for (unsigned st = 0; st < e->n_stages; st++)
            e->stages[st].fn(ctx, sig);
        out[k] = head(sig)->pix;
        if (probe)
            probe(pctx, core, sig, k);
        cnt->pixels++;
        clk->now = t;
        t += 1u + e->advance(core, cnt);
    }
}

/* --- Cycle-accurate model --- */

int np_span_sim_init(np_span_sim *m, const np_span_engine *e, const void *cfg, const np_tex_regs *r)
{
    memset(m, 0, sizeof *m);
    m->eng = e;
    m->core = calloc(1, e->core_size);
    m->pending = calloc(1, e->sig_size);
    if (!m->core || !m->pending) {
        np_span_sim_free(m);
        return -1;
    }
    e->init(m->core, cfg, r);
    ((np_span_ctx *)m->core)->timed = 1;
    if (np_pipe_init(&m->pipe, e->stages, e->n_stages, e->sig_size, np_span_ctx_of(m->core)) != 0) {
        np_span_sim_free(m);
        return -1;
    }
    return 0;
}

void np_span_sim_free(np_span_sim *m)
{
    np_pipe_free(&m->pipe);
    free(m->core);
    free(m->pending);
    m->core = m->pending = NULL;
}

void np_span_sim_reset(np_span_sim *m)
{
    const np_span_ctx c = *np_span_ctx_of(m->core);
    np_pipe_reset(&m->pipe);
    m->eng->init(m->core, c.cfg, c.r);
    ((np_span_ctx *)m->core)->timed = 1;
    m->busy = 0;
    m->has_next = 0;
    m->stall = 0;
    m->k = 0;
    memset(&m->stats, 0, sizeof m->stats);
}

void np_span_sim_eval(np_span_sim *m, np_span_port *p)
{
    p->in_ready = m->eng->prefetch ? !m->has_next : !m->busy;
    m->pport.in_valid = m->busy && m->stall == 0;
    if (m->pport.in_valid)
        issue(m->eng, m->core, m->pending, &m->sp, m->k);
    m->pport.in_sig = m->pending;
    m->pport.out_ready = p->out_ready;
    np_pipe_eval(&m->pipe, &m->pport);
    p->out_valid = m->pport.out_valid;
    if (p->out_valid)
        p->out = ((const np_span_sig *)m->pport.out_sig)->pix;
}

/* Load span sp into the engine (clock: the current one). */
static void sim_begin(np_span_sim *m, const np_span *sp)
{
    m->sp = *sp;
    m->k = 0;
    m->stall = m->eng->begin(m->core, &m->sp, &m->stats.counts);
    m->busy = m->sp.n > 0;
}

void np_span_sim_clock(np_span_sim *m, const np_span_port *p)
{
    np_span_stats *st = &m->stats;
    ((np_span_ctx *)m->core)->now = st->cycles;
    st->cycles++;
    int issued = m->pport.in_valid && m->pport.in_ready;
    int accept = p->in_valid && p->in_ready;
    np_pipe_clock(&m->pipe, &m->pport); /* reads the pending bundle */
    if (m->busy) {
        if (accept) { /* only with prefetch: into the buffer, its set-up may start */
            m->next = *p->in;
            m->has_next = 1;
            m->eng->prefetch(m->core, &m->next);
            accept = 0;
        }
        if (m->stall > 0) {
            m->stall--;
            st->setup_stalls++;
        } else if (issued) {
            st->counts.pixels++;
            m->stall = m->eng->advance(m->core, &st->counts);
            if (++m->k >= m->sp.n) {
                m->busy = 0;
                /* The buffered span begins in this clock (and an empty one leaves the unit idle). */
                if (m->has_next) {
                    m->has_next = 0;
                    sim_begin(m, &m->next);
                }
            }
        } else {
            st->out_stalls++;
        }
    } else if (accept) {
        sim_begin(m, p->in);
    } else if (m->has_next) {
        m->has_next = 0;
        sim_begin(m, &m->next);
    } else {
        st->idle++;
    }
}

int np_span_sim_idle(const np_span_sim *m) { return !m->busy && !m->has_next && np_pipe_occupancy(&m->pipe) == 0; }
