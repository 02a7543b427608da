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
#include "np_common.h"
#include "np_cmd.h"
#include "np_ref.h"
#include "np_simplex.h"
#include "np_sweep.h"
#include "np_unit.h"

#include "np_bench_units.h"

static const char usage_text[] =
    "usage: noisepipe bench [--seconds S] [--unit U|all [--config K=V,...]]\n"
    "\n"
    "Measures, for the classic3 unit in its default configuration: the bit-exact model\n"
    "per input and through the sweep kernel, the float reference likewise, the\n"
    "cycle-accurate model, and the exhaustive sweep on two threads with the projected\n"
    "time of a full z slice (2^32 inputs); every unit's per-input, batch and kernel\n"
    "speeds beside stb_perlin_noise3; and the C cycle models beside the Verilated RTL\n"
    "on the same stimulus (when CTest has built the co-simulation; skipped with a line\n"
    "saying why otherwise). S: seconds per figure (default 1, 0.01..60).\n"
    "\n"
    "Then the table of every registered unit (default configuration, 65,536\n"
    "evaluations, S/4 per figure): per input, batch (np_unit_eval_n), sweep kernel,\n"
    "float reference per input and cycle model, each in M per CPU second and as a\n"
    "ratio to stb_perlin_noise3 measured in the same run. --unit U: only that table,\n"
    "only unit U, S per figure (all: every unit); --config: unit U's configuration.\n";

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

/* The unit's sweep kernel, NP_SWEEP_ROWS rows of one x cell per call, walking a slice. */
static rate bench_kernel(const np_unit *u, const void *cfg, unsigned what, double secs)
{
    rate r = { 0, 0, 0 };
    np_unit_fields f;
    u->fields(cfg, &f);
    size_t n = (size_t)NP_SWEEP_ROWS * NP_SWEEP_ROW; /* inputs per call */
    int32_t *code = malloc(n * f.n_out * sizeof *code); /* every output field */
    double *ref = malloc(n * f.n_out * sizeof *ref);
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

/*
 * The units side by side on the same inputs (issue 13): stb_perlin_noise3
 * (float, from Debian's libstb-dev) as the yardstick, then each model per
 * input, through its batch API, and the float references, each as a ratio to
 * stb per CPU second.
 */
#if defined(__has_include)
#if __has_include(<stb/stb_perlin.h>)
#define NP_HAVE_STB 1
#endif
#endif
#ifdef NP_HAVE_STB
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wsign-conversion"
#pragma GCC diagnostic ignored "-Wdouble-promotion"
#pragma GCC diagnostic ignored "-Wmissing-prototypes"
#pragma GCC diagnostic ignored "-Wstrict-prototypes"
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wfloat-conversion"
#define STB_PERLIN_IMPLEMENTATION
#include <stb/stb_perlin.h>
#pragma GCC diagnostic pop
#endif

enum { SIDE_N = 65536 }; /* inputs per pass; every figure runs whole passes */

typedef struct side_in {
    uint16_t x[SIDE_N], y[SIDE_N], z[SIDE_N];
    float fx[SIDE_N], fy[SIDE_N], fz[SIDE_N]; /* the same points as floats, word / 256 */
    int32_t code[SIDE_N];
    np_simplex_out sout[SIDE_N];
    np_classic_cfg cc;
    np_simplex_cfg sd, sf;
    unsigned spath; /* side_simplex_d_path's np_simplex_eval_n_path path */
} side_in;

typedef uint64_t (*side_fn)(side_in *in);

static uint64_t side_stb(side_in *in)
{
    float acc = 0.0f;
#ifdef NP_HAVE_STB
    for (unsigned n = 0; n < SIDE_N; n++)
        acc += stb_perlin_noise3(in->fx[n], in->fy[n], in->fz[n], 0, 0, 0);
#else
    (void)in;
#endif
    return (uint64_t)(acc != 0.0f);
}
static uint64_t side_classic_one(side_in *in)
{
    uint64_t acc = 0;
    for (unsigned n = 0; n < SIDE_N; n++)
        acc += (uint32_t)np_classic_eval(&in->cc, in->x[n], in->y[n], in->z[n]);
    return acc;
}
static uint64_t side_classic_n(side_in *in)
{
    np_classic_eval_n(&in->cc, in->x, in->y, in->z, in->code, SIDE_N);
    return (uint32_t)in->code[SIDE_N / 2];
}
static uint64_t side_classic_ref(side_in *in)
{
    double acc = 0.0;
    for (unsigned n = 0; n < SIDE_N; n++)
        acc += np_ref_classic3_q88(in->x[n], in->y[n], in->z[n]);
    return (uint64_t)(acc != 0.0);
}
static uint64_t simplex_one(side_in *in, const np_simplex_cfg *c)
{
    uint64_t acc = 0;
    for (unsigned n = 0; n < SIDE_N; n++) {
        np_simplex_out o;
        np_simplex_eval(c, in->x[n], in->y[n], in->z[n], &o);
        acc += (uint32_t)(o.f + o.df[0]);
    }
    return acc;
}
static uint64_t side_simplex_d_one(side_in *in) { return simplex_one(in, &in->sd); }
static uint64_t side_simplex_f_one(side_in *in) { return simplex_one(in, &in->sf); }
static uint64_t side_simplex_d_n(side_in *in)
{
    np_simplex_eval_n(&in->sd, in->x, in->y, in->z, in->sout, SIDE_N);
    return (uint32_t)in->sout[SIDE_N / 2].f;
}
static uint64_t side_simplex_d_path(side_in *in)
{
    np_simplex_eval_n_path(in->spath, &in->sd, in->x, in->y, in->z, in->sout, SIDE_N);
    return (uint32_t)in->sout[SIDE_N / 2].f;
}
static uint64_t side_simplex_f_n(side_in *in)
{
    np_simplex_eval_n(&in->sf, in->x, in->y, in->z, in->sout, SIDE_N);
    return (uint32_t)in->sout[SIDE_N / 2].f;
}
static uint64_t side_simplex_ref(side_in *in)
{
    double acc = 0.0, g[3];
    for (unsigned n = 0; n < SIDE_N; n++)
        acc += np_ref_simplex3_q88(in->x[n], in->y[n], in->z[n], g) + g[0];
    return (uint64_t)(acc != 0.0);
}

/* Whole passes of fn over the inputs for about secs. */
static rate side_run(side_fn fn, side_in *in, double secs)
{
    rate r = { 0, 0, 0 };
    uint64_t acc = 0;
    double t0 = np_now(), c0 = cpu_now(CLOCK_THREAD_CPUTIME_ID);
    do {
        acc += fn(in);
        r.n += SIDE_N;
        r.seconds = np_now() - t0;
        r.cpu = cpu_now(CLOCK_THREAD_CPUTIME_ID) - c0;
    } while (r.seconds < secs);
    sink = acc;
    return r;
}

/* One line with the ratio to stb per CPU second. */
static void side_row(const char *what, rate r, rate stb)
{
    char note[64] = "";
    if (per_cpu_s(stb) > 0)
        snprintf(note, sizeof note, "  %6.2fx stb", per_cpu_s(r) / per_cpu_s(stb));
    row(what, r, "evaluations", note);
}

static int bench_units(double secs, const np_unit *classic)
{
    side_in *in = malloc(sizeof *in);
    if (!in) {
        np_err("bench", "out of memory");
        return NP_EXIT_USAGE;
    }
    for (unsigned n = 0; n < SIDE_N; n++) { /* the same walk over cells and fractions as above */
        uint64_t v = next_input(n);
        in->x[n] = (uint16_t)v;
        in->y[n] = (uint16_t)(v >> 16);
        in->z[n] = (uint16_t)(v >> 32);
        in->fx[n] = (float)in->x[n] / 256.0f;
        in->fy[n] = (float)in->y[n] / 256.0f;
        in->fz[n] = (float)in->z[n] / 256.0f;
    }
    in->cc = np_classic_cfg_default(8);
    in->sd = np_simplex_cfg_default(16, 16, 1);
    in->sf = np_simplex_cfg_default(16, 16, 0);
    printf("\nunits side by side on the same %u inputs (8.8 words; stb gets word / 256 as float), one thread,\n"
           "default configurations; ratios are per CPU second\n", (unsigned)SIDE_N);
    printf("%-50s %9s %9s\n", "", "wall", "CPU");
#ifdef NP_HAVE_STB
    rate stb = side_run(side_stb, in, secs);
    row("stb_perlin_noise3 (float, libstb-dev)", stb, "evaluations", "   1.00x stb");
#else
    rate stb = { 0, 0, 0 };
    printf("stb_perlin_noise3: not built (no <stb/stb_perlin.h>; Debian libstb-dev)\n");
#endif
    rate c1 = side_run(side_classic_one, in, secs);
    side_row("classic3 bit-exact, np_classic_eval per input", c1, stb);
    rate cn = side_run(side_classic_n, in, secs);
    side_row("classic3 bit-exact, np_classic_eval_n batch", cn, stb);
    if (classic->sweep_rows) {
        np_unit_cfg cfg;
        char err[256];
        if (np_unit_configure(classic, &cfg, NULL, err, sizeof err) == 0)
            side_row("classic3 bit-exact, sweep kernel (rows of a cell)",
                     bench_kernel(classic, &cfg, NP_SWEEP_MODEL, secs), stb);
    }
    side_row("classic3 float reference per input", side_run(side_classic_ref, in, secs), stb);
    side_row("simplex3 + derivatives, np_simplex_eval per input", side_run(side_simplex_d_one, in, secs), stb);
    side_row("simplex3 + derivatives, np_simplex_eval_n batch", side_run(side_simplex_d_n, in, secs), stb);
    /* Each specialised path that applies on this CPU (np_simplex_eval_n runs the last of them that applies). */
    static const struct { unsigned path; const char *what; } sp[] = {
        { NP_SIMPLEX_BATCH_WIDTHS, "simplex3 + derivatives, batch path widths" },
        { NP_SIMPLEX_BATCH_AVX2, "simplex3 + derivatives, batch path avx2" },
        { NP_SIMPLEX_BATCH_AVX512, "simplex3 + derivatives, batch path avx512" },
    };
    for (unsigned k = 0; k < sizeof sp / sizeof sp[0]; k++) {
        in->spath = sp[k].path;
        if (np_simplex_eval_n_path(sp[k].path, &in->sd, in->x, in->y, in->z, in->sout, 16) == 0)
            side_row(sp[k].what, side_run(side_simplex_d_path, in, secs), stb);
        else
            printf("%-50s does not apply on this CPU\n", sp[k].what);
    }
    side_row("simplex3 value only, np_simplex_eval per input", side_run(side_simplex_f_one, in, secs), stb);
    side_row("simplex3 value only, np_simplex_eval_n batch", side_run(side_simplex_f_n, in, secs), stb);
    const np_unit *su = np_unit_find("simplex3");
    if (su && su->sweep_rows) {
        np_unit_cfg cfg;
        char err[256];
        if (np_unit_configure(su, &cfg, NULL, err, sizeof err) == 0)
        {
            side_row("simplex3 + derivatives, sweep kernel (rows)", bench_kernel(su, &cfg, NP_SWEEP_MODEL, secs),
                     stb);
            side_row("simplex3 float reference, sweep kernel (rows)", bench_kernel(su, &cfg, NP_SWEEP_REF, secs),
                     stb);
        }
    }
    side_row("simplex3 float reference (value + gradient)", side_run(side_simplex_ref, in, secs), stb);
    printf("  targets (issue 13, not asserted): classic3 batch >= 1x stb; simplex3 batch with derivatives >= 0.75x\n");
    free(in);
    return NP_EXIT_OK;
}

/* The cycle-accurate model at full throughput: an input every clock, output always ready. */
static rate bench_pipe(const np_unit *u, const void *cfg, int copy_banks, double secs)
{
    rate r = { 0, 0, 0 };
    np_pipe p;
    if (u->pipe_init(&p, cfg) != 0)
        return r;
    p.copy_banks = copy_banks;
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

/*
 * The C cycle model against the Verilated RTL on the same stimulus (issue
 * 12): the co-simulation binary that CTest builds (testbench/rtl.cmake,
 * rtl.<unit>.cosim.build.default) runs its lock-step comparison and then,
 * with --bench, the same stimulus (same seed, bubbles and stalls) through
 * each model alone; its figures are printed here. The Verilated model is a
 * C++ build, so noisepipe runs that program instead of linking it.
 * NOISEPIPE_COSIM_DIR overrides where the binaries are looked for.
 */
#ifndef NP_COSIM_DIR
#define NP_COSIM_DIR ""
#endif
#ifndef NP_HAVE_VERILATOR
#define NP_HAVE_VERILATOR 0
#endif

static void bench_verilated(double secs)
{
    static const struct {
        const char *unit, *cfg;
    } v[] = { { "classic3", "8,12,11" }, { "simplex3", "16,16,1,24,22,22" } };
    const char *dir = getenv("NOISEPIPE_COSIM_DIR");
    if (!dir || !*dir)
        dir = NP_COSIM_DIR;
    printf("\nC cycle model against the Verilated RTL, same stimulus with bubbles and stalls (cosim --bench)\n");
    for (unsigned k = 0; k < sizeof v / sizeof v[0]; k++) {
        char path[1024], cmd[1400], line[1024];
        snprintf(path, sizeof path, "%s/%s/cosim-default/cosim", dir, v[k].unit);
        FILE *f = *dir ? fopen(path, "rb") : NULL;
        if (!f) {
            if (!NP_HAVE_VERILATOR && !getenv("NOISEPIPE_COSIM_DIR"))
                printf("  %s: skipped: verilator was not found when noisepipe was configured (Debian package verilator)\n",
                       v[k].unit);
            else
                printf("  %s: skipped: no co-simulation binary %s (ctest -R 'rtl\\.%s\\.cosim\\.build\\.default' "
                       "builds it)\n", v[k].unit, *dir ? path : "(no build directory known)", v[k].unit);
            continue;
        }
        fclose(f);
        unsigned long cycles = (unsigned long)(secs * 500000.0);
        cycles = cycles < 20000ul ? 20000ul : cycles;
        snprintf(cmd, sizeof cmd, "'%s' --unit %s --cfg %s --cycles %lu --bench 2>&1", path, v[k].unit, v[k].cfg,
                 cycles);
        fflush(stdout);
        FILE *pp = popen(cmd, "r");
        double c = 0, r = 0;
        int mism = 0;
        while (pp && fgets(line, sizeof line, pp)) {
            const char *a = strstr(line, "C cycle model "), *b = strstr(line, "Verilated RTL ");
            if (strncmp(line, "bench ", 6) == 0 && a && b) {
                c = strtod(a + strlen("C cycle model "), NULL);
                r = strtod(b + strlen("Verilated RTL "), NULL);
            }
            if (strstr(line, " mismatch") && !strstr(line, " 0 mismatches"))
                mism = 1;
        }
        int rc = pp ? pclose(pp) : -1;
        if (rc != 0 || mism || !(c > 0) || !(r > 0)) {
            printf("  %s: the co-simulation failed (exit status %d): run %s --unit %s --cfg %s --bench\n", v[k].unit,
                   rc, path, v[k].unit, v[k].cfg);
            continue;
        }
        printf("  %-8s %lu cycles: C cycle model %6.2f M cycles/s, Verilated RTL %6.2f M cycles/s: %.2fx (wall)\n",
               v[k].unit, cycles, c / 1e6, r / 1e6, c / r);
    }
    printf("  target (issue 13, not asserted): the C cycle model >= 5x the Verilated RTL\n");
}

int np_cmd_bench(int argc, char **argv)
{
    double secs = 1.0;
    const char *only = NULL, *spec = NULL; /* --unit: only the table of every unit; --config: U's configuration */
    for (int k = 1; k < argc; k++) {
        if (strcmp(argv[k], "--help") == 0 || strcmp(argv[k], "-h") == 0) {
            fputs(usage_text, stdout);
            return NP_EXIT_OK;
        } else if (strcmp(argv[k], "--seconds") == 0 && k + 1 < argc) {
            char *end;
            secs = strtod(argv[++k], &end);
            if (*end != '\0' || !(secs >= 0.01 && secs <= 60.0)) {
                np_err("bench", "--seconds %s: expected 0.01..60", argv[k]);
                return NP_EXIT_USAGE;
            }
        } else if (strcmp(argv[k], "--unit") == 0 && k + 1 < argc) {
            only = argv[++k];
        } else if (strcmp(argv[k], "--config") == 0 && k + 1 < argc) {
            spec = argv[++k];
        } else {
            np_err("bench", "unknown option '%s' (see --help)", argv[k]);
            return NP_EXIT_USAGE;
        }
    }
    if (spec && (!only || strcmp(only, "all") == 0)) {
        np_err("bench", "--config needs --unit U (one unit)");
        return NP_EXIT_USAGE;
    }
    if (only)
        return np_bench_units(secs, strcmp(only, "all") == 0 ? NULL : only, spec);
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
    rate pipe_copy = bench_pipe(u, &cfg, 1, secs);
    row("cycle-accurate model, copying bundles (former)", pipe_copy, "cycles", "");
    rate pipe_rot = bench_pipe(u, &cfg, 0, secs);
    char pnote[64];
    snprintf(pnote, sizeof pnote, " (%.2fx copying)", per_cpu_s(pipe_copy) > 0 ? per_cpu_s(pipe_rot) / per_cpu_s(pipe_copy) : 0.0);
    row("cycle-accurate model, np_pipe at 1 input/clock", pipe_rot, "cycles", pnote);

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
    int rc = bench_units(secs, u);
    bench_verilated(secs);
    int rc_all = np_bench_units(secs / 4.0, NULL, NULL);
    return rc != NP_EXIT_OK ? rc : rc_all;
}
