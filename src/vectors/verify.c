/* SPDX-License-Identifier: MIT */
/*
 * verify.c - the verifier, TestFloat style. For every vector it checks:
 *
 *   model     the file's expected outputs and reference against the bit-exact
 *             model and the float reference recomputed from its inputs (a
 *             corrupted or misconfigured file, or a model that changed);
 *   bits      the outputs under test (a device's, or the cycle-accurate
 *             model's) against the expected outputs, bit for bit;
 *   accuracy  |output - reference| <= tolerance, in output LSB;
 *   latency   (cycle model) every output leaves exactly `latency` clocks after
 *             its input when no output stall came in between, and never held
 *             longer than the stalls that came in between.
 *
 * It prints `inputs => got expected: want (reasons)` per failing vector,
 * stops after --errors of them, then the error summary and one verdict line.
 */
#include "np_vec.h"

#include <math.h>
#include <stdarg.h>
#include <string.h>

#include "np_common.h"

typedef struct verifier {
    const np_verify_opts *o;
    const np_vec_header *h;
    const char *name; /* the vector file, for messages */
    FILE *out;
    double tol;
    uint64_t tests, errors, exact_latency;
    int stopped;
    np_vec_acc acc[NP_UNIT_MAX_FIELDS];
    np_progress progress; /* on a terminal only */
} verifier;

/* A reason text under construction. */
typedef struct why {
    char s[1024];
    size_t at;
} why;

static void why_add(why *w, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void why_add(why *w, const char *fmt, ...)
{
    if (w->at + 3 >= sizeof w->s)
        return;
    if (w->at) {
        memcpy(w->s + w->at, "; ", 2);
        w->at += 2;
    }
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(w->s + w->at, sizeof w->s - w->at, fmt, ap);
    va_end(ap);
    if (n > 0)
        w->at += (size_t)n < sizeof w->s - w->at ? (size_t)n : sizeof w->s - w->at - 1u;
}

/* --- Accuracy against the float reference --- */

/* floor(x + 1/2) without the rounding of x + 0.5: exact for |x| < 2^52. */
static double round_half_up(double x)
{
    double r = floor(x);
    return x - r >= 0.5 ? r + 1.0 : r;
}

/*
 * The correctly rounded output code for reference value ref: the rule of
 * np_shr_round_half_up applied to ref * 2^frac, saturated to the field.
 */
static double ideal_code(const np_field *f, double ref)
{
    int b = (int)f->bits;
    double lo = f->is_signed ? -ldexp(1.0, b - 1) : 0.0;
    double hi = ldexp(1.0, f->is_signed ? b - 1 : b) - 1.0;
    double c = round_half_up(ldexp(ref, (int)f->frac));
    return c < lo ? lo : c > hi ? hi : c;
}

/* Error of an output word against the reference, in LSB of field f. */
static double err_lsb(const np_field *f, uint64_t word, double ref)
{
    return ldexp(np_unit_field_value(f, word) - ref, (int)f->frac);
}

/* Count output word (error e LSB against reference ref) in the statistics of its field. */
static void acc_add(np_vec_acc *a, const np_field *f, uint64_t word, double ref, double e,
                    uint64_t index)
{
    a->n++;
    a->rounded += ldexp(np_unit_field_value(f, word), (int)f->frac) == ideal_code(f, ref);
    if (fabs(e) > a->max_abs || a->n == 1) {
        a->max_abs = fabs(e);
        a->max_index = index;
    }
    double bin = floor(e * 8.0) + NP_VEC_HIST_HALF;
    if (!(bin >= 0.0))
        a->below++;
    else if (bin >= 2.0 * NP_VEC_HIST_HALF)
        a->above++;
    else
        a->bin[(unsigned)bin]++;
}

/* --- One vector --- */

static void put_words(FILE *out, const np_vec_col *cols, unsigned n, const uint64_t *w)
{
    for (unsigned k = 0; k < n; k++)
        fprintf(out, "%s%0*llx", k ? " " : "", (int)cols[k].digits, (unsigned long long)w[k]);
}

static void report(verifier *v, const np_vec_rec *rec, const uint64_t *got, const why *w)
{
    np_vec_col cols[NP_VEC_MAX_COLS];
    unsigned ni = np_vec_columns(v->h, NP_VEC_M_IN, cols);
    fprintf(v->out, "%s:%llu: vector %llu: ", v->name, (unsigned long long)rec->line,
            (unsigned long long)rec->index);
    put_words(v->out, cols, ni, rec->w[NP_VEC_IN]);
    unsigned no = np_vec_columns(v->h, NP_VEC_M_OUT, cols);
    fputs(" => ", v->out);
    put_words(v->out, cols, no, got);
    fputs(" expected: ", v->out);
    put_words(v->out, cols, no, rec->w[NP_VEC_OUT]);
    fprintf(v->out, "  (%s)\n", w->s);
}

static void check_latency(verifier *v, const np_vec_timing *t, why *w)
{
    if (t->clocks >= t->latency && t->clocks <= t->latency + t->stalls) {
        v->exact_latency += t->stalls == 0;
        return;
    }
    if (t->stalls == 0)
        why_add(w, "latency: output %llu clocks after its input with no stall in between, expected %u",
                (unsigned long long)t->clocks, t->latency);
    else
        why_add(w, "latency: output %llu clocks after its input, expected %u plus at most %llu stall cycles",
                (unsigned long long)t->clocks, t->latency, (unsigned long long)t->stalls);
}

/*
 * Check one transaction: got are the outputs under test, t their timing
 * (NULL for a device). Returns 1 when the error limit is reached.
 */
static int check(verifier *v, const np_vec_rec *rec, const uint64_t *got, const np_vec_timing *t)
{
    const np_unit_fields *F = &v->h->fields;
    uint64_t model[NP_UNIT_MAX_FIELDS], ref[NP_UNIT_MAX_FIELDS];
    why w = { .at = 0 };
    w.s[0] = '\0';
    np_vec_compute(v->h, rec->w[NP_VEC_IN], model, ref);
    if ((++v->tests & 0xffffu) == 0)
        np_progress_update(&v->progress, v->tests);
    for (unsigned k = 0; k < F->n_out; k++) {
        const np_field *f = &F->out[k];
        double r = np_vec_ref_value(ref[k]);
        if (model[k] != rec->w[NP_VEC_OUT][k])
            why_add(&w, "%s: the file's expected value disagrees with the bit-exact model, which gives %0*llx: corrupted or misconfigured vector file",
                    f->name, (int)((f->bits + 3u) / 4u), (unsigned long long)model[k]);
        if (ref[k] != rec->w[NP_VEC_REF][k])
            why_add(&w, "%s.ref %016llx disagrees with the float reference %016llx (%.17g): corrupted vector file",
                    f->name, (unsigned long long)rec->w[NP_VEC_REF][k], (unsigned long long)ref[k], r);
        if (got[k] != rec->w[NP_VEC_OUT][k])
            why_add(&w, "%s: bit mismatch, got ^ expected = %llx", f->name,
                    (unsigned long long)(got[k] ^ rec->w[NP_VEC_OUT][k]));
        double e = err_lsb(f, got[k], r);
        if (!(fabs(e) <= v->tol))
            why_add(&w, "%s: accuracy: |error| %.4f LSB > tolerance %g LSB (reference %.10f)", f->name,
                    fabs(e), v->tol, r);
        acc_add(&v->acc[k], f, got[k], r, e, rec->index);
    }
    if (t)
        check_latency(v, t, &w);
    if (!w.at)
        return 0;
    v->errors++;
    report(v, rec, got, &w);
    if (v->o->max_errors && v->errors >= v->o->max_errors) {
        v->stopped = 1;
        return 1;
    }
    return 0;
}

/* --- Summary --- */

static void print_histogram(FILE *out, const np_vec_acc *a)
{
    int lo = -1, hi = -1;
    uint64_t top = a->below > a->above ? a->below : a->above;
    for (int k = 0; k < 2 * NP_VEC_HIST_HALF; k++)
        if (a->bin[k]) {
            if (lo < 0)
                lo = k;
            hi = k;
            top = a->bin[k] > top ? a->bin[k] : top;
        }
    fputs("  histogram of (output - reference) in LSB, 1/8-LSB bins:\n", out);
    if (a->below)
        fprintf(out, "    %-18s %10llu\n", "< -4", (unsigned long long)a->below);
    for (int k = lo; lo >= 0 && k <= hi; k++) {
        char range[32];
        unsigned bar = (unsigned)((a->bin[k] * 40u + top - 1u) / top);
        snprintf(range, sizeof range, "[%+.3f, %+.3f)", (k - NP_VEC_HIST_HALF) / 8.0,
                 (k - NP_VEC_HIST_HALF + 1) / 8.0);
        fprintf(out, "    %-18s %10llu %.*s\n", range, (unsigned long long)a->bin[k], (int)bar,
                "########################################");
    }
    if (a->above)
        fprintf(out, "    %-18s %10llu\n", ">= +4", (unsigned long long)a->above);
}

static void print_summary(const verifier *v, const np_vec_drive_stats *ds)
{
    const np_unit *u = v->h->unit;
    for (unsigned k = 0; k < v->h->fields.n_out; k++) {
        const np_field *f = &v->h->fields.out[k];
        const np_vec_acc *a = &v->acc[k];
        if (!a->n)
            continue;
        fprintf(v->out, "error of %s (%s, 1 LSB = 2^-%u) against the float reference, %llu outputs:\n",
                f->name, f->format, f->frac, (unsigned long long)a->n);
        fprintf(v->out, "  max |error| %.4f LSB at vector %llu; tolerance %g LSB, bound of the error argument %.4f LSB\n",
                a->max_abs, (unsigned long long)a->max_index, v->tol, u->error_bound_lsb(&v->h->cfg));
        fprintf(v->out, "  correctly rounded (round half up): %llu of %llu (%.2f%%)\n",
                (unsigned long long)a->rounded, (unsigned long long)a->n,
                100.0 * (double)a->rounded / (double)a->n);
        print_histogram(v->out, a);
    }
    if (ds)
        fprintf(v->out, "cycle model: latency %u clocks, exact on the %llu transactions that met no output stall; "
                        "%llu cycles, %llu input bubbles, %llu output stalls\n",
                ds->latency, (unsigned long long)v->exact_latency, (unsigned long long)ds->cycles,
                (unsigned long long)ds->bubbles, (unsigned long long)ds->stalls);
}

static void print_verdict(const verifier *v, const char *against)
{
    fprintf(v->out, "In %llu tests, ", (unsigned long long)v->tests);
    if (v->errors)
        fprintf(v->out, "%llu error%s found", (unsigned long long)v->errors, v->errors == 1 ? "" : "s");
    else
        fputs("no errors found", v->out);
    fprintf(v->out, " in %s (%s) %s", v->h->unit->name, v->h->cfg_text, against);
    if (v->stopped)
        fprintf(v->out, ", stopped after %llu errors", (unsigned long long)v->errors);
    fputs(".\n", v->out);
}

/* --- The two sources of outputs --- */

static int sink_check(void *ctx, const np_vec_rec *rec, const uint64_t *out, const np_vec_timing *t)
{
    return check(ctx, rec, out, t);
}

/* Outputs from the cycle-accurate model. NP_EXIT_USAGE on bad input. */
static int verify_pipe(verifier *v, np_vec_reader *r, np_vec_drive_stats *ds)
{
    char err[NP_VEC_ERRLEN];
    int rc = np_vec_drive(v->h, np_vec_read_source, r, sink_check, v, v->o->traffic, v->o->seed, ds, err,
                          sizeof err);
    if (rc == NP_DRIVE_BAD_INPUT) {
        np_err(v->o->cmd, "%s", r->L.err);
        return NP_EXIT_USAGE;
    }
    if (rc == NP_DRIVE_MODEL) {
        fprintf(v->out, "%s: cycle model failure: %s\n", v->name, err);
        v->errors++;
    }
    return NP_EXIT_OK;
}

/*
 * Outputs from a device: the results file (when results != NULL, read in
 * step with the vectors, and exactly as long) or the GOT columns.
 * NP_EXIT_USAGE on bad input.
 */
static int verify_device(verifier *v, np_vec_reader *r, const char *results)
{
    np_vec_results rr;
    np_vec_rec rec;
    int n, m = 1;
    memset(&rec, 0, sizeof rec);
    if (results && np_vec_results_open(&rr, results, &r->h) != 0) {
        np_err(v->o->cmd, "%s", rr.L.err);
        np_vec_results_close(&rr);
        return NP_EXIT_USAGE;
    }
    while ((n = np_vec_read(r, &rec)) == 1) {
        if (results && (m = np_vec_results_read(&rr, &rec)) != 1)
            break;
        if (check(v, &rec, rec.w[NP_VEC_GOT], NULL))
            break;
    }
    if (results && n == 0 && np_vec_results_read(&rr, &rec) != 0)
        m = -1; /* the results go on after the last vector, or end in a bad line */
    if (n < 0)
        np_err(v->o->cmd, "%s", r->L.err);
    else if (m != 1)
        np_err(v->o->cmd, "%s", rr.L.err);
    if (results)
        np_vec_results_close(&rr);
    return n < 0 || m != 1 ? NP_EXIT_USAGE : NP_EXIT_OK;
}

int np_verify(const char *path, const np_verify_opts *o, FILE *out)
{
    np_vec_reader r;
    verifier v;
    np_vec_drive_stats ds;
    char against[4200];
    memset(&v, 0, sizeof v);
    if (np_vec_open(&r, path) != 0) {
        np_err(o->cmd, "%s", r.L.err);
        np_vec_close(&r);
        return NP_EXIT_USAGE;
    }
    int rc = NP_EXIT_USAGE;
    if (r.h.count == 0)
        np_err(o->cmd, "%s: the header declares 0 vectors: nothing to verify", r.L.name);
    else if (o->results && r.h.has_got)
        np_err(o->cmd, "%s: the vector lines already carry device results; drop --results", r.L.name);
    else {
        v.o = o;
        v.h = &r.h;
        v.name = r.L.name;
        v.out = out;
        v.tol = o->tolerance < 0 ? r.h.unit->tolerance_lsb : o->tolerance;
        int dev = o->results || r.h.has_got;
        np_progress_start(&v.progress, o->cmd, r.h.count);
        rc = dev ? verify_device(&v, &r, o->results) : verify_pipe(&v, &r, &ds);
        np_progress_end(&v.progress);
        if (o->results)
            snprintf(against, sizeof against, "in the device results of %s", o->results);
        else if (dev)
            snprintf(against, sizeof against, "in the device results carried by the vector lines");
        else
            snprintf(against, sizeof against, "on the cycle model (%s)",
                     o->traffic ? "random bubbles and stalls" : "no bubbles, no stalls");
        if (rc == NP_EXIT_OK) {
            print_summary(&v, dev ? NULL : &ds);
            print_verdict(&v, against);
            rc = v.errors ? NP_EXIT_FAIL : NP_EXIT_OK;
        }
    }
    np_vec_close(&r);
    return rc;
}
