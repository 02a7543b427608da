/* SPDX-License-Identifier: MIT */
/*
 * Error against cost: a design-space sweep over two internal widths of a
 * unit. Each configuration's error is the adversarial search's
 * (np_search.h, docs/search.md) with the same budget and seed, and its
 * verdict one of the three of PRODUCT.md's Claims: faithful (proved), no
 * counterexample in N adversarial inputs, not faithful with the input;
 * its cost is the gate report's estimate.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "np_common.h"
#include "np_pareto.h"
#include "np_plot.h"
#include "np_search.h"

/* The design spaces swept for `noisepipe report pareto` (docs/pareto-*.md). */
const np_dse_space np_dse_spaces[] = {
    /* Narrowed from the keys' 1..24 and 0..30 to the widths around the 8-bit output's faithful ones. */
    { "classic3", "out_bits=8", { { "s_frac", 3, 16 }, { "lerp_frac", 6, 14 } }, 1 },
    /* The powers' and the products' fraction bits: they size every multiplier (k_frac only the constants'). */
    { "simplex3", "out_bits=16,dout_bits=16,deriv=1", { { "t_frac", 16, 26 }, { "p_frac", 14, 24 } }, 0 },
    { NULL, NULL, { { NULL, 0, 0 }, { NULL, 0, 0 } }, 0 },
};

/* The range of axis a of sp from the unit's key table (narrowed by sp). 0, or -1 with err. */
static int resolve_axis(const np_unit *u, const np_dse_axis *a, np_dse_axis *out, char *err, size_t errlen)
{
    const np_unit_key *k = np_unit_key_find(u, a->key);
    if (!k || k->word) {
        snprintf(err, errlen, "unit %s: '%s' is not a numeric configuration key (noisepipe units)", u->name, a->key);
        return -1;
    }
    *out = *a;
    if (a->lo == 0 && a->hi == 0) {
        out->lo = k->lo;
        out->hi = k->hi;
    } else if (a->lo > a->hi || a->lo < k->lo || a->hi > k->hi) {
        snprintf(err, errlen, "unit %s: sweep of %s over %u..%u is outside the key's range %u..%u", u->name, a->key,
                 a->lo, a->hi, k->lo, k->hi);
        return -1;
    }
    return 0;
}

enum { CHECK_WAVE = NP_SEARCH_WAVE * NP_SEARCH_CHUNK };

/* The search of one configuration, into p. 0, or -1 with err. */
static int search_point(const np_unit *u, const void *cfg, uint64_t n, uint64_t seed, np_dse_point *p, char *err,
                        size_t errlen)
{
    np_search_opts o;
    np_search_result r;
    memset(&o, 0, sizeof o);
    o.unit = u;
    o.cfg = cfg;
    /* A configuration proved faithful by its bound gets one wave: a check of the argument, not its evidence. */
    o.n = u->error_bound_lsb(cfg) <= 1.0 && n > CHECK_WAVE ? CHECK_WAVE : n;
    o.seed = seed;
    o.stop_early = 1;
    if (np_search_run(&o, &r, err, errlen) != 0)
        return -1;
    np_unit_fields f;
    u->fields(cfg, &f);
    p->verdict = (int)r.verdict;
    p->tried = r.total.n;
    p->max_err = r.worst.err;
    p->cr_pct = 100.0 * (double)r.total.cr / ((double)r.total.n * f.n_out);
    memcpy(p->cex, r.worst.in, sizeof p->cex);
    /* The counterexample's worst field, its output and true value in that field's LSB. */
    uint64_t in[NP_UNIT_MAX_FIELDS] = { r.worst.in[0], r.worst.in[1], r.worst.in[2] }, out[NP_UNIT_MAX_FIELDS];
    double ref[NP_UNIT_MAX_FIELDS];
    u->eval(cfg, in, out);
    u->ref(cfg, in, ref);
    double top = -1.0;
    for (unsigned k = 0; k < f.n_out; k++) {
        double sc = ldexp(1.0, (int)f.out[k].frac), got = np_unit_field_value(&f.out[k], out[k]) * sc;
        if (fabs(got - ref[k] * sc) > top) {
            top = fabs(got - ref[k] * sc);
            snprintf(p->cex_field, sizeof p->cex_field, "%s", f.out[k].name);
            p->cex_out = got;
            p->cex_true = ref[k] * sc;
        }
    }
    return 0;
}

int np_dse_run(const np_dse_space *sp, uint64_t samples, uint64_t seed, np_dse_result *res, char *err,
               size_t errlen)
{
    memset(res, 0, sizeof *res);
    res->space = sp;
    res->samples = samples;
    res->seed = seed;
    const np_unit *u = np_unit_find(sp->unit);
    if (!u) {
        snprintf(err, errlen, "unknown unit '%s'", sp->unit);
        return -1;
    }
    res->unit = u;
    for (unsigned i = 0; i < 2; i++)
        if (resolve_axis(u, &sp->axis[i], &res->axis[i], err, errlen) != 0)
            return -1;
    const np_dse_axis *a1 = &res->axis[0], *a2 = &res->axis[1];
    np_unit_cfg cfg;
    if (np_unit_configure(u, &cfg, sp->base, err, errlen) != 0)
        return -1;
    if (samples < NP_SEARCH_CHUNK)
        res->samples = samples = NP_SEARCH_CHUNK;
    size_t total = (size_t)(a1->hi - a1->lo + 1) * (size_t)(a2->hi - a2->lo + 1);
    res->pts = calloc(total, sizeof *res->pts);
    if (!res->pts) {
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    np_progress pr;
    np_progress_start(&pr, "pareto", total);
    for (unsigned a = a1->lo; a <= a1->hi; a++)
        for (unsigned b = a2->lo; b <= a2->hi; b++) {
            np_dse_point *p = &res->pts[res->n];
            char spec[256], e2[256];
            snprintf(spec, sizeof spec, "%s,%s=%u,%s=%u", sp->base, a1->key, a, a2->key, b);
            if (np_unit_configure(u, &cfg, spec, e2, sizeof e2) != 0)
                continue; /* outside the unit's valid range */
            np_unit_cost c;
            if (np_unit_cost_compute(u, &cfg, &np_cost_default, &c, err, errlen) != 0)
                return -1;
            p->v1 = a;
            p->v2 = b;
            np_unit_cfg_format(u, &cfg, p->cfg, sizeof p->cfg);
            p->gates = c.total;
            p->latency = c.latency;
            p->crit = c.crit;
            p->bound = u->error_bound_lsb(&cfg);
            if (search_point(u, &cfg, samples, seed, p, err, errlen) != 0)
                return -1;
            res->n++;
            np_progress_update(&pr, res->n);
        }
    np_progress_end(&pr);
    /* Pareto front on (gates, max error): no other point is at most as costly and as wrong, and better in one. */
    for (size_t i = 0; i < res->n; i++) {
        np_dse_point *p = &res->pts[i];
        p->pareto = 1;
        for (size_t j = 0; j < res->n && p->pareto; j++) {
            const np_dse_point *q = &res->pts[j];
            if (j != i && q->gates <= p->gates && q->max_err <= p->max_err &&
                (q->gates < p->gates || q->max_err < p->max_err))
                p->pareto = 0;
        }
    }
    return 0;
}

void np_dse_free(np_dse_result *res)
{
    free(res->pts);
    res->pts = NULL;
    res->n = 0;
}

static int by_gates(const void *a, const void *b)
{
    const np_dse_point *p = a, *q = b;
    return (p->gates > q->gates) - (p->gates < q->gates);
}

static double min_gates(const np_dse_result *r)
{
    double g = HUGE_VAL;
    for (size_t i = 0; i < r->n; i++)
        g = fmin(g, r->pts[i].gates);
    return g;
}

/* The cheapest point with verdict v (np_search_verdict), or NULL. */
static const np_dse_point *cheapest(const np_dse_result *r, int v)
{
    const np_dse_point *best = NULL;
    for (size_t i = 0; i < r->n; i++) {
        const np_dse_point *p = &r->pts[i];
        if (p->verdict == v && (!best || p->gates < best->gates))
            best = p;
    }
    return best;
}

static size_t count_verdict(const np_dse_result *r, int v)
{
    size_t n = 0;
    for (size_t i = 0; i < r->n; i++)
        n += r->pts[i].verdict == v;
    return n;
}

/* A point's verdict in the project's words (np_search_verdict_text's). */
static void verdict_text(const np_dse_point *p, char *buf, size_t len)
{
    np_search_result r;
    memset(&r, 0, sizeof r);
    r.verdict = (np_search_verdict)p->verdict;
    r.total.n = p->tried;
    memcpy(r.worst.in, p->cex, sizeof p->cex);
    np_search_verdict_text(&r, buf, len);
}

/* The sweep's point with the base configuration's own widths (the unit's default), or NULL. */
static const np_dse_point *base_point(const np_dse_result *r)
{
    np_unit_cfg cfg;
    char e[256], name[128];
    if (np_unit_configure(r->unit, &cfg, r->space->base, e, sizeof e) != 0)
        return NULL;
    np_unit_cfg_format(r->unit, &cfg, name, sizeof name);
    for (size_t i = 0; i < r->n; i++)
        if (strcmp(r->pts[i].cfg, name) == 0)
            return &r->pts[i];
    return NULL;
}

/* One summary line for a point: "`cfg`, **G gates**, max error E LSB in N inputs, bound B LSB". */
static void point_line(FILE *f, const char *what, const np_dse_point *p, const np_dse_point *d)
{
    fprintf(f, "- %s: `%s`, **%.0f gates**, max error %.4f LSB in %llu adversarial inputs, %.2f %% correctly "
               "rounded, bound %.4f LSB",
            what, p->cfg, p->gates, p->max_err, (unsigned long long)p->tried, p->cr_pct, p->bound);
    if (d && d != p && d->gates > 0.0)
        fprintf(f, " (%.1f %% fewer gates than the default)", 100.0 * (1.0 - p->gates / d->gates));
    fprintf(f, ".\n");
}

/* The cheapest proved and searched configurations, and the counterexamples' count. */
static void verdict_lines(FILE *f, const np_dse_result *r, const np_dse_point *d)
{
    const np_dse_point *a = cheapest(r, NP_SEARCH_PROVED), *m = cheapest(r, NP_SEARCH_NO_COUNTER);
    if (a)
        point_line(f, "Cheapest configuration **faithful (proved)** (bound ≤ 1 LSB for every input)", a, d);
    else
        fprintf(f, "- No configuration of this space is faithful by proof.\n");
    if (m && (!a || m->gates < a->gates))
        point_line(f, "Cheapest configuration with **no counterexample in its adversarial inputs** (bound > 1 LSB: "
                      "not proved faithful)", m, d);
    fprintf(f, "- Not faithful, with a counterexample (listed below): **%zu** of %zu configurations; no "
               "counterexample but no proof: %zu; faithful (proved): %zu.\n",
            count_verdict(r, NP_SEARCH_COUNTEREXAMPLE), r->n, count_verdict(r, NP_SEARCH_NO_COUNTER),
            count_verdict(r, NP_SEARCH_PROVED));
}

/* Perlin's "under 10K gates" claim for the classic unit (np_dse_space.claim_10k). */
static void write_claim_10k(FILE *f, const np_dse_result *r)
{
    fprintf(f, "## Perlin's claim\n\n");
    fprintf(f, "The seed claims the classic unit in *under 10K gates* with *about twenty clocks* of latency, "
               "one result per clock, 8-bit output. Every configuration here has latency %u clocks and one "
               "result per clock.\n\n", r->n ? r->pts[0].latency : 0);
    verdict_lines(f, r, NULL);
    size_t meet = 0;
    for (size_t i = 0; i < r->n; i++)
        meet += r->pts[i].gates < 10000.0 && r->pts[i].verdict != NP_SEARCH_COUNTEREXAMPLE;
    fprintf(f, "- Configurations under 10,000 gates without a counterexample: **%zu**.\n\n", meet);
    /* The cheapest configuration not shown unfaithful: a lower bound on what a faithful one costs. */
    const np_dse_point *m = NULL;
    for (size_t i = 0; i < r->n; i++)
        if (r->pts[i].verdict != NP_SEARCH_COUNTEREXAMPLE && (!m || r->pts[i].gates < m->gates))
            m = &r->pts[i];
    if (meet == 0 && m) {
        /* Where its gates go. */
        np_unit_cfg cfg;
        np_unit_cost c;
        char e[256];
        fprintf(f, "**Verdict:** no configuration of this datapath meets the claim: the cheapest one without a "
                   "counterexample costs %.0f NAND2 equivalents, %.1f× the claimed 10K.", m->gates, m->gates / 10000.0);
        if (np_unit_configure(r->unit, &cfg, m->cfg, e, sizeof e) == 0 &&
            np_unit_cost_compute(r->unit, &cfg, &np_cost_default, &c, e, sizeof e) == 0) {
            fprintf(f, " Its gates by stage:");
            for (unsigned k = 0; k < c.n_stages; k++)
                fprintf(f, "%s %s %.0f", k ? "," : "", c.st[k].name, c.st[k].logic + c.st[k].regs);
            fprintf(f, " (registers %.0f of the total, %u bits).", c.regs, c.reg_bits);
        }
        fprintf(f, " Even the cheapest configuration of all, faithful or not, costs %.0f. The claim can "
                   "only hold with fewer gates per result than this one-result-per-clock datapath has: "
                   "shared or time-multiplexed corner hashing, narrower interpolators than faithful "
                   "rounding allows, or a smaller gate-equivalent measure than NAND2.\n\n",
                min_gates(r));
    }
    else if (meet > 0)
        fprintf(f, "**Verdict:** configurations under 10K gates have no counterexample: see the last column.\n\n");
}

/* Any other unit: the cheapest faithful configurations against the default widths. */
static void write_summary(FILE *f, const np_dse_result *r)
{
    unsigned lo = 0, hi = 0;
    size_t front = 0;
    for (size_t i = 0; i < r->n; i++) {
        unsigned l = r->pts[i].latency;
        lo = i == 0 || l < lo ? l : lo;
        hi = i == 0 || l > hi ? l : hi;
        front += r->pts[i].pareto != 0;
    }
    fprintf(f, "## Summary\n\n");
    if (lo == hi)
        fprintf(f, "Every configuration here has latency %u clocks and one result per clock; the widths change "
                   "gates and error only.\n\n", lo);
    else
        fprintf(f, "Latency %u to %u clocks, one result per clock.\n\n", lo, hi);
    const np_dse_point *d = base_point(r);
    if (d) {
        char v[128];
        verdict_text(d, v, sizeof v);
        point_line(f, "Default widths", d, NULL);
        fprintf(f, "  Verdict: %s.\n", v);
    }
    verdict_lines(f, r, d);
    fprintf(f, "- Pareto front (no other point as cheap and as accurate, and better in one): **%zu** of %zu "
               "configurations, marked ● below.\n\n", front, r->n);
}

/* Every counterexample, cheapest configuration first (sorted: the points by gates). */
static void write_counterexamples(FILE *f, const np_dse_point *sorted, size_t n)
{
    fprintf(f, "## Counterexamples\n\n");
    fprintf(f, "Each configuration below is not faithful: at the input shown its output is more than 1 LSB from "
               "the float reference (`noisepipe search --unit U --config ...` reproduces it).\n\n");
    fprintf(f, "| configuration | input (x, y, z) | output | model (LSB) | true value (LSB) | error (LSB) |\n");
    fprintf(f, "| --- | --- | --- | ---: | ---: | ---: |\n");
    for (size_t i = 0; i < n; i++) {
        const np_dse_point *p = &sorted[i];
        if (p->verdict != NP_SEARCH_COUNTEREXAMPLE)
            continue;
        fprintf(f, "| `%s` | (0x%04x, 0x%04x, 0x%04x) | %s | %.0f | %.4f | %.4f |\n", p->cfg, p->cex[0], p->cex[1],
                p->cex[2], p->cex_field, p->cex_out, p->cex_true, p->max_err);
    }
    fprintf(f, "\n");
}

void np_dse_write_md(FILE *f, const np_dse_result *r, const char *svg_name)
{
    const np_dse_space *sp = r->space;
    np_unit_fields uf;
    np_unit_cfg bcfg;
    char e[256];
    uf.n_out = 1;
    if (np_unit_configure(r->unit, &bcfg, sp->base, e, sizeof e) == 0)
        r->unit->fields(&bcfg, &uf);
    fprintf(f, "# Error against cost: %s\n\n", sp->unit);
    fprintf(f, "Generated by `noisepipe report pareto`; do not edit (the test `report.docs_fresh` fails when "
               "this copy is stale). Design space: `%s` with `%s` = %u..%u and `%s` = %u..%u. Each "
               "configuration's bit-exact model is checked against the float reference by the adversarial "
               "search of [search.md](search.md) (extremes, lattice and cell faces, equal offsets and the "
               "unit's faces, the inputs where its roundings are worst, random inputs and a hill-climb) with a "
               "budget of %llu inputs, seed %llu, stopped at the first wave of %u inputs that holds a "
               "counterexample; a configuration whose bound proves it faithful gets one wave, as a check of the "
               "argument. Each configuration gets one of three verdicts: **faithful (proved)** when "
               "its error bound (the unit's argument, valid for every input) is ≤ 1 LSB; **no counterexample "
               "in N adversarial inputs** when the bound is larger and the search found no input over 1 LSB "
               "(not a proof); **not faithful** with the counterexample's input. *Max error* and *correctly "
               "rounded* are over the inputs the search tried. Gates are the estimate of "
               "[gates.md](gates.md) ([cost-model.md](cost-model.md)).",
            sp->base, r->axis[0].key, r->axis[0].lo, r->axis[0].hi, r->axis[1].key, r->axis[1].lo, r->axis[1].hi,
            (unsigned long long)r->samples, (unsigned long long)r->seed, NP_SEARCH_WAVE * NP_SEARCH_CHUNK);
    if (uf.n_out > 1) {
        fprintf(f, " The unit has %u outputs (", uf.n_out);
        for (unsigned k = 0; k < uf.n_out; k++)
            fprintf(f, "%s`%s` %s", k ? ", " : "", uf.out[k].name, uf.out[k].format);
        fprintf(f, "): *max error* and *bound* are the largest over them, each in its own output's LSB; "
                   "*correctly rounded* counts every output of every input.");
    }
    fprintf(f, "\n\n");
    fprintf(f, "![error against gates](%s)\n\n", svg_name);
    if (sp->claim_10k)
        write_claim_10k(f, r);
    else
        write_summary(f, r);
    np_dse_point *sorted = malloc((r->n ? r->n : 1) * sizeof *sorted);
    if (!sorted)
        return;
    memcpy(sorted, r->pts, r->n * sizeof *sorted);
    qsort(sorted, r->n, sizeof *sorted, by_gates);
    fprintf(f, "## All configurations, cheapest first\n\n");
    fprintf(f, "| configuration | gates | latency | path (levels) | inputs tried | max error (LSB) | bound (LSB) | "
               "correctly rounded | Pareto | verdict |\n");
    fprintf(f, "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | :---: | --- |\n");
    for (size_t i = 0; i < r->n; i++) {
        const np_dse_point *p = &sorted[i];
        char v[128];
        verdict_text(p, v, sizeof v);
        fprintf(f, "| `%s` | %.0f | %u | %.0f | %llu | %.4f | %.4f | %.2f %% | %s | %s |\n", p->cfg, p->gates,
                p->latency, p->crit, (unsigned long long)p->tried, p->max_err, p->bound, p->cr_pct,
                p->pareto ? "●" : "", v);
    }
    fprintf(f, "\n");
    if (count_verdict(r, NP_SEARCH_COUNTEREXAMPLE))
        write_counterexamples(f, sorted, r->n);
    free(sorted);
}

void np_dse_write_json(FILE *f, const np_dse_result *r)
{
    static const char *const vname[3] = { "faithful (proved)", "no counterexample", "not faithful" };
    const np_dse_space *sp = r->space;
    fprintf(f, "{\n  \"generator\": \"noisepipe report pareto\",\n  \"unit\": \"%s\",\n  \"base\": \"%s\",\n"
               "  \"search_inputs\": %llu,\n  \"seed\": %llu,\n  \"points\": [\n",
            sp->unit, sp->base, (unsigned long long)r->samples, (unsigned long long)r->seed);
    for (size_t i = 0; i < r->n; i++) {
        const np_dse_point *p = &r->pts[i];
        fprintf(f, "    { \"config\": \"%s\", \"gates\": %.1f, \"latency\": %u, \"path_levels\": %.1f, "
                   "\"max_error_lsb\": %.6f, \"bound_lsb\": %.6f, \"correctly_rounded_pct\": %.4f, \"pareto\": %s, "
                   "\"verdict\": \"%s\", \"inputs_tried\": %llu, \"worst_input\": [%u, %u, %u] }%s\n",
                p->cfg, p->gates, p->latency, p->crit, p->max_err, p->bound, p->cr_pct,
                p->pareto ? "true" : "false", vname[p->verdict], (unsigned long long)p->tried, p->cex[0], p->cex[1],
                p->cex[2], i + 1 < r->n ? "," : "");
    }
    fprintf(f, "  ]\n}\n");
}

void np_dse_write_svg(FILE *f, const np_dse_result *r)
{
    size_t n = r->n, cnt[3] = { 0, 0, 0 }, np = 0;
    double *buf = malloc(8 * (n ? n : 1) * sizeof *buf);
    if (!buf)
        return;
    double *xs[3] = { buf, buf + 2 * n, buf + 4 * n }, *ys[3] = { buf + n, buf + 3 * n, buf + 5 * n };
    double *px = buf + 6 * n, *py = buf + 7 * n;
    np_dse_point *sorted = malloc((n ? n : 1) * sizeof *sorted);
    if (!sorted) {
        free(buf);
        return;
    }
    memcpy(sorted, r->pts, n * sizeof *sorted);
    qsort(sorted, n, sizeof *sorted, by_gates);
    for (size_t i = 0; i < n; i++) {
        const np_dse_point *p = &sorted[i];
        double e = fmax(p->max_err, 0.1);
        unsigned v = (unsigned)p->verdict;
        xs[v][cnt[v]] = p->gates;
        ys[v][cnt[v]++] = e;
        if (p->pareto) {
            px[np] = p->gates;
            py[np++] = e;
        }
    }
    char title[128];
    snprintf(title, sizeof title, "%s: max error against estimated gates (%s)", r->space->unit, r->space->base);
    np_plot pl = { title, "estimated gates (NAND2 equivalents)", "max error (output LSB, log)", 0, 0, 0, 0, 1,
                   r->space->claim_10k ? 10000.0 : (double)NAN, 1.0, r->space->claim_10k ? "Perlin: 10K gates" : NULL,
                   "1 LSB" };
    np_plot_series s[4] = {
        { "faithful (proved)", "#1a7f37", xs[NP_SEARCH_PROVED], ys[NP_SEARCH_PROVED], cnt[NP_SEARCH_PROVED], 0, 1 },
        { "no counterexample (searched)", "#bf8700", xs[NP_SEARCH_NO_COUNTER], ys[NP_SEARCH_NO_COUNTER],
          cnt[NP_SEARCH_NO_COUNTER], 0, 1 },
        { "not faithful (counterexample)", "#999999", xs[NP_SEARCH_COUNTEREXAMPLE], ys[NP_SEARCH_COUNTEREXAMPLE],
          cnt[NP_SEARCH_COUNTEREXAMPLE], 0, 1 },
        { "Pareto front", "#0550ae", px, py, np, 1, 0 },
    };
    np_plot_svg(f, &pl, s, 4);
    free(sorted);
    free(buf);
}
