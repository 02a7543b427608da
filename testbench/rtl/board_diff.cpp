// SPDX-License-Identifier: MIT
// board_diff - the differential test of the board's protocol engine (docs/board.md): the same
// OUT byte streams into the Verilated np_board_core (np_link_engine.v + classic3 LERP_SERIAL)
// and into the C board emulator (np_board, src/link/link_board.c) presenting the same INFO,
// and their IN byte streams compared frame by frame, byte by byte.
//
// Where the two may differ, by the protocol (docs/usb-protocol.md), and nowhere else:
//   CONFIG_ACK latency, clock_hz   information (4.2): the emulator's C pipe has latency 9 and no
//                                  clock; the gateware's serial classic3 17, at 12 MHz
//   BYE_ACK cycles, stalls         "0 when not counted" (4.4): clocks of different machines
//   ERROR message                  "text for a person, may be empty" (6): the gateware's is empty
// Those bytes are compared for nothing but the frame's own pcrc (each side's must be right);
// every other byte, headers and hcrc included, must be equal. Everything else (frame count,
// types, seq, tag, count, len, INFO, results, counters records/data_frames/errors, error
// codes and details) is byte for byte.
//
// Streams: a normal session (HELLO, CONFIG, DATA frames of random record counts, BYE), and the
// faults: a dropped byte, a corrupted hcrc, a corrupted pcrc, a wrong seq, a duplicated frame,
// garbage before HELLO, a HELLO mid-stream, DATA before CONFIG, a CONFIG the board does not
// have, a HELLO of version 2, a bad len, an unknown type, and the edges of the rules (a HELLO
// with a payload, a CONFIG with more padding, another layout, a host ERROR frame); each fault is followed by a new
// session (HELLO ...) that must work. Every stream also runs with the IN side stalled at
// random (out_ready low for random runs of clocks).
//
// Usage: board_diff [--seed N] [--frames N] [--stall-max N] [--verbose]
// Prints one line per stream and "In N streams, F frames (B bytes) compared, M mismatches."
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "Vbd.h"
#include "verilated.h"

extern "C" {
#include "np_link.h"
#include "np_rng.h"
}

namespace {

typedef std::vector<uint8_t> bytes;

const unsigned kMaxPayload = 1024, kWindow = 2;  // np_board_core.v's parameters
const char *const kBoardId = "classic3 on iCE40-HX8K breakout";
const char *const kUnit = "classic3";
const char *const kCfg = "out_bits=8 s_frac=12 lerp_frac=11";

struct Ctx {
    np_link_job job;
    np_rng rng;
    unsigned frames = 40;
    unsigned stall_max = 2000;
    int verbose = 0;
    uint64_t next_rec = 0;  // record index of the next DATA frame
};

void put_frame(bytes &s, unsigned type, uint32_t seq, uint64_t tag, unsigned count, const uint8_t *p,
               unsigned len, unsigned ver = 1)
{
    std::vector<uint8_t> f(NP_LINK_OVERHEAD + len);
    np_link_hdr h = {ver, type, seq, tag, count, len};
    np_link_encode(f.data(), &h, p);
    s.insert(s.end(), f.begin(), f.end());
}

void put_hello(bytes &s, uint64_t nonce, unsigned ver = 1) { put_frame(s, NP_LINK_HELLO, 0, nonce, 0, nullptr, 0, ver); }

void put_config(Ctx &c, bytes &s, uint32_t seq, const char *cfg = kCfg)
{
    np_link_config k;
    memset(&k, 0, sizeof k);
    snprintf(k.unit, sizeof k.unit, "%s", kUnit);
    k.lay = c.job.lay;
    snprintf(k.cfg, sizeof k.cfg, "%s", cfg);
    uint8_t p[NP_LINK_CONFIG_FIXED + NP_LINK_CFG_BYTES];
    size_t n = np_link_config_encode(p, &k);
    put_frame(s, NP_LINK_CONFIG, seq, 0, 0, p, (unsigned)n);
}

// A DATA frame of count records from the job (wrapping around its records).
void put_data(Ctx &c, bytes &s, uint32_t seq, unsigned count)
{
    const unsigned st = c.job.lay.in_stride;
    std::vector<uint8_t> p((size_t)count * st);
    for (unsigned k = 0; k < count; k++) {
        uint64_t i = (c.next_rec + k) % c.job.n;
        memcpy(&p[(size_t)k * st], c.job.in + i * st, st);
    }
    put_frame(s, NP_LINK_DATA, seq, c.next_rec, count, p.data(), (unsigned)p.size());
    c.next_rec += count;
}

unsigned rand_count(Ctx &c)
{
    unsigned most = kMaxPayload / c.job.lay.in_stride;
    return 1u + (unsigned)np_rng_below(&c.rng, most);
}

// HELLO, CONFIG, n DATA, BYE: the frames' start offsets in s go to starts (if given).
void put_session(Ctx &c, bytes &s, unsigned n, uint64_t nonce, std::vector<size_t> *starts = nullptr)
{
    uint32_t seq = 1;
    if (starts) starts->push_back(s.size());
    put_hello(s, nonce);
    if (starts) starts->push_back(s.size());
    put_config(c, s, seq++);
    for (unsigned k = 0; k < n; k++) {
        if (starts) starts->push_back(s.size());
        put_data(c, s, seq++, rand_count(c));
    }
    if (starts) starts->push_back(s.size());
    put_frame(s, NP_LINK_BYE, seq, 0, 0, nullptr, 0);
}

// ------------------------------------------------------------------ the two boards

bytes run_emulator(const bytes &out)
{
    np_board_opts o;
    memset(&o, 0, sizeof o);
    o.board_id = kBoardId;
    o.max_payload = kMaxPayload;
    o.window = kWindow;
    o.n_slots = 1;
    snprintf(o.slot[0].unit, sizeof o.slot[0].unit, "%s", kUnit);
    snprintf(o.slot[0].cfg, sizeof o.slot[0].cfg, "%s", kCfg);
    np_board *b = np_board_new(&o);
    if (!b) {
        fprintf(stderr, "board_diff: out of memory\n");
        exit(2);
    }
    bytes in;
    std::vector<uint8_t> buf(65536);
    size_t at = 0;
    while (at < out.size()) {
        size_t n = out.size() - at < 512 ? out.size() - at : 512;
        at += np_board_rx(b, out.data() + at, n);
        size_t m;
        while ((m = np_board_tx(b, buf.data(), buf.size())) > 0)
            in.insert(in.end(), buf.begin(), buf.begin() + (long)m);
    }
    np_board_free(b);
    return in;
}

struct Gate {
    Vbd *top;
    uint64_t cycles = 0;
};

void tick(Vbd *t)
{
    t->clk = 0;
    t->eval();
    t->clk = 1;
    t->eval();
}

// The gateware: OUT bytes offered every clock (in_valid held until taken), out_ready low for
// random runs when stall is set. Runs until the stream is in and nothing came out for a while.
bytes run_gateware(Ctx &c, const bytes &out, int stall, uint64_t *cycles, uint64_t *held_off)
{
    Vbd *t = new Vbd;
    t->rst = 1;
    t->in_valid = 0;
    t->out_ready = 0;
    tick(t);
    tick(t);
    t->rst = 0;
    bytes in;
    size_t at = 0;
    uint64_t quiet = 0, n = 0;
    *held_off = 0;
    unsigned stall_left = 0;
    while (quiet < 20000) {
        if (stall) {
            if (stall_left == 0 && np_rng_below(&c.rng, 256) == 0)
                stall_left = 1u + (unsigned)np_rng_below(&c.rng, c.stall_max);
        }
        t->out_ready = stall_left == 0;
        if (stall_left)
            stall_left--;
        t->in_valid = at < out.size();
        t->in_data = at < out.size() ? out[at] : 0;
        t->clk = 0;
        t->eval();
        int took = t->in_valid && t->in_ready;
        if (t->in_valid && !t->in_ready)
            (*held_off)++;
        int gave = t->out_valid && t->out_ready;
        uint8_t d = t->out_data;
        t->clk = 1;
        t->eval();
        n++;
        if (took)
            at++;
        if (gave)
            in.push_back(d);
        quiet = (took || gave || at < out.size()) ? 0 : quiet + 1;
    }
    t->final();
    delete t;
    *cycles = n;
    return in;
}

// ------------------------------------------------------------------ comparison

struct Frame {
    size_t at, len;  // offset in the stream, total bytes
    unsigned type, plen;
};

// Split an IN stream into frames (a board's stream is frames back to back). -1: not frames.
int split(const bytes &s, std::vector<Frame> &fr, std::string &why)
{
    size_t at = 0;
    while (at < s.size()) {
        if (s.size() - at < NP_LINK_HDR_BYTES || !np_link_header_ok(&s[at])) {
            why = "no frame header at byte " + std::to_string(at);
            return -1;
        }
        np_link_hdr h;
        np_link_header_decode(&s[at], &h);
        size_t flen = NP_LINK_OVERHEAD + (size_t)h.len;
        if (s.size() - at < flen) {
            why = "frame at byte " + std::to_string(at) + " cut short";
            return -1;
        }
        const uint8_t *pl = &s[at + NP_LINK_HDR_BYTES];
        if (np_link_crc32(0, pl, h.len) != np_link_get32(pl + h.len)) {
            why = "frame at byte " + std::to_string(at) + ": wrong pcrc";
            return -1;
        }
        fr.push_back(Frame{at, flen, h.type, h.len});
        at += flen;
    }
    return 0;
}

// 1 when payload byte k of a frame of this type may differ (see the top of the file).
int masked(unsigned type, unsigned k)
{
    if (type == NP_LINK_CONFIG_ACK)
        return k < 8;
    if (type == NP_LINK_BYE_ACK)
        return k >= 8 && k < 24;
    if (type == NP_LINK_ERROR)
        return k >= 8 && k < NP_LINK_ERROR_BYTES;
    return 0;
}

struct Tally {
    unsigned streams = 0;
    uint64_t frames = 0, bytes_cmp = 0, mismatches = 0;
};

void describe(const bytes &s, const std::vector<Frame> &fr, std::string &out)
{
    for (const Frame &f : fr) {
        np_link_hdr h;
        np_link_header_decode(&s[f.at], &h);
        char b[128];
        snprintf(b, sizeof b, " %s/%u", np_link_type_name(h.type), (unsigned)h.seq);
        out += b;
        if (h.type == NP_LINK_ERROR) {
            snprintf(b, sizeof b, "(%s)", np_link_errcode_name(np_link_get32(&s[f.at + NP_LINK_HDR_BYTES])));
            out += b;
        }
    }
}

// Compare the emulator's stream e with the gateware's g. Returns the mismatches.
uint64_t compare(const char *name, const bytes &e, const bytes &g, Tally &t, int verbose)
{
    std::vector<Frame> fe, fg;
    std::string why;
    uint64_t bad = 0;
    if (split(e, fe, why) != 0) {
        printf("%s: the emulator's IN stream is not frames: %s\n", name, why.c_str());
        return 1;
    }
    if (split(g, fg, why) != 0) {
        printf("%s: the gateware's IN stream is not frames: %s\n", name, why.c_str());
        bad++;
    }
    if (fe.size() != fg.size()) {
        printf("%s: the emulator sent %zu frames, the gateware %zu\n", name, fe.size(), fg.size());
        bad++;
    }
    size_t nf = fe.size() < fg.size() ? fe.size() : fg.size();
    for (size_t i = 0; i < nf && bad < 10; i++) {
        const Frame &a = fe[i], &b = fg[i];
        if (a.len != b.len) {
            printf("%s: frame %zu (%s): %zu bytes from the emulator, %zu from the gateware\n", name, i,
                   np_link_type_name(a.type), a.len, b.len);
            bad++;
            continue;
        }
        for (size_t k = 0; k < a.len - NP_LINK_CRC_BYTES; k++) {
            int is_pay = k >= NP_LINK_HDR_BYTES;
            if (is_pay && masked(a.type, (unsigned)(k - NP_LINK_HDR_BYTES)))
                continue;
            t.bytes_cmp++;
            if (e[a.at + k] != g[b.at + k]) {
                printf("%s: frame %zu (%s) byte %zu: emulator %02x, gateware %02x\n", name, i,
                       np_link_type_name(a.type), k, e[a.at + k], g[b.at + k]);
                bad++;
                break;
            }
        }
        // The pcrc: equal when the payloads are; each side's was checked right by split().
        int same = memcmp(&e[a.at + NP_LINK_HDR_BYTES], &g[b.at + NP_LINK_HDR_BYTES], a.plen) == 0;
        if (same) {
            t.bytes_cmp += NP_LINK_CRC_BYTES;
            if (memcmp(&e[a.at + a.len - 4], &g[b.at + b.len - 4], 4) != 0) {
                printf("%s: frame %zu: pcrc differs\n", name, i);
                bad++;
            }
        }
    }
    t.frames += nf;
    if (verbose || bad) {
        std::string de, dg;
        describe(e, fe, de);
        describe(g, fg, dg);
        printf("  emulator:%s\n  gateware:%s\n", de.c_str(), dg.c_str());
    }
    return bad;
}

// ------------------------------------------------------------------ the streams

struct Stream {
    std::string name;
    bytes out;
};

std::vector<Stream> make_streams(Ctx &c)
{
    std::vector<Stream> v;
    uint64_t nonce = 0x1000;
    {  // a normal session
        Stream s{"normal", {}};
        put_session(c, s.out, c.frames, ++nonce);
        v.push_back(s);
    }
    // The faults: a session with the fault in DATA frame k, then a new session that must work.
    const char *const kinds[] = {"dropped_byte", "hcrc", "pcrc", "wrong_seq", "duplicate", "bad_len",
                                 "bad_type", "bad_sync"};
    for (const char *kind : kinds) {
        Stream s{kind, {}};
        std::vector<size_t> st;
        bytes one;
        put_session(c, one, 8, ++nonce, &st);
        st.push_back(one.size());
        unsigned k = 2 + (unsigned)np_rng_below(&c.rng, 8);  // a DATA frame (index 2..9)
        size_t f0 = st[k], f1 = st[k + 1];
        bytes o(one.begin(), one.begin() + (long)f0), frame(one.begin() + (long)f0, one.begin() + (long)f1),
            rest(one.begin() + (long)f1, one.end());
        std::string n = kind;
        if (n == "dropped_byte") {
            frame.erase(frame.begin() + 1 + (long)np_rng_below(&c.rng, frame.size() - 1));
        } else if (n == "hcrc") {
            frame[NP_LINK_POS_HCRC + np_rng_below(&c.rng, 4)] ^= (uint8_t)(1u << np_rng_below(&c.rng, 8));
        } else if (n == "pcrc") {
            // A bit of x, y or z of one record: its result would differ, were it computed.
            size_t recs = (frame.size() - NP_LINK_OVERHEAD) / c.job.lay.in_stride;
            size_t at = NP_LINK_HDR_BYTES + np_rng_below(&c.rng, recs) * c.job.lay.in_stride + np_rng_below(&c.rng, 6);
            frame[at] ^= (uint8_t)(1u << np_rng_below(&c.rng, 8));
        } else if (n == "wrong_seq") {
            np_link_hdr h;
            np_link_header_decode(frame.data(), &h);
            h.seq += 1u + (uint32_t)np_rng_below(&c.rng, 3);
            np_link_seal(frame.data(), &h);
        } else if (n == "duplicate") {
            bytes d = frame;
            frame.insert(frame.end(), d.begin(), d.end());
        } else if (n == "bad_len") {
            np_link_hdr h;
            np_link_header_decode(frame.data(), &h);
            h.len = (h.len + 2u) & 0xffffu;  // not a multiple of 4, with a right hcrc
            np_link_put16(frame.data() + NP_LINK_POS_LEN, h.len);
            np_link_put32(frame.data() + NP_LINK_POS_HCRC, np_link_crc32(0, frame.data(), NP_LINK_POS_HCRC));
        } else if (n == "bad_type") {
            frame[NP_LINK_POS_TYPE] = 0x42;
            np_link_put32(frame.data() + NP_LINK_POS_HCRC, np_link_crc32(0, frame.data(), NP_LINK_POS_HCRC));
        } else if (n == "bad_sync") {  // in step, a header that does not start with NP
            frame[0] = 0x4F;
        }
        o.insert(o.end(), frame.begin(), frame.end());
        o.insert(o.end(), rest.begin(), rest.end());
        put_session(c, o, 6, ++nonce);  // straight after: recovery
        s.out = o;
        v.push_back(s);
    }
    {  // garbage (with stray sync bytes and a header-like run) before HELLO
        Stream s{"garbage", {}};
        unsigned n = 100 + (unsigned)np_rng_below(&c.rng, 400);
        for (unsigned k = 0; k < n; k++) {
            uint8_t b = (uint8_t)np_rng_next(&c.rng);
            if (np_rng_below(&c.rng, 8) == 0) b = 0x4E;
            else if (np_rng_below(&c.rng, 8) == 0) b = 0x50;
            s.out.push_back(b);
        }
        bytes half;  // a torn frame: the first 30 bytes of a DATA frame
        put_frame(half, NP_LINK_DATA, 1, 0, 1, c.job.in, c.job.lay.in_stride);
        s.out.insert(s.out.end(), half.begin(), half.begin() + 30);
        put_session(c, s.out, 8, ++nonce);
        v.push_back(s);
    }
    {  // a HELLO in the middle of a session: a new one starts there
        Stream s{"hello_mid", {}};
        std::vector<size_t> st;
        bytes one;
        put_session(c, one, 10, ++nonce, &st);
        s.out.assign(one.begin(), one.begin() + (long)st[6]);
        put_session(c, s.out, 10, ++nonce);
        v.push_back(s);
    }
    {  // a HELLO inside a damaged frame's bytes: found by re-scanning (section 2)
        Stream s{"hello_in_bad", {}};
        std::vector<size_t> st;
        bytes one;
        put_session(c, one, 4, ++nonce, &st);
        s.out.assign(one.begin(), one.begin() + (long)st[3]);
        bytes d;
        put_data(c, d, 3, 60);  // 480 bytes of payload
        bytes h;
        put_hello(h, ++nonce);
        memcpy(&d[NP_LINK_HDR_BYTES + 100], h.data(), h.size());  // breaks d's pcrc
        s.out.insert(s.out.end(), d.begin(), d.end());
        bytes more;
        put_session(c, more, 3, ++nonce);
        // The HELLO inside d opens a session; d's bytes after it are then no header (BAD_HEADER).
        s.out.insert(s.out.end(), more.begin(), more.end());
        v.push_back(s);
    }
    {  // DATA before CONFIG, then a CONFIG the board does not have, then a version-2 HELLO
        Stream s{"refusals", {}};
        put_hello(s.out, ++nonce);
        put_data(c, s.out, 1, 3);
        put_hello(s.out, ++nonce);
        put_config(c, s.out, 1, "out_bits=8 s_frac=10 lerp_frac=11");
        put_hello(s.out, ++nonce, 2);
        put_hello(s.out, ++nonce);
        put_frame(s.out, NP_LINK_BYE, 1, 0, 0, nullptr, 0);
        put_frame(s.out, NP_LINK_DATA, 2, 0, 1, c.job.in, c.job.lay.in_stride);  // BYE unconfigures
        put_session(c, s.out, 4, ++nonce);
        v.push_back(s);
    }
    {  // frames at the edges of the rules, each followed by a new session where it halts the board
        Stream s{"edges", {}};
        uint8_t eight[8] = {1, 2, 3, 4, 5, 6, 7, 8};
        put_frame(s.out, NP_LINK_HELLO, 7, ++nonce, 3, eight, 8);  // a HELLO's seq, count, payload: not checked
        put_config(c, s.out, 1);
        put_data(c, s.out, 2, 5);
        np_link_config k;  // the same CONFIG with 8 more NULs of padding: accepted
        memset(&k, 0, sizeof k);
        snprintf(k.unit, sizeof k.unit, "%s", kUnit);
        k.lay = c.job.lay;
        snprintf(k.cfg, sizeof k.cfg, "%s", kCfg);
        uint8_t p[NP_LINK_CONFIG_FIXED + NP_LINK_CFG_BYTES];
        memset(p, 0, sizeof p);
        size_t n = np_link_config_encode(p, &k);
        put_frame(s.out, NP_LINK_CONFIG, 3, 0, 0, p, (unsigned)n + 8);
        // DATA whose len is not count x in_stride: BAD_LENGTH
        put_frame(s.out, NP_LINK_DATA, 4, 0, 2, c.job.in, c.job.lay.in_stride);
        put_hello(s.out, ++nonce);
        p[28] = 10;  // out_bits[0] 10: a consistent layout (lane 2, stride 4) but not the slot's
        put_frame(s.out, NP_LINK_CONFIG, 1, 0, 0, p, (unsigned)n);
        put_hello(s.out, ++nonce);
        put_frame(s.out, NP_LINK_ERROR, 1, 0, 0, eight, 8, 2);  // a host ERROR of version 2: read, BAD_TYPE
        put_hello(s.out, ++nonce);
        put_frame(s.out, NP_LINK_RESULT, 1, 0, 0, nullptr, 0);  // a board-to-host type: BAD_TYPE
        put_hello(s.out, ++nonce);
        p[28] = 8;
        p[0] = 'C';  // another unit: NO_SUCH_CONFIG
        put_frame(s.out, NP_LINK_CONFIG, 1, 0, 0, p, (unsigned)n);
        put_hello(s.out, ++nonce);
        put_frame(s.out, NP_LINK_CONFIG, 1, 0, 0, p, 36);  // too short: BAD_LENGTH
        put_session(c, s.out, 3, ++nonce);
        v.push_back(s);
    }
    return v;
}

}  // namespace

int main(int argc, char **argv)
{
    Verilated::commandArgs(argc, argv);
    Ctx c;
    uint64_t seed = 1;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--seed") && i + 1 < argc)
            seed = strtoull(argv[++i], nullptr, 0);
        else if (!strcmp(argv[i], "--frames") && i + 1 < argc)
            c.frames = (unsigned)strtoul(argv[++i], nullptr, 0);
        else if (!strcmp(argv[i], "--stall-max") && i + 1 < argc)
            c.stall_max = (unsigned)strtoul(argv[++i], nullptr, 0);
        else if (!strcmp(argv[i], "--verbose"))
            c.verbose = 1;
        else if (argv[i][0] == '+')
            ;  // Verilator's
        else {
            fprintf(stderr, "board_diff: unknown option '%s' (--seed N, --frames N, --stall-max N, --verbose)\n", argv[i]);
            return 2;
        }
    }
    if (c.frames < 1 || c.stall_max < 1) {
        fprintf(stderr, "board_diff: --frames and --stall-max must be at least 1\n");
        return 2;
    }
    np_rng_seed(&c.rng, seed);
    const np_unit *u = np_unit_find(kUnit);
    np_unit_cfg cfg;
    char err[256];
    if (!u || np_unit_configure(u, &cfg, kCfg, err, sizeof err) != 0) {
        fprintf(stderr, "board_diff: unit %s %s: %s\n", kUnit, kCfg, u ? err : "not found");
        return 2;
    }
    if (np_link_job_random(&c.job, u, &cfg, 4096, seed) != 0) {
        fprintf(stderr, "board_diff: out of memory\n");
        return 2;
    }
    Tally t;
    std::string differ;
    uint64_t total_cycles = 0, total_off = 0;
    std::vector<Stream> v = make_streams(c);
    for (const Stream &s : v)
        for (int stall = 0; stall < 2; stall++) {
            std::string name = s.name + (stall ? "+stall" : "");
            bytes e = run_emulator(s.out);
            uint64_t cyc = 0, off = 0;
            bytes g = run_gateware(c, s.out, stall, &cyc, &off);
            total_off += off;
            total_cycles += cyc;
            uint64_t before = t.bytes_cmp;
            uint64_t bad = compare(name.c_str(), e, g, t, c.verbose);
            t.mismatches += bad;
            if (bad)
                differ += " " + name;
            t.streams++;
            printf("%-18s OUT %6zu bytes, IN %6zu / %6zu bytes (emulator / gateware), %7llu bytes compared, %llu clocks (OUT held off %llu): %s\n",
                   name.c_str(), s.out.size(), e.size(), g.size(), (unsigned long long)(t.bytes_cmp - before),
                   (unsigned long long)cyc, (unsigned long long)off, bad ? "DIFFERENT" : "same");
        }
    printf("%llu clocks simulated; the engine held the OUT stream off (in_ready low) for %llu of them\n",
           (unsigned long long)total_cycles, (unsigned long long)total_off);
    if (!differ.empty())
        printf("Streams that differ:%s.\n", differ.c_str());
    printf("In %u streams, %llu frames (%llu bytes) compared, %llu mismatches.\n", t.streams,
           (unsigned long long)t.frames, (unsigned long long)t.bytes_cmp, (unsigned long long)t.mismatches);
    np_link_job_free(&c.job);
    return t.mismatches ? 1 : 0;
}
