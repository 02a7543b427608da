/* SPDX-License-Identifier: MIT */
#include "np_cosim.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "np_classic.h"
#include "np_pipe.h"
#include "np_rng.h"
#include "np_simplex.h"
#include "np_wave.h"

/* Densities of a traffic phase, out of 256 (as src/vecdrive.c). */
static const unsigned density[4] = { 0, 32, 128, 224 };
enum { PHASE_MIN = 16, PHASE_SPAN = 256 };

struct np_cosim {
    int simplex, wave;
    np_classic_cfg ccfg;
    np_wave_unit wu;
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
        np_wave_sig w;
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
    } else if (strcmp(unit, "wave") == 0 && np == 6) {
        c->wave = 1;
        c->wu.c = np_wave_cfg_default();
        c->wu.c.trains = p[0];
        c->wu.c.irr = p[1];
        c->wu.c.cap = p[2];
        c->wu.c.rom_log2 = p[3];
        c->wu.c.normals = p[4];
        c->wu.c.fold = p[5];
        bad = np_wave_cfg_check(&c->wu.c);
        if (!bad) {
            if (np_wave_has_jac(&c->wu.c))
                np_wave_regs_test_jac(1, c->wu.c.trains, &c->wu.r);
            else
                np_wave_regs_test(1, c->wu.c.trains, &c->wu.r);
            bad = np_wave_regs_check(&c->wu.c, &c->wu.r);
        }
        if (!bad)
            rc = np_wave_pipe_init(&c->pipe, &c->wu);
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

const struct np_wave_regs *np_cosim_wave_regs(const np_cosim *c) { return c->wave ? &c->wu.r : NULL; }

int np_cosim_is_wave(const np_cosim *c) { return c->wave; }

unsigned np_cosim_outputs(const np_cosim *c)
{
    if (c->wave)
        return 3u + 3u * c->wu.c.normals + c->wu.c.fold;
    return c->simplex ? 4u : 1u;
}

unsigned np_cosim_out_bits(const np_cosim *c, unsigned k)
{
    if (c->wave)
        return k < 3 ? 16u : (c->wu.c.normals && k < 6) ? 20u : 1u;
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

/*
 * A random wave transaction: uniform fields, with a quarter of each at an
 * edge: v at the box's sides (0 .. 9, V - 10 .. V + 1), t near 0 or 2^32,
 * g around 0, gcap and 0x7fff, the phase shift at a quarter turn.
 */
static void random_wave(np_rng *r, const np_wave_regs *w, uint32_t in[NP_COSIM_WAVE_INS])
{
    uint64_t a = np_rng_next(r), b = np_rng_next(r), e = np_rng_next(r);
    in[0] = (uint32_t)(a & 0xffffu);
    in[1] = (uint32_t)((a >> 16) & 0xffffu);
    in[2] = (uint32_t)(a >> 32);
    in[3] = (uint32_t)b;
    in[4] = (uint32_t)((b >> 32) & 0xffffu);
    in[5] = (uint32_t)((b >> 48) & 0xffffu);
    in[6] = (uint32_t)(e & 0xffu);
    in[7] = (uint32_t)((e >> 8) & 0x7fffu);
    if (((e >> 23) & 3u) == 0)
        in[5] = (uint32_t)(((e >> 25) & 1u) ? ((e >> 26) % 10u) : (uint32_t)w->width - 10u + (uint32_t)((e >> 26) % 12u)) & 0xffffu;
    if (((e >> 30) & 3u) == 0)
        in[2] = ((e >> 32) & 1u) ? (uint32_t)((e >> 33) & 7u) : UINT32_MAX - (uint32_t)((e >> 33) & 7u);
    if (((e >> 36) & 3u) == 0) {
        static const uint32_t gv[6] = { 0u, 1u, 16384u, 0x7fffu, 0u, 0u };
        unsigned q = (unsigned)((e >> 38) % 6u);
        in[7] = q < 4 ? gv[q] : (uint32_t)w->gcap - 1u + (q - 4u) * 2u;
    }
    if (((e >> 41) & 3u) == 0)
        in[3] = (uint32_t)((e >> 43) & 3u) << 30;
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
            if (c->wave) {
                random_wave(&c->rng, &c->wu.r, cy->win);
            } else {
                cy->x = random_word(&c->rng);
                cy->y = random_word(&c->rng);
                cy->z = random_word(&c->rng);
            }
            c->pending = 1;
        }
    }
    cy->out_ready = !stall;
}

void np_cosim_eval(np_cosim *c, np_cosim_cycle *cy)
{
    /* Only the inputs change: the rest of the bundle stays as calloc left it (the stages write banks, never in_sig). */
    if (c->wave) {
        np_wave_in *w = &c->in.w.in;
        w->i = (uint16_t)cy->win[0];
        w->j = (uint16_t)cy->win[1];
        w->t = cy->win[2];
        w->ph = cy->win[3];
        w->u = (uint16_t)cy->win[4];
        w->v = (uint16_t)cy->win[5];
        w->r = (uint8_t)cy->win[6];
        w->g = (uint16_t)cy->win[7];
    } else if (c->simplex) {
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
    if (c->wave) {
        const np_wave_sig *s = c->port.out_sig;
        unsigned k = 0;
        cy->out[k++] = (uint16_t)s->out.y;
        cy->out[k++] = (uint16_t)s->out.dx;
        cy->out[k++] = (uint16_t)s->out.dz;
        if (c->wu.c.normals) {
            cy->out[k++] = (uint32_t)np_trunc_u((uint64_t)(int64_t)s->jac.nx, 20);
            cy->out[k++] = (uint32_t)np_trunc_u((uint64_t)(int64_t)s->jac.ny, 20);
            cy->out[k++] = (uint32_t)np_trunc_u((uint64_t)(int64_t)s->jac.nz, 20);
        }
        if (c->wu.c.fold)
            cy->out[k++] = s->jac.fold;
    } else if (c->simplex) {
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
