/* SPDX-License-Identifier: MIT */
/*
 * link_proto.c - the USB link protocol's frames, CRC, records and payloads
 * (docs/usb-protocol.md, sections 2, 4 and 5). Pure C, no USB: the host and
 * the board emulator both use this one implementation.
 */
#include "np_link.h"

#include <stdlib.h>
#include <string.h>

const char *np_link_errcode_name(uint32_t code)
{
    static const char *const names[] = {
        "?",           "BAD_HEADER", "BAD_CRC",        "BAD_VERSION",
        "BAD_TYPE",    "BAD_LENGTH", "BAD_SEQ",        "NOT_CONFIGURED",
        "NO_SUCH_CONFIG", "BAD_LAYOUT", "OVERFLOW",    "INTERNAL",
    };
    return code < sizeof names / sizeof names[0] ? names[code] : "?";
}

const char *np_link_type_name(unsigned type)
{
    switch (type) {
    case NP_LINK_HELLO: return "HELLO";
    case NP_LINK_CONFIG: return "CONFIG";
    case NP_LINK_DATA: return "DATA";
    case NP_LINK_BYE: return "BYE";
    case NP_LINK_INFO: return "INFO";
    case NP_LINK_CONFIG_ACK: return "CONFIG_ACK";
    case NP_LINK_RESULT: return "RESULT";
    case NP_LINK_BYE_ACK: return "BYE_ACK";
    case NP_LINK_ERROR: return "ERROR";
    default: {
        static char buf[16];
        snprintf(buf, sizeof buf, "type 0x%02x", type & 0xffu);
        return buf;
    }
    }
}

/* ------------------------------------------------------------------------- */
/* Frames. */

static void header_encode(uint8_t *f, const np_link_hdr *h)
{
    f[NP_LINK_POS_SYNC] = NP_LINK_SYNC0;
    f[NP_LINK_POS_SYNC + 1] = NP_LINK_SYNC1;
    f[NP_LINK_POS_VER] = (uint8_t)(h->version ? h->version : NP_LINK_VERSION);
    f[NP_LINK_POS_TYPE] = (uint8_t)(h->type & 0xffu);
    np_link_put32(f + NP_LINK_POS_SEQ, h->seq);
    np_link_put64(f + NP_LINK_POS_TAG, h->tag);
    np_link_put16(f + NP_LINK_POS_COUNT, h->count);
    np_link_put16(f + NP_LINK_POS_LEN, h->len);
    np_link_put32(f + NP_LINK_POS_HCRC, np_link_crc32(0, f, NP_LINK_POS_HCRC));
}

size_t np_link_seal(uint8_t *f, const np_link_hdr *h)
{
    header_encode(f, h);
    uint8_t *pl = np_link_payload(f);
    np_link_put32(pl + h->len, np_link_crc32(0, pl, h->len));
    return NP_LINK_OVERHEAD + (size_t)h->len;
}

size_t np_link_encode(uint8_t *f, const np_link_hdr *h, const void *p)
{
    if (h->len)
        memmove(np_link_payload(f), p, h->len);
    return np_link_seal(f, h);
}

int np_link_header_ok(const uint8_t *p)
{
    return p[NP_LINK_POS_SYNC] == NP_LINK_SYNC0 && p[NP_LINK_POS_SYNC + 1] == NP_LINK_SYNC1 &&
           np_link_get32(p + NP_LINK_POS_HCRC) == np_link_crc32(0, p, NP_LINK_POS_HCRC);
}

void np_link_header_decode(const uint8_t *p, np_link_hdr *h)
{
    h->version = p[NP_LINK_POS_VER];
    h->type = p[NP_LINK_POS_TYPE];
    h->seq = np_link_get32(p + NP_LINK_POS_SEQ);
    h->tag = np_link_get64(p + NP_LINK_POS_TAG);
    h->count = np_link_get16(p + NP_LINK_POS_COUNT);
    h->len = np_link_get16(p + NP_LINK_POS_LEN);
}

/* ------------------------------------------------------------------------- */
/* Receiver. Input is copied into buf (one memcpy per byte, negligible beside
 * the CRC); frames are parsed in place from buf[start..have). */

int np_link_rx_init(np_link_rx *rx, unsigned max_payload)
{
    memset(rx, 0, sizeof *rx);
    rx->max_payload = max_payload;
    rx->version = NP_LINK_VERSION;
    rx->cap = (size_t)NP_LINK_OVERHEAD + max_payload;
    rx->buf = malloc(rx->cap);
    return rx->buf ? 0 : -1;
}

void np_link_rx_free(np_link_rx *rx)
{
    free(rx->buf);
    rx->buf = NULL;
}

void np_link_rx_hunt(np_link_rx *rx)
{
    rx->discarded += rx->have - rx->start;
    rx->have = rx->start = 0;
    rx->in_step = 0;
}

/*
 * Check a whole frame at f (header already known good): payload CRC, and
 * when it is wrong, whether the payload is cut off by another frame's header.
 */
static np_link_rx_event frame_check(np_link_rx *rx, const uint8_t *f, np_link_rx_ev *ev)
{
    const uint8_t *pl = f + NP_LINK_HDR_BYTES;
    ev->payload = pl;
    ev->crc_want = np_link_get32(pl + ev->h.len);
    ev->crc_got = np_link_crc32(0, pl, ev->h.len);
    if (ev->crc_got == ev->crc_want) {
        rx->in_step = 1;
        return NP_RX_FRAME;
    }
    /* A header inside the payload region means the frame was cut short. */
    for (size_t k = 0; k + NP_LINK_HDR_BYTES <= (size_t)ev->h.len + NP_LINK_CRC_BYTES; k++)
        if (pl[k] == NP_LINK_SYNC0 && np_link_header_ok(pl + k)) {
            ev->short_at = k;
            return NP_RX_SHORT;
        }
    return NP_RX_BAD_CRC;
}

/* Drop the first byte of a bad frame start and hunt from the next one. */
static np_link_rx_event reject(np_link_rx *rx, np_link_rx_event e)
{
    rx->start++;
    rx->discarded++;
    rx->in_step = 0;
    return e;
}

np_link_rx_event np_link_rx_step(np_link_rx *rx, const uint8_t **p, size_t *n, np_link_rx_ev *ev)
{
    memset(ev, 0, sizeof *ev);
    for (;;) {
        size_t avail = rx->have - rx->start;
        if (!rx->in_step)
            while (avail >= NP_LINK_HDR_BYTES && !np_link_header_ok(rx->buf + rx->start)) {
                rx->start++;
                rx->discarded++;
                avail--;
            }
        if (avail >= NP_LINK_HDR_BYTES) {
            const uint8_t *f = rx->buf + rx->start;
            np_link_header_decode(f, &ev->h);
            if (!np_link_header_ok(f))
                return reject(rx, NP_RX_BAD_HEADER); /* in step: a header must start here */
            /* An ERROR frame is read whatever its ver: its layout never changes (section 10). */
            if (ev->h.version != rx->version && ev->h.type != NP_LINK_ERROR)
                return reject(rx, NP_RX_BAD_VERSION);
            if (ev->h.len % 4u != 0 || ev->h.len > rx->max_payload)
                return reject(rx, NP_RX_BAD_LENGTH);
            size_t flen = NP_LINK_OVERHEAD + (size_t)ev->h.len;
            if (avail >= flen) {
                np_link_rx_event e = frame_check(rx, f, ev);
                if (e != NP_RX_FRAME)
                    return reject(rx, e);
                rx->start += flen;
                return NP_RX_FRAME;
            }
        }
        if (*n == 0)
            return NP_RX_MORE;
        /* Need more bytes: compact, then take what fits. */
        if (rx->start) {
            memmove(rx->buf, rx->buf + rx->start, avail);
            rx->have = avail;
            rx->start = 0;
        }
        size_t take = rx->cap - rx->have < *n ? rx->cap - rx->have : *n;
        memcpy(rx->buf + rx->have, *p, take);
        rx->have += take;
        rx->bytes += take;
        *p += take;
        *n -= take;
    }
}

/* ------------------------------------------------------------------------- */
/* Records. */

unsigned np_link_lane(unsigned bits)
{
    return bits <= 8 ? 1u : bits <= 16 ? 2u : bits <= 32 ? 4u : 8u;
}

static unsigned stride_of(const unsigned *lane, unsigned n)
{
    unsigned s = 0;
    for (unsigned k = 0; k < n; k++)
        s += lane[k];
    return (s + 3u) & ~3u;
}

void np_link_layout_init(np_link_layout *l, const np_unit_fields *f)
{
    memset(l, 0, sizeof *l);
    l->n_in = f->n_in;
    l->n_out = f->n_out;
    for (unsigned k = 0; k < f->n_in; k++) {
        l->in_bits[k] = f->in[k].bits;
        l->in_lane[k] = np_link_lane(f->in[k].bits);
    }
    for (unsigned k = 0; k < f->n_out; k++) {
        l->out_bits[k] = f->out[k].bits;
        l->out_lane[k] = np_link_lane(f->out[k].bits);
    }
    l->in_stride = stride_of(l->in_lane, l->n_in);
    l->out_stride = stride_of(l->out_lane, l->n_out);
}

void np_link_pack(uint8_t *rec, const uint64_t *w, const unsigned *lane, unsigned n,
                  unsigned stride)
{
    unsigned at = 0;
    for (unsigned k = 0; k < n; k++)
        for (unsigned b = 0; b < lane[k]; b++)
            rec[at++] = (uint8_t)((w[k] >> (8u * b)) & 0xffu);
    while (at < stride)
        rec[at++] = 0;
}

void np_link_unpack(const uint8_t *rec, uint64_t *w, const unsigned *lane, unsigned n)
{
    unsigned at = 0;
    for (unsigned k = 0; k < n; k++) {
        uint64_t v = 0;
        for (unsigned b = 0; b < lane[k]; b++)
            v |= (uint64_t)rec[at++] << (8u * b);
        w[k] = v;
    }
}

/* ------------------------------------------------------------------------- */
/* Payloads. Strings: NUL-padded fields; a full field has no NUL. */

static void put_str(uint8_t *p, const char *s, size_t field)
{
    size_t n = strlen(s);
    if (n > field)
        n = field;
    memcpy(p, s, n);
    memset(p + n, 0, field - n);
}

/* Copy a field into dst (field + 1 bytes); -1 when a non-printable byte precedes the padding. */
static int get_str(const uint8_t *p, size_t field, char *dst)
{
    size_t n = 0;
    while (n < field && p[n] != 0) {
        if (p[n] < 0x20 || p[n] > 0x7e)
            return -1;
        n++;
    }
    memcpy(dst, p, n);
    dst[n] = '\0';
    for (size_t k = n; k < field; k++)
        if (p[k] != 0)
            return -1; /* padding must be NULs */
    return 0;
}

size_t np_link_info_encode(uint8_t *p, const np_link_info *i)
{
    np_link_put32(p + 0, i->version);
    np_link_put32(p + 4, i->max_payload);
    np_link_put32(p + 8, i->window);
    np_link_put32(p + 12, i->n_slots);
    put_str(p + 16, i->board_id, NP_LINK_BOARD_ID_BYTES);
    size_t at = NP_LINK_INFO_FIXED;
    for (uint32_t k = 0; k < i->n_slots && k < NP_LINK_MAX_SLOTS; k++) {
        put_str(p + at, i->slot[k].unit, NP_LINK_NAME_BYTES);
        put_str(p + at + NP_LINK_NAME_BYTES, i->slot[k].cfg, NP_LINK_SLOT_CFG_BYTES);
        at += NP_LINK_SLOT_BYTES;
    }
    return at;
}

int np_link_info_decode(const uint8_t *p, size_t len, np_link_info *i)
{
    memset(i, 0, sizeof *i);
    if (len < NP_LINK_INFO_FIXED)
        return -1;
    i->version = np_link_get32(p + 0);
    i->max_payload = np_link_get32(p + 4);
    i->window = np_link_get32(p + 8);
    i->n_slots = np_link_get32(p + 12);
    if (get_str(p + 16, NP_LINK_BOARD_ID_BYTES, i->board_id) != 0)
        return -1;
    if (i->n_slots > NP_LINK_MAX_SLOTS ||
        len != NP_LINK_INFO_FIXED + (size_t)i->n_slots * NP_LINK_SLOT_BYTES)
        return -1;
    /* (A max_payload below NP_LINK_MIN_PAYLOAD is well-formed; the host refuses it with its own message.) */
    if (i->max_payload == 0 || i->max_payload > NP_LINK_MAX_PAYLOAD || i->max_payload % 4u != 0 ||
        i->window < 1)
        return -1;
    for (uint32_t k = 0; k < i->n_slots; k++) {
        const uint8_t *s = p + NP_LINK_INFO_FIXED + (size_t)k * NP_LINK_SLOT_BYTES;
        if (get_str(s, NP_LINK_NAME_BYTES, i->slot[k].unit) != 0 ||
            get_str(s + NP_LINK_NAME_BYTES, NP_LINK_SLOT_CFG_BYTES, i->slot[k].cfg) != 0)
            return -1;
    }
    return 0;
}

size_t np_link_config_encode(uint8_t *p, const np_link_config *c)
{
    size_t tl = strlen(c->cfg) + 1u; /* with its NUL */
    size_t padded = (tl + 3u) & ~(size_t)3u;
    if (padded > NP_LINK_CFG_BYTES || strlen(c->unit) > NP_LINK_NAME_BYTES)
        return 0;
    put_str(p, c->unit, NP_LINK_NAME_BYTES);
    p[16] = (uint8_t)c->lay.n_in;
    p[17] = (uint8_t)c->lay.n_out;
    p[18] = (uint8_t)c->lay.in_stride;
    p[19] = (uint8_t)c->lay.out_stride;
    for (unsigned k = 0; k < NP_UNIT_MAX_FIELDS; k++) {
        p[20 + k] = (uint8_t)(k < c->lay.n_in ? c->lay.in_bits[k] : 0u);
        p[28 + k] = (uint8_t)(k < c->lay.n_out ? c->lay.out_bits[k] : 0u);
    }
    put_str(p + NP_LINK_CONFIG_FIXED, c->cfg, padded);
    return NP_LINK_CONFIG_FIXED + padded;
}

int np_link_config_decode(const uint8_t *p, size_t len, np_link_config *c)
{
    memset(c, 0, sizeof *c);
    if (len < NP_LINK_CONFIG_FIXED + 4u || len > NP_LINK_CONFIG_FIXED + (size_t)NP_LINK_CFG_BYTES)
        return -1;
    if (get_str(p, NP_LINK_NAME_BYTES, c->unit) != 0)
        return -1;
    np_link_layout *l = &c->lay;
    l->n_in = p[16];
    l->n_out = p[17];
    if (l->n_in < 1 || l->n_in > NP_UNIT_MAX_FIELDS || l->n_out < 1 || l->n_out > NP_UNIT_MAX_FIELDS)
        return -1;
    for (unsigned k = 0; k < NP_UNIT_MAX_FIELDS; k++) {
        l->in_bits[k] = p[20 + k];
        l->out_bits[k] = p[28 + k];
        if ((k < l->n_in) != (l->in_bits[k] != 0) || (k < l->n_out) != (l->out_bits[k] != 0) ||
            l->in_bits[k] > 64 || l->out_bits[k] > 64)
            return -1;
        if (k < l->n_in)
            l->in_lane[k] = np_link_lane(l->in_bits[k]);
        if (k < l->n_out)
            l->out_lane[k] = np_link_lane(l->out_bits[k]);
    }
    l->in_stride = stride_of(l->in_lane, l->n_in);
    l->out_stride = stride_of(l->out_lane, l->n_out);
    if (p[18] != l->in_stride || p[19] != l->out_stride)
        return -1;
    /* The text: NUL-terminated inside its padded field. */
    size_t tl = len - NP_LINK_CONFIG_FIXED;
    const uint8_t *t = p + NP_LINK_CONFIG_FIXED;
    if (memchr(t, 0, tl) == NULL)
        return -1;
    return get_str(t, tl, c->cfg);
}

size_t np_link_ack_encode(uint8_t *p, const np_link_ack *a)
{
    memset(p, 0, NP_LINK_ACK_BYTES);
    np_link_put32(p + 0, a->latency);
    np_link_put32(p + 4, a->clock_hz);
    p[8] = (uint8_t)a->in_stride;
    p[9] = (uint8_t)a->out_stride;
    return NP_LINK_ACK_BYTES;
}

int np_link_ack_decode(const uint8_t *p, size_t len, np_link_ack *a)
{
    if (len != NP_LINK_ACK_BYTES)
        return -1;
    a->latency = np_link_get32(p + 0);
    a->clock_hz = np_link_get32(p + 4);
    a->in_stride = p[8];
    a->out_stride = p[9];
    return 0;
}

size_t np_link_bye_encode(uint8_t *p, const np_link_bye *b)
{
    np_link_put64(p + 0, b->records);
    np_link_put64(p + 8, b->cycles);
    np_link_put64(p + 16, b->stalls);
    np_link_put32(p + 24, b->data_frames);
    np_link_put32(p + 28, b->errors);
    return NP_LINK_BYE_ACK_BYTES;
}

int np_link_bye_decode(const uint8_t *p, size_t len, np_link_bye *b)
{
    if (len != NP_LINK_BYE_ACK_BYTES)
        return -1;
    b->records = np_link_get64(p + 0);
    b->cycles = np_link_get64(p + 8);
    b->stalls = np_link_get64(p + 16);
    b->data_frames = np_link_get32(p + 24);
    b->errors = np_link_get32(p + 28);
    return 0;
}

size_t np_link_error_encode(uint8_t *p, const np_link_error *e)
{
    np_link_put32(p + 0, e->code);
    np_link_put32(p + 4, e->detail);
    put_str(p + 8, e->msg, NP_LINK_ERROR_MSG_BYTES);
    return NP_LINK_ERROR_BYTES;
}

int np_link_error_decode(const uint8_t *p, size_t len, np_link_error *e)
{
    memset(e, 0, sizeof *e);
    if (len != NP_LINK_ERROR_BYTES)
        return -1;
    e->code = np_link_get32(p + 0);
    e->detail = np_link_get32(p + 4);
    if (get_str(p + 8, NP_LINK_ERROR_MSG_BYTES, e->msg) != 0)
        snprintf(e->msg, sizeof e->msg, "(unreadable message)");
    return 0;
}
