/* SPDX-License-Identifier: MIT */
/*
 * noisepipe bench: throughput of the classic unit's models and of the sweep,
 * all measured in one run so that the ratios mean something on a shared
 * machine. Each figure runs for about --seconds of wall time and is given
 * per wall-clock second and per CPU second: on a loaded machine the first
 * drops, the second measures the work.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "np_classic.h"
#include "np_cli.h"
#include "np_cmd.h"
#include "np_ref.h"
#include "np_sweep.h"
#include "np_unit.h"

static const char usage_text[] =
    "usage: noisepipe bench [--seconds S]\n"
    "\n"
    "Measures, for the classic3 unit in its default configuration: the bit-exact model\n"
    "per input and through the sweep kernel, the float reference likewise, the\n"
    "cycle-accurate model, and the exhaustive sweep on two threads with the projected\n"
    "time of a full z slice (2^32 inputs). S: seconds per figure (default 1, 0.05..60).\n";

/* Sink for results, so that no evaluation is optimised away. */
static volatile uint64_t sink;

/* A stream of inputs that walks all cells and fractions (an odd-step counter). */
static uint64_t next_input(uint64_t k) { return k * 0x9e3779b97f4a7c15u >> 16; }

/* CPU seconds used so far by the calling thread, or by the whole process. */
static double cpu_now(clockid_t clock)
{
    struct timespec ts;
    clock_gettime(clock, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

typedef struct rate {
    uint64_t n;
    double seconds; /* wall */
    double cpu;     /* CPU seconds of the measuring thread (or process, for the sweep) */
} rate;

static double per_s(rate r) { return r.seconds > 0 ? (double)r.n / r.seconds : 0.0; }
static double per_cpu_s(rate r) { return r.cpu > 0 ? (double)r.n / r.cpu : 0.0; }

/* One line of the table: what, M per wall second, M per CPU second, and a note. */
static void row(const char *what, rate r, const char *unit, const char *note)
{
    printf("%-50s %9.2f %9.2f  M %s/s%s\n", what, per_s(r) * 1e-6, per_cpu_s(r) * 1e-6, unit, note);
    fflush(stdout);
}

/* np_classic_eval, one input at a time. */
static rate bench_model_plain(const np_classic_cfg *cfg, double secs)
{
    rate r = { 0, 0, 0 };
    uint64_t acc = 0;
    double t0 = np_now(), c0 = cpu_now(CLOCK_THREAD_CPUTIME_ID);
    do {
        for (unsigned k = 0; k < 65536; k++, r.n++) {
            uint64_t in = next_input(r.n);
            acc += (uint32_t)np_classic_eval(cfg, (uint16_t)in, (uint16_t)(in >> 16),
                                             (uint16_t)(in >> 32));
        }
        r.seconds = np_now() - t0;
        r.cpu = cpu_now(CLOCK_THREAD_CPUTIME_ID) - c0;
    } while (r.seconds < secs);
    sink = acc;
    return r;
}

/* np_ref_classic3_q88, one input at a time. */
static rate bench_ref_plain(double secs)
{
    rate r = { 0, 0, 0 };
    double acc = 0;
    double t0 = np_now(), c0 = cpu_now(CLOCK_THREAD_CPUTIME_ID);
    do {
        for (unsigned k = 0; k < 65536; k++, r.n++) {
            uint64_t in = next_input(r.n);
            acc += np_ref_classic3_q88((uint16_t)in, (uint16_t)(in >> 16), (uint16_t)(in >> 32));
        }
        r.seconds = np_now() - t0;
        r.cpu = cpu_now(CLOCK_THREAD_CPUTIME_ID) - c0;
    } while (r.seconds < secs);
    sink = (uint64_t)acc;
    return r;
}

/* Through the registry: unit->eval (what 0) or unit->ref (what 1), one input at a time. */
static rate bench_unit(const np_unit *u, const void *cfg, int what, double secs)
{
    rate r = { 0, 0, 0 };
    np_unit_fields f;
    u->fields(cfg, &f);
    uint64_t in[NP_UNIT_MAX_FIELDS] = { 0 }, out[NP_UNIT_MAX_FIELDS], acc = 0;
    double ref[NP_UNIT_MAX_FIELDS], facc = 0.0;
    double t0 = np_now(), c0 = cpu_now(CLOCK_THREAD_CPUTIME_ID);
    do {
        for (unsigned k = 0; k < 16384; k++, r.n++) {
            uint64_t v = next_input(r.n);
            for (unsigned i = 0; i < f.n_in; i++) /* 16-bit fields: x, y, z from one word */
                in[i] = (v >> (16u * i)) & ((f.in[i].bits < 64 ? ((uint64_t)1 << f.in[i].bits) : 0u) - 1u);
            if (what == 0) {
                u->eval(cfg, in, out);
                acc += out[0];
            } else {
                u->ref(cfg, in, ref);
                facc += ref[0];
            }
        }
        r.seconds = np_now() - t0;
        r.cpu = cpu_now(CLOCK_THREAD_CPUTIME_ID) - c0;
    } while (r.seconds < secs);
    sink = acc + (uint64_t)facc;
    return r;
}

/* Every unit and variant side by side, plain per-input evaluation through the registry. */
static int bench_units(double secs)
{
    static const struct { const char *unit, *spec, *label; } v[] = {
        { "classic3", NULL, "classic3" },
        { "simplex3", "deriv=1", "simplex3 value + derivatives" },
        { "simplex3", "deriv=0", "simplex3 value only" },
    };
    printf("\nunits side by side: plain per-input evaluation through the registry, one thread\n");
    printf("%-50s %9s %9s\n", "", "wall", "CPU");
    for (unsigned i = 0; i < sizeof v / sizeof v[0]; i++) {
        const np_unit *u = np_unit_find(v[i].unit);
        np_unit_cfg cfg;
        char err[256], what[128], text[256];
        if (!u)
            continue;
        if (np_unit_configure(u, &cfg, v[i].spec, err, sizeof err) != 0) {
            np_err("bench", "%s: %s", v[i].unit, err);
            return NP_EXIT_USAGE;
        }
        np_unit_cfg_format(u, &cfg, text, sizeof text);
        printf("  %s: %s\n", v[i].label, text);
        snprintf(what, sizeof what, "%s, bit-exact model", v[i].label);
        row(what, bench_unit(u, &cfg, 0, secs), "evaluations", "");
        if (i != 2) { /* the reference computes value and derivatives together */
            snprintf(what, sizeof what, "%s, float reference", v[i].unit);
            row(what, bench_unit(u, &cfg, 1, secs), "evaluations", "");
        }
    }
    return NP_EXIT_OK;
}

/* The unit's sweep kernel, NP_SWEEP_ROWS rows of one x cell per call, walking a slice. */
static rate bench_kernel(const np_unit *u, const void *cfg, unsigned what, double secs)
{
    rate r = { 0, 0, 0 };
    size_t n = (size_t)NP_SWEEP_ROWS * NP_SWEEP_ROW;
    int32_t *code = malloc(n * sizeof *code);
    double *ref = malloc(n * sizeof *ref);
    if (!code || !ref) {
        free(code);
        free(ref);
        return r;
    }
    uint64_t acc = 0;
    uint32_t call = 0;
    double t0 = np_now(), c0 = cpu_now(CLOCK_THREAD_CPUTIME_ID);
    do {
        for (unsigned k = 0; k < 64; k++, call++) {
            uint16_t x0 = (uint16_t)(call % 256u * 256u), y0 = (uint16_t)(call / 256u * NP_SWEEP_ROWS);
            u->sweep_rows(cfg, x0, y0, 0x0080, NP_SWEEP_ROWS, what, code, ref);
            acc += (uint32_t)code[call % n] + (uint64_t)(ref[call % n] > 0);
            r.n += n;
        }
        r.seconds = np_now() - t0;
        r.cpu = cpu_now(CLOCK_THREAD_CPUTIME_ID) - c0;
    } while (r.seconds < secs);
    sink = acc;
    free(code);
    free(ref);
    return r;
}

/* The cycle-accurate model at full throughput: an input every clock, output always ready. */
static rate bench_pipe(const np_unit *u, const void *cfg, double secs)
{
    rate r = { 0, 0, 0 };
    np_pipe p;
    if (u->pipe_init(&p, cfg) != 0)
        return r;
    unsigned char sig[1024];
    if (p.sig_size > sizeof sig) {
        np_pipe_free(&p);
        return r;
    }
    np_pipe_port port;
    memset(&port, 0, sizeof port);
    port.in_valid = 1;
    port.out_ready = 1;
    port.in_sig = sig;
    uint64_t acc = 0;
    double t0 = np_now(), c0 = cpu_now(CLOCK_THREAD_CPUTIME_ID);
    do {
        for (unsigned k = 0; k < 4096; k++, r.n++) {
            uint64_t v = next_input(r.n), in[NP_UNIT_MAX_FIELDS] = { v & 0xffff, v >> 16 & 0xffff,
                                                                     v >> 32 & 0xffff };
            u->sig_set_in(sig, in);
            np_pipe_eval(&p, &port);
            if (port.out_valid) {
                uint64_t out[NP_UNIT_MAX_FIELDS];
                u->sig_get_out(cfg, port.out_sig, out);
                acc += out[0];
            }
            np_pipe_clock(&p, &port);
        }
        r.seconds = np_now() - t0;
        r.cpu = cpu_now(CLOCK_THREAD_CPUTIME_ID) - c0;
    } while (r.seconds < secs);
    sink = acc + p.stats.delivered;
    np_pipe_free(&p);
    return r;
}

int np_cmd_bench(int argc, char **argv)
{
    double secs = 1.0;
    for (int k = 1; k < argc; k++) {
        if (strcmp(argv[k], "--help") == 0 || strcmp(argv[k], "-h") == 0) {
            fputs(usage_text, stdout);
            return NP_EXIT_OK;
        } else if (strcmp(argv[k], "--seconds") == 0 && k + 1 < argc) {
            char *end;
            secs = strtod(argv[++k], &end);
            if (*end != '\0' || !(secs >= 0.05 && secs <= 60.0)) {
                np_err("bench", "--seconds %s: expected 0.05..60", argv[k]);
                return NP_EXIT_USAGE;
            }
        } else {
            np_err("bench", "unknown option '%s' (see --help)", argv[k]);
            return NP_EXIT_USAGE;
        }
    }
    const np_unit *u = np_unit_find("classic3");
    np_unit_cfg cfg;
    char err[512], cfgtext[256];
    if (!u || np_unit_configure(u, &cfg, NULL, err, sizeof err) != 0) {
        np_err("bench", "unit classic3 unavailable");
        return NP_EXIT_USAGE;
    }
    const np_classic_cfg ccfg = np_classic_cfg_default(8);
    np_unit_cfg_format(u, &cfg, cfgtext, sizeof cfgtext);
    printf("bench of unit classic3 (%s), about %.2f s per figure, one thread unless stated\n",
           cfgtext, secs);
    printf("%-50s %9s %9s\n", "", "wall", "CPU");
    fflush(stdout);

    rate model = bench_model_plain(&ccfg, secs);
    row("bit-exact model, np_classic_eval per input", model, "evaluations", "");
    rate ref = bench_ref_plain(secs);
    row("float reference, np_ref_classic3_q88 per input", ref, "evaluations", "");
    if (u->sweep_rows) {
        char note[64];
        rate km = bench_kernel(u, &cfg, NP_SWEEP_MODEL, secs);
        snprintf(note, sizeof note, " (%.0fx plain)", per_cpu_s(model) > 0 ? per_cpu_s(km) / per_cpu_s(model) : 0.0);
        row("bit-exact model, sweep kernel (hoisted per cell)", km, "evaluations", note);
        rate kr = bench_kernel(u, &cfg, NP_SWEEP_REF, secs);
        snprintf(note, sizeof note, " (%.0fx plain)", per_cpu_s(ref) > 0 ? per_cpu_s(kr) / per_cpu_s(ref) : 0.0);
        row("float reference, sweep kernel (hoisted per row)", kr, "evaluations", note);
        row("model + reference, sweep kernel", bench_kernel(u, &cfg, NP_SWEEP_MODEL | NP_SWEEP_REF, secs),
            "inputs", "");
    }
    row("cycle-accurate model, np_pipe at 1 input/clock", bench_pipe(u, &cfg, secs), "cycles", "");

    /* The sweep itself: enough whole blocks for about secs on two threads. */
    np_sweep_opts o;
    memset(&o, 0, sizeof o);
    o.unit = u;
    o.cfg = &cfg;
    o.z = 0x0080;
    o.threads = 2;
    o.use_kernel = 1;
    unsigned blocks = (unsigned)(secs * 8.0 + 0.5);
    blocks = blocks < 2 ? 2 : blocks > NP_SWEEP_CELLS ? NP_SWEEP_CELLS : blocks & ~1u;
    o.x_first = 0;
    o.x_end = blocks;
    np_sweep_result r;
    double c0 = cpu_now(CLOCK_PROCESS_CPUTIME_ID);
    if (np_sweep_run(&o, &r, err, sizeof err) != 0) {
        np_err("bench", "sweep: %s", err);
        return NP_EXIT_USAGE;
    }
    rate sw = { r.computed, r.seconds, cpu_now(CLOCK_PROCESS_CPUTIME_ID) - c0 };
    char what[96];
    snprintf(what, sizeof what, "sweep, model + reference + statistics, %u threads", r.threads);
    row(what, sw, "inputs", "");
    printf("  (x cells 0..%u of z=0x%04x; the CPU figure is per CPU second, all threads together)\n",
           blocks - 1u, (unsigned)o.z);
    printf("projected full z slice (2^32 inputs): %.1f s at this run's load, %.1f s on %u idle cores\n",
           per_s(sw) > 0 ? 4294967296.0 / per_s(sw) : 0.0,
           per_cpu_s(sw) > 0 ? 4294967296.0 / per_cpu_s(sw) / r.threads : 0.0, r.threads);
    return bench_units(secs);
}
