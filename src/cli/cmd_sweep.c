/* SPDX-License-Identifier: MIT */
/* noisepipe sweep: the exhaustive error sweep of one z slice (np_sweep.h). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "np_cli.h"
#include "np_cmd.h"
#include "np_sweep.h"
#include "np_unit.h"

static const char usage_text[] =
    "usage: noisepipe sweep --z Z [--unit NAME] [--config K=V,...] [--threads N]\n"
    "                       [--journal FILE [--resume]] [--x-cells A:B] [--no-kernel]\n"
    "\n"
    "Checks every (x, y) input of the z slice Z (2^32 inputs, u16 each) of the bit-exact\n"
    "model against the float reference and prints the error statistics.\n"
    "\n"
    "  --z Z            the slice: a u16 input word (Q8.8 for classic3), decimal or 0x hex\n"
    "  --unit NAME      the unit (default classic3; `noisepipe units` lists them)\n"
    "  --config K=V,... the unit's configuration (default: the unit's default)\n"
    "  --threads N      worker threads (default: one per online CPU)\n"
    "  --journal FILE   append each completed block (x cell, 2^24 inputs) to FILE\n"
    "  --resume         continue FILE: skip its blocks and merge their statistics;\n"
    "                   refused when FILE was written for another unit, config or z\n"
    "  --x-cells A:B    only x cells A <= i < B (0 <= A < B <= 256; default 0:256)\n"
    "  --no-kernel      evaluate the model and the reference per input through the\n"
    "                   unit's plain functions instead of its sweep kernel (slow;\n"
    "                   gives the same statistics, for cross-checking)\n"
    "\n"
    "Exit status: 0 when every input is within the unit's tolerance and the measured\n"
    "maximum is within the unit's guaranteed error bound, 1 when not, 2 on bad usage.\n";

/* "--name value" or "--name=value": the value, advancing *k; NULL if not this option. */
static const char *opt_value(int argc, char **argv, int *k, const char *name, int *missing)
{
    size_t n = strlen(name);
    if (strncmp(argv[*k], name, n) != 0)
        return NULL;
    if (argv[*k][n] == '=')
        return argv[*k] + n + 1;
    if (argv[*k][n] != '\0')
        return NULL;
    if (*k + 1 >= argc) {
        *missing = 1;
        return NULL;
    }
    return argv[++*k];
}

static int parse_cells(const char *s, unsigned *a, unsigned *b)
{
    char buf[64];
    const char *colon = strchr(s, ':');
    uint64_t va, vb;
    if (!colon || (size_t)(colon - s) >= sizeof buf)
        return -1;
    memcpy(buf, s, (size_t)(colon - s));
    buf[colon - s] = '\0';
    if (np_parse_u64(buf, 0, NP_SWEEP_CELLS - 1, &va) != 0 ||
        np_parse_u64(colon + 1, 1, NP_SWEEP_CELLS, &vb) != 0 || va >= vb)
        return -1;
    *a = (unsigned)va;
    *b = (unsigned)vb;
    return 0;
}

static void print_hist(const np_sweep_stats *s)
{
    uint64_t top = 1;
    for (unsigned b = 0; b < NP_SWEEP_HIST_BINS; b++)
        top = s->hist[b] > top ? s->hist[b] : top;
    printf("histogram of the error (bins of 1/%u LSB; empty bins left out):\n",
           NP_SWEEP_HIST_PER_LSB);
    for (unsigned b = 0; b < NP_SWEEP_HIST_BINS; b++) {
        if (!s->hist[b])
            continue;
        double lo = (double)b / NP_SWEEP_HIST_PER_LSB, hi = (double)(b + 1) / NP_SWEEP_HIST_PER_LSB;
        char range[32];
        if (b + 1 < NP_SWEEP_HIST_BINS)
            snprintf(range, sizeof range, "[%.3f, %.3f)", lo, hi);
        else
            snprintf(range, sizeof range, ">= %.3f", lo);
        char bar[41];
        unsigned w = (unsigned)((40 * s->hist[b] + top - 1) / top);
        memset(bar, '#', w);
        bar[w] = '\0';
        printf("  %-16s %12llu %9.5f%%  %s\n", range, (unsigned long long)s->hist[b],
               100.0 * (double)s->hist[b] / (double)s->n, bar);
    }
}

static void print_summary(const np_unit *u, const void *cfg, const np_sweep_opts *o,
                          const np_sweep_result *r, double bound)
{
    const np_sweep_stats *s = &r->total;
    char cfgtext[256];
    np_unit_fields f;
    np_unit_cfg_format(u, cfg, cfgtext, sizeof cfgtext);
    u->fields(cfg, &f);
    printf("sweep of unit %s (%s), slice %s = 0x%04x\n", u->name, cfgtext, f.in[2].name,
           (unsigned)o->z);
    printf("x cells %u..%u: %u block%s of 2^24 inputs, %u resumed from the journal\n", o->x_first,
           o->x_end - 1u, r->blocks, r->blocks == 1 ? "" : "s", r->blocks_resumed);
    if (f.n_out > 1) {
        printf("error of an input   the largest over its outputs");
        for (unsigned k = 0; k < f.n_out; k++)
            printf("%s%s", k ? ", " : " ", f.out[k].name);
        printf(" (each in its own LSB)\n");
    }
    printf("inputs checked      %llu\n", (unsigned long long)s->n);
    uint64_t in[NP_UNIT_MAX_FIELDS] = { s->max_x, s->max_y, o->z }, out[NP_UNIT_MAX_FIELDS];
    double ref[NP_UNIT_MAX_FIELDS];
    u->eval(cfg, in, out);
    u->ref(cfg, in, ref);
    printf("max error           %.6f LSB at %s=0x%04x %s=0x%04x %s=0x%04x:\n", s->max_err,
           f.in[0].name, (unsigned)s->max_x, f.in[1].name, (unsigned)s->max_y, f.in[2].name,
           (unsigned)o->z);
    for (unsigned k = 0; k < f.n_out; k++) {
        double v = np_unit_field_value(&f.out[k], out[k]);
        printf("    %-6s model %+.*f (word 0x%0*llx), reference %+.12f, error %.6f LSB\n",
               f.out[k].name, (int)f.out[k].frac, v, (int)(f.out[k].bits + 3u) / 4,
               (unsigned long long)out[k], ref[k], fabs(v - ref[k]) * ldexp(1.0, (int)f.out[k].frac));
    }
    printf("correctly rounded   %llu (%.4f%%)\n", (unsigned long long)s->cr,
           100.0 * (double)s->cr / (double)s->n);
    printf("mean error          %.6f LSB\n", s->sum / (double)s->n);
    printf("RMS error           %.6f LSB\n", sqrt(s->sum2 / (double)s->n));
    print_hist(s);
    printf("over tolerance      %llu (tolerance %g LSB)\n", (unsigned long long)s->over,
           u->tolerance_lsb);
    printf("guaranteed bound    %.6f LSB (the unit's error argument): %s\n", bound,
           s->max_err <= bound ? "holds" : "VIOLATED");
    printf("wall time           %.2f s on %u thread%s (%s), %llu inputs computed, %.1f M inputs/s\n",
           r->seconds, r->threads, r->threads == 1 ? "" : "s",
           r->kernel ? "sweep kernel" : "plain eval/ref per input",
           (unsigned long long)r->computed,
           r->seconds > 0 ? (double)r->computed / r->seconds * 1e-6 : 0.0);
}

int np_cmd_sweep(int argc, char **argv)
{
    const char *unit_name = "classic3", *config = NULL, *z_text = NULL, *cells = NULL;
    np_sweep_opts o;
    memset(&o, 0, sizeof o);
    o.x_end = NP_SWEEP_CELLS;
    o.use_kernel = 1;
    o.progress = 1;
    for (int k = 1; k < argc; k++) {
        const char *v;
        int missing = 0;
        if (strcmp(argv[k], "--help") == 0 || strcmp(argv[k], "-h") == 0) {
            fputs(usage_text, stdout);
            return NP_EXIT_OK;
        } else if ((v = opt_value(argc, argv, &k, "--unit", &missing))) {
            unit_name = v;
        } else if ((v = opt_value(argc, argv, &k, "--config", &missing))) {
            config = v;
        } else if ((v = opt_value(argc, argv, &k, "--z", &missing))) {
            z_text = v;
        } else if ((v = opt_value(argc, argv, &k, "--threads", &missing))) {
            uint64_t n;
            if (np_parse_u64(v, 1, NP_SWEEP_CELLS, &n) != 0) {
                np_err("sweep", "--threads %s: expected 1..%u", v, NP_SWEEP_CELLS);
                return NP_EXIT_USAGE;
            }
            o.threads = (unsigned)n;
        } else if ((v = opt_value(argc, argv, &k, "--journal", &missing))) {
            o.journal = v;
        } else if ((v = opt_value(argc, argv, &k, "--x-cells", &missing))) {
            cells = v;
        } else if (strcmp(argv[k], "--resume") == 0) {
            o.resume = 1;
        } else if (strcmp(argv[k], "--no-kernel") == 0) {
            o.use_kernel = 0;
        } else {
            np_err("sweep", missing ? "%s needs a value" : "unknown option '%s' (see --help)",
                   argv[k]);
            return NP_EXIT_USAGE;
        }
    }
    if (!z_text) {
        np_err("sweep", "--z is required (see --help)");
        return NP_EXIT_USAGE;
    }
    uint64_t z;
    if (np_parse_u64_or_0x(z_text, 0, 0xffff, &z) != 0) {
        np_err("sweep", "--z %s: expected a u16 word, 0..65535 or 0x0000..0xffff", z_text);
        return NP_EXIT_USAGE;
    }
    o.z = (uint16_t)z;
    if (cells && parse_cells(cells, &o.x_first, &o.x_end) != 0) {
        np_err("sweep", "--x-cells %s: expected A:B with 0 <= A < B <= 256", cells);
        return NP_EXIT_USAGE;
    }
    if (o.resume && !o.journal) {
        np_err("sweep", "--resume needs --journal FILE");
        return NP_EXIT_USAGE;
    }
    const np_unit *u = np_unit_find(unit_name);
    if (!u) {
        np_err("sweep", "unknown unit '%s' (see noisepipe units)", unit_name);
        return NP_EXIT_USAGE;
    }
    np_unit_cfg cfg;
    char err[1024];
    if (np_unit_configure(u, &cfg, config, err, sizeof err) != 0) {
        np_err("sweep", "--config: %s", err);
        return NP_EXIT_USAGE;
    }
    o.unit = u;
    o.cfg = &cfg;
    np_sweep_result r;
    if (np_sweep_run(&o, &r, err, sizeof err) != 0) {
        np_err("sweep", "%s", err);
        return NP_EXIT_USAGE;
    }
    double bound = u->error_bound_lsb(&cfg);
    print_summary(u, &cfg, &o, &r, bound);
    int ok = r.total.over == 0 && r.total.max_err <= bound;
    if (ok)
        printf("verdict: PASS, every input within %g LSB\n", u->tolerance_lsb);
    else
        printf("verdict: FAIL, %llu input%s over %g LSB%s\n", (unsigned long long)r.total.over,
               r.total.over == 1 ? "" : "s", u->tolerance_lsb,
               r.total.max_err <= bound ? "" : ", and the guaranteed bound does not hold");
    return ok ? NP_EXIT_OK : NP_EXIT_FAIL;
}
