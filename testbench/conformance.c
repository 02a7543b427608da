/* SPDX-License-Identifier: MIT */
/* The unit-conformance checks (np_conformance.h), over the registry only. */
#include "np_conformance.h"

#include <dirent.h>
#include <inttypes.h>
#include <stdlib.h>
#include <string.h>

#include "np_kat.h"
#include "np_rng.h"
#include "np_stream.h"
#include "np_test.h"
#include "np_vec.h"
#include "np_widths.h"
#include "span_test.h"

/* Random cases added to the generator's for the width trace: the default, each other configuration. */
enum { MAX_CONFIGS = 8, MAX_OPS = 256, WIDTH_RANDOM = 100000, WIDTH_RANDOM_OTHER = 40000 };
/* The span units' width trace draws its random cases from np_rng seeded with this. */
static const uint64_t WIDTH_SEED = 43;

/* The default ("") then the unit's conformance configurations; returns how many. */
static unsigned configs_of(const np_unit *u, const char *out[MAX_CONFIGS])
{
    unsigned n = 0;
    out[n++] = "";
    for (const char *const *c = u->conformance_configs; c && *c && n < MAX_CONFIGS; c++)
        out[n++] = *c;
    return n;
}

static int header(np_vec_header *h, const np_unit *u, const char *spec)
{
    char err[NP_VEC_ERRLEN];
    int rc = np_vec_header_init(h, u, spec, err, sizeof err);
    NP_CHECK(rc == 0, "%s '%s': %s", u->name, spec, err);
    return rc;
}

static void work_path(char *buf, size_t len, const np_conf_env *e, const np_unit *u, const char *what)
{
    snprintf(buf, len, "%s/%s-%s", e->work_dir, u->name, what);
}

/* Byte for byte; 1 when equal. */
static int same_bytes(const char *a, const char *b)
{
    FILE *fa = fopen(a, "rb"), *fb = fopen(b, "rb");
    int same = fa && fb;
    while (same) {
        int ca = getc(fa), cb = getc(fb);
        same = ca == cb;
        if (ca == EOF)
            break;
    }
    if (fa)
        fclose(fa);
    if (fb)
        fclose(fb);
    return same;
}

/* --- cycle_vs_bitexact --- */

typedef struct cycle_sink {
    const np_vec_header *h;
    int is_stream;
    uint64_t n, bad, exact;
} cycle_sink;

static int cycle_put(void *ctx, const np_vec_rec *rec, const uint64_t *out, const np_vec_timing *t)
{
    cycle_sink *s = ctx;
    for (unsigned k = 0; k < s->h->fields.n_out; k++)
        if (out[k] != rec->w[NP_VEC_OUT][k]) {
            s->bad++;
            NP_CHECK(0, "%s transaction %" PRIu64 ": %s = %" PRIx64 ", bit-exact model %" PRIx64, s->h->unit->name,
                     rec->index, s->h->fields.out[k].name, out[k], rec->w[NP_VEC_OUT][k]);
        }
    NP_CHECK(rec->index == s->n, "%s: transaction %" PRIu64 " delivered as number %" PRIu64, s->h->unit->name,
             rec->index, s->n);
    if (!s->is_stream) {
        /* A pipe: exactly its latency when no output stall held the transaction, never faster. */
        NP_CHECK(t->clocks >= t->latency && t->clocks <= t->latency + t->stalls,
                 "%s transaction %" PRIu64 ": %" PRIu64 " clocks, latency %u, %" PRIu64 " stalls",
                 s->h->unit->name, rec->index, t->clocks, t->latency, t->stalls);
        if (t->stalls == 0) {
            NP_CHECK(t->clocks == t->latency, "%s transaction %" PRIu64 ": %" PRIu64 " clocks unstalled, latency %u",
                     s->h->unit->name, rec->index, t->clocks, t->latency);
            s->exact++;
        }
    }
    s->n++;
    return 0;
}

static int cycle_vs_bitexact(const np_unit *u, const np_conf_env *e)
{
    const char *cfgs[MAX_CONFIGS];
    unsigned nc = configs_of(u, cfgs);
    for (unsigned c = 0; c < nc; c++) {
        np_vec_header h;
        char err[NP_VEC_ERRLEN], path[4096], what[32];
        if (header(&h, u, cfgs[c]) != 0)
            continue;
        snprintf(what, sizeof what, "cycle%u.vec", c);
        work_path(path, sizeof path, e, u, what);
        np_vec_output o = { path, NP_VEC_TEXT };
        if (np_vec_generate(&h, 1, 1, UINT64_MAX, &o, 1, err, sizeof err) != 0) {
            NP_CHECK(0, "%s: %s", u->name, err);
            continue;
        }
        for (int traffic = 1; traffic >= 0; traffic--) {
            np_vec_reader r;
            if (np_vec_open(&r, path) != 0) {
                NP_CHECK(0, "%s", r.L.err);
                break;
            }
            cycle_sink s = { &r.h, u->stream != NULL, 0, 0, 0 };
            np_vec_drive_stats st;
            int rc = np_vec_drive(&r.h, np_vec_read_source, &r, cycle_put, &s, traffic, 100u + c, &st, err,
                                  sizeof err);
            NP_CHECK(rc == NP_DRIVE_DONE, "%s: drive: %d %s %s", u->name, rc, err, r.L.err);
            NP_CHECK(s.n == r.h.count && st.delivered == r.h.count, "%s: %" PRIu64 " of %" PRIu64 " delivered",
                     u->name, s.n, r.h.count);
            if (!u->stream && !traffic)
                NP_CHECK(st.cycles == r.h.count + st.latency && s.exact == s.n,
                         "%s: %" PRIu64 " transactions in %" PRIu64 " cycles unstalled, latency %u", u->name,
                         r.h.count, st.cycles, st.latency);
            printf("%s [%s]: %" PRIu64 " transactions %s: %" PRIu64 " cycles, %" PRIu64 " bubbles, %" PRIu64
                   " stall cycles, %" PRIu64 " mismatches%s\n",
                   u->name, h.cfg_text, s.n, traffic ? "with random bubbles and stalls" : "streamed", st.cycles,
                   st.bubbles, st.stalls, s.bad, u->stream ? "" : ", every unstalled one at the pipe's latency");
            np_vec_close(&r);
        }
        remove(path);
    }
    return 0;
}

/* --- datapath_widths --- */

typedef struct widths {
    const np_unit *u;
    const void *cfg;
    np_op ops[MAX_OPS];
    size_t n_ops;
    np_trace t[MAX_OPS];
    size_t n_t;
    np_pipe pipe;
    unsigned char *sig;
} widths;

/* Run the pipe's stages on one input, tracing after each; the bundle's outputs must be eval's. */
static void widths_input(widths *w, const np_vec_header *h, const uint64_t *in)
{
    memset(w->sig, 0, w->pipe.sig_size);
    w->u->sig_set_in(w->sig, in);
    for (unsigned k = 0; k < w->pipe.depth; k++) {
        w->pipe.stages[k].fn(w->pipe.cfg, w->sig);
        w->u->trace(w->cfg, k, w->sig, w->t, w->n_t);
    }
    uint64_t got[NP_UNIT_MAX_FIELDS], want[NP_UNIT_MAX_FIELDS];
    w->u->sig_get_out(w->cfg, w->sig, got);
    w->u->eval(w->cfg, in, want);
    for (unsigned k = 0; k < h->fields.n_out; k++)
        NP_CHECK(got[k] == want[k], "%s: stages and eval differ in %s", w->u->name, h->fields.out[k].name);
}

static void widths_config(const np_unit *u, const char *spec, int print)
{
    static widths w; /* large: kept off the stack */
    np_vec_header h;
    if (header(&h, u, spec) != 0)
        return;
    memset(&w, 0, sizeof w);
    w.u = u;
    w.cfg = &h.cfg;
    w.n_ops = u->datapath(&h.cfg, w.ops, MAX_OPS);
    NP_CHECK(w.n_ops <= MAX_OPS, "%s: declaration of %zu ops", u->name, w.n_ops);
    if (w.n_ops > MAX_OPS)
        return;
    w.n_t = np_widths_traces(w.ops, w.n_ops, w.t);
    if (u->pipe_init(&w.pipe, &h.cfg) != 0 || !(w.sig = malloc(w.pipe.sig_size))) {
        NP_CHECK(0, "%s: pipe init", u->name);
        return;
    }
    np_vecgen g;
    np_vec_rec rec;
    char err[NP_VEC_ERRLEN];
    uint64_t n = 0;
    if (np_vecgen_init(&g, &h, 1, 7, print ? WIDTH_RANDOM : WIDTH_RANDOM_OTHER, err, sizeof err) == 0) {
        for (; np_vecgen_next(&g, &rec); n++)
            widths_input(&w, &h, rec.w[NP_VEC_IN]);
        np_vecgen_free(&g);
    } else {
        NP_CHECK(0, "%s: %s", u->name, err);
    }
    char what[320];
    snprintf(what, sizeof what, "%s [%s]", u->name, h.cfg_text);
    unsigned bad = np_widths_judge(w.ops, w.n_ops, w.t, NP_CONF_WIDTH_MARGIN, what, print);
    printf("%s [%s]: %zu traced signals over %" PRIu64 " inputs: %s\n", u->name, h.cfg_text, w.n_t, n,
           bad ? "FAILED" : "every declared width holds, margin <= 1");
    free(w.sig);
    np_pipe_free(&w.pipe);
}

/*
 * A span unit: its engine's declaration for two register sets over their
 * full formats (span_wide_regs: 8 octaves and a 256-entry repeating table;
 * 3 octaves and a clamped one), since it holds for any registers, against
 * what the unit's span->trace drives through the engine's signals for them.
 */
static void widths_span(const np_unit *u, const char *spec, np_rng *g, int print)
{
    static widths w;
    np_vec_header h;
    if (header(&h, u, spec) != 0)
        return;
    const void *ecfg = np_unit_span_cfg(u->span, &h.cfg);
    for (int variant = 0; variant < 2; variant++) {
        np_tex_regs r = span_wide_regs(g, variant ? 3u : 8u, variant);
        char what[320];
        snprintf(what, sizeof what, "%s [%s], %s table", u->name, h.cfg_text, variant ? "clamped" : "repeating");
        w.n_ops = u->span->engine->datapath(ecfg, &r, w.ops, MAX_OPS);
        NP_CHECK(w.n_ops <= MAX_OPS, "%s: declaration of %zu ops", what, w.n_ops);
        if (w.n_ops > MAX_OPS)
            return;
        w.n_t = np_widths_traces(w.ops, w.n_ops, w.t);
        const char *why = u->span->trace(ecfg, &r, g, w.t, w.n_t);
        NP_CHECK(why == NULL, "%s: %s", what, why);
        unsigned bad = np_widths_judge(w.ops, w.n_ops, w.t, NP_CONF_WIDTH_MARGIN, what, print && variant == 0);
        printf("%s: %zu traced signals, %u octaves: %s\n", what, w.n_t, r.n_oct,
               bad || why ? "FAILED" : "every declared width holds, margin <= 1");
    }
}

static int datapath_widths(const np_unit *u, const np_conf_env *e)
{
    (void)e;
    const int span = u->span && u->span->trace;
    if (!u->datapath || !(span || (u->trace && !u->stream))) {
        printf("%s: skipped: %s\n", u->name,
               !u->datapath ? "no datapath declared (np_unit.datapath)"
               : u->span    ? "no trace of the engine's signals (np_unit_span.trace)"
                            : "no trace of the pipe's signals (np_unit.trace)");
        return NP_TEST_SKIP;
    }
    const char *cfgs[MAX_CONFIGS];
    unsigned nc = configs_of(u, cfgs);
    np_rng g;
    np_rng_seed(&g, WIDTH_SEED);
    for (unsigned c = 0; c < nc; c++) {
        if (span)
            widths_span(u, cfgs[c], &g, c == 0);
        else
            widths_config(u, cfgs[c], c == 0);
    }
    return 0;
}

/* --- cfg_roundtrip --- */

static int cfg_roundtrip(const np_unit *u, const np_conf_env *e)
{
    (void)e;
    const char *cfgs[MAX_CONFIGS];
    unsigned nc = configs_of(u, cfgs);
    for (unsigned c = 0; c < nc; c++) {
        np_vec_header a, b;
        if (header(&a, u, cfgs[c]) != 0 || header(&b, u, a.cfg_text) != 0)
            continue;
        NP_CHECK(strcmp(a.cfg_text, b.cfg_text) == 0, "%s: '%s' formats as '%s', which configures to '%s'", u->name,
                 cfgs[c], a.cfg_text, b.cfg_text);
        NP_CHECK(memcmp(&a.fields, &b.fields, sizeof a.fields) == 0, "%s '%s': fields differ after the round trip",
                 u->name, a.cfg_text);
        /* Same configuration, same bits: the boundary cases through both. */
        uint64_t (*in)[NP_UNIT_MAX_FIELDS] = calloc(4096, sizeof *in);
        size_t nb = in ? u->boundary(&a.cfg, in, 4096) : 0;
        for (size_t i = 0; i < nb && i < 4096; i++) {
            uint64_t oa[NP_UNIT_MAX_FIELDS], ob[NP_UNIT_MAX_FIELDS], ra[NP_UNIT_MAX_FIELDS], rb[NP_UNIT_MAX_FIELDS];
            np_vec_compute(&a, in[i], oa, ra);
            np_vec_compute(&b, in[i], ob, rb);
            NP_CHECK(memcmp(oa, ob, a.fields.n_out * sizeof oa[0]) == 0 &&
                         memcmp(ra, rb, a.fields.n_out * sizeof ra[0]) == 0,
                     "%s '%s': boundary case %zu differs after the round trip", u->name, a.cfg_text, i);
        }
        free(in);
        printf("%s: '%s' -> '%s' -> '%s'\n", u->name, cfgs[c], a.cfg_text, b.cfg_text);
    }
    /*
     * Every key of the table: its ends and its default, where the unit's
     * consistency check allows them, survive the round trip; one past the
     * top is refused naming the key (an enumeration takes words instead);
     * a key given twice is refused naming it.
     */
    unsigned keys = 0, values = 0;
    for (const np_unit_key *k = u->keys; k && k->name; k++, keys++) {
        unsigned v3[3] = { k->lo, k->hi, k->def };
        for (unsigned i = 0; i < 3 && !k->word; i++) {
            char spec[96], text[64];
            np_vec_header a, b;
            snprintf(spec, sizeof spec, "%s=%u", k->name, v3[i]);
            np_unit_cfg cfg;
            char why[256];
            if (np_unit_configure(u, &cfg, spec, why, sizeof why) != 0)
                continue; /* inconsistent with the other keys' defaults */
            if (header(&a, u, spec) != 0 || header(&b, u, a.cfg_text) != 0)
                continue;
            np_unit_key_text(k, &a.cfg, text, sizeof text);
            NP_CHECK(strcmp(a.cfg_text, b.cfg_text) == 0 && np_unit_key_get(k, &a.cfg) == v3[i],
                     "%s: %s gives '%s' (%s=%s), which configures to '%s'", u->name, spec, a.cfg_text, k->name, text,
                     b.cfg_text);
            values++;
        }
        char spec[256], why[256] = "";
        np_unit_cfg cfg;
        if (!k->word && k->hi < 4000000000u) {
            snprintf(spec, sizeof spec, "%s=%u", k->name, k->hi + 1u);
            NP_CHECK(np_unit_configure(u, &cfg, spec, why, sizeof why) != 0 && strstr(why, k->name),
                     "%s: %s accepted or the refusal does not name the key: '%s'", u->name, spec, why);
        }
        np_vec_header d;
        if (header(&d, u, "") == 0) {
            char val[64];
            np_unit_key_text(k, &d.cfg, val, sizeof val);
            snprintf(spec, sizeof spec, "%s=%s,%s=%s", k->name, val, k->name, val);
            NP_CHECK(np_unit_configure(u, &cfg, spec, why, sizeof why) != 0 && strstr(why, k->name),
                     "%s: %s accepted or the refusal does not name the key: '%s'", u->name, spec, why);
        }
    }
    printf("%s: %u keys; %u end and default values round-trip; past the top and twice refused by name\n", u->name,
           keys, values);
    /* An unknown key is refused with its name. */
    np_unit_cfg cfg;
    char err[256] = "";
    NP_CHECK(np_unit_configure(u, &cfg, "no_such_key=1", err, sizeof err) != 0 && strstr(err, "no_such_key"),
             "%s: unknown key accepted or not named: '%s'", u->name, err);
    printf("%s: unknown key refused: %s\n", u->name, err);
    return 0;
}

/* --- golden_vectors --- */

static void golden_one(const np_unit *u, const np_conf_env *e, const char *dir, const char *name, unsigned level,
                       uint64_t seed, const char *ext)
{
    char set[4400], vec[4400], out[4096], err[NP_VEC_ERRLEN];
    snprintf(set, sizeof set, "%s/%s", dir, name);
    /* The configuration is the one the set's text file names. */
    snprintf(vec, sizeof vec, "%.*s.vec", (int)(strlen(set) - strlen(ext) - 1), set);
    np_vec_reader r;
    if (np_vec_open(&r, vec) != 0) {
        NP_CHECK(0, "%s", r.L.err);
        return;
    }
    np_vec_header h;
    int ok = header(&h, u, r.h.cfg_text) == 0;
    /* The refresh hint names the set's configuration ("K=V K=V" in the file, "K=V,K=V" for --config). */
    char cfg[1024];
    snprintf(cfg, sizeof cfg, "%s", r.h.cfg_text);
    for (char *c = cfg; *c; c++)
        if (*c == ' ')
            *c = ',';
    np_vec_close(&r);
    if (!ok)
        return;
    work_path(out, sizeof out, e, u, name);
    np_vec_format fmt = strcmp(ext, "vec") == 0 ? NP_VEC_TEXT : NP_VEC_READMEMH;
    np_vec_output o = { out, fmt };
    if (np_vec_generate(&h, level, seed, UINT64_MAX, &o, 1, err, sizeof err) != 0) {
        NP_CHECK(0, "%s: %s", u->name, err);
        return;
    }
    int same = same_bytes(out, set);
    NP_CHECK(same, "regenerated %s differs from %s\nrefresh with: noisepipe vectors --unit %s --config %s --seed %" PRIu64
             " --level %u --format %s -o %s", out, set, u->name, cfg, seed, level, fmt == NP_VEC_TEXT ? "text" : "readmemh",
             set);
    printf("%s: regenerated level %u seed %" PRIu64 " (%" PRIu64 " vectors): %s %s\n", u->name, level, seed, h.count,
           same ? "identical to" : "DIFFERS from", set);
    remove(out);
}

static int golden_vectors(const np_unit *u, const np_conf_env *e)
{
    char dir[4096];
    snprintf(dir, sizeof dir, "%s/%s", e->vec_dir, u->name);
    DIR *d = opendir(dir);
    unsigned sets = 0;
    for (struct dirent *de; d && (de = readdir(d)) != NULL;) {
        char tail[16];
        unsigned level;
        uint64_t seed;
        size_t nl = strlen(u->name);
        int used = 0;
        if (strncmp(de->d_name, u->name, nl) != 0 ||
            sscanf(de->d_name + nl, "-l%u-seed%" SCNu64 ".%15s%n", &level, &seed, tail, &used) != 3 ||
            de->d_name[nl + (size_t)used] != '\0' || (strcmp(tail, "vec") != 0 && strcmp(tail, "memh") != 0))
            continue;
        golden_one(u, e, dir, de->d_name, level, seed, tail);
        if (strcmp(tail, "vec") != 0)
            continue;
        sets++;
        /* The checked-in set verifies: the model's outputs through the cycle model, the reference's tolerance. */
        char path[8192];
        snprintf(path, sizeof path, "%s/%s", dir, de->d_name);
        for (int traffic = 1; traffic >= 0; traffic--) {
            np_verify_opts vo = { "conformance", 10, -1.0, traffic, 1, NULL };
            FILE *sink = tmpfile();
            int rc = np_verify(path, &vo, sink ? sink : stdout);
            if (sink)
                fclose(sink);
            NP_CHECK(rc == 0, "%s: noisepipe verify%s %s fails (%d)", u->name, traffic ? "" : " --no-stalls", path, rc);
        }
        printf("%s: %s verifies with random stalls and without\n", u->name, de->d_name);
    }
    if (d)
        closedir(d);
    NP_CHECK(sets > 0, "%s: no golden vector set in %s; check one in: noisepipe vectors --unit %s --seed 1 -o %s/%s-l1-seed1.vec",
             u->name, dir, u->name, dir, u->name);
    return 0;
}

/* --- batch --- */

enum { BATCH_MAX = 1u << 16, BATCH_RANDOM = 4096, BATCH_RUN = 256 };

typedef struct batch_cases {
    np_unit_fields f;
    size_t n;
    uint64_t (*in)[NP_UNIT_MAX_FIELDS]; /* point i's input words */
} batch_cases;

static void batch_add(batch_cases *c, const uint64_t *in)
{
    if (c->n < BATCH_MAX)
        memcpy(c->in[c->n++], in, sizeof c->in[0]);
}

/*
 * The points of the check: the unit's boundary table; then a stream unit's
 * runs of consecutive beats (what a batch of a span unit is) of its
 * annotated descriptors and of random ones, else the generator's level-1
 * walks and BATCH_RANDOM weighted random cases.
 */
static void batch_collect(const np_unit *u, const np_vec_header *h, batch_cases *c)
{
    static uint64_t bnd[4096][NP_UNIT_MAX_FIELDS];
    size_t nb = u->boundary(&h->cfg, bnd, 4096);
    for (size_t i = 0; i < nb && i < 4096; i++)
        batch_add(c, bnd[i]);
    if (u->stream) {
        const np_unit_stream *st = u->stream;
        size_t nd = st->descriptors ? st->descriptors(&h->cfg, bnd, 4096) : 0;
        np_rng g;
        np_rng_seed(&g, 11);
        for (size_t d = 0; d < (nd < 4096 ? nd : 4096) + 16; d++) {
            uint64_t desc[NP_UNIT_MAX_FIELDS] = { 0 };
            if (d < nd && d < 4096)
                memcpy(desc, bnd[d], sizeof desc);
            else
                st->random_desc(&h->cfg, &g, desc);
            uint64_t b = st->beats(&h->cfg, desc), m = b < BATCH_RUN ? b : BATCH_RUN;
            for (uint64_t k = 0; k < m; k++) {
                desc[st->n_desc] = k;
                batch_add(c, desc);
            }
        }
        return;
    }
    np_vecgen g;
    np_vec_rec rec;
    char err[NP_VEC_ERRLEN];
    if (np_vecgen_init(&g, h, 1, 5, BATCH_RANDOM, err, sizeof err) != 0) {
        NP_CHECK(0, "%s: %s", u->name, err);
        return;
    }
    while (np_vecgen_next(&g, &rec))
        batch_add(c, rec.w[NP_VEC_IN]);
    np_vecgen_free(&g);
}

/*
 * np_unit_eval_n over the points at order[0..n) in calls of `chunk` points
 * (the last one shorter); 0, or 1 after recording the first point whose
 * words differ from eval's (want).
 */
static int batch_compare(const np_unit *u, const np_vec_header *h, const batch_cases *c, const size_t *order,
                         size_t chunk, const uint64_t (*want)[NP_UNIT_MAX_FIELDS], uint64_t *in, uint64_t *out,
                         const char *how)
{
    for (size_t i0 = 0; i0 < c->n; i0 += chunk) {
        size_t m = c->n - i0 < chunk ? c->n - i0 : chunk;
        for (size_t i = 0; i < m; i++)
            for (unsigned k = 0; k < c->f.n_in; k++)
                in[k * m + i] = c->in[order[i0 + i]][k];
        np_unit_eval_n(u, &h->cfg, in, out, m);
        for (size_t i = 0; i < m; i++)
            for (unsigned k = 0; k < c->f.n_out; k++) {
                const size_t p = order[i0 + i];
                if (out[k * m + i] == want[p][k])
                    continue;
                char ins[256] = "";
                for (unsigned a = 0; a < c->f.n_in; a++)
                    snprintf(ins + strlen(ins), sizeof ins - strlen(ins), "%s%s=%" PRIx64, a ? " " : "",
                             c->f.in[a].name, c->in[p][a]);
                NP_CHECK(0, "%s [%s] %s, chunk %zu: %s => %s %" PRIx64 " expected (eval): %" PRIx64, u->name,
                         h->cfg_text, how, chunk, ins, c->f.out[k].name, out[k * m + i], want[p][k]);
                return 1;
            }
    }
    return 0;
}

static int batch(const np_unit *u, const np_conf_env *e)
{
    (void)e;
    const char *cfgs[MAX_CONFIGS];
    unsigned nc = configs_of(u, cfgs);
    batch_cases c;
    c.in = malloc(BATCH_MAX * sizeof c.in[0]);
    uint64_t(*want)[NP_UNIT_MAX_FIELDS] = malloc(BATCH_MAX * sizeof want[0]);
    size_t *order = malloc(BATCH_MAX * sizeof *order), *shuffled = malloc(BATCH_MAX * sizeof *shuffled);
    uint64_t *in = malloc((size_t)BATCH_MAX * NP_UNIT_MAX_FIELDS * sizeof *in);
    uint64_t *out = malloc((size_t)BATCH_MAX * NP_UNIT_MAX_FIELDS * sizeof *out);
    NP_CHECK(c.in && want && order && shuffled && in && out, "out of memory");
    for (unsigned q = 0; q < nc && c.in && want && order && shuffled && in && out; q++) {
        np_vec_header h;
        if (header(&h, u, cfgs[q]) != 0)
            continue;
        u->fields(&h.cfg, &c.f);
        c.n = 0;
        batch_collect(u, &h, &c);
        np_rng g;
        np_rng_seed(&g, 17 + q);
        for (size_t i = 0; i < c.n; i++) {
            order[i] = shuffled[i] = i;
            u->eval(&h.cfg, c.in[i], want[i]);
        }
        for (size_t i = c.n; i > 1; i--) { /* Fisher-Yates */
            size_t j = (size_t)(np_rng_next(&g) % i), t = shuffled[i - 1];
            shuffled[i - 1] = shuffled[j];
            shuffled[j] = t;
        }
        /* One call; runs of a span's length and odd sizes (a chunk's edge inside a run); one point a call. */
        static const size_t chunks[] = { BATCH_MAX, BATCH_RUN, 7, 1 };
        int bad = 0;
        for (unsigned k = 0; k < sizeof chunks / sizeof chunks[0] && !bad; k++)
            bad = batch_compare(u, &h, &c, order, chunks[k], (const uint64_t(*)[NP_UNIT_MAX_FIELDS])want, in, out,
                                "in order");
        for (unsigned k = 0; k < 2 && !bad; k++)
            bad = batch_compare(u, &h, &c, shuffled, chunks[k], (const uint64_t(*)[NP_UNIT_MAX_FIELDS])want, in,
                                out, "shuffled");
        printf("%s [%s]: %zu points (boundary table, %s): %s, in order in calls of %u, 256, 7 and 1 points "
               "and shuffled: %s\n",
               u->name, h.cfg_text, c.n, u->stream ? "runs of consecutive beats" : "level-1 walks and random",
               u->eval_n ? "the unit's eval_n" : "the generic np_unit_eval_n", (unsigned)BATCH_MAX,
               bad ? "DIFFERS" : "every word equals eval's");
    }
    free(c.in);
    free(want);
    free(order);
    free(shuffled);
    free(in);
    free(out);
    return 0;
}

/* --- kat --- */

static int kat(const np_unit *u, const np_conf_env *e)
{
    char path[4096], err[1024];
    snprintf(path, sizeof path, "%s/%s_kat.inc", e->kat_dir, u->name);
    int rc = np_kat_check(path, err, sizeof err);
    NP_CHECK(rc == 0, "%s: %s%s", u->name, err,
             rc < 0 ? "; a unit checks in its table: gen_kat UNIT -o testbench/UNIT_kat.inc" : "");
    if (rc == 0)
        printf("%s: %s regenerated byte for byte\n", u->name, path);
    return 0;
}

const np_conf_check np_conf_checks[] = {
    { "cycle_vs_bitexact", cycle_vs_bitexact },
    { "datapath_widths", datapath_widths },
    { "cfg_roundtrip", cfg_roundtrip },
    { "golden_vectors", golden_vectors },
    { "kat", kat },
    { "batch", batch },
    { NULL, NULL },
};

const np_conf_check *np_conf_find(const char *name)
{
    for (const np_conf_check *c = np_conf_checks; c->name; c++)
        if (strcmp(c->name, name) == 0)
            return c;
    return NULL;
}
