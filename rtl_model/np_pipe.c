/* SPDX-License-Identifier: MIT */
#include "np_pipe.h"

#include <stdlib.h>
#include <string.h>

int np_pipe_init(np_pipe *p, const np_stage_desc *stages, unsigned depth, size_t sig_size,
                 const void *cfg)
{
    memset(p, 0, sizeof *p);
    if (depth == 0)
        return -1;
    p->cfg = cfg;
    p->stages = stages;
    p->depth = depth;
    p->sig_size = sig_size;
    p->regs = calloc(depth, sig_size);
    p->valid = calloc(depth, 1);
    p->moves = calloc(depth, 1);
    if (!p->regs || !p->valid || !p->moves) {
        np_pipe_free(p);
        return -1;
    }
    return 0;
}

void np_pipe_free(np_pipe *p)
{
    free(p->regs);
    free(p->valid);
    free(p->moves);
    p->regs = NULL;
    p->valid = p->moves = NULL;
}

void np_pipe_reset(np_pipe *p)
{
    memset(p->valid, 0, p->depth);
    memset(p->moves, 0, p->depth);
    memset(p->regs, 0, p->depth * p->sig_size);
    memset(&p->stats, 0, sizeof p->stats);
}

unsigned np_pipe_occupancy(const np_pipe *p)
{
    unsigned n = 0;
    for (unsigned k = 0; k < p->depth; k++)
        n += p->valid[k];
    return n;
}

static unsigned char *bank(np_pipe *p, unsigned k) { return p->regs + (size_t)k * p->sig_size; }

void np_pipe_eval(np_pipe *p, np_pipe_port *port)
{
    unsigned last = p->depth - 1u;
    /* Ready chain, from the output back to the input. */
    p->moves[last] = (unsigned char)(p->valid[last] && port->out_ready);
    for (unsigned k = last; k-- > 0;)
        p->moves[k] = (unsigned char)(p->valid[k] && (!p->valid[k + 1] || p->moves[k + 1]));
    port->in_ready = !p->valid[0] || p->moves[0];
    port->out_valid = p->valid[last];
    port->out_sig = bank(p, last);
}

void np_pipe_clock(np_pipe *p, const np_pipe_port *port)
{
    unsigned last = p->depth - 1u;
    p->stats.cycles++;
    if (port->out_valid && !port->out_ready)
        p->stats.out_stalls++;
    if (port->in_ready && !port->in_valid)
        p->stats.in_bubbles++;
    if (p->moves[last])
        p->stats.delivered++;
    /* Back to front, so each bank reads its predecessor's old content. */
    for (unsigned k = last; k > 0; k--) {
        if (p->valid[k] && !p->moves[k])
            continue; /* holds */
        if (p->moves[k - 1]) {
            memcpy(bank(p, k), bank(p, k - 1), p->sig_size);
            p->stages[k].fn(p->cfg, bank(p, k));
            p->valid[k] = 1;
        } else {
            p->valid[k] = 0;
        }
    }
    if (port->in_ready) {
        if (port->in_valid) {
            memcpy(bank(p, 0), port->in_sig, p->sig_size);
            p->stages[0].fn(p->cfg, bank(p, 0));
            p->valid[0] = 1;
            p->stats.accepted++;
        } else {
            p->valid[0] = 0;
        }
    }
}
