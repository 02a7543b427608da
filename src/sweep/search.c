/* SPDX-License-Identifier: MIT */
/* The adversarial error search (np_search.h): input classes, hill-climb, threads, journal. */
#include "np_search.h"

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
#include "np_rng.h"
#include "np_sweep.h"
#include "sweep_internal.h"

const char *const np_search_class_name[NP_SEARCH_CLASSES] = {
    "extremes", "lattice and cell faces", "equal-offset and unit faces", "worst rounding", "random",
    "hill-climb",
};

/* ---------------------------------------------------------------- the unit */

const char *np_search_unit_check(const np_unit *u, const void *cfg)
{
    np_unit_fields f;
    u->fields(cfg, &f);
    if (f.n_in == 3)
        return np_sweep_unit_check(u, cfg);
    if (f.n_in < NP_SEARCH_MIN_IN || f.n_in > NP_SEARCH_MAX_IN)
        return "the search needs a unit with 2 to 5 inputs (x, y, z, w, v)";
    return np_sweep_fields_check(&f, "search", "x, y, ...");
}

typedef struct search_unit {
    const np_unit *u;
    const void *cfg;
    np_unit_fields f;
    unsigned dims;                    /* inputs: 2..5 u16 words */
    double scale[NP_UNIT_MAX_FIELDS]; /* 2^F per output field */
    double tol;
    int have_fine;                    /* the unit's fine_cfg: the climb's objective */
    np_unit_cfg fine;
    np_unit_fields ff;
} search_unit;

static void search_unit_init(search_unit *su, const np_unit *u, const void *cfg)
{
    su->u = u;
    su->cfg = cfg;
    u->fields(cfg, &su->f);
    su->dims = su->f.n_in;
    for (unsigned k = 0; k < su->f.n_out; k++)
        su->scale[k] = ldexp(1.0, (int)su->f.out[k].frac);
    su->tol = u->tolerance_lsb;
    su->have_fine = u->fine_cfg != NULL;
    if (su->have_fine) {
        u->fine_cfg(cfg, &su->fine);
        u->fields(&su->fine, &su->ff);
    }
}

/*
 * Errors of one input per field (e[k], output LSB); returns the objective
 * the worst list and the climb rank by: the largest field error before the
 * output rounding (the fine configuration's, in the same output LSB) when
 * the unit has one, else the largest field error. A NaN wins.
 */
static double eval_input(const search_unit *su, const uint16_t in16[NP_SEARCH_MAX_IN], double *e, unsigned *n_cr)
{
    uint64_t in[NP_UNIT_MAX_FIELDS] = { 0 }, out[NP_UNIT_MAX_FIELDS];
    for (unsigned a = 0; a < su->dims; a++)
        in[a] = in16[a];
    double ref[NP_UNIT_MAX_FIELDS];
    su->u->eval(su->cfg, in, out);
    su->u->ref(su->cfg, in, ref);
    double m = -1.0;
    for (unsigned k = 0; k < su->f.n_out; k++) {
        const np_field *fd = &su->f.out[k];
        int32_t code = (int32_t)(fd->is_signed ? np_sext(out[k], fd->bits) : (int64_t)out[k]);
        unsigned char cr;
        e[k] = np_sweep_error(code, ref[k], su->scale[k], &cr);
        *n_cr += cr;
        m = e[k] <= m ? m : e[k];
    }
    if (!su->have_fine)
        return m;
    su->u->eval(&su->fine, in, out);
    m = -1.0;
    for (unsigned k = 0; k < su->f.n_out; k++) {
        double d = fabs(np_unit_field_value(&su->ff.out[k], out[k]) - ref[k]) * su->scale[k];
        m = d <= m ? m : d;
    }
    return m;
}

/* ---------------------------------------------------------------- statistics */

/* Is a before b in the order that ranks equal errors: smaller x, then y, then z (then w, v)? */
static int in_before(const uint16_t *a, const uint16_t *b)
{
    for (unsigned k = 0; k < NP_SEARCH_MAX_IN; k++)
        if (a[k] != b[k])
            return a[k] < b[k];
    return 0;
}

/* Does point a rank above b (larger error, a NaN above everything, then the smaller input)? */
static int pt_above(const np_search_pt *a, const np_search_pt *b)
{
    int an = isnan(a->err), bn = isnan(b->err);
    if (an != bn)
        return an;
    if (!an && a->err != b->err)
        return a->err > b->err;
    return in_before(a->in, b->in);
}

static void stats_init(np_search_stats *s, unsigned n_out)
{
    memset(s, 0, sizeof *s);
    s->n_out = n_out;
    for (unsigned k = 0; k < NP_UNIT_MAX_FIELDS; k++)
        s->fmax[k].err = -1.0;
    for (unsigned c = 0; c < NP_SEARCH_CLASSES; c++)
        s->cls_max[c] = -1.0;
}

static void take_pt(np_search_pt *into, const np_search_pt *p)
{
    if (into->err < 0.0 || pt_above(p, into))
        *into = *p;
}

/* Insert p into the worst list (distinct inputs, ranked by pt_above). */
static void worst_insert(np_search_stats *s, const np_search_pt *p)
{
    for (unsigned i = 0; i < s->n_worst; i++)
        if (memcmp(s->worst[i].in, p->in, sizeof p->in) == 0)
            return;
    unsigned i = s->n_worst < NP_SEARCH_WORST ? s->n_worst++ : NP_SEARCH_WORST;
    if (i == NP_SEARCH_WORST) {
        if (!pt_above(p, &s->worst[NP_SEARCH_WORST - 1]))
            return;
        i = NP_SEARCH_WORST - 1;
    }
    while (i > 0 && pt_above(p, &s->worst[i - 1])) {
        s->worst[i] = s->worst[i - 1];
        i--;
    }
    s->worst[i] = *p;
}

static double add_input(np_search_stats *s, const search_unit *su, const uint16_t in[NP_SEARCH_MAX_IN], unsigned cls)
{
    double e[NP_UNIT_MAX_FIELDS];
    np_search_pt p;
    memcpy(p.in, in, sizeof p.in);
    unsigned n_cr = 0;
    p.err = eval_input(su, in, e, &n_cr);
    double worst = -1.0;
    s->cr += n_cr;
    s->n++;
    s->cls_n[cls]++;
    int over = 0;
    for (unsigned k = 0; k < su->f.n_out; k++) {
        np_search_pt q = p;
        q.err = e[k];
        take_pt(&s->fmax[k], &q);
        if (!(e[k] <= su->tol)) {
            s->fover[k]++;
            over = 1;
        }
        worst = e[k] <= worst ? worst : e[k];
    }
    s->over += (uint64_t)over;
    if (!(worst <= s->cls_max[cls]))
        s->cls_max[cls] = worst;
    worst_insert(s, &p);
    return p.err;
}

/* into += from. Every part is independent of the order of merges. */
static void stats_merge(np_search_stats *into, const np_search_stats *from)
{
    into->n += from->n;
    into->over += from->over;
    into->cr += from->cr;
    for (unsigned k = 0; k < into->n_out; k++) {
        if (from->fmax[k].err >= 0.0 || isnan(from->fmax[k].err))
            take_pt(&into->fmax[k], &from->fmax[k]);
        into->fover[k] += from->fover[k];
    }
    for (unsigned c = 0; c < NP_SEARCH_CLASSES; c++) {
        into->cls_n[c] += from->cls_n[c];
        if (!(from->cls_max[c] <= into->cls_max[c]))
            into->cls_max[c] = from->cls_max[c];
    }
    for (unsigned i = 0; i < from->n_worst; i++)
        worst_insert(into, &from->worst[i]);
}

static int same_pt(const np_search_pt *a, const np_search_pt *b)
{
    return memcmp(a->in, b->in, sizeof a->in) == 0 && memcmp(&a->err, &b->err, sizeof a->err) == 0;
}

int np_search_stats_equal(const np_search_stats *a, const np_search_stats *b)
{
    if (a->n != b->n || a->over != b->over || a->cr != b->cr || a->n_out != b->n_out || a->n_worst != b->n_worst ||
        memcmp(a->cls_n, b->cls_n, sizeof a->cls_n) != 0 || memcmp(a->cls_max, b->cls_max, sizeof a->cls_max) != 0)
        return 0;
    for (unsigned k = 0; k < a->n_out; k++)
        if (!same_pt(&a->fmax[k], &b->fmax[k]) || a->fover[k] != b->fover[k])
            return 0;
    for (unsigned i = 0; i < a->n_worst; i++)
        if (!same_pt(&a->worst[i], &b->worst[i]))
            return 0;
    return 1;
}

/* ---------------------------------------------------------------- the classes */

/* Per-axis words of the extremes class: input ends and the cell wrap at 256. */
static const uint16_t extreme_axis[] = {
    0x0000, 0x0001, 0x00ff, 0x0100, 0x0101, 0x7fff, 0x8000, 0x8001, 0xfeff, 0xff00, 0xff01, 0xffff,
};
enum { N_EXTREME_AXIS = sizeof extreme_axis / sizeof extreme_axis[0] };
/* For five inputs (12^5 = 248,832 would outgrow a search's first chunks): the input ends, the mid wrap and cell faces. */
static const uint16_t extreme_axis5[] = { 0x0000, 0x00ff, 0x0100, 0x7fff, 0x8000, 0xff00, 0xffff };
enum { N_EXTREME_AXIS5 = sizeof extreme_axis5 / sizeof extreme_axis5[0] };

static uint16_t rnd16(np_rng *r) { return (uint16_t)(np_rng_next(r) >> 48); }

/* Lattice: each axis on a lattice point or 1 LSB beside it, or (a cell face) a random word. */
static void gen_lattice(np_rng *r, uint16_t in[NP_SEARCH_MAX_IN], unsigned dims)
{
    static const uint8_t frac[3] = { 0xff, 0x00, 0x01 };
    uint64_t bits = np_rng_next(r);
    for (unsigned a = 0; a < dims; a++) {
        uint16_t w = rnd16(r);
        if ((bits >> a & 1u) || (bits >> dims & 7u) == 0) /* every axis on the lattice 1 time in 8 */
            w = (uint16_t)((w & 0xff00u) | frac[np_rng_below(r, 3)]);
        in[a] = w;
    }
}

/*
 * Equal offsets: x = y, y = z, x = z or x = y = z, then 0, 1 or 2 LSB off on
 * one axis. For n != 3 inputs: a group of 2..n axes (pairs, triples, ...,
 * all; its size uniform, its axes random) made equal - the whole word (the
 * same cell and fraction: offsets tie in every lattice) or, half the time,
 * the fraction only (each its own cell: the classic lattice's diagonal
 * faces) - then 0, 1 or 2 LSB off on one axis.
 */
static void gen_face(np_rng *r, uint16_t in[NP_SEARCH_MAX_IN], unsigned dims)
{
    static const int delta[6] = { 0, 0, 1, -1, 2, -2 };
    for (unsigned a = 0; a < dims; a++)
        in[a] = rnd16(r);
    if (dims == 3) {
        unsigned kind = (unsigned)np_rng_below(r, 4);
        if (kind == 3)
            in[1] = in[2] = in[0];
        else
            in[(kind + 1u) % 3u] = in[kind];
    } else {
        unsigned k = 2u + (unsigned)np_rng_below(r, dims - 1u), ax[NP_SEARCH_MAX_IN];
        for (unsigned a = 0; a < dims; a++)
            ax[a] = a;
        for (unsigned a = 0; a < k; a++) { /* the first k of a random permutation */
            unsigned b = a + (unsigned)np_rng_below(r, dims - a), t = ax[a];
            ax[a] = ax[b];
            ax[b] = t;
        }
        int frac_only = (int)(np_rng_next(r) & 1u);
        for (unsigned a = 1; a < k; a++)
            in[ax[a]] = frac_only ? (uint16_t)((in[ax[a]] & 0xff00u) | (in[ax[0]] & 0x00ffu)) : in[ax[0]];
    }
    unsigned axis = (unsigned)np_rng_below(r, dims);
    in[axis] = (uint16_t)(in[axis] + delta[np_rng_below(r, 6)]);
}

/*
 * Worst rounding for a unit without classes of its own but with a finer
 * output (np_unit.fine_cfg): of ADV_CANDIDATES random inputs, the one whose
 * output before the last rounding (the fine configuration's, in output LSB)
 * lies nearest a rounding tie (a half LSB): there the internal roundings
 * decide the output's last bit. Returns 0 when the unit has no finer output.
 */
enum { ADV_CANDIDATES = 16 };
static int gen_rounding_fine(const search_unit *su, np_rng *r, uint16_t in[NP_SEARCH_MAX_IN])
{
    if (!su->have_fine)
        return 0;
    double best = 2.0;
    for (unsigned c = 0; c < ADV_CANDIDATES; c++) {
        uint64_t w[NP_UNIT_MAX_FIELDS] = { 0 }, out[NP_UNIT_MAX_FIELDS];
        for (unsigned a = 0; a < su->dims; a++)
            w[a] = rnd16(r);
        su->u->eval(&su->fine, w, out);
        double v = np_unit_field_value(&su->ff.out[0], out[0]) * su->scale[0];
        double d = fabs(v - floor(v) - 0.5);
        if (d < best) {
            best = d;
            for (unsigned a = 0; a < su->dims; a++)
                in[a] = (uint16_t)w[a];
        }
    }
    return 1;
}

/*
 * Fill in[0..n) with class cls from the unit's own generator; a unit without
 * one gets gen_rounding_fine for the worst-rounding class; else random.
 */
static void gen_unit(const search_unit *su, unsigned cls, np_rng *r, uint16_t (*in)[NP_SEARCH_MAX_IN], size_t n)
{
    uint64_t (*buf)[NP_UNIT_MAX_FIELDS] = malloc(n * sizeof *buf);
    size_t got = buf && su->u->adversarial ? su->u->adversarial(su->cfg, cls, r, buf, n) : 0;
    for (size_t i = 0; i < n; i++) {
        if (got != n && !su->u->adversarial && cls == NP_ADV_ROUNDING && gen_rounding_fine(su, r, in[i]))
            continue;
        for (unsigned a = 0; a < su->dims; a++)
            in[i][a] = got == n ? (uint16_t)buf[i][a] : rnd16(r);
    }
    free(buf);
}

/*
 * The neighbour offsets, in the order tried: each axis alone by +-1..+-256,
 * then every combination of -2..+2 over the axes (n <= 3) or of -1..+1
 * (n = 4, 5: 80 and 242 combinations rather than 624 and 3124), the first
 * axis varying slowest.
 */
enum { N_STEPS = 12, N_NEIGH_MAX = NP_SEARCH_MAX_IN * 2 * N_STEPS + 242 };
typedef struct neighbours {
    unsigned n;
    int16_t d[N_NEIGH_MAX][NP_SEARCH_MAX_IN];
} neighbours;

/* The run: what every chunk and climb needs. */
typedef struct search_run {
    const np_search_opts *o;
    search_unit su;
    uint16_t (*ext)[NP_SEARCH_MAX_IN]; /* the extremes list */
    size_t n_ext;
    uint64_t n_chunks;  /* phase 1 */
    np_search_stats *chunk;
    unsigned char *have;
    uint64_t next, wave_end, done;
    pthread_mutex_t mu;
    np_jfile jf;
    int failed;
    char err[512];
    np_progress prog;
    /* the climbs of one round */
    np_search_stats *climb;
    const np_search_pt *starts;
    unsigned n_starts, next_climb;
    uint64_t *climb_budget;
    unsigned round;
    neighbours nb;      /* the climb's steps */
} search_run;

static np_rng chunk_rng(uint64_t seed, uint64_t k, uint64_t stream)
{
    uint64_t st = seed ^ (k * 0xd1342543de82ef95u) ^ (stream * 0x9e3779b97f4a7c15u);
    np_rng r;
    np_rng_seed(&r, np_splitmix64(&st));
    return r;
}

/*
 * The class schedule of the chunks after the extremes: of every 16, 6
 * random, 6 worst-rounding, 2 faces (half equal offsets, half the unit's
 * own), 2 lattice.
 */
static unsigned chunk_class(uint64_t j)
{
    unsigned m = (unsigned)(j % 16u);
    return m < 6 ? NP_SC_RANDOM : m < 12 ? NP_SC_ROUNDING : m < 14 ? NP_SC_FACE : NP_SC_LATTICE;
}

static void chunk_run(const search_run *run, uint64_t k, np_search_stats *s)
{
    const search_unit *su = &run->su;
    uint16_t in[NP_SEARCH_CHUNK][NP_SEARCH_MAX_IN];
    unsigned char cls[NP_SEARCH_CHUNK];
    memset(in, 0, sizeof in);
    np_rng r = chunk_rng(run->o->seed, k, 0);
    uint64_t n_ext_chunks = (run->n_ext + NP_SEARCH_CHUNK - 1) / NP_SEARCH_CHUNK;
    if (k < n_ext_chunks) {
        for (size_t i = 0; i < NP_SEARCH_CHUNK; i++) {
            size_t j = (size_t)k * NP_SEARCH_CHUNK + i;
            if (j < run->n_ext) {
                memcpy(in[i], run->ext[j], sizeof in[i]);
                cls[i] = NP_SC_EXTREME;
            } else {
                gen_lattice(&r, in[i], su->dims);
                cls[i] = NP_SC_LATTICE;
            }
        }
    } else {
        unsigned c = chunk_class(k - n_ext_chunks);
        if (c == NP_SC_ROUNDING || (c == NP_SC_FACE && (k & 16u)))
            gen_unit(su, c == NP_SC_ROUNDING ? NP_ADV_ROUNDING : NP_ADV_FACES, &r, in, NP_SEARCH_CHUNK);
        for (size_t i = 0; i < NP_SEARCH_CHUNK; i++) {
            if (c == NP_SC_RANDOM)
                for (unsigned a = 0; a < su->dims; a++)
                    in[i][a] = rnd16(&r);
            else if (c == NP_SC_LATTICE)
                gen_lattice(&r, in[i], su->dims);
            else if (c == NP_SC_FACE && !(k & 16u))
                gen_face(&r, in[i], su->dims);
            cls[i] = (unsigned char)c;
        }
    }
    stats_init(s, su->f.n_out);
    for (size_t i = 0; i < NP_SEARCH_CHUNK; i++)
        add_input(s, su, in[i], cls[i]);
}

/* ---------------------------------------------------------------- the hill-climb */

static void neigh_init(neighbours *nb, unsigned dims)
{
    static const int16_t step[N_STEPS] = { 1, 2, 3, 4, 6, 8, 12, 16, 32, 64, 128, 256 };
    unsigned n = 0;
    memset(nb, 0, sizeof *nb);
    for (unsigned a = 0; a < dims; a++)
        for (unsigned k = 0; k < N_STEPS; k++)
            for (int sg = -1; sg <= 1; sg += 2)
                nb->d[n++][a] = (int16_t)(sg * step[k]);
    int reach = dims <= 3 ? 2 : 1, v[NP_SEARCH_MAX_IN];
    for (unsigned a = 0; a < dims; a++)
        v[a] = -reach;
    for (;;) {
        int any = 0;
        for (unsigned a = 0; a < dims; a++)
            any |= v[a] != 0;
        if (any) {
            for (unsigned a = 0; a < dims; a++)
                nb->d[n][a] = (int16_t)v[a];
            n++;
        }
        unsigned a = dims;
        while (a > 0 && v[a - 1] == reach)
            v[--a] = -reach;
        if (a == 0)
            break;
        v[a - 1]++;
    }
    nb->n = n;
}

/*
 * One climb of `budget` inputs from start: steepest ascent over the
 * neighbours; when no neighbour is worse than the current point, a random
 * kick within +-16 per axis of the best point, and on.
 */
static void climb_run(const search_run *run, const np_search_pt *start, uint64_t budget, uint64_t id,
                      np_search_stats *s)
{
    const search_unit *su = &run->su;
    np_rng r = chunk_rng(run->o->seed, id, 1);
    stats_init(s, su->f.n_out);
    np_search_pt cur = *start, best = *start;
    while (s->n < budget) {
        np_search_pt top = cur;
        for (unsigned k = 0; k < run->nb.n && s->n < budget; k++) {
            np_search_pt p;
            memset(p.in, 0, sizeof p.in);
            for (unsigned a = 0; a < su->dims; a++)
                p.in[a] = (uint16_t)(cur.in[a] + run->nb.d[k][a]);
            p.err = add_input(s, su, p.in, NP_SC_CLIMB);
            if (p.err > top.err)
                top = p;
        }
        if (top.err > cur.err) {
            cur = top;
            if (cur.err > best.err)
                best = cur;
        } else if (s->n < budget) {
            np_search_pt p;
            memset(p.in, 0, sizeof p.in);
            for (unsigned a = 0; a < su->dims; a++)
                p.in[a] = (uint16_t)(best.in[a] + (int)np_rng_below(&r, 33) - 16);
            p.err = add_input(s, su, p.in, NP_SC_CLIMB);
            cur = p;
        }
    }
}

/* ---------------------------------------------------------------- journal */

/*
 * A journal (np_jfile.h) bound to unit, configuration, seed and budget,
 * then one record per completed phase-1 chunk, in the order chunks
 * completed; a record is 3 + F lines for F output fields, the last one
 * committing it:
 *
 *   noisepipe-search-journal 2
 *   unit=classic3 *crc
 *   config=out_bits=8 s_frac=12 lerp_frac=11 *crc
 *   seed=7 *crc
 *   n=65536 *crc
 *   chunk 3 n=4096 over=0 cr=4096 *crc                          opens a record
 *   field 0 max=0x1.2p-1 at=0x1234,0x0100,0xffff over=0 *crc    one per output field
 *   class n=0,4096,0,0,0,0 max=-0x1p+0,0x1.2p-1,... *crc        per class, np_search_class_name order
 *   worst 0x1234,0x0100,0xffff:0x1.2p-1 ... *crc                the W worst, ranked; commits
 *
 * Counts are decimal, doubles C99 hex (%a): a resumed chunk merges to the
 * same bits as a computed one. Not bound, because the result does not
 * depend on them: the thread count (np_search.h, Determinism) and
 * stop_early (chunk k's statistics are the same whichever waves run). The
 * climbs are not journalled: a resumed run climbs again from the same worst
 * list, so the same bits.
 */
#define JOURNAL_MAGIC "noisepipe-search-journal 2"

/* Synced at most this often (s): a chunk takes milliseconds, a sync as long. */
#define JOURNAL_SYNC_INTERVAL 1.0

/* An input's n words as the journal writes them: "0xXXXX,0xYYYY,..." (n = 3: x, y, z, as always). */
static const char *in_text(char *buf, size_t len, const uint16_t *in, unsigned dims)
{
    buf[0] = '\0';
    for (unsigned a = 0; a < dims; a++)
        snprintf(buf + strlen(buf), len - strlen(buf), "%s0x%04x", a ? "," : "", (unsigned)in[a]);
    return buf;
}

/* Add chunk k's record (an n-input unit's) to the journal's pending lines. 0, or -1. */
static int chunk_record(np_jfile *jf, uint64_t k, const np_search_stats *s, unsigned dims)
{
    char at[NP_SEARCH_MAX_IN * 7];
    int rc = np_jfile_add(jf, "chunk %" PRIu64 " n=%" PRIu64 " over=%" PRIu64 " cr=%" PRIu64, k, s->n, s->over,
                          s->cr);
    for (unsigned f = 0; f < s->n_out && rc == 0; f++)
        rc = np_jfile_add(jf, "field %u max=%a at=%s over=%" PRIu64, f, s->fmax[f].err,
                          in_text(at, sizeof at, s->fmax[f].in, dims), s->fover[f]);
    /* Room for the longest: a count is 20 digits, a %a double 24 characters, and a separator. */
    char n[NP_SEARCH_CLASSES * 21], max[NP_SEARCH_CLASSES * 25], worst[NP_SEARCH_WORST * (NP_SEARCH_MAX_IN * 7 + 26)];
    size_t ln = 0, lm = 0, lw = 0;
    for (unsigned c = 0; c < NP_SEARCH_CLASSES; c++) {
        ln += (size_t)snprintf(n + ln, sizeof n - ln, "%s%" PRIu64, c ? "," : "", s->cls_n[c]);
        lm += (size_t)snprintf(max + lm, sizeof max - lm, "%s%a", c ? "," : "", s->cls_max[c]);
    }
    worst[0] = '\0';
    for (unsigned i = 0; i < s->n_worst; i++)
        lw += (size_t)snprintf(worst + lw, sizeof worst - lw, " %s:%a", in_text(at, sizeof at, s->worst[i].in, dims),
                               s->worst[i].err);
    if (rc == 0)
        rc = np_jfile_add(jf, "class n=%s max=%s", n, max);
    return rc == 0 ? np_jfile_add(jf, "worst%s", worst) : rc;
}

/* Reading back: a record's lines into s, committed into run->chunk/have by its worst line. */
typedef struct chunk_reader {
    search_run *run;
    uint64_t k;
    np_search_stats s;
    unsigned next; /* the line expected: 0 chunk, 1..F field, F + 1 class, F + 2 worst */
} chunk_reader;

/* dims words "0xXXXX,0xYYYY,..." at *p into in (the rest 0): 0 (*p after it), or -1. */
static int parse_in(const char **p, uint16_t in[NP_SEARCH_MAX_IN], unsigned dims)
{
    const char *q = *p;
    memset(in, 0, NP_SEARCH_MAX_IN * sizeof *in);
    for (unsigned a = 0; a < dims; a++) {
        unsigned v;
        int used = -1;
        if ((a && *q++ != ',') || sscanf(q, "0x%x%n", &v, &used) != 1 || used < 0 || v > 0xffffu)
            return -1;
        in[a] = (uint16_t)v;
        q += used;
    }
    *p = q;
    return 0;
}

/* The class line's lists, "n=a,b,... max=x,y,...": 0, or -1. */
static int parse_classes(const char *p, np_search_stats *s)
{
    char *end;
    uint64_t total = 0;
    if (strncmp(p, "n=", 2) != 0)
        return -1;
    p += 2;
    for (unsigned c = 0; c < NP_SEARCH_CLASSES; c++, p = end + 1) {
        if (*p < '0' || *p > '9')
            return -1;
        s->cls_n[c] = strtoull(p, &end, 10);
        total += s->cls_n[c];
        if (*end != (c + 1u < NP_SEARCH_CLASSES ? ',' : ' '))
            return -1;
    }
    if (strncmp(p, "max=", 4) != 0)
        return -1;
    p += 4;
    for (unsigned c = 0; c < NP_SEARCH_CLASSES; c++, p = end + (*end != '\0')) {
        s->cls_max[c] = strtod(p, &end);
        if (end == p || *end != (c + 1u < NP_SEARCH_CLASSES ? ',' : '\0'))
            return -1;
    }
    return total == s->n ? 0 : -1;
}

static int parse_worst(const char *p, np_search_stats *s, unsigned dims)
{
    s->n_worst = 0;
    while (*p == ' ') {
        np_search_pt *w = &s->worst[s->n_worst];
        char *end;
        p++;
        if (s->n_worst == NP_SEARCH_WORST || parse_in(&p, w->in, dims) != 0 || *p++ != ':')
            return -1;
        w->err = strtod(p, &end);
        if (end == p)
            return -1;
        p = end;
        s->n_worst++;
    }
    return *p == '\0' && s->n_worst > 0 ? 0 : -1;
}

/* One record line read back (its checksum checked and cut off): NP_JFILE_OPEN, NP_JFILE_COMMIT, or -1. */
static int resume_line(void *ctx, const np_jfile_info *info, char *line, uint64_t lineno, char *err,
                       size_t errlen)
{
    chunk_reader *rd = ctx;
    search_run *run = rd->run;
    np_search_stats *s = &rd->s;
    unsigned n_out = run->su.f.n_out;
    int used = -1;
    (void)info;
    (void)lineno;
    if (rd->next == 0) {
        stats_init(s, n_out);
        if (sscanf(line, "chunk %" SCNu64 " n=%" SCNu64 " over=%" SCNu64 " cr=%" SCNu64 "%n", &rd->k, &s->n,
                   &s->over, &s->cr, &used) != 4 ||
            used < 0 || line[used] != '\0' || rd->k >= run->n_chunks || s->n != NP_SEARCH_CHUNK ||
            s->over > s->n || s->cr > s->n * n_out)
            return np_errf(err, errlen, "malformed chunk line (a record starts with one)");
    } else if (rd->next <= n_out) {
        unsigned f = 0;
        np_search_pt *m = &s->fmax[rd->next - 1u];
        const char *q = NULL;
        if (sscanf(line, "field %u max=%la at=%n", &f, &m->err, &used) == 2 && used > 0) {
            q = line + used;
            used = -1;
            if (parse_in(&q, m->in, run->su.dims) != 0 ||
                sscanf(q, " over=%" SCNu64 "%n", &s->fover[rd->next - 1u], &used) != 1)
                q = NULL;
        }
        if (!q || used < 0 || q[used] != '\0' || f != rd->next - 1u || s->fover[f] > s->over)
            return np_errf(err, errlen, "malformed field line (field %u of %u of chunk %" PRIu64 " expected)",
                           rd->next - 1u, n_out, rd->k);
    } else if (rd->next == n_out + 1u) {
        if (strncmp(line, "class ", 6) != 0 || parse_classes(line + 6, s) != 0)
            return np_errf(err, errlen, "malformed class line of chunk %" PRIu64, rd->k);
    } else {
        if (strncmp(line, "worst", 5) != 0 || parse_worst(line + 5, s, run->su.dims) != 0)
            return np_errf(err, errlen, "malformed worst line of chunk %" PRIu64, rd->k);
        if (run->have[rd->k] && !np_search_stats_equal(&run->chunk[rd->k], s))
            return np_errf(err, errlen, "chunk %" PRIu64 " appears twice with different statistics", rd->k);
        run->chunk[rd->k] = *s;
        run->have[rd->k] = 1;
        rd->next = 0;
        return NP_JFILE_COMMIT;
    }
    rd->next++;
    return NP_JFILE_OPEN;
}

/* Open the journal (np_jfile_open_run): chunks read back go into run->chunk/have. */
static int journal_open(search_run *run, char *err, size_t errlen)
{
    const np_search_opts *o = run->o;
    np_jfile_binds b;
    np_jfile_binds_init(&b);
    if (np_sweep_bind_unit(&b, o->unit, o->cfg) != 0 || np_jfile_bind(&b, "seed=%" PRIu64, o->seed) != 0 ||
        np_jfile_bind(&b, "n=%" PRIu64, o->n) != 0)
        return np_errf(err, errlen, "journal %s: a binding is too long", o->journal);
    chunk_reader rd = { .run = run, .next = 0 };
    return np_jfile_open_run(&run->jf, o->journal, JOURNAL_MAGIC, &b, o->resume, resume_line, &rd, err, errlen);
}

/* ---------------------------------------------------------------- threads */

/* n more inputs done (the caller holds the lock). */
static void count_done(search_run *run, uint64_t n)
{
    run->done += n;
    if (run->o->progress)
        np_progress_update(&run->prog, run->done);
}

static void *chunk_worker(void *arg)
{
    search_run *run = arg;
    pthread_mutex_lock(&run->mu);
    while (!run->failed && run->next < run->wave_end) {
        uint64_t k = run->next++;
        if (run->have[k])
            continue;
        pthread_mutex_unlock(&run->mu);
        np_search_stats s;
        chunk_run(run, k, &s);
        pthread_mutex_lock(&run->mu);
        run->chunk[k] = s;
        run->have[k] = 1;
        /* The record goes out in one write: a kill leaves at most a torn tail. */
        if (run->jf.fd >= 0 && !run->failed) {
            char jerr[sizeof run->err];
            if (chunk_record(&run->jf, k, &s, run->su.dims) != 0) {
                np_jfile_discard(&run->jf);
                run->failed = 1;
                snprintf(run->err, sizeof run->err, "cannot write journal %s: line too long or out of memory",
                         run->o->journal);
            } else if (np_jfile_commit(&run->jf, np_now() - run->jf.last_sync >= JOURNAL_SYNC_INTERVAL, jerr,
                                       sizeof jerr) != 0) {
                run->failed = 1;
                snprintf(run->err, sizeof run->err, "%s", jerr);
            }
        }
        count_done(run, s.n);
    }
    pthread_mutex_unlock(&run->mu);
    return NULL;
}

static void *climb_worker(void *arg)
{
    search_run *run = arg;
    pthread_mutex_lock(&run->mu);
    while (run->next_climb < run->n_starts) {
        unsigned i = run->next_climb++;
        pthread_mutex_unlock(&run->mu);
        np_search_stats s;
        climb_run(run, &run->starts[i], run->climb_budget[i], (uint64_t)run->round * NP_SEARCH_WORST + i, &s);
        pthread_mutex_lock(&run->mu);
        run->climb[i] = s;
        count_done(run, s.n);
    }
    pthread_mutex_unlock(&run->mu);
    return NULL;
}

enum { MAX_THREADS = 64 };

static unsigned online_cpus(void)
{
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n < 1 ? 1u : n > MAX_THREADS ? MAX_THREADS : (unsigned)n;
}

static void run_threads(void *(*fn)(void *), search_run *run, unsigned nt)
{
    pthread_t tid[MAX_THREADS];
    unsigned started = 0;
    for (; started < nt; started++)
        if (pthread_create(&tid[started], NULL, fn, run) != 0)
            break;
    if (started == 0)
        fn(run);
    for (unsigned k = 0; k < started; k++)
        pthread_join(tid[k], NULL);
}

/* The extremes list: every combination of extreme_axis, then the unit's boundary table. */
static int make_extremes(search_run *run)
{
    const np_unit *u = run->su.u;
    const unsigned dims = run->su.dims;
    size_t nb = u->boundary ? u->boundary(run->su.cfg, NULL, 0) : 0;
    const uint16_t *axis = dims == 5 ? extreme_axis5 : extreme_axis;
    const unsigned na = dims == 5 ? N_EXTREME_AXIS5 : N_EXTREME_AXIS;
    size_t n = 1;
    for (unsigned a = 0; a < dims; a++)
        n *= na; /* 12^n for n <= 4 (144, 1,728, 20,736), 7^5 = 16,807 */
    uint64_t (*b)[NP_UNIT_MAX_FIELDS] = malloc((nb ? nb : 1) * sizeof *b);
    run->ext = calloc(n + nb, sizeof *run->ext);
    if (!b || !run->ext) {
        free(b);
        return -1;
    }
    size_t k = 0;
    for (; k < n; k++) /* the last axis varying fastest */
        for (unsigned a = 0, q = (unsigned)k; a < dims; a++, q /= na)
            run->ext[k][dims - 1u - a] = axis[q % na];
    if (nb)
        u->boundary(run->su.cfg, b, nb);
    for (size_t i = 0; i < nb; i++, k++)
        for (unsigned a = 0; a < dims; a++)
            run->ext[k][a] = (uint16_t)b[i][a];
    run->n_ext = k;
    free(b);
    return 0;
}

static void free_run(search_run *run)
{
    np_jfile_close(&run->jf);
    free(run->ext);
    free(run->chunk);
    free(run->have);
    free(run);
}

int np_search_run(const np_search_opts *o, np_search_result *res, char *err, size_t errlen)
{
    memset(res, 0, sizeof *res);
    const char *why = np_search_unit_check(o->unit, o->cfg);
    if (why) {
        snprintf(err, errlen, "unit %s: %s", o->unit->name, why);
        return -1;
    }
    if (o->n < NP_SEARCH_CHUNK) {
        snprintf(err, errlen, "a search needs at least %u inputs", NP_SEARCH_CHUNK);
        return -1;
    }
    search_run *run = calloc(1, sizeof *run);
    if (!run) {
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    run->o = o;
    np_jfile_none(&run->jf);
    search_unit_init(&run->su, o->unit, o->cfg);
    const unsigned dims = run->su.dims;
    stats_init(&res->total, run->su.f.n_out);
    /* Phase 1: 3/4 of the budget in whole chunks; the climbs take the rest. */
    run->n_chunks = (o->n - o->n / 4u) / NP_SEARCH_CHUNK;
    if (run->n_chunks == 0)
        run->n_chunks = 1;
    run->chunk = malloc(run->n_chunks * sizeof *run->chunk);
    run->have = calloc(run->n_chunks, 1);
    if (!run->chunk || !run->have || make_extremes(run) != 0) {
        free_run(run);
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    if (o->journal && journal_open(run, err, errlen) != 0) {
        free_run(run);
        return -1;
    }
    neigh_init(&run->nb, run->su.dims);
    unsigned nt = o->threads ? (o->threads < MAX_THREADS ? o->threads : MAX_THREADS) : online_cpus();
    res->threads = nt;
    res->chunks = run->n_chunks;
    for (uint64_t k = 0; k < run->n_chunks; k++)
        res->chunks_resumed += run->have[k];
    double t0 = np_now();
    if (o->progress)
        np_progress_start(&run->prog, "search", o->n);
    pthread_mutex_init(&run->mu, NULL);
    uint64_t ck = 0;
    while (ck < run->n_chunks && !run->failed) {
        run->next = ck;
        run->wave_end = ck + NP_SEARCH_WAVE < run->n_chunks ? ck + NP_SEARCH_WAVE : run->n_chunks;
        run_threads(chunk_worker, run, nt);
        for (; ck < run->wave_end && !run->failed; ck++)
            stats_merge(&res->total, &run->chunk[ck]);
        if (o->stop_early && res->total.over)
            break;
    }

    /* Phase 2: rounds of climbs from the current worst list until the budget is spent. */
    uint64_t left = o->n > res->total.n && !(o->stop_early && res->total.over) ? o->n - res->total.n : 0;
    uint64_t per_round = left / 4u + 1u;
    np_search_stats climbs[NP_SEARCH_WORST];
    uint64_t budget[NP_SEARCH_WORST];
    np_search_pt starts[NP_SEARCH_WORST];
    while (left > 0 && !run->failed && res->total.n_worst > 0) {
        uint64_t r = per_round < left ? per_round : left;
        unsigned ns = res->total.n_worst;
        memcpy(starts, res->total.worst, ns * sizeof *starts);
        for (unsigned i = 0; i < ns; i++)
            budget[i] = r / ns + (i < r % ns ? 1u : 0u);
        run->climb = climbs;
        run->starts = starts;
        run->n_starts = ns;
        run->next_climb = 0;
        run->climb_budget = budget;
        run_threads(climb_worker, run, nt < ns ? nt : ns);
        for (unsigned i = 0; i < ns; i++)
            stats_merge(&res->total, &climbs[i]);
        left -= r;
        run->round++;
    }
    pthread_mutex_destroy(&run->mu);
    if (o->progress)
        np_progress_end(&run->prog);
    res->seconds = np_now() - t0;
    if (run->jf.fd >= 0 && !run->failed) {
        char jerr[sizeof run->err];
        if (np_jfile_sync(&run->jf, jerr, sizeof jerr) != 0) {
            run->failed = 1;
            snprintf(run->err, sizeof run->err, "%s", jerr);
        } else if (np_jfile_close(&run->jf) != 0) {
            run->failed = 1;
            snprintf(run->err, sizeof run->err, "cannot close journal %s", o->journal);
        }
    }
    int failed = run->failed;
    if (failed)
        snprintf(err, errlen, "%s", run->err);
    free_run(run);
    if (failed)
        return -1;
    res->bound = o->unit->error_bound_lsb(o->cfg);
    res->dims = dims;
    res->worst = res->total.fmax[0];
    for (unsigned k = 1; k < res->total.n_out; k++)
        if (pt_above(&res->total.fmax[k], &res->worst))
            res->worst = res->total.fmax[k];
    res->verdict = res->total.over ? NP_SEARCH_COUNTEREXAMPLE
                   : res->bound <= 1.0 ? NP_SEARCH_PROVED : NP_SEARCH_NO_COUNTER;
    return 0;
}

void np_search_verdict_text(const np_search_result *res, char *buf, size_t len)
{
    switch (res->verdict) {
    case NP_SEARCH_PROVED:
        snprintf(buf, len, "faithful (proved)");
        break;
    case NP_SEARCH_NO_COUNTER:
        snprintf(buf, len, "no counterexample in %" PRIu64 " adversarial inputs", res->total.n);
        break;
    default:
        snprintf(buf, len, "not faithful, counterexample (");
        /* A result put together by hand (a report's cache) may leave dims 0: a 3-input unit's. */
        for (unsigned a = 0; a < (res->dims ? res->dims : 3u); a++)
            snprintf(buf + strlen(buf), len - strlen(buf), "%s0x%04x", a ? ", " : "", res->worst.in[a]);
        snprintf(buf + strlen(buf), len - strlen(buf), ")");
        break;
    }
}
