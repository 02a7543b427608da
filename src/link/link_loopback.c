/* SPDX-License-Identifier: MIT */
/*
 * link_loopback.c - the in-process transport: the host engine and the board
 * emulator in one process, bytes moved between them in frames or in chunks
 * (to exercise reassembly), with the host's time-out and a test "kill".
 */
#include "np_link.h"

#include <stdlib.h>
#include <time.h>

#include "np_common.h"

static double thread_cpu(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

int np_link_loopback(np_host *h, np_board *b, np_loop_opts *o)
{
    size_t cap = NP_LINK_MAX_FRAME;
    uint8_t *obuf = malloc(cap), *ibuf = malloc(cap);
    if (!obuf || !ibuf) {
        free(obuf);
        free(ibuf);
        np_host_fault(h, NP_FAULT_USB, "out of memory");
        return 0;
    }
    double timeout = o->timeout > 0 ? o->timeout : 2.0;
    size_t olen = 0, ooff = 0;
    double last = np_now();
    const np_host_stats *st = np_host_get_stats(h);
    uint64_t results0 = st->verified;
    uint64_t frames0 = st->frames_in;
    int stopped = 0;
    o->board_cpu = 0;
    while (!np_host_done(h) && np_host_get_fault(h) == NP_FAULT_NONE) {
        int progress = 0;
        if (ooff == olen) {
            olen = np_host_pull(h, obuf, cap);
            ooff = 0;
        }
        if (ooff < olen) {
            size_t m = olen - ooff;
            if (o->chunk && m > o->chunk)
                m = o->chunk;
            double t0 = thread_cpu();
            size_t k = np_board_rx(b, obuf + ooff, m);
            o->board_cpu += thread_cpu() - t0;
            ooff += k;
            progress |= k > 0;
        }
        size_t want = o->chunk ? o->chunk : cap;
        double t0 = thread_cpu();
        size_t m = np_board_tx(b, ibuf, want);
        o->board_cpu += thread_cpu() - t0;
        if (m) {
            np_host_push(h, ibuf, m);
            progress = 1;
        }
        if (o->stop_after && st->frames_in - frames0 >= o->stop_after && st->verified > results0) {
            stopped = 1;
            break;
        }
        if (progress) {
            last = np_now();
            continue;
        }
        if (!np_host_waiting(h) && ooff == olen) {
            np_host_fault(h, NP_FAULT_USB, "internal: the session stalled with nothing to wait for");
            break;
        }
        if (np_now() - last > timeout) {
            np_host_timeout(h, timeout);
            break;
        }
        struct timespec ts = { 0, 1000000 };
        nanosleep(&ts, NULL);
    }
    free(obuf);
    free(ibuf);
    return stopped;
}
