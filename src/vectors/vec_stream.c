/* SPDX-License-Identifier: MIT */
/* Vectors of stream units: generation and the testbench loop (np_vec_stream.h; the format: np_stream.h). */
#include "np_vec_stream.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* --- Generation --- */

typedef struct gen_ctx {
    const np_vec_header *h;
    const np_unit_stream *st;
    np_vec_writer *w;   /* NULL: count only */
    unsigned n_w;
    uint64_t n;
    int failed;
} gen_ctx;

/* Emit beats k0 .. k0 + m - 1 of descriptor desc. */
static void emit_run(gen_ctx *g, const uint64_t *desc, uint64_t k0, uint64_t m)
{
    const unsigned nd = g->st->n_desc;
    for (uint64_t k = k0; k < k0 + m && !g->failed; k++) {
        if (g->w) {
            np_vec_rec rec;
            memset(&rec, 0, sizeof rec);
            rec.index = g->n;
            memcpy(rec.w[NP_VEC_IN], desc, nd * sizeof desc[0]);
            rec.w[NP_VEC_IN][nd] = k;
            np_vec_compute(g->h, rec.w[NP_VEC_IN], rec.w[NP_VEC_OUT], rec.w[NP_VEC_REF]);
            for (unsigned i = 0; i < g->n_w; i++)
                if (np_vec_writer_put(&g->w[i], &rec) != 0)
                    g->failed = 1;
        }
        g->n++;
    }
}

static void emit_desc(gen_ctx *g, const uint64_t *desc)
{
    uint64_t b = g->st->beats(&g->h->cfg, desc);
    if (b <= NP_STREAM_FULL) {
        emit_run(g, desc, 0, b);
    } else {
        emit_run(g, desc, 0, NP_STREAM_EDGE);
        emit_run(g, desc, b - NP_STREAM_EDGE, NP_STREAM_EDGE);
    }
}

/* Every case once; returns the descriptor counts through nd_out / nr_out. */
static void gen_all(gen_ctx *g, uint64_t (*bnd)[NP_UNIT_MAX_FIELDS], size_t nb, uint64_t seed, uint64_t n_random,
                    uint64_t *beats_bnd)
{
    np_rng rng;
    np_rng_seed(&rng, seed);
    for (size_t i = 0; i < nb; i++)
        emit_desc(g, bnd[i]);
    *beats_bnd = g->n;
    for (uint64_t i = 0; i < n_random; i++) {
        uint64_t d[NP_UNIT_MAX_FIELDS] = { 0 };
        g->st->random_desc(&g->h->cfg, &rng, d);
        emit_desc(g, d);
    }
}

int np_stream_generate(np_vec_header *h, unsigned level, uint64_t seed, uint64_t n_random,
                       const np_vec_output *outs, unsigned n_outs, char *err, size_t errlen)
{
    const np_unit_stream *st = h->unit->stream;
    if (!st) {
        snprintf(err, errlen, "unit %s is not a stream unit", h->unit->name);
        return -1;
    }
    if (n_outs < 1 || n_outs > NP_VEC_MAX_OUTPUTS) {
        snprintf(err, errlen, "1..%d outputs", NP_VEC_MAX_OUTPUTS);
        return -1;
    }
    if (n_random == UINT64_MAX)
        n_random = level >= 2 ? NP_STREAM_L2_RANDOM : NP_STREAM_L1_RANDOM;
    size_t nb = st->descriptors(&h->cfg, NULL, 0);
    uint64_t(*bnd)[NP_UNIT_MAX_FIELDS] = calloc(nb ? nb : 1, sizeof *bnd);
    np_vec_writer *w = calloc(n_outs, sizeof *w);
    if (!bnd || !w) {
        free(bnd);
        free(w);
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    st->descriptors(&h->cfg, bnd, nb);
    /* Count, then write: the header carries the count. */
    gen_ctx g = { h, st, NULL, 0, 0, 0 };
    uint64_t beats_bnd;
    gen_all(&g, bnd, nb, seed, n_random, &beats_bnd);
    h->seed = seed;
    h->has_seed = 1;
    h->level = level;
    h->count = g.n;
    snprintf(h->sources, sizeof h->sources, "stream: %zu annotated descriptors (%llu beats), %llu random (%llu beats)",
             nb, (unsigned long long)beats_bnd, (unsigned long long)n_random,
             (unsigned long long)(g.n - beats_bnd));
    unsigned opened = 0;
    int rc = 0;
    for (; opened < n_outs; opened++)
        if (np_vec_writer_open(&w[opened], outs[opened].path, outs[opened].fmt, h) != 0) {
            snprintf(err, errlen, "%s", w[opened].err);
            rc = -1;
            break;
        }
    if (rc == 0) {
        gen_ctx g2 = { h, st, w, n_outs, 0, 0 };
        gen_all(&g2, bnd, nb, seed, n_random, &beats_bnd);
        rc = g2.failed ? -1 : 0;
        if (rc)
            for (unsigned i = 0; i < n_outs; i++)
                if (w[i].err[0])
                    snprintf(err, errlen, "%s", w[i].err);
    }
    /* Every file appears only when all are complete. */
    for (unsigned i = 0; i < opened; i++)
        if (np_vec_writer_close(&w[i], rc == 0) != 0 && rc == 0) {
            snprintf(err, errlen, "%s", w[i].err);
            rc = -1;
        }
    free(bnd);
    free(w);
    return rc;
}

/* --- The testbench loop --- */

/* A run of beats: consecutive transactions of one descriptor with consecutive k. */
typedef struct run {
    np_vec_rec *rec;
    size_t m, cap;
    uint64_t k0;
    uint64_t desc[NP_UNIT_MAX_FIELDS]; /* as presented: length cut to k0 + m */
    uint64_t next_beat;                /* beats delivered by the model so far */
    uint64_t in_cycle;
} run;

typedef struct bench {
    const np_vec_header *h;
    const np_unit_stream *st;
    np_vec_source_fn source;
    void *ctx;
    np_vec_rec look;   /* the record that ended the last run */
    int have_look, eof;
    run *q;            /* runs accepted by the model and not yet fully delivered, then the presented one */
    size_t qn, qcap;
    int presented;     /* the last run in q is presented, not accepted */
} bench;

static int same_desc(const bench *b, const np_vec_rec *a, const np_vec_rec *c)
{
    return memcmp(a->w[NP_VEC_IN], c->w[NP_VEC_IN], b->st->n_desc * sizeof(uint64_t)) == 0;
}

static int run_push(run *r, const np_vec_rec *rec)
{
    if (r->m == r->cap) {
        size_t nc = r->cap ? 2 * r->cap : 16;
        np_vec_rec *nr = realloc(r->rec, nc * sizeof *nr);
        if (!nr)
            return -1;
        r->rec = nr;
        r->cap = nc;
    }
    r->rec[r->m++] = *rec;
    return 0;
}

/* Read the next run into a new queue slot: 1, 0 at the end, -1 on bad input or no memory. */
static int next_run(bench *b)
{
    np_vec_rec rec;
    if (b->have_look) {
        rec = b->look;
        b->have_look = 0;
    } else {
        if (b->eof)
            return 0;
        int r = b->source(b->ctx, &rec);
        if (r <= 0) {
            b->eof = 1;
            return r;
        }
    }
    if (b->qn == b->qcap) {
        size_t nc = b->qcap ? 2 * b->qcap : 8;
        run *nq = realloc(b->q, nc * sizeof *nq);
        if (!nq)
            return -1;
        b->q = nq;
        b->qcap = nc;
    }
    run *rn = &b->q[b->qn];
    memset(rn, 0, sizeof *rn);
    const unsigned nd = b->st->n_desc;
    rn->k0 = rec.w[NP_VEC_IN][nd];
    if (run_push(rn, &rec))
        return -1;
    for (;;) {
        int r = b->source(b->ctx, &b->look);
        if (r < 0)
            return -1;
        if (r == 0) {
            b->eof = 1;
            break;
        }
        if (!same_desc(b, &b->look, &rn->rec[rn->m - 1]) ||
            b->look.w[NP_VEC_IN][nd] != rn->rec[rn->m - 1].w[NP_VEC_IN][nd] + 1u) {
            b->have_look = 1;
            break;
        }
        if (run_push(rn, &b->look))
            return -1;
    }
    memcpy(rn->desc, rec.w[NP_VEC_IN], nd * sizeof rn->desc[0]);
    rn->desc[b->st->length_field] = rn->k0 + rn->m;
    b->qn++;
    return 1;
}

static void run_free(run *r) { free(r->rec); }

enum { WATCHDOG = 1000000 };

int np_stream_drive(const np_vec_header *h, np_vec_source_fn source, void *src_ctx, np_vec_sink_fn sink,
                    void *sink_ctx, int traffic, uint64_t seed, np_vec_drive_stats *st, char *err, size_t errlen)
{
    const np_unit_stream *us = h->unit->stream;
    memset(st, 0, sizeof *st);
    if (!us) {
        snprintf(err, errlen, "unit %s is not a stream unit", h->unit->name);
        return NP_DRIVE_MODEL;
    }
    void *state = calloc(1, us->state_size);
    if (!state || us->init(state, &h->cfg) != 0) {
        free(state);
        snprintf(err, errlen, "cannot build the stream model of %s: out of memory", h->unit->name);
        return NP_DRIVE_MODEL;
    }
    bench b;
    memset(&b, 0, sizeof b);
    b.h = h;
    b.st = us;
    b.source = source;
    b.ctx = src_ctx;
    np_rng rng;
    np_rng_seed(&rng, seed);
    uint64_t cycle = 0, last = 0, phase = 0;
    unsigned p_gap = 0, p_stall = 0;
    int rc = NP_DRIVE_DONE;
    size_t head = 0; /* oldest run still delivering */
    for (;;) {
        if (head > 256) { /* drop delivered runs from the queue */
            memmove(b.q, b.q + head, (b.qn - head) * sizeof *b.q);
            b.qn -= head;
            head = 0;
        }
        if (traffic) {
            if (phase == 0) {
                uint64_t r = np_rng_next(&rng);
                static const unsigned dens[4] = { 0, 32, 128, 224 };
                phase = 16u + r % 256u;
                p_gap = dens[(r >> 8) & 3u];
                p_stall = dens[(r >> 10) & 3u];
            }
            phase--;
        }
        uint64_t r = traffic ? np_rng_next(&rng) : 0;
        int gap = traffic && (unsigned)(r & 255u) < p_gap, stall = traffic && (unsigned)((r >> 8) & 255u) < p_stall;
        if (!b.presented && !gap) {
            int k = next_run(&b);
            if (k < 0) {
                rc = NP_DRIVE_BAD_INPUT;
                break;
            }
            b.presented = k > 0;
        }
        if (!b.presented && b.eof && head == b.qn && us->idle(state))
            break;
        np_unit_stream_port p;
        memset(&p, 0, sizeof p);
        p.in_valid = b.presented;
        p.in = b.presented ? b.q[b.qn - 1].desc : NULL;
        p.out_ready = !stall;
        us->eval(state, &p);
        if (p.out_valid && p.out_ready) {
            if (head >= b.qn - (b.presented ? 1u : 0u)) {
                snprintf(err, errlen, "cycle %llu: the model delivered a beat no descriptor asked for",
                         (unsigned long long)cycle);
                rc = NP_DRIVE_MODEL;
                break;
            }
            run *rn = &b.q[head];
            uint64_t beat = rn->next_beat++;
            last = cycle;
            if (beat >= rn->k0) {
                const np_vec_rec *rec = &rn->rec[beat - rn->k0];
                uint64_t clocks = cycle - rn->in_cycle;
                np_vec_timing tm = { (unsigned)(clocks > 0xffffffffu ? 0xffffffffu : clocks), clocks, 0 };
                st->delivered++;
                if (sink(sink_ctx, rec, p.out, &tm)) {
                    rc = NP_DRIVE_STOPPED;
                    break;
                }
            }
            if (rn->next_beat >= rn->k0 + rn->m) {
                run_free(rn);
                rn->rec = NULL;
                head++;
            }
        }
        if (p.out_valid && !p.out_ready)
            st->stalls++;
        if (p.in_valid && p.in_ready) {
            b.q[b.qn - 1].in_cycle = cycle;
            st->accepted += b.q[b.qn - 1].m;
            b.presented = 0;
            last = cycle;
        } else if (!p.in_valid && !b.eof) {
            st->bubbles++;
        }
        us->clock(state, &p);
        cycle++;
        if (cycle - last > WATCHDOG) {
            snprintf(err, errlen, "cycle %llu: the stream model made no transfer for %d clocks",
                     (unsigned long long)cycle, WATCHDOG);
            rc = NP_DRIVE_MODEL;
            break;
        }
    }
    st->cycles = cycle;
    for (size_t i = 0; i < b.qn; i++)
        run_free(&b.q[i]);
    free(b.q);
    us->free(state);
    free(state);
    return rc;
}
