/* SPDX-License-Identifier: MIT */
/*
 * vecgen.c - the cases of a golden vector file, TestFloat style, from three
 * sources: the unit's hand-annotated boundary table, bit patterns per input
 * field, and weighted random values from our own seeded generator (np_rng).
 *
 * Each source is an index space walked in order; decode() turns an index into
 * an input tuple or says the index is skipped (a duplicate or a pattern that
 * does not fit the field). Counting and generating both go through decode(),
 * so the header's count and the file agree by construction. Nothing here
 * depends on the machine: same unit, configuration, level, seed and random
 * count give the same cases in the same order.
 *
 * Bit patterns of a w-bit field, with W the widest input field (so that the
 * lock-step source moves the same bit in every field):
 *
 *   k = 0            all zeros          k = 4 + j       walking one, bit j
 *   k = 1            all ones           k = 4 + W + j   walking zero, bit j
 *   k = 2            ...0101 (0x5555)   (0 <= j < W; bits at or above w are
 *   k = 3            ...1010 (0xaaaa)    dropped, so a narrow field reads 0 / ones)
 *
 * k < 4 are the "uniform" patterns, used as backgrounds.
 */
#include "np_vec.h"
#include "np_vec_stream.h"

#include <stdlib.h>
#include <string.h>

#include "np_common.h"

enum { N_UNIFORM = 4 };

static uint64_t pattern(unsigned w, unsigned W, uint64_t k)
{
    const uint64_t m = np_vec_mask(w);
    switch (k) {
    case 0: return 0;
    case 1: return m;
    case 2: return 0x5555555555555555u & m;
    case 3: return 0xaaaaaaaaaaaaaaaau & m;
    default: break;
    }
    uint64_t j = k - N_UNIFORM;
    if (j < W)
        return j < w ? (uint64_t)1 << j : 0;
    j -= W;
    return j < w ? m & ~((uint64_t)1 << j) : m;
}

/* Is pattern k one of a w-bit field's own (a uniform one, or its walking bit inside the field)? */
static int pattern_fits(unsigned w, unsigned W, uint64_t k)
{
    if (k < N_UNIFORM)
        return 1;
    uint64_t j = (k - N_UNIFORM) % W;
    return j < w;
}

static unsigned n_in(const np_vecgen *g) { return g->h->fields.n_in; }
static unsigned in_bits(const np_vecgen *g, unsigned f) { return g->h->fields.in[f].bits; }
static uint64_t n_patterns(const np_vecgen *g) { return N_UNIFORM + 2u * (uint64_t)g->pat_w; }
static uint64_t n_walking(const np_vecgen *g) { return 2u * (uint64_t)g->pat_w; }

/* Every input field at background pattern b. */
static void background(const np_vecgen *g, uint64_t b, uint64_t *in)
{
    for (unsigned f = 0; f < n_in(g); f++)
        in[f] = pattern(in_bits(g, f), g->pat_w, b);
}

/*
 * Boundary: the unit's table; at level 2 each case is followed by its
 * neighbours with one field moved by -1 and +1 (modulo its width).
 */
static int dec_boundary(const np_vecgen *g, uint64_t i, uint64_t *in)
{
    uint64_t per = g->level >= 2 ? 1u + 2u * (uint64_t)n_in(g) : 1u;
    uint64_t t = i / per, m = i % per;
    for (unsigned f = 0; f < n_in(g); f++)
        in[f] = g->bnd[t][f] & np_vec_mask(in_bits(g, f));
    if (m > 0) {
        unsigned f = (unsigned)((m - 1u) / 2u);
        uint64_t step = (m - 1u) % 2u ? 1u : ~(uint64_t)0; /* +1 or -1 */
        in[f] = (in[f] + step) & np_vec_mask(in_bits(g, f));
    }
    return 1;
}

/*
 * Walk: field f takes each of its patterns while every other field holds
 * background b (a uniform pattern). The all-background tuple is emitted
 * once, for f = 0.
 */
static int dec_walk(const np_vecgen *g, uint64_t i, uint64_t *in)
{
    uint64_t np = n_patterns(g);
    uint64_t k = i % np, b = i / np / n_in(g);
    unsigned f = (unsigned)(i / np % n_in(g));
    if (!pattern_fits(in_bits(g, f), g->pat_w, k) || (k == b && f > 0))
        return 0;
    background(g, b, in);
    in[f] = pattern(in_bits(g, f), g->pat_w, k);
    return 1;
}

/* Step: every field takes walking pattern k at once (only with several fields). */
static int dec_step(const np_vecgen *g, uint64_t i, uint64_t *in)
{
    if (n_in(g) < 2)
        return 0;
    background(g, N_UNIFORM + i, in);
    return 1;
}

/* Pair number p (0-based, in order (0,1), (0,2), ..., (1,2), ...) as fields a < b. */
static void pair_of(unsigned n, uint64_t p, unsigned *a, unsigned *b)
{
    for (*a = 0; *a + 1u < n; (*a)++) {
        uint64_t row = n - 1u - *a;
        if (p < row) {
            *b = *a + 1u + (unsigned)p;
            return;
        }
        p -= row;
    }
}

/*
 * Pair (level 2): two fields cross all their walking patterns while the
 * others hold background b; with only two fields, background 0 alone.
 */
static int dec_pair(const np_vecgen *g, uint64_t i, uint64_t *in)
{
    uint64_t nw = n_walking(g), n_pairs = (uint64_t)n_in(g) * (n_in(g) - 1u) / 2u;
    uint64_t kb = N_UNIFORM + i % nw, ka = N_UNIFORM + i / nw % nw;
    uint64_t p = i / (nw * nw) % n_pairs, b = i / (nw * nw * n_pairs);
    unsigned fa = 0, fb = 1;
    pair_of(n_in(g), p, &fa, &fb);
    if (!pattern_fits(in_bits(g, fa), g->pat_w, ka) || !pattern_fits(in_bits(g, fb), g->pat_w, kb) ||
        (n_in(g) == 2 && b > 0))
        return 0;
    background(g, b, in);
    in[fa] = pattern(in_bits(g, fa), g->pat_w, ka);
    in[fb] = pattern(in_bits(g, fb), g->pat_w, kb);
    return 1;
}

/*
 * A weighted random w-bit value: 1/2 uniform; 1/4 uniform with its low j
 * bits (j uniform in 1..w) forced to all zeros or all ones (carry chains,
 * fraction edges); 1/4 small, uniform below 2^j (j in 0..w), complemented
 * half of the time (near zero, near all ones / -1).
 */
static uint64_t random_value(np_rng *r, unsigned w)
{
    uint64_t sel = np_rng_next(r);
    uint64_t v = np_rng_next(r) & np_vec_mask(w);
    switch (sel & 3u) {
    case 2: {
        uint64_t low = np_vec_mask((unsigned)(1u + np_rng_below(r, w)));
        return (sel & 4u) ? v | low : v & ~low;
    }
    case 3: {
        unsigned j = (unsigned)np_rng_below(r, (uint64_t)w + 1u);
        v = j ? v & np_vec_mask(j) : 0;
        return (sel & 4u) ? ~v & np_vec_mask(w) : v;
    }
    default: return v;
    }
}

static int dec_random(np_vecgen *g, uint64_t i, uint64_t *in)
{
    (void)i;
    for (unsigned f = 0; f < n_in(g); f++)
        in[f] = random_value(&g->rng, in_bits(g, f));
    return 1;
}

/* Input tuple number i of source src into in: 1, or 0 when that index is skipped. */
static int decode(np_vecgen *g, np_vecgen_src src, uint64_t i, uint64_t *in)
{
    switch (src) {
    case NP_VECGEN_BOUNDARY: return dec_boundary(g, i, in);
    case NP_VECGEN_WALK: return dec_walk(g, i, in);
    case NP_VECGEN_STEP: return dec_step(g, i, in);
    case NP_VECGEN_PAIR: return dec_pair(g, i, in);
    case NP_VECGEN_RANDOM: return dec_random(g, i, in);
    default: return 0;
    }
}

/* Load the unit's boundary table. 0, or -1 when out of memory. */
static int load_boundary(np_vecgen *g)
{
    const np_unit *u = g->h->unit;
    if (!u->boundary)
        return 0;
    size_t n = u->boundary(&g->h->cfg, NULL, 0);
    if (n == 0)
        return 0;
    g->bnd = calloc(n, sizeof *g->bnd);
    if (!g->bnd)
        return -1;
    g->n_bnd = u->boundary(&g->h->cfg, g->bnd, n);
    return 0;
}

int np_vecgen_init(np_vecgen *g, const np_vec_header *h, unsigned level, uint64_t seed,
                   uint64_t n_random, char *err, size_t errlen)
{
    memset(g, 0, sizeof *g);
    g->h = h;
    g->level = level;
    if (load_boundary(g) != 0) {
        snprintf(err, errlen, "out of memory for the boundary table");
        return -1;
    }
    for (unsigned f = 0; f < n_in(g); f++)
        if (in_bits(g, f) > g->pat_w)
            g->pat_w = in_bits(g, f);
    uint64_t nw = n_walking(g), n_pairs = (uint64_t)n_in(g) * (n_in(g) - 1u) / 2u;
    g->space[NP_VECGEN_BOUNDARY] = g->n_bnd * (level >= 2 ? 1u + 2u * (uint64_t)n_in(g) : 1u);
    g->space[NP_VECGEN_WALK] = N_UNIFORM * (uint64_t)n_in(g) * n_patterns(g);
    g->space[NP_VECGEN_STEP] = nw;
    g->space[NP_VECGEN_PAIR] = level >= 2 ? N_UNIFORM * n_pairs * nw * nw : 0;
    g->space[NP_VECGEN_RANDOM] = n_random != UINT64_MAX ? n_random
                                 : level >= 2         ? NP_VEC_L2_RANDOM
                                                      : NP_VEC_L1_RANDOM;
    uint64_t in[NP_UNIT_MAX_FIELDS];
    for (unsigned s = 0; s < NP_VECGEN_RANDOM; s++)
        for (uint64_t i = 0; i < g->space[s]; i++)
            g->count[s] += (uint64_t)decode(g, (np_vecgen_src)s, i, in);
    g->count[NP_VECGEN_RANDOM] = g->space[NP_VECGEN_RANDOM];
    np_rng_seed(&g->rng, seed);
    return 0;
}

uint64_t np_vecgen_total(const np_vecgen *g)
{
    uint64_t t = 0;
    for (unsigned s = 0; s < NP_VECGEN_NSRC; s++)
        t += g->count[s];
    return t;
}

int np_vecgen_next(np_vecgen *g, np_vec_rec *rec)
{
    while (g->src < NP_VECGEN_NSRC) {
        if (g->i == g->space[g->src]) {
            g->src++;
            g->i = 0;
            continue;
        }
        if (!decode(g, g->src, g->i++, rec->w[NP_VEC_IN]))
            continue;
        rec->index = g->seq++;
        rec->line = 0;
        np_vec_compute(g->h, rec->w[NP_VEC_IN], rec->w[NP_VEC_OUT], rec->w[NP_VEC_REF]);
        return 1;
    }
    return 0;
}

void np_vecgen_free(np_vecgen *g)
{
    free(g->bnd);
    g->bnd = NULL;
}

int np_vec_generate(np_vec_header *h, unsigned level, uint64_t seed, uint64_t n_random,
                    const np_vec_output *outs, unsigned n_outs, char *err, size_t errlen)
{
    /* Stream units (span descriptors in, pixels out) have their own generator. */
    if (h->unit->stream)
        return np_stream_generate(h, level, seed, n_random, outs, n_outs, err, errlen);
    np_vecgen g;
    np_vec_rec rec;
    unsigned opened = 0;
    np_vec_writer *w = n_outs <= NP_VEC_MAX_OUTPUTS ? calloc(n_outs, sizeof *w) : NULL;
    if (!w) {
        snprintf(err, errlen, n_outs > NP_VEC_MAX_OUTPUTS ? "too many outputs" : "out of memory");
        return -1;
    }
    if (np_vecgen_init(&g, h, level, seed, n_random, err, errlen) != 0) {
        free(w);
        return -1;
    }
    h->seed = seed;
    h->has_seed = 1;
    h->level = level;
    h->count = np_vecgen_total(&g);
    snprintf(h->sources, sizeof h->sources,
             "boundary %llu, walk %llu, step %llu, pair %llu, random %llu",
             (unsigned long long)g.count[NP_VECGEN_BOUNDARY], (unsigned long long)g.count[NP_VECGEN_WALK],
             (unsigned long long)g.count[NP_VECGEN_STEP], (unsigned long long)g.count[NP_VECGEN_PAIR],
             (unsigned long long)g.count[NP_VECGEN_RANDOM]);
    const char *why = NULL;
    for (; opened < n_outs && !why; opened++)
        if (np_vec_writer_open(&w[opened], outs[opened].path, outs[opened].fmt, h) != 0)
            why = w[opened].err;
    if (why)
        opened--; /* the one that failed is not open */
    np_progress progress;
    np_progress_start(&progress, "vectors", h->count);
    memset(&rec, 0, sizeof rec);
    while (!why && np_vecgen_next(&g, &rec)) {
        for (unsigned k = 0; k < opened && !why; k++)
            if (np_vec_writer_put(&w[k], &rec) != 0)
                why = w[k].err;
        if ((g.seq & 0xffffu) == 0)
            np_progress_update(&progress, g.seq);
    }
    np_progress_end(&progress);
    for (unsigned k = 0; k < opened; k++)
        if (np_vec_writer_close(&w[k], !why) != 0 && !why)
            why = w[k].err;
    if (why)
        snprintf(err, errlen, "%s", why);
    np_vecgen_free(&g);
    free(w);
    return why ? -1 : 0;
}
