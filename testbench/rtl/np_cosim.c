/* SPDX-License-Identifier: MIT */
#include "np_cosim.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "np_classic.h"
#include "np_pipe.h"
#include "np_rng.h"
#include "np_simplex.h"

/* Densities of a traffic phase, out of 256 (as src/vecdrive.c). */
static const unsigned density[4] = { 0, 32, 128, 224 };
enum { PHASE_MIN = 16, PHASE_SPAN = 256 };

struct np_cosim {
    int simplex;
    np_classic_cfg ccfg;
    np_simplex_cfg scfg;
    np_pipe pipe;
    np_pipe_port port;
    np_rng rng;
    uint64_t left;
    unsigned p_bubble, p_stall;
    int pending;                 /* an input is presented and not yet accepted */
    union {
        np_classic_sig c;
        np_simplex_sig s;
    } in;
    uint64_t bubbles, stalls;
};

np_cosim *np_cosim_open(const char *unit, const unsigned *p, unsigned np, int in_reg, int out_skid,
                        uint64_t seed, char *err, unsigned errn)
{
    np_cosim *c = calloc(1, sizeof *c);
    const char *bad = NULL;
    int rc = -1;
    if (!c) {
        snprintf(err, errn, "out of memory");
        return NULL;
    }
    if (strcmp(unit, "classic3") == 0 && np == 3) {
        c->ccfg.out_bits = p[0];
        c->ccfg.s_frac = p[1];
        c->ccfg.lerp_frac = p[2];
        bad = np_classic_cfg_check(&c->ccfg);
        if (!bad)
            rc = np_classic_pipe_init(&c->pipe, &c->ccfg);
    } else if (strcmp(unit, "simplex3") == 0 && np == 6) {
        c->simplex = 1;
        c->scfg.out_bits = p[0];
        c->scfg.dout_bits = p[1];
        c->scfg.deriv = p[2];
        c->scfg.t_frac = p[3];
        c->scfg.p_frac = p[4];
        c->scfg.k_frac = p[5];
        bad = np_simplex_cfg_check(&c->scfg);
        if (!bad)
            rc = np_simplex_pipe_init(&c->pipe, &c->scfg);
    } else {
        bad = "unknown unit or wrong number of configuration values";
    }
    if (bad || rc != 0) {
        snprintf(err, errn, "%s", bad ? bad : "out of memory");
        free(c);
        return NULL;
    }
    c->pipe.in_reg = in_reg != 0;
    c->pipe.out_skid = out_skid != 0;
    np_pipe_reset(&c->pipe);
    np_rng_seed(&c->rng, seed);
    return c;
}

void np_cosim_close(np_cosim *c)
{
    if (!c)
        return;
    np_pipe_free(&c->pipe);
    free(c);
}

unsigned np_cosim_outputs(const np_cosim *c) { return c->simplex ? 4u : 1u; }

unsigned np_cosim_out_bits(const np_cosim *c, unsigned k)
{
    if (!c->simplex)
        return c->ccfg.out_bits;
    return k == 0 ? c->scfg.out_bits : c->scfg.dout_bits;
}

/* A random 8.8 input word: uniform, or with the fraction at an edge (1/4). */
static uint16_t random_word(np_rng *r)
{
    static const uint16_t edge[8] = { 0x00, 0x01, 0x7f, 0x80, 0x81, 0xaa, 0xfe, 0xff };
    uint64_t v = np_rng_next(r);
    uint16_t w = (uint16_t)(v & 0xffffu);
    if (((v >> 16) & 3u) == 0)
        w = (uint16_t)((w & 0xff00u) | edge[(v >> 18) & 7u]);
    return w;
}

void np_cosim_drive(np_cosim *c, np_cosim_cycle *cy, int traffic)
{
    int bubble = 0, stall = 0;
    if (traffic) {
        if (c->left == 0) {
            uint64_t r = np_rng_next(&c->rng);
            c->left = PHASE_MIN + (r % PHASE_SPAN);
            c->p_bubble = density[(r >> 8) & 3u];
            c->p_stall = density[(r >> 10) & 3u];
        }
        c->left--;
        uint64_t r = np_rng_next(&c->rng);
        bubble = (unsigned)(r & 255u) < c->p_bubble;
        stall = (unsigned)((r >> 8) & 255u) < c->p_stall;
    }
    if (!c->pending) {
        if (bubble) {
            cy->in_valid = 0;
        } else {
            cy->in_valid = 1;
            cy->x = random_word(&c->rng);
            cy->y = random_word(&c->rng);
            cy->z = random_word(&c->rng);
            c->pending = 1;
        }
    }
    cy->out_ready = !stall;
}

void np_cosim_eval(np_cosim *c, np_cosim_cycle *cy)
{
    /* Only the inputs change: the rest of the bundle stays as calloc left it (the stages write banks, never in_sig). */
    if (c->simplex) {
        c->in.s.x = cy->x;
        c->in.s.y = cy->y;
        c->in.s.z = cy->z;
    } else {
        c->in.c.x = cy->x;
        c->in.c.y = cy->y;
        c->in.c.z = cy->z;
    }
    c->port.in_valid = cy->in_valid;
    c->port.in_sig = &c->in;
    c->port.out_ready = cy->out_ready;
    np_pipe_eval(&c->pipe, &c->port);
    cy->in_ready = c->port.in_ready;
    cy->out_valid = c->port.out_valid;
    memset(cy->out, 0, sizeof cy->out);
    if (!cy->out_valid)
        return;
    if (c->simplex) {
        const np_simplex_sig *s = c->port.out_sig;
        cy->out[0] = (uint32_t)np_trunc_u((uint64_t)(int64_t)s->f, c->scfg.out_bits);
        for (unsigned a = 0; a < 3; a++)
            cy->out[1 + a] = (uint32_t)np_trunc_u((uint64_t)(int64_t)s->df[a], c->scfg.dout_bits);
    } else {
        const np_classic_sig *s = c->port.out_sig;
        cy->out[0] = (uint32_t)np_trunc_u((uint64_t)(int64_t)s->out, c->ccfg.out_bits);
    }
}

void np_cosim_accept(np_cosim *c, const np_cosim_cycle *cy)
{
    if (cy->in_valid && cy->in_ready)
        c->pending = 0;
    if (!cy->in_valid && cy->in_ready)
        c->bubbles++;
    if (cy->out_valid && !cy->out_ready)
        c->stalls++;
}

void np_cosim_clock(np_cosim *c, const np_cosim_cycle *cy)
{
    np_cosim_accept(c, cy);
    np_pipe_clock(&c->pipe, &c->port);
}

void np_cosim_counts(const np_cosim *c, uint64_t counts[5])
{
    counts[0] = c->pipe.stats.cycles;
    counts[1] = c->pipe.stats.accepted;
    counts[2] = c->pipe.stats.delivered;
    counts[3] = c->bubbles;
    counts[4] = c->stalls;
}
