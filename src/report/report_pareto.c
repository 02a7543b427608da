/* SPDX-License-Identifier: MIT */
/*
 * Error against cost: a design-space sweep over two internal widths of a
 * unit. Each configuration's error is measured by running its bit-exact model
 * against the float reference on the same seeded inputs (the unit's boundary
 * table plus random inputs); its cost is the gate report's estimate.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "np_cli.h"
#include "np_pareto.h"
#include "np_plot.h"
#include "np_rng.h"

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

/* The inputs every configuration is measured on, with their reference values. */
typedef struct sample_set {
    size_t n;
    unsigned n_in, n_out;
    uint64_t *in;  /* n * n_in */
    double *ref;   /* n * n_out */
} sample_set;

static int make_samples(const np_unit *u, const void *cfg, uint64_t count, uint64_t seed, sample_set *s)
{
    np_unit_fields f;
    u->fields(cfg, &f);
    size_t nb = u->boundary(cfg, NULL, 0);
    s->n = nb + (size_t)count;
    s->n_in = f.n_in;
    s->n_out = f.n_out;
    s->in = malloc(s->n * f.n_in * sizeof *s->in);
    s->ref = malloc(s->n * f.n_out * sizeof *s->ref);
    uint64_t (*b)[NP_UNIT_MAX_FIELDS] = malloc((nb ? nb : 1) * sizeof *b);
    if (!s->in || !s->ref || !b) {
        free(b);
        return -1;
    }
    u->boundary(cfg, b, nb);
    np_rng r;
    np_rng_seed(&r, seed);
    for (size_t i = 0; i < s->n; i++) {
        uint64_t *in = &s->in[i * f.n_in];
        for (unsigned k = 0; k < f.n_in; k++)
            in[k] = i < nb ? b[i][k] : np_rng_next(&r) >> (64u - f.in[k].bits);
        u->ref(cfg, in, &s->ref[i * f.n_out]);
    }
    free(b);
    return 0;
}

/* Max error (LSB) and correctly rounded share of one configuration. */
static void measure(const np_unit *u, const void *cfg, const sample_set *s, double *max_err, double *cr_pct)
{
    np_unit_fields f;
    u->fields(cfg, &f);
    uint64_t out[NP_UNIT_MAX_FIELDS];
    double worst = 0.0;
    uint64_t cr = 0;
    for (size_t i = 0; i < s->n; i++) {
        u->eval(cfg, &s->in[i * s->n_in], out);
        for (unsigned k = 0; k < s->n_out; k++) {
            double scale = ldexp(1.0, (int)f.out[k].frac);
            double got = np_unit_field_value(&f.out[k], out[k]) * scale;
            double want = s->ref[i * s->n_out + k] * scale;
            worst = fmax(worst, fabs(got - want));
            cr += got == floor(want + 0.5);
        }
    }
    *max_err = worst;
    *cr_pct = 100.0 * (double)cr / ((double)s->n * s->n_out);
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
    sample_set s;
    if (make_samples(u, &cfg, samples, seed, &s) != 0) {
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    res->inputs = s.n;
    size_t total = (size_t)(a1->hi - a1->lo + 1) * (size_t)(a2->hi - a2->lo + 1);
    res->pts = calloc(total, sizeof *res->pts);
    if (!res->pts) {
        free(s.in);
        free(s.ref);
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
            if (np_unit_cost_compute(u, &cfg, &np_cost_default, &c, err, errlen) != 0) {
                free(s.in);
                free(s.ref);
                return -1;
            }
            p->v1 = a;
            p->v2 = b;
            np_unit_cfg_format(u, &cfg, p->cfg, sizeof p->cfg);
            p->gates = c.total;
            p->latency = c.latency;
            p->crit = c.crit;
            p->bound = u->error_bound_lsb(&cfg);
            measure(u, &cfg, &s, &p->max_err, &p->cr_pct);
            res->n++;
            np_progress_update(&pr, res->n);
        }
    np_progress_end(&pr);
    free(s.in);
    free(s.ref);
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

/* The cheapest point meeting a predicate on (max error, bound). */
static const np_dse_point *cheapest(const np_dse_result *r, int by_argument)
{
    const np_dse_point *best = NULL;
    for (size_t i = 0; i < r->n; i++) {
        const np_dse_point *p = &r->pts[i];
        int ok = by_argument ? p->bound <= 1.0 : p->max_err <= 1.0;
        if (ok && (!best || p->gates < best->gates))
            best = p;
    }
    return best;
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

/* Perlin's "under 10K gates" claim for the classic unit (np_dse_space.claim_10k). */
static void write_claim_10k(FILE *f, const np_dse_result *r, const np_dse_point *m, const np_dse_point *a)
{
    fprintf(f, "## Perlin's claim\n\n");
    fprintf(f, "The seed claims the classic unit in *under 10K gates* with *about twenty clocks* of latency, "
               "one result per clock, 8-bit output. Every configuration here has latency %u clocks and one "
               "result per clock.\n\n", r->n ? r->pts[0].latency : 0);
    size_t meet = 0;
    for (size_t i = 0; i < r->n; i++)
        meet += r->pts[i].gates < 10000.0 && r->pts[i].max_err <= 1.0;
    if (m)
        fprintf(f, "- Cheapest configuration measured faithful (max error ≤ 1 LSB on these inputs): `%s`, "
                   "**%.0f gates**, max error %.4f LSB, %.2f %% correctly rounded, bound %.4f LSB.\n",
                m->cfg, m->gates, m->max_err, m->cr_pct, m->bound);
    if (a)
        fprintf(f, "- Cheapest configuration faithful by argument (bound ≤ 1 LSB for every input): `%s`, "
                   "**%.0f gates**, measured %.4f LSB, %.2f %% correctly rounded.\n",
                a->cfg, a->gates, a->max_err, a->cr_pct);
    fprintf(f, "- Configurations under 10,000 gates that are measured faithful: **%zu**.\n\n", meet);
    if (meet == 0 && m) {
        /* Where the gates of the cheapest faithful configuration go. */
        np_unit_cfg cfg;
        np_unit_cost c;
        char e[256];
        fprintf(f, "**Verdict:** no configuration of this datapath meets the claim: the cheapest faithful one "
                   "costs %.0f NAND2 equivalents, %.1f× the claimed 10K.", m->gates, m->gates / 10000.0);
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
        fprintf(f, "**Verdict:** the claim is met by the configurations above marked ✓ in the last column.\n\n");
}

/* Any other unit: the cheapest faithful configurations against the default widths. */
static void write_summary(FILE *f, const np_dse_result *r, const np_dse_point *m, const np_dse_point *a)
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
    if (d)
        fprintf(f, "- Default widths: `%s`, **%.0f gates**, max error %.4f LSB, %.2f %% correctly rounded, "
                   "bound %.4f LSB.\n", d->cfg, d->gates, d->max_err, d->cr_pct, d->bound);
    if (m) {
        fprintf(f, "- Cheapest configuration measured faithful (max error ≤ 1 LSB on these inputs): `%s`, "
                   "**%.0f gates**, max error %.4f LSB, %.2f %% correctly rounded, bound %.4f LSB",
                m->cfg, m->gates, m->max_err, m->cr_pct, m->bound);
        if (d && d->gates > 0.0)
            fprintf(f, " (%.1f %% fewer gates than the default)", 100.0 * (1.0 - m->gates / d->gates));
        fprintf(f, ".\n");
    }
    if (a) {
        fprintf(f, "- Cheapest configuration faithful by argument (bound ≤ 1 LSB for every input): `%s`, "
                   "**%.0f gates**, measured %.4f LSB, %.2f %% correctly rounded",
                a->cfg, a->gates, a->max_err, a->cr_pct);
        if (d && d->gates > 0.0)
            fprintf(f, " (%.1f %% fewer gates than the default)", 100.0 * (1.0 - a->gates / d->gates));
        fprintf(f, ".\n");
    }
    if (!m)
        fprintf(f, "- No configuration of this space is measured faithful.\n");
    fprintf(f, "- Pareto front (no other point as cheap and as accurate, and better in one): **%zu** of %zu "
               "configurations, marked ● below.\n\n", front, r->n);
    if (m && a && m != a)
        fprintf(f, "The measured-faithful configurations below the one faithful by argument are faithful on "
                   "these inputs only: the bound, not the measurement, guarantees every input.\n\n");
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
               "configuration's bit-exact model runs on the same %zu inputs (the unit's boundary table and "
               "%llu seeded random inputs, seed %llu) against the float reference; gates are the estimate of "
               "[gates.md](gates.md) ([cost-model.md](cost-model.md)). *Bound* is the unit's error argument "
               "(valid for every input); *measured* holds for the inputs tried.",
            sp->base, r->axis[0].key, r->axis[0].lo, r->axis[0].hi, r->axis[1].key, r->axis[1].lo, r->axis[1].hi, r->inputs,
            (unsigned long long)r->samples, (unsigned long long)r->seed);
    if (uf.n_out > 1) {
        fprintf(f, " The unit has %u outputs (", uf.n_out);
        for (unsigned k = 0; k < uf.n_out; k++)
            fprintf(f, "%s`%s` %s", k ? ", " : "", uf.out[k].name, uf.out[k].format);
        fprintf(f, "): *max error* and *bound* are the largest over them, each in its own output's LSB; "
                   "*correctly rounded* counts every output of every input.");
    }
    fprintf(f, "\n\n");
    fprintf(f, "![error against gates](%s)\n\n", svg_name);
    const np_dse_point *m = cheapest(r, 0), *a = cheapest(r, 1);
    if (sp->claim_10k)
        write_claim_10k(f, r, m, a);
    else
        write_summary(f, r, m, a);
    fprintf(f, "## All configurations, cheapest first\n\n");
    if (sp->claim_10k) {
        fprintf(f, "| configuration | gates | latency | path (levels) | max error (LSB) | bound (LSB) | correctly rounded | Pareto | < 10K and faithful |\n");
        fprintf(f, "| --- | ---: | ---: | ---: | ---: | ---: | ---: | :---: | :---: |\n");
    } else {
        fprintf(f, "| configuration | gates | latency | path (levels) | max error (LSB) | bound (LSB) | correctly rounded | Pareto | faithful |\n");
        fprintf(f, "| --- | ---: | ---: | ---: | ---: | ---: | ---: | :---: | :---: |\n");
    }
    np_dse_point *sorted = malloc(r->n * sizeof *sorted);
    if (!sorted)
        return;
    memcpy(sorted, r->pts, r->n * sizeof *sorted);
    qsort(sorted, r->n, sizeof *sorted, by_gates);
    for (size_t i = 0; i < r->n; i++) {
        const np_dse_point *p = &sorted[i];
        int mark = sp->claim_10k ? p->gates < 10000.0 && p->max_err <= 1.0 : p->max_err <= 1.0;
        fprintf(f, "| `%s` | %.0f | %u | %.0f | %.4f | %.4f | %.2f %% | %s | %s |\n", p->cfg, p->gates, p->latency,
                p->crit, p->max_err, p->bound, p->cr_pct, p->pareto ? "●" : "", mark ? "✓" : "");
    }
    free(sorted);
}

void np_dse_write_json(FILE *f, const np_dse_result *r)
{
    const np_dse_space *sp = r->space;
    fprintf(f, "{\n  \"generator\": \"noisepipe report pareto\",\n  \"unit\": \"%s\",\n  \"base\": \"%s\",\n"
               "  \"inputs\": %zu,\n  \"seed\": %llu,\n  \"points\": [\n",
            sp->unit, sp->base, r->inputs, (unsigned long long)r->seed);
    for (size_t i = 0; i < r->n; i++) {
        const np_dse_point *p = &r->pts[i];
        fprintf(f, "    { \"config\": \"%s\", \"gates\": %.1f, \"latency\": %u, \"path_levels\": %.1f, "
                   "\"max_error_lsb\": %.6f, \"bound_lsb\": %.6f, \"correctly_rounded_pct\": %.4f, \"pareto\": %s }%s\n",
                p->cfg, p->gates, p->latency, p->crit, p->max_err, p->bound, p->cr_pct,
                p->pareto ? "true" : "false", i + 1 < r->n ? "," : "");
    }
    fprintf(f, "  ]\n}\n");
}

void np_dse_write_svg(FILE *f, const np_dse_result *r)
{
    size_t n = r->n, nf = 0, nu = 0, np = 0;
    double *buf = malloc(6 * (n ? n : 1) * sizeof *buf);
    if (!buf)
        return;
    double *fx = buf, *fy = buf + n, *ux = buf + 2 * n, *uy = buf + 3 * n, *px = buf + 4 * n, *py = buf + 5 * n;
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
        if (p->max_err <= 1.0) {
            fx[nf] = p->gates;
            fy[nf++] = e;
        } else {
            ux[nu] = p->gates;
            uy[nu++] = e;
        }
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
    np_plot_series s[3] = {
        { "faithful (max error <= 1 LSB)", "#1a7f37", fx, fy, nf, 0, 1 },
        { "not faithful", "#999999", ux, uy, nu, 0, 1 },
        { "Pareto front", "#0550ae", px, py, np, 1, 0 },
    };
    np_plot_svg(f, &pl, s, 3);
    free(sorted);
    free(buf);
}
