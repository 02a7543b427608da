// SPDX-License-Identifier: MIT
// board_e2e - the whole board's gateware (np_board_top.v: UART in, protocol engine, classic3
// LERP_SERIAL, UART out) under Verilator, driven by the real host engine of `noisepipe stream`
// (np_host_*: src/link/link_engine.c), as link_loopback.c drives the C emulator. The harness is
// the cable and the FT2232H: it moves the host's OUT frames onto the UART line (8N1 at
// CLKS_PER_BIT clocks a bit, honouring the board's rts_n), reads the board's line back into
// bytes for the host, and owns time. The host checks every result against the bit-exact model
// and journals what it verified (in memory).
//
// Faults on the line (--fault KIND:N, repeatable): drop-out:N drops the Nth OUT byte,
// flip-out:N and flip-in:N flip a bit of the Nth OUT or IN byte (counted from 0 over the
// whole run). After a link fault the harness starts a new session on the same journal (as
// `noisepipe stream --resume` does), until every vector is verified or --sessions are used up.
// The verdict: every vector verified exactly once (the sessions' verified counts add up to
// the job, the journal holds each once), no failing vector, no overflow on the board.
//
// Usage: board_e2e [--records N] [--seed N] [--fault KIND:N]... [--sessions N] [--verbose]
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <string>
#include <vector>

#include "Vbd.h"
#include "np_uart_line.h"
#include "verilated.h"

extern "C" {
#include "np_link.h"
}

namespace {

const double kClockHz = 12e6;
const uint64_t kQuiet = 400000;  // clocks without a byte either way: the host's time-out

struct Fault {
    int kind;  // 0 drop-out, 1 flip-out, 2 flip-in
    uint64_t at;
};

// The host's side of the line: a UART transmitter that starts a byte only while rts_n is low.
struct LineOut {
    std::deque<uint8_t> q;
    np_line::Tx tx;
    int level = 1;
    uint64_t sent = 0;
    bool idle() const { return tx.idle(); }
    // One clock; returns the line level for this clock.
    int step(int rts_n, const std::vector<Fault> &faults, uint64_t *n_faults)
    {
        if (tx.idle()) {
            if (q.empty() || rts_n)
                return level = 1;
            uint8_t cur = q.front();
            q.pop_front();
            uint64_t idx = sent++;
            for (const Fault &f : faults)
                if (f.at == idx && f.kind == 0) {
                    (*n_faults)++;
                    return level = 1;  // dropped: never on the line
                } else if (f.at == idx && f.kind == 1) {
                    (*n_faults)++;
                    cur ^= 0x10;
                }
            tx.start(cur);
        }
        return level = tx.clock();
    }
};

// The host's receiver: the board's line sampled in the middle of each bit; flip-in faults on
// the bytes received whole.
struct LineIn {
    np_line::Rx rx;
    uint64_t got = 0;
    // One clock of line level v; returns 1 with a byte in *b.
    int step(int v, uint8_t *b, const std::vector<Fault> &faults, uint64_t *n_faults)
    {
        if (!rx.step(v, b))
            return 0;
        uint64_t idx = got++;
        for (const Fault &f : faults)
            if (f.at == idx && f.kind == 2) {
                (*n_faults)++;
                *b ^= 0x04;
            }
        return 1;
    }
};

}  // namespace

int main(int argc, char **argv)
{
    Verilated::commandArgs(argc, argv);
    uint64_t records = 2000, seed = 1;
    unsigned max_sessions = 8;
    int verbose = 0;
    std::vector<Fault> faults;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--records") && i + 1 < argc)
            records = strtoull(argv[++i], nullptr, 0);
        else if (!strcmp(argv[i], "--seed") && i + 1 < argc)
            seed = strtoull(argv[++i], nullptr, 0);
        else if (!strcmp(argv[i], "--sessions") && i + 1 < argc)
            max_sessions = (unsigned)strtoul(argv[++i], nullptr, 0);
        else if (!strcmp(argv[i], "--fault") && i + 1 < argc) {
            const char *a = argv[++i];
            const char *colon = strchr(a, ':');
            static const char *const kinds[] = {"drop-out", "flip-out", "flip-in"};
            int k = -1;
            for (int q = 0; q < 3 && colon; q++)
                if ((size_t)(colon - a) == strlen(kinds[q]) && !strncmp(a, kinds[q], strlen(kinds[q])))
                    k = q;
            if (k < 0) {
                fprintf(stderr, "board_e2e: --fault '%s': want drop-out:N, flip-out:N or flip-in:N\n", a);
                return 2;
            }
            faults.push_back(Fault{k, strtoull(colon + 1, nullptr, 0)});
        } else if (!strcmp(argv[i], "--verbose"))
            verbose = 1;
        else if (argv[i][0] == '+')
            ;  // Verilator's
        else {
            fprintf(stderr, "board_e2e: unknown option '%s' (--records N, --seed N, --fault KIND:N, --sessions N, --verbose)\n", argv[i]);
            return 2;
        }
    }
    if (records < 1 || max_sessions < 1) {
        fprintf(stderr, "board_e2e: --records and --sessions must be at least 1\n");
        return 2;
    }
    const np_unit *u = np_unit_find("classic3");
    np_unit_cfg cfg;
    char err[256];
    if (!u || np_unit_configure(u, &cfg, "out_bits=8 s_frac=12 lerp_frac=11", err, sizeof err) != 0) {
        fprintf(stderr, "board_e2e: unit classic3: %s\n", u ? err : "not found");
        return 2;
    }
    np_link_job job;
    if (np_link_job_random(&job, u, &cfg, records, seed) != 0) {
        fprintf(stderr, "board_e2e: out of memory\n");
        return 2;
    }
    np_journal jn;
    if (np_journal_open(&jn, nullptr, &job, 0, err, sizeof err) != 0) {
        fprintf(stderr, "board_e2e: journal: %s\n", err);
        return 2;
    }

    Vbd *t = new Vbd;
    np_line::reset(t);
    LineOut lo;
    LineIn li;
    uint64_t n_faults = 0, clocks = 0, verified_sum = 0, errors_sum = 0, frame_errs = 0;
    std::vector<uint8_t> obuf(NP_LINK_MAX_FRAME);
    auto t0 = std::chrono::steady_clock::now();
    unsigned session = 0;
    int ok = 1;
    while (jn.n_checked < job.n && session < max_sessions) {
        np_host_opts ho;
        memset(&ho, 0, sizeof ho);
        ho.nonce = 0x5eed0000u + seed * 256u + session;
        np_host *h = np_host_new(&job, &jn, &ho);
        if (!h) {
            fprintf(stderr, "board_e2e: out of memory\n");
            return 2;
        }
        uint64_t quiet = 0, c0 = clocks;
        while (!np_host_done(h) && np_host_get_fault(h) == NP_FAULT_NONE) {
            if (lo.q.empty() && lo.idle()) {
                size_t n = np_host_pull(h, obuf.data(), obuf.size());
                lo.q.insert(lo.q.end(), obuf.begin(), obuf.begin() + (long)n);
            }
            int moved = !lo.idle();
            t->rxd = (uint8_t)lo.step(t->rts_n, faults, &n_faults);
            t->clk = 0;
            t->eval();
            uint8_t b;
            if (li.step(t->txd, &b, faults, &n_faults)) {
                np_host_push(h, &b, 1);
                moved = 1;
            }
            t->clk = 1;
            t->eval();
            clocks++;
            if (t->frame_err)
                frame_errs++;
            quiet = moved ? 0 : quiet + 1;
            if (quiet > kQuiet) {
                np_host_timeout(h, (double)kQuiet / kClockHz);
                break;
            }
        }
        // A USB OUT transfer (one frame) completes: the frame on the line is finished (the
        // queue holds no more than it).
        while (!lo.idle() || !lo.q.empty()) {
            t->rxd = (uint8_t)lo.step(t->rts_n, faults, &n_faults);
            t->clk = 0;
            t->eval();
            uint8_t b;
            li.step(t->txd, &b, faults, &n_faults);  // stale answers of the old session
            t->clk = 1;
            t->eval();
            clocks++;
        }
        const np_host_stats *st = np_host_get_stats(h);
        verified_sum += st->verified;
        errors_sum += st->errors;
        np_link_fault f = np_host_get_fault(h);
        printf("session %u: %llu vectors sent, %llu verified, %llu failed; %s%s%s; board: records %llu, data_frames %u, cycles %llu, stalls %llu; %llu clocks\n",
               session, (unsigned long long)st->sent, (unsigned long long)st->verified,
               (unsigned long long)st->errors, f == NP_FAULT_NONE ? "done" : np_link_fault_name(f),
               f == NP_FAULT_NONE ? "" : ": ", f == NP_FAULT_NONE ? "" : np_host_fault_msg(h),
               (unsigned long long)st->bye.records, (unsigned)st->bye.data_frames,
               (unsigned long long)st->bye.cycles, (unsigned long long)st->bye.stalls,
               (unsigned long long)(clocks - c0));
        if (verbose)
            printf("  info: '%s' max_payload %u window %u; ack latency %u clock %u Hz\n", st->info.board_id,
                   (unsigned)st->info.max_payload, (unsigned)st->info.window, (unsigned)st->ack.latency,
                   (unsigned)st->ack.clock_hz);
        if (f == NP_FAULT_NONE && !(st->have_bye && st->bye.records == st->verified))
            ok = 0;  // the board's count must agree with the host's in a clean session
        np_host_free(h);
        session++;
    }
    double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    int once = verified_sum == job.n && jn.n_checked == job.n;
    printf("line: %llu OUT bytes, %llu IN bytes, %llu faults injected, %llu framing errors at the board\n",
           (unsigned long long)lo.sent, (unsigned long long)li.got, (unsigned long long)n_faults,
           (unsigned long long)frame_errs);
    printf("%llu clocks simulated (%.3f s of board time at 12 MHz, 3 Mbaud), %.2f s wall\n",
           (unsigned long long)clocks, (double)clocks / kClockHz, wall);
    if (t->overflow) {
        printf("the board lost OUT bytes (overflow)\n");
        ok = 0;
    }
    if (!once)
        ok = 0;
    if (errors_sum || jn.n_errors)
        ok = 0;
    printf("In %llu records, %llu verified in %u sessions (%llu counted by the sessions), %llu failed: %s.\n",
           (unsigned long long)job.n, (unsigned long long)jn.n_checked, session,
           (unsigned long long)verified_sum, (unsigned long long)(errors_sum + jn.n_errors),
           ok ? "every record verified exactly once" : "NOT verified");
    t->final();
    delete t;
    np_journal_close(&jn);
    np_link_job_free(&job);
    return ok ? 0 : 1;
}
