/* SPDX-License-Identifier: MIT */
/*
 * link_engine.c - the host's protocol engine (docs/usb-protocol.md, sections
 * 3, 4 and 7): session, window, verification of every result bit for bit,
 * faults and their messages. A byte-stream state machine: a transport
 * (link_loopback.c, link_usb.c) moves its bytes and owns time.
 */
#include "np_link.h"

#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "np_common.h"
#include "np_rng.h"

typedef enum host_state {
    H_HELLO,     /* HELLO due */
    H_WAIT_INFO, /* dropping stale IN bytes until INFO with our nonce */
    H_CONFIG,    /* CONFIG due */
    H_WAIT_ACK,
    H_STREAM,    /* DATA out, RESULT in */
    H_WAIT_BYE,
    H_DONE,
    H_FAULT
} host_state;

typedef struct outstanding {
    uint32_t seq;
    uint64_t tag;
    unsigned count;
} outstanding;

struct np_host {
    const np_link_job *j;
    np_journal *jn;
    np_host_opts o;
    np_link_rx rx;
    host_state state;
    uint32_t tx_seq, rx_expect;
    unsigned frame_records, window;
    uint64_t cursor;
    outstanding *out;
    unsigned out_head, out_n, out_cap;
    int stopping;
    np_link_fault fault;
    char msg[1024];
    np_host_stats st;
    np_journal_fail *fbuf;
    size_t fbuf_cap;
    np_link_error stale_err; /* the last ERROR met while waiting for INFO without our nonce (code 0: none) */
    unsigned stale_err_ver;
    size_t config_len;       /* payload bytes of our CONFIG frame */
};

const char *np_link_fault_name(np_link_fault f)
{
    static const char *const names[] = {
        "none", "timeout", "device gone", "stalled endpoint", "USB error", "corrupted frame",
        "short frame", "lost or repeated frame", "board error", "configuration refused", "journal",
        "incompatible board",
    };
    return (unsigned)f < sizeof names / sizeof names[0] ? names[f] : "?";
}

static void vfault(np_host *h, np_link_fault f, const char *fmt, va_list ap)
{
    if (h->fault != NP_FAULT_NONE)
        return;
    h->fault = f;
    h->state = H_FAULT;
    vsnprintf(h->msg, sizeof h->msg, fmt, ap);
}

void np_host_fault(np_host *h, np_link_fault f, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vfault(h, f, fmt, ap);
    va_end(ap);
}

np_host *np_host_new(const np_link_job *j, np_journal *jn, const np_host_opts *o)
{
    np_host *h = calloc(1, sizeof *h);
    if (!h)
        return NULL;
    h->j = j;
    h->jn = jn;
    h->o = *o;
    if (!h->o.nonce) {
        struct timespec ts;
        clock_gettime(CLOCK_REALTIME, &ts);
        uint64_t s = (uint64_t)ts.tv_nsec ^ (uint64_t)ts.tv_sec << 30 ^ (uint64_t)getpid() << 48;
        h->o.nonce = np_splitmix64(&s) | 1u;
    }
    if (np_link_rx_init(&h->rx, NP_LINK_MAX_PAYLOAD) != 0) {
        free(h);
        return NULL;
    }
    return h;
}

void np_host_free(np_host *h)
{
    if (!h)
        return;
    np_link_rx_free(&h->rx);
    free(h->out);
    free(h->fbuf);
    free(h);
}

/* "vectors 2048..4095" of an outstanding frame. */
static void range_text(char *buf, size_t len, uint64_t tag, unsigned count)
{
    snprintf(buf, len, "vectors %llu..%llu", (unsigned long long)tag,
             (unsigned long long)(tag + count - 1u));
}

void np_host_outstanding(const np_host *h, char *buf, size_t len)
{
    if (h->out_n == 0) {
        snprintf(buf, len, "no DATA frame outstanding");
        return;
    }
    const outstanding *a = &h->out[h->out_head];
    const outstanding *z = &h->out[(h->out_head + h->out_n - 1u) % h->out_cap];
    snprintf(buf, len, "%u DATA frame%s outstanding (vectors %llu..%llu)", h->out_n,
             h->out_n == 1 ? "" : "s", (unsigned long long)a->tag,
             (unsigned long long)(z->tag + z->count - 1u));
}

static const char *waiting_for(const np_host *h)
{
    switch (h->state) {
    case H_WAIT_INFO: return "INFO (the answer to HELLO)";
    case H_WAIT_ACK: return "CONFIG_ACK";
    case H_WAIT_BYE: return "BYE_ACK";
    default: return "RESULT";
    }
}

void np_host_timeout(np_host *h, double seconds)
{
    char outs[128], part[480] = "";
    np_host_outstanding(h, outs, sizeof outs);
    size_t pend = np_link_rx_pending(&h->rx);
    if (pend)
        snprintf(part, sizeof part, "; %zu bytes of an unfinished frame arrived before the silence (a short frame?)", pend);
    if (h->state == H_WAIT_INFO && h->stale_err.code)
        snprintf(part + strlen(part), sizeof part - strlen(part),
                 "; the board had sent ERROR %s (code %u, version %u frame: %s), not marked as the answer to this HELLO",
                 np_link_errcode_name(h->stale_err.code), (unsigned)h->stale_err.code, h->stale_err_ver,
                 h->stale_err.msg[0] ? h->stale_err.msg : "no message");
    np_host_fault(h, NP_FAULT_TIMEOUT,
                  "timeout: the board sent nothing for %.1f s while the host waited for %s; %s%s",
                  seconds, waiting_for(h), outs, part);
}

int np_host_waiting(const np_host *h)
{
    return h->state == H_WAIT_INFO || h->state == H_WAIT_ACK || h->state == H_WAIT_BYE ||
           (h->state == H_STREAM && h->out_n > 0);
}

int np_host_done(const np_host *h) { return h->state == H_DONE; }
np_link_fault np_host_get_fault(const np_host *h) { return h->fault; }
const char *np_host_fault_msg(const np_host *h) { return h->msg; }
const np_host_stats *np_host_get_stats(const np_host *h) { return &h->st; }
int np_host_complete(const np_host *h) { return h->jn->n_checked == h->j->n; }
unsigned np_host_frame_records(const np_host *h) { return h->frame_records; }

static size_t emit(np_host *h, uint8_t *buf, unsigned type, uint64_t tag, unsigned count, unsigned len)
{
    np_link_hdr hd = { NP_LINK_VERSION, type, h->tx_seq++, tag, count, len };
    size_t n = np_link_seal(buf, &hd);
    h->st.frames_out++;
    h->st.bytes_out += n;
    return n;
}

/* The CONFIG payload for job j at p (section 4.2): its length, 0 when it cannot be encoded. */
static size_t config_encode(const np_link_job *j, uint8_t *p)
{
    np_link_config c;
    memset(&c, 0, sizeof c);
    snprintf(c.unit, sizeof c.unit, "%s", j->unit->name);
    snprintf(c.cfg, sizeof c.cfg, "%s", j->cfg_text);
    c.lay = j->lay;
    return np_link_config_encode(p, &c);
}

size_t np_host_pull(np_host *h, uint8_t *buf, size_t cap)
{
    if (cap < NP_LINK_MAX_FRAME)
        return 0;
    const np_link_job *j = h->j;
    switch (h->state) {
    case H_HELLO:
        h->tx_seq = 0;
        h->state = H_WAIT_INFO;
        return emit(h, buf, NP_LINK_HELLO, h->o.nonce, 0, 0);
    case H_CONFIG: {
        size_t len = config_encode(j, np_link_payload(buf)); /* fits: checked against INFO */
        h->state = H_WAIT_ACK;
        return emit(h, buf, NP_LINK_CONFIG, 0, 0, (unsigned)len);
    }
    case H_STREAM: {
        if (h->out_n >= h->window)
            return 0;
        while (h->cursor < j->n && np_journal_has(h->jn, h->cursor))
            h->cursor++;
        if (h->stopping || h->cursor == j->n) {
            if (h->out_n)
                return 0;
            h->state = H_WAIT_BYE;
            return emit(h, buf, NP_LINK_BYE, 0, 0, 0);
        }
        uint64_t first = h->cursor, end = first;
        while (end < j->n && end - first < h->frame_records && !np_journal_has(h->jn, end))
            end++;
        unsigned count = (unsigned)(end - first);
        unsigned len = count * j->lay.in_stride;
        memcpy(np_link_payload(buf), j->in + first * j->lay.in_stride, len);
        outstanding *slot = &h->out[(h->out_head + h->out_n) % h->out_cap];
        slot->seq = h->tx_seq;
        slot->tag = first;
        slot->count = count;
        h->out_n++;
        h->cursor = end;
        h->st.sent += count;
        if (h->st.t_first_data == 0)
            h->st.t_first_data = np_now();
        return emit(h, buf, NP_LINK_DATA, first, count, len);
    }
    default:
        return 0;
    }
}

/* INFO with our nonce: the session is open. */
static void on_info(np_host *h, const np_link_rx_ev *ev)
{
    np_link_info *in = &h->st.info;
    if (np_link_info_decode(ev->payload, ev->h.len, in) != 0) {
        np_host_fault(h, NP_FAULT_CORRUPT, "malformed INFO payload from the board");
        return;
    }
    if (in->version != NP_LINK_VERSION) {
        np_host_fault(h, NP_FAULT_INCOMPATIBLE, "the board speaks protocol version %u; this host speaks %d",
                      (unsigned)in->version, NP_LINK_VERSION);
        return;
    }
    /* Section 4.1: the board must take the longest CONFIG; this host's own must fit in any case. */
    uint8_t cp[NP_LINK_CONFIG_FIXED + NP_LINK_CFG_BYTES];
    h->config_len = config_encode(h->j, cp);
    if (!h->config_len) {
        np_host_fault(h, NP_FAULT_CONFIG, "unit name or configuration text too long for CONFIG");
        return;
    }
    if (in->max_payload < NP_LINK_MIN_PAYLOAD || in->max_payload < h->config_len) {
        np_host_fault(h, NP_FAULT_INCOMPATIBLE,
                      "the board '%s' announces max_payload %u bytes, less than the %d the protocol requires "
                      "(docs/usb-protocol.md 4.1: the longest CONFIG payload, 36 + 256 bytes); this host's CONFIG "
                      "for %s %s alone is %zu bytes",
                      in->board_id, (unsigned)in->max_payload, NP_LINK_MIN_PAYLOAD, h->j->unit->name,
                      h->j->cfg_text, h->config_len);
        return;
    }
    const np_link_layout *l = &h->j->lay;
    unsigned fr = h->o.frame_records ? h->o.frame_records : NP_LINK_MAX_COUNT;
    if (fr > in->max_payload / l->in_stride)
        fr = in->max_payload / l->in_stride;
    if (fr > NP_LINK_MAX_PAYLOAD / l->out_stride)
        fr = NP_LINK_MAX_PAYLOAD / l->out_stride;
    if (fr == 0) {
        np_host_fault(h, NP_FAULT_CONFIG, "the board's max_payload (%u bytes) holds no %u-byte record",
                      (unsigned)in->max_payload, l->in_stride);
        return;
    }
    h->frame_records = fr;
    h->window = h->o.window && h->o.window < in->window ? h->o.window : in->window;
    h->out_cap = h->window;
    h->out = calloc(h->out_cap, sizeof *h->out);
    h->fbuf_cap = fr;
    h->fbuf = calloc(fr, sizeof *h->fbuf);
    if (!h->out || !h->fbuf) {
        np_host_fault(h, NP_FAULT_USB, "out of memory");
        return;
    }
    h->rx_expect = 1;
    h->state = H_CONFIG;
}

static void config_refused(np_host *h, const np_link_error *e)
{
    char offers[1024] = "";
    size_t at = 0;
    const np_link_info *in = &h->st.info;
    if (in->n_slots == 0)
        snprintf(offers, sizeof offers, " (it says it offers any configuration)");
    for (uint32_t k = 0; k < in->n_slots && at < sizeof offers; k++)
        at += (size_t)snprintf(offers + at, sizeof offers - at, "%s slot %u: %s %s", k ? ";" : " it offers:",
                               (unsigned)k, in->slot[k].unit, in->slot[k].cfg);
    np_host_fault(h, NP_FAULT_CONFIG, "the board '%s' does not run %s %s: %s (%s)%s", in->board_id,
                  h->j->unit->name, h->j->cfg_text, np_link_errcode_name(e->code), e->msg, offers);
}

/* A RESULT: must answer the oldest outstanding DATA frame; verify every record. */
static void on_result(np_host *h, const np_link_rx_ev *ev)
{
    const np_link_job *j = h->j;
    const np_link_layout *l = &j->lay;
    char want[64], got[64];
    if (h->out_n == 0) {
        np_host_fault(h, NP_FAULT_SEQ, "RESULT seq %u for vectors %llu.. arrived, but no DATA frame is outstanding",
                      (unsigned)ev->h.seq, (unsigned long long)ev->h.tag);
        return;
    }
    outstanding *o = &h->out[h->out_head];
    if (ev->h.tag != o->tag || ev->h.count != o->count) {
        range_text(want, sizeof want, o->tag, o->count);
        range_text(got, sizeof got, ev->h.tag, ev->h.count ? ev->h.count : 1u);
        np_host_fault(h, NP_FAULT_SEQ, "the board answered %s (RESULT seq %u), but the oldest outstanding DATA frame holds %s",
                      got, (unsigned)ev->h.seq, want);
        return;
    }
    if (ev->h.len != o->count * l->out_stride) {
        range_text(want, sizeof want, o->tag, o->count);
        np_host_fault(h, NP_FAULT_SHORT, "short frame from the board: RESULT seq %u (%s) carries %u bytes for %u records of %u bytes",
                      (unsigned)ev->h.seq, want, ev->h.len, o->count, l->out_stride);
        return;
    }
    size_t nf = 0;
    const uint8_t *g = ev->payload;
    const uint8_t *w = j->want + o->tag * l->out_stride;
    for (unsigned i = 0; i < o->count; i++, g += l->out_stride, w += l->out_stride) {
        if (memcmp(g, w, l->out_stride) == 0)
            continue;
        np_journal_fail *f = &h->fbuf[nf++];
        memset(f, 0, sizeof *f);
        f->index = o->tag + i;
        /* The whole record: pad bytes count too (section 5). */
        np_link_unpack(g, f->got, l->out_lane, l->n_out);
        for (unsigned k = l->n_out; k < NP_UNIT_MAX_FIELDS; k++)
            f->got[k] = 0;
        if (h->o.on_fail)
            h->o.on_fail(h->o.fail_ctx, f->index, f->got);
    }
    char err[512];
    if (np_journal_append(h->jn, o->tag, o->count, h->fbuf, nf, err, sizeof err) != 0) {
        np_host_fault(h, NP_FAULT_JOURNAL, "%s", err);
        return;
    }
    h->st.verified += o->count;
    h->st.errors += nf;
    h->st.t_last_result = np_now();
    h->out_head = (h->out_head + 1u) % h->out_cap;
    h->out_n--;
    if (h->o.max_errors && h->jn->n_errors >= h->o.max_errors)
        h->stopping = 1;
    if (h->o.on_progress)
        h->o.on_progress(h->o.fail_ctx, h->st.verified);
}

/* The board answered HELLO with ERROR (seq 0, our nonce): it will not open a session. */
static void hello_refused(np_host *h, const np_link_hdr *hd, const np_link_error *e)
{
    if (e->code == NP_LINK_E_BAD_VERSION) {
        np_host_fault(h, NP_FAULT_INCOMPATIBLE,
                      "the board refused HELLO: ERROR BAD_VERSION (code 3): it speaks protocol version %u, this host "
                      "speaks %d (%s); use a noisepipe that speaks version %u, or a board that speaks %d",
                      (unsigned)e->detail, NP_LINK_VERSION, e->msg[0] ? e->msg : "no message", (unsigned)e->detail,
                      NP_LINK_VERSION);
        return;
    }
    np_host_fault(h, NP_FAULT_BOARD, "the board refused HELLO: ERROR %s (code %u, detail %u, version %u frame): %s",
                  np_link_errcode_name(e->code), (unsigned)e->code, (unsigned)e->detail, hd->version,
                  e->msg[0] ? e->msg : "(no message)");
}

static void on_frame(np_host *h, const np_link_rx_ev *ev)
{
    const np_link_hdr *hd = &ev->h;
    if (h->state == H_WAIT_INFO) {
        if (hd->type == NP_LINK_INFO && hd->tag == h->o.nonce && hd->seq == 0 && hd->version == NP_LINK_VERSION) {
            h->st.frames_in++;
            on_info(h, ev);
        } else if (hd->type == NP_LINK_ERROR) {
            np_link_error e;
            int ok = np_link_error_decode(ev->payload, hd->len, &e) == 0;
            if (ok && hd->tag == h->o.nonce && hd->seq == 0) {
                h->st.frames_in++;
                hello_refused(h, hd, &e); /* section 3: the answer to this HELLO */
                return;
            }
            if (ok) { /* an earlier session's, or a board that does not echo the nonce: named on a time-out */
                h->stale_err = e;
                h->stale_err_ver = hd->version;
            }
            h->st.stale_bytes += NP_LINK_OVERHEAD + (uint64_t)hd->len;
        } else {
            h->st.stale_bytes += NP_LINK_OVERHEAD + (uint64_t)hd->len; /* an earlier session's */
        }
        return;
    }
    if (hd->version != NP_LINK_VERSION) { /* an ERROR of another version, in a session: as any ERROR */
        np_link_error e;
        if (np_link_error_decode(ev->payload, hd->len, &e) != 0)
            e.code = 0;
        np_host_fault(h, e.code == NP_LINK_E_BAD_VERSION ? NP_FAULT_INCOMPATIBLE : NP_FAULT_BOARD,
                      "the board sent a protocol version %u ERROR %s (code %u, detail %u): %s; this host speaks %d",
                      hd->version, np_link_errcode_name(e.code), (unsigned)e.code, (unsigned)e.detail,
                      e.msg[0] ? e.msg : "(no message)", NP_LINK_VERSION);
        return;
    }
    h->st.frames_in++;
    char outs[128];
    if (hd->seq != h->rx_expect) {
        np_host_outstanding(h, outs, sizeof outs);
        np_host_fault(h, NP_FAULT_SEQ,
                      "lost or repeated frame from the board: %s seq %u arrived, seq %u was expected (%s)",
                      np_link_type_name(hd->type), (unsigned)hd->seq, (unsigned)h->rx_expect, outs);
        return;
    }
    h->rx_expect++;
    if (hd->type == NP_LINK_ERROR) {
        np_link_error e;
        if (np_link_error_decode(ev->payload, hd->len, &e) != 0) {
            np_host_fault(h, NP_FAULT_CORRUPT, "malformed ERROR payload from the board");
            return;
        }
        if (h->state == H_WAIT_ACK && (e.code == NP_LINK_E_NO_SUCH_CONFIG || e.code == NP_LINK_E_BAD_LAYOUT)) {
            config_refused(h, &e);
            return;
        }
        np_host_outstanding(h, outs, sizeof outs);
        np_host_fault(h, NP_FAULT_BOARD,
                      "the board reported ERROR %s (code %u, detail %u) expecting host frame seq %llu: %s; %s",
                      np_link_errcode_name(e.code), (unsigned)e.code, (unsigned)e.detail,
                      (unsigned long long)hd->tag, e.msg[0] ? e.msg : "(no message)", outs);
        return;
    }
    switch (h->state) {
    case H_WAIT_ACK:
        if (hd->type == NP_LINK_CONFIG_ACK) {
            np_link_ack *a = &h->st.ack;
            if (np_link_ack_decode(ev->payload, hd->len, a) != 0 || a->in_stride != h->j->lay.in_stride ||
                a->out_stride != h->j->lay.out_stride) {
                np_host_fault(h, NP_FAULT_CONFIG, "the board's CONFIG_ACK does not confirm the record layout (strides %u/%u, host %u/%u)",
                              a->in_stride, a->out_stride, h->j->lay.in_stride, h->j->lay.out_stride);
                return;
            }
            h->state = H_STREAM;
            return;
        }
        break;
    case H_STREAM:
        if (hd->type == NP_LINK_RESULT) {
            on_result(h, ev);
            return;
        }
        break;
    case H_WAIT_BYE:
        if (hd->type == NP_LINK_BYE_ACK) {
            if (np_link_bye_decode(ev->payload, hd->len, &h->st.bye) == 0)
                h->st.have_bye = 1;
            h->state = H_DONE;
            return;
        }
        break;
    default:
        break;
    }
    np_host_fault(h, NP_FAULT_SEQ, "unexpected %s frame (seq %u) from the board while waiting for %s",
                  np_link_type_name(hd->type), (unsigned)hd->seq, waiting_for(h));
}

static void on_stream_error(np_host *h, np_link_rx_event e, const np_link_rx_ev *ev)
{
    if (h->state == H_WAIT_INFO)
        return; /* stale bytes of an earlier session: hunting */
    char what[160] = "";
    if (ev->h.type == NP_LINK_RESULT && h->out_n && ev->h.tag == h->out[h->out_head].tag) {
        char r[64];
        range_text(r, sizeof r, ev->h.tag, ev->h.count ? ev->h.count : 1u);
        snprintf(what, sizeof what, " (%s)", r);
    }
    switch (e) {
    case NP_RX_SHORT:
        np_host_fault(h, NP_FAULT_SHORT,
                      "short frame from the board: %s seq %u%s was cut off after %zu of its %u payload bytes (the next frame's header follows)",
                      np_link_type_name(ev->h.type), (unsigned)ev->h.seq, what, ev->short_at, ev->h.len);
        break;
    case NP_RX_BAD_CRC:
        np_host_fault(h, NP_FAULT_CORRUPT,
                      "corrupted frame from the board: %s seq %u%s fails its payload CRC (computed %08x, the frame says %08x)",
                      np_link_type_name(ev->h.type), (unsigned)ev->h.seq, what, (unsigned)ev->crc_got,
                      (unsigned)ev->crc_want);
        break;
    case NP_RX_BAD_VERSION:
        np_host_fault(h, NP_FAULT_INCOMPATIBLE, "the board sent a protocol version %u frame; this host speaks %d",
                      ev->h.version, NP_LINK_VERSION);
        break;
    case NP_RX_BAD_LENGTH:
        np_host_fault(h, NP_FAULT_CORRUPT, "corrupted frame header from the board: payload length %u", ev->h.len);
        break;
    default:
        np_host_fault(h, NP_FAULT_CORRUPT,
                      "corrupted stream from the board: no valid frame header where frame seq %u must start",
                      (unsigned)h->rx_expect);
        break;
    }
}

int np_host_push(np_host *h, const uint8_t *p, size_t n)
{
    h->st.bytes_in += n;
    while (h->state != H_FAULT) {
        np_link_rx_ev ev;
        np_link_rx_event e = np_link_rx_step(&h->rx, &p, &n, &ev);
        if (e == NP_RX_MORE)
            break;
        if (e == NP_RX_FRAME)
            on_frame(h, &ev);
        else
            on_stream_error(h, e, &ev);
    }
    if (h->state == H_WAIT_INFO)
        h->st.stale_bytes = h->rx.discarded;
    return h->state == H_FAULT ? -1 : 0;
}
