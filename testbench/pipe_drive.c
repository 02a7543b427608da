/* SPDX-License-Identifier: MIT */
/* The random-traffic driver of a unit's np_pipe (np_pipe_drive.h). */
#include "np_pipe_drive.h"

#include <stdlib.h>
#include <string.h>

#include "np_test.h"

enum { QN = 64 };

np_pipe_drive_result np_pipe_drive_random(const np_pipe_dut *d, uint64_t n, unsigned pb, unsigned ps,
                                          uint64_t seed)
{
    np_pipe *p = d->pipe;
    size_t sz = p->sig_size;
    np_pipe_drive_result res = { 0, 0, 0, 0 };
    /* The transactions in flight: input bundle, cycle accepted, output stalls seen by then. */
    unsigned char *q_in = calloc(QN + 1, sz), *in = NULL;
    uint64_t q_cycle[QN], q_stalls[QN];
    if (!q_in) {
        NP_CHECK(0, "out of memory");
        return res;
    }
    in = q_in + (size_t)QN * sz;
    np_rng r;
    np_rng_seed(&r, seed);
    uint64_t sent = 0, got = 0, cycle = 0, stalls = 0;
    np_pipe_port port;
    memset(&port, 0, sizeof port);
    int have = 0;
    unsigned lat = np_pipe_latency(p);
    while (got < n) {
        if (!have && sent < n) {
            uint64_t w[NP_UNIT_MAX_FIELDS] = { 0 };
            for (unsigned a = 0; a < d->n_in; a++)
                w[a] = np_rng_next(&r) >> (64u - d->in_bits);
            memset(in, 0, sz);
            d->unit->sig_set_in(in, w);
            have = 1;
        }
        uint64_t coin = np_rng_next(&r);
        port.in_valid = have && (coin & 15u) >= pb;
        port.in_sig = in;
        port.out_ready = ((coin >> 4) & 15u) >= ps;
        np_pipe_eval(p, &port);
        if (port.out_valid && !port.out_ready)
            stalls++;
        if (port.out_valid && port.out_ready) {
            unsigned slot = (unsigned)(got % QN);
            if (!d->check(d->cfg, q_in + slot * sz, port.out_sig, got))
                res.mismatches++;
            /* No stall while in flight: exactly the latency. */
            if (q_stalls[slot] == stalls) {
                NP_CHECK(cycle - q_cycle[slot] == lat, "transaction %llu latency %llu, want %u",
                         (unsigned long long)got, (unsigned long long)(cycle - q_cycle[slot]), lat);
                res.exact++;
            } else {
                /* A stall elsewhere may be absorbed by a bubble ahead: never faster, though. */
                NP_CHECK(cycle - q_cycle[slot] >= lat, "transaction faster than the latency");
            }
            got++;
        }
        if (port.in_valid && port.in_ready) {
            unsigned slot = (unsigned)(sent % QN);
            NP_CHECK(sent - got < QN, "more than %d in flight", QN);
            memcpy(q_in + slot * sz, in, sz);
            q_cycle[slot] = cycle;
            q_stalls[slot] = stalls;
            sent++;
            have = 0;
        }
        np_pipe_clock(p, &port);
        cycle++;
        NP_CHECK(np_pipe_occupancy(p) <= lat, "occupancy");
    }
    NP_CHECK(p->stats.accepted == n && p->stats.delivered == n, "stats count");
    free(q_in);
    res.transactions = got;
    res.cycles = cycle;
    return res;
}
