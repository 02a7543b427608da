/* SPDX-License-Identifier: MIT */
/*
 * test_sweep - the exhaustive sweep (np_sweep.h) and the classic unit's
 * accuracy over random inputs:
 *   - the sweep kernel gives the bits of np_classic_eval and the doubles of
 *     np_ref_classic3_q88 (one whole x cell exhaustively, random cells in
 *     many configurations);
 *   - max error <= 1 LSB over 10^7 seeded random inputs;
 *   - the statistics do not depend on the thread count, nor on a journal
 *     being resumed (a partial range, and a real kill -9 of the command);
 *   - a journal for another slice or configuration is refused;
 *   - a deliberately cheap configuration fails (so the check can fail).
 */
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "np_classic.h"
#include "np_ref.h"
#include "np_rng.h"
#include "np_sweep.h"
#include "np_test.h"
#include "np_unit.h"

static const np_unit *classic3(void)
{
    const np_unit *u = np_unit_find("classic3");
    if (!u) {
        fprintf(stderr, "unit classic3 missing\n");
        exit(2);
    }
    return u;
}

static const char *cfg_name(const char *spec) { return spec ? spec : "default"; }

static void configure(const np_unit *u, np_unit_cfg *cfg, const char *spec)
{
    char err[256];
    if (np_unit_configure(u, cfg, spec, err, sizeof err) != 0) {
        fprintf(stderr, "config '%s': %s\n", cfg_name(spec), err);
        exit(2);
    }
}

/* The registry's classic configuration block starts with the model's np_classic_cfg. */
static const np_classic_cfg *model_cfg(const np_unit_cfg *cfg)
{
    return (const np_classic_cfg *)(const void *)cfg;
}

static int same_bits(double a, double b) { return memcmp(&a, &b, sizeof a) == 0; }

/* Buffers for one kernel call. */
enum { N_CALL = NP_SWEEP_ROWS * NP_SWEEP_ROW };
static int32_t code_k[N_CALL], code_g[N_CALL];
static double ref_k[N_CALL], ref_g[N_CALL];

/* ---------------------------------------------------------------- kernel == plain */

/* Every input of x cell 0xff, z = 0xff80 (both wrap to cell 0): model bits. */
static int t_kernel_model_cell(void)
{
    const np_unit *u = classic3();
    np_unit_cfg cfg;
    configure(u, &cfg, NULL);
    const uint16_t x0 = 0xff00, z = 0xff80;
    uint64_t bad = 0, n = 0;
    for (unsigned y0 = 0; y0 < 65536u; y0 += NP_SWEEP_ROWS) {
        u->sweep_rows(&cfg, x0, (uint16_t)y0, z, NP_SWEEP_ROWS, NP_SWEEP_MODEL, code_k, ref_k);
        for (unsigned r = 0; r < NP_SWEEP_ROWS; r++)
            for (unsigned t = 0; t < NP_SWEEP_ROW; t++, n++) {
                int32_t want = np_classic_eval(model_cfg(&cfg), (uint16_t)(x0 + t),
                                               (uint16_t)(y0 + r), z);
                int32_t got = code_k[r * NP_SWEEP_ROW + t];
                if (got != want && bad++ < 5)
                    NP_CHECK(got == want, "x=0x%04x y=0x%04x z=0x%04x => kernel %d, np_classic_eval %d",
                             x0 + t, y0 + r, z, got, want);
            }
    }
    printf("x cell 0xff, z=0xff80: %llu inputs, %llu kernel outputs differ from np_classic_eval\n",
           (unsigned long long)n, (unsigned long long)bad);
    NP_CHECK(bad == 0 && n == NP_SWEEP_BLOCK_INPUTS, "%llu differences", (unsigned long long)bad);
    return 0;
}

/* Every input of x cell 0xff, z = 0xff00 (wrapping, w = 0): reference doubles, bit for bit. */
static int t_kernel_ref_cell(void)
{
    const np_unit *u = classic3();
    np_unit_cfg cfg;
    configure(u, &cfg, NULL);
    const uint16_t x0 = 0xff00, z = 0xff00;
    uint64_t bad = 0, n = 0, negzero = 0;
    for (unsigned y0 = 0; y0 < 65536u; y0 += NP_SWEEP_ROWS) {
        u->sweep_rows(&cfg, x0, (uint16_t)y0, z, NP_SWEEP_ROWS, NP_SWEEP_REF, code_k, ref_k);
        for (unsigned r = 0; r < NP_SWEEP_ROWS; r++)
            for (unsigned t = 0; t < NP_SWEEP_ROW; t++, n++) {
                double want = np_ref_classic3_q88((uint16_t)(x0 + t), (uint16_t)(y0 + r), z);
                double got = ref_k[r * NP_SWEEP_ROW + t];
                negzero += want == 0.0 && signbit(want);
                if (!same_bits(got, want) && bad++ < 5)
                    NP_CHECK(same_bits(got, want), "x=0x%04x y=0x%04x z=0x%04x => kernel %a, ref %a",
                             x0 + t, y0 + r, z, got, want);
            }
    }
    printf("x cell 0xff, z=0xff00: %llu inputs, %llu kernel references differ in any bit from "
           "np_ref_classic3_q88 (%llu of them are -0.0)\n",
           (unsigned long long)n, (unsigned long long)bad, (unsigned long long)negzero);
    NP_CHECK(bad == 0 && n == NP_SWEEP_BLOCK_INPUTS, "%llu differences", (unsigned long long)bad);

    return 0;
}

/*
 * Every lattice cell (i, j) of the slices z = 0x0000 and 0xff00 (w = 0): the
 * fractions 0, 1/256, 1/2 and 255/256 of each row. The reference returns
 * -0.0 only at lattice points (u = v = w = 0), for some gradients: this is
 * where the kernel's signed-zero argument is put to the test.
 */
static int t_kernel_lattice(void)
{
    static const unsigned ts[] = { 0x00, 0x01, 0x80, 0xff };
    const np_unit *u = classic3();
    np_unit_cfg cfg;
    configure(u, &cfg, NULL);
    uint64_t n = 0, bad = 0, negzero = 0;
    for (unsigned z = 0x0000; z <= 0xff00; z += 0xff00)
        for (unsigned cell = 0; cell < 65536u; cell++) {
            uint16_t x0 = (uint16_t)(cell << 8), y0 = (uint16_t)(cell & 0xff00);
            u->sweep_rows(&cfg, x0, y0, (uint16_t)z, 1, NP_SWEEP_MODEL | NP_SWEEP_REF, code_k, ref_k);
            for (unsigned k = 0; k < sizeof ts / sizeof ts[0]; k++, n++) {
                uint16_t x = (uint16_t)(x0 + ts[k]);
                int32_t want = np_classic_eval(model_cfg(&cfg), x, y0, (uint16_t)z);
                double wref = np_ref_classic3_q88(x, y0, (uint16_t)z);
                negzero += wref == 0.0 && signbit(wref);
                if ((code_k[ts[k]] != want || !same_bits(ref_k[ts[k]], wref)) && bad++ < 5)
                    NP_CHECK(0, "x=0x%04x y=0x%04x z=0x%04x => kernel %d %a, plain %d %a", x, y0, z,
                             code_k[ts[k]], ref_k[ts[k]], want, wref);
            }
        }
    printf("%llu inputs on the lattice planes of z=0x0000 and 0xff00: %llu differ from "
           "np_classic_eval/np_ref_classic3_q88 (%llu references are -0.0)\n",
           (unsigned long long)n, (unsigned long long)bad, (unsigned long long)negzero);
    NP_CHECK(bad == 0, "%llu differences", (unsigned long long)bad);
    NP_CHECK(negzero > 0, "no -0.0 reference met: the signed-zero path went untested");
    return 0;
}

/*
 * Random kernel calls in many configurations (both of the kernel's model
 * paths: the one specialised for the default widths and the general one),
 * against np_sweep_rows_generic, i.e. u->eval and u->ref per input. Slices
 * and rows with a zero fraction are drawn often: that is where signed zeros
 * appear in the reference.
 */
static int t_kernel_random(void)
{
    static const char *const configs[] = {
        NULL,                                 /* default: the specialised path */
        "s_frac=4,lerp_frac=6",               /* cheap */
        "out_bits=16",                        /* wide output */
        "out_bits=16,s_frac=24,lerp_frac=30", /* exact s-curve, widest interpolators */
        "s_frac=1,lerp_frac=30",              /* interpolator widens (shift left) */
        "out_bits=2",                         /* narrowest */
        "out_bits=8,s_frac=24,lerp_frac=6",   /* no interpolator fraction beyond the output */
    };
    const np_unit *u = classic3();
    np_rng rng;
    np_rng_seed(&rng, 0x5eed5eedu);
    uint64_t calls = 0, bad = 0, negzero = 0;
    for (unsigned c = 0; c < sizeof configs / sizeof configs[0]; c++) {
        np_unit_cfg cfg;
        configure(u, &cfg, configs[c]);
        for (unsigned k = 0; k < 200; k++, calls++) {
            uint16_t x0 = (uint16_t)(np_rng_below(&rng, 256) << 8);
            uint16_t y0 = (uint16_t)(np_rng_below(&rng, 65536 / NP_SWEEP_ROWS) * NP_SWEEP_ROWS);
            uint16_t z = (uint16_t)np_rng_below(&rng, 65536);
            if (k % 4 == 0)
                z &= 0xff00; /* w = 0 */
            if (k % 3 == 0)
                y0 &= 0xff00; /* a row with v = 0 */
            if (k == 1)
                x0 = 0xff00, y0 = 0xff00 + 256 - NP_SWEEP_ROWS, z = 0xffff; /* all wrap */
            u->sweep_rows(&cfg, x0, y0, z, NP_SWEEP_ROWS, NP_SWEEP_MODEL | NP_SWEEP_REF, code_k,
                          ref_k);
            np_sweep_rows_generic(u, &cfg, x0, y0, z, NP_SWEEP_ROWS, NP_SWEEP_MODEL | NP_SWEEP_REF,
                                  code_g, ref_g);
            for (unsigned i = 0; i < N_CALL; i++) {
                negzero += ref_g[i] == 0.0 && signbit(ref_g[i]);
                if ((code_k[i] != code_g[i] || !same_bits(ref_k[i], ref_g[i])) && bad++ < 5)
                    NP_CHECK(0, "config '%s' x=0x%04x y=0x%04x z=0x%04x => kernel %d %a, plain %d %a",
                             cfg_name(configs[c]), x0 + i % NP_SWEEP_ROW,
                             y0 + i / NP_SWEEP_ROW, z, code_k[i], ref_k[i], code_g[i], ref_g[i]);
            }
        }
    }
    printf("%llu random kernel calls (%llu inputs) in %zu configurations: %llu differ from "
           "eval/ref per input (%llu references are -0.0)\n",
           (unsigned long long)calls, (unsigned long long)calls * N_CALL,
           sizeof configs / sizeof configs[0], (unsigned long long)bad, (unsigned long long)negzero);
    NP_CHECK(bad == 0, "%llu differences", (unsigned long long)bad);
    return 0;
}

/* ---------------------------------------------------------------- random accuracy */

/*
 * One coordinate: uniform, or (one time in four) a boundary fraction
 * (0, 1/256, 1/2 - 1/256, 1/2, 1/2 + 1/256, 254/256, 255/256) in a random
 * cell or in the wrapping cells 0 and 255.
 */
static uint16_t weighted_coord(np_rng *r)
{
    static const uint8_t frac[] = { 0x00, 0x01, 0x7f, 0x80, 0x81, 0xfe, 0xff };
    if (np_rng_below(r, 4) != 0)
        return (uint16_t)np_rng_below(r, 65536);
    uint64_t cell = np_rng_below(r, 3) == 0 ? (np_rng_below(r, 2) ? 0xff : 0x00) : np_rng_below(r, 256);
    return (uint16_t)(cell << 8 | frac[np_rng_below(r, sizeof frac)]);
}

/* Max error, CR % over n seeded random inputs of one configuration; checks max <= 1 and <= bound. */
static void random_accuracy(const char *spec, uint64_t n, uint64_t seed)
{
    const np_unit *u = classic3();
    np_unit_cfg cfg;
    configure(u, &cfg, spec);
    const np_classic_cfg *mc = model_cfg(&cfg);
    double scale = 1.0;
    for (unsigned k = 0; k < np_classic_out_frac(mc); k++)
        scale *= 2.0;
    np_rng rng;
    np_rng_seed(&rng, seed);
    double max = -1.0, sum = 0.0;
    uint64_t cr = 0;
    uint16_t mx = 0, my = 0, mz = 0;
    for (uint64_t k = 0; k < n; k++) {
        uint16_t x = weighted_coord(&rng), y = weighted_coord(&rng), z = weighted_coord(&rng);
        unsigned char ok;
        double e = np_sweep_error(np_classic_eval(mc, x, y, z), np_ref_classic3_q88(x, y, z), scale, &ok);
        cr += ok;
        sum += e;
        if (e > max) {
            max = e;
            mx = x, my = y, mz = z;
        }
    }
    double bound = u->error_bound_lsb(&cfg);
    printf("config %-12s %9llu random inputs (seed %#llx): max error %.6f LSB at (0x%04x, 0x%04x, "
           "0x%04x), mean %.4f LSB, correctly rounded %.4f%%, bound %.4f LSB\n",
           cfg_name(spec), (unsigned long long)n, (unsigned long long)seed, max, mx, my, mz,
           sum / (double)n, 100.0 * (double)cr / (double)n, bound);
    NP_CHECK(max <= u->tolerance_lsb, "%s: max error %.6f LSB over the tolerance", cfg_name(spec), max);
    NP_CHECK(max <= bound, "%s: max error %.6f LSB over the guaranteed bound %.6f", cfg_name(spec),
             max, bound);
}

static int t_random_1e7(void)
{
    random_accuracy(NULL, 10000000u, 0x6e6f697365u);
    return 0;
}

static int t_random_widths(void)
{
    random_accuracy("out_bits=4", 1000000u, 4);
    random_accuracy("out_bits=12", 1000000u, 12);
    random_accuracy("out_bits=16", 1000000u, 16);
    return 0;
}

/* ---------------------------------------------------------------- the sweep */

static np_sweep_opts opts(const np_unit *u, const np_unit_cfg *cfg, uint16_t z, unsigned a,
                          unsigned b, unsigned threads)
{
    np_sweep_opts o;
    memset(&o, 0, sizeof o);
    o.unit = u;
    o.cfg = cfg;
    o.z = z;
    o.x_first = a;
    o.x_end = b;
    o.threads = threads;
    o.use_kernel = 1;
    return o;
}

static int run(const np_sweep_opts *o, np_sweep_result *r, char *err, size_t len)
{
    int rc = np_sweep_run(o, r, err, len);
    if (rc != 0)
        printf("np_sweep_run: %s\n", err);
    return rc;
}

static void print_stats(const char *what, const np_sweep_stats *s)
{
    printf("%-28s n=%llu max=%.6f at (0x%04x, 0x%04x) cr=%llu over=%llu sum=%a sum2=%a\n", what,
           (unsigned long long)s->n, s->max_err, s->max_x, s->max_y, (unsigned long long)s->cr,
           (unsigned long long)s->over, s->sum, s->sum2);
}

static int t_threads(void)
{
    const np_unit *u = classic3();
    np_unit_cfg cfg;
    configure(u, &cfg, NULL);
    char err[512];
    np_sweep_result r[4];
    static const unsigned nt[4] = { 1, 2, 3, 5 };
    for (unsigned k = 0; k < 4; k++) {
        np_sweep_opts o = opts(u, &cfg, 0x0040, 3, 8, nt[k]);
        NP_CHECK(run(&o, &r[k], err, sizeof err) == 0, "run");
        char what[32];
        snprintf(what, sizeof what, "5 blocks on %u thread%s", r[k].threads, nt[k] > 1 ? "s" : "");
        print_stats(what, &r[k].total);
        NP_CHECK(np_sweep_stats_equal(&r[0].total, &r[k].total), "%u threads differ from 1", nt[k]);
        NP_CHECK(r[k].total.n == 5 * NP_SWEEP_BLOCK_INPUTS, "n");
    }
    return 0;
}

static int t_kernel_vs_plain_stats(void)
{
    const np_unit *u = classic3();
    np_unit_cfg cfg;
    configure(u, &cfg, "s_frac=7,lerp_frac=8");
    np_sweep_stats a, b;
    NP_CHECK(np_sweep_block(u, &cfg, 0x0180, 0x17, 1, &a) == 0, "block");
    NP_CHECK(np_sweep_block(u, &cfg, 0x0180, 0x17, 0, &b) == 0, "block");
    print_stats("block 0x17, sweep kernel", &a);
    print_stats("block 0x17, eval/ref per input", &b);
    NP_CHECK(np_sweep_stats_equal(&a, &b), "the kernel's statistics differ from the plain path's");
    return 0;
}

/*
 * simplex3's block statistics pinned, every bit: x cell 0xff of z = 0xfff1
 * (the input words wrap), default configuration and deriv=0, through the
 * sweep kernel. The values are the kernel's before its int32 model row and
 * whole-block passes (issue 13; the same as the journal lines of
 * `noisepipe sweep --unit simplex3 --z 0xfff1 --x-cells 255:256` then), so a
 * faster kernel must leave every count, the maximum and where, the two sums
 * and the histogram unchanged.
 */
static int t_simplex3_pinned(void)
{
    static const struct {
        const char *config;
        uint64_t cr;
        double max_err;
        uint16_t max_x, max_y;
        double sum, sum2;
        uint64_t hist[5];
    } pins[] = {
        { NULL, 16345130, 0x1.12d1b13c26p-1, 0xff04, 0xc0e9, 0x1.99d0a3400ade8p+22, 0x1.55d284df9e01ep+21,
          { 66952, 984215, 4256669, 11037294, 432086 } },
        { "deriv=0", 16459498, 0x1.2c1bb36ce9p-1, 0xff18, 0x7457, 0x1.007a6f7e63338p+22, 0x1.5776c5a0b602cp+20,
          { 4197042, 4194501, 4193675, 3874280, 317718 } },
    };
    const np_unit *u = np_unit_find("simplex3");
    NP_CHECK(u != NULL && u->sweep_rows != NULL, "simplex3 with a sweep kernel");
    if (!u)
        return 0;
    for (unsigned k = 0; k < sizeof pins / sizeof pins[0]; k++) {
        np_unit_cfg cfg;
        configure(u, &cfg, pins[k].config);
        np_sweep_stats want, got;
        np_sweep_stats_init(&want);
        want.n = NP_SWEEP_BLOCK_INPUTS;
        want.cr = pins[k].cr;
        want.over = 0;
        want.max_err = pins[k].max_err;
        want.max_x = pins[k].max_x;
        want.max_y = pins[k].max_y;
        want.sum = pins[k].sum;
        want.sum2 = pins[k].sum2;
        memcpy(want.hist, pins[k].hist, sizeof pins[k].hist);
        NP_CHECK(np_sweep_block(u, &cfg, 0xfff1, 0xff, 1, &got) == 0, "block");
        print_stats(pins[k].config ? pins[k].config : "default", &got);
        NP_CHECK(np_sweep_stats_equal(&got, &want), "simplex3 %s: block statistics differ from the pinned ones",
                 cfg_name(pins[k].config));
    }
    return 0;
}

/* Count the complete block lines of a journal. */
static unsigned journal_blocks(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return 0;
    char line[2048];
    unsigned n = 0;
    while (fgets(line, sizeof line, f))
        n += strncmp(line, "block ", 6) == 0 && strchr(line, '\n') != NULL;
    fclose(f);
    return n;
}

static void append(const char *path, const char *text)
{
    FILE *f = fopen(path, "ab");
    if (f) {
        fputs(text, f);
        fclose(f);
    }
}

/* A partial range, a torn last line, then the whole range resumed == one uninterrupted run. */
static int t_journal_resume(void)
{
    const np_unit *u = classic3();
    np_unit_cfg cfg;
    configure(u, &cfg, NULL);
    const char *j = "sweep_resume.journal";
    char err[512];
    remove(j);
    np_sweep_result whole, part, rest, again;
    np_sweep_opts o = opts(u, &cfg, 0xff80, 250, 256, 2);
    NP_CHECK(run(&o, &whole, err, sizeof err) == 0, "uninterrupted run");
    print_stats("uninterrupted 250..255", &whole.total);

    np_sweep_opts p = opts(u, &cfg, 0xff80, 252, 254, 2);
    p.journal = j;
    NP_CHECK(run(&p, &part, err, sizeof err) == 0, "partial run");
    NP_CHECK(journal_blocks(j) == 2, "journal has %u blocks", journal_blocks(j));
    append(j, "block 250 n=16777216 cr=123"); /* what a kill during a write leaves */

    o.journal = j;
    o.resume = 1;
    NP_CHECK(run(&o, &rest, err, sizeof err) == 0, "resumed run");
    print_stats("resumed 250..255", &rest.total);
    NP_CHECK(rest.blocks_resumed == 2 && rest.computed == 4 * NP_SWEEP_BLOCK_INPUTS,
             "resumed %u blocks, computed %llu inputs", rest.blocks_resumed,
             (unsigned long long)rest.computed);
    NP_CHECK(np_sweep_stats_equal(&whole.total, &rest.total), "resumed statistics differ");

    NP_CHECK(run(&o, &again, err, sizeof err) == 0, "second resume");
    NP_CHECK(again.blocks_resumed == 6 && again.computed == 0, "nothing left to compute");
    NP_CHECK(np_sweep_stats_equal(&whole.total, &again.total), "statistics from the journal alone differ");
    NP_CHECK(journal_blocks(j) == 6, "journal has %u blocks", journal_blocks(j));
    remove(j);
    return 0;
}

/* A journal written for another slice, configuration or nothing at all is refused. */
static int t_journal_refuse(void)
{
    const np_unit *u = classic3();
    np_unit_cfg cfg, other;
    configure(u, &cfg, NULL);
    configure(u, &other, "s_frac=10");
    const char *j = "sweep_refuse.journal";
    char err[512];
    np_sweep_result r;
    remove(j);
    np_sweep_opts o = opts(u, &cfg, 0x0000, 0, 1, 1);
    o.journal = j;
    NP_CHECK(run(&o, &r, err, sizeof err) == 0, "first run");

    NP_CHECK(np_sweep_run(&o, &r, err, sizeof err) != 0, "an existing journal without resume");
    printf("existing journal, no resume: %s\n", err);
    o.resume = 1;
    o.z = 0x0001;
    NP_CHECK(np_sweep_run(&o, &r, err, sizeof err) != 0 && strstr(err, "z=0x0000"), "other z");
    printf("other z: %s\n", err);
    o.z = 0x0000;
    o.cfg = &other;
    NP_CHECK(np_sweep_run(&o, &r, err, sizeof err) != 0 && strstr(err, "s_frac=12"), "other config");
    printf("other config: %s\n", err);
    o.cfg = &cfg;
    append(j, "block 7 n=16777216 garbage check=00000000\n");
    NP_CHECK(np_sweep_run(&o, &r, err, sizeof err) != 0 && strstr(err, "malformed"), "corrupt line");
    printf("corrupt line: %s\n", err);
    remove(j);
    append(j, "something else\n");
    NP_CHECK(np_sweep_run(&o, &r, err, sizeof err) != 0, "not a journal");
    printf("not a journal: %s\n", err);
    remove(j);
    return 0;
}

static void sleep_ms(long ms)
{
    struct timespec ts = { ms / 1000, (ms % 1000) * 1000000L };
    nanosleep(&ts, NULL);
}

/*
 * `noisepipe sweep --journal` killed with SIGKILL after a few blocks, then
 * resumed: the same statistics as a run that was never interrupted.
 * NOISEPIPE names the command (set by sweep.cmake).
 */
static int t_kill_resume(void)
{
    const char *exe = getenv("NOISEPIPE");
    NP_CHECK(exe != NULL, "NOISEPIPE is not set");
    if (!exe)
        return 1;
    const char *j = "sweep_kill.journal";
    remove(j);
    pid_t pid = fork();
    if (pid == 0) {
        if (!freopen("/dev/null", "w", stdout))
            _exit(127);
        execl(exe, exe, "sweep", "--z", "0x1234", "--threads", "1", "--x-cells", "0:64",
              "--journal", j, (char *)NULL);
        _exit(127);
    }
    NP_CHECK(pid > 0, "fork");
    if (pid <= 0)
        return 1;
    unsigned seen = 0;
    int status, exited = 0;
    for (unsigned waited = 0; waited < 120000 && (seen = journal_blocks(j)) < 3; waited += 10) {
        if (waitpid(pid, &status, WNOHANG) == pid) {
            exited = 1;
            break;
        }
        sleep_ms(10);
    }
    if (!exited) {
        kill(pid, SIGKILL);
        waitpid(pid, &status, 0);
    }
    NP_CHECK(!exited && WIFSIGNALED(status), "the sweep ended before it was killed");
    printf("killed the sweep with %u blocks in its journal\n", journal_blocks(j));

    const np_unit *u = classic3();
    np_unit_cfg cfg;
    configure(u, &cfg, NULL);
    char err[512];
    np_sweep_result whole, resumed;
    np_sweep_opts o = opts(u, &cfg, 0x1234, 0, 6, 2);
    NP_CHECK(run(&o, &whole, err, sizeof err) == 0, "uninterrupted");
    o.journal = j;
    o.resume = 1;
    NP_CHECK(run(&o, &resumed, err, sizeof err) == 0, "resumed");
    print_stats("uninterrupted 0..5", &whole.total);
    print_stats("killed, resumed 0..5", &resumed.total);
    printf("resumed %u blocks from the killed run's journal\n", resumed.blocks_resumed);
    NP_CHECK(seen >= 3 && resumed.blocks_resumed >= 3, "resumed %u blocks", resumed.blocks_resumed);
    NP_CHECK(np_sweep_stats_equal(&whole.total, &resumed.total), "statistics differ");
    remove(j);
    return 0;
}

/* s_frac=4 lerp_frac=6: the bound is loose (38.5 LSB) and the sweep must see errors > 1 LSB. */
static int t_cheap_fails(void)
{
    const np_unit *u = classic3();
    np_unit_cfg cfg;
    configure(u, &cfg, "s_frac=4,lerp_frac=6");
    np_sweep_stats s;
    NP_CHECK(np_sweep_block(u, &cfg, 0x0000, 0, 1, &s) == 0, "block");
    double bound = u->error_bound_lsb(&cfg);
    print_stats("s_frac=4 lerp_frac=6, block 0", &s);
    printf("max error %.4f LSB, %llu inputs over 1 LSB, bound %.4f LSB\n", s.max_err,
           (unsigned long long)s.over, bound);
    NP_CHECK(s.max_err > 1.0 && s.over > 0, "a cheap configuration must fail the 1 LSB tolerance");
    NP_CHECK(s.max_err <= bound, "and still respect its own bound");
    return 0;
}

static const np_test_case cases[] = {
    { "kernel_model_cell", t_kernel_model_cell },
    { "kernel_ref_cell", t_kernel_ref_cell },
    { "kernel_lattice", t_kernel_lattice },
    { "kernel_random", t_kernel_random },
    { "kernel_vs_plain_stats", t_kernel_vs_plain_stats },
    { "simplex3_pinned", t_simplex3_pinned },
    { "random_1e7", t_random_1e7 },
    { "random_widths", t_random_widths },
    { "threads", t_threads },
    { "journal_resume", t_journal_resume },
    { "journal_refuse", t_journal_refuse },
    { "kill_resume", t_kill_resume },
    { "cheap_fails", t_cheap_fails },
    { NULL, NULL },
};

NP_TEST_MAIN(cases)
