/* SPDX-License-Identifier: MIT */
/*
 * noisepipe stream - send vectors over USB to a board running a unit, read
 * the results back and verify every bit (docs/usb-protocol.md). --emulate
 * runs the same session against the in-process board emulator; --sim against
 * a board simulator run as a child on pipes (testbench/rtl/board_sim.cpp: the
 * Verilated gateware), through the file-descriptor transport.
 */
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "np_common.h"
#include "np_cmd.h"
#include "np_link.h"
#include "np_outfile.h"
#include "np_vec.h"

static const char usage_text[] =
    "usage: noisepipe stream (--device VID:PID | --ftdi [VID:PID] | --tty DEVICE |\n"
    "                        --emulate | --sim PROGRAM) [options]\n"
    "                        (VECTORS | --random N)\n"
    "                        [-- SIMULATOR ARGUMENTS]\n"
    "\n"
    "Stream the vectors to a board running the unit, verify every result bit for\n"
    "bit against the expected outputs, report TestFloat style.\n"
    "\n"
    "  VECTORS             vector file (noisepipe vectors); '-' = stdin\n"
    "  --random N          instead: N vectors made in memory, inputs from the seeded\n"
    "                      generator, expected outputs from the bit-exact model\n"
    "  --seed S            seed for --random (default 1)\n"
    "  --unit U            the unit (with --random; with VECTORS it must match the file)\n"
    "  --config K=V,...    its configuration (with --random; default: the unit's)\n"
    "  --device VID:PID    the board, hex ids (e.g. 1209:0001)\n"
    "  --interface N       USB interface (default 0)\n"
    "  --ep-out 0xA        bulk OUT endpoint address (default: the interface's first)\n"
    "  --ep-in 0xB         bulk IN endpoint address (default: the interface's first)\n"
    "  --in-flight N       USB transfers in flight each way (default 8)\n"
    "  --ftdi [VID:PID]    the board behind an FTDI FT2232H's UART channel (the\n"
    "                      iCE40-HX8K breakout, docs/board.md), through libftdi1;\n"
    "                      default 0403:6010\n"
    "  --ftdi-interface C  the FT2232H's channel A..D (default B: the FPGA's UART)\n"
    "  --ftdi-serial S     the FTDI chip with this serial number (default: the first)\n"
    "  --tty DEVICE        the board behind a kernel tty, e.g. /dev/ttyUSB1 (the\n"
    "                      FT2232H's channel B through ftdi_sio): raw 8N1, RTS/CTS,\n"
    "                      --baud; the journal binds \"tty DEVICE\"\n"
    "  --baud N            with --ftdi or --tty: the UART's rate (default 3000000:\n"
    "                      the gateware's); 8N1, RTS/CTS flow control\n"
    "  --emulate           no USB: the board emulator (cycle-accurate models) in process\n"
    "  --inject F:INDEX[:BIT]  with --emulate: make the emulated board fail at vector\n"
    "                      INDEX; F = wrong-bit, corrupt, short, drop, silent\n"
    "  --sim PROGRAM       a board simulator run as a child (no shell): OUT bytes to\n"
    "                      its stdin, IN bytes from its stdout; the words after '--'\n"
    "                      are its arguments. build/testbench/rtl_board/board_sim/\n"
    "                      board_sim is the Verilated gateware (docs/board.md); the\n"
    "                      journal binds \"sim PROGRAM\" (its arguments are not bound)\n"
    "  --journal FILE      journal of verified ranges (default VECTORS.journal;\n"
    "                      none with --random unless given)\n"
    "  --resume            continue the journal: send only what it does not hold; it\n"
    "                      must be of these vectors (unit, configuration, file size\n"
    "                      and contents) and this target (the emulator, the same\n"
    "                      --sim PROGRAM or --tty DEVICE, or the same VID:PID and\n"
    "                      serial number)\n"
    "  --force             without --resume: replace an existing journal (only once\n"
    "                      the target is open); without it an existing journal is\n"
    "                      never overwritten\n"
    "  --errors N          stop after N failing vectors (default 20; 0 = never)\n"
    "  --timeout SEC       a silent board with work outstanding is a fault (default 2)\n"
    "  --frame N           vectors per frame (default: as many as the board takes)\n"
    "  --window N          DATA frames outstanding at most (default: the board's)\n"
    "  --reconnect N       with --sim or --tty: after a link fault (time-out, a\n"
    "                      damaged frame, an ERROR from the board) start a new\n"
    "                      session (HELLO) on the same link, at most N times;\n"
    "                      what was verified stays verified (default 0)\n"
    "  --quiet             no per-vector failure lines\n"
    "\n"
    "Exit status: 0 every vector verified; 1 a result differed, or the link failed\n"
    "before the end (what was verified stays in the journal: rerun with --resume);\n"
    "2 bad usage or input (also a journal of other vectors or another target, or an\n"
    "existing journal without --resume/--force), board not found, a --sim program\n"
    "that cannot be run or ends before it answers, or the board does not run the\n"
    "unit or does not speak this protocol (docs/usb-protocol.md).\n";

typedef struct stream_args {
    const char *vectors, *unit, *config, *device, *journal, *inject;
    const char *ftdi, *ftdi_serial; /* ftdi: "" for the default VID:PID */
    const char *sim;                /* --sim PROGRAM */
    const char *tty;                /* --tty DEVICE */
    uint64_t reconnect;             /* --reconnect N */
    char **sim_args;                /* the words after "--" (sim_nargs of them) */
    int sim_nargs, have_dashdash;
    uint64_t random_n, seed, max_errors, frame, window, in_flight, baud;
    int ftdi_interface, have_baud;
    int have_random, emulate, resume, force, quiet;
    int interface, ep_out, ep_in;
    double timeout;
} stream_args;

/* "--name VALUE" or "--name=VALUE": 1 and *val set, 0 when argv[*i] is not it, -1 when VALUE is missing. */
/* The option parser every vector command shares (vec_cli.c). */
static int opt(int argc, char **argv, int *i, const char *name, const char **val)
{
    return np_vec_opt("stream", argc, argv, i, name, val);
}

static int num(const char *name, const char *v, uint64_t lo, uint64_t hi, uint64_t *out)
{
    if (np_parse_u64(v, lo, hi, out) == 0)
        return 0;
    np_err("stream", "%s %s: expected a decimal number in %llu..%llu", name, v, (unsigned long long)lo,
           (unsigned long long)hi);
    return -1;
}

/* An endpoint address: documented (and printed by lsusb) as 0x hex; decimal also taken. */
static int ep_num(const char *name, const char *v, uint64_t lo, uint64_t hi, uint64_t *out)
{
    if (np_parse_u64_or_0x(v, lo, hi, out) == 0)
        return 0;
    np_err("stream", "%s %s: expected an endpoint address 0x%02llx..0x%02llx", name, v, (unsigned long long)lo,
           (unsigned long long)hi);
    return -1;
}

static int parse_device(const char *s, uint16_t *vid, uint16_t *pid)
{
    char *end;
    unsigned long v = strtoul(s, &end, 16);
    if (end == s || *end != ':' || v > 0xffff)
        return -1;
    const char *p = end + 1;
    unsigned long q = strtoul(p, &end, 16);
    if (end == p || *end || q > 0xffff)
        return -1;
    *vid = (uint16_t)v;
    *pid = (uint16_t)q;
    return 0;
}

static int parse_args(int argc, char **argv, stream_args *a)
{
    memset(a, 0, sizeof *a);
    a->seed = 1;
    a->max_errors = 20;
    a->interface = a->ep_out = a->ep_in = -1;
    a->timeout = 2.0;
    a->ftdi_interface = -1;
    a->baud = 3000000;
    for (int i = 1; i < argc; i++) {
        const char *v = NULL;
        uint64_t x;
        int r;
        const char *arg = argv[i];
        if (strcmp(arg, "--") == 0) {
            /* the rest: the simulator's arguments, passed as they are */
            a->have_dashdash = 1;
            a->sim_args = argv + i + 1;
            a->sim_nargs = argc - i - 1;
            break;
        } else if ((r = opt(argc, argv, &i, "--sim", &v)) != 0) {
            if (r < 0)
                return -1;
            if (!v[0] || strlen(v) > 180) {
                np_err("stream", "--sim '%s': expected the simulator's program (a path of at most 180 characters, or a name in PATH)", v);
                return -1;
            }
            a->sim = v;
        } else if ((r = opt(argc, argv, &i, "--tty", &v)) != 0) {
            if (r < 0)
                return -1;
            if (!v[0] || strlen(v) > 180) {
                np_err("stream", "--tty '%s': expected the tty's path (at most 180 characters), e.g. /dev/ttyUSB1", v);
                return -1;
            }
            a->tty = v;
        } else if ((r = opt(argc, argv, &i, "--reconnect", &v)) != 0) {
            if (r < 0 || num("--reconnect", v, 0, 1000, &a->reconnect) != 0)
                return -1;
        } else if (strcmp(arg, "--emulate") == 0) {
            a->emulate = 1;
        } else if (strcmp(arg, "--ftdi") == 0) {
            /* VID:PID is optional: the next word is taken when it has a ':' (checked later) */
            a->ftdi = "";
            if (i + 1 < argc && argv[i + 1][0] != '-' && strchr(argv[i + 1], ':'))
                a->ftdi = argv[++i];
        } else if (strncmp(arg, "--ftdi=", 7) == 0) {
            a->ftdi = arg + 7;
        } else if ((r = opt(argc, argv, &i, "--ftdi-interface", &v)) != 0) {
            if (r < 0)
                return -1;
            if (!((v[0] >= 'A' && v[0] <= 'D') || (v[0] >= 'a' && v[0] <= 'd')) || v[1]) {
                np_err("stream", "--ftdi-interface %s: expected A, B, C or D (the FT2232H has A and B)", v);
                return -1;
            }
            a->ftdi_interface = (v[0] | 0x20) - 'a';
        } else if ((r = opt(argc, argv, &i, "--ftdi-serial", &v)) != 0) {
            if (r < 0)
                return -1;
            if (!v[0] || strlen(v) >= 128) {
                np_err("stream", "--ftdi-serial '%s': expected the chip's serial number, 1..127 characters", v);
                return -1;
            }
            a->ftdi_serial = v;
        } else if ((r = opt(argc, argv, &i, "--baud", &v)) != 0) {
            if (r < 0 || num("--baud", v, 300, 12000000, &a->baud) != 0)
                return -1;
            a->have_baud = 1;
        } else if (strcmp(arg, "--resume") == 0) {
            a->resume = 1;
        } else if (strcmp(arg, "--force") == 0) {
            a->force = 1;
        } else if (strcmp(arg, "--quiet") == 0) {
            a->quiet = 1;
        } else if ((r = opt(argc, argv, &i, "--unit", &v)) != 0) {
            if (r < 0)
                return -1;
            a->unit = v;
        } else if ((r = opt(argc, argv, &i, "--config", &v)) != 0) {
            if (r < 0)
                return -1;
            a->config = v;
        } else if ((r = opt(argc, argv, &i, "--device", &v)) != 0) {
            if (r < 0)
                return -1;
            a->device = v;
        } else if ((r = opt(argc, argv, &i, "--journal", &v)) != 0) {
            if (r < 0)
                return -1;
            a->journal = v;
        } else if ((r = opt(argc, argv, &i, "--inject", &v)) != 0) {
            if (r < 0)
                return -1;
            a->inject = v;
        } else if ((r = opt(argc, argv, &i, "--random", &v)) != 0) {
            if (r < 0 || num("--random", v, 1, (uint64_t)1 << 40, &a->random_n) != 0)
                return -1;
            a->have_random = 1;
        } else if ((r = opt(argc, argv, &i, "--seed", &v)) != 0) {
            if (r < 0 || num("--seed", v, 0, UINT64_MAX, &a->seed) != 0)
                return -1;
        } else if ((r = opt(argc, argv, &i, "--errors", &v)) != 0) {
            if (r < 0 || num("--errors", v, 0, UINT64_MAX, &a->max_errors) != 0)
                return -1;
        } else if ((r = opt(argc, argv, &i, "--frame", &v)) != 0) {
            if (r < 0 || num("--frame", v, 1, NP_LINK_MAX_COUNT, &a->frame) != 0)
                return -1;
        } else if ((r = opt(argc, argv, &i, "--window", &v)) != 0) {
            if (r < 0 || num("--window", v, 1, 1024, &a->window) != 0)
                return -1;
        } else if ((r = opt(argc, argv, &i, "--in-flight", &v)) != 0) {
            if (r < 0 || num("--in-flight", v, 2, 64, &a->in_flight) != 0)
                return -1;
        } else if ((r = opt(argc, argv, &i, "--interface", &v)) != 0) {
            if (r < 0 || num("--interface", v, 0, 255, &x) != 0)
                return -1;
            a->interface = (int)x;
        } else if ((r = opt(argc, argv, &i, "--ep-out", &v)) != 0) {
            if (r < 0 || ep_num("--ep-out", v, 0x01, 0x0f, &x) != 0)
                return -1;
            a->ep_out = (int)x;
        } else if ((r = opt(argc, argv, &i, "--ep-in", &v)) != 0) {
            if (r < 0 || ep_num("--ep-in", v, 0x81, 0x8f, &x) != 0)
                return -1;
            a->ep_in = (int)x;
        } else if ((r = opt(argc, argv, &i, "--timeout", &v)) != 0) {
            char *end;
            if (r < 0)
                return -1;
            a->timeout = strtod(v, &end);
            if (*v == '\0' || *end || !(a->timeout >= 0.01 && a->timeout <= 3600.0)) {
                np_err("stream", "--timeout %s: expected seconds in 0.01..3600", v);
                return -1;
            }
        } else if (arg[0] == '-' && arg[1] != '\0') {
            np_err("stream", "unknown option '%s' (noisepipe stream --help)", arg);
            return -1;
        } else if (!a->vectors) {
            a->vectors = arg;
        } else {
            np_err("stream", "more than one vector file ('%s' and '%s')", a->vectors, arg);
            return -1;
        }
    }
    if (!a->vectors == !a->have_random) {
        np_err("stream", "give a vector file or --random N (noisepipe stream --help)");
        return -1;
    }
    if (!!a->device + !!a->emulate + !!a->ftdi + !!a->sim + !!a->tty != 1) {
        np_err("stream", "give one of --device VID:PID, --ftdi [VID:PID], --tty DEVICE, --emulate or --sim PROGRAM "
                         "(noisepipe stream --help)");
        return -1;
    }
    if (a->have_dashdash && !a->sim) {
        np_err("stream", "arguments after '--' are the simulator's: they go with --sim PROGRAM");
        return -1;
    }
    if (a->inject && !a->emulate) {
        np_err("stream", "--inject works only with --emulate");
        return -1;
    }
    if (a->have_random && !a->unit) {
        np_err("stream", "--random needs --unit");
        return -1;
    }
    if (!a->ftdi && (a->ftdi_interface >= 0 || a->ftdi_serial)) {
        np_err("stream", "%s goes with --ftdi", a->ftdi_serial ? "--ftdi-serial" : "--ftdi-interface");
        return -1;
    }
    if (a->have_baud && !a->ftdi && !a->tty) {
        np_err("stream", "--baud goes with --ftdi or --tty");
        return -1;
    }
    if (a->reconnect && !a->sim && !a->tty) {
        np_err("stream", "--reconnect goes with --sim or --tty (the transports on a byte stream)");
        return -1;
    }
    if (a->resume && a->force) {
        np_err("stream", "--resume continues a journal, --force replaces it: give one of them");
        return -1;
    }
    return 0;
}

static int parse_inject(const char *s, np_board_fault *f)
{
    static const struct {
        const char *name;
        np_board_fault_kind kind;
    } kinds[] = {
        { "wrong-bit", NP_BOARD_WRONG_BIT }, { "corrupt", NP_BOARD_CORRUPT }, { "short", NP_BOARD_SHORT },
        { "drop", NP_BOARD_DROP },           { "silent", NP_BOARD_SILENT },
    };
    const char *colon = strchr(s, ':');
    if (!colon)
        return -1;
    memset(f, 0, sizeof *f);
    size_t n = (size_t)(colon - s);
    unsigned k = 0;
    while (k < sizeof kinds / sizeof kinds[0] && (strlen(kinds[k].name) != n || strncmp(s, kinds[k].name, n) != 0))
        k++;
    if (k == sizeof kinds / sizeof kinds[0])
        return -1;
    f->kind = kinds[k].kind;
    char buf[64];
    snprintf(buf, sizeof buf, "%s", colon + 1);
    char *bit = strchr(buf, ':');
    if (bit)
        *bit++ = '\0';
    uint64_t v;
    if (np_parse_u64(buf, 0, UINT64_MAX, &f->at) != 0)
        return -1;
    if (bit) {
        if (f->kind != NP_BOARD_WRONG_BIT || np_parse_u64(bit, 0, 63, &v) != 0)
            return -1;
        f->bit = (unsigned)v;
    }
    return 0;
}

/*
 * Read the vector file into the job, checking every expected output against
 * the model and every reference word against the float reference, as verify
 * does; size gets the file's size in bytes (the journal binds it).
 */
static int load_file(const stream_args *a, np_link_job *j, char *size, size_t sizelen)
{
    np_vec_reader r;
    if (np_vec_open(&r, a->vectors) != 0) {
        np_err("stream", "%s", r.L.err);
        np_vec_close(&r);
        return -1;
    }
    const np_vec_header *h = &r.h;
    struct stat sb;
    if (fstat(fileno(r.L.f), &sb) == 0 && S_ISREG(sb.st_mode))
        snprintf(size, sizelen, "%lld", (long long)sb.st_size);
    else
        snprintf(size, sizelen, "pipe");
    if (a->unit && strcmp(a->unit, h->unit->name) != 0) {
        np_err("stream", "%s holds vectors of unit %s, not %s", a->vectors, h->unit->name, a->unit);
        np_vec_close(&r);
        return -1;
    }
    if (a->config) {
        np_unit_cfg c;
        char err[256], text[256];
        if (np_unit_configure(h->unit, &c, a->config, err, sizeof err) != 0) {
            np_err("stream", "--config %s: %s", a->config, err);
            np_vec_close(&r);
            return -1;
        }
        np_unit_cfg_format(h->unit, &c, text, sizeof text);
        if (strcmp(text, h->cfg_text) != 0) {
            np_err("stream", "%s is for configuration '%s', not '%s'", a->vectors, h->cfg_text, text);
            np_vec_close(&r);
            return -1;
        }
    }
    if (np_link_job_init(j, h->unit, &h->cfg, h->count) != 0 ||
        !(j->line = malloc((size_t)(h->count ? h->count : 1) * sizeof *j->line))) {
        np_err("stream", "out of memory for %llu vectors", (unsigned long long)h->count);
        np_vec_close(&r);
        return -1;
    }
    np_vec_rec rec;
    uint64_t model[NP_UNIT_MAX_FIELDS], ref[NP_UNIT_MAX_FIELDS];
    int rc;
    while ((rc = np_vec_read(&r, &rec)) == 1) {
        np_vec_compute(h, rec.w[NP_VEC_IN], model, ref);
        for (unsigned k = 0; k < h->fields.n_out; k++) {
            if (ref[k] != rec.w[NP_VEC_REF][k]) {
                np_err("stream", "%s:%llu: %s.ref %016llx disagrees with the float reference %016llx (%.17g): corrupted vector file",
                       a->vectors, (unsigned long long)rec.line, h->fields.out[k].name,
                       (unsigned long long)rec.w[NP_VEC_REF][k], (unsigned long long)ref[k],
                       np_vec_ref_value(ref[k]));
                np_vec_close(&r);
                return -1;
            }
            if (model[k] != rec.w[NP_VEC_OUT][k]) {
                np_err("stream", "%s:%llu: expected %s = %llx, but the bit-exact model gives %llx: not a golden file for %s %s",
                       a->vectors, (unsigned long long)rec.line, h->fields.out[k].name,
                       (unsigned long long)rec.w[NP_VEC_OUT][k], (unsigned long long)model[k],
                       h->unit->name, h->cfg_text);
                np_vec_close(&r);
                return -1;
            }
        }
        np_link_job_set(j, rec.index, rec.w[NP_VEC_IN], rec.w[NP_VEC_OUT]);
        j->line[rec.index] = rec.line;
    }
    if (rc < 0) {
        np_err("stream", "%s", r.L.err);
        np_vec_close(&r);
        return -1;
    }
    np_vec_close(&r);
    np_link_job_seal(j);
    return 0;
}

/* --- Report --- */

typedef struct report {
    const np_link_job *j;
    const char *journal;     /* NULL: none */
    const np_journal *jn;
    uint64_t printed, limit;
    int quiet;
    /* progress */
    int tty;
    double t0, last;
    uint64_t todo;
    const np_host *h;
} report;

static void put_words(const uint64_t *w, const np_field *f, const unsigned *lane, unsigned n)
{
    for (unsigned k = 0; k < n; k++) {
        unsigned digits = (f[k].bits + 3u) / 4u;
        uint64_t mask = np_link_mask(f[k].bits);
        if (w[k] & ~mask)
            digits = 2u * lane[k]; /* bits above the width: show the whole lane */
        printf("%s%0*llx", k ? " " : "", (int)digits, (unsigned long long)w[k]);
    }
}

/* TestFloat style: "inputs => got expected: want", then where the vector is. */
static void print_fail(report *rp, uint64_t index, const uint64_t *got)
{
    if (rp->quiet || (rp->limit && rp->printed >= rp->limit))
        return;
    const np_link_job *j = rp->j;
    const np_link_layout *l = &j->lay;
    uint64_t in[NP_UNIT_MAX_FIELDS], want[NP_UNIT_MAX_FIELDS];
    np_link_unpack(j->in + index * l->in_stride, in, l->in_lane, l->n_in);
    np_link_unpack(j->want + index * l->out_stride, want, l->out_lane, l->n_out);
    if (rp->tty)
        fputs("\r\033[K", stderr);
    put_words(in, j->fields.in, l->in_lane, l->n_in);
    fputs(" => ", stdout);
    put_words(got, j->fields.out, l->out_lane, l->n_out);
    fputs(" expected: ", stdout);
    put_words(want, j->fields.out, l->out_lane, l->n_out);
    printf("   vector %llu", (unsigned long long)index);
    if (j->line)
        printf(" (line %llu)", (unsigned long long)j->line[index]);
    int same = 1;
    for (unsigned k = 0; k < l->n_out; k++)
        same &= got[k] == want[k];
    if (same)
        fputs("   (every field is right: the record's padding bytes are not 0)", stdout);
    putchar('\n');
    fflush(stdout);
    rp->printed++;
}

static void on_fail(void *ctx, uint64_t index, const uint64_t *got) { print_fail(ctx, index, got); }

/* What an interruption keeps, and how to go on (np_interrupt_note): kept current as results arrive. */
static void interrupt_note(const report *rp)
{
    char note[4600];
    const np_journal *jn = rp->jn;
    if (rp->journal)
        snprintf(note, sizeof note,
                 "journal %s keeps %llu of %llu vectors verified (%llu errors); run again with --resume (not --force) "
                 "to send the other %llu",
                 rp->journal, (unsigned long long)jn->n_checked, (unsigned long long)jn->n,
                 (unsigned long long)jn->n_errors, (unsigned long long)(jn->n - jn->n_checked));
    else
        snprintf(note, sizeof note,
                 "no journal (--journal FILE keeps one): the %llu vectors verified are not kept",
                 (unsigned long long)jn->n_checked);
    np_interrupt_note(note);
}

static void on_progress(void *ctx, uint64_t verified)
{
    report *rp = ctx;
    interrupt_note(rp);
    if (!rp->tty)
        return;
    double t = np_now();
    if (t - rp->last < 0.25 && verified < rp->todo)
        return;
    rp->last = t;
    const np_host_stats *s = np_host_get_stats(rp->h);
    double el = t - rp->t0 > 1e-6 ? t - rp->t0 : 1e-6;
    double rate = (double)verified / el;
    double left = rate > 0 ? (double)(rp->todo - verified) / rate : 0.0;
    fprintf(stderr, "\rstream: %5.1f%%  %llu/%llu  %.0f vectors/s  %.1f MB/s  %.0f s left   ",
            rp->todo ? 100.0 * (double)verified / (double)rp->todo : 100.0, (unsigned long long)verified,
            (unsigned long long)rp->todo, rate, (double)(s->bytes_out + s->bytes_in) / el / 1e6, left);
    fflush(stderr);
}

static void close_target(np_board *board, np_usb_board *ub)
{
    np_board_free(board);
#ifdef NOISEPIPE_HAVE_USB
    np_link_usb_close(ub);
#else
    (void)ub;
#endif
}

static void close_all(np_board *board, np_usb_board *ub, np_ftdi_board *fb)
{
    close_target(board, ub);
#ifdef NOISEPIPE_HAVE_FTDI
    np_link_ftdi_close(fb);
#else
    (void)fb;
#endif
}

/* Faults after which a new session on the same byte stream can go on: the board is still there. */
static int reconnectable(np_link_fault f)
{
    return f == NP_FAULT_TIMEOUT || f == NP_FAULT_CORRUPT || f == NP_FAULT_SHORT || f == NP_FAULT_SEQ ||
           f == NP_FAULT_BOARD;
}

/*
 * The sessions on a byte stream (--sim, --tty): the first, then with
 * --reconnect N up to N more after a link fault, each a new host (a new HELLO
 * and nonce: the board's stale answers to the old one are dropped before
 * INFO) on the same job and journal, so a new session sends only what the
 * journal does not hold. Each ended session but the last prints its
 * "session:" line here. The last host is returned (NULL: out of memory).
 */
static np_host *fd_sessions(int rfd, int wfd, np_host *h, const stream_args *a, const np_link_job *j,
                            np_journal *jn, const np_host_opts *ho, report *rp)
{
    np_fd_opts fo;
    memset(&fo, 0, sizeof fo);
    fo.timeout = a->timeout;
    for (uint64_t n = 0;; n++) {
        np_link_fd_stream(rfd, wfd, h, &fo);
        np_link_fault f = np_host_get_fault(h);
        if (n >= a->reconnect || !reconnectable(f) || np_host_complete(h) ||
            (a->max_errors && jn->n_errors >= a->max_errors))
            return h;
        const np_host_stats *s = np_host_get_stats(h);
        np_err("stream", "%s", np_host_fault_msg(h));
        printf("session: %llu vectors sent, %llu verified; %s: a new session on the same link (--reconnect, %llu of %llu)\n",
               (unsigned long long)s->sent, (unsigned long long)s->verified, np_link_fault_name(f),
               (unsigned long long)n + 1, (unsigned long long)a->reconnect);
        fflush(stdout);
        np_host_free(h);
        if (!(h = np_host_new(j, jn, ho))) {
            rp->h = NULL;
            return NULL;
        }
        rp->h = h;
    }
}

static double cpu_seconds(void)
{
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    return (double)ru.ru_utime.tv_sec + (double)ru.ru_utime.tv_usec * 1e-6 + (double)ru.ru_stime.tv_sec +
           (double)ru.ru_stime.tv_usec * 1e-6;
}

int np_cmd_stream(int argc, char **argv)
{
    for (int i = 1; i < argc; i++)
        if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
            fputs(usage_text, stdout);
            return NP_EXIT_OK;
        }
    stream_args a;
    if (parse_args(argc, argv, &a) != 0)
        return NP_EXIT_USAGE;
    np_usb_opts uo;
    memset(&uo, 0, sizeof uo);
    if (a.device) {
#ifndef NOISEPIPE_HAVE_USB
        np_err("stream", "this noisepipe was built without USB support (libusb-1.0 was not found when it was "
                         "configured): install libusb-1.0-0-dev and rebuild, or use --emulate");
        return NP_EXIT_USAGE;
#endif
        if (parse_device(a.device, &uo.vid, &uo.pid) != 0) {
            np_err("stream", "--device %s: expected VID:PID in hex, e.g. 1209:0001", a.device);
            return NP_EXIT_USAGE;
        }
    }
    uint16_t fvid = 0x0403, fpid = 0x6010;
    int ftdi_baud = 0;
    if (a.ftdi) {
#ifndef NOISEPIPE_HAVE_FTDI
        np_err("stream", "this noisepipe was built without the FTDI transport (libftdi1 was not found when it "
                         "was configured): install libftdi1-dev and rebuild");
        return NP_EXIT_USAGE;
#endif
        if (a.ftdi[0] && parse_device(a.ftdi, &fvid, &fpid) != 0) {
            np_err("stream", "--ftdi %s: expected VID:PID in hex, e.g. 0403:6010", a.ftdi);
            return NP_EXIT_USAGE;
        }
    }
    (void)ftdi_baud;
    np_board_opts bo;
    memset(&bo, 0, sizeof bo);
    if (a.inject && parse_inject(a.inject, &bo.fault) != 0) {
        np_err("stream", "--inject %s: expected wrong-bit|corrupt|short|drop|silent:INDEX[:BIT]", a.inject);
        return NP_EXIT_USAGE;
    }

    /* The vectors. */
    np_link_job j;
    memset(&j, 0, sizeof j);
    char source[4200], size[64] = "generated";
    if (a.have_random) {
        const np_unit *u = np_unit_find(a.unit);
        np_unit_cfg cfg;
        char err[256];
        if (!u) {
            np_err("stream", "unknown unit '%s' (noisepipe units lists them)", a.unit);
            return NP_EXIT_USAGE;
        }
        if (np_unit_configure(u, &cfg, a.config, err, sizeof err) != 0) {
            np_err("stream", "--config: %s", err);
            return NP_EXIT_USAGE;
        }
        if (np_link_job_random(&j, u, &cfg, a.random_n, a.seed) != 0) {
            np_err("stream", "out of memory for %llu vectors", (unsigned long long)a.random_n);
            return NP_EXIT_USAGE;
        }
        snprintf(source, sizeof source, "random, seed %llu", (unsigned long long)a.seed);
    } else {
        if (load_file(&a, &j, size, sizeof size) != 0) {
            np_link_job_free(&j);
            return NP_EXIT_USAGE;
        }
        snprintf(source, sizeof source, "%s", a.vectors);
    }

    char jpath[4200];
    const char *journal = a.journal;
    if (!journal && a.vectors && strcmp(a.vectors, "-") != 0) {
        snprintf(jpath, sizeof jpath, "%s.journal", a.vectors);
        journal = jpath;
    }
    if ((a.resume || a.force) && !journal) {
        np_err("stream", "%s needs a journal (--journal FILE)", a.resume ? "--resume" : "--force");
        np_link_job_free(&j);
        return NP_EXIT_USAGE;
    }

    /* The target first: a journal is opened (and, with --force, replaced) only once it is open. */
    np_link_target tg;
    memset(&tg, 0, sizeof tg);
    snprintf(tg.size, sizeof tg.size, "%s", size);
    np_board *board = NULL;
    np_usb_board *ub = NULL;
    np_ftdi_board *fb = NULL;
    (void)fb;
    np_usb_info ui;
    memset(&ui, 0, sizeof ui);
    char err[1024];
    np_link_child sim;
    memset(&sim, 0, sizeof sim);
    sim.pid = sim.rfd = sim.wfd = -1;
    np_tty tty;
    memset(&tty, 0, sizeof tty);
    tty.fd = -1;
    if (a.tty) {
        if (np_link_tty_open(&tty, a.tty, (unsigned)a.baud, err, sizeof err) != 0) {
            np_err("stream", "%s", err);
            np_link_job_free(&j);
            return NP_EXIT_USAGE;
        }
        /* bound to the device's path as given (the rate is not bound: a resume may run at another) */
        snprintf(tg.target, sizeof tg.target, "tty %.*s", (int)(sizeof tg.target - 8), a.tty);
    } else if (a.sim) {
        /* argv for exec: the program, then the words after "--" */
        char **sargv = calloc((size_t)a.sim_nargs + 2, sizeof *sargv);
        if (!sargv) {
            np_err("stream", "out of memory");
            np_link_job_free(&j);
            return NP_EXIT_USAGE;
        }
        sargv[0] = (char *)a.sim;
        for (int k = 0; k < a.sim_nargs; k++)
            sargv[k + 1] = a.sim_args[k];
        int rc = np_link_spawn(&sim, sargv, err, sizeof err);
        free(sargv);
        if (rc != 0) {
            np_err("stream", "--sim: %s", err);
            np_link_job_free(&j);
            return NP_EXIT_USAGE;
        }
        /* bound to the simulator's program as given (its arguments, such as injected faults, are not bound) */
        snprintf(tg.target, sizeof tg.target, "sim %.*s", (int)(sizeof tg.target - 8), a.sim);
    } else if (a.emulate) {
        if (!(board = np_board_new(&bo))) {
            np_err("stream", "out of memory");
            np_link_job_free(&j);
            return NP_EXIT_USAGE;
        }
        snprintf(tg.target, sizeof tg.target, "emulator");
    } else if (a.ftdi) {
#ifdef NOISEPIPE_HAVE_FTDI
        np_ftdi_opts fo;
        np_ftdi_info fi;
        memset(&fo, 0, sizeof fo);
        fo.vid = fvid;
        fo.pid = fpid;
        fo.interface = a.ftdi_interface >= 0 ? a.ftdi_interface : 1;
        fo.baud = (unsigned)a.baud;
        fo.timeout = a.timeout;
        if (a.ftdi_serial)
            snprintf(fo.serial, sizeof fo.serial, "%s", a.ftdi_serial);
        if (np_link_ftdi_open(&fb, &fo, &fi, err, sizeof err) != 0) {
            np_err("stream", "%s", err);
            np_link_job_free(&j);
            return NP_EXIT_USAGE;
        }
        snprintf(tg.target, sizeof tg.target, "ftdi %04x:%04x interface %c serial %s", fvid, fpid,
                 'A' + fo.interface, fi.serial[0] ? fi.serial : "none");
        ftdi_baud = fi.baud;
#endif
    } else {
#ifdef NOISEPIPE_HAVE_USB
        uo.interface = a.interface;
        uo.ep_out = a.ep_out;
        uo.ep_in = a.ep_in;
        uo.in_flight = (unsigned)a.in_flight;
        uo.timeout = a.timeout;
        if (np_link_usb_open(&ub, &uo, &ui, err, sizeof err) != 0) {
            np_err("stream", "%s", err);
            np_link_job_free(&j);
            return NP_EXIT_USAGE;
        }
#endif
        snprintf(tg.target, sizeof tg.target, "usb %04x:%04x serial %s", uo.vid, uo.pid,
                 ui.serial[0] ? ui.serial : "none");
    }

    /* The journal. */
    np_journal jn;
    if (np_journal_open_bound(&jn, journal, &j, &tg, a.resume, a.force, err, sizeof err) != 0) {
        np_err("stream", "%s", err);
        np_journal_close(&jn);
        np_link_child_close(&sim, 2.0);
        np_link_tty_close(&tty);
        close_all(board, ub, fb);
        np_link_job_free(&j);
        return NP_EXIT_USAGE;
    }

    report rp;
    memset(&rp, 0, sizeof rp);
    rp.j = &j;
    rp.journal = journal;
    rp.jn = &jn;
    rp.limit = a.max_errors;
    rp.quiet = a.quiet;
    rp.tty = isatty(2);
    rp.todo = j.n - jn.prior_checked;
    printf("stream: %s %s, %llu vectors (%s, %016llx) to %s%s\n", j.unit->name, j.cfg_text,
           (unsigned long long)j.n, source, (unsigned long long)j.hash,
           a.emulate ? "the board emulator" : a.ftdi ? "the FT2232H" : a.sim ? "the simulator " : a.tty ? "the tty " : a.device,
           a.sim ? a.sim : a.tty ? a.tty : "");
    if (!a.emulate)
        printf("target: %s\n", tg.target);
    if (journal)
        printf("journal: %s%s\n", journal, a.resume ? "" : a.force ? " (new, --force)" : " (new)");
    if (a.resume) {
        printf("resumed: %llu vectors verified before (%llu errors); %llu to send\n",
               (unsigned long long)jn.prior_checked, (unsigned long long)jn.prior_errors,
               (unsigned long long)rp.todo);
        for (size_t k = 0; k < jn.n_fails; k++)
            print_fail(&rp, jn.fails[k].index, jn.fails[k].got);
    }
    fflush(stdout);
    interrupt_note(&rp);

    np_host_opts ho;
    memset(&ho, 0, sizeof ho);
    ho.frame_records = (unsigned)a.frame;
    ho.window = (unsigned)a.window;
    ho.max_errors = a.max_errors;
    ho.on_fail = on_fail;
    ho.on_progress = on_progress;
    ho.fail_ctx = &rp;
    np_host *h = np_host_new(&j, &jn, &ho);
    if (!h) {
        np_err("stream", "out of memory");
        np_interrupt_note(NULL);
        np_journal_close(&jn);
        np_link_child_close(&sim, 2.0);
        np_link_tty_close(&tty);
        close_all(board, ub, fb);
        np_link_job_free(&j);
        return NP_EXIT_USAGE;
    }
    rp.h = h;

    /* Run the session. */
    double cpu0 = cpu_seconds(), board_cpu = 0;
    rp.t0 = rp.last = np_now();
    if (board) {
        np_loop_opts lo;
        memset(&lo, 0, sizeof lo);
        lo.timeout = a.timeout;
        np_link_loopback(h, board, &lo);
        board_cpu = lo.board_cpu;
    }
#ifdef NOISEPIPE_HAVE_USB
    if (ub)
        np_link_usb_stream(ub, h);
#endif
#ifdef NOISEPIPE_HAVE_FTDI
    if (fb)
        np_link_ftdi_stream(fb, h);
#endif
    int sim_early = 0; /* the simulator ended before it answered HELLO: not a board (usage) */
    char sim_status[128] = "";
    if (a.tty) {
        h = fd_sessions(tty.fd, tty.fd, h, &a, &j, &jn, &ho, &rp);
        np_link_tty_close(&tty);
    }
    if (a.sim) {
        h = fd_sessions(sim.rfd, sim.wfd, h, &a, &j, &jn, &ho, &rp);
        if (h && np_host_get_fault(h) == NP_FAULT_NO_DEVICE && np_host_get_stats(h)->info.board_id[0] == '\0') {
            /* its end of the pipes closed before INFO: a program that exited (give it a second to be reaped) */
            double t0 = np_now();
            while (!np_link_child_exited(&sim) && np_now() - t0 < 1.0) {
                struct timespec ts = { 0, 2000000 };
                nanosleep(&ts, NULL);
            }
            sim_early = np_link_child_exited(&sim);
        }
        int signalled = np_link_child_close(&sim, 2.0);
        np_link_child_status(&sim, sim_status, sizeof sim_status);
        if (signalled)
            np_err("stream", "the simulator %s did not end within 2 s of the end of its input: stopped (%s)",
                   a.sim, sim_status);
    }
    close_all(board, ub, fb);
    if (!h) {
        np_err("stream", "out of memory for a new session");
        np_interrupt_note(NULL);
        np_journal_close(&jn);
        np_link_job_free(&j);
        return NP_EXIT_USAGE;
    }
    double cpu = cpu_seconds() - cpu0 - board_cpu;
    char jerr[512];
    int jsync = np_journal_sync(&jn, jerr, sizeof jerr);
    np_interrupt_note(NULL); /* from here on the journal is whole and synced */
    if (rp.tty)
        fputs("\r\033[K", stderr);

    const np_host_stats *s = np_host_get_stats(h);
    np_link_fault fault = np_host_get_fault(h);
    int status;
    {
        /* Figures. */
        double span = s->t_last_result > s->t_first_data ? s->t_last_result - s->t_first_data : 0.0;
        if (s->verified && span > 0) {
            printf("link: %llu vectors in %.3f s: %.0f vectors/s; %.2f MB/s out, %.2f MB/s in (%.2f MB/s both ways)\n",
                   (unsigned long long)s->verified, span, (double)s->verified / span,
                   (double)s->bytes_out / span / 1e6, (double)s->bytes_in / span / 1e6,
                   (double)(s->bytes_out + s->bytes_in) / span / 1e6);
            printf("host CPU: %.3f s, %.0f ns per vector%s\n", cpu, cpu / (double)s->verified * 1e9,
                   a.emulate ? " (the emulator's own time excluded)" : "");
            if (a.emulate)
                printf("emulator CPU: %.3f s, %.0f ns per vector (cycle-accurate model)\n", board_cpu,
                       board_cpu / (double)s->verified * 1e9);
        }
        if (ftdi_baud)
            printf("ftdi: %d baud, 8N1, RTS/CTS, latency timer 1 ms\n", ftdi_baud);
        if (!a.emulate && ui.max_packet)
            printf("usb: endpoints 0x%02x/0x%02x, wMaxPacketSize %u, %u transfers in flight each way, IN transfers of %zu bytes\n",
                   ui.ep_out, ui.ep_in, ui.max_packet, ui.in_flight, ui.in_transfer);
        if (s->info.board_id[0])
            printf("board: '%s', window %u, max payload %u; %u vectors per frame", s->info.board_id,
                   (unsigned)s->info.window, (unsigned)s->info.max_payload, np_host_frame_records(h));
        if (s->have_bye && s->bye.records)
            printf("; %llu records in %llu clocks (%.3f clocks per vector, latency %u)",
                   (unsigned long long)s->bye.records, (unsigned long long)s->bye.cycles,
                   (double)s->bye.cycles / (double)s->bye.records, (unsigned)s->ack.latency);
        if (s->info.board_id[0])
            putchar('\n');
        if (fault != NP_FAULT_NONE)
            np_err("stream", "%s", np_host_fault_msg(h));
        if (a.sim && fault == NP_FAULT_NO_DEVICE)
            np_err("stream", "the simulator %s ended: %s%s", a.sim, sim_status,
                   sim_early ? " before it answered HELLO (is it a board simulator that reads the host's bytes "
                               "on stdin and writes the board's on stdout? docs/board.md)"
                             : "");
        if (a.sim)
            printf("session: %llu vectors sent, %llu verified; the simulator: %s\n", (unsigned long long)s->sent,
                   (unsigned long long)s->verified, sim_status);
        if (a.tty)
            printf("session: %llu vectors sent, %llu verified; tty %s at %u baud, RTS/CTS %s\n",
                   (unsigned long long)s->sent, (unsigned long long)s->verified, a.tty, tty.baud,
                   tty.rtscts ? "on" : "not kept by the driver");
        if (jsync != 0 && fault == NP_FAULT_NONE) {
            np_err("stream", "%s", jerr);
            fault = NP_FAULT_JOURNAL;
        }
        uint64_t checked = jn.n_checked, errors = jn.n_errors;
        const char *what = j.unit->name;
        char found[64];
        if (errors == 0)
            snprintf(found, sizeof found, "no errors");
        else
            snprintf(found, sizeof found, "%llu error%s", (unsigned long long)errors, errors == 1 ? "" : "s");
        int usage = fault == NP_FAULT_CONFIG || fault == NP_FAULT_INCOMPATIBLE || sim_early;
        if (usage) {
            /* a usage error: nothing was tested, no verdict */
        } else if (checked == j.n) {
            printf("In %llu tests, %s found in %s %s.\n", (unsigned long long)checked, found, what, j.cfg_text);
        } else {
            const char *why = fault != NP_FAULT_NONE ? np_link_fault_name(fault)
                                                     : "stopped after the error limit (--errors)";
            printf("In %llu tests, %s found in %s %s; INCOMPLETE: %llu of %llu vectors not verified (%s).\n",
                   (unsigned long long)checked, found, what, j.cfg_text,
                   (unsigned long long)(j.n - checked), (unsigned long long)j.n, why);
            if (journal && fault != NP_FAULT_JOURNAL)
                printf("The journal %s keeps the %llu verified vectors: run again with --resume to send the other %llu.\n",
                       journal, (unsigned long long)checked, (unsigned long long)(j.n - checked));
        }
        if (usage && journal && !a.resume && checked == 0)
            unlink(journal); /* this run's own new journal, holding nothing: not left to block the next run */
        if (usage || fault == NP_FAULT_JOURNAL)
            status = NP_EXIT_USAGE;
        else if (fault != NP_FAULT_NONE || errors || checked != j.n)
            status = NP_EXIT_FAIL;
        else
            status = NP_EXIT_OK;
    }
    fflush(stdout);
    np_host_free(h);
    np_journal_close(&jn);
    np_link_job_free(&j);
    return status;
}
