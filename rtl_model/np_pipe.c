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
    p->slot = calloc(depth, sizeof *p->slot);
    p->opt = calloc(3, sig_size);
    if (!p->regs || !p->valid || !p->moves || !p->slot || !p->opt) {
        np_pipe_free(p);
        return -1;
    }
    for (unsigned k = 0; k < depth; k++)
        p->slot[k] = k;
    return 0;
}

void np_pipe_free(np_pipe *p)
{
    free(p->regs);
    free(p->valid);
    free(p->moves);
    free(p->slot);
    free(p->opt);
    p->slot = NULL;
    p->regs = NULL;
    p->valid = p->moves = p->opt = NULL;
}

void np_pipe_reset(np_pipe *p)
{
    memset(p->valid, 0, p->depth);
    memset(p->moves, 0, p->depth);
    memset(p->regs, 0, p->depth * p->sig_size);
    for (unsigned k = 0; k < p->depth; k++)
        p->slot[k] = k;
    memset(p->opt, 0, 3 * p->sig_size);
    p->in_v = p->main_v = p->skid_v = 0;
    memset(&p->stats, 0, sizeof p->stats);
}

unsigned np_pipe_occupancy(const np_pipe *p)
{
    unsigned n = 0;
    for (unsigned k = 0; k < p->depth; k++)
        n += p->valid[k];
    return n + p->in_v + p->main_v + p->skid_v;
}

static unsigned char *bank(np_pipe *p, unsigned k) { return p->regs + (size_t)p->slot[k] * p->sig_size; }
/* The option registers: 0 input register, 1 skid main, 2 skid spare. */
static unsigned char *opt(np_pipe *p, unsigned k) { return p->opt + (size_t)k * p->sig_size; }

void np_pipe_eval(np_pipe *p, np_pipe_port *port)
{
    unsigned last = p->depth - 1u;
    /* Ready chain, from the output back to the input. The skid buffer's
     * ready is its spare register being empty: a flip-flop. */
    unsigned ready = p->out_skid ? !p->skid_v : port->out_ready != 0;
    /*
     * Bank k moves when it is valid and the bank after it is ready: empty, or
     * moving itself (the last bank: the output is ready). Computed with 0/1
     * arithmetic instead of && and || so that the random handshakes of a
     * co-simulation cost no mispredicted branches; the same values.
     */
    for (unsigned k = last + 1u; k-- > 0;) {
        unsigned v = p->valid[k] != 0, m = v & ready;
        p->moves[k] = (unsigned char)m;
        ready = (v ^ 1u) | m;
    }
    p->core_in_ready = (unsigned char)ready;
    port->in_ready = p->in_reg ? (!p->in_v || p->core_in_ready) : p->core_in_ready;
    port->out_valid = p->out_skid ? p->main_v : p->valid[last];
    port->out_sig = p->out_skid ? opt(p, 1) : bank(p, last);
}

void np_pipe_clock(np_pipe *p, const np_pipe_port *port)
{
    unsigned last = p->depth - 1u;
    p->stats.cycles++;
    if (port->out_valid && !port->out_ready)
        p->stats.out_stalls++;
    if (port->in_ready && !port->in_valid)
        p->stats.in_bubbles++;
    if (port->out_valid && port->out_ready)
        p->stats.delivered++;
    if (p->out_skid) {
        /* Before the banks move: the last bank's content is what it offers. */
        if (!p->main_v || port->out_ready) {
            if (p->skid_v) {
                memcpy(opt(p, 1), opt(p, 2), p->sig_size);
                p->skid_v = 0;
            } else {
                p->main_v = p->valid[last];
                if (p->valid[last])
                    memcpy(opt(p, 1), bank(p, last), p->sig_size);
            }
        } else if (p->valid[last] && !p->skid_v) {
            memcpy(opt(p, 2), bank(p, last), p->sig_size);
            p->skid_v = 1;
        }
    }
    /* Back to front, so each bank reads its predecessor's old content. */
    for (unsigned k = last; k > 0; k--) {
        if (p->valid[k] && !p->moves[k])
            continue; /* holds */
        if (p->moves[k - 1]) {
            /*
             * Bank k takes bank k - 1's bundle; bank k - 1 gets bank k's old
             * one, which is free (it moved on: handled already, back to front;
             * or it was empty), and is written before it is read again. Stage
             * k works in place on the bundle, so the bits are those of a copy.
             */
            if (p->copy_banks) {
                memcpy(bank(p, k), bank(p, k - 1), p->sig_size);
            } else {
                unsigned t = p->slot[k];
                p->slot[k] = p->slot[k - 1];
                p->slot[k - 1] = t;
            }
            p->stages[k].fn(p->cfg, bank(p, k));
            p->valid[k] = 1;
        } else {
            p->valid[k] = 0;
        }
    }
    if (port->in_ready && port->in_valid)
        p->stats.accepted++;
    int in_valid = p->in_reg ? p->in_v : port->in_valid;
    const void *in_sig = p->in_reg ? opt(p, 0) : port->in_sig;
    if (p->core_in_ready) {
        if (in_valid) {
            memcpy(bank(p, 0), in_sig, p->sig_size);
            p->stages[0].fn(p->cfg, bank(p, 0));
            p->valid[0] = 1;
        } else {
            p->valid[0] = 0;
        }
    }
    if (p->in_reg && port->in_ready) {
        p->in_v = (unsigned char)(port->in_valid != 0);
        if (port->in_valid)
            memcpy(opt(p, 0), port->in_sig, p->sig_size);
    }
}
