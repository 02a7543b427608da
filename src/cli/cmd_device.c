/* SPDX-License-Identifier: MIT */
/*
 * noisepipe device - a stand-in device: runs each vector's inputs through the
 * cycle-accurate model and writes the line back with the results appended
 * (TestFloat's `gen | device | ver` pipe), or the results alone. Fault
 * injection (--flip-bit) lets tests prove the verifier catches one wrong bit.
 */
#include <stdio.h>
#include <string.h>

#include "np_common.h"
#include "np_cmd.h"
#include "np_vec.h"

static const char usage[] =
    "usage: noisepipe device [--unit-from-header | --unit U] [--format text|results]\n"
    "                        [--flip-bit B --at K [--field F]] [-o FILE] [VECTORS|-]\n"
    "\n"
    "Acts as the device under test: reads a vector file (default stdin), configures the unit\n"
    "from its header (--unit-from-header, the only mode), runs the inputs through the\n"
    "cycle-accurate model and writes each vector line back with one extra field per output,\n"
    "the device's result. Pipe it into `noisepipe verify -`.\n"
    "\n"
    "  --unit U          require the header's unit to be U (exit 2 otherwise)\n"
    "  --format text     the vector lines with the results appended (default)\n"
    "  --format results  the results only, one line per vector ('//' header): for\n"
    "                    `verify --results` and for a Verilog testbench's $readmemh\n"
    "  --flip-bit B      fault injection: flip bit B (0 = LSB) of output field F ...\n"
    "  --at K            ... in transaction K (0-based, the $readmemh address)\n"
    "  --field F         the output field to flip (default: the first)\n"
    "  -o FILE           write FILE (atomically); default stdout\n";

/* Fault injection: flip one bit of one output of one transaction. */
typedef struct flip {
    int on;
    uint64_t bit, at;
    unsigned field;
} flip;

typedef struct device {
    np_vec_writer w;
    flip fl;
} device;

static int sink_write(void *ctx, const np_vec_rec *rec, const uint64_t *out, const np_vec_timing *t)
{
    device *d = ctx;
    np_vec_rec r = *rec;
    (void)t;
    memcpy(r.w[NP_VEC_GOT], out, sizeof r.w[NP_VEC_GOT]);
    if (d->fl.on && r.index == d->fl.at)
        r.w[NP_VEC_GOT][d->fl.field] ^= (uint64_t)1 << d->fl.bit;
    return np_vec_writer_put(&d->w, &r) != 0;
}

/* Check --flip-bit/--at/--field against the file's unit. 0, or -1 after a message. */
static int flip_resolve(const char *cmd, flip *fl, const char *field, const np_vec_reader *r)
{
    const np_unit_fields *F = &r->h.fields;
    if (!fl->on)
        return 0;
    for (fl->field = 0; field && fl->field < F->n_out; fl->field++)
        if (strcmp(F->out[fl->field].name, field) == 0)
            break;
    if (fl->field == F->n_out) {
        np_err(cmd, "--field %s: unit %s has no such output", field, r->h.unit->name);
        return -1;
    }
    if (fl->bit >= F->out[fl->field].bits) {
        np_err(cmd, "--flip-bit %llu: output %s has %u bits", (unsigned long long)fl->bit,
               F->out[fl->field].name, F->out[fl->field].bits);
        return -1;
    }
    if (fl->at >= r->h.count) {
        np_err(cmd, "--at %llu: the file has %llu transactions", (unsigned long long)fl->at,
               (unsigned long long)r->h.count);
        return -1;
    }
    return 0;
}

/* Run the device over the open reader r; NP_EXIT_*. */
static int run_device(const char *cmd, np_vec_reader *r, device *d, np_vec_format fmt,
                      const char *out_path)
{
    char err[NP_VEC_ERRLEN];
    np_vec_drive_stats st;
    np_vec_header oh = r->h;
    oh.has_got = 1;
    if (np_vec_writer_open(&d->w, out_path, fmt, &oh) != 0) {
        np_err(cmd, "%s", d->w.err);
        return NP_EXIT_USAGE;
    }
    int rc = np_vec_drive(&r->h, np_vec_read_source, r, sink_write, d, 0, 0, &st, err, sizeof err);
    if (rc == NP_DRIVE_BAD_INPUT)
        np_err(cmd, "%s", r->L.err);
    else if (rc == NP_DRIVE_MODEL)
        np_err(cmd, "cycle model failure: %s", err);
    else if (rc == NP_DRIVE_STOPPED)
        np_err(cmd, "%s", d->w.err);
    if (np_vec_writer_close(&d->w, rc == NP_DRIVE_DONE) != 0 && rc == NP_DRIVE_DONE) {
        np_err(cmd, "%s", d->w.err);
        rc = NP_DRIVE_STOPPED;
    }
    return rc == NP_DRIVE_DONE ? NP_EXIT_OK : rc == NP_DRIVE_MODEL ? NP_EXIT_FAIL : NP_EXIT_USAGE;
}

int np_cmd_device(int argc, char **argv)
{
    const char *cmd = "device", *in_path = NULL, *out_path = NULL, *field = NULL, *unit = NULL, *v;
    np_vec_format fmt = NP_VEC_TEXT;
    device d;
    int have_bit = 0, have_at = 0;
    memset(&d, 0, sizeof d);
    for (int i = 1; i < argc; i++) {
        int r;
        if (np_vec_is_help(argv[i])) {
            fputs(usage, stdout);
            return NP_EXIT_OK;
        } else if (strcmp(argv[i], "--unit-from-header") == 0) {
            r = 1;
        } else if ((r = np_vec_opt(cmd, argc, argv, &i, "--unit", &v)) != 0) {
            unit = v;
        } else if ((r = np_vec_opt(cmd, argc, argv, &i, "--format", &v)) != 0) {
            if (r > 0 && (np_vec_format_parse(v, &fmt) != 0 || (fmt != NP_VEC_TEXT && fmt != NP_VEC_RESULTS))) {
                np_err(cmd, "--format '%s': expected text or results", v);
                return NP_EXIT_USAGE;
            }
        } else if ((r = np_vec_opt(cmd, argc, argv, &i, "--flip-bit", &v)) != 0) {
            if (r > 0 && np_vec_opt_u64(cmd, "--flip-bit", v, 0, 63, &d.fl.bit) != 0)
                return NP_EXIT_USAGE;
            have_bit = 1;
        } else if ((r = np_vec_opt(cmd, argc, argv, &i, "--at", &v)) != 0) {
            if (r > 0 && np_vec_opt_u64(cmd, "--at", v, 0, UINT64_MAX, &d.fl.at) != 0)
                return NP_EXIT_USAGE;
            have_at = 1;
        } else if ((r = np_vec_opt(cmd, argc, argv, &i, "--field", &v)) != 0) {
            field = v;
        } else if ((r = np_vec_opt(cmd, argc, argv, &i, "-o", &v)) != 0) {
            out_path = v;
        } else if (argv[i][0] == '-' && argv[i][1] != '\0') {
            np_err(cmd, "unknown option '%s' (see noisepipe device --help)", argv[i]);
            return NP_EXIT_USAGE;
        } else if (in_path) {
            np_err(cmd, "one vector file only ('%s' and '%s')", in_path, argv[i]);
            return NP_EXIT_USAGE;
        } else {
            in_path = argv[i];
            r = 1;
        }
        if (r < 0)
            return NP_EXIT_USAGE;
    }
    if (have_bit != have_at || (field && !have_bit)) {
        np_err(cmd, "--flip-bit and --at go together (and --field needs them)");
        return NP_EXIT_USAGE;
    }
    d.fl.on = have_bit;
    np_vec_reader r;
    int rc = NP_EXIT_USAGE;
    if (np_vec_open(&r, in_path ? in_path : "-") != 0)
        np_err(cmd, "%s", r.L.err);
    else if (r.h.has_got)
        np_err(cmd, "%s: the vector lines already carry device results", r.L.name);
    else if (unit && strcmp(unit, r.h.unit->name) != 0)
        np_err(cmd, "%s: the vectors are for unit %s, not %s", r.L.name, r.h.unit->name, unit);
    else if (flip_resolve(cmd, &d.fl, field, &r) == 0)
        rc = run_device(cmd, &r, &d, fmt, out_path);
    np_vec_close(&r);
    return rc;
}
