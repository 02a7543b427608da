/* SPDX-License-Identifier: MIT */
/*
 * np_link.h - the USB link: protocol (framing, CRC, records), the board
 * emulator, the host's protocol engine with its journal, and the transports.
 *
 * docs/usb-protocol.md is the specification; the constants below are its
 * tables. Layering:
 *
 *   link_proto.c   frames, CRC-32, record packing, payload layouts: pure C,
 *                  no USB, shared by the host and the emulator (one implementation)
 *   link_board.c   the board side, on the cycle-accurate models (np_unit pipes)
 *   link_job.c     the host's vectors, packed as they travel, and their hash
 *   link_journal.c the host's journal of verified ranges (on np_jfile.h)
 *   link_engine.c  the host's protocol engine: session, window, verification
 *   link_loopback.c the in-process transport: host engine <-> emulator
 *   link_usb.c     the libusb transport (built only with NOISEPIPE_USB)
 *   link_fd.c      a byte stream on file descriptors (a tty, the pipes of a
 *                  board simulator run as a child: stream --sim)
 *   link_tty.c     a kernel tty set up for link_fd.c (stream --tty)
 *
 * The host engine and the board are byte-stream state machines: the
 * transport moves bytes between them (np_host_pull -> OUT -> np_board_rx,
 * np_board_tx -> IN -> np_host_push) and owns time.
 */
#ifndef NP_LINK_H
#define NP_LINK_H

#include <stddef.h>
#include <stdint.h>
#include <termios.h>
#include <stdio.h>

#include "np_crc32.h"
#include "np_jfile.h"
#include "np_unit.h"

/* ------------------------------------------------------------------------- */
/* Frames (docs/usb-protocol.md, section 2).
 *
 * byte   0      1      2      3      4    7  8           15  16  17  18  19  20   23
 *      +------+------+------+------+-------+---------------+-------+-------+-------+
 *      | 0x4E | 0x50 | ver  | type |  seq  |      tag      | count |  len  | hcrc  |
 *      +------+------+------+------+-------+---------------+-------+-------+-------+
 *      | payload: len bytes                                    | pcrc (4 bytes)    |
 */
enum {
    NP_LINK_VERSION = 1,
    NP_LINK_SYNC0 = 0x4E, /* 'N' */
    NP_LINK_SYNC1 = 0x50, /* 'P' */
    NP_LINK_POS_SYNC = 0, NP_LINK_SIZE_SYNC = 2,
    NP_LINK_POS_VER = 2, NP_LINK_SIZE_VER = 1,
    NP_LINK_POS_TYPE = 3, NP_LINK_SIZE_TYPE = 1,
    NP_LINK_POS_SEQ = 4, NP_LINK_SIZE_SEQ = 4,
    NP_LINK_POS_TAG = 8, NP_LINK_SIZE_TAG = 8,
    NP_LINK_POS_COUNT = 16, NP_LINK_SIZE_COUNT = 2,
    NP_LINK_POS_LEN = 18, NP_LINK_SIZE_LEN = 2,
    NP_LINK_POS_HCRC = 20, NP_LINK_SIZE_HCRC = 4,
    NP_LINK_HDR_BYTES = 24,
    NP_LINK_CRC_BYTES = 4,
    NP_LINK_OVERHEAD = NP_LINK_HDR_BYTES + NP_LINK_CRC_BYTES,
    NP_LINK_MAX_PAYLOAD = 65532, /* len is 16 bits, a multiple of 4 */
    /*
     * A board's max_payload at least (section 4.1): the longest CONFIG
     * payload, 36 bytes + 256 of configuration text. The host refuses a
     * board that announces less. The host's own max_payload for IN frames is
     * NP_LINK_MAX_PAYLOAD.
     */
    NP_LINK_MIN_PAYLOAD = 292,
    NP_LINK_MAX_FRAME = NP_LINK_OVERHEAD + NP_LINK_MAX_PAYLOAD,
    NP_LINK_MAX_COUNT = 65535
};

typedef enum np_link_type {
    NP_LINK_HELLO = 0x01,
    NP_LINK_CONFIG = 0x02,
    NP_LINK_DATA = 0x03,
    NP_LINK_BYE = 0x04,
    NP_LINK_INFO = 0x81,
    NP_LINK_CONFIG_ACK = 0x82,
    NP_LINK_RESULT = 0x83,
    NP_LINK_BYE_ACK = 0x84,
    NP_LINK_ERROR = 0xEE,
    NP_LINK_FROM_BOARD = 0x80 /* bit 7 of type */
} np_link_type;

/* ERROR frame codes (section 6). */
typedef enum np_link_errcode {
    NP_LINK_E_BAD_HEADER = 1,
    NP_LINK_E_BAD_CRC = 2,
    NP_LINK_E_BAD_VERSION = 3,
    NP_LINK_E_BAD_TYPE = 4,
    NP_LINK_E_BAD_LENGTH = 5,
    NP_LINK_E_BAD_SEQ = 6,
    NP_LINK_E_NOT_CONFIGURED = 7,
    NP_LINK_E_NO_SUCH_CONFIG = 8,
    NP_LINK_E_BAD_LAYOUT = 9,
    NP_LINK_E_OVERFLOW = 10,
    NP_LINK_E_INTERNAL = 11
} np_link_errcode;

/* "BAD_CRC" etc.; "?" for an unknown code. */
const char *np_link_errcode_name(uint32_t code);
/* "DATA", "RESULT" ...; "type 0x42" style for unknown ones (static buffer: not thread-safe). */
const char *np_link_type_name(unsigned type);

typedef struct np_link_hdr {
    unsigned version; /* NP_LINK_VERSION when encoding */
    unsigned type;
    uint32_t seq;
    uint64_t tag;
    unsigned count; /* 0..65535 */
    unsigned len;   /* payload bytes, multiple of 4, <= NP_LINK_MAX_PAYLOAD */
} np_link_hdr;

/*
 * The frames' CRC is the project's CRC-32/ISO-HDLC (np_crc32.h: reflected
 * polynomial 0xEDB88320, init and final XOR 0xFFFFFFFF), the one the
 * journals' lines carry. np_link_crc32(0, p, n) is the CRC of p[0..n); pass a
 * previous result as crc to continue it. "123456789" -> 0xCBF43926.
 */
#define np_link_crc_table np_crc32_table
static inline uint32_t np_link_crc32(uint32_t crc, const void *p, size_t n)
{
    return np_crc32(crc, p, n);
}

static inline void np_link_put16(uint8_t *p, unsigned v)
{
    p[0] = (uint8_t)(v & 0xffu);
    p[1] = (uint8_t)((v >> 8) & 0xffu);
}
static inline void np_link_put32(uint8_t *p, uint32_t v)
{
    for (unsigned k = 0; k < 4; k++)
        p[k] = (uint8_t)((v >> (8u * k)) & 0xffu);
}
static inline void np_link_put64(uint8_t *p, uint64_t v)
{
    for (unsigned k = 0; k < 8; k++)
        p[k] = (uint8_t)((v >> (8u * k)) & 0xffu);
}
static inline unsigned np_link_get16(const uint8_t *p) { return (unsigned)p[0] | (unsigned)p[1] << 8; }
static inline uint32_t np_link_get32(const uint8_t *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}
static inline uint64_t np_link_get64(const uint8_t *p)
{
    return (uint64_t)np_link_get32(p) | (uint64_t)np_link_get32(p + 4) << 32;
}

/* Payload of a frame under construction at f. */
static inline uint8_t *np_link_payload(uint8_t *f) { return f + NP_LINK_HDR_BYTES; }
/*
 * Finish the frame at f whose h->len payload bytes are already in place:
 * write the header and both CRCs.
 * Returns the frame's length, NP_LINK_OVERHEAD + h->len.
 */
size_t np_link_seal(uint8_t *f, const np_link_hdr *h);
/* (h->version 0 is NP_LINK_VERSION; another version only for tests of section 10.) */
/* Header, payload copied from p (may be NULL when h->len is 0), CRCs: the frame length. */
size_t np_link_encode(uint8_t *f, const np_link_hdr *h, const void *p);
/* 1 when the 24 bytes at p are a header with sync and a correct hcrc (version not checked). */
int np_link_header_ok(const uint8_t *p);
void np_link_header_decode(const uint8_t *p, np_link_hdr *h);

/* ------------------------------------------------------------------------- */
/* Receiver: the byte stream -> frames, with hunting and checks (section 2). */

typedef enum np_link_rx_event {
    NP_RX_MORE = 0,     /* all input consumed, no complete frame yet */
    NP_RX_FRAME,        /* a frame: ev->h, ev->payload */
    NP_RX_BAD_HEADER,   /* in step, and no header where one must start */
    NP_RX_BAD_VERSION,  /* ev->h valid; ver is not rx->version (and the frame is no ERROR) */
    NP_RX_BAD_LENGTH,   /* ev->h valid; len not a multiple of 4 or > max_payload */
    NP_RX_BAD_CRC,      /* ev->h valid; payload CRC wrong (ev->crc_got/crc_want) */
    NP_RX_SHORT         /* ev->h valid; payload cut off by a header at ev->short_at */
} np_link_rx_event;

typedef struct np_link_rx_ev {
    np_link_hdr h;
    const uint8_t *payload; /* valid until the next np_link_rx_step() */
    uint32_t crc_got, crc_want;
    size_t short_at;        /* payload bytes before the next header (NP_RX_SHORT) */
} np_link_rx_ev;

typedef struct np_link_rx {
    uint8_t *buf;          /* input copied here; frames parsed in place */
    size_t cap, start, have; /* buf[start..have) not yet parsed */
    unsigned max_payload;
    unsigned version;      /* the ver read (NP_LINK_VERSION); ERROR frames of any ver are read too (section 10) */
    int in_step;
    uint64_t discarded;    /* bytes skipped while hunting */
    uint64_t bytes;        /* bytes taken in */
} np_link_rx;

/* 0, or -1 when out of memory. max_payload: the largest payload accepted. */
int np_link_rx_init(np_link_rx *rx, unsigned max_payload);
void np_link_rx_free(np_link_rx *rx);
/* Forget any partial frame and start hunting. */
void np_link_rx_hunt(np_link_rx *rx);
/*
 * Consume bytes from *p (advancing *p and *n) up to the next event; returns
 * it. After an error event the receiver hunts again from the byte after the
 * offending frame's first byte. A frame's payload stays valid until the next call.
 */
np_link_rx_event np_link_rx_step(np_link_rx *rx, const uint8_t **p, size_t *n, np_link_rx_ev *ev);
/* Bytes of an incomplete frame held (for "short frame" messages). */
static inline size_t np_link_rx_pending(const np_link_rx *rx) { return rx->have - rx->start; }

/* ------------------------------------------------------------------------- */
/* Records (section 5): each field in a 1/2/4/8-byte little-endian lane. */

typedef struct np_link_layout {
    unsigned n_in, n_out;
    unsigned in_bits[NP_UNIT_MAX_FIELDS], out_bits[NP_UNIT_MAX_FIELDS];
    unsigned in_lane[NP_UNIT_MAX_FIELDS], out_lane[NP_UNIT_MAX_FIELDS];
    unsigned in_stride, out_stride; /* bytes, multiples of 4 */
} np_link_layout;

/* The low bits set, 1 <= bits <= 64. */
static inline uint64_t np_link_mask(unsigned bits)
{
    return bits >= 64 ? ~(uint64_t)0 : ((uint64_t)1 << bits) - 1u;
}
/* Lane bytes for a width: 1..8 -> 1, 9..16 -> 2, 17..32 -> 4, 33..64 -> 8. */
unsigned np_link_lane(unsigned bits);
void np_link_layout_init(np_link_layout *l, const np_unit_fields *f);
/* Pack n words (masked to their widths by the caller) into a record of stride bytes. */
void np_link_pack(uint8_t *rec, const uint64_t *w, const unsigned *lane, unsigned n,
                  unsigned stride);
/* Unpack n lanes into words (the whole lane: high bits are not masked off). */
void np_link_unpack(const uint8_t *rec, uint64_t *w, const unsigned *lane, unsigned n);

/* ------------------------------------------------------------------------- */
/* Payloads (section 4). */

enum {
    NP_LINK_NAME_BYTES = 16,
    NP_LINK_CFG_BYTES = 256,     /* configuration text in CONFIG, at most */
    NP_LINK_SLOT_CFG_BYTES = 112,
    NP_LINK_SLOT_BYTES = NP_LINK_NAME_BYTES + NP_LINK_SLOT_CFG_BYTES,
    NP_LINK_MAX_SLOTS = 16,
    NP_LINK_BOARD_ID_BYTES = 32,
    NP_LINK_INFO_FIXED = 48,
    NP_LINK_CONFIG_FIXED = 36,
    NP_LINK_ACK_BYTES = 16,
    NP_LINK_BYE_ACK_BYTES = 32,
    NP_LINK_ERROR_BYTES = 64,
    NP_LINK_ERROR_MSG_BYTES = 56
};

typedef struct np_link_slot {
    char unit[NP_LINK_NAME_BYTES + 1];
    char cfg[NP_LINK_SLOT_CFG_BYTES + 1];
} np_link_slot;

typedef struct np_link_info {
    uint32_t version, max_payload, window, n_slots;
    char board_id[NP_LINK_BOARD_ID_BYTES + 1];
    np_link_slot slot[NP_LINK_MAX_SLOTS];
} np_link_info;

typedef struct np_link_config {
    char unit[NP_LINK_NAME_BYTES + 1];
    np_link_layout lay; /* n_in, n_out, strides and widths (lanes derived) */
    char cfg[NP_LINK_CFG_BYTES + 1];
} np_link_config;

typedef struct np_link_ack {
    uint32_t latency, clock_hz;
    unsigned in_stride, out_stride;
} np_link_ack;

typedef struct np_link_bye {
    uint64_t records, cycles, stalls;
    uint32_t data_frames, errors;
} np_link_bye;

typedef struct np_link_error {
    uint32_t code, detail;
    char msg[NP_LINK_ERROR_MSG_BYTES + 1];
} np_link_error;

/* Encoders write the payload at p and return its length; decoders return 0 or -1 (malformed). */
size_t np_link_info_encode(uint8_t *p, const np_link_info *i);
int np_link_info_decode(const uint8_t *p, size_t len, np_link_info *i);
size_t np_link_config_encode(uint8_t *p, const np_link_config *c); /* -> 0 if too long */
int np_link_config_decode(const uint8_t *p, size_t len, np_link_config *c);
size_t np_link_ack_encode(uint8_t *p, const np_link_ack *a);
int np_link_ack_decode(const uint8_t *p, size_t len, np_link_ack *a);
size_t np_link_bye_encode(uint8_t *p, const np_link_bye *b);
int np_link_bye_decode(const uint8_t *p, size_t len, np_link_bye *b);
size_t np_link_error_encode(uint8_t *p, const np_link_error *e);
int np_link_error_decode(const uint8_t *p, size_t len, np_link_error *e);

/* ------------------------------------------------------------------------- */
/* Board emulator (link_board.c). */

typedef enum np_board_fault_kind {
    NP_BOARD_OK = 0,
    NP_BOARD_WRONG_BIT, /* flip bit `bit` of output field 0 of record `at` */
    NP_BOARD_CORRUPT,   /* flip a payload bit of the RESULT frame holding record `at` */
    NP_BOARD_SHORT,     /* cut the RESULT frame holding record `at` after half its payload */
    NP_BOARD_DROP,      /* never send the RESULT frame holding record `at` (a seq gap) */
    NP_BOARD_SILENT     /* from the RESULT frame holding record `at` on, send nothing */
} np_board_fault_kind;

typedef struct np_board_fault {
    np_board_fault_kind kind;
    uint64_t at;  /* record index */
    unsigned bit; /* NP_BOARD_WRONG_BIT */
} np_board_fault;

typedef struct np_board_opts {
    const char *board_id;  /* NULL: "noisepipe board emulator" */
    unsigned version;      /* protocol version the board speaks; 0: NP_LINK_VERSION (tests of section 10) */
    unsigned max_payload;  /* 0: 16384 */
    unsigned window;       /* 0: 8 */
    size_t tx_limit;       /* bytes queued IN before OUT is refused (NAK); 0: 4 frames */
    unsigned n_slots;      /* 0: any unit and configuration of the registry */
    np_link_slot slot[NP_LINK_MAX_SLOTS];
    np_board_fault fault;
} np_board_opts;

typedef struct np_board_stats {
    uint64_t rx_bytes, tx_bytes;
    uint64_t frames_in, frames_out;
    uint64_t data_frames, records;
    uint64_t cycles, stalls, bubbles;
    uint64_t errors_sent, hellos;
    uint64_t faults_applied;
} np_board_stats;

typedef struct np_board np_board;

/* NULL when out of memory. */
np_board *np_board_new(const np_board_opts *o);
void np_board_free(np_board *b);
/*
 * OUT bytes from the host. Returns how many were taken: all of them, or 0
 * while the IN queue holds more than tx_limit bytes (the board NAKs).
 */
size_t np_board_rx(np_board *b, const uint8_t *p, size_t n);
/*
 * IN bytes for the host: up to cap bytes of the queue. The board ends a
 * burst when its queue runs empty (the IN rule), so a caller filling a USB
 * transfer completes it when this returns less than it asked for.
 */
size_t np_board_tx(np_board *b, uint8_t *p, size_t cap);
size_t np_board_tx_pending(const np_board *b);
const np_board_stats *np_board_get_stats(const np_board *b);
/* The last ERROR the board sent, for tests; code 0 when none. */
const np_link_error *np_board_last_error(const np_board *b);

/* ------------------------------------------------------------------------- */
/* Vectors to stream (link_job.c): packed as they travel. */

typedef struct np_link_job {
    const np_unit *unit;
    np_unit_cfg cfg;
    np_unit_fields fields;
    char cfg_text[NP_LINK_CFG_BYTES];
    np_link_layout lay;
    uint64_t n;
    uint8_t *in;    /* n * lay.in_stride bytes: input records */
    uint8_t *want;  /* n * lay.out_stride bytes: expected output records */
    uint64_t *line; /* source line of each vector, or NULL */
    uint64_t hash;  /* identity of (unit, configuration, every record); np_link_job_seal */
} np_link_job;

/* Allocate for n vectors of unit u configured as cfg. 0, or -1 (no memory). */
int np_link_job_init(np_link_job *j, const np_unit *u, const void *cfg, uint64_t n);
void np_link_job_set(np_link_job *j, uint64_t i, const uint64_t *in, const uint64_t *want);
/* Compute the hash once every vector is set. */
void np_link_job_seal(np_link_job *j);
/* n vectors: inputs from np_rng(seed), each field uniform over its width; expected = unit->eval. */
int np_link_job_random(np_link_job *j, const np_unit *u, const void *cfg, uint64_t n,
                       uint64_t seed);
void np_link_job_free(np_link_job *j);

/* ------------------------------------------------------------------------- */
/* Journal (link_journal.c): the verified ranges, in a journal file (np_jfile.h).
 *
 *   # noisepipe stream journal 2
 *   unit=<unit> *<crc>
 *   config=<configuration...> *<crc>
 *   count=<vectors, decimal> *<crc>
 *   vectors=<hash, 16 hex digits> *<crc>   np_link_job.hash: unit, configuration, every record
 *   size=<bytes of the vector file> *<crc>  or "generated" (--random), "pipe" (stdin, not a file)
 *   target=<emulator | usb VID:PID serial S> *<crc>
 *   E <index> <got word>... *<crc>          a failing vector of the next R line
 *   R <first> <count> <errors> *<crc>       vectors first..first+count-1 verified
 *
 * Numbers in E and R lines are hex, words hex; <crc> is the CRC-32 of the
 * line up to the blank before '*'. An E line counts only with the R line that
 * commits it; a torn tail (a kill mid-write) is ignored and cut off, so what
 * it held is sent again; a complete line with a bad CRC, a range that
 * overlaps another, or bindings of other vectors make the journal unusable.
 */

/*
 * What a journal is bound to besides the vectors (section 11): the size of
 * the vector file, and the target, "emulator" or "usb VID:PID serial S".
 */
typedef struct np_link_target {
    char size[64];   /* "123456" bytes of the vector file; "generated" (--random); "pipe" */
    char target[192];
} np_link_target;

typedef struct np_journal_fail {
    uint64_t index;
    uint64_t got[NP_UNIT_MAX_FIELDS];
} np_journal_fail;

typedef struct np_journal {
    np_jfile file;         /* file.fd -1: in memory only */
    uint64_t n;            /* vectors in the job */
    uint8_t *checked;      /* bitmap: 1 = a result is journaled */
    uint64_t n_checked, n_errors;
    uint64_t prior_checked, prior_errors; /* from the file when resumed */
    np_journal_fail *fails; /* every failing vector, in journal order */
    size_t n_fails, cap_fails;
    unsigned n_out;
    double sync_interval;  /* seconds between syncs (default 0.25) */
} np_journal;

/*
 * Open the journal for job j. path NULL: in memory only. resume: the file
 * must exist and describe these vectors; its verified ranges are loaded.
 * Not resume: an existing non-empty file is refused (so that nothing
 * verified is thrown away by mistake); otherwise a new journal is started.
 * 0, or -1 with a message in err.
 */
int np_journal_open(np_journal *jn, const char *path, const np_link_job *j, int resume,
                    char *err, size_t errlen);
/*
 * The same, bound to the vector file's size and the target too (t NULL: no
 * such bindings, for tests). force: an existing file that is not to be
 * resumed is replaced (only then); without it any existing non-empty file
 * is refused (exit 2 for the caller), so nothing verified is thrown away.
 */
int np_journal_open_bound(np_journal *jn, const char *path, const np_link_job *j,
                          const np_link_target *t, int resume, int force, char *err, size_t errlen);
/* Record a verified range with its failures (each with the got words). 0, or -1 with err. */
int np_journal_append(np_journal *jn, uint64_t first, uint64_t count,
                      const np_journal_fail *fails, size_t n_fails, char *err, size_t errlen);
/* fdatasync now. 0, or -1 with err. */
int np_journal_sync(np_journal *jn, char *err, size_t errlen);
void np_journal_close(np_journal *jn);
static inline int np_journal_has(const np_journal *jn, uint64_t i)
{
    return (int)(((unsigned)jn->checked[i >> 3] >> (unsigned)(i & 7u)) & 1u);
}

/* ------------------------------------------------------------------------- */
/* Host engine (link_engine.c). */

typedef enum np_link_fault {
    NP_FAULT_NONE = 0,
    NP_FAULT_TIMEOUT,    /* the board was silent too long */
    NP_FAULT_NO_DEVICE,  /* the board disappeared */
    NP_FAULT_STALL,      /* an endpoint stalled */
    NP_FAULT_USB,        /* another USB error */
    NP_FAULT_CORRUPT,    /* an IN frame failed its CRC or framing */
    NP_FAULT_SHORT,      /* an IN frame was cut short */
    NP_FAULT_SEQ,        /* lost, repeated or unexpected IN frame */
    NP_FAULT_BOARD,      /* the board sent ERROR */
    NP_FAULT_CONFIG,     /* the board does not run the unit/configuration (usage) */
    NP_FAULT_JOURNAL,    /* the journal could not be written (usage) */
    NP_FAULT_INCOMPATIBLE /* the board does not speak this protocol: version, max_payload (usage) */
} np_link_fault;

const char *np_link_fault_name(np_link_fault f);

typedef struct np_host np_host;

/* Called for each failing vector as its RESULT is verified. */
typedef void (*np_host_fail_fn)(void *ctx, uint64_t index, const uint64_t *got);
/* Called after each verified RESULT with the vectors verified in this session. */
typedef void (*np_host_progress_fn)(void *ctx, uint64_t verified);

typedef struct np_host_opts {
    unsigned frame_records; /* vectors per DATA frame; 0: as many as the board takes */
    unsigned window;        /* 0: the board's */
    uint64_t max_errors;    /* stop sending after this many failures; 0: never */
    uint64_t nonce;         /* HELLO tag; 0: from the clock and pid */
    np_host_fail_fn on_fail;
    np_host_progress_fn on_progress;
    void *fail_ctx; /* for both callbacks */
} np_host_opts;

typedef struct np_host_stats {
    uint64_t frames_out, frames_in, bytes_out, bytes_in;
    uint64_t sent, verified, errors; /* this session */
    uint64_t stale_bytes;            /* IN bytes dropped before INFO */
    double t_first_data, t_last_result;
    np_link_info info;
    np_link_ack ack;
    np_link_bye bye;
    int have_bye;
} np_host_stats;

np_host *np_host_new(const np_link_job *j, np_journal *jn, const np_host_opts *o);
void np_host_free(np_host *h);
/* Next OUT frame into buf (cap >= NP_LINK_MAX_FRAME): its length, 0 when nothing is due now. */
size_t np_host_pull(np_host *h, uint8_t *buf, size_t cap);
/* IN bytes from the board. 0, or -1 once the host has faulted. */
int np_host_push(np_host *h, const uint8_t *p, size_t n);
/* Record a transport fault (the first one wins). */
void np_host_fault(np_host *h, np_link_fault f, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
/* 1 while the host waits for a frame from the board. */
int np_host_waiting(const np_host *h);
/* 1 when the session ended with BYE_ACK. */
int np_host_done(const np_host *h);
np_link_fault np_host_get_fault(const np_host *h);
const char *np_host_fault_msg(const np_host *h);
const np_host_stats *np_host_get_stats(const np_host *h);
/* "vectors 2048..4095" of the outstanding DATA frames, for messages. */
void np_host_outstanding(const np_host *h, char *buf, size_t len);
/* A timeout message with what was outstanding; sets the fault. */
void np_host_timeout(np_host *h, double seconds);
/* Vectors per DATA frame (known once INFO arrived). */
unsigned np_host_frame_records(const np_host *h);
/* 1 when every vector of the job is journaled. */
int np_host_complete(const np_host *h);

/* ------------------------------------------------------------------------- */
/* Transports. Each runs the session to its end (done or fault). */

typedef struct np_loop_opts {
    double timeout;        /* seconds of silence with work outstanding; 0: 2 s */
    size_t chunk;          /* bytes per move, to exercise reassembly; 0: whole frames */
    uint64_t stop_after;   /* testing: return after this many IN frames (a "kill") */
    double board_cpu;      /* out: thread CPU seconds spent inside the board */
} np_loop_opts;

/* In-process: host <-> emulator. Returns 0 when the session ended (done or fault), 1 when stopped by stop_after. */
int np_link_loopback(np_host *h, np_board *b, np_loop_opts *o);

typedef struct np_usb_opts {
    uint16_t vid, pid;
    int interface;         /* -1: 0 */
    int ep_out, ep_in;     /* -1: the first bulk endpoints of the interface */
    unsigned in_flight;    /* transfers in flight each way; 0: 8 */
    double timeout;        /* seconds; 0: 2 */
    int verbose;
} np_usb_opts;

typedef struct np_usb_info {
    unsigned ep_out, ep_in, max_packet;
    unsigned in_flight;
    size_t in_transfer;    /* bytes per IN transfer */
    int speed;             /* libusb_speed */
    uint16_t vid, pid;
    char serial[128];      /* iSerialNumber's string; "" when the device has none */
} np_usb_info;

typedef struct np_usb_board np_usb_board;

/*
 * Open the board: find VID:PID, claim the interface, find its first bulk
 * pair (or the endpoints given), clear their halt, read the serial number
 * (info). 0, or -1 when it could not be opened or claimed (message in err:
 * a usage problem). Only with NOISEPIPE_HAVE_USB.
 */
int np_link_usb_open(np_usb_board **out, const np_usb_opts *o, np_usb_info *info, char *err,
                     size_t errlen);
/* Stream the session of h through libusb asynchronous bulk transfers until it ends (done or fault). */
void np_link_usb_stream(np_usb_board *b, np_host *h);
/* Release the interface and close (NULL is fine). */
void np_link_usb_close(np_usb_board *b);

/*
 * A byte stream on file descriptors (link_fd.c): a kernel tty (/dev/ttyUSB1 of
 * an FT2232H through ftdi_sio), a pipe or socket to a board simulator. rfd
 * carries IN bytes, wfd OUT bytes (they may be the same descriptor). Runs the
 * session of h to its end (done or fault): non-blocking for the session,
 * poll(), partial reads and writes; silence for timeout seconds while the host
 * waits, or OUT bytes not taken that long, is NP_FAULT_TIMEOUT; end of file,
 * EPIPE or EIO is NP_FAULT_NO_DEVICE. SIGPIPE is ignored during the session.
 * A tty is the caller's to set up (raw, baud, CRTSCTS, VMIN >= 1): np_link_tty_open.
 */
typedef struct np_fd_opts {
    double timeout;        /* seconds; 0: 2 */
    size_t chunk;          /* bytes per write() at most; 0: a whole frame */
} np_fd_opts;

void np_link_fd_stream(int rfd, int wfd, np_host *h, const np_fd_opts *o);

/* A board simulator run as a child on two pipes (its stdin: OUT bytes, its stdout: IN bytes). */
typedef struct np_link_child {
    int pid;               /* -1: none */
    int rfd, wfd;          /* the host's ends: read IN bytes from rfd, write OUT bytes to wfd */
    int status;            /* waitpid's, once reaped */
    int reaped;
} np_link_child;

/*
 * Start argv[0] (a path, or a name looked up in PATH; no shell) with argv,
 * stdin and stdout on pipes, stderr shared. 0, or -1 with err (it could not
 * be run: exec's reason, e.g. "No such file or directory").
 */
int np_link_spawn(np_link_child *c, char *const argv[], char *err, size_t errlen);
/* 1 once the child has exited (reaped, status kept), 0 while it runs. */
int np_link_child_exited(np_link_child *c);
/* "exit status 3", "killed by signal 9 (Killed)", "still running". */
void np_link_child_status(const np_link_child *c, char *buf, size_t len);
/*
 * Close both pipes (EOF on the child's stdin ends its session), wait up to
 * grace seconds for it to exit, then SIGTERM, then SIGKILL; reap it.
 * 0 when it exited by itself, 1 when it had to be signalled.
 */
int np_link_child_close(np_link_child *c, double grace);

/*
 * A kernel tty (link_tty.c): opened O_RDWR | O_NOCTTY, raw 8N1 (cfmakeraw),
 * CLOCAL | CREAD | CRTSCTS, the baud rate, both buffers flushed; the old
 * settings kept for close. The session then runs on fd with np_link_fd_stream.
 */
typedef struct np_tty {
    int fd;                /* -1: not open */
    unsigned baud;
    int rtscts;            /* CRTSCTS as the driver reports it back */
    int have_old;
    struct termios old;
} np_tty;

/* 1 when termios has a rate for baud. */
int np_link_tty_baud_ok(unsigned baud);
/* "9600, 19200, ..." into buf. */
void np_link_tty_rates(char *buf, size_t len);
/* 0, or -1 with err naming the device (missing, not a tty, a rate it cannot set). */
int np_link_tty_open(np_tty *t, const char *path, unsigned baud, char *err, size_t errlen);
/* Restore the settings and close (a closed one is fine). */
void np_link_tty_close(np_tty *t);

/* The FTDI FT2232H's UART channel through libftdi1 (link_ftdi.c; only with NOISEPIPE_HAVE_FTDI). */
typedef struct np_ftdi_opts {
    uint16_t vid, pid;     /* 0403:6010 for the FT2232H */
    int interface;         /* 0..3 = A..D; the HX8K breakout's FPGA UART is B (1) */
    unsigned baud;         /* 3000000 for the board's gateware */
    char serial[128];      /* "" any */
    double timeout;        /* seconds */
} np_ftdi_opts;

typedef struct np_ftdi_info {
    char serial[128];      /* iSerialNumber, "" when none */
    int baud;              /* the rate libftdi set (the chip's nearest) */
} np_ftdi_info;

typedef struct np_ftdi_board np_ftdi_board;

/* Open, set the baud rate, 8N1, RTS/CTS, latency timer 1 ms, purge. 0, or -1 with err (usage). */
int np_link_ftdi_open(np_ftdi_board **out, const np_ftdi_opts *o, np_ftdi_info *info, char *err,
                      size_t errlen);
void np_link_ftdi_stream(np_ftdi_board *b, np_host *h);
void np_link_ftdi_close(np_ftdi_board *b);

#endif /* NP_LINK_H */
