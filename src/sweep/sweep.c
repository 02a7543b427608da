/* SPDX-License-Identifier: MIT */
/* The exhaustive error sweep (np_sweep.h): statistics, blocks, journal, threads. */
#include "np_sweep.h"
#include "np_outfile.h"

#include <inttypes.h>
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "np_common.h"
#include "np_fixed.h"
#include "np_jfile.h"
#include "sweep_internal.h"

/* ---------------------------------------------------------------- statistics */

void np_sweep_stats_init(np_sweep_stats *s)
{
    memset(s, 0, sizeof *s);
    s->max_err = -1.0;
}

/* Is input (x1, y1) before (x0, y0) in the order that picks the reported maximum? */
static int before(uint16_t x1, uint16_t y1, uint16_t x0, uint16_t y0)
{
    return x1 < x0 || (x1 == x0 && y1 < y0);
}

static void take_max(np_sweep_stats *s, double e, uint16_t x, uint16_t y)
{
    if (e > s->max_err || (e == s->max_err && before(x, y, s->max_x, s->max_y))) {
        s->max_err = e;
        s->max_x = x;
        s->max_y = y;
    }
}

void np_sweep_stats_merge(np_sweep_stats *into, const np_sweep_stats *from)
{
    into->n += from->n;
    into->cr += from->cr;
    into->over += from->over;
    into->sum += from->sum;
    into->sum2 += from->sum2;
    for (unsigned b = 0; b < NP_SWEEP_HIST_BINS; b++)
        into->hist[b] += from->hist[b];
    if (from->n)
        take_max(into, from->max_err, from->max_x, from->max_y);
}

static int same_double(double a, double b) { return memcmp(&a, &b, sizeof a) == 0; }

int np_sweep_stats_equal(const np_sweep_stats *a, const np_sweep_stats *b)
{
    return a->n == b->n && a->cr == b->cr && a->over == b->over &&
           same_double(a->max_err, b->max_err) && a->max_x == b->max_x && a->max_y == b->max_y &&
           same_double(a->sum, b->sum) && same_double(a->sum2, b->sum2) &&
           memcmp(a->hist, b->hist, sizeof a->hist) == 0;
}

/* ------------------------------------------------------------------ the unit */

const char *np_sweep_fields_check(const np_unit_fields *f, const char *who, const char *in_names)
{
    static _Thread_local char why[128];
    for (unsigned k = 0; k < f->n_in; k++)
        if (f->in[k].bits != 16 || f->in[k].is_signed) {
            snprintf(why, sizeof why, "the %s needs u16 inputs %s", who, in_names);
            return why;
        }
    if (f->n_out < 1)
        return "the unit has no output";
    for (unsigned k = 0; k < f->n_out; k++)
        if (f->out[k].bits > (f->out[k].is_signed ? 32u : 31u)) {
            snprintf(why, sizeof why, "the %s handles output fields of at most 32 bits", who);
            return why;
        }
    return NULL;
}

const char *np_sweep_unit_check(const np_unit *u, const void *cfg)
{
    np_unit_fields f;
    u->fields(cfg, &f);
    if (f.n_in != 3)
        return "the sweep needs a unit with three inputs (x, y, z)";
    return np_sweep_fields_check(&f, "sweep", "x, y, z");
}

void np_sweep_rows_generic(const np_unit *u, const void *cfg, uint16_t x0, uint16_t y0,
                           uint16_t z, unsigned rows, unsigned what, int32_t *code, double *ref)
{
    np_unit_fields f;
    u->fields(cfg, &f);
    for (unsigned r = 0; r < rows; r++)
        for (unsigned t = 0; t < NP_SWEEP_ROW; t++) {
            uint64_t in[NP_UNIT_MAX_FIELDS] = { (uint64_t)x0 + t, (uint64_t)y0 + r, z };
            uint64_t out[NP_UNIT_MAX_FIELDS];
            double rv[NP_UNIT_MAX_FIELDS];
            if (what & NP_SWEEP_MODEL)
                u->eval(cfg, in, out);
            if (what & NP_SWEEP_REF)
                u->ref(cfg, in, rv);
            for (unsigned k = 0; k < f.n_out; k++) {
                size_t i = ((size_t)k * rows + r) * NP_SWEEP_ROW + t;
                if (what & NP_SWEEP_MODEL)
                    code[i] = (int32_t)(f.out[k].is_signed ? np_sext(out[k], f.out[k].bits)
                                                           : (int64_t)out[k]);
                if (what & NP_SWEEP_REF)
                    ref[i] = rv[k];
            }
        }
}

/* ---------------------------------------------------------------- one block */

/* What a block needs to know about the unit, looked up once. */
typedef struct sweep_unit {
    const np_unit *u;
    const void *cfg;
    int kernel;
    unsigned n_out;
    double scale[NP_UNIT_MAX_FIELDS]; /* 2^F of each output field: real value -> LSB */
    double tol;
} sweep_unit;

static void sweep_unit_init(sweep_unit *su, const np_unit *u, const void *cfg, int use_kernel)
{
    np_unit_fields f;
    u->fields(cfg, &f);
    su->u = u;
    su->cfg = cfg;
    su->kernel = use_kernel && u->sweep_rows != NULL;
    su->n_out = f.n_out;
    for (unsigned k = 0; k < f.n_out; k++)
        su->scale[k] = ldexp(1.0, (int)f.out[k].frac);
    su->tol = u->tolerance_lsb;
}

/* A thread's scratch: one kernel call's outputs and one row's errors. */
typedef struct sweep_buf {
    int32_t *code;
    double *ref;
    double e[NP_SWEEP_ROW];
    unsigned char cr[NP_SWEEP_ROW];
} sweep_buf;

static int buf_init(sweep_buf *b, unsigned n_out)
{
    size_t n = (size_t)n_out * NP_SWEEP_ROWS * NP_SWEEP_ROW;
    b->code = malloc(n * sizeof *b->code);
    b->ref = malloc(n * sizeof *b->ref);
    return b->code && b->ref ? 0 : -1;
}

static void buf_free(sweep_buf *b)
{
    free(b->code);
    free(b->ref);
}

/*
 * Running sums of a block, one per lane: the lanes let the compiler
 * vectorise the hot loop while the order of every double addition stays
 * the one written here (no reassociation: no fast-math).
 */
enum { LANES = 8 };
typedef struct block_acc {
    double sum[LANES], sum2[LANES];
    np_sweep_stats s; /* everything but sum and sum2 */
} block_acc;

/* A kernel call's histogram, in interleaved copies so that consecutive increments rarely wait on each other. */
enum { HIST_WAYS = 4 };
typedef uint32_t call_hist[HIST_WAYS][NP_SWEEP_HIST_BINS];

/*
 * sum[j] += e[t + j], sum2[j] += e[t + j]^2 and mx[j] = max over t of
 * e[t + j] (mx from -1; a NaN never replaces it), for t = 0, 8, 16, ...: each
 * lane's additions in increasing t, exactly the scalar loop's order; with
 * GCC's vector extension the eight lanes are one vector (AVX-512) or two or
 * four, whatever the clone has.
 */
#if defined(__GNUC__)
typedef double lanes_d __attribute__((vector_size(LANES * sizeof(double))));
typedef long long lanes_i __attribute__((vector_size(LANES * sizeof(long long))));
NP_SWEEP_INLINE void lanes_sum(double *sum, double *sum2, double *mx, const double *e)
{
    lanes_d vs, vs2, vm, v;
    memcpy(&vs, sum, sizeof vs);
    memcpy(&vs2, sum2, sizeof vs2);
    for (unsigned j = 0; j < LANES; j++)
        vm[j] = -1.0;
    for (unsigned t = 0; t < NP_SWEEP_ROW; t += LANES) {
        memcpy(&v, e + t, sizeof v);
        vs += v;
        vs2 += v * v;
        lanes_i gt = v > vm; /* all ones where v > vm */
        vm = (lanes_d)(((lanes_i)v & gt) | ((lanes_i)vm & ~gt));
    }
    memcpy(sum, &vs, sizeof vs);
    memcpy(sum2, &vs2, sizeof vs2);
    memcpy(mx, &vm, sizeof vm);
}
#else
static void lanes_sum(double *sum, double *sum2, double *mx, const double *e)
{
    for (unsigned j = 0; j < LANES; j++)
        mx[j] = -1.0;
    for (unsigned t = 0; t < NP_SWEEP_ROW; t += LANES)
        for (unsigned j = 0; j < LANES; j++) {
            double v = e[t + j];
            sum[j] += v;
            sum2[j] += v * v;
            mx[j] = v > mx[j] ? v : mx[j];
        }
}
#endif

/* Errors and correctly-rounded flags of row r of the kernel's output. */
NP_SWEEP_INLINE void row_errors(const sweep_unit *su, const sweep_buf *b, unsigned r, double *e,
                                unsigned char *crm)
{
    for (unsigned f = 0; f < su->n_out; f++) {
        size_t base = ((size_t)f * NP_SWEEP_ROWS + r) * NP_SWEEP_ROW;
        const int32_t *code = b->code + base;
        const double *ref = b->ref + base;
        double scale = su->scale[f];
        for (unsigned t = 0; t < NP_SWEEP_ROW; t++) {
            unsigned char ok;
            double d = np_sweep_error(code[t], ref[t], scale, &ok);
            if (f == 0) {
                e[t] = d;
                crm[t] = ok;
            } else {
                e[t] = d <= e[t] ? e[t] : d; /* a NaN wins */
                crm[t] &= ok;
            }
        }
    }
}

NP_SWEEP_INLINE void acc_row(np_sweep_stats *s, double *sum, double *sum2, call_hist hist,
                             const double *e, const unsigned char *crm, double tol, uint16_t x0,
                             uint16_t y)
{
    double mx[LANES];
    lanes_sum(sum, sum2, mx, e);
    unsigned cr = 0, over = 0;
    for (unsigned t = 0; t < NP_SWEEP_ROW; t++) {
        cr += (unsigned)crm[t];
        over += (unsigned)!(e[t] <= tol);
    }
    for (unsigned t = 0; t < NP_SWEEP_ROW; t += HIST_WAYS)
        for (unsigned w = 0; w < HIST_WAYS; w++) {
            double q = e[t + w] * (double)NP_SWEEP_HIST_PER_LSB;
            unsigned bin = q < (double)(NP_SWEEP_HIST_BINS - 1) ? (unsigned)q : NP_SWEEP_HIST_BINS - 1u;
            hist[w][bin]++;
        }
    s->n += (uint64_t)NP_SWEEP_ROW;
    s->cr += (uint64_t)cr;
    s->over += (uint64_t)over;
    double m = mx[0];
    for (unsigned j = 1; j < LANES; j++)
        m = mx[j] > m ? mx[j] : m;
    if (m >= s->max_err) {
        unsigned t = 0;
        while (t + 1 < NP_SWEEP_ROW && e[t] != m) /* first input of the row at m */
            t++;
        take_max(s, m, (uint16_t)(x0 + t), y);
    }
}

/* Statistics of the NP_SWEEP_ROWS rows of one kernel call, rows y0, y0 + 1, ... */
NP_SWEEP_CLONES static void acc_rows(const sweep_unit *su, sweep_buf *b, block_acc *a, uint16_t x0,
                                     uint16_t y0)
{
    double sum[LANES], sum2[LANES]; /* in registers for the call */
    call_hist hist;
    memcpy(sum, a->sum, sizeof sum);
    memcpy(sum2, a->sum2, sizeof sum2);
    memset(hist, 0, sizeof hist);
    for (unsigned r = 0; r < NP_SWEEP_ROWS; r++) {
        row_errors(su, b, r, b->e, b->cr);
        acc_row(&a->s, sum, sum2, hist, b->e, b->cr, su->tol, x0, (uint16_t)(y0 + r));
    }
    memcpy(a->sum, sum, sizeof sum);
    memcpy(a->sum2, sum2, sizeof sum2);
    for (unsigned w = 0; w < HIST_WAYS; w++)
        for (unsigned k = 0; k < NP_SWEEP_HIST_BINS; k++)
            a->s.hist[k] += (uint64_t)hist[w][k];
}

static void block_run(const sweep_unit *su, sweep_buf *b, uint16_t z, unsigned xcell,
                      np_sweep_stats *out)
{
    block_acc a;
    memset(&a, 0, sizeof a);
    np_sweep_stats_init(&a.s);
    uint16_t x0 = (uint16_t)(xcell * NP_SWEEP_ROW);
    for (unsigned y0 = 0; y0 < 65536u; y0 += NP_SWEEP_ROWS) {
        unsigned what = NP_SWEEP_MODEL | NP_SWEEP_REF;
        if (su->kernel)
            su->u->sweep_rows(su->cfg, x0, (uint16_t)y0, z, NP_SWEEP_ROWS, what, b->code, b->ref);
        else
            np_sweep_rows_generic(su->u, su->cfg, x0, (uint16_t)y0, z, NP_SWEEP_ROWS, what,
                                  b->code, b->ref);
        acc_rows(su, b, &a, x0, (uint16_t)y0);
    }
    a.s.sum = a.s.sum2 = 0.0;
    for (unsigned j = 0; j < LANES; j++) {
        a.s.sum += a.sum[j];
        a.s.sum2 += a.sum2[j];
    }
    *out = a.s;
}

int np_sweep_block(const np_unit *u, const void *cfg, uint16_t z, unsigned xcell, int use_kernel,
                   np_sweep_stats *out)
{
    sweep_unit su;
    sweep_buf b;
    sweep_unit_init(&su, u, cfg, use_kernel);
    int rc = buf_init(&b, su.n_out);
    if (rc == 0)
        block_run(&su, &b, z, xcell, out);
    buf_free(&b);
    return rc;
}

/* ---------------------------------------------------------------- journal */

/*
 * A journal (np_jfile.h) bound to unit, configuration and slice, then one
 * line per completed block, in the order blocks completed:
 *
 *   noisepipe-sweep-journal 2
 *   unit=classic3 *crc
 *   config=out_bits=8 s_frac=12 lerp_frac=11 *crc
 *   z=0x0000 *crc
 *   block 17 n=16777216 cr=... over=0 max=0x1.4p-1 at=0x1134,0x9a01 sum=0x1.8p+21
 *     sum2=0x1.2p+20 hist=c0,c1,...,c32 *1a2b3c4d        (one line)
 *
 * Counts are decimal, doubles C99 hex (%a), so a resumed block merges to the
 * same bits as a computed one. A torn last line is what a killed run leaves
 * behind: resuming cuts it off and computes that block again.
 */
#define JOURNAL_MAGIC "noisepipe-sweep-journal 2"

int np_sweep_bind_unit(np_jfile_binds *b, const np_unit *u, const void *cfg)
{
    char cfgtext[NP_JFILE_TEXT_MAX - 16];
    np_unit_cfg_format(u, cfg, cfgtext, sizeof cfgtext);
    return np_jfile_bind(b, "unit=%s", u->name) != 0 || np_jfile_bind(b, "config=%s", cfgtext) != 0 ? -1 : 0;
}

/* Add the block line to the journal's pending record. 0, or -1. */
static int block_line(np_jfile *jf, unsigned blk, const np_sweep_stats *s)
{
    char hist[NP_SWEEP_HIST_BINS * 21];
    size_t len = 0;
    for (unsigned b = 0; b < NP_SWEEP_HIST_BINS; b++)
        len += (size_t)snprintf(hist + len, sizeof hist - len, "%s%" PRIu64, b ? "," : "", s->hist[b]);
    return np_jfile_add(jf,
                        "block %u n=%" PRIu64 " cr=%" PRIu64 " over=%" PRIu64
                        " max=%a at=0x%04x,0x%04x sum=%a sum2=%a hist=%s",
                        blk, s->n, s->cr, s->over, s->max_err, (unsigned)s->max_x,
                        (unsigned)s->max_y, s->sum, s->sum2, hist);
}

/* Parse one block line (its checksum checked and cut off); 0, or -1 when malformed. */
static int parse_block(const char *line, unsigned *blk, np_sweep_stats *s)
{
    char *end;
    unsigned b, mx, my;
    int used = -1;
    np_sweep_stats_init(s);
    if (sscanf(line,
               "block %u n=%" SCNu64 " cr=%" SCNu64 " over=%" SCNu64
               " max=%la at=0x%x,0x%x sum=%la sum2=%la hist=%n",
               &b, &s->n, &s->cr, &s->over, &s->max_err, &mx, &my, &s->sum, &s->sum2,
               &used) != 9 ||
        used < 0)
        return -1;
    const char *p = line + used;
    uint64_t total = 0;
    for (unsigned k = 0; k < NP_SWEEP_HIST_BINS; k++) {
        if (k > 0 && *p++ != ',')
            return -1;
        if (*p < '0' || *p > '9')
            return -1;
        s->hist[k] = strtoull(p, &end, 10);
        total += s->hist[k];
        p = end;
    }
    if (*p != '\0' || b >= NP_SWEEP_CELLS || mx > 0xffffu || my > 0xffffu ||
        s->n != NP_SWEEP_BLOCK_INPUTS || total != s->n || s->cr > s->n || s->over > s->n)
        return -1;
    s->max_x = (uint16_t)mx;
    s->max_y = (uint16_t)my;
    *blk = b;
    return 0;
}

/* The run's shared state. */
typedef struct sweep_run {
    const np_sweep_opts *o;
    sweep_unit su;
    np_sweep_stats blk[NP_SWEEP_CELLS];
    unsigned char have[NP_SWEEP_CELLS];
    unsigned todo[NP_SWEEP_CELLS], n_todo, next;
    pthread_mutex_t mu;
    np_jfile jf;
    int failed;
    char err[512];
    np_progress prog;
    uint64_t done;
} sweep_run;

/* A block line read back: into run->blk/have. */
static int resume_line(void *ctx, const np_jfile_info *info, char *line, uint64_t lineno, char *err,
                       size_t errlen)
{
    sweep_run *run = ctx;
    unsigned b;
    np_sweep_stats s;
    (void)info;
    (void)lineno;
    if (parse_block(line, &b, &s) != 0)
        return np_errf(err, errlen, "malformed block line");
    if (run->have[b] && !np_sweep_stats_equal(&run->blk[b], &s))
        return np_errf(err, errlen, "block %u appears twice with different statistics", b);
    run->blk[b] = s;
    run->have[b] = 1;
    return NP_JFILE_COMMIT;
}

/* Open the journal (np_jfile_open_run): blocks read back go into run->blk/have. */
static int journal_open(sweep_run *run, char *err, size_t errlen)
{
    np_jfile_binds b;
    np_jfile_binds_init(&b);
    if (np_sweep_bind_unit(&b, run->o->unit, run->o->cfg) != 0 ||
        np_jfile_bind(&b, "z=0x%04x", (unsigned)run->o->z) != 0)
        return np_errf(err, errlen, "journal %s: a binding is too long", run->o->journal);
    return np_jfile_open_run(&run->jf, run->o->journal, JOURNAL_MAGIC, &b, run->o->resume, resume_line, run, err,
                             errlen);
}

/* ---------------------------------------------------------------- threads */

/* What an interrupt (SIGINT, SIGTERM) keeps, for its handler to say (np_outfile.h). */
static void interrupt_note(const sweep_run *run)
{
    unsigned kept = 0;
    for (unsigned k = 0; k < NP_SWEEP_CELLS; k++)
        kept += run->have[k] != 0;
    char note[600];
    snprintf(note, sizeof note,
             "journal %.400s keeps %u finished block%s of 2^24 inputs; run the same command with --resume to go on",
             run->o->journal, kept, kept == 1 ? "" : "s");
    np_interrupt_note(note);
}

static void *worker(void *arg)
{
    sweep_run *run = arg;
    sweep_buf b;
    int ok = buf_init(&b, run->su.n_out) == 0;
    pthread_mutex_lock(&run->mu);
    if (!ok && !run->failed) {
        run->failed = 1;
        snprintf(run->err, sizeof run->err, "out of memory");
    }
    while (ok && !run->failed && run->next < run->n_todo) {
        unsigned blk = run->todo[run->next++];
        pthread_mutex_unlock(&run->mu);
        np_sweep_stats s;
        block_run(&run->su, &b, run->o->z, blk, &s);
        pthread_mutex_lock(&run->mu);
        run->blk[blk] = s;
        run->have[blk] = 1;
        run->done += s.n;
        if (run->jf.fd >= 0) {
            /* Synced before the next block is taken: a block counts once it is durable. */
            char jerr[sizeof run->err];
            if (block_line(&run->jf, blk, &s) != 0) {
                run->failed = 1;
                snprintf(run->err, sizeof run->err, "cannot write journal %s: line too long or out of memory",
                         run->o->journal);
            } else if (np_jfile_commit(&run->jf, 1, jerr, sizeof jerr) != 0) {
                run->failed = 1;
                snprintf(run->err, sizeof run->err, "%s", jerr);
            } else {
                interrupt_note(run);
            }
        }
        if (run->o->progress)
            np_progress_update(&run->prog, run->done);
    }
    pthread_mutex_unlock(&run->mu);
    buf_free(&b);
    return NULL;
}

static unsigned online_cpus(void)
{
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n < 1 ? 1u : n > NP_SWEEP_CELLS ? (unsigned)NP_SWEEP_CELLS : (unsigned)n;
}

int np_sweep_run(const np_sweep_opts *o, np_sweep_result *res, char *err, size_t errlen)
{
    memset(res, 0, sizeof *res);
    np_sweep_stats_init(&res->total);
    if (o->x_first >= o->x_end || o->x_end > NP_SWEEP_CELLS)
        return np_errf(err, errlen, "x cells %u:%u: need A < B <= 256", o->x_first, o->x_end);
    const char *why = np_sweep_unit_check(o->unit, o->cfg);
    if (why)
        return np_errf(err, errlen, "unit %s: %s", o->unit->name, why);

    sweep_run *run = calloc(1, sizeof *run);
    if (!run)
        return np_errf(err, errlen, "out of memory");
    run->o = o;
    sweep_unit_init(&run->su, o->unit, o->cfg, o->use_kernel);
    np_jfile_none(&run->jf);
    if (o->journal && journal_open(run, err, errlen) != 0) {
        np_jfile_close(&run->jf);
        free(run);
        return -1;
    }
    if (o->journal)
        interrupt_note(run);

    for (unsigned b = o->x_first; b < o->x_end; b++) {
        if (run->have[b])
            res->blocks_resumed++;
        else
            run->todo[run->n_todo++] = b;
    }
    res->blocks = o->x_end - o->x_first;
    res->kernel = run->su.kernel;
    unsigned nt = o->threads ? o->threads : online_cpus();
    if (nt > run->n_todo)
        nt = run->n_todo;
    res->threads = nt;

    double t0 = np_now();
    if (o->progress)
        np_progress_start(&run->prog, "sweep", (uint64_t)run->n_todo * NP_SWEEP_BLOCK_INPUTS);
    pthread_mutex_init(&run->mu, NULL);
    pthread_t tid[NP_SWEEP_CELLS];
    unsigned started = 0;
    for (; started < nt; started++)
        if (pthread_create(&tid[started], NULL, worker, run) != 0)
            break;
    if (started == 0 && run->n_todo > 0)
        worker(run); /* no thread could start: do the work here */
    for (unsigned k = 0; k < started; k++)
        pthread_join(tid[k], NULL);
    pthread_mutex_destroy(&run->mu);
    if (o->progress)
        np_progress_end(&run->prog);
    res->seconds = np_now() - t0;
    res->computed = run->done;

    if (np_jfile_close(&run->jf) != 0 && !run->failed) {
        run->failed = 1;
        snprintf(run->err, sizeof run->err, "cannot close journal %s", o->journal);
    }
    if (run->failed) {
        snprintf(err, errlen, "%s", run->err);
        free(run);
        return -1;
    }
    for (unsigned b = o->x_first; b < o->x_end; b++)
        np_sweep_stats_merge(&res->total, &run->blk[b]);
    free(run);
    return 0;
}
