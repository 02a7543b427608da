/* SPDX-License-Identifier: MIT */
/* noisepipe search: the adversarial error search (np_search.h, docs/search.md). */
#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "np_common.h"
#include "np_cmd.h"
#include "np_search.h"
#include "np_unit.h"

static const char usage_text[] =
    "usage: noisepipe search --unit U [--config K=V,...] [-n N] [--seed S] [--threads T]\n"
    "                        [--journal FILE [--resume]]\n"
    "\n"
    "Tries N inputs chosen to break the unit's 1 LSB contract (a unit with 2 to 5 u16 inputs:\n"
    "x, y, z of the 3-D units, x .. w or x .. v of the n-D ones):\n"
    "extremes and the boundary table, lattice points and cell faces, equal offsets and the\n"
    "unit's own faces, the fractions where the internal roundings are worst (derived from\n"
    "the configuration's formats), seeded random inputs, and a hill-climb around the worst\n"
    "inputs found (docs/search.md). Prints the max error per output field and where, the\n"
    "inputs over 1 LSB, and the verdict: 'faithful (proved)' (the unit's error bound is\n"
    "<= 1 LSB), 'no counterexample in N adversarial inputs', or 'not faithful,\n"
    "counterexample (x, y, z)' with the model's output and the true value.\n"
    "\n"
    "  --unit U         the unit (classic3, simplex3, simplex4, classic5, ...: `noisepipe units`)\n"
    "  --config K=V,... its configuration (default: the unit's default)\n"
    "  -n N             inputs to evaluate in all (default 1000000, at least 4096)\n"
    "  --seed S         the generator's seed (default 1); same seed, same result, for any\n"
    "                   thread count\n"
    "  --threads T      worker threads (default: one per online CPU)\n"
    "  --journal FILE   append each completed chunk of 4096 inputs to FILE\n"
    "  --resume         continue FILE (refused when written for another unit, config, seed or N)\n"
    "\n"
    "Exit status: 0 when no input is over 1 LSB, 1 on a counterexample, 2 on bad usage.\n";

/* The unit's n input words of p as "(0xXXXX, 0xYYYY, ...)", and as words for eval. */
static const char *point_text(const np_search_pt *p, unsigned dims, char *buf, size_t len, uint64_t *in)
{
    snprintf(buf, len, "(");
    for (unsigned a = 0; a < NP_UNIT_MAX_FIELDS; a++)
        in[a] = a < dims ? p->in[a] : 0;
    for (unsigned a = 0; a < dims; a++)
        snprintf(buf + strlen(buf), len - strlen(buf), "%s0x%04x", a ? ", " : "", p->in[a]);
    snprintf(buf + strlen(buf), len - strlen(buf), ")");
    return buf;
}

static void print_result(const np_unit *u, const void *cfg, const np_search_opts *o, const np_search_result *r)
{
    const np_search_stats *s = &r->total;
    char cfgtext[256], verdict[128];
    np_unit_fields f;
    np_unit_cfg_format(u, cfg, cfgtext, sizeof cfgtext);
    u->fields(cfg, &f);
    printf("search of unit %s (%s), seed %" PRIu64 "\n", u->name, cfgtext, o->seed);
    printf("inputs evaluated    %" PRIu64 " (%" PRIu64 " chunks of %u, %" PRIu64 " resumed from the journal)\n",
           s->n, r->chunks, NP_SEARCH_CHUNK, r->chunks_resumed);
    for (unsigned c = 0; c < NP_SEARCH_CLASSES; c++)
        if (s->cls_n[c])
            printf("  %-28s %12" PRIu64 " inputs, max error %.6f LSB\n", np_search_class_name[c], s->cls_n[c],
                   s->cls_max[c]);
    for (unsigned k = 0; k < f.n_out; k++) {
        const np_search_pt *p = &s->fmax[k];
        uint64_t in[NP_UNIT_MAX_FIELDS], out[NP_UNIT_MAX_FIELDS];
        char at[64];
        double ref[NP_UNIT_MAX_FIELDS], sc = ldexp(1.0, (int)f.out[k].frac);
        point_text(p, f.n_in, at, sizeof at, in);
        u->eval(cfg, in, out);
        u->ref(cfg, in, ref);
        printf("field %-6s max error %.6f LSB at %s: output %.0f LSB, true %.6f LSB; "
               "over 1 LSB: %" PRIu64 "\n",
               f.out[k].name, p->err, at, np_unit_field_value(&f.out[k], out[k]) * sc, ref[k] * sc, s->fover[k]);
    }
    printf("inputs over %g LSB   %" PRIu64 "\n", u->tolerance_lsb, s->over);
    printf("error bound         %.6f LSB (the unit's error argument)%s\n", r->bound,
           r->bound <= 1.0 ? ": faithful by proof" : "");
    printf("wall time           %.2f s on %u thread%s, %.2f M inputs/s\n", r->seconds, r->threads,
           r->threads == 1 ? "" : "s", r->seconds > 0 ? (double)s->n / r->seconds * 1e-6 : 0.0);
    np_search_verdict_text(r, verdict, sizeof verdict);
    printf("verdict: %s", verdict);
    if (r->verdict == NP_SEARCH_COUNTEREXAMPLE) {
        uint64_t in[NP_UNIT_MAX_FIELDS], out[NP_UNIT_MAX_FIELDS];
        double ref[NP_UNIT_MAX_FIELDS];
        char at[64];
        point_text(&r->worst, f.n_in, at, sizeof at, in);
        u->eval(cfg, in, out);
        u->ref(cfg, in, ref);
        for (unsigned k = 0; k < f.n_out; k++) {
            double sc = ldexp(1.0, (int)f.out[k].frac);
            printf("%s %s = %.0f LSB, true %.4f LSB", k ? ";" : ":", f.out[k].name,
                   np_unit_field_value(&f.out[k], out[k]) * sc, ref[k] * sc);
        }
        printf(" (error %.4f LSB)", r->worst.err);
        if (r->bound <= 1.0)
            printf("; the error bound does NOT hold");
    }
    printf("\n");
}

int np_cmd_search(int argc, char **argv)
{
    const char *unit_name = NULL, *config = NULL;
    np_search_opts o;
    memset(&o, 0, sizeof o);
    o.n = 1000000;
    o.seed = 1;
    o.progress = 1;
    for (int k = 1; k < argc; k++) {
        const char *a = argv[k], *v = k + 1 < argc ? argv[k + 1] : NULL;
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            fputs(usage_text, stdout);
            return NP_EXIT_OK;
        }
        if (strcmp(a, "--resume") == 0) {
            o.resume = 1;
            continue;
        }
        if (!v) {
            np_err("search", "%s needs a value, or is unknown (see --help)", a);
            return NP_EXIT_USAGE;
        }
        uint64_t n;
        if (strcmp(a, "--unit") == 0)
            unit_name = v;
        else if (strcmp(a, "--config") == 0)
            config = v;
        else if (strcmp(a, "--journal") == 0)
            o.journal = v;
        else if (strcmp(a, "-n") == 0) {
            if (np_parse_u64(v, NP_SEARCH_CHUNK, UINT64_C(1) << 48, &o.n) != 0) {
                np_err("search", "-n %s: expected %u..2^48", v, NP_SEARCH_CHUNK);
                return NP_EXIT_USAGE;
            }
        } else if (strcmp(a, "--seed") == 0) {
            if (np_parse_u64(v, 0, UINT64_MAX, &o.seed) != 0) {
                np_err("search", "--seed %s: expected an unsigned integer", v);
                return NP_EXIT_USAGE;
            }
        } else if (strcmp(a, "--threads") == 0) {
            if (np_parse_u64(v, 1, 64, &n) != 0) {
                np_err("search", "--threads %s: expected 1..64", v);
                return NP_EXIT_USAGE;
            }
            o.threads = (unsigned)n;
        } else {
            np_err("search", "unknown option '%s' (see --help)", a);
            return NP_EXIT_USAGE;
        }
        k++;
    }
    if (!unit_name) {
        np_err("search", "--unit is required (see --help)");
        return NP_EXIT_USAGE;
    }
    if (o.resume && !o.journal) {
        np_err("search", "--resume needs --journal FILE");
        return NP_EXIT_USAGE;
    }
    const np_unit *u = np_unit_find(unit_name);
    if (!u) {
        np_err("search", "unknown unit '%s' (see noisepipe units)", unit_name);
        return NP_EXIT_USAGE;
    }
    np_unit_cfg cfg;
    char err[1024];
    if (np_unit_configure(u, &cfg, config, err, sizeof err) != 0) {
        np_err("search", "--config: %s", err);
        return NP_EXIT_USAGE;
    }
    o.unit = u;
    o.cfg = &cfg;
    np_search_result r;
    if (np_search_run(&o, &r, err, sizeof err) != 0) {
        np_err("search", "%s", err);
        return NP_EXIT_USAGE;
    }
    print_result(u, &cfg, &o, &r);
    return r.verdict == NP_SEARCH_COUNTEREXAMPLE ? NP_EXIT_FAIL : NP_EXIT_OK;
}
