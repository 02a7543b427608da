/* SPDX-License-Identifier: MIT */
/*
 * test_link.c - the USB link without USB: frames, CRC, records, payloads,
 * the board emulator against the bit-exact model and against the protocol
 * document, and whole sessions host <-> emulator in process, with every
 * fault the emulator can inject, the journal, and kill-and-resume.
 */
#include <fcntl.h>
#include <signal.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "np_child.h"
#include "np_common.h"
#include "np_link.h"
#include "np_rng.h"
#include "np_test.h"

static const np_unit *classic(void) { return np_unit_find("classic3"); }

static void cfg_of(const np_unit *u, np_unit_cfg *c, const char *spec)
{
    char err[256];
    if (np_unit_configure(u, c, spec, err, sizeof err) != 0) {
        fprintf(stderr, "configure %s: %s\n", spec ? spec : "", err);
        exit(2);
    }
}

/* A job of n random vectors (seed) for classic3 at spec (NULL: its default configuration). */
static void classic_job(np_link_job *j, const char *spec, uint64_t n, uint64_t seed)
{
    np_unit_cfg cfg;
    cfg_of(classic(), &cfg, spec);
    np_link_job_random(j, classic(), &cfg, n, seed);
}

/* A host with the default options on job j, its journal jn in memory. */
static np_host *memory_host(const np_link_job *j, np_journal *jn)
{
    char err[256];
    np_journal_open(jn, NULL, j, 0, err, sizeof err);
    np_host_opts ho;
    memset(&ho, 0, sizeof ho);
    return np_host_new(j, jn, &ho);
}

/* A per-test scratch path in the build tree's working directory. */
static void tmp_path(char *buf, size_t len, const char *name)
{
    snprintf(buf, len, "test_link.%ld.%s", (long)getpid(), name);
    unlink(buf);
}

/* ------------------------------------------------------------------------- */

static int t_crc_kat(void)
{
    NP_CHECK(np_link_crc32(0, "123456789", 9) == 0xcbf43926u, "check value %08x",
             (unsigned)np_link_crc32(0, "123456789", 9));
    NP_CHECK(np_link_crc32(0, "", 0) == 0, "empty");
    uint32_t part = np_link_crc32(0, "12345", 5);
    NP_CHECK(np_link_crc32(part, "6789", 4) == 0xcbf43926u, "continued CRC");
    /* Regenerate the table and compare every entry with the checked-in one. */
    for (uint32_t i = 0; i < 256; i++) {
        uint32_t c = i;
        for (int k = 0; k < 8; k++)
            c = c & 1u ? (c >> 1) ^ 0xedb88320u : c >> 1;
        NP_CHECK(np_link_crc_table[i] == c, "table[%u] = %08x, want %08x", (unsigned)i,
                 (unsigned)np_link_crc_table[i], (unsigned)c);
    }
    return 0;
}

/* A frame with a payload of len bytes of pattern. */
static size_t make_frame(uint8_t *f, unsigned type, uint32_t seq, uint64_t tag, unsigned count, unsigned len,
                         uint8_t pattern)
{
    np_link_hdr h = { NP_LINK_VERSION, type, seq, tag, count, len };
    for (unsigned k = 0; k < len; k++)
        np_link_payload(f)[k] = (uint8_t)(pattern + 7u * k);
    return np_link_seal(f, &h);
}

static int t_frame_codec(void)
{
    uint8_t f[256];
    size_t n = make_frame(f, NP_LINK_DATA, 0x01020304u, 0x1122334455667788u, 9, 64, 3);
    NP_CHECK(n == NP_LINK_OVERHEAD + 64, "length %zu", n);
    NP_CHECK(f[0] == 0x4e && f[1] == 0x50 && f[2] == 1 && f[3] == NP_LINK_DATA, "first word");
    NP_CHECK(f[4] == 0x04 && f[7] == 0x01 && f[8] == 0x88 && f[15] == 0x11, "little-endian seq and tag");
    NP_CHECK(f[16] == 9 && f[17] == 0 && f[18] == 64 && f[19] == 0, "count and len");
    NP_CHECK(np_link_header_ok(f), "header CRC");
    np_link_hdr h;
    np_link_header_decode(f, &h);
    NP_CHECK(h.seq == 0x01020304u && h.tag == 0x1122334455667788u && h.count == 9 && h.len == 64,
             "decode");
    /* Every single-bit error anywhere in the frame is caught: no frame comes out. */
    unsigned caught = 0;
    for (size_t bit = 0; bit < 8 * n; bit++) {
        uint8_t g[256];
        memcpy(g, f, n);
        g[bit / 8] ^= (uint8_t)(1u << (bit % 8));
        np_link_rx rx;
        np_link_rx_init(&rx, 1024);
        const uint8_t *p = g;
        size_t left = n;
        np_link_rx_ev ev;
        int frames = 0;
        for (;;) {
            np_link_rx_event e = np_link_rx_step(&rx, &p, &left, &ev);
            if (e == NP_RX_MORE)
                break;
            frames += e == NP_RX_FRAME;
        }
        np_link_rx_free(&rx);
        NP_CHECK(frames == 0, "bit %zu flipped, yet a frame was accepted", bit);
        caught += frames == 0;
    }
    printf("single-bit errors caught: %u of %zu\n", caught, 8 * n);
    return 0;
}

static int t_rx_reassembly(void)
{
    /* garbage, 20 frames of varied lengths, fed in chunks of 1..37 bytes */
    static uint8_t stream[20 * 300 + 64];
    size_t n = 0;
    const char garbage[] = "NP\x01 garbage before the first frame";
    memcpy(stream, garbage, sizeof garbage - 1);
    n = sizeof garbage - 1;
    for (unsigned k = 0; k < 20; k++)
        n += make_frame(stream + n, NP_LINK_RESULT, k, 1000u * k, k, 4u * (k * 13u % 60u), (uint8_t)k);
    for (size_t chunk = 1; chunk <= 37; chunk += 4) {
        np_link_rx rx;
        np_link_rx_init(&rx, 1024);
        unsigned got = 0;
        for (size_t at = 0; at < n; at += chunk) {
            const uint8_t *p = stream + at;
            size_t left = at + chunk <= n ? chunk : n - at;
            np_link_rx_ev ev;
            np_link_rx_event e;
            while ((e = np_link_rx_step(&rx, &p, &left, &ev)) != NP_RX_MORE) {
                NP_CHECK(e == NP_RX_FRAME, "chunk %zu: event %d", chunk, (int)e);
                if (e != NP_RX_FRAME)
                    continue;
                NP_CHECK(ev.h.seq == got && ev.h.tag == 1000u * got, "chunk %zu: frame %u out of order", chunk, got);
                for (unsigned b = 0; b < ev.h.len; b++)
                    if (ev.payload[b] != (uint8_t)(got + 7u * b)) {
                        NP_CHECK(0, "chunk %zu: payload of frame %u differs at %u", chunk, got, b);
                        break;
                    }
                got++;
            }
        }
        NP_CHECK(got == 20, "chunk %zu: %u frames", chunk, got);
        NP_CHECK(rx.discarded == sizeof garbage - 1, "chunk %zu: %llu bytes discarded", chunk,
                 (unsigned long long)rx.discarded);
        np_link_rx_free(&rx);
    }
    return 0;
}

static int t_rx_short(void)
{
    uint8_t s[1024];
    size_t a = make_frame(s, NP_LINK_RESULT, 5, 0, 16, 64, 1);
    size_t cut = NP_LINK_HDR_BYTES + 20; /* header and 20 payload bytes of frame 5 */
    size_t b = make_frame(s + cut, NP_LINK_RESULT, 6, 16, 16, 64, 2);
    size_t c = make_frame(s + cut + b, NP_LINK_RESULT, 7, 32, 16, 64, 3);
    (void)a;
    np_link_rx rx;
    np_link_rx_init(&rx, 1024);
    const uint8_t *p = s;
    size_t left = cut + b + c;
    np_link_rx_ev ev;
    np_link_rx_event e = np_link_rx_step(&rx, &p, &left, &ev);
    NP_CHECK(e == NP_RX_SHORT && ev.h.seq == 5 && ev.short_at == 20, "event %d seq %u at %zu", (int)e,
             (unsigned)ev.h.seq, ev.short_at);
    e = np_link_rx_step(&rx, &p, &left, &ev);
    NP_CHECK(e == NP_RX_FRAME && ev.h.seq == 6, "the next frame after the short one: %d seq %u", (int)e,
             (unsigned)ev.h.seq);
    e = np_link_rx_step(&rx, &p, &left, &ev);
    NP_CHECK(e == NP_RX_FRAME && ev.h.seq == 7, "and the one after");
    np_link_rx_free(&rx);
    return 0;
}

static int t_records(void)
{
    const np_unit *u = classic();
    np_unit_cfg c;
    np_unit_fields f;
    np_link_layout l;
    cfg_of(u, &c, NULL);
    u->fields(&c, &f);
    np_link_layout_init(&l, &f);
    NP_CHECK(l.in_stride == 8 && l.out_stride == 4, "classic3 strides %u/%u", l.in_stride, l.out_stride);
    /* The document's example (section 5). */
    uint8_t rec[8];
    uint64_t in[3] = { 0x12ab, 0x0080, 0xffff }, back[3];
    np_link_pack(rec, in, l.in_lane, l.n_in, l.in_stride);
    static const uint8_t want_in[8] = { 0xab, 0x12, 0x80, 0x00, 0xff, 0xff, 0x00, 0x00 };
    NP_CHECK(memcmp(rec, want_in, 8) == 0, "input record bytes");
    np_link_unpack(rec, back, l.in_lane, l.n_in);
    NP_CHECK(back[0] == in[0] && back[1] == in[1] && back[2] == in[2], "unpack");
    uint64_t fq = 0xe0; /* -0.5 in s8 Q2.6 */
    np_link_pack(rec, &fq, l.out_lane, l.n_out, l.out_stride);
    NP_CHECK(rec[0] == 0xe0 && rec[1] == 0 && rec[2] == 0 && rec[3] == 0, "output record bytes");
    cfg_of(u, &c, "out_bits=10");
    u->fields(&c, &f);
    np_link_layout_init(&l, &f);
    NP_CHECK(l.out_lane[0] == 2 && l.out_stride == 4, "out_bits=10: lane %u", l.out_lane[0]);
    fq = 0x380; /* -0.5 in s10 Q2.8 */
    np_link_pack(rec, &fq, l.out_lane, l.n_out, l.out_stride);
    NP_CHECK(rec[0] == 0x80 && rec[1] == 0x03 && rec[2] == 0 && rec[3] == 0, "s10 output bytes");
    NP_CHECK(np_link_lane(1) == 1 && np_link_lane(8) == 1 && np_link_lane(9) == 2 && np_link_lane(16) == 2 &&
             np_link_lane(17) == 4 && np_link_lane(33) == 8 && np_link_lane(64) == 8, "lanes");
    return 0;
}

static int t_payloads(void)
{
    uint8_t p[4096];
    np_link_info i, i2;
    memset(&i, 0, sizeof i);
    i.version = 1;
    i.max_payload = 16384;
    i.window = 8;
    i.n_slots = 2;
    snprintf(i.board_id, sizeof i.board_id, "Arty A7");
    snprintf(i.slot[0].unit, sizeof i.slot[0].unit, "classic3");
    snprintf(i.slot[0].cfg, sizeof i.slot[0].cfg, "out_bits=8 s_frac=12 lerp_frac=11");
    snprintf(i.slot[1].unit, sizeof i.slot[1].unit, "classic3");
    snprintf(i.slot[1].cfg, sizeof i.slot[1].cfg, "out_bits=10 s_frac=14 lerp_frac=13");
    size_t n = np_link_info_encode(p, &i);
    NP_CHECK(n == 48 + 2 * 128, "INFO length %zu", n);
    NP_CHECK(np_link_info_decode(p, n, &i2) == 0 && memcmp(&i, &i2, sizeof i) == 0, "INFO round trip");
    p[16 + 20] = 'x'; /* a byte after the board id's NUL */
    NP_CHECK(np_link_info_decode(p, n, &i2) != 0, "non-NUL padding refused");
    NP_CHECK(np_link_info_decode(p, n - 4, &i2) != 0, "wrong length refused");

    np_link_config c, c2;
    const np_unit *u = classic();
    np_unit_cfg cfg;
    np_unit_fields f;
    cfg_of(u, &cfg, NULL);
    u->fields(&cfg, &f);
    memset(&c, 0, sizeof c);
    snprintf(c.unit, sizeof c.unit, "classic3");
    np_unit_cfg_format(u, &cfg, c.cfg, sizeof c.cfg);
    np_link_layout_init(&c.lay, &f);
    n = np_link_config_encode(p, &c);
    NP_CHECK(n == 36 + 36, "CONFIG length %zu (section 8 says 72)", n);
    NP_CHECK(p[16] == 3 && p[17] == 1 && p[18] == 8 && p[19] == 4 && p[20] == 16 && p[23] == 0 && p[28] == 8,
             "CONFIG layout bytes");
    NP_CHECK(np_link_config_decode(p, n, &c2) == 0 && strcmp(c2.cfg, c.cfg) == 0 && strcmp(c2.unit, "classic3") == 0 &&
                 c2.lay.in_stride == 8 && c2.lay.out_stride == 4,
             "CONFIG round trip");
    p[18] = 12;
    NP_CHECK(np_link_config_decode(p, n, &c2) != 0, "inconsistent stride refused");

    np_link_ack a = { 9, 100000000, 8, 4 }, a2;
    n = np_link_ack_encode(p, &a);
    NP_CHECK(n == 16 && np_link_ack_decode(p, n, &a2) == 0 && a2.latency == 9 && a2.clock_hz == 100000000 &&
                 a2.in_stride == 8 && a2.out_stride == 4,
             "CONFIG_ACK round trip");
    np_link_bye b = { 1000000, 1004401, 7, 489, 0 }, b2;
    n = np_link_bye_encode(p, &b);
    NP_CHECK(n == 32 && np_link_bye_decode(p, n, &b2) == 0 && memcmp(&b, &b2, sizeof b) == 0, "BYE_ACK round trip");
    np_link_error e = { NP_LINK_E_BAD_SEQ, 17, "DATA seq 18, expected 17" }, e2;
    n = np_link_error_encode(p, &e);
    NP_CHECK(n == 64 && np_link_error_decode(p, n, &e2) == 0 && e2.code == 6 && e2.detail == 17 &&
                 strcmp(e2.msg, e.msg) == 0,
             "ERROR round trip");
    NP_CHECK(strcmp(np_link_errcode_name(NP_LINK_E_BAD_SEQ), "BAD_SEQ") == 0, "error names");
    return 0;
}

/* ------------------------------------------------------------------------- */
/* Talking to the emulator by hand. */

typedef struct chat {
    np_board *b;
    np_link_rx rx;
    uint8_t f[NP_LINK_MAX_FRAME];
    uint32_t seq;
    uint8_t in[2 * NP_LINK_MAX_FRAME];
    size_t have, at;
} chat;

static void chat_open(chat *c, const np_board_opts *o)
{
    memset(c, 0, sizeof *c);
    /* (c is large: callers keep it static) */
    c->b = np_board_new(o);
    np_link_rx_init(&c->rx, NP_LINK_MAX_PAYLOAD);
}

static void chat_close(chat *c)
{
    np_board_free(c->b);
    np_link_rx_free(&c->rx);
}

static void chat_send(chat *c, unsigned type, uint64_t tag, unsigned count, const void *p, unsigned len)
{
    np_link_hdr h = { NP_LINK_VERSION, type, c->seq++, tag, count, len };
    size_t n = np_link_encode(c->f, &h, p);
    np_board_rx(c->b, c->f, n);
}

/* The next frame from the board into ev (payload copied to buf); the rx event. */
static np_link_rx_event chat_recv(chat *c, np_link_rx_ev *ev, uint8_t *buf)
{
    for (;;) {
        const uint8_t *p = c->in + c->at;
        size_t left = c->have - c->at;
        np_link_rx_event e = np_link_rx_step(&c->rx, &p, &left, ev);
        c->at = c->have - left;
        if (e != NP_RX_MORE) {
            if (e == NP_RX_FRAME && buf)
                memcpy(buf, ev->payload, ev->h.len);
            return e;
        }
        c->have = np_board_tx(c->b, c->in, sizeof c->in);
        c->at = 0;
        if (c->have == 0)
            return NP_RX_MORE;
    }
}

static void config_payload(const np_unit *u, const char *spec, uint8_t *p, unsigned *len)
{
    np_unit_cfg cfg;
    np_unit_fields f;
    np_link_config c;
    cfg_of(u, &cfg, spec);
    u->fields(&cfg, &f);
    memset(&c, 0, sizeof c);
    snprintf(c.unit, sizeof c.unit, "%s", u->name);
    np_unit_cfg_format(u, &cfg, c.cfg, sizeof c.cfg);
    np_link_layout_init(&c.lay, &f);
    *len = (unsigned)np_link_config_encode(p, &c);
}

/* Section 8 of docs/usb-protocol.md, frame by frame. */
static int t_doc_session(void)
{
    static chat c;
    np_board_opts o;
    memset(&o, 0, sizeof o);
    chat_open(&c, &o);
    uint8_t p[NP_LINK_MAX_PAYLOAD];
    np_link_rx_ev ev;
    chat_send(&c, NP_LINK_HELLO, 0xfeedfacecafebeefu, 0, NULL, 0);
    NP_CHECK(c.f[0] == 0x4e && c.f[1] == 0x50 && c.f[2] == 1 && c.f[3] == 1, "HELLO first word");
    NP_CHECK(np_link_get32(c.f + 24) == 0, "HELLO pcrc of the empty payload is 0");
    NP_CHECK(chat_recv(&c, &ev, p) == NP_RX_FRAME && ev.h.type == NP_LINK_INFO && ev.h.seq == 0 &&
                 ev.h.tag == 0xfeedfacecafebeefu,
             "INFO echoes the nonce with seq 0");
    np_link_info info;
    NP_CHECK(np_link_info_decode(p, ev.h.len, &info) == 0 && info.version == 1 && info.window >= 1 &&
                 info.n_slots == 0,
             "INFO payload");
    unsigned len;
    config_payload(classic(), NULL, p, &len);
    NP_CHECK(len == 72, "CONFIG len 0x48");
    chat_send(&c, NP_LINK_CONFIG, 0, 0, p, len);
    NP_CHECK(c.f[4] == 1 && c.f[18] == 0x48 && c.f[19] == 0, "CONFIG seq 1, len 0048");
    NP_CHECK(chat_recv(&c, &ev, p) == NP_RX_FRAME && ev.h.type == NP_LINK_CONFIG_ACK && ev.h.seq == 1 &&
                 ev.h.tag == 0 && ev.h.len == 16,
             "CONFIG_ACK");
    NP_CHECK(p[0] == 9 && p[1] == 0 && p[8] == 8 && p[9] == 4, "latency 9, strides 8/4");
    uint64_t in[2][3] = { { 0x12ab, 0x0080, 0xffff }, { 0x0100, 0x0203, 0x8000 } };
    const np_unit *u = classic();
    np_unit_cfg cfg;
    cfg_of(u, &cfg, NULL);
    unsigned lane3[3] = { 2, 2, 2 };
    np_link_pack(p, in[0], lane3, 3, 8);
    np_link_pack(p + 8, in[1], lane3, 3, 8);
    chat_send(&c, NP_LINK_DATA, 0, 2, p, 16);
    NP_CHECK(c.f[4] == 2 && c.f[16] == 2 && c.f[18] == 0x10, "DATA seq 2, count 2, len 0010");
    NP_CHECK(chat_recv(&c, &ev, p) == NP_RX_FRAME && ev.h.type == NP_LINK_RESULT && ev.h.seq == 2 &&
                 ev.h.count == 2 && ev.h.len == 8,
             "RESULT");
    for (unsigned k = 0; k < 2; k++) {
        uint64_t want;
        u->eval(&cfg, in[k], &want);
        NP_CHECK(p[4 * k] == want && p[4 * k + 1] == 0 && p[4 * k + 2] == 0 && p[4 * k + 3] == 0,
                 "record %u: %02x, model %02llx", k, p[4 * k], (unsigned long long)want);
    }
    chat_send(&c, NP_LINK_BYE, 0, 0, NULL, 0);
    NP_CHECK(chat_recv(&c, &ev, p) == NP_RX_FRAME && ev.h.type == NP_LINK_BYE_ACK && ev.h.seq == 3 && ev.h.len == 32,
             "BYE_ACK");
    np_link_bye bye;
    np_link_bye_decode(p, 32, &bye);
    NP_CHECK(bye.records == 2 && bye.data_frames == 1 && bye.errors == 0 && bye.cycles >= 2 + 9,
             "counters: %llu records, %llu cycles", (unsigned long long)bye.records, (unsigned long long)bye.cycles);
    chat_close(&c);
    return 0;
}

/* Section 6: each error, then halted until HELLO. */
static int t_board_errors(void)
{
    static chat c;
    np_board_opts o;
    memset(&o, 0, sizeof o);
    uint8_t p[NP_LINK_MAX_PAYLOAD];
    np_link_rx_ev ev;
    unsigned len;
    np_link_error e;
    const np_link_error *last;

    /* DATA before CONFIG. */
    chat_open(&c, &o);
    chat_send(&c, NP_LINK_HELLO, 1, 0, NULL, 0);
    chat_recv(&c, &ev, p);
    memset(p, 0, 8);
    chat_send(&c, NP_LINK_DATA, 0, 1, p, 8);
    NP_CHECK(chat_recv(&c, &ev, p) == NP_RX_FRAME && ev.h.type == NP_LINK_ERROR, "ERROR frame");
    np_link_error_decode(p, ev.h.len, &e);
    NP_CHECK(e.code == NP_LINK_E_NOT_CONFIGURED, "NOT_CONFIGURED, got %s", np_link_errcode_name(e.code));
    /* Halted: a CONFIG now is ignored... */
    config_payload(classic(), NULL, p, &len);
    chat_send(&c, NP_LINK_CONFIG, 0, 0, p, len);
    NP_CHECK(chat_recv(&c, &ev, p) == NP_RX_MORE, "halted board stays silent");
    /* ...until HELLO. */
    c.seq = 0;
    chat_send(&c, NP_LINK_HELLO, 2, 0, NULL, 0);
    NP_CHECK(chat_recv(&c, &ev, p) == NP_RX_FRAME && ev.h.type == NP_LINK_INFO && ev.h.seq == 0 && ev.h.tag == 2,
             "HELLO restarts the session");
    /* A gap in seq. */
    config_payload(classic(), NULL, p, &len);
    c.seq = 5;
    chat_send(&c, NP_LINK_CONFIG, 0, 0, p, len);
    NP_CHECK(chat_recv(&c, &ev, p) == NP_RX_FRAME && ev.h.type == NP_LINK_ERROR && ev.h.tag == 1, "ERROR tag = expected seq");
    np_link_error_decode(p, ev.h.len, &e);
    NP_CHECK(e.code == NP_LINK_E_BAD_SEQ && e.detail == 1, "BAD_SEQ detail %u", (unsigned)e.detail);
    chat_close(&c);

    /* A corrupted OUT frame, a wrong version, a bad length, unknown configurations. */
    struct {
        const char *what;
        int mode;
        uint32_t code;
    } cases[] = {
        { "payload CRC", 0, NP_LINK_E_BAD_CRC },       { "version 2", 1, NP_LINK_E_BAD_VERSION },
        { "len not count*stride", 2, NP_LINK_E_BAD_LENGTH }, { "unknown unit", 3, NP_LINK_E_NO_SUCH_CONFIG },
        { "non-canonical config", 4, NP_LINK_E_NO_SUCH_CONFIG }, { "wrong widths", 5, NP_LINK_E_BAD_LAYOUT },
        { "board type from host", 6, NP_LINK_E_BAD_TYPE },
    };
    for (unsigned k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        chat_open(&c, &o);
        chat_send(&c, NP_LINK_HELLO, 1, 0, NULL, 0);
        chat_recv(&c, &ev, p);
        config_payload(classic(), NULL, p, &len);
        if (cases[k].mode == 3)
            memcpy(p, "nosuchunit\0\0\0\0\0", 16);
        if (cases[k].mode == 4)
            p[36 + 10] = p[36 + 20] = ','; /* "out_bits=8,s_frac=12,lerp_frac=11": valid, not canonical */
        if (cases[k].mode == 5)
            p[28] = 9; /* out_bits field width */
        if (cases[k].mode >= 3 && cases[k].mode <= 5) {
            if (cases[k].mode == 5)
                p[19] = 4; /* keep the stride consistent with a 9-bit lane (2 bytes -> 4) */
            chat_send(&c, NP_LINK_CONFIG, 0, 0, p, len);
        } else {
            chat_send(&c, NP_LINK_CONFIG, 0, 0, p, len);
            chat_recv(&c, &ev, p);
            memset(p, 0, 16);
            np_link_hdr h = { NP_LINK_VERSION, NP_LINK_DATA, c.seq++, 0, 2, 16 };
            size_t n = np_link_encode(c.f, &h, p);
            if (cases[k].mode == 0)
                c.f[30] ^= 1u;
            if (cases[k].mode == 1) {
                c.f[2] = 2;
                np_link_put32(c.f + 20, np_link_crc32(0, c.f, 20));
            }
            if (cases[k].mode == 2) {
                c.f[16] = 3; /* count 3, len still 16 */
                np_link_put32(c.f + 20, np_link_crc32(0, c.f, 20));
            }
            if (cases[k].mode == 6) {
                c.f[3] = NP_LINK_RESULT;
                np_link_put32(c.f + 20, np_link_crc32(0, c.f, 20));
            }
            np_board_rx(c.b, c.f, n);
        }
        np_link_rx_event r = chat_recv(&c, &ev, p);
        NP_CHECK(r == NP_RX_FRAME && ev.h.type == NP_LINK_ERROR, "%s: no ERROR frame (event %d type %s)",
                 cases[k].what, (int)r, np_link_type_name(ev.h.type));
        last = np_board_last_error(c.b);
        NP_CHECK(last->code == cases[k].code, "%s: %s, want %s", cases[k].what, np_link_errcode_name(last->code),
                 np_link_errcode_name(cases[k].code));
        printf("%-22s -> ERROR %s: %s\n", cases[k].what, np_link_errcode_name(last->code), last->msg);
        chat_close(&c);
    }
    return 0;
}

/* Section 4.2 and 6: a refused CONFIG halts the board: a second CONFIG is not heard until HELLO. */
static int t_config_refused_halts(void)
{
    static chat c;
    np_board_opts o;
    memset(&o, 0, sizeof o);
    o.n_slots = 1;
    snprintf(o.slot[0].unit, sizeof o.slot[0].unit, "classic3");
    snprintf(o.slot[0].cfg, sizeof o.slot[0].cfg, "out_bits=8 s_frac=12 lerp_frac=11");
    uint8_t p[NP_LINK_MAX_PAYLOAD];
    np_link_rx_ev ev;
    unsigned len;
    chat_open(&c, &o);
    chat_send(&c, NP_LINK_HELLO, 7, 0, NULL, 0);
    chat_recv(&c, &ev, p);
    config_payload(classic(), "out_bits=10", p, &len);
    chat_send(&c, NP_LINK_CONFIG, 0, 0, p, len);
    NP_CHECK(chat_recv(&c, &ev, p) == NP_RX_FRAME && ev.h.type == NP_LINK_ERROR, "refused");
    NP_CHECK(np_board_last_error(c.b)->code == NP_LINK_E_NO_SUCH_CONFIG, "NO_SUCH_CONFIG");
    config_payload(classic(), NULL, p, &len); /* the slot's own, next seq: still not heard */
    chat_send(&c, NP_LINK_CONFIG, 0, 0, p, len);
    NP_CHECK(chat_recv(&c, &ev, p) == NP_RX_MORE, "a board halted by a refused CONFIG stays silent");
    c.seq = 0;
    chat_send(&c, NP_LINK_HELLO, 8, 0, NULL, 0);
    NP_CHECK(chat_recv(&c, &ev, p) == NP_RX_FRAME && ev.h.type == NP_LINK_INFO && ev.h.tag == 8, "HELLO reopens");
    chat_close(&c);
    return 0;
}

/*
 * Section 2 and 3: the state before the first HELLO (halted, hunting), and
 * what a hunting receiver does with a header whose CRC is right but whose
 * len or ver is out of range: discards its first byte and hunts on, silently
 * (no ERROR), except a HELLO of another version, which is answered with
 * ERROR BAD_VERSION (section 10).
 */
static int t_hunting(void)
{
    static chat c;
    np_board_opts o;
    memset(&o, 0, sizeof o);
    uint8_t p[NP_LINK_MAX_PAYLOAD];
    np_link_rx_ev ev;
    unsigned len;
    chat_open(&c, &o);
    /* Hunting from power-on: a header with len above the board's max_payload, one with len not a multiple of 4, a ver 9 DATA. */
    uint8_t f[NP_LINK_HDR_BYTES];
    np_link_hdr bad[3] = { { 1, NP_LINK_DATA, 5, 0, 1, 65532 }, { 1, NP_LINK_DATA, 5, 0, 1, 6 },
                           { 9, NP_LINK_DATA, 5, 0, 1, 8 } };
    for (unsigned k = 0; k < 3; k++) {
        np_link_seal(c.f, &bad[k]);
        memcpy(f, c.f, sizeof f); /* the header alone: its payload never comes */
        np_board_rx(c.b, f, sizeof f);
    }
    NP_CHECK(chat_recv(&c, &ev, p) == NP_RX_MORE, "out-of-range headers while hunting: no ERROR");
    /* Before any HELLO: a CONFIG and a DATA frame are not heard. */
    config_payload(classic(), NULL, p, &len);
    chat_send(&c, NP_LINK_CONFIG, 0, 0, p, len);
    memset(p, 0, 8);
    chat_send(&c, NP_LINK_DATA, 0, 1, p, 8);
    NP_CHECK(chat_recv(&c, &ev, p) == NP_RX_MORE, "a board before its first HELLO is silent");
    NP_CHECK(np_board_get_stats(c.b)->errors_sent == 0, "no ERROR sent");
    c.seq = 0;
    chat_send(&c, NP_LINK_HELLO, 0x1234, 0, NULL, 0);
    NP_CHECK(chat_recv(&c, &ev, p) == NP_RX_FRAME && ev.h.type == NP_LINK_INFO && ev.h.tag == 0x1234,
             "the HELLO after them is found and answered");
    /* A HELLO of version 2 to this version-1 board, in a session: ERROR BAD_VERSION, seq 0, the nonce. */
    np_link_hdr h2 = { 2, NP_LINK_HELLO, 0, 0xabcdef, 0, 0 };
    size_t n = np_link_seal(c.f, &h2);
    np_board_rx(c.b, c.f, n);
    NP_CHECK(chat_recv(&c, &ev, p) == NP_RX_FRAME && ev.h.type == NP_LINK_ERROR && ev.h.seq == 0 &&
                 ev.h.tag == 0xabcdef && ev.h.version == 1,
             "foreign HELLO: ERROR seq %u tag %llx", (unsigned)ev.h.seq, (unsigned long long)ev.h.tag);
    np_link_error e;
    NP_CHECK(np_link_error_decode(p, ev.h.len, &e) == 0 && e.code == NP_LINK_E_BAD_VERSION && e.detail == 1,
             "BAD_VERSION, detail 1");
    printf("version-2 HELLO -> ERROR %s detail %u: %s\n", np_link_errcode_name(e.code), (unsigned)e.detail, e.msg);
    chat_close(&c);
    return 0;
}

/* One session of job j against a board made with bo; the host's fault (NONE when done). */
static np_link_fault session_with(const np_link_job *j, const np_board_opts *bo, char *msg, size_t msglen)
{
    np_journal jn;
    np_host *h = memory_host(j, &jn);
    np_board *b = np_board_new(bo);
    np_loop_opts lo;
    memset(&lo, 0, sizeof lo);
    lo.timeout = 0.5;
    np_link_loopback(h, b, &lo);
    np_link_fault f = np_host_get_fault(h);
    snprintf(msg, msglen, "%s", f == NP_FAULT_NONE && !(np_host_done(h) && jn.n_checked == j->n)
                                    ? "not done" : np_host_fault_msg(h));
    if (f == NP_FAULT_NONE && !(np_host_done(h) && jn.n_checked == j->n))
        f = NP_FAULT_USB;
    np_host_free(h);
    np_board_free(b);
    np_journal_close(&jn);
    return f;
}

/* Section 10: a board that answers HELLO with ERROR BAD_VERSION (it speaks version 2). */
static int t_hello_bad_version(void)
{
    np_link_job j;
    classic_job(&j, NULL, 1000, 17);
    np_board_opts bo;
    memset(&bo, 0, sizeof bo);
    bo.version = 2;
    char msg[1024];
    np_link_fault f = session_with(&j, &bo, msg, sizeof msg);
    NP_CHECK(f == NP_FAULT_INCOMPATIBLE, "fault %s: %s", np_link_fault_name(f), msg);
    NP_CHECK(strstr(msg, "refused HELLO: ERROR BAD_VERSION") && strstr(msg, "speaks protocol version 2"), "%s", msg);
    NP_CHECK(!strstr(msg, "sent nothing"), "not a time-out: %s", msg);
    printf("%s\n", msg);
    np_link_job_free(&j);
    return 0;
}

/*
 * Section 4.1: the smallest max_payload the document allows (292) works; a
 * board announcing less (64, and 288: more than classic3's 72-byte CONFIG,
 * still below the minimum) is refused with the documented message.
 */
static int t_min_payload(void)
{
    np_link_job j;
    classic_job(&j, "out_bits=16,s_frac=16,lerp_frac=16", 5000, 18);
    np_board_opts bo;
    memset(&bo, 0, sizeof bo);
    bo.max_payload = NP_LINK_MIN_PAYLOAD;
    char msg[1024];
    np_link_fault f = session_with(&j, &bo, msg, sizeof msg);
    NP_CHECK(NP_LINK_MIN_PAYLOAD == 36 + 256, "the minimum is the longest CONFIG payload");
    NP_CHECK(f == NP_FAULT_NONE, "max_payload 292: %s", msg);
    unsigned small[] = { 64, 288 };
    for (unsigned k = 0; k < 2; k++) {
        bo.max_payload = small[k];
        f = session_with(&j, &bo, msg, sizeof msg);
        NP_CHECK(f == NP_FAULT_INCOMPATIBLE && strstr(msg, "less than the 292 the protocol requires"),
                 "max_payload %u: %s: %s", small[k], np_link_fault_name(f), msg);
        printf("max_payload %u: %s\n", small[k], msg);
    }
    np_link_job_free(&j);
    return 0;
}

/* An ERROR left queued by an earlier session (no nonce) is stale: the host skips it and streams. */
static int t_stale_error(void)
{
    np_link_job j;
    classic_job(&j, NULL, 3000, 19);
    np_board_opts bo;
    memset(&bo, 0, sizeof bo);
    static chat c;
    memset(&c, 0, sizeof c);
    c.b = np_board_new(&bo);
    uint8_t p[8] = { 0 };
    chat_send(&c, NP_LINK_HELLO, 99, 0, NULL, 0);
    chat_send(&c, NP_LINK_DATA, 0, 1, p, 8); /* DATA before CONFIG: ERROR NOT_CONFIGURED queued */
    NP_CHECK(np_board_get_stats(c.b)->errors_sent == 1, "an ERROR is queued");
    np_journal jn;
    np_host *h = memory_host(&j, &jn);
    np_loop_opts lo;
    memset(&lo, 0, sizeof lo);
    np_link_loopback(h, c.b, &lo);
    NP_CHECK(np_host_done(h) && jn.n_checked == j.n, "%s", np_host_fault_msg(h));
    np_host_free(h);
    np_board_free(c.b);
    np_journal_close(&jn);
    np_link_job_free(&j);
    return 0;
}

/* The emulator's cycle-accurate results equal the bit-exact model. */
static int t_board_vs_model(void)
{
    const char *specs[] = { NULL, "out_bits=10", "out_bits=16", "out_bits=4,s_frac=3,lerp_frac=2" };
    const np_unit *u = classic();
    for (unsigned s = 0; s < sizeof specs / sizeof specs[0]; s++) {
        np_unit_cfg cfg;
        cfg_of(u, &cfg, specs[s]);
        uint64_t (*bnd)[NP_UNIT_MAX_FIELDS] = calloc(4096, sizeof *bnd);
        size_t nb = u->boundary(&cfg, bnd, 4096);
        if (nb > 4096)
            nb = 4096;
        np_link_job j;
        np_link_job_init(&j, u, &cfg, nb + 20000);
        np_rng r;
        np_rng_seed(&r, 42 + s);
        uint64_t out[NP_UNIT_MAX_FIELDS];
        for (uint64_t i = 0; i < j.n; i++) {
            uint64_t in[NP_UNIT_MAX_FIELDS] = { 0 };
            if (i < nb)
                memcpy(in, bnd[i], sizeof in);
            else
                for (unsigned k = 0; k < 3; k++)
                    in[k] = np_rng_next(&r) & 0xffffu;
            u->eval(&cfg, in, out);
            np_link_job_set(&j, i, in, out);
        }
        np_link_job_seal(&j);
        np_journal jn;
        np_host *h = memory_host(&j, &jn);
        np_board_opts bo;
        memset(&bo, 0, sizeof bo);
        np_board *b = np_board_new(&bo);
        np_loop_opts lo;
        memset(&lo, 0, sizeof lo);
        np_link_loopback(h, b, &lo);
        NP_CHECK(np_host_done(h), "%s: %s", specs[s] ? specs[s] : "default", np_host_fault_msg(h));
        NP_CHECK(jn.n_checked == j.n && jn.n_errors == 0, "%s: %llu checked, %llu errors",
                 specs[s] ? specs[s] : "default", (unsigned long long)jn.n_checked, (unsigned long long)jn.n_errors);
        printf("%-32s %llu vectors (%zu boundary), %llu errors, %.4f clocks per vector\n",
               specs[s] ? specs[s] : "default", (unsigned long long)j.n, nb, (unsigned long long)jn.n_errors,
               (double)np_board_get_stats(b)->cycles / (double)j.n);
        np_board_free(b);
        np_host_free(h);
        np_journal_close(&jn);
        np_link_job_free(&j);
        free(bnd);
    }
    return 0;
}

/* ------------------------------------------------------------------------- */
/* Whole sessions. */

typedef struct fails {
    uint64_t index[16];
    unsigned n;
} fails;

static void record_fail(void *ctx, uint64_t index, const uint64_t *got)
{
    fails *f = ctx;
    (void)got;
    if (f->n < 16)
        f->index[f->n] = index;
    f->n++;
}

typedef struct session {
    np_host *h;
    np_board *b;
    np_journal jn;
    fails fl;
    int stopped;
    uint64_t board_records;
} session;

/* One session of job j against an emulator with fault f; journal at path (NULL: memory). */
static void run_session(session *s, const np_link_job *j, const char *path, int resume, const np_board_fault *f,
                        size_t chunk, uint64_t stop_after, double timeout)
{
    memset(s, 0, sizeof *s);
    char err[1024];
    if (np_journal_open(&s->jn, path, j, resume, err, sizeof err) != 0) {
        fprintf(stderr, "journal: %s\n", err);
        exit(2);
    }
    np_host_opts ho;
    memset(&ho, 0, sizeof ho);
    ho.on_fail = record_fail;
    ho.fail_ctx = &s->fl;
    s->h = np_host_new(j, &s->jn, &ho);
    np_board_opts bo;
    memset(&bo, 0, sizeof bo);
    if (f)
        bo.fault = *f;
    s->b = np_board_new(&bo);
    np_loop_opts lo;
    memset(&lo, 0, sizeof lo);
    lo.chunk = chunk;
    lo.stop_after = stop_after;
    lo.timeout = timeout;
    s->stopped = np_link_loopback(s->h, s->b, &lo);
    s->board_records = np_board_get_stats(s->b)->records;
}

static void end_session(session *s)
{
    np_board_free(s->b);
    np_host_free(s->h);
    np_journal_close(&s->jn);
}

static int t_e2e(void)
{
    np_link_job j;
    classic_job(&j, NULL, 200000, 7);
    session s;
    double t0 = np_now();
    run_session(&s, &j, NULL, 0, NULL, 1000, 0, 2.0);
    double t = np_now() - t0;
    NP_CHECK(np_host_done(s.h), "%s", np_host_fault_msg(s.h));
    NP_CHECK(s.jn.n_checked == j.n && s.jn.n_errors == 0 && s.fl.n == 0, "%llu checked, %llu errors",
             (unsigned long long)s.jn.n_checked, (unsigned long long)s.jn.n_errors);
    NP_CHECK(s.board_records == j.n, "board saw %llu records", (unsigned long long)s.board_records);
    const np_host_stats *st = np_host_get_stats(s.h);
    NP_CHECK(st->have_bye && st->bye.records == j.n, "BYE_ACK counts %llu", (unsigned long long)st->bye.records);
    printf("200000 vectors in 1000-byte chunks: %.3f s, %llu frames out, %llu in\n", t,
           (unsigned long long)st->frames_out, (unsigned long long)st->frames_in);
    end_session(&s);
    np_link_job_free(&j);
    return 0;
}

static int t_e2e_wrong_bit(void)
{
    np_link_job j;
    classic_job(&j, NULL, 100000, 8);
    np_board_fault f = { NP_BOARD_WRONG_BIT, 77777, 5 };
    session s;
    run_session(&s, &j, NULL, 0, &f, 0, 0, 2.0);
    NP_CHECK(np_host_done(s.h), "%s", np_host_fault_msg(s.h));
    NP_CHECK(s.fl.n == 1 && s.fl.index[0] == 77777, "%u failures, first at %llu", s.fl.n,
             (unsigned long long)s.fl.index[0]);
    NP_CHECK(s.jn.n_checked == j.n && s.jn.n_errors == 1, "checked %llu", (unsigned long long)s.jn.n_checked);
    NP_CHECK(s.jn.n_fails == 1 && s.jn.fails[0].index == 77777, "journal failure");
    /* The got word differs from the expected one in exactly bit 5. */
    uint64_t want;
    np_link_unpack(j.want + 77777u * j.lay.out_stride, &want, j.lay.out_lane, 1);
    NP_CHECK((s.jn.fails[0].got[0] ^ want) == 32u, "got %llx want %llx", (unsigned long long)s.jn.fails[0].got[0],
             (unsigned long long)want);
    end_session(&s);
    np_link_job_free(&j);
    return 0;
}

/* Each frame fault stops the session with its fault; a resume finishes the job exactly. */
static int t_e2e_faults(void)
{
    struct {
        np_board_fault_kind kind;
        np_link_fault want;
        const char *words;
    } cases[] = {
        { NP_BOARD_CORRUPT, NP_FAULT_CORRUPT, "fails its payload CRC" },
        { NP_BOARD_SHORT, NP_FAULT_SHORT, "was cut off after" },
        { NP_BOARD_DROP, NP_FAULT_SEQ, "lost or repeated frame" },
        { NP_BOARD_SILENT, NP_FAULT_TIMEOUT, "timeout: the board sent nothing" },
    };
    np_link_job j;
    classic_job(&j, NULL, 60000, 9);
    char path[256];
    tmp_path(path, sizeof path, "faults.journal");
    for (unsigned k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        unlink(path);
        np_board_fault f = { cases[k].kind, 30000, 0 };
        session s;
        run_session(&s, &j, path, 0, &f, 0, 0, 0.2);
        const char *msg = np_host_fault_msg(s.h);
        NP_CHECK(np_host_get_fault(s.h) == cases[k].want, "fault %s, want %s: %s",
                 np_link_fault_name(np_host_get_fault(s.h)), np_link_fault_name(cases[k].want), msg);
        NP_CHECK(strstr(msg, cases[k].words) != NULL, "message: %s", msg);
        uint64_t kept = s.jn.n_checked;
        NP_CHECK(kept > 0 && kept <= 30000 && s.jn.n_errors == 0, "kept %llu", (unsigned long long)kept);
        printf("%s\n  kept %llu verified vectors\n", msg, (unsigned long long)kept);
        end_session(&s);
        session r;
        run_session(&r, &j, path, 1, NULL, 0, 0, 2.0);
        NP_CHECK(np_host_done(r.h), "resume: %s", np_host_fault_msg(r.h));
        NP_CHECK(r.board_records == j.n - kept, "resume sent %llu, want %llu", (unsigned long long)r.board_records,
                 (unsigned long long)(j.n - kept));
        NP_CHECK(r.jn.n_checked == j.n && r.jn.n_errors == 0, "after resume %llu checked",
                 (unsigned long long)r.jn.n_checked);
        end_session(&r);
    }
    unlink(path);
    np_link_job_free(&j);
    return 0;
}

/* A board with stale frames queued from an earlier session: the host skips them. */
static int t_stale_input(void)
{
    np_link_job j;
    classic_job(&j, NULL, 5000, 10);
    np_board_opts bo;
    memset(&bo, 0, sizeof bo);
    np_board *b = np_board_new(&bo);
    /* An earlier host's session, cut off with results still queued. */
    static chat c;
    memset(&c, 0, sizeof c);
    c.b = b;
    uint8_t p[NP_LINK_MAX_PAYLOAD];
    unsigned len;
    chat_send(&c, NP_LINK_HELLO, 99, 0, NULL, 0);
    config_payload(classic(), NULL, p, &len);
    chat_send(&c, NP_LINK_CONFIG, 0, 0, p, len);
    memcpy(p, j.in, 16 * 8);
    chat_send(&c, NP_LINK_DATA, 0, 16, p, 16 * 8);
    NP_CHECK(np_board_tx_pending(b) > 0, "stale bytes queued");
    np_journal jn;
    np_host *h = memory_host(&j, &jn);
    np_loop_opts lo;
    memset(&lo, 0, sizeof lo);
    lo.chunk = 333;
    np_link_loopback(h, b, &lo);
    NP_CHECK(np_host_done(h) && jn.n_checked == j.n && jn.n_errors == 0, "%s", np_host_fault_msg(h));
    NP_CHECK(np_host_get_stats(h)->stale_bytes > 0, "stale bytes counted");
    printf("stale bytes skipped: %llu\n", (unsigned long long)np_host_get_stats(h)->stale_bytes);
    np_host_free(h);
    np_board_free(b);
    np_journal_close(&jn);
    np_link_job_free(&j);
    return 0;
}

/* A host frame corrupted on the way: the board says BAD_CRC, the host reports it. */
static int t_board_reports(void)
{
    np_link_job j;
    classic_job(&j, NULL, 20000, 11);
    np_journal jn;
    np_host *h = memory_host(&j, &jn);
    np_board_opts bo;
    memset(&bo, 0, sizeof bo);
    np_board *b = np_board_new(&bo);
    static uint8_t f[NP_LINK_MAX_FRAME], in[NP_LINK_MAX_FRAME];
    unsigned frames = 0;
    for (int guard = 0; guard < 10000 && !np_host_done(h) && np_host_get_fault(h) == NP_FAULT_NONE; guard++) {
        size_t n = np_host_pull(h, f, sizeof f);
        if (n) {
            if (++frames == 5)
                f[NP_LINK_HDR_BYTES + 100] ^= 0x40u; /* the 3rd DATA frame, in the cable */
            np_board_rx(b, f, n);
        }
        size_t m = np_board_tx(b, in, sizeof in);
        if (m)
            np_host_push(h, in, m);
    }
    const char *msg = np_host_fault_msg(h);
    NP_CHECK(np_host_get_fault(h) == NP_FAULT_BOARD && strstr(msg, "BAD_CRC"), "%s", msg);
    NP_CHECK(jn.n_checked == 2u * np_host_frame_records(h), "the two good frames are kept: %llu",
             (unsigned long long)jn.n_checked);
    printf("%s\n", msg);
    np_host_free(h);
    np_board_free(b);
    np_journal_close(&jn);
    np_link_job_free(&j);
    return 0;
}

/* A board with slots refuses another configuration; the host lists them. */
static int t_config_refused(void)
{
    np_link_job j;
    classic_job(&j, "out_bits=10", 100, 12);
    np_journal jn;
    np_host *h = memory_host(&j, &jn);
    np_board_opts bo;
    memset(&bo, 0, sizeof bo);
    bo.board_id = "classic3 on a test board";
    bo.n_slots = 1;
    snprintf(bo.slot[0].unit, sizeof bo.slot[0].unit, "classic3");
    snprintf(bo.slot[0].cfg, sizeof bo.slot[0].cfg, "out_bits=8 s_frac=12 lerp_frac=11");
    np_board *b = np_board_new(&bo);
    np_loop_opts lo;
    memset(&lo, 0, sizeof lo);
    np_link_loopback(h, b, &lo);
    const char *msg = np_host_fault_msg(h);
    NP_CHECK(np_host_get_fault(h) == NP_FAULT_CONFIG && strstr(msg, "NO_SUCH_CONFIG") &&
                 strstr(msg, "slot 0: classic3 out_bits=8"),
             "%s", msg);
    printf("%s\n", msg);
    np_host_free(h);
    np_board_free(b);
    np_journal_close(&jn);
    np_link_job_free(&j);
    return 0;
}

/* ------------------------------------------------------------------------- */
/* Journal. */

static void append_text(const char *path, const char *text)
{
    FILE *f = fopen(path, "a");
    fputs(text, f);
    fclose(f);
}

static int t_journal(void)
{
    np_link_job j, other;
    classic_job(&j, NULL, 10000, 13);
    classic_job(&other, NULL, 10000, 14);
    char path[256], err[1024];
    tmp_path(path, sizeof path, "journal");
    np_journal jn;
    NP_CHECK(np_journal_open(&jn, path, &j, 1, err, sizeof err) != 0, "resume without a file is refused");
    np_journal_close(&jn);
    NP_CHECK(np_journal_open(&jn, path, &j, 0, err, sizeof err) == 0, "%s", err);
    np_journal_fail f = { 1234, { 0x7f } };
    NP_CHECK(np_journal_append(&jn, 1024, 1024, &f, 1, err, sizeof err) == 0, "%s", err);
    NP_CHECK(np_journal_append(&jn, 0, 1024, NULL, 0, err, sizeof err) == 0, "%s", err);
    np_journal_close(&jn);
    /* Fresh start over an unfinished journal: refused. */
    NP_CHECK(np_journal_open(&jn, path, &j, 0, err, sizeof err) != 0 && strstr(err, "--resume"), "%s", err);
    np_journal_close(&jn);
    /* Other vectors: refused, naming both. */
    NP_CHECK(np_journal_open(&jn, path, &other, 1, err, sizeof err) != 0 && strstr(err, "belongs to other vectors"),
             "%s", err);
    printf("%s\n", err);
    np_journal_close(&jn);
    /* A torn last line (a kill mid-write): ignored, and cut off. */
    {
        /* One append torn by a kill: its E line whole, its R line cut. */
        char torn[64];
        snprintf(torn, sizeof torn, "E 800 7f *%08x\nR 800 4", (unsigned)np_link_crc32(0, "E 800 7f", 8));
        append_text(path, torn);
    }
    NP_CHECK(np_journal_open(&jn, path, &j, 1, err, sizeof err) == 0, "%s", err);
    NP_CHECK(jn.n_checked == 2048 && jn.n_errors == 1 && jn.n_fails == 1 && jn.fails[0].index == 1234 &&
                 jn.fails[0].got[0] == 0x7f,
             "loaded %llu checked, %llu errors", (unsigned long long)jn.n_checked, (unsigned long long)jn.n_errors);
    NP_CHECK(np_journal_append(&jn, 2048, 100, NULL, 0, err, sizeof err) == 0, "%s", err);
    np_journal_close(&jn);
    NP_CHECK(np_journal_open(&jn, path, &j, 1, err, sizeof err) == 0 && jn.n_checked == 2148,
             "after the cut: %s %llu", err, (unsigned long long)jn.n_checked);
    np_journal_close(&jn);
    /* A damaged line (the first record, after the magic line and four bindings): refused. */
    char copy[300];
    tmp_path(copy, sizeof copy, "journal.bad");
    FILE *in = fopen(path, "r"), *out = fopen(copy, "w");
    int ch, line = 1;
    while ((ch = fgetc(in)) != EOF) {
        if (line == 6 && ch == '4')
            ch = '5';
        line += ch == '\n';
        fputc(ch, out);
    }
    fclose(in);
    fclose(out);
    NP_CHECK(np_journal_open(&jn, copy, &j, 1, err, sizeof err) != 0 && strstr(err, "damaged"), "%s", err);
    np_journal_close(&jn);
    /* A frame whose every record failed: 2048 E lines for one R line. */
    unlink(copy);
    NP_CHECK(np_journal_open(&jn, copy, &j, 0, err, sizeof err) == 0, "%s", err);
    {
        np_journal_fail *all = calloc(2048, sizeof *all);
        for (unsigned k = 0; k < 2048; k++) {
            all[k].index = 4096u + k;
            all[k].got[0] = k & 0xffu;
        }
        NP_CHECK(np_journal_append(&jn, 4096, 2048, all, 2048, err, sizeof err) == 0, "%s", err);
        free(all);
    }
    np_journal_close(&jn);
    NP_CHECK(np_journal_open(&jn, copy, &j, 1, err, sizeof err) == 0 && jn.n_errors == 2048 && jn.n_fails == 2048 &&
                 jn.fails[2047].index == 4096u + 2047u && jn.fails[2047].got[0] == 0xff,
             "2048 failures in one record: %s", err);
    np_journal_close(&jn);
    /* The same range twice: refused (nothing is counted twice). */
    unlink(copy);
    NP_CHECK(np_journal_open(&jn, copy, &j, 0, err, sizeof err) == 0, "%s", err);
    np_journal_append(&jn, 0, 10, NULL, 0, err, sizeof err);
    np_journal_append(&jn, 5, 10, NULL, 0, err, sizeof err);
    np_journal_close(&jn);
    NP_CHECK(np_journal_open(&jn, copy, &j, 1, err, sizeof err) != 0 && strstr(err, "twice"), "%s", err);
    np_journal_close(&jn);
    unlink(copy);
    unlink(path);
    np_link_job_free(&j);
    np_link_job_free(&other);
    return 0;
}

/* Read every R line of a journal: 1 when they cover 0..n-1 exactly once. */
static int journal_exactly_once(const char *path, uint64_t n)
{
    FILE *f = fopen(path, "r");
    if (!f)
        return 0;
    uint8_t *seen = calloc((size_t)n, 1);
    char line[512];
    int ok = 1;
    while (fgets(line, sizeof line, f)) {
        unsigned long long first, count, errs;
        if (line[0] != 'R' || sscanf(line, "R %llx %llx %llx", &first, &count, &errs) != 3)
            continue;
        for (uint64_t i = first; i < first + count && i < n; i++)
            ok &= seen[i]++ == 0;
    }
    for (uint64_t i = 0; i < n; i++)
        ok &= seen[i] == 1;
    fclose(f);
    free(seen);
    return ok;
}

/*
 * Kill and resume: the host process is killed (SIGKILL) at a random moment,
 * then resumed; every vector ends up verified exactly once, and the resume
 * sends exactly what the journal did not hold.
 */
static int t_kill_resume(void)
{
    uint64_t seed = np_child_seed();
    np_rng r;
    np_rng_seed(&r, seed);
    np_link_job j;
    classic_job(&j, NULL, 300000, 15);
    char path[256];
    tmp_path(path, sizeof path, "kill.journal");
    for (int trial = 0; trial < 6; trial++) {
        unlink(path);
        /* Measure nothing: pick a kill time in 0..150 ms (a full run takes ~250 ms). */
        long us = (long)np_rng_below(&r, 150000);
        pid_t pid = fork();
        if (pid == 0) {
            session s;
            run_session(&s, &j, path, 0, NULL, 0, 0, 2.0);
            _exit(np_host_done(s.h) ? 0 : 1);
        }
        struct timespec ts = { 0, us * 1000L };
        nanosleep(&ts, NULL);
        kill(pid, SIGKILL);
        int st;
        waitpid(pid, &st, 0);
        /* What the journal holds now is what the resume must not send. */
        np_journal probe;
        char err[1024];
        uint64_t held = 0;
        if (np_journal_open(&probe, path, &j, 1, err, sizeof err) == 0)
            held = probe.n_checked;
        else
            NP_CHECK(strstr(err, "cannot resume") != NULL, "after the kill: %s", err); /* killed before creating it */
        np_journal_close(&probe);
        if (held == 0 && access(path, F_OK) != 0) {
            printf("trial %d: killed after %ld us, before the journal existed\n", trial, us);
            continue;
        }
        session s;
        run_session(&s, &j, path, 1, NULL, 0, 0, 2.0);
        NP_CHECK(np_host_done(s.h), "trial %d: %s", trial, np_host_fault_msg(s.h));
        NP_CHECK(s.board_records == j.n - held, "trial %d: resume sent %llu, journal held %llu", trial,
                 (unsigned long long)s.board_records, (unsigned long long)held);
        NP_CHECK(s.jn.n_checked == j.n && s.jn.n_errors == 0, "trial %d: %llu checked", trial,
                 (unsigned long long)s.jn.n_checked);
        end_session(&s);
        NP_CHECK(journal_exactly_once(path, j.n), "trial %d: journal does not cover every vector exactly once", trial);
        printf("trial %d: killed after %ld us%s with %llu vectors journaled; resume sent %llu; every vector once\n",
               trial, us, WIFSIGNALED(st) ? "" : " (it had finished)", (unsigned long long)held,
               (unsigned long long)(j.n - held));
    }
    /* And in process, at every frame boundary of a small job: stop, resume. */
    np_link_job small;
    classic_job(&small, NULL, 9000, 16);
    for (uint64_t stop = 1; stop <= 8; stop++) {
        unlink(path);
        session s;
        run_session(&s, &small, path, 0, NULL, 0, stop, 2.0);
        uint64_t held = s.jn.n_checked;
        end_session(&s);
        session t;
        run_session(&t, &small, path, 1, NULL, 0, 0, 2.0);
        NP_CHECK(np_host_done(t.h) && t.board_records == small.n - held && journal_exactly_once(path, small.n),
                 "stop after %llu frames: held %llu, resent %llu", (unsigned long long)stop,
                 (unsigned long long)held, (unsigned long long)t.board_records);
        end_session(&t);
    }
    unlink(path);
    np_link_job_free(&small);
    np_link_job_free(&j);
    return 0;
}

/* ------------------------------------------------------------------------- */
/* The command against the emulator (--emulate): the journal's bindings, --force, the ref column, SIGINT. */

typedef struct cli_run {
    int status; /* exit status, or 128 + signal */
    char out[16384], err[16384];
} cli_run;

static void read_into(const char *path, char *buf, size_t len)
{
    FILE *f = fopen(path, "r");
    size_t n = f ? fread(buf, 1, len - 1, f) : 0;
    buf[n] = '\0';
    if (f)
        fclose(f);
    unlink(path);
}

/* Count the complete R lines of a journal (0 when there is none). */
static unsigned r_lines(const char *path)
{
    FILE *f = fopen(path, "r");
    char line[512];
    unsigned n = 0;
    while (f && fgets(line, sizeof line, f))
        n += line[0] == 'R' && strchr(line, '\n') != NULL;
    if (f)
        fclose(f);
    return n;
}

/*
 * noisepipe stream ARGS (NULL-terminated) in a child; with sig, the signal
 * is sent once the journal at jpath holds a verified range.
 */
static void cli(cli_run *r, int sig, const char *jpath, ...)
{
    char *argv[32];
    int n = 0;
    argv[n++] = (char *)NP_CLI;
    argv[n++] = (char *)"stream";
    va_list ap;
    va_start(ap, jpath);
    for (char *a; n < 31 && (a = va_arg(ap, char *)) != NULL;)
        argv[n++] = a;
    va_end(ap);
    argv[n] = NULL;
    char out[128], err[128];
    tmp_path(out, sizeof out, "cli.out");
    tmp_path(err, sizeof err, "cli.err");
    pid_t pid = np_child_start(argv, out, err);
    if (sig) {
        double t0 = np_now();
        while (r_lines(jpath) < 1 && np_now() - t0 < 60) {
            struct timespec ts = { 0, 200000 };
            nanosleep(&ts, NULL);
        }
        kill(pid, sig);
    }
    int st;
    waitpid(pid, &st, 0);
    r->status = WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
    read_into(out, r->out, sizeof r->out);
    read_into(err, r->err, sizeof r->err);
    printf("$ noisepipe");
    for (int k = 1; k < n; k++)
        printf(" %s", argv[k]);
    printf("\n%s%s[exit %d]\n", r->out, r->err, r->status);
}

/* The file's bytes, for "left exactly as it was". */
static char *file_bytes(const char *path, size_t *n)
{
    FILE *f = fopen(path, "rb");
    char *b = NULL;
    *n = 0;
    if (!f)
        return NULL;
    fseek(f, 0, SEEK_END);
    long len = ftell(f);
    fseek(f, 0, SEEK_SET);
    b = len < 0 ? NULL : malloc((size_t)len + 1u);
    if (!b) {
        fclose(f);
        return NULL;
    }
    *n = fread(b, 1, (size_t)len, f);
    b[*n] = '\0'; /* the callers search it as a string */
    fclose(f);
    return b;
}

static int same_bytes(const char *path, const char *was, size_t n)
{
    size_t m;
    char *now = file_bytes(path, &m);
    int same = now && m == n && memcmp(now, was, n) == 0;
    free(now);
    return same;
}

/*
 * Item 3 of issue 11 on the emulator path: a journal is never replaced
 * without --force, is bound to the vector file's size and to the target,
 * and a vector file whose reference column is wrong is refused.
 */
static int t_cli_journal(void)
{
    char vec[256], jnl[256], vec2[256];
    tmp_path(vec, sizeof vec, "cli.vec");
    tmp_path(jnl, sizeof jnl, "cli.journal");
    tmp_path(vec2, sizeof vec2, "cli2.vec");
    char cmd[1024];
    snprintf(cmd, sizeof cmd, "%s vectors --unit classic3 -n 20000 -o %s", NP_CLI, vec);
    NP_CHECK(system(cmd) == 0, "%s", cmd);
    cli_run r;
    /* A link fault part way: the journal keeps what was verified. */
    cli(&r, 0, NULL, "--emulate", vec, "--journal", jnl, "--inject", "silent:12000", "--timeout", "0.3", NULL);
    NP_CHECK(r.status == 1 && strstr(r.out, "INCOMPLETE"), "exit %d", r.status);
    size_t n0;
    char *before = file_bytes(jnl, &n0);
    NP_CHECK(before && strstr(before, "\ntarget=emulator *") && strstr(before, "\nsize="), "bindings: %s",
             before ? before : "(none)");
    /* Without --resume: refused, the journal left exactly as it was. */
    cli(&r, 0, NULL, "--emulate", vec, "--journal", jnl, NULL);
    NP_CHECK(r.status == 2 && strstr(r.err, "--resume, or start over with --force"), "exit %d", r.status);
    NP_CHECK(same_bytes(jnl, before, n0), "the journal changed");
    /* The same records in a file of another size (one comment line more): refused, naming size=. */
    snprintf(cmd, sizeof cmd, "(head -n 12 %s; echo '# a comment'; tail -n +13 %s) > %s", vec, vec, vec2);
    NP_CHECK(system(cmd) == 0, "%s", cmd);
    cli(&r, 0, NULL, "--emulate", vec2, "--journal", jnl, "--resume", NULL);
    NP_CHECK(r.status == 2 && strstr(r.err, "'size=") && strstr(r.err, "another vector file"), "exit %d", r.status);
    NP_CHECK(same_bytes(jnl, before, n0), "the journal changed");
    /* --resume and --force together: usage. */
    cli(&r, 0, NULL, "--emulate", vec, "--journal", jnl, "--resume", "--force", NULL);
    NP_CHECK(r.status == 2 && strstr(r.err, "give one of them"), "exit %d", r.status);
    /* Resumed: complete, every vector once. */
    cli(&r, 0, NULL, "--emulate", vec, "--journal", jnl, "--resume", NULL);
    NP_CHECK(r.status == 0 && strstr(r.out, "In 23200 tests, no errors found"), "exit %d", r.status);
    NP_CHECK(journal_exactly_once(jnl, 23200), "every vector once");
    /* A finished journal is not replaced either; --force starts over. */
    free(before);
    before = file_bytes(jnl, &n0);
    cli(&r, 0, NULL, "--emulate", vec, "--journal", jnl, NULL);
    NP_CHECK(r.status == 2 && strstr(r.err, "23200 of 23200 vectors verified") && same_bytes(jnl, before, n0),
             "exit %d", r.status);
    cli(&r, 0, NULL, "--emulate", vec, "--journal", jnl, "--force", NULL);
    NP_CHECK(r.status == 0 && strstr(r.out, "(new, --force)") && journal_exactly_once(jnl, 23200), "exit %d",
             r.status);
    free(before);
    /* The reference column checked as verify does: one f.ref word changed. */
    snprintf(cmd, sizeof cmd,
             "awk 'NR==40{ $5 = ($5 == \"3ff0000000000000\" ? \"3fe0000000000000\" : \"3ff0000000000000\") } 1' %s > %s",
             vec, vec2);
    NP_CHECK(system(cmd) == 0, "%s", cmd);
    cli(&r, 0, NULL, "--emulate", vec2, "--journal", jnl, "--force", NULL);
    NP_CHECK(r.status == 2 && strstr(r.err, ":40: f.ref") && strstr(r.err, "disagrees with the float reference"),
             "exit %d", r.status);
    unlink(vec);
    unlink(vec2);
    unlink(jnl);
    return 0;
}

/* SIGINT and SIGTERM during stream: 130/143, the note says what was kept and how to resume; the resume is exact. */
static int t_cli_interrupt(void)
{
    char jnl[256];
    tmp_path(jnl, sizeof jnl, "int.journal");
    int sigs[2] = { SIGINT, SIGTERM };
    for (unsigned k = 0; k < 2; k++) {
        unlink(jnl);
        cli_run r;
        cli(&r, sigs[k], jnl, "--emulate", "--unit", "classic3", "--random", "2000000", "--journal", jnl, NULL);
        NP_CHECK(r.status == 128 + sigs[k], "exit %d", r.status);
        NP_CHECK(strstr(r.err, k ? "interrupted by SIGTERM" : "interrupted by SIGINT") && strstr(r.err, "journal ") &&
                     strstr(r.err, "vectors verified") && strstr(r.err, "run again with --resume"),
                 "the note: %s", r.err);
        unsigned long long kept = 0;
        const char *at = strstr(r.err, " keeps ");
        NP_CHECK(at && sscanf(at, " keeps %llu", &kept) == 1, "a count in the note");
        cli(&r, 0, NULL, "--emulate", "--unit", "classic3", "--random", "2000000", "--journal", jnl, "--resume", NULL);
        NP_CHECK(r.status == 0 && strstr(r.out, "In 2000000 tests, no errors found"), "resumed: exit %d", r.status);
        unsigned long long before = 0;
        at = strstr(r.out, "resumed: ");
        NP_CHECK(at && sscanf(at, "resumed: %llu", &before) == 1 && before >= kept,
                 "the journal holds at least what the note said (%llu, %llu)", before, kept);
        NP_CHECK(journal_exactly_once(jnl, 2000000), "every vector once");
    }
    unlink(jnl);
    return 0;
}

static const np_test_case cases[] = {
    { "crc_kat", t_crc_kat },
    { "frame_codec", t_frame_codec },
    { "rx_reassembly", t_rx_reassembly },
    { "rx_short", t_rx_short },
    { "records", t_records },
    { "payloads", t_payloads },
    { "doc_session", t_doc_session },
    { "board_errors", t_board_errors },
    { "config_refused_halts", t_config_refused_halts },
    { "hunting", t_hunting },
    { "hello_bad_version", t_hello_bad_version },
    { "min_payload", t_min_payload },
    { "stale_error", t_stale_error },
    { "cli_journal", t_cli_journal },
    { "cli_interrupt", t_cli_interrupt },
    { "board_vs_model", t_board_vs_model },
    { "e2e", t_e2e },
    { "e2e_wrong_bit", t_e2e_wrong_bit },
    { "e2e_faults", t_e2e_faults },
    { "stale_input", t_stale_input },
    { "board_reports", t_board_reports },
    { "config_refused", t_config_refused },
    { "journal", t_journal },
    { "kill_resume", t_kill_resume },
    { NULL, NULL },
};

NP_TEST_MAIN(cases)
