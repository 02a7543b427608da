/* SPDX-License-Identifier: MIT */
/*
 * link_proto.c - the USB link protocol's frames, CRC, records and payloads
 * (docs/usb-protocol.md, sections 2, 4 and 5). Pure C, no USB: the host and
 * the board emulator both use this one implementation.
 */
#include "np_link.h"

#include <stdlib.h>
#include <string.h>

/* CRC-32/ISO-HDLC byte table: entry i = i shifted through 8 steps of 0xEDB88320 (test_link regenerates it). */
const uint32_t np_link_crc_table[256] = {
    0x00000000u, 0x77073096u, 0xee0e612cu, 0x990951bau, 0x076dc419u, 0x706af48fu,
    0xe963a535u, 0x9e6495a3u, 0x0edb8832u, 0x79dcb8a4u, 0xe0d5e91eu, 0x97d2d988u,
    0x09b64c2bu, 0x7eb17cbdu, 0xe7b82d07u, 0x90bf1d91u, 0x1db71064u, 0x6ab020f2u,
    0xf3b97148u, 0x84be41deu, 0x1adad47du, 0x6ddde4ebu, 0xf4d4b551u, 0x83d385c7u,
    0x136c9856u, 0x646ba8c0u, 0xfd62f97au, 0x8a65c9ecu, 0x14015c4fu, 0x63066cd9u,
    0xfa0f3d63u, 0x8d080df5u, 0x3b6e20c8u, 0x4c69105eu, 0xd56041e4u, 0xa2677172u,
    0x3c03e4d1u, 0x4b04d447u, 0xd20d85fdu, 0xa50ab56bu, 0x35b5a8fau, 0x42b2986cu,
    0xdbbbc9d6u, 0xacbcf940u, 0x32d86ce3u, 0x45df5c75u, 0xdcd60dcfu, 0xabd13d59u,
    0x26d930acu, 0x51de003au, 0xc8d75180u, 0xbfd06116u, 0x21b4f4b5u, 0x56b3c423u,
    0xcfba9599u, 0xb8bda50fu, 0x2802b89eu, 0x5f058808u, 0xc60cd9b2u, 0xb10be924u,
    0x2f6f7c87u, 0x58684c11u, 0xc1611dabu, 0xb6662d3du, 0x76dc4190u, 0x01db7106u,
    0x98d220bcu, 0xefd5102au, 0x71b18589u, 0x06b6b51fu, 0x9fbfe4a5u, 0xe8b8d433u,
    0x7807c9a2u, 0x0f00f934u, 0x9609a88eu, 0xe10e9818u, 0x7f6a0dbbu, 0x086d3d2du,
    0x91646c97u, 0xe6635c01u, 0x6b6b51f4u, 0x1c6c6162u, 0x856530d8u, 0xf262004eu,
    0x6c0695edu, 0x1b01a57bu, 0x8208f4c1u, 0xf50fc457u, 0x65b0d9c6u, 0x12b7e950u,
    0x8bbeb8eau, 0xfcb9887cu, 0x62dd1ddfu, 0x15da2d49u, 0x8cd37cf3u, 0xfbd44c65u,
    0x4db26158u, 0x3ab551ceu, 0xa3bc0074u, 0xd4bb30e2u, 0x4adfa541u, 0x3dd895d7u,
    0xa4d1c46du, 0xd3d6f4fbu, 0x4369e96au, 0x346ed9fcu, 0xad678846u, 0xda60b8d0u,
    0x44042d73u, 0x33031de5u, 0xaa0a4c5fu, 0xdd0d7cc9u, 0x5005713cu, 0x270241aau,
    0xbe0b1010u, 0xc90c2086u, 0x5768b525u, 0x206f85b3u, 0xb966d409u, 0xce61e49fu,
    0x5edef90eu, 0x29d9c998u, 0xb0d09822u, 0xc7d7a8b4u, 0x59b33d17u, 0x2eb40d81u,
    0xb7bd5c3bu, 0xc0ba6cadu, 0xedb88320u, 0x9abfb3b6u, 0x03b6e20cu, 0x74b1d29au,
    0xead54739u, 0x9dd277afu, 0x04db2615u, 0x73dc1683u, 0xe3630b12u, 0x94643b84u,
    0x0d6d6a3eu, 0x7a6a5aa8u, 0xe40ecf0bu, 0x9309ff9du, 0x0a00ae27u, 0x7d079eb1u,
    0xf00f9344u, 0x8708a3d2u, 0x1e01f268u, 0x6906c2feu, 0xf762575du, 0x806567cbu,
    0x196c3671u, 0x6e6b06e7u, 0xfed41b76u, 0x89d32be0u, 0x10da7a5au, 0x67dd4accu,
    0xf9b9df6fu, 0x8ebeeff9u, 0x17b7be43u, 0x60b08ed5u, 0xd6d6a3e8u, 0xa1d1937eu,
    0x38d8c2c4u, 0x4fdff252u, 0xd1bb67f1u, 0xa6bc5767u, 0x3fb506ddu, 0x48b2364bu,
    0xd80d2bdau, 0xaf0a1b4cu, 0x36034af6u, 0x41047a60u, 0xdf60efc3u, 0xa867df55u,
    0x316e8eefu, 0x4669be79u, 0xcb61b38cu, 0xbc66831au, 0x256fd2a0u, 0x5268e236u,
    0xcc0c7795u, 0xbb0b4703u, 0x220216b9u, 0x5505262fu, 0xc5ba3bbeu, 0xb2bd0b28u,
    0x2bb45a92u, 0x5cb36a04u, 0xc2d7ffa7u, 0xb5d0cf31u, 0x2cd99e8bu, 0x5bdeae1du,
    0x9b64c2b0u, 0xec63f226u, 0x756aa39cu, 0x026d930au, 0x9c0906a9u, 0xeb0e363fu,
    0x72076785u, 0x05005713u, 0x95bf4a82u, 0xe2b87a14u, 0x7bb12baeu, 0x0cb61b38u,
    0x92d28e9bu, 0xe5d5be0du, 0x7cdcefb7u, 0x0bdbdf21u, 0x86d3d2d4u, 0xf1d4e242u,
    0x68ddb3f8u, 0x1fda836eu, 0x81be16cdu, 0xf6b9265bu, 0x6fb077e1u, 0x18b74777u,
    0x88085ae6u, 0xff0f6a70u, 0x66063bcau, 0x11010b5cu, 0x8f659effu, 0xf862ae69u,
    0x616bffd3u, 0x166ccf45u, 0xa00ae278u, 0xd70dd2eeu, 0x4e048354u, 0x3903b3c2u,
    0xa7672661u, 0xd06016f7u, 0x4969474du, 0x3e6e77dbu, 0xaed16a4au, 0xd9d65adcu,
    0x40df0b66u, 0x37d83bf0u, 0xa9bcae53u, 0xdebb9ec5u, 0x47b2cf7fu, 0x30b5ffe9u,
    0xbdbdf21cu, 0xcabac28au, 0x53b39330u, 0x24b4a3a6u, 0xbad03605u, 0xcdd70693u,
    0x54de5729u, 0x23d967bfu, 0xb3667a2eu, 0xc4614ab8u, 0x5d681b02u, 0x2a6f2b94u,
    0xb40bbe37u, 0xc30c8ea1u, 0x5a05df1bu, 0x2d02ef8du,
};

uint32_t np_link_crc32(uint32_t crc, const void *p, size_t n)
{
    const uint8_t *b = p;
    uint32_t c = ~crc;
    for (size_t k = 0; k < n; k++)
        c = np_link_crc_table[(c ^ b[k]) & 0xffu] ^ (c >> 8);
    return ~c;
}

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
    f[NP_LINK_POS_VER] = NP_LINK_VERSION;
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
            if (ev->h.version != NP_LINK_VERSION)
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
    if (i->max_payload < NP_LINK_MIN_PAYLOAD || i->max_payload > NP_LINK_MAX_PAYLOAD ||
        i->max_payload % 4u != 0 || i->window < 1)
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
