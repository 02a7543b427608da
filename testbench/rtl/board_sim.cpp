// SPDX-License-Identifier: MIT
// board_sim - the whole board (np_board_top.v: UART in, protocol engine, classic3 LERP_SERIAL,
// UART out) under Verilator as a program on a byte stream: host (OUT) bytes on stdin, board (IN)
// bytes on stdout. It stands where the FT2232H and the cable stand, so that `noisepipe stream
// --sim board_sim` runs the command's own transport (src/link/link_fd.c), job, journal, resume
// and verdict against the gateware (docs/board.md).
//
// The line as board_e2e.cpp models it: 8N1 at CLKS_PER_BIT (4) clocks a bit each way; an OUT byte
// starts on the line only while the board's rts_n is low (the FT2232H's CTS#), so the host's bytes
// wait in this program while the board says stop. IN bytes are read off the board's line in the
// middle of each bit and go to stdout (the bridge's receive buffer, which never fills here). The
// simulated clock runs while a byte moves on either line and 20,000 clocks after (the unit's
// latency, the start of an answer); when the board is quiet and no byte waits, the program sleeps
// in poll() until the host writes. It runs until end of file on stdin, lets the board finish what
// it has (at most 5 * 10^7 clocks more: a host killed mid-frame leaves the engine waiting for
// bytes that never come), writes what the board sent and exits 0 (a host that is gone, EPIPE on
// stdout, ends it at once, also 0).
//
// Faults (--fault KIND:N[:ARG], repeatable), N a byte index counted from 0 over the whole run,
// OUT bytes (host to board) and IN bytes (board to host) each on their own count:
//   drop-out:N          OUT byte N never reaches the board's line
//   drop-in:N           IN byte N never reaches the host
//   flip-out:N[:BIT]    bit BIT (default 4) of OUT byte N flipped on the line
//   flip-in:N[:BIT]     bit BIT (default 2) of IN byte N flipped
//   stall-out:N:T       the bridge stops sending OUT bytes for T before byte N
//   stall-in:N:T        the bridge holds IN byte N and all after it for T
//                       (T: clocks, or milliseconds of wall time as "250ms"; the board keeps
//                       running: in a stall-in it keeps sending into the bridge's buffer; end of
//                       input ends a stall: the host is gone)
//   reset:N             the gateware's rst high for 16 clocks before OUT byte N goes on the line:
//                       the engine forgets its session (it hunts, halted, for a HELLO)
//   ignore-rts:N        from OUT byte N on, the bridge starts bytes whatever rts_n says (a host
//                       or bridge without flow control): applied at the first byte started while
//                       rts_n is high; the board then loses bytes (overflow) once its buffer is full
// Other options: --pace HZ (at most HZ simulated clocks a second of wall time; 0, the default:
// as fast as it runs), --quiet (no summary line on stderr at exit).
//
// On exit it prints one line on stderr: bytes each way, clocks, faults applied, framing errors,
// the clocks rts_n was high and the clocks host bytes waited in the bridge because of it (with
// the most that waited), the OUT bytes started against rts_n, and overflow (a byte the board
// lost: never while rts_n is honoured).
#include <poll.h>
#include <signal.h>
#include <time.h>
#include <unistd.h>

#include <cerrno>
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

namespace {

const uint64_t kLinger = 20000;   // clocks the board runs on after the last byte either way
const uint64_t kBatch = 2048;     // clocks between looks at stdin while the board runs
const unsigned kResetClocks = 16;
const uint64_t kAfterEof = 50000000;  // at most this many clocks after end of input (about 20 s)

enum Kind { DROP_OUT, DROP_IN, FLIP_OUT, FLIP_IN, STALL_OUT, STALL_IN, RESET, IGNORE_RTS, N_KINDS };
const char *const kNames[N_KINDS] = {"drop-out", "drop-in", "flip-out", "flip-in", "stall-out", "stall-in", "reset",
                                     "ignore-rts"};

struct Fault {
    Kind kind;
    uint64_t at;
    unsigned bit;        // flips
    uint64_t clocks;     // stalls in clocks
    double ms;           // stalls in wall milliseconds (clocks 0)
    bool done;
};

double now_s()
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// A stall in progress: until a clock count or a wall time.
struct Stall {
    bool on = false;
    uint64_t until_clock = 0;
    double until_wall = 0;
    bool active(uint64_t clock) const
    {
        return on && (until_wall > 0 ? now_s() < until_wall : clock < until_clock);
    }
    void start(const Fault &f, uint64_t clock)
    {
        on = true;
        until_clock = clock + f.clocks;
        until_wall = f.clocks ? 0 : now_s() + f.ms / 1000.0;
    }
};

struct Sim {
    std::vector<Fault> faults;
    uint64_t applied = 0;

    // Faults of kind k at index i: each applies once.
    Fault *find(Kind k, uint64_t i)
    {
        for (Fault &f : faults)
            if (!f.done && f.kind == k && f.at == i)
                return &f;
        return nullptr;
    }
    // An ignore-rts fault in force at OUT byte i (it holds from its byte on).
    Fault *ignoring_rts(uint64_t i)
    {
        for (Fault &f : faults)
            if (f.kind == IGNORE_RTS && i >= f.at)
                return &f;
        return nullptr;
    }
};

// The bridge's side of the OUT line: a UART transmitter that starts a byte only while rts_n is low.
struct LineOut {
    std::deque<uint8_t> q;  // host bytes not yet on the line
    np_line::Tx tx;
    uint64_t sent = 0;   // bytes taken from q (the OUT byte index)
    Stall stall;
    unsigned reset_left = 0;  // clocks of rst still to hold
    uint64_t held_clocks = 0;   // clocks a host byte waited, the line free, because rts_n was high
    size_t held_max = 0;        // the most host bytes waiting at such a clock
    uint64_t against_rts = 0;   // bytes started while rts_n was high (ignore-rts)
    // One clock; the line level.
    int step(int rts_n, Sim &s, uint64_t clock)
    {
        if (tx.idle()) {
            if (q.empty() || stall.active(clock) || reset_left)
                return 1;
            uint64_t idx = sent;
            if (rts_n) {
                Fault *f = s.ignoring_rts(idx);
                if (!f) {
                    held_clocks++;
                    if (q.size() > held_max)
                        held_max = q.size();
                    return 1;
                }
                if (!f->done) {
                    f->done = true;
                    s.applied++;
                }
                against_rts++;
            }
            if (Fault *f = s.find(STALL_OUT, idx)) {
                f->done = true;
                s.applied++;
                stall.start(*f, clock);
                return 1;
            }
            if (Fault *f = s.find(RESET, idx)) {
                f->done = true;
                s.applied++;
                reset_left = kResetClocks;
                return 1;
            }
            uint8_t cur = q.front();
            q.pop_front();
            sent++;
            if (Fault *f = s.find(DROP_OUT, idx)) {
                f->done = true;
                s.applied++;
                return 1;  // never on the line
            }
            if (Fault *f = s.find(FLIP_OUT, idx)) {
                f->done = true;
                s.applied++;
                cur = (uint8_t)(cur ^ (1u << f->bit));
            }
            tx.start(cur);
        }
        return tx.clock();
    }
    bool idle() const { return tx.idle(); }
};

// The bridge's receiver: the board's line sampled in the middle of each bit.
typedef np_line::Rx LineIn;

// The IN side of the bridge: bytes off the line, faults, the stall, then stdout.
struct Bridge {
    std::vector<uint8_t> pending;  // for stdout, in order
    std::deque<uint8_t> held;      // behind a stall-in
    uint64_t index = 0, written = 0;
    Stall stall;
    void take(uint8_t b, Sim &s, uint64_t clock)
    {
        uint64_t idx = index++;
        if (Fault *f = s.find(DROP_IN, idx)) {
            f->done = true;
            s.applied++;
            return;
        }
        if (Fault *f = s.find(FLIP_IN, idx)) {
            f->done = true;
            s.applied++;
            b = (uint8_t)(b ^ (1u << f->bit));
        }
        if (Fault *f = s.find(STALL_IN, idx)) {
            f->done = true;
            s.applied++;
            stall.start(*f, clock);
        }
        held.push_back(b);
        release(clock);
    }
    void release(uint64_t clock)
    {
        if (stall.active(clock))
            return;
        stall.on = false;
        pending.insert(pending.end(), held.begin(), held.end());
        held.clear();
    }
    // Write pending bytes to fd 1; false when the host is gone.
    bool flush()
    {
        size_t off = 0;
        while (off < pending.size()) {
            ssize_t k = write(1, pending.data() + off, pending.size() - off);
            if (k < 0 && errno == EINTR)
                continue;
            if (k <= 0)
                return false;
            off += (size_t)k;
        }
        written += pending.size();
        pending.clear();
        return true;
    }
};

bool parse_u64(const char *s, uint64_t *v)
{
    char *end;
    errno = 0;
    unsigned long long x = strtoull(s, &end, 10);
    if (end == s || errno || *s == '-')
        return false;
    *v = x;
    return *end == '\0';
}

// KIND:N[:ARG] into f; false with a message.
bool parse_fault(const char *a, Fault *f)
{
    std::string s(a);
    size_t c1 = s.find(':');
    if (c1 == std::string::npos)
        return false;
    std::string kind = s.substr(0, c1), rest = s.substr(c1 + 1), arg;
    size_t c2 = rest.find(':');
    if (c2 != std::string::npos) {
        arg = rest.substr(c2 + 1);
        rest = rest.substr(0, c2);
    }
    int k = -1;
    for (int q = 0; q < N_KINDS; q++)
        if (kind == kNames[q])
            k = q;
    if (k < 0 || !parse_u64(rest.c_str(), &f->at))
        return false;
    f->kind = (Kind)k;
    f->bit = f->kind == FLIP_OUT ? 4 : 2;
    f->clocks = 0;
    f->ms = 0;
    f->done = false;
    uint64_t v;
    if (f->kind == FLIP_OUT || f->kind == FLIP_IN) {
        if (!arg.empty()) {
            if (!parse_u64(arg.c_str(), &v) || v > 7)
                return false;
            f->bit = (unsigned)v;
        }
        return true;
    }
    if (f->kind == STALL_OUT || f->kind == STALL_IN) {
        if (arg.size() > 2 && arg.compare(arg.size() - 2, 2, "ms") == 0) {
            if (!parse_u64(arg.substr(0, arg.size() - 2).c_str(), &v) || v < 1 || v > 600000)
                return false;
            f->ms = (double)v;
            return true;
        }
        return parse_u64(arg.c_str(), &f->clocks) && f->clocks >= 1;
    }
    return arg.empty();  // drops, reset and ignore-rts take no argument
}

}  // namespace

int main(int argc, char **argv)
{
    Verilated::commandArgs(argc, argv);
    Sim s;
    double pace = 0;
    int quiet = 0;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--fault") && i + 1 < argc) {
            Fault f;
            if (!parse_fault(argv[++i], &f)) {
                fprintf(stderr,
                        "board_sim: --fault '%s': want drop-out:N, drop-in:N, flip-out:N[:BIT], flip-in:N[:BIT], "
                        "stall-out:N:CLOCKS, stall-in:N:CLOCKS (or :MSms), reset:N, ignore-rts:N\n",
                        argv[i]);
                return 2;
            }
            s.faults.push_back(f);
        } else if (!strcmp(argv[i], "--pace") && i + 1 < argc) {
            uint64_t v;
            if (!parse_u64(argv[++i], &v)) {
                fprintf(stderr, "board_sim: --pace '%s': want clocks a second (0: no limit)\n", argv[i]);
                return 2;
            }
            pace = (double)v;
        } else if (!strcmp(argv[i], "--quiet")) {
            quiet = 1;
        } else if (argv[i][0] == '+') {
            // Verilator's
        } else {
            fprintf(stderr, "board_sim: unknown option '%s' (--fault KIND:N[:ARG]..., --pace HZ, --quiet)\n", argv[i]);
            return 2;
        }
    }
    signal(SIGPIPE, SIG_IGN);  // a host that is gone: EPIPE, not a signal

    Vbd *t = new Vbd;
    np_line::reset(t);
    LineOut lo;
    LineIn li;
    Bridge br;
    uint64_t clock = 0, quiet_clocks = 0, resets = 0, eof_clock = 0, rts_high = 0;
    bool eof = false, host_gone = false;
    std::vector<uint8_t> ibuf(65536);
    double t0 = now_s();
    for (;;) {
        // Is there anything to run the clock for?
        // A stall in clocks needs the clock; one in wall time is waited for in poll().
        bool out_wall = lo.stall.until_wall > 0 && lo.stall.active(clock);
        bool in_wall = br.stall.until_wall > 0 && br.stall.active(clock);
        bool stalled = out_wall || in_wall;
        // Not `busy`: an engine left in a frame by a host that stopped mid-frame waits for bytes
        // that never come; kLinger covers the unit's latency and the start of an answer.
        bool active = (!lo.q.empty() && !out_wall) || !lo.idle() || !li.idle() || quiet_clocks < kLinger ||
                      (!br.held.empty() && !in_wall) || lo.reset_left;
        if (eof && ((!active && !stalled) || clock - eof_clock > kAfterEof))
            break;
        // Look at stdin: wait for it only while nothing else moves (or until a wall-time stall ends).
        if (!eof) {
            int ms = 0;
            if (!active) {
                double left = 0;
                if (out_wall)
                    left = lo.stall.until_wall - now_s();
                if (in_wall && (left <= 0 || br.stall.until_wall - now_s() < left))
                    left = br.stall.until_wall - now_s();
                ms = stalled ? (left > 0 ? (int)(left * 1000.0) + 1 : 0) : -1;
            }
            struct pollfd pf;
            pf.fd = 0;
            pf.events = POLLIN;
            pf.revents = 0;
            int r = poll(&pf, 1, ms);
            if (r > 0) {
                ssize_t k = read(0, ibuf.data(), ibuf.size());
                if (k > 0) {
                    lo.q.insert(lo.q.end(), ibuf.begin(), ibuf.begin() + k);
                    quiet_clocks = 0;
                } else if (k == 0 || (errno != EINTR && errno != EAGAIN)) {
                    eof = true;
                    eof_clock = clock;
                    // the host is gone: a bridge stall holds nothing back any more
                    lo.stall.on = false;
                    br.stall.on = false;
                }
            }
        } else if (!active && stalled) {
            struct timespec ts = {0, 1000000};
            nanosleep(&ts, nullptr);
        }
        // A batch of clocks.
        for (uint64_t n = 0; n < kBatch; n++) {
            bool moved = !lo.idle();
            t->rxd = (uint8_t)lo.step(t->rts_n, s, clock);
            if (lo.reset_left) {
                t->rst = 1;
                if (--lo.reset_left == 0)
                    resets++;
            } else {
                t->rst = 0;
            }
            t->clk = 0;
            t->eval();
            uint8_t b;
            if (li.step(t->txd, &b)) {
                br.take(b, s, clock);
                moved = true;
            }
            moved = moved || !li.idle();
            t->clk = 1;
            t->eval();
            clock++;
            rts_high += t->rts_n;
            quiet_clocks = moved ? 0 : quiet_clocks + 1;
        }
        br.release(clock);
        if (!br.pending.empty() && !br.flush()) {
            host_gone = true;
            break;
        }
        if (pace > 0) {
            double ahead = (double)clock / pace - (now_s() - t0);
            if (ahead > 0.001) {
                struct timespec ts = {(time_t)ahead, (long)((ahead - (double)(time_t)ahead) * 1e9)};
                nanosleep(&ts, nullptr);
            }
        }
    }
    if (!host_gone) {
        br.stall.on = false;  // what a stall still holds at the end goes out
        br.release(clock);
        host_gone = !br.flush();
    }
    double wall = now_s() - t0;
    if (!quiet)
        fprintf(stderr,
                "board_sim: %s; %llu OUT bytes on the line, %llu IN bytes (%llu to the host), %llu clocks "
                "(%.3f s of board time at 12 MHz), %.2f s wall; %llu faults applied, %llu resets, "
                "%llu framing errors at the host, rts_n high %llu clocks, host bytes held back by rts_n %llu "
                "clocks (at most %zu waiting), %llu OUT bytes sent against rts_n, overflow %d\n",
                host_gone ? "the host is gone (EPIPE)" : "end of input", (unsigned long long)lo.sent,
                (unsigned long long)br.index, (unsigned long long)br.written, (unsigned long long)clock,
                (double)clock / 12e6, wall, (unsigned long long)s.applied, (unsigned long long)resets,
                (unsigned long long)li.framing, (unsigned long long)rts_high, (unsigned long long)lo.held_clocks,
                lo.held_max, (unsigned long long)lo.against_rts, (int)t->overflow);
    t->final();
    delete t;
    return 0;
}
