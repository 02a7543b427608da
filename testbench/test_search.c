/* SPDX-License-Identifier: MIT */
/*
 * The adversarial search (src/sweep/np_search.h, docs/search.md): the
 * counterexamples of issue 10 found again in a CI budget and pinned, the
 * defaults faithful by proof with no counterexample, the same bits for any
 * thread count, the journal (resumed to the same bits; refused when damaged
 * or another run's).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "np_crc32.h"
#include "np_search.h"
#include "np_test.h"
#include "np_unit.h"

/* The CI budget of the named cases: a few seconds on one core. */
enum { CI_BUDGET = 262144 };

static const np_unit *configure(const char *unit, np_unit_cfg *cfg, const char *spec)
{
    const np_unit *u = np_unit_find(unit);
    char err[256];
    NP_CHECK(u != NULL, "unit %s", unit);
    if (u)
        NP_CHECK(np_unit_configure(u, cfg, spec, err, sizeof err) == 0, "%s", err);
    return u;
}

static int search(const np_unit *u, const void *cfg, uint64_t n, unsigned threads, np_search_result *r)
{
    np_search_opts o;
    char err[256];
    memset(&o, 0, sizeof o);
    o.unit = u;
    o.cfg = cfg;
    o.n = n;
    o.seed = 1;
    o.threads = threads;
    int rc = np_search_run(&o, r, err, sizeof err);
    NP_CHECK(rc == 0, "%s", err);
    return rc;
}

/* The error of field k at one input, in that field's LSB; the output and the true value too. */
static double field_error(const np_unit *u, const void *cfg, const uint16_t in16[3], unsigned k, double *got,
                          double *want)
{
    np_unit_fields f;
    uint64_t in[NP_UNIT_MAX_FIELDS] = { in16[0], in16[1], in16[2] }, out[NP_UNIT_MAX_FIELDS];
    double ref[NP_UNIT_MAX_FIELDS];
    u->fields(cfg, &f);
    u->eval(cfg, in, out);
    u->ref(cfg, in, ref);
    double sc = ldexp(1.0, (int)f.out[k].frac);
    *got = np_unit_field_value(&f.out[k], out[k]) * sc;
    *want = ref[k] * sc;
    return fabs(*got - *want);
}

static void print_result(const char *what, const np_search_result *r)
{
    char v[160];
    np_search_verdict_text(r, v, sizeof v);
    printf("%s: %llu inputs, %llu over 1 LSB, max error %.6f LSB at (0x%04x, 0x%04x, 0x%04x, 0x%04x, 0x%04x), "
           "bound %.4f LSB: %s\n",
           what, (unsigned long long)r->total.n, (unsigned long long)r->total.over, r->worst.err, r->worst.in[0],
           r->worst.in[1], r->worst.in[2], r->worst.in[3], r->worst.in[4], r->bound, v);
}

/*
 * A configuration the issue reports not faithful: its pinned counterexample
 * (field k at in: the model's output and the true value, in LSB) is over
 * 1 LSB, and the search finds one (maybe another) in the CI budget.
 */
static void counterexample(const char *unit, const char *spec, const uint16_t in[3], unsigned k, double got_lsb,
                           double want_lsb, double err_lsb)
{
    np_unit_cfg cfg;
    const np_unit *u = configure(unit, &cfg, spec);
    if (!u)
        return;
    double got, want, e = field_error(u, &cfg, in, k, &got, &want);
    printf("%s %s: pinned (0x%04x, 0x%04x, 0x%04x): output %.0f LSB, true %.6f LSB, error %.6f LSB\n", unit, spec,
           in[0], in[1], in[2], got, want, e);
    NP_CHECK(got == got_lsb && fabs(want - want_lsb) < 5e-7 && fabs(e - err_lsb) < 5e-7,
             "pinned counterexample moved: output %.0f, true %.7f, error %.7f", got, want, e);
    NP_CHECK(e > 1.0, "the pinned input is not over 1 LSB");
    np_search_result r;
    if (search(u, &cfg, CI_BUDGET, 0, &r) != 0)
        return;
    print_result(spec, &r);
    NP_CHECK(r.verdict == NP_SEARCH_COUNTEREXAMPLE && r.total.over > 0 && r.worst.err > 1.0,
             "the search of %u inputs found no counterexample for %s %s", CI_BUDGET, unit, spec);
}

/* Issue 10: the 28,578-gate "measured faithful" point, 1.0459 LSB at the issue's own input. */
static int t_classic3_s8_l9(void)
{
    static const uint16_t issue[3] = { 0xe6db, 0x2a83, 0x07db };
    counterexample("classic3", "s_frac=8,lerp_frac=9", issue, 0, 33.0, 31.9541339, 1.0458661);
    return 0;
}

static int t_classic3_s9_l8(void)
{
    static const uint16_t found[3] = { 0x0808, 0xdd08, 0xdb05 }; /* noisepipe search, seed 1, 262144 inputs */
    counterexample("classic3", "s_frac=9,lerp_frac=8", found, 0, 0.0, -1.0314149, 1.0314149);
    return 0;
}

static int t_simplex3_t19_p19(void)
{
    static const uint16_t found[3] = { 0xd46c, 0xb555, 0xb924 }; /* noisepipe search, seed 1, 200000 inputs: df/dx */
    counterexample("simplex3", "t_frac=19,p_frac=19", found, 1, -5733.0, -5734.0418468, 1.0418468);
    return 0;
}

/*
 * The design space's cheapest simplex3 point without a counterexample in its
 * 262,144-input search: the documented 10^8 run (docs/search.md) found 404
 * inputs over 1 LSB; its worst, checked here without a search.
 */
static int t_simplex3_t19_p21_pinned(void)
{
    static const uint16_t in[3] = { 0x6c08, 0x6a08, 0xf760 };
    np_unit_cfg cfg;
    const np_unit *u = configure("simplex3", &cfg, "t_frac=19,p_frac=21");
    if (!u)
        return 0;
    double got, want, e = field_error(u, &cfg, in, 2, &got, &want);
    printf("simplex3 t_frac=19 p_frac=21 at (0x6c08, 0x6a08, 0xf760): df/dy %.0f LSB, true %.6f LSB, error %.6f LSB\n",
           got, want, e);
    NP_CHECK(got == -11446.0 && fabs(want + 11447.0610780) < 5e-7 && e > 1.0, "pinned counterexample moved");
    return 0;
}

/* The defaults: proved faithful by their bound, and the search agrees (none over, max within the bound). */
static int t_defaults_faithful(void)
{
    static const char *const units[2] = { "classic3", "simplex3" };
    for (unsigned i = 0; i < 2; i++) {
        np_unit_cfg cfg;
        const np_unit *u = configure(units[i], &cfg, NULL);
        np_search_result r;
        if (!u || search(u, &cfg, CI_BUDGET, 0, &r) != 0)
            continue;
        print_result(units[i], &r);
        NP_CHECK(r.verdict == NP_SEARCH_PROVED && r.bound <= 1.0, "%s default: not faithful (proved)", units[i]);
        NP_CHECK(r.total.over == 0 && r.worst.err <= r.bound, "%s default: error %.6f over its bound %.6f",
                 units[i], r.worst.err, r.bound);
        NP_CHECK(r.total.n == CI_BUDGET, "%s: %llu inputs, budget %u", units[i], (unsigned long long)r.total.n,
                 CI_BUDGET);
    }
    return 0;
}

/* Each class of inputs is present, the unit's own classes included. */
static int t_classes(void)
{
    np_unit_cfg cfg;
    const np_unit *u = configure("simplex3", &cfg, NULL);
    np_search_result r;
    if (!u || search(u, &cfg, 131072, 0, &r) != 0)
        return 0;
    for (unsigned c = 0; c < NP_SEARCH_CLASSES; c++) {
        printf("%-28s %llu inputs, max %.6f LSB\n", np_search_class_name[c], (unsigned long long)r.total.cls_n[c],
               r.total.cls_max[c]);
        NP_CHECK(r.total.cls_n[c] > 0, "class %s empty", np_search_class_name[c]);
    }
    return 0;
}

static int same_result(const np_search_result *a, const np_search_result *b)
{
    return np_search_stats_equal(&a->total, &b->total) && a->verdict == b->verdict &&
           memcmp(a->worst.in, b->worst.in, sizeof a->worst.in) == 0 &&
           memcmp(&a->worst.err, &b->worst.err, sizeof a->worst.err) == 0;
}

/* One, two and three threads: the same statistics, bit for bit (doubles included). */
static int t_threads(void)
{
    np_unit_cfg cfg;
    const np_unit *u = configure("classic3", &cfg, "s_frac=9,lerp_frac=8");
    np_search_result r1, r2, r3;
    if (!u || search(u, &cfg, 100000, 1, &r1) || search(u, &cfg, 100000, 2, &r2) || search(u, &cfg, 100000, 3, &r3))
        return 0;
    print_result("1 thread", &r1);
    print_result("3 threads", &r3);
    NP_CHECK(same_result(&r1, &r2) && same_result(&r1, &r3), "the thread count changed the result");
    return 0;
}

/* The whole file at path into buf (at most len bytes): its size. */
static size_t slurp(const char *path, char *buf, size_t len)
{
    FILE *f = fopen(path, "rb");
    size_t n = f ? fread(buf, 1, len, f) : 0;
    if (f)
        fclose(f);
    return n;
}

static void spit(const char *path, const char *buf, size_t n)
{
    FILE *f = fopen(path, "wb");
    NP_CHECK(f != NULL, "cannot write %s", path);
    if (f) {
        fwrite(buf, 1, n, f);
        fclose(f);
    }
}

/* The byte offset just after line `lines` (counting from 1) of buf[0..n), or n. */
static size_t after_line(const char *buf, size_t n, unsigned lines)
{
    size_t at = 0;
    for (unsigned seen = 0; at < n && seen < lines; at++)
        seen += buf[at] == '\n';
    return at;
}

/* The byte offset just after the k-th line that starts with "worst" (the end of the k-th record), or n. */
static size_t after_record(const char *buf, size_t n, unsigned k)
{
    size_t at = 0;
    for (unsigned seen = 0; at < n && seen < k;) {
        seen += strncmp(buf + at, "worst", 5) == 0;
        at = after_line(buf + at, n - at, 1) + at;
    }
    return at;
}

/* A name for a new file from the mkstemp template path (the file is not left behind). 0, or -1. */
static int free_path(char *path)
{
    int fd = mkstemp(path);
    NP_CHECK(fd >= 0, "mkstemp %s", path);
    if (fd < 0)
        return -1;
    close(fd);
    remove(path);
    return 0;
}

static np_search_opts journal_opts(const np_unit *u, const void *cfg, const char *path)
{
    np_search_opts o;
    memset(&o, 0, sizeof o);
    o.unit = u;
    o.cfg = cfg;
    o.n = 65536;
    o.seed = 7;
    o.journal = path;
    return o;
}

/*
 * A journal: a run cut short (its records dropped after the fourth; then a
 * torn record: the fifth's chunk line whole, its field line cut) resumes
 * to the same bits.
 */
static int t_journal_resume(void)
{
    np_unit_cfg cfg;
    const np_unit *u = configure("classic3", &cfg, NULL);
    if (!u)
        return 0;
    char path[] = "/tmp/np_search_journal_XXXXXX";
    if (free_path(path) != 0)
        return 0;
    np_search_opts o = journal_opts(u, &cfg, path);
    np_search_result full, again;
    char err[512];
    NP_CHECK(np_search_run(&o, &full, err, sizeof err) == 0, "%s", err);
    NP_CHECK(np_search_run(&o, &again, err, sizeof err) != 0 && strstr(err, "exists"), "an existing journal "
             "was overwritten: %s", err);
    static char buf[1 << 16];
    size_t n = slurp(path, buf, sizeof buf);
    size_t cut = after_record(buf, n, 4);
    size_t torn = after_line(buf + cut, n - cut, 1) + cut + 20;
    NP_CHECK(torn < n, "the journal has fewer than 6 records");
    spit(path, buf, torn < n ? torn : n);
    o.resume = 1;
    NP_CHECK(np_search_run(&o, &again, err, sizeof err) == 0, "%s", err);
    printf("resumed %llu of %llu chunks\n", (unsigned long long)again.chunks_resumed,
           (unsigned long long)again.chunks);
    NP_CHECK(again.chunks_resumed == 4, "resumed %llu chunks, expected 4", (unsigned long long)again.chunks_resumed);
    NP_CHECK(same_result(&full, &again), "a resumed search differs from the whole one");
    /* Resumed again, every chunk comes from the journal: still the same bits. */
    NP_CHECK(np_search_run(&o, &again, err, sizeof err) == 0, "%s", err);
    NP_CHECK(again.chunks_resumed == again.chunks, "resumed %llu of %llu chunks the second time",
             (unsigned long long)again.chunks_resumed, (unsigned long long)again.chunks);
    NP_CHECK(same_result(&full, &again), "a search resumed from a whole journal differs from the whole one");
    remove(path);
    return 0;
}

/*
 * A journal that is not this run's, or cannot be trusted, is refused with
 * a message: a damaged middle line with its line number, each binding of
 * another run (unit, configuration, seed, budget) named, a record line that
 * checks but does not parse, the format before np_jfile.
 */
static int t_journal_refuse(void)
{
    np_unit_cfg cfg, other;
    const np_unit *u = configure("classic3", &cfg, NULL);
    const np_unit *simplex = configure("simplex3", &other, NULL);
    if (!u || !simplex)
        return 0;
    char path[] = "/tmp/np_search_refuse_XXXXXX";
    if (free_path(path) != 0)
        return 0;
    np_search_opts o = journal_opts(u, &cfg, path);
    np_search_result r;
    char err[512];
    NP_CHECK(np_search_run(&o, &r, err, sizeof err) == 0, "%s", err);
    static char good[1 << 16], bad[1 << 16];
    size_t n = slurp(path, good, sizeof good);
    o.resume = 1;

    /* Line 8, a class line in the middle of the first record: one digit changed. */
    memcpy(bad, good, n);
    size_t at = after_line(bad, n, 7);
    char *digit = strpbrk(bad + at, "0123456789");
    NP_CHECK(digit != NULL && digit < bad + after_line(bad, n, 8), "no digit on line 8");
    if (digit)
        *digit = *digit == '9' ? '8' : (char)(*digit + 1);
    spit(path, bad, n);
    NP_CHECK(np_search_run(&o, &r, err, sizeof err) != 0 && strstr(err, ":8: malformed or damaged line"),
             "a damaged line 8 was not refused with its number: %s", err);
    printf("damaged line: %s\n", err);
    spit(path, good, n);

    struct {
        const char *what, *named;
        const np_unit *u;
        const void *cfg;
        uint64_t seed, n;
    } mismatch[] = {
        { "another unit", "was written for 'unit=classic3'", simplex, &other, 7, 65536 },
        { "another seed", "was written for 'seed=7', this run is 'seed=8'", u, &cfg, 8, 65536 },
        { "another budget", "was written for 'n=65536', this run is 'n=65537'", u, &cfg, 7, 65537 },
    };
    np_unit_cfg cheap;
    if (np_unit_configure(u, &cheap, "s_frac=10", err, sizeof err) == 0) {
        o.cfg = &cheap;
        NP_CHECK(np_search_run(&o, &r, err, sizeof err) != 0 && strstr(err, "was written for 'config=") &&
                     strstr(err, "s_frac=12") && strstr(err, "this run is 'config=") && strstr(err, "s_frac=10"),
                 "another config was not refused naming config=: %s", err);
        printf("another config: %s\n", err);
        o.cfg = &cfg;
    }
    for (unsigned k = 0; k < sizeof mismatch / sizeof mismatch[0]; k++) {
        np_search_opts m = o;
        m.unit = mismatch[k].u;
        m.cfg = mismatch[k].cfg;
        m.seed = mismatch[k].seed;
        m.n = mismatch[k].n;
        NP_CHECK(np_search_run(&m, &r, err, sizeof err) != 0 && strstr(err, mismatch[k].named) &&
                     strstr(err, "not resuming"),
                 "%s was not refused naming it: %s", mismatch[k].what, err);
        printf("%s: %s\n", mismatch[k].what, err);
    }
    NP_CHECK(slurp(path, bad, sizeof bad) == n && memcmp(bad, good, n) == 0, "a refused journal was changed");

    /* A record line with a good checksum that does not parse: a chunk index past the budget's. */
    char line[128];
    int len = snprintf(line, sizeof line, "chunk 99999 n=4096 over=0 cr=4096");
    unsigned lineno = 1;
    for (size_t i = 0; i < n; i++)
        lineno += good[i] == '\n';
    memcpy(bad, good, n);
    n += (size_t)snprintf(bad + n, sizeof bad - n, "%s *%08x\n", line, (unsigned)np_crc32(0, line, (size_t)len));
    spit(path, bad, n);
    char where[32];
    snprintf(where, sizeof where, ":%u: malformed chunk line", lineno);
    NP_CHECK(np_search_run(&o, &r, err, sizeof err) != 0 && strstr(err, where),
             "a malformed chunk line was not refused with its number %u: %s", lineno, err);
    printf("malformed record: %s\n", err);

    /* The format before np_jfile (FNV-1a check= lines) is named, not read. */
    static const char v1[] = "noisepipe-search-journal 1\nunit classic3\n";
    spit(path, v1, sizeof v1 - 1);
    NP_CHECK(np_search_run(&o, &r, err, sizeof err) != 0 && strstr(err, "has format 'noisepipe-search-journal 1'"),
             "a format 1 journal was not refused by name: %s", err);
    printf("format 1: %s\n", err);
    remove(path);
    return 0;
}

/* --- n-input units (n = 2, 4, 5: issue 18's simplexn and classicn) --- */

static const char *const ndim_units[6] = { "simplex2", "simplex4", "simplex5", "classic2", "classic4", "classic5" };

/*
 * Every n-D default: proved faithful by its bound, and the search over all
 * its classes (extremes 12^n, lattice, faces of every size, worst rounding
 * through the fine output, random, climb) finds nothing over it; the worst
 * input has the unit's n words.
 */
static int t_ndim_defaults(void)
{
    for (unsigned i = 0; i < 6; i++) {
        np_unit_cfg cfg;
        const np_unit *u = configure(ndim_units[i], &cfg, NULL);
        np_search_result r;
        np_unit_fields f;
        if (!u || search(u, &cfg, 131072, 0, &r) != 0)
            continue;
        u->fields(&cfg, &f);
        print_result(ndim_units[i], &r);
        NP_CHECK(r.dims == f.n_in && f.n_in != 3, "%s: dims %u, %u inputs", ndim_units[i], r.dims, f.n_in);
        NP_CHECK(u->fine_cfg != NULL, "%s: no finer output for the climb and the rounding class", ndim_units[i]);
        NP_CHECK(r.verdict == NP_SEARCH_PROVED && r.total.over == 0 && r.worst.err <= r.bound,
                 "%s default: error %.6f, bound %.6f, %llu over", ndim_units[i], r.worst.err, r.bound,
                 (unsigned long long)r.total.over);
        for (unsigned c = 0; c < NP_SEARCH_CLASSES; c++)
            NP_CHECK(r.total.cls_n[c] > 0, "%s: class %s empty", ndim_units[i], np_search_class_name[c]);
        for (unsigned a = f.n_in; a < NP_SEARCH_MAX_IN; a++)
            NP_CHECK(r.worst.in[a] == 0, "%s: word %u of the worst input set", ndim_units[i], a);
    }
    return 0;
}

/*
 * Narrow n-D configurations are caught: the counterexample printed with the
 * unit's n words, over 1 LSB when evaluated again; the same bits on one and
 * two threads; a 4-D journal resumes to the same bits.
 */
static int t_ndim_counterexample(void)
{
    static const struct {
        const char *unit, *cfg;
    } bad[] = { { "simplex4", "out_bits=12,t_frac=8,p_frac=8" }, { "classic2", "out_bits=8,s_frac=4,lerp_frac=6" } };
    for (unsigned i = 0; i < 2; i++) {
        np_unit_cfg cfg;
        const np_unit *u = configure(bad[i].unit, &cfg, bad[i].cfg);
        np_search_result r1, r2;
        if (!u || search(u, &cfg, 16384, 1, &r1) != 0 || search(u, &cfg, 16384, 2, &r2) != 0)
            continue;
        char v[160];
        np_search_verdict_text(&r1, v, sizeof v);
        printf("%s %s: %s (error %.4f LSB)\n", bad[i].unit, bad[i].cfg, v, r1.worst.err);
        np_unit_fields f;
        u->fields(&cfg, &f);
        uint64_t in[NP_UNIT_MAX_FIELDS] = { 0 }, out[NP_UNIT_MAX_FIELDS];
        double ref[NP_UNIT_MAX_FIELDS];
        for (unsigned a = 0; a < f.n_in; a++)
            in[a] = r1.worst.in[a];
        u->eval(&cfg, in, out);
        u->ref(&cfg, in, ref);
        double e = fabs(np_unit_field_value(&f.out[0], out[0]) - ref[0]) * ldexp(1.0, (int)f.out[0].frac);
        unsigned commas = 0;
        for (const char *p = v; *p; p++)
            commas += *p == ',';
        NP_CHECK(r1.verdict == NP_SEARCH_COUNTEREXAMPLE && e > 1.0 && e == r1.worst.err,
                 "%s %s: verdict %d, error again %.4f", bad[i].unit, bad[i].cfg, (int)r1.verdict, e);
        NP_CHECK(commas == f.n_in, "%s: '%s' does not name %u words", bad[i].unit, v, f.n_in);
        NP_CHECK(same_result(&r1, &r2), "%s: the thread count changed the result", bad[i].unit);
    }
    np_unit_cfg cfg;
    const np_unit *u = configure("simplex4", &cfg, NULL);
    char path[] = "/tmp/np_search_journal4_XXXXXX";
    if (!u || free_path(path) != 0)
        return 0;
    np_search_opts o = journal_opts(u, &cfg, path);
    np_search_result full, again;
    char err[512];
    NP_CHECK(np_search_run(&o, &full, err, sizeof err) == 0, "%s", err);
    static char buf[1 << 16];
    size_t n = slurp(path, buf, sizeof buf);
    NP_CHECK(strstr(buf, "at=0x") != NULL && n > 0, "no field line in the 4-D journal");
    spit(path, buf, after_record(buf, n, 3));
    o.resume = 1;
    NP_CHECK(np_search_run(&o, &again, err, sizeof err) == 0, "%s", err);
    NP_CHECK(again.chunks_resumed == 3 && same_result(&full, &again), "4-D journal: resumed %llu chunks, same %d",
             (unsigned long long)again.chunks_resumed, same_result(&full, &again));
    remove(path);
    return 0;
}

static const np_test_case cases[] = {
    { "classic3_s8_l9_counterexample", t_classic3_s8_l9 },
    { "classic3_s9_l8_counterexample", t_classic3_s9_l8 },
    { "simplex3_t19_p19_counterexample", t_simplex3_t19_p19 },
    { "simplex3_t19_p21_pinned", t_simplex3_t19_p21_pinned },
    { "defaults_faithful", t_defaults_faithful },
    { "classes", t_classes },
    { "threads", t_threads },
    { "journal_resume", t_journal_resume },
    { "journal_refuse", t_journal_refuse },
    { "ndim_defaults", t_ndim_defaults },
    { "ndim_counterexample", t_ndim_counterexample },
    { NULL, NULL },
};

NP_TEST_MAIN(cases)
