/* SPDX-License-Identifier: MIT */
/*
 * link_board.c - the board side of the USB link protocol, on the
 * cycle-accurate models: an emulated FPGA board.
 *
 * Written from docs/usb-protocol.md alone, section by section, as a board
 * designer would; the section numbers below point into it. Keep the two in
 * step: a change of the protocol changes the document first, then this file.
 * The frame codec it uses (link_proto.c) is the document's section 2 and 5.
 *
 * What the emulator chooses where the document leaves a choice:
 *   - It offers every unit of the registry in every valid configuration
 *     (INFO n_slots = 0) unless slots are given; a configuration must be in
 *     canonical form (np_unit_cfg_format), compared byte for byte.
 *   - It runs each DATA frame's records through the unit's np_pipe, one input
 *     per clock with the output always ready, and drains the pipe at the end
 *     of the frame (a real board may overlap frames: the protocol does not
 *     care, the cycle counts in BYE_ACK do).
 *   - NAK flow control: np_board_rx() takes nothing while more than tx_limit
 *     bytes wait to go IN.
 *   - It does not discard queued results on HELLO (section 3 allows either;
 *     the host ignores everything before the INFO that echoes its nonce).
 *   - Faults for tests (np_board_fault) are applied once, to the RESULT frame
 *     holding record `at`; after a SILENT fault it never sends again.
 *   - For tests of section 10 it can speak another protocol version
 *     (np_board_opts.version): then every version-1 frame is foreign to it, and
 *     it answers a version-1 HELLO with ERROR BAD_VERSION.
 */
#include "np_link.h"

#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

enum { DEFAULT_MAX_PAYLOAD = 16384, DEFAULT_WINDOW = 8 };

typedef enum board_state {
    B_HALTED,    /* no session, or after an error: only HELLO is heard (section 6) */
    B_READY,     /* session open, unconfigured */
    B_CONFIGURED /* a slot is selected: DATA is accepted */
} board_state;

struct np_board {
    np_board_opts o;
    np_link_rx rx;
    board_state state;
    uint32_t rx_expect; /* seq of the next OUT frame */
    uint32_t tx_seq;    /* seq of the next IN frame */
    /* The configured unit. */
    const np_unit *unit;
    np_unit_cfg cfg;
    np_link_layout lay;
    np_pipe pipe;
    int have_pipe;
    unsigned char *sig_in;
    /* IN queue: bytes tx[tx_start..tx_len) wait to be sent. */
    uint8_t *tx;
    size_t tx_start, tx_len, tx_cap;
    uint8_t *frame; /* scratch: the frame being built */
    /* Counters: lifetime, and the session's (BYE_ACK). */
    np_board_stats st;
    np_link_bye session;
    np_link_error last_err;
    int silent, fault_done;
};

/* ------------------------------------------------------------------------- */
/* Sending (IN). */

static int tx_reserve(np_board *b, size_t more)
{
    if (b->tx_start == b->tx_len)
        b->tx_start = b->tx_len = 0;
    if (b->tx_len + more <= b->tx_cap)
        return 0;
    if (b->tx_start) {
        memmove(b->tx, b->tx + b->tx_start, b->tx_len - b->tx_start);
        b->tx_len -= b->tx_start;
        b->tx_start = 0;
        if (b->tx_len + more <= b->tx_cap)
            return 0;
    }
    size_t cap = b->tx_cap ? b->tx_cap : 65536;
    while (cap < b->tx_len + more)
        cap *= 2;
    uint8_t *t = realloc(b->tx, cap);
    if (!t)
        return -1;
    b->tx = t;
    b->tx_cap = cap;
    return 0;
}

/* Queue n bytes of frame f (n may be less than the frame: a fault). */
static void tx_put(np_board *b, const uint8_t *f, size_t n)
{
    if (b->silent || tx_reserve(b, n) != 0)
        return;
    memcpy(b->tx + b->tx_len, f, n);
    b->tx_len += n;
}

/* Seal the frame in b->frame with this header and queue it; each IN frame takes the next seq. */
static void send_frame(np_board *b, unsigned type, uint64_t tag, unsigned count, unsigned len)
{
    np_link_hdr h = { b->o.version, type, b->tx_seq++, tag, count, len };
    size_t n = np_link_seal(b->frame, &h);
    tx_put(b, b->frame, n);
    if (!b->silent)
        b->st.frames_out++;
}

/* Section 6: one ERROR frame with this tag, then halted. */
static void verror(np_board *b, uint64_t tag, np_link_errcode code, uint32_t detail, const char *fmt,
                   va_list ap)
{
    np_link_error e = { (uint32_t)code, detail, "" };
    vsnprintf(e.msg, sizeof e.msg, fmt, ap);
    b->last_err = e;
    size_t len = np_link_error_encode(np_link_payload(b->frame), &e);
    send_frame(b, NP_LINK_ERROR, tag, 0, (unsigned)len);
    b->st.errors_sent++;
    b->session.errors++;
    b->state = B_HALTED;
}

/* An ERROR of the session: its tag is the OUT seq the board expected next. */
static void send_error(np_board *b, np_link_errcode code, uint32_t detail, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
static void send_error(np_board *b, np_link_errcode code, uint32_t detail, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    verror(b, b->rx_expect, code, detail, fmt, ap);
    va_end(ap);
}

/* The ERROR that answers a HELLO (section 3): seq 0, the HELLO's nonce as tag. */
static void refuse_hello(np_board *b, uint64_t nonce, np_link_errcode code, uint32_t detail, const char *fmt, ...)
    __attribute__((format(printf, 5, 6)));
static void refuse_hello(np_board *b, uint64_t nonce, np_link_errcode code, uint32_t detail, const char *fmt, ...)
{
    va_list ap;
    b->tx_seq = 0;
    b->rx_expect = 1;
    memset(&b->session, 0, sizeof b->session);
    va_start(ap, fmt);
    verror(b, nonce, code, detail, fmt, ap);
    va_end(ap);
}

/* ------------------------------------------------------------------------- */
/* Section 3 and 4.1: HELLO -> INFO. */

static void on_hello(np_board *b, const np_link_hdr *h)
{
    b->state = B_READY;
    b->rx_expect = 1; /* HELLO is seq 0 (section 3) */
    b->tx_seq = 0;
    memset(&b->session, 0, sizeof b->session);
    b->st.hellos++;
    np_link_info info;
    memset(&info, 0, sizeof info);
    info.version = b->o.version;
    info.max_payload = b->o.max_payload;
    info.window = b->o.window;
    info.n_slots = b->o.n_slots;
    snprintf(info.board_id, sizeof info.board_id, "%s",
             b->o.board_id ? b->o.board_id : "noisepipe board emulator");
    memcpy(info.slot, b->o.slot, sizeof info.slot);
    size_t len = np_link_info_encode(np_link_payload(b->frame), &info);
    send_frame(b, NP_LINK_INFO, h->tag, 0, (unsigned)len);
}

/* ------------------------------------------------------------------------- */
/* Section 4.2: CONFIG -> CONFIG_ACK or ERROR. */

static int layout_equal(const np_link_layout *a, const np_link_layout *c)
{
    if (a->n_in != c->n_in || a->n_out != c->n_out || a->in_stride != c->in_stride ||
        a->out_stride != c->out_stride)
        return 0;
    for (unsigned k = 0; k < a->n_in; k++)
        if (a->in_bits[k] != c->in_bits[k])
            return 0;
    for (unsigned k = 0; k < a->n_out; k++)
        if (a->out_bits[k] != c->out_bits[k])
            return 0;
    return 1;
}

static void on_config(np_board *b, const np_link_hdr *h, const uint8_t *payload)
{
    np_link_config c;
    if (np_link_config_decode(payload, h->len, &c) != 0) {
        send_error(b, NP_LINK_E_BAD_LENGTH, 0, "malformed CONFIG payload");
        return;
    }
    unsigned slot = 0;
    if (b->o.n_slots) {
        while (slot < b->o.n_slots &&
               (strcmp(b->o.slot[slot].unit, c.unit) != 0 || strcmp(b->o.slot[slot].cfg, c.cfg) != 0))
            slot++;
        if (slot == b->o.n_slots) {
            send_error(b, NP_LINK_E_NO_SUCH_CONFIG, 0, "no slot runs %.16s %.30s", c.unit, c.cfg);
            return;
        }
    }
    const np_unit *u = np_unit_find(c.unit);
    char err[256], canon[NP_LINK_CFG_BYTES];
    if (!u) {
        send_error(b, NP_LINK_E_NO_SUCH_CONFIG, 0, "unknown unit %.16s", c.unit);
        return;
    }
    if (np_unit_configure(u, &b->cfg, c.cfg, err, sizeof err) != 0) {
        send_error(b, NP_LINK_E_NO_SUCH_CONFIG, 0, "%.50s", err);
        return;
    }
    np_unit_cfg_format(u, &b->cfg, canon, sizeof canon);
    if (strcmp(canon, c.cfg) != 0) {
        send_error(b, NP_LINK_E_NO_SUCH_CONFIG, 0, "configuration not canonical");
        return;
    }
    np_unit_fields f;
    u->fields(&b->cfg, &f);
    np_link_layout lay;
    np_link_layout_init(&lay, &f);
    if (!layout_equal(&lay, &c.lay)) {
        send_error(b, NP_LINK_E_BAD_LAYOUT, 0, "field widths differ from %.16s's", c.unit);
        return;
    }
    /* Build the unit: a fresh pipe on the board's copy of the configuration. */
    if (b->have_pipe) {
        np_pipe_free(&b->pipe);
        b->have_pipe = 0;
    }
    free(b->sig_in);
    b->sig_in = NULL;
    if (u->pipe_init(&b->pipe, &b->cfg) != 0 || !(b->sig_in = calloc(1, b->pipe.sig_size))) {
        send_error(b, NP_LINK_E_INTERNAL, 0, "out of memory");
        return;
    }
    b->have_pipe = 1;
    b->unit = u;
    b->lay = lay;
    b->state = B_CONFIGURED;
    np_link_ack a = { np_pipe_latency(&b->pipe), 0, lay.in_stride, lay.out_stride };
    size_t len = np_link_ack_encode(np_link_payload(b->frame), &a);
    send_frame(b, NP_LINK_CONFIG_ACK, slot, 0, (unsigned)len);
}

/* ------------------------------------------------------------------------- */
/* Section 4.3: DATA -> RESULT, through the cycle-accurate pipe. */

/* Does the RESULT for records tag..tag+count-1 carry the armed frame fault? */
static int fault_here(const np_board *b, uint64_t tag, unsigned count)
{
    const np_board_fault *f = &b->o.fault;
    return !b->fault_done && f->kind >= NP_BOARD_CORRUPT && f->at >= tag && f->at - tag < count;
}

static void on_data(np_board *b, const np_link_hdr *h, const uint8_t *in)
{
    if (b->state != B_CONFIGURED) {
        send_error(b, NP_LINK_E_NOT_CONFIGURED, 0, "DATA before CONFIG");
        return;
    }
    const np_link_layout *l = &b->lay;
    if (h->count == 0 || (size_t)h->count * l->in_stride != h->len) {
        send_error(b, NP_LINK_E_BAD_LENGTH, 0, "DATA: %u records need %u bytes, len is %u",
                   h->count, h->count * l->in_stride, h->len);
        return;
    }
    if ((size_t)h->count * l->out_stride > NP_LINK_MAX_PAYLOAD) {
        send_error(b, NP_LINK_E_BAD_LENGTH, b->o.max_payload, "DATA: results would not fit one frame");
        return;
    }
    uint8_t *out = np_link_payload(b->frame);
    np_pipe *p = &b->pipe;
    np_pipe_stats before = p->stats;
    np_pipe_port port;
    memset(&port, 0, sizeof port);
    port.in_sig = b->sig_in;
    port.out_ready = 1;
    unsigned i_in = 0, i_out = 0;
    uint64_t w[NP_UNIT_MAX_FIELDS];
    const np_board_fault *f = &b->o.fault;
    /* Drive, clock, sample: one input per clock, as an RTL testbench would. */
    uint64_t budget = (uint64_t)h->count + 4u * np_pipe_latency(p) + 64u;
    while (i_out < h->count) {
        if (budget-- == 0) {
            send_error(b, NP_LINK_E_INTERNAL, 0, "the unit's pipe stopped delivering (%u of %u)", i_out, h->count);
            return;
        }
        port.in_valid = i_in < h->count;
        if (port.in_valid) {
            np_link_unpack(in + (size_t)i_in * l->in_stride, w, l->in_lane, l->n_in);
            for (unsigned k = 0; k < l->n_in; k++)
                w[k] &= np_link_mask(l->in_bits[k]);
            b->unit->sig_set_in(b->sig_in, w);
        }
        np_pipe_eval(p, &port);
        if (port.out_valid && port.out_ready) {
            b->unit->sig_get_out(&b->cfg, port.out_sig, w);
            if (f->kind == NP_BOARD_WRONG_BIT && f->at == h->tag + i_out) {
                w[0] ^= (uint64_t)1 << (f->bit & 63u);
                b->st.faults_applied++;
            }
            np_link_pack(out + (size_t)i_out * l->out_stride, w, l->out_lane, l->n_out, l->out_stride);
            i_out++;
        }
        int accepted = port.in_valid && port.in_ready;
        np_pipe_clock(p, &port);
        if (accepted)
            i_in++;
    }
    b->st.cycles += p->stats.cycles - before.cycles;
    b->st.stalls += p->stats.out_stalls - before.out_stalls;
    b->st.bubbles += p->stats.in_bubbles - before.in_bubbles;
    b->session.cycles += p->stats.cycles - before.cycles;
    b->session.stalls += p->stats.out_stalls - before.out_stalls;
    b->session.records += h->count;
    b->session.data_frames++;
    b->st.records += h->count;
    b->st.data_frames++;

    unsigned len = h->count * l->out_stride;
    if (!fault_here(b, h->tag, h->count)) {
        send_frame(b, NP_LINK_RESULT, h->tag, h->count, len);
        return;
    }
    /* A fault for tests: what a broken board or cable would do to this frame. */
    b->fault_done = 1;
    b->st.faults_applied++;
    np_link_hdr rh = { b->o.version, NP_LINK_RESULT, b->tx_seq++, h->tag, h->count, len };
    size_t n = np_link_seal(b->frame, &rh);
    switch (f->kind) {
    case NP_BOARD_CORRUPT:
        b->frame[NP_LINK_HDR_BYTES + len / 2u] ^= 0x10u; /* one payload bit */
        tx_put(b, b->frame, n);
        break;
    case NP_BOARD_SHORT:
        tx_put(b, b->frame, NP_LINK_HDR_BYTES + ((len / 2u) & ~3u));
        break;
    case NP_BOARD_DROP:
        break; /* the seq is used up: the host sees a gap */
    case NP_BOARD_SILENT:
    default:
        b->silent = 1;
        break;
    }
    b->st.frames_out++;
}

/* ------------------------------------------------------------------------- */
/* Section 4.4: BYE -> BYE_ACK. */

static void on_bye(np_board *b)
{
    size_t len = np_link_bye_encode(np_link_payload(b->frame), &b->session);
    send_frame(b, NP_LINK_BYE_ACK, 0, 0, (unsigned)len);
    b->state = B_READY;
}

/* ------------------------------------------------------------------------- */
/* Receiving (OUT): sections 2, 3 and 6. */

static void on_frame(np_board *b, const np_link_rx_ev *ev)
{
    const np_link_hdr *h = &ev->h;
    b->st.frames_in++;
    if (h->type == NP_LINK_HELLO) {
        on_hello(b, h);
        return;
    }
    if (b->state == B_HALTED)
        return; /* dropped silently until HELLO */
    if (h->seq != b->rx_expect) {
        send_error(b, NP_LINK_E_BAD_SEQ, b->rx_expect, "%s seq %u, expected %u",
                   np_link_type_name(h->type), (unsigned)h->seq, (unsigned)b->rx_expect);
        return;
    }
    b->rx_expect++;
    switch (h->type) {
    case NP_LINK_CONFIG: on_config(b, h, ev->payload); break;
    case NP_LINK_DATA: on_data(b, h, ev->payload); break;
    case NP_LINK_BYE: on_bye(b); break;
    default:
        send_error(b, NP_LINK_E_BAD_TYPE, 0, "%s is not a host frame", np_link_type_name(h->type));
        break;
    }
}

static void on_stream_error(np_board *b, np_link_rx_event e, const np_link_rx_ev *ev)
{
    if (e == NP_RX_BAD_VERSION && ev->h.type == NP_LINK_HELLO) {
        /* Section 10: a HELLO of another version, in any state: ERROR BAD_VERSION as its answer. */
        refuse_hello(b, ev->h.tag, NP_LINK_E_BAD_VERSION, b->o.version, "HELLO version %u, this board speaks %u",
                     ev->h.version, b->o.version);
        return;
    }
    if (b->state == B_HALTED)
        return; /* hunting for HELLO */
    switch (e) {
    case NP_RX_BAD_VERSION:
        send_error(b, NP_LINK_E_BAD_VERSION, b->o.version, "version %u, this board speaks %u",
                   ev->h.version, b->o.version);
        break;
    case NP_RX_BAD_LENGTH:
        send_error(b, NP_LINK_E_BAD_LENGTH, b->o.max_payload, "len %u", ev->h.len);
        break;
    case NP_RX_BAD_CRC:
    case NP_RX_SHORT:
        send_error(b, NP_LINK_E_BAD_CRC, 0, "%s seq %u: payload CRC %08x, frame says %08x",
                   np_link_type_name(ev->h.type), (unsigned)ev->h.seq, (unsigned)ev->crc_got,
                   (unsigned)ev->crc_want);
        break;
    case NP_RX_BAD_HEADER:
    default:
        send_error(b, NP_LINK_E_BAD_HEADER, 0, "no frame header where one must start");
        break;
    }
}

size_t np_board_rx(np_board *b, const uint8_t *p, size_t n)
{
    if (np_board_tx_pending(b) > b->o.tx_limit)
        return 0; /* NAK */
    const uint8_t *q = p;
    size_t left = n;
    for (;;) {
        np_link_rx_ev ev;
        np_link_rx_event e = np_link_rx_step(&b->rx, &q, &left, &ev);
        if (e == NP_RX_MORE)
            break;
        if (e == NP_RX_FRAME)
            on_frame(b, &ev);
        else
            on_stream_error(b, e, &ev);
    }
    b->st.rx_bytes += n;
    return n;
}

size_t np_board_tx(np_board *b, uint8_t *p, size_t cap)
{
    size_t n = b->tx_len - b->tx_start;
    if (n > cap)
        n = cap;
    if (n == 0)
        return 0; /* (b->tx is NULL until the board first sends) */
    memcpy(p, b->tx + b->tx_start, n);
    b->tx_start += n;
    b->st.tx_bytes += n;
    return n;
}

size_t np_board_tx_pending(const np_board *b) { return b->tx_len - b->tx_start; }
const np_board_stats *np_board_get_stats(const np_board *b) { return &b->st; }
const np_link_error *np_board_last_error(const np_board *b) { return &b->last_err; }

np_board *np_board_new(const np_board_opts *o)
{
    np_board *b = calloc(1, sizeof *b);
    if (!b)
        return NULL;
    b->o = *o;
    if (!b->o.version)
        b->o.version = NP_LINK_VERSION;
    if (!b->o.max_payload)
        b->o.max_payload = DEFAULT_MAX_PAYLOAD;
    if (!b->o.window)
        b->o.window = DEFAULT_WINDOW;
    if (!b->o.tx_limit)
        b->o.tx_limit = 4u * ((size_t)NP_LINK_OVERHEAD + b->o.max_payload);
    b->state = B_HALTED;
    b->frame = malloc(NP_LINK_MAX_FRAME);
    if (!b->frame || np_link_rx_init(&b->rx, b->o.max_payload) != 0) {
        np_board_free(b);
        return NULL;
    }
    b->rx.version = b->o.version;
    return b;
}

void np_board_free(np_board *b)
{
    if (!b)
        return;
    if (b->have_pipe)
        np_pipe_free(&b->pipe);
    free(b->sig_in);
    free(b->tx);
    free(b->frame);
    np_link_rx_free(&b->rx);
    free(b);
}
