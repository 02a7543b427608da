/* SPDX-License-Identifier: MIT */
#include "np_dpi.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "np_classic.h"
#include "np_simplex.h"

/* The output word of a signed value in an n-bit field. */
static int word_of(int32_t v, unsigned n) { return (int)np_trunc_u((uint64_t)(int64_t)v, n); }

static int classic_cfg(int out_bits, int s_frac, int lerp_frac, np_classic_cfg *c)
{
    if (out_bits < 0 || s_frac < 0 || lerp_frac < 0)
        return -1;
    c->out_bits = (unsigned)out_bits;
    c->s_frac = (unsigned)s_frac;
    c->lerp_frac = (unsigned)lerp_frac;
    return np_classic_cfg_check(c) ? -1 : 0;
}

static int simplex_cfg(int out_bits, int dout_bits, int deriv, int t_frac, int p_frac, int k_frac,
                       np_simplex_cfg *c)
{
    if (out_bits < 0 || dout_bits < 0 || deriv < 0 || t_frac < 0 || p_frac < 0 || k_frac < 0)
        return -1;
    c->out_bits = (unsigned)out_bits;
    c->dout_bits = (unsigned)dout_bits;
    c->deriv = (unsigned)deriv;
    c->t_frac = (unsigned)t_frac;
    c->p_frac = (unsigned)p_frac;
    c->k_frac = (unsigned)k_frac;
    return np_simplex_cfg_check(c) ? -1 : 0;
}

int np_dpi_classic3_eval(int out_bits, int s_frac, int lerp_frac, int x, int y, int z)
{
    np_classic_cfg c;
    if (classic_cfg(out_bits, s_frac, lerp_frac, &c) != 0)
        return -1;
    return word_of(np_classic_eval(&c, (uint16_t)x, (uint16_t)y, (uint16_t)z), c.out_bits);
}

int np_dpi_simplex3_eval(int out_bits, int dout_bits, int deriv, int t_frac, int p_frac, int k_frac,
                         int x, int y, int z, int *f, int *dfdx, int *dfdy, int *dfdz)
{
    np_simplex_cfg c;
    np_simplex_out o;
    if (simplex_cfg(out_bits, dout_bits, deriv, t_frac, p_frac, k_frac, &c) != 0)
        return -1;
    np_simplex_eval(&c, (uint16_t)x, (uint16_t)y, (uint16_t)z, &o);
    *f = word_of(o.f, c.out_bits);
    *dfdx = c.deriv ? word_of(o.df[0], c.dout_bits) : 0;
    *dfdy = c.deriv ? word_of(o.df[1], c.dout_bits) : 0;
    *dfdz = c.deriv ? word_of(o.df[2], c.dout_bits) : 0;
    return 0;
}

/* A cycle model: the pipe owns a copy of its configuration and its port. */
typedef struct dpi_pipe {
    int simplex;
    np_classic_cfg cc;
    np_simplex_cfg sc;
    np_pipe pipe;
    np_pipe_port port;
    union {
        np_classic_sig c;
        np_simplex_sig s;
    } in;
} dpi_pipe;

static void *pipe_finish(dpi_pipe *d, int rc, int in_reg, int out_skid)
{
    if (rc != 0) {
        free(d);
        return NULL;
    }
    d->pipe.in_reg = in_reg != 0;
    d->pipe.out_skid = out_skid != 0;
    np_pipe_reset(&d->pipe);
    return d;
}

void *np_dpi_classic3_pipe_new(int out_bits, int s_frac, int lerp_frac, int in_reg, int out_skid)
{
    dpi_pipe *d = calloc(1, sizeof *d);
    if (!d)
        return NULL;
    if (classic_cfg(out_bits, s_frac, lerp_frac, &d->cc) != 0)
        return pipe_finish(d, -1, 0, 0);
    return pipe_finish(d, np_classic_pipe_init(&d->pipe, &d->cc), in_reg, out_skid);
}

void *np_dpi_simplex3_pipe_new(int out_bits, int dout_bits, int deriv, int t_frac, int p_frac,
                               int k_frac, int in_reg, int out_skid)
{
    dpi_pipe *d = calloc(1, sizeof *d);
    if (!d)
        return NULL;
    d->simplex = 1;
    if (simplex_cfg(out_bits, dout_bits, deriv, t_frac, p_frac, k_frac, &d->sc) != 0)
        return pipe_finish(d, -1, 0, 0);
    return pipe_finish(d, np_simplex_pipe_init(&d->pipe, &d->sc), in_reg, out_skid);
}

void np_dpi_pipe_eval(void *pipe, int in_valid, int x, int y, int z, int out_ready, int *in_ready,
                      int *out_valid, int *f, int *dfdx, int *dfdy, int *dfdz)
{
    dpi_pipe *d = pipe;
    memset(&d->in, 0, sizeof d->in);
    if (d->simplex) {
        d->in.s.x = (uint16_t)x;
        d->in.s.y = (uint16_t)y;
        d->in.s.z = (uint16_t)z;
    } else {
        d->in.c.x = (uint16_t)x;
        d->in.c.y = (uint16_t)y;
        d->in.c.z = (uint16_t)z;
    }
    d->port.in_valid = in_valid != 0;
    d->port.in_sig = &d->in;
    d->port.out_ready = out_ready != 0;
    np_pipe_eval(&d->pipe, &d->port);
    *in_ready = d->port.in_ready;
    *out_valid = d->port.out_valid;
    *f = *dfdx = *dfdy = *dfdz = 0;
    if (!d->port.out_valid)
        return;
    if (d->simplex) {
        const np_simplex_sig *s = d->port.out_sig;
        *f = word_of(s->f, d->sc.out_bits);
        if (d->sc.deriv) {
            *dfdx = word_of(s->df[0], d->sc.dout_bits);
            *dfdy = word_of(s->df[1], d->sc.dout_bits);
            *dfdz = word_of(s->df[2], d->sc.dout_bits);
        }
    } else {
        const np_classic_sig *s = d->port.out_sig;
        *f = word_of(s->out, d->cc.out_bits);
    }
}

void np_dpi_pipe_clock(void *pipe)
{
    dpi_pipe *d = pipe;
    np_pipe_clock(&d->pipe, &d->port);
}

void np_dpi_pipe_free(void *pipe)
{
    dpi_pipe *d = pipe;
    if (!d)
        return;
    np_pipe_free(&d->pipe);
    free(d);
}
