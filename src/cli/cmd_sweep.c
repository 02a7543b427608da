/* SPDX-License-Identifier: MIT */
/* noisepipe sweep: the exhaustive error sweep of one z slice (np_sweep.h). */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#ifdef NOISEPIPE_HAVE_MPI
#include <mpi.h>
#endif

#include "np_common.h"
#include "np_cmd.h"
#include "np_sweep.h"
#include "np_unit.h"

static const char usage_text[] =
    "usage: noisepipe sweep --z Z|A:B [--unit NAME] [--config K=V,...] [--threads N]\n"
    "                       [--journal FILE|DIR [--resume]] [--x-cells A:B] [--no-kernel]\n"
    "       mpirun -np N noisepipe sweep --z A:B ...   (when built with MPI)\n"
    "\n"
    "Checks every (x, y) input of the z slice Z (2^32 inputs, u16 each) of the bit-exact\n"
    "model against the float reference and prints the error statistics.\n"
    "\n"
    "  --z Z            the slice: a u16 input word (Q8.8 for classic3), decimal or 0x hex\n"
    "  --z A:B          the slices A <= z < B (B <= 65536), one summary over all of them;\n"
    "                   under mpirun the ranks share the slices (rank r takes every N-th)\n"
    "  --unit NAME      the unit (default classic3; `noisepipe units` lists them)\n"
    "  --config K=V,... the unit's configuration (default: the unit's default)\n"
    "  --threads N      worker threads (default: one per online CPU)\n"
    "  --journal FILE   append each completed block (x cell, 2^24 inputs) to FILE;\n"
    "                   with --z A:B a directory (made if missing), one journal per slice\n"
    "  --resume         continue FILE: skip its blocks and merge their statistics;\n"
    "                   refused when FILE was written for another unit, config or z\n"
    "  --x-cells A:B    only x cells A <= i < B (0 <= A < B <= 256; default 0:256),\n"
    "                   in every slice\n"
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

/* "Z" or "A:B" (A < B <= 65536): the slices a <= z < b. */
static int parse_z(const char *s, unsigned *a, unsigned *b, int *range)
{
    const char *colon = strchr(s, ':');
    uint64_t va, vb;
    if (!colon) {
        if (np_parse_u64_or_0x(s, 0, 0xffff, &va) != 0)
            return -1;
        *a = (unsigned)va;
        *b = (unsigned)va + 1u;
        *range = 0;
        return 0;
    }
    char buf[64];
    if ((size_t)(colon - s) >= sizeof buf)
        return -1;
    memcpy(buf, s, (size_t)(colon - s));
    buf[colon - s] = '\0';
    if (np_parse_u64_or_0x(buf, 0, 0xffff, &va) != 0 || np_parse_u64_or_0x(colon + 1, 1, 0x10000, &vb) != 0 ||
        va >= vb)
        return -1;
    *a = (unsigned)va;
    *b = (unsigned)vb;
    *range = 1;
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

/*
 * The summary. A range of slices (z_end > z_first + 1 or range) prints the
 * slices and the z of the maximum; the run figures (time, ranks) come last.
 */
static void print_summary(const np_unit *u, const void *cfg, const np_sweep_opts *o,
                          const np_sweep_result *r, double bound, unsigned z_first, unsigned z_end,
                          int range, uint16_t zmax, double cpu)
{
    const np_sweep_stats *s = &r->total;
    char cfgtext[256];
    np_unit_fields f;
    np_unit_cfg_format(u, cfg, cfgtext, sizeof cfgtext);
    u->fields(cfg, &f);
    if (range)
        printf("sweep of unit %s (%s), slices %s = 0x%04x..0x%04x (%u slices)\n", u->name, cfgtext,
               f.in[2].name, z_first, z_end - 1u, z_end - z_first);
    else
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
    uint64_t in[NP_UNIT_MAX_FIELDS] = { s->max_x, s->max_y, zmax }, out[NP_UNIT_MAX_FIELDS];
    double ref[NP_UNIT_MAX_FIELDS];
    u->eval(cfg, in, out);
    u->ref(cfg, in, ref);
    printf("max error           %.6f LSB at %s=0x%04x %s=0x%04x %s=0x%04x:\n", s->max_err,
           f.in[0].name, (unsigned)s->max_x, f.in[1].name, (unsigned)s->max_y, f.in[2].name,
           (unsigned)zmax);
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
    /* CPU-seconds beside the wall time: on a shared machine the wall time says little about the work */
    printf("wall time           %.2f s on %u thread%s (%s), %.2f CPU-seconds, %llu inputs computed, "
           "%.1f M inputs/s\n",
           r->seconds, r->threads, r->threads == 1 ? "" : "s",
           r->kernel ? "sweep kernel" : "plain eval/ref per input", cpu,
           (unsigned long long)r->computed,
           r->seconds > 0 ? (double)r->computed / r->seconds * 1e-6 : 0.0);
}

/* ------------------------------------------------------------ several slices, MPI */

/*
 * A run over slices z_first <= z < z_end. Each process (an MPI rank, or the
 * only one) computes the slices z with (z - z_first) mod ranks == rank, each
 * through np_sweep_run (threads, journal: DIR/z-0xZZZZ.journal), and rank 0
 * merges every slice's statistics in increasing z: the same bits whatever the
 * number of ranks and whatever came from journals (np_sweep_stats_merge in a
 * fixed order; among equal maxima the smallest z, then x, then y).
 */
typedef struct slice_res {
    np_sweep_stats s;
    uint64_t computed;
    uint32_t resumed, threads;
} slice_res;

typedef struct comm {
    int rank, size, mpi;
} comm;

/* MPI only when a launcher started us (mpirun, srun): a plain run stays a plain process. */
static void comm_init(comm *c, int *argc, char ***argv)
{
    c->rank = 0;
    c->size = 1;
    c->mpi = 0;
#ifdef NOISEPIPE_HAVE_MPI
    if (getenv("OMPI_COMM_WORLD_SIZE") || getenv("PMI_SIZE") || getenv("PMIX_RANK") ||
        getenv("PMI_RANK")) {
        MPI_Init(argc, argv);
        MPI_Comm_rank(MPI_COMM_WORLD, &c->rank);
        MPI_Comm_size(MPI_COMM_WORLD, &c->size);
        c->mpi = 1;
    }
#else
    (void)argc;
    (void)argv;
#endif
}

/* End the MPI run; status != 0 on any rank ends every rank with it. */
static int comm_end(const comm *c, int status)
{
#ifdef NOISEPIPE_HAVE_MPI
    if (c->mpi) {
        if (status == NP_EXIT_USAGE)
            MPI_Abort(MPI_COMM_WORLD, status);
        MPI_Finalize();
    }
#else
    (void)c;
#endif
    return status;
}

/* The slice results computed on other ranks, into res[] on rank 0 (fixed-size bytes: one binary). */
static void comm_collect(const comm *c, slice_res *res, unsigned z_first, unsigned n, double *cpu)
{
#ifdef NOISEPIPE_HAVE_MPI
    if (!c->mpi || c->size == 1)
        return;
    for (unsigned k = 0; k < n; k++) {
        int owner = (int)(k % (unsigned)c->size);
        if (owner == 0)
            continue;
        if (c->rank == owner)
            MPI_Send(&res[k], (int)sizeof res[k], MPI_BYTE, 0, (int)(z_first + k), MPI_COMM_WORLD);
        else if (c->rank == 0)
            MPI_Recv(&res[k], (int)sizeof res[k], MPI_BYTE, owner, (int)(z_first + k), MPI_COMM_WORLD,
                     MPI_STATUS_IGNORE);
    }
    double mine = *cpu;
    MPI_Reduce(&mine, cpu, 1, MPI_DOUBLE, MPI_SUM, 0, MPI_COMM_WORLD);
#else
    (void)c;
    (void)res;
    (void)z_first;
    (void)n;
    (void)cpu;
#endif
}

static double cpu_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

/* Among equal maxima the first in (z, x, y) order: slices are merged in increasing z. */
static void merge_slice(np_sweep_stats *into, uint16_t *zmax, const np_sweep_stats *from, uint16_t z)
{
    np_sweep_stats keep = *into;
    np_sweep_stats_merge(into, from); /* counts, sums, histogram; its tie rule knows x, y only */
    const np_sweep_stats *m = from->n && from->max_err > keep.max_err ? from : &keep;
    into->max_err = m->max_err;
    into->max_x = m->max_x;
    into->max_y = m->max_y;
    if (m == from)
        *zmax = z;
}

static int run_slices(const comm *c, np_sweep_opts *o, const char *jdir, unsigned z_first, unsigned z_end,
                      int range, double bound)
{
    unsigned n = z_end - z_first;
    slice_res *res = calloc(n, sizeof *res);
    if (!res) {
        np_err("sweep", "out of memory");
        return NP_EXIT_USAGE;
    }
    if (jdir && range && mkdir(jdir, 0777) != 0 && errno != EEXIST) {
        np_err("sweep", "cannot make journal directory %s: %s", jdir, strerror(errno));
        free(res);
        return NP_EXIT_USAGE;
    }
    double t0 = np_now(), cpu0 = cpu_seconds();
    char jpath[4096], err[1024];
    np_sweep_result r;
    memset(&r, 0, sizeof r);
    for (unsigned k = (unsigned)c->rank; k < n; k += (unsigned)c->size) {
        o->z = (uint16_t)(z_first + k);
        if (jdir && range) {
            snprintf(jpath, sizeof jpath, "%s/z-0x%04x.journal", jdir, (unsigned)o->z);
            o->journal = jpath;
        }
        if (np_sweep_run(o, &r, err, sizeof err) != 0) {
            np_err("sweep", "%s%s", c->mpi ? "rank: " : "", err);
            free(res);
            return NP_EXIT_USAGE;
        }
        res[k].s = r.total;
        res[k].computed = r.computed;
        res[k].resumed = r.blocks_resumed;
        res[k].threads = r.threads;
    }
    double cpu = cpu_seconds() - cpu0;
    comm_collect(c, res, z_first, n, &cpu);
    if (c->rank != 0) {
        free(res);
        return NP_EXIT_OK;
    }
    np_sweep_result all;
    memset(&all, 0, sizeof all);
    np_sweep_stats_init(&all.total);
    uint16_t zmax = (uint16_t)z_first;
    for (unsigned k = 0; k < n; k++) {
        merge_slice(&all.total, &zmax, &res[k].s, (uint16_t)(z_first + k));
        all.computed += res[k].computed;
        all.blocks_resumed += res[k].resumed;
        all.threads = res[k].threads > all.threads ? res[k].threads : all.threads;
    }
    all.blocks = n * (o->x_end - o->x_first);
    all.kernel = o->use_kernel && o->unit->sweep_rows != NULL;
    all.seconds = np_now() - t0;
    free(res);
    print_summary(o->unit, o->cfg, o, &all, bound, z_first, z_end, range, zmax, cpu);
    if (range || c->size > 1)
        printf("processes           %d (MPI %s), %.2f CPU-seconds in all, %.2f s wall\n", c->size,
               c->mpi ? "on" : "off", cpu, all.seconds);
    int ok = all.total.over == 0 && all.total.max_err <= bound;
    if (ok)
        printf("verdict: PASS, every input within %g LSB\n", o->unit->tolerance_lsb);
    else
        printf("verdict: FAIL, %llu input%s over %g LSB%s\n", (unsigned long long)all.total.over,
               all.total.over == 1 ? "" : "s", o->unit->tolerance_lsb,
               all.total.max_err <= bound ? "" : ", and the guaranteed bound does not hold");
    return ok ? NP_EXIT_OK : NP_EXIT_FAIL;
}



static int cmd_sweep(const comm *c, int argc, char **argv)
{
    const char *unit_name = "classic3", *config = NULL, *z_text = NULL, *cells = NULL;
    int threads_given = 0;
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
            threads_given = 1;
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
    unsigned z_first, z_end;
    int range;
    if (parse_z(z_text, &z_first, &z_end, &range) != 0) {
        np_err("sweep", "--z %s: expected a u16 word (0..65535 or 0x0000..0xffff) or A:B with A < B <= 65536",
               z_text);
        return NP_EXIT_USAGE;
    }
    o.z = (uint16_t)z_first;
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
    if (c->rank != 0)
        o.progress = 0;
    if (c->size > 1 && !threads_given)
        o.threads = 1; /* one thread per rank unless told: the launcher places the ranks */
    return run_slices(c, &o, o.journal, z_first, z_end, range, u->error_bound_lsb(&cfg));
}

int np_cmd_sweep(int argc, char **argv)
{
    comm c;
    comm_init(&c, &argc, &argv);
    return comm_end(&c, cmd_sweep(&c, argc, argv));
}
