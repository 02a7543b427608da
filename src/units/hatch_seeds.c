/* SPDX-License-Identifier: MIT */
/*
 * hatch_seeds.c - de Bruijn seed sets for the hatching unit (hatch_seeds.h).
 */
#include "hatch_seeds.h"

#include <math.h>
#include <string.h>

#include "np_rng.h"

unsigned np_seeds_n(unsigned K) { return 1u << (2u * K); }

void np_seeds_from_digits(unsigned K, const uint8_t *digits, np_seedset *s)
{
    unsigned n = np_seeds_n(K);
    s->K = K;
    s->n = n;
    s->bu = s->bv = 0;
    for (unsigned j = 0; j < n; j++) {
        unsigned pos = n - 1u - j;
        s->bu |= (uint64_t)((digits[j] >> 1) & 1u) << pos;
        s->bv |= (uint64_t)(digits[j] & 1u) << pos;
    }
}

void np_seeds_to_digits(const np_seedset *s, uint8_t *digits)
{
    for (unsigned j = 0; j < s->n; j++) {
        unsigned pos = s->n - 1u - j;
        digits[j] = (uint8_t)(2u * ((s->bu >> pos) & 1u) + ((s->bv >> pos) & 1u));
    }
}

/* FKM: concatenate, in lexicographic order, the Lyndon words whose length divides K. */
static void fkm_rec(unsigned K, unsigned t, unsigned p, uint8_t *a, uint8_t *out, unsigned *len)
{
    if (t > K) {
        if (K % p == 0)
            for (unsigned j = 1; j <= p; j++)
                out[(*len)++] = a[j];
        return;
    }
    a[t] = a[t - p];
    fkm_rec(K, t + 1u, p, a, out, len);
    for (unsigned j = (unsigned)a[t - p] + 1u; j < 4u; j++) {
        a[t] = (uint8_t)j;
        fkm_rec(K, t + 1u, t, a, out, len);
    }
}

void np_seeds_fkm(unsigned K, uint8_t *digits)
{
    uint8_t a[NP_SEEDS_KMAX + 2] = { 0 };
    unsigned len = 0;
    fkm_rec(K, 1, 1, a, digits, &len);
}

int np_seeds_is_debruijn(unsigned K, const uint8_t *digits)
{
    unsigned n = np_seeds_n(K);
    unsigned char seen[NP_SEEDS_NMAX] = { 0 };
    for (unsigned i = 0; i < n; i++) {
        unsigned w = 0;
        for (unsigned k = 0; k < K; k++) {
            if (digits[(i + k) % n] > 3u)
                return 0;
            w = w * 4u + digits[(i + k) % n];
        }
        if (seen[w]++)
            return 0;
    }
    return 1;
}

/* floor(2^K * W / (2^N - 1)) for an N-bit word W: the exact cell of the rational W / (2^N - 1). */
static unsigned exact_cell(uint64_t w, unsigned K, unsigned n)
{
    np_u128 d = ((np_u128)1 << n) - 1u;
    return (unsigned)(((np_u128)w << K) / d);
}

unsigned np_seeds_cells(const np_seedset *s, unsigned *cells)
{
    unsigned side = 1u << s->K;
    unsigned count[NP_SEEDS_NMAX] = { 0 };
    for (unsigned i = 0; i < s->n; i++) {
        unsigned cu = exact_cell(np_seed_rotl(s->bu, i, s->n), s->K, s->n);
        unsigned cv = exact_cell(np_seed_rotl(s->bv, i, s->n), s->K, s->n);
        count[cv * side + cu]++;
    }
    unsigned bad = 0;
    for (unsigned c = 0; c < side * side; c++) {
        if (count[c] != 1u)
            bad++;
        if (cells)
            cells[c] = count[c];
    }
    return bad;
}

/* Toroidal distance between two numerators over D = 2^N - 1, in units of 1/D. */
static uint64_t tor(uint64_t a, uint64_t b, uint64_t dd)
{
    uint64_t d = a > b ? a - b : b - a;
    return d < dd - d ? d : dd - d;
}

double np_seeds_spacing(const np_seedset *s, np_u128 *num2, unsigned *pi, unsigned *pj)
{
    uint64_t u[NP_SEEDS_NMAX], v[NP_SEEDS_NMAX];
    uint64_t dd = s->n == 64 ? ~(uint64_t)0 : NP_MASK(s->n);
    for (unsigned i = 0; i < s->n; i++) {
        u[i] = np_seed_rotl(s->bu, i, s->n);
        v[i] = np_seed_rotl(s->bv, i, s->n);
    }
    np_u128 best = ~(np_u128)0;
    unsigned bi = 0, bj = 0;
    for (unsigned i = 0; i < s->n; i++)
        for (unsigned j = i + 1u; j < s->n; j++) {
            np_u128 du = tor(u[i], u[j], dd), dv = tor(v[i], v[j], dd);
            np_u128 q = du * du + dv * dv; /* du, dv <= 2^63: the sum < 2^127 */
            if (q < best) {
                best = q;
                bi = i;
                bj = j;
            }
        }
    if (num2)
        *num2 = best;
    if (pi)
        *pi = bi;
    if (pj)
        *pj = bj;
    return sqrt((double)best) / (double)dd;
}

double np_seeds_coord(uint64_t b, unsigned i, unsigned n)
{
    uint64_t dd = n == 64 ? ~(uint64_t)0 : NP_MASK(n);
    return (double)np_seed_rotl(b, i, n) / (double)dd;
}

double np_seeds_best_count(unsigned K)
{
    /* BEST: ec = t_w * prod (deg - 1)!, t_w = 4^(4^(K-1)) / 4^K arborescences (de Bruijn graph). */
    double v = (double)np_seeds_n(K - 1u), r = 1.0;
    for (unsigned i = 0; i < (unsigned)v; i++)
        r *= 24.0; /* 4^V arborescence factor times 3!^V = 24^V */
    return r / (double)np_seeds_n(K);
}

/* --- Eulerian circuits of the de Bruijn graph: node = last K-1 digits, edge = next digit --- */

typedef struct euler {
    unsigned K, n, V;
    uint8_t used[NP_SEEDS_NMAX]; /* edge (node, digit) = node * 4 + digit */
    uint8_t seq[NP_SEEDS_NMAX];
    uint64_t visited;
    int stop;
    int (*fn)(const uint8_t *, void *);
    void *user;
} euler;

static void euler_rec(euler *e, unsigned node, unsigned depth)
{
    if (e->stop)
        return;
    if (depth == e->n) {
        if (node == 0u) { /* closed at the start node (always, for an Eulerian circuit) */
            e->visited++;
            if (e->fn && e->fn(e->seq, e->user))
                e->stop = 1;
        }
        return;
    }
    for (unsigned d = 0; d < 4u; d++) {
        unsigned ed = node * 4u + d;
        if (e->used[ed])
            continue;
        e->used[ed] = 1;
        e->seq[depth] = (uint8_t)d;
        euler_rec(e, (node * 4u + d) % e->V, depth + 1u);
        e->used[ed] = 0;
        if (e->stop)
            return;
    }
}

uint64_t np_seeds_enumerate(unsigned K, int (*fn)(const uint8_t *, void *), void *user)
{
    euler e;
    memset(&e, 0, sizeof e);
    e.K = K;
    e.n = np_seeds_n(K);
    e.V = np_seeds_n(K - 1u);
    e.fn = fn;
    e.user = user;
    /*
     * Start at node 0^(K-1) with the edge 0: every cyclic sequence holds the
     * window 0^K once, so each is visited once, rotated to begin with that
     * window's last digit.
     */
    e.used[0] = 1;
    e.seq[0] = 0;
    euler_rec(&e, 0, 1);
    return e.visited;
}

void np_seeds_random(unsigned K, np_rng *rng, uint8_t *digits)
{
    unsigned n = np_seeds_n(K), V = np_seeds_n(K - 1u);
    unsigned char in_tree[NP_SEEDS_NMAX / 4] = { 0 };
    uint8_t next_digit[NP_SEEDS_NMAX / 4] = { 0 };
    /* Wilson: loop-erased random walks along uniformly chosen exit edges, toward root 0. */
    in_tree[0] = 1;
    for (unsigned v0 = 1; v0 < V; v0++) {
        unsigned v = v0;
        while (!in_tree[v]) {
            unsigned d = (unsigned)np_rng_below(rng, 4);
            next_digit[v] = (uint8_t)d;
            v = (v * 4u + d) % V;
        }
        for (v = v0; !in_tree[v]; v = (v * 4u + next_digit[v]) % V)
            in_tree[v] = 1;
    }
    /* Exit orders: the tree edge last at every node but the root; the rest shuffled. */
    uint8_t order[NP_SEEDS_NMAX / 4][4];
    uint8_t pos[NP_SEEDS_NMAX / 4] = { 0 };
    for (unsigned v = 0; v < V; v++) {
        unsigned k = 0;
        for (unsigned d = 0; d < 4u; d++)
            if (v == 0u || d != next_digit[v])
                order[v][k++] = (uint8_t)d;
        for (unsigned a = k - 1u; a > 0u; a--) {
            unsigned b = (unsigned)np_rng_below(rng, (uint64_t)a + 1u);
            uint8_t t = order[v][a];
            order[v][a] = order[v][b];
            order[v][b] = t;
        }
        if (v != 0u)
            order[v][3] = next_digit[v];
    }
    unsigned node = 0;
    for (unsigned j = 0; j < n; j++) {
        unsigned d = order[node][pos[node]++];
        digits[j] = (uint8_t)d;
        node = (node * 4u + d) % V;
    }
}

const np_hatch_set *np_seeds_find(const char *name)
{
    for (unsigned i = 0; i < NP_HATCH_SETS; i++)
        if (strcmp(np_hatch_sets[i].name, name) == 0)
            return &np_hatch_sets[i];
    return NULL;
}

np_seedset np_seeds_of(const np_hatch_set *hs)
{
    np_seedset s = { hs->K, hs->n, hs->bu, hs->bv };
    return s;
}
