/* SPDX-License-Identifier: MIT */
/* noisepipe report: gate and latency estimates; error against cost. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "np_common.h"
#include "np_outfile.h"
#include "np_cmd.h"
#include "np_pareto.h"
#include "np_render.h"
#include "render_cli.h"
#include "np_hatch.h"
#include "np_report.h"
#include "np_tradeoff.h"
#include "np_report_dims.h"
#include "np_anim4d.h"
#include "np_scene.h"
#include "np_synth.h"
#include "np_fpga.h"
#include "np_stream.h"
#include "np_wave_json.h"
#include "np_wave_scene.h"
#include "unit_span.h"

/* --levels: the target clock in gate levels the gate reports pipeline every stage to (np_report_levels_md). */
static unsigned g_levels = NP_REPORT_LEVELS_DEFAULT;
/* --sized: gates --scene with the span units' registers sized by the scene (np_scene.size_registers). */
static int g_sized;

static const char usage_text[] =
    "usage: noisepipe report gates  [--unit U] [--config K=V,...] [--levels N] [-o DIR]\n"
    "       noisepipe report gates  --scene SCENE.json [--sized] [--levels N] [-o DIR]\n"
    "       noisepipe report gates  --synth [--unit U] [--config K=V,...] [--rtl DIR] [--per-stage] [--abc-full] [--tolerance PCT]\n"
    "                                [--rtl-param NAME=V,...]\n"
    "       noisepipe report fpga   [--unit U] [--config K=V,...] [--rtl-param NAME=V,...] [--device hx8k|up5k]\n"
    "                                [--package P] [--freq MHZ] [--seed N] [--retime] [--rtl DIR] [-o DIR]\n"
    "       noisepipe report pareto [--unit U] [--samples N] [--seed S] [-o DIR]\n"
    "       noisepipe report runtime [--scene SCENE.json] [--repeat N] -o DIR\n"
    "       noisepipe report all    -o DIR        (what docs/ holds: gates + every pareto sweep + runtime in DIR/plots)\n"
    "       noisepipe report tradeoff --scene SCENE.json [-o DIR]   (fdiff against texel at <= 1 LSB: gates x cycles\n"
    "                                     against image size and octave count; DIR/tradeoff-NAME.{md,svg})\n"
    "       noisepipe report dims   [-o DIR]      (noise in n = 2..5 dimensions: gates against n, Perlin's claims)\n"
    "       noisepipe report dims   --synth -o DIR [--unit U] [--rtl DIR] [--per-stage] [--tolerance PCT]\n"
    "                                     (the n-D RTL through Yosys beside the model: DIR/dims-synth.md; each\n"
    "                                     synthesis cached in DIR/synth-cache/, reused while the RTL is unchanged)\n"
    "       noisepipe report anim4d [--frames N] -o DIR  (a time-varying solid texture through simplex4: PNG frames)\n"
    "\n"
    "gates: per unit and per stage, the operators, register bits, gate estimate (NAND2\n"
    "  equivalents, docs/cost-model.md), latency in clocks (from the cycle-accurate model),\n"
    "  throughput and critical path. Every unit with a datapath declaration by default, each in\n"
    "  its default configuration. Without -o, Markdown on stdout; with -o, DIR/gates.md and\n"
    "  DIR/gates.json.\n"
    "  --scene: only what the scene needs: the units it uses (configured from it: its texture's\n"
    "  octaves, transforms and colour table), which outputs it reads, how many units and passes,\n"
    "  the cycles per frame from each unit's cycle-accurate model; the units it does not use are\n"
    "  listed as left out. A scene with an \"aa\" section also prices aacount from it (m, the\n"
    "  metrics it enables, luma_taps, tile), parallel and serial. With -o, DIR/scene-NAME-gates.md\n"
    "  and .json. A wave scene (a \"waves\" section): the wave unit with the effects the scene does\n"
    "  not use left out, and the frame's cycles with the culled boxes left out.\n"
    "  --sized (with --scene): the span units' registers sized by the scene - the fewest\n"
    "  transform, quadric, index and guard bits whose predicted bound is <= 1 LSB (render\n"
    "  --sized renders with them) - instead of the default widths; DIR/scene-NAME-sized-gates.md.\n"
    "  --synth: synthesise the reference RTL (rtl_model/verilog, or --rtl DIR) with Yosys + ABC\n"
    "  and print its NAND2 equivalents per stage beside the cost model's (classic3, simplex3;\n"
    "  with --unit also wave, aacount, hatch, classic2/4/5, simplex2/4/5; docs/cost-model.md). Needs\n"
    "  yosys (exit 2 without it); --tolerance PCT: exit 1 when a stage is more than PCT % from\n"
    "  synthesis; --per-stage: ABC on each stage's cone alone\n"
    "  (much faster on simplex3; within a few % of the whole-design flow on classic3); ABC\n"
    "  runs its default script with the SAT sweep bounded (&fraig -x -C 1000), --abc-full: unbounded.\n"
    "  --rtl-param NAME=V,...: RTL parameters that are not configuration keys (with --unit;\n"
    "  classic3: IN_REG, OUT_SKID, S_TABLE, HASH_SERIAL, LERP_SERIAL; simplex3, wave, aacount, hatch:\n"
    "  IN_REG, OUT_SKID; docs/rtl.md):\n"
    "  Yosys per stage beside the cost model of the as-built circuit, labelled so (no --tolerance).\n"
    "fpga: each unit with reference RTL (or U) through the open iCE40 flow (docs/fpga.md): Yosys\n"
    "  synth_ice40, nextpnr-ice40, icepack, icetime. Prints the unit's LUT4s, flip-flops, carries and\n"
    "  block RAMs, the placed design's logic cells, Fmax after routing with its critical path (the\n"
    "  registers and stages it runs between), icetime's Fmax, results per second, and the seed.\n"
    "  The unit sits in a generated I/O harness (its ports shift in and out on two pins). --device\n"
    "  (default hx8k, package ct256; up5k: sg48), --freq the target (default 12 MHz, the boards'\n"
    "  oscillator), --seed nextpnr's (default 1), --retime: also with synth_ice40 -retime (what\n"
    "  retiming gains, measured). -o DIR keeps DIR/fpga.md and DIR/fpga-UNIT.{bin,asc,json,report.json,\n"
    "  nextpnr.log}. Exit 1 when a unit does not place and route (it does not fit: the tool's message).\n"
    "pareto: the design-space sweep of a unit's internal widths: each configuration's verdict\n"
    "  (faithful (proved), no counterexample in N adversarial inputs, not faithful with the\n"
    "  counterexample) and the adversarial search's max error against gates and latency;\n"
    "  DIR/pareto-UNIT.{md,json,svg}. --samples: the search's budget per configuration\n"
    "  (default 262144, docs/search.md); --seed (default 1).\n"
    "runtime: error against run time: every unit that renders the scene (default: the seed scenes\n"
    "  wood and marble), over each of the unit's sweeps (guard bits, re-set-up interval, set-up\n"
    "  multipliers, weight bits): max error against the float reference, cycles per frame, model\n"
    "  time (best of --repeat N runs, default 3); DIR/error_runtime.{md,csv}, plots and images.\n";

/*
 * Open DIR/name for writing through np_outfile (atomic for a regular file,
 * written through a symbolic link, refused for a directory; removed on a
 * signal); commit() finishes it. One report file is open at a time.
 */
static np_outfile report_out;

static FILE *open_tmp(const char *dir, const char *name, char *tmp, char *final, size_t len)
{
    snprintf(final, len, "%s/%s", dir, name);
    snprintf(tmp, len, "%s", final);
    if (np_outfile_open(&report_out, final, "w") != 0) {
        np_err("report", "cannot write %s", report_out.err);
        return NULL;
    }
    return report_out.f;
}

static int commit(FILE *f, const char *tmp, const char *final)
{
    (void)tmp;
    (void)final;
    if (f != report_out.f || np_outfile_close(&report_out, 1) != 0) {
        np_err("report", "cannot write %s", report_out.err);
        return -1;
    }
    return 0;
}

static int write_gates(const char *dir, const np_unit *only, const char *spec)
{
    size_t nunits = 0;
    while (np_unit_at(nunits) != NULL)
        nunits++;
    np_unit_cost *costs = calloc(nunits ? nunits : 1, sizeof *costs);
    size_t n = 0;
    char err[256];
    if (!costs)
        return NP_EXIT_USAGE;
    const np_unit *u;
    for (size_t i = 0; (u = np_unit_at(i)) != NULL && n < nunits; i++) {
        if ((only && u != only) || !u->datapath)
            continue;
        np_unit_cfg cfg;
        if (np_unit_configure(u, &cfg, only ? spec : NULL, err, sizeof err) != 0 ||
            np_unit_cost_compute(u, &cfg, &np_cost_default, &costs[n], err, sizeof err) != 0) {
            np_err("report", "%s: %s", u->name, err);
            free(costs);
            return NP_EXIT_USAGE;
        }
        n++;
    }
    if (n == 0) {
        np_err("report", "unit %s declares no datapath", only ? only->name : "(any)");
        free(costs);
        return NP_EXIT_USAGE;
    }
    int rc = NP_EXIT_OK;
    if (!dir) {
        np_report_gates_md(stdout, costs, n, "Gate and latency estimates");
        np_report_levels_md(stdout, costs, n, g_levels);
    } else {
        char tmp[1024], fin[1024];
        FILE *f = open_tmp(dir, "gates.md", tmp, fin, sizeof tmp);
        if (!f)
            rc = NP_EXIT_USAGE;
        else {
            np_report_gates_md(f, costs, n, "Gate and latency estimates");
            np_report_levels_md(f, costs, n, g_levels);
            rc = commit(f, tmp, fin) ? NP_EXIT_USAGE : rc;
        }
        f = rc ? NULL : open_tmp(dir, "gates.json", tmp, fin, sizeof tmp);
        if (f) {
            np_report_gates_json(f, costs, n);
            rc = commit(f, tmp, fin) ? NP_EXIT_USAGE : rc;
        } else
            rc = NP_EXIT_USAGE;
        if (rc == NP_EXIT_OK)
            printf("wrote %s/gates.md and %s/gates.json (%zu units)\n", dir, dir, n);
    }
    free(costs);
    return rc;
}

/* --- Per scene --- */

typedef struct scene_unit {
    const np_unit *u;
    np_unit_cfg cfg;
    int have_frame;
    int renders;          /* 1: a span unit that renders the scene; 0: another unit it uses (aacount) */
    uint64_t cycles, setup_stalls, pixels, spans;
    /* --sized: the set-up engine sizes tried (setup_mults), their gates and frame cycles; chosen: the least gates x cycles. */
    unsigned n_p, p[5], chosen;
    double p_gates[5];
    uint64_t p_cycles[5], p_stalls[5];
} scene_unit;

static int scene_frame(scene_unit *su, const np_render_frame *fr);

/*
 * --sized (issue 14): the set-up multiplier count chosen for the scene by
 * the least gates x cycles over P = 1, 2, 4, 8, 16 (those the unit's key
 * takes), each priced and run through the stream model on the frame; su
 * and c become the chosen one's. 0, or -1 with err.
 */
static int scene_choose_p(scene_unit *su, np_unit_cost *c, const np_render_frame *fr, char *err, size_t errlen)
{
    static const unsigned ps[] = { 1, 2, 4, 8, 16 };
    scene_unit best = *su;
    np_unit_cost *cb = malloc(sizeof *cb), *ct = malloc(sizeof *ct);
    double best_gc = (double)INFINITY;
    int rc = cb && ct ? 0 : -1;
    su->n_p = 0;
    for (size_t i = 0; i < sizeof ps / sizeof ps[0] && rc == 0; i++) {
        scene_unit t = *su;
        char v[16], e2[256];
        snprintf(v, sizeof v, "%u", ps[i]);
        if (np_unit_cfg_set(su->u, &t.cfg, "setup_mults", v, e2, sizeof e2) != 0)
            continue; /* beyond the unit's engine */
        if (np_unit_cost_compute(su->u, &t.cfg, &np_cost_default, ct, err, errlen) != 0 || scene_frame(&t, fr) != 0) {
            if (!err[0])
                snprintf(err, errlen, "setup_mults=%u: the stream model did not finish the frame", ps[i]);
            rc = -1;
            break;
        }
        unsigned k = su->n_p++;
        su->p[k] = ps[i];
        su->p_gates[k] = ct->total;
        su->p_cycles[k] = t.cycles;
        su->p_stalls[k] = t.setup_stalls;
        const double gc = ct->total * (double)t.cycles;
        if (gc < best_gc) {
            best_gc = gc;
            best = t;
            *cb = *ct;
            su->chosen = ps[i];
        }
    }
    if (rc == 0 && su->n_p) {
        unsigned n_p = su->n_p, chosen = su->chosen;
        unsigned p[5];
        double g[5];
        uint64_t cy[5], st[5];
        memcpy(p, su->p, sizeof p);
        memcpy(g, su->p_gates, sizeof g);
        memcpy(cy, su->p_cycles, sizeof cy);
        memcpy(st, su->p_stalls, sizeof st);
        *su = best;
        su->n_p = n_p;
        su->chosen = chosen;
        memcpy(su->p, p, sizeof p);
        memcpy(su->p_gates, g, sizeof g);
        memcpy(su->p_cycles, cy, sizeof cy);
        memcpy(su->p_stalls, st, sizeof st);
        *c = *cb;
    }
    free(cb);
    free(ct);
    return rc;
}

/* Index of the input field called name, or -1. */
static int field_index(const np_unit_fields *f, const char *name)
{
    for (unsigned i = 0; i < f->n_in; i++)
        if (strcmp(f->in[i].name, name) == 0)
            return (int)i;
    return -1;
}

/*
 * The frame through the unit's stream model, descriptor after descriptor,
 * no backpressure: clocks from the first descriptor to the last pixel out.
 * The descriptor's fields are found by name (s t r ds dt dr n); 0, or -1
 * when the unit's descriptor does not have them or the model stops.
 */
static int scene_frame(scene_unit *su, const np_render_frame *fr)
{
    const np_unit_stream *st = su->u->stream;
    np_unit_fields f;
    su->u->fields(&su->cfg, &f);
    static const char *const names[7] = { "s", "t", "r", "ds", "dt", "dr", "n" };
    int idx[7];
    for (int i = 0; i < 7; i++)
        if ((idx[i] = field_index(&f, names[i])) < 0)
            return -1;
    void *state = calloc(1, st->state_size);
    if (!state || st->init(state, &su->cfg) != 0) {
        free(state);
        return -1;
    }
    size_t next = 0;
    uint64_t beats = 0, cyc = 0, d[NP_UNIT_MAX_FIELDS];
    int rc = 0;
    for (;;) {
        np_unit_stream_port p;
        memset(&p, 0, sizeof p);
        if (next < fr->n_spans) {
            const np_span *sp = &fr->spans[next].hw;
            memset(d, 0, sizeof d);
            for (int a = 0; a < 3; a++) {
                unsigned i = (unsigned)idx[a], j = (unsigned)idx[3 + a];
                d[i] = np_trunc_u((uint64_t)sp->s[a], f.in[i].bits);
                d[j] = np_trunc_u((uint64_t)sp->ds[a], f.in[j].bits);
            }
            d[idx[6]] = sp->n;
            p.in_valid = 1;
            p.in = d;
        }
        p.out_ready = 1;
        st->eval(state, &p);
        if (p.in_valid && p.in_ready)
            next++;
        if (p.out_valid)
            beats++;
        st->clock(state, &p);
        cyc++;
        if (next == fr->n_spans && st->idle(state))
            break;
        if (cyc > 4000000000u) {
            rc = -1;
            break;
        }
    }
    uint64_t c = 0, stalls = 0;
    st->counters(state, &c, &stalls);
    st->free(state);
    free(state);
    su->have_frame = rc == 0 && beats == fr->pixels;
    su->cycles = cyc;
    su->setup_stalls = stalls;
    su->pixels = beats;
    su->spans = fr->n_spans;
    return su->have_frame ? 0 : -1;
}

static void scene_md(FILE *f, const np_scene *sc, const np_render_frame *fr, const scene_unit *su,
                     const np_unit_cost *c, size_t n, const np_unit *const *left, size_t nleft)
{
    char title[160];
    snprintf(title, sizeof title, "Gate and latency estimates for scene %s", sc->name);
    const np_ref_texture *t = &sc->tex;
    int diag = np_tex_regs_diagonal(&fr->regs);
    fprintf(f, "# %s\n\n", title);
    fprintf(f, "Generated by `noisepipe report gates --scene %s`. Cost model: [cost-model.md](cost-model.md). "
               "Gates are NAND2 equivalents; delays are gate levels.\n\n", sc->path);
    fprintf(f, "## What the scene needs\n\n");
    if (sc->noise.present) /* texture.noise: the octaves read a 4-D noise unit, time its fourth input */
        fprintf(f, "- **texture:** 4-D noise `%s` (w register u16 Q8.8, %u frames), %u octave%s (%s transforms), "
                   "a quadric, a %u-entry %s colour table; shaded on the G-buffer, one noise transaction per "
                   "covered pixel and octave (docs/noise-nd.md)\n",
                sc->noise.unit, sc->noise.frames, t->n_oct, t->n_oct == 1 ? "" : "s", diag ? "diagonal" : "general",
                t->cmap.n, t->cmap.repeat ? "repeating" : "clamped");
    else
        fprintf(f, "- **texture:** lattice value noise, %u octave%s (%s transforms), a quadric, a %u-entry %s colour table\n",
                t->n_oct, t->n_oct == 1 ? "" : "s", diag ? "diagonal" : "general", t->cmap.n,
                t->cmap.repeat ? "repeating" : "clamped");
    fprintf(f, "- **outputs read:** the colour (RGB, 8 bits each); no derivative is read, so no derivative "
               "datapath is counted\n");
    if (sc->noise.present)
        fprintf(f, "- **octaves:** %u, one noise transaction each, one transaction a clock through one unit: "
                   "%llu transactions per frame\n", t->n_oct, (unsigned long long)fr->pixels * t->n_oct);
    else
        fprintf(f, "- **octaves:** %u, evaluated in parallel inside one unit (one octave lane each): 1 unit, 1 pass "
                   "per frame\n", t->n_oct);
    fprintf(f, "- **frame:** %ux%u, %llu covered pixels in %zu spans (longest %u)\n", sc->width, sc->height,
            (unsigned long long)fr->pixels, fr->n_spans, fr->longest);
    if (!sc->noise.present) {
        fprintf(f, "- **units that can render it** (either one; both are priced here, configured from the scene):");
        for (size_t i = 0, k = 0; i < n; i++)
            if (su[i].renders)
                fprintf(f, "%s `%s`", k++ ? "," : "", c[i].unit->name);
    } else
        fprintf(f, "- **span units:** none renders a 4-D noise texture");
    for (size_t i = 0; i < n; i++)
        if (!su[i].renders)
            fprintf(f, "\n- **also used:** `%s` `%s` (configured from the scene's section for it%s)", c[i].unit->name,
                    c[i].cfg,
                    strcmp(c[i].unit->name, "aacount") == 0 ? "; c_d at a depth range of 1: the register's value, not the datapath"
                    : strcmp(c[i].unit->name, "hatch") == 0 ? "; coverage logic only with mode coverage, the smoothstep only "
                                                              "with fade onebyone, only the scene's layers"
                                                            : "");
    fprintf(f, "\n- **left out** (the scene does not use them):");
    for (size_t i = 0; i < nleft; i++)
        fprintf(f, "%s `%s`", i ? "," : "", left[i]->name);
    fprintf(f, "%s\n\n", nleft ? "" : " none");
    /*
     * The registers' widths (issue 10): the default ones, or (--sized) the
     * fewest whose predicted bound over this scene is <= 1 LSB.
     */
    fprintf(f, "Registers %s: the predicted bound is the unit's own over the scene's widest span (%u pixels) plus "
               "the registers' rounding over its texture coordinates (docs/fdiff.md).\n\n",
            sc->size_registers ? "**sized by the scene** (`--sized`: the fewest transform, quadric, index and guard "
                                 "bits whose predicted bound is <= 1 LSB)"
                               : "at the units' default widths (`--sized` prices the scene-sized ones)",
            sc->width);
    fprintf(f, "| unit | configuration | quadric A'..J' | transform M | predicted bound |\n| --- | --- | --- | --- | ---: |\n");
    for (size_t i = 0; i < n; i++) {
        if (!su[i].renders)
            continue;
        const unsigned tex = np_su_texture(c[i].unit->span, &su[i].cfg);
        const np_tex_regs *rg = np_ut_regs(tex);
        fprintf(f, "| %s | `%s` | s%u Q%u.%u | s%u Q%u.%u | %.3f LSB |\n", c[i].unit->name, c[i].cfg, np_tex_k_bits(rg),
                np_tex_k_bits(rg) - 1u - np_tex_k_frac(rg), np_tex_k_frac(rg), np_tex_m_bits(rg),
                np_tex_m_bits(rg) - 1u - np_tex_m_frac(rg), np_tex_m_frac(rg),
                np_su_predicted_lsb(c[i].unit, &su[i].cfg, sc->width));
    }
    fprintf(f, "\n");
    for (size_t i = 0; i < n; i++) {
        if (!su[i].renders || !su[i].n_p)
            continue;
        fprintf(f, "Set-up multipliers of %s (`setup_mults`), chosen for this scene by the least gates x cycles "
                   "(the stream model on the frame):\n\n| P | gates | cycles / frame | set-up stall cycles | gates x "
                   "cycles |\n| ---: | ---: | ---: | ---: | ---: |\n",
                c[i].unit->name);
        for (unsigned k = 0; k < su[i].n_p; k++)
            fprintf(f, "| %s%u%s | %.0f | %llu | %llu | %.3g |\n", su[i].p[k] == su[i].chosen ? "**" : "", su[i].p[k],
                    su[i].p[k] == su[i].chosen ? " (chosen)**" : "", su[i].p_gates[k],
                    (unsigned long long)su[i].p_cycles[k], (unsigned long long)su[i].p_stalls[k],
                    su[i].p_gates[k] * (double)su[i].p_cycles[k]);
        fprintf(f, "\n");
    }
    fprintf(f, "| unit | octave lanes | gates | latency | throughput | cycles / frame (cycle model) | set-up stalls | cycles / pixel |\n");
    fprintf(f, "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
    for (size_t i = 0; i < n; i++) {
        if (!su[i].renders)
            continue;
        fprintf(f, "| %s | %u | %.0f | %u clocks | %g / clock | ", c[i].unit->name, t->n_oct, c[i].total, c[i].latency,
                c[i].throughput);
        if (su[i].have_frame)
            fprintf(f, "%llu | %llu | %.2f |\n", (unsigned long long)su[i].cycles,
                    (unsigned long long)su[i].setup_stalls,
                    su[i].pixels ? (double)su[i].cycles / (double)su[i].pixels : 0.0);
        else
            fprintf(f, "— | — | — |\n");
    }
    fprintf(f, "\n");
    size_t others = 0;
    for (size_t i = 0; i < n; i++)
        others += !su[i].renders;
    if (others) {
        fprintf(f, "Other units the scene uses, each variant priced (a metric the scene does not enable is not "
                   "built: no gates):\n\n| unit | configuration | gates | latency | throughput |\n"
                   "| --- | --- | ---: | ---: | ---: |\n");
        for (size_t i = 0; i < n; i++)
            if (!su[i].renders)
                fprintf(f, "| %s | `%s` | %.0f | %u clocks | %g / clock |\n", c[i].unit->name, c[i].cfg, c[i].total,
                        c[i].latency, c[i].throughput);
        fprintf(f, "\n");
    }
    /* The per-unit tables (the same format as gates.md), without its title. */
    char *buf = NULL;
    size_t len = 0;
    FILE *m = open_memstream(&buf, &len);
    if (m) {
        np_report_gates_md(m, c, n, title);
        np_report_levels_md(m, c, n, g_levels);
        fclose(m);
        const char *body = strstr(buf, "\n| unit |");
        fputs(body ? body + 1 : buf, f);
        free(buf);
    }
}

static void scene_json(FILE *f, const np_scene *sc, const np_render_frame *fr, const scene_unit *su,
                       const np_unit_cost *c, size_t n, const np_unit *const *left, size_t nleft)
{
    const np_ref_texture *t = &sc->tex;
    fprintf(f, "{\n  \"generator\": \"noisepipe report gates --scene\",\n  \"scene\": \"%s\",\n", sc->name);
    fprintf(f, "  \"octaves\": %u,\n  \"diagonal_transforms\": %s,\n  \"colour_table\": { \"entries\": %u, \"repeat\": %s },\n",
            t->n_oct, np_tex_regs_diagonal(&fr->regs) ? "true" : "false", t->cmap.n, t->cmap.repeat ? "true" : "false");
    fprintf(f, "  \"outputs_read\": [\"rgb\"],\n  \"derivative_datapath\": false,\n  \"units_per_frame\": 1,\n"
               "  \"passes\": 1,\n  \"pixels\": %llu,\n  \"spans\": %zu,\n  \"left_out\": [",
            (unsigned long long)fr->pixels, fr->n_spans);
    for (size_t i = 0; i < nleft; i++)
        fprintf(f, "%s\"%s\"", i ? ", " : "", left[i]->name);
    fprintf(f, "],\n  \"frame\": [");
    for (size_t i = 0, k = 0; i < n; i++)
        if (su[i].renders)
            fprintf(f, "%s\n    { \"unit\": \"%s\", \"octave_lanes\": %u, \"total_gates\": %.1f, \"cycles\": %llu, "
                       "\"setup_stalls\": %llu, \"pixels\": %llu }",
                    k++ ? "," : "", c[i].unit->name, t->n_oct, c[i].total, (unsigned long long)su[i].cycles,
                    (unsigned long long)su[i].setup_stalls, (unsigned long long)su[i].pixels);
    fprintf(f, " ],\n  \"also_used\": [");
    for (size_t i = 0, k = 0; i < n; i++)
        if (!su[i].renders)
            fprintf(f, "%s\n    { \"unit\": \"%s\", \"config\": \"%s\", \"total_gates\": %.1f, \"latency\": %u }",
                    k++ ? "," : "", c[i].unit->name, c[i].cfg, c[i].total, c[i].latency);
    fprintf(f, " ],\n  \"gates\": ");
    np_report_gates_json(f, c, n);
    fprintf(f, "}\n");
}

/*
 * The gate report of a wave scene (a file with a "waves" section, docs/wave.md):
 * the wave unit configured from what the scene uses - lanes = its `lanes`,
 * irr and cap only when it has irregular height or capillary noise (the
 * effects it does not use are left out of the datapath; refraction and round
 * waves are per-ray phases, no unit gates); the normals and the fold flag
 * only when the scene reads them ("normals", "fold") - and the frame's cycles with the culled boxes
 * left out (each costs its 6 plane tests, nothing per point). Widths are
 * priced at the registry's test register set (regs=1), which fills the output
 * range: an upper bound for a scene's registers.
 */
static void wave_scene_md(FILE *f, const char *path, const np_wave_scene *s, const np_wave_plan *p, const char *cfg_text,
                          const np_unit_cost *used, const np_unit_cost *full, const char *full_text)
{
    const unsigned fx = s->effects;
    np_wave_plan none = *p;
    unsigned vis = 0, culled = 0;
    for (unsigned k = 0; k < s->nbox; k++) {
        vis += (unsigned)(p->visible[k] != 0);
        none.visible[k] = 0;
        none.sel[k] = 0;
    }
    culled = s->nbox - vis;
    uint64_t cyc = np_wave_plan_cycles(s, p);
    fprintf(f, "# Gate and latency estimates for wave scene %s\n\n", path);
    fprintf(f, "Generated by `noisepipe report gates --scene %s`. Cost model: [cost-model.md](cost-model.md). "
               "Gates are NAND2 equivalents; widths priced at the test register set (regs=1), which fills the "
               "output range (an upper bound for this scene's registers).\n\n", path);
    fprintf(f, "## What the scene needs\n\n");
    fprintf(f, "- **unit:** `wave` %s (lanes = the scene's `lanes`: %u)\n", cfg_text, s->lanes);
    fprintf(f, "- **effects in the datapath:** irregular height (eq. (8)) %s; capillary noise (eq. (9)) %s\n",
            fx & NP_WAVE_FX_IRREGULAR ? "used" : "**left out** (irr=0)",
            fx & NP_WAVE_FX_NOISE ? "used" : "**left out** (cap=0)");
    fprintf(f, "- **effects on the host, no unit gates:** refraction %s, round waves %s (per-ray phase ph)\n",
            fx & NP_WAVE_FX_REFRACTION ? "used" : "not used", fx & NP_WAVE_FX_ROUND ? "used" : "not used");
    fprintf(f, "- **outputs read:** y, dx, dz; normals nx, ny, nz %s; fold flag %s\n",
            s->reads_normals ? "read" : "**left out** (normals=0)", s->reads_fold ? "read" : "**left out** (fold=0)");
    fprintf(f, "- **boxes:** %u, %u visible, %u culled%s\n", s->nbox, vis, culled,
            s->has_camera ? " by the camera's frustum" : " (no camera: every box visible)");
    fprintf(f, "- **gates:** %.0f for what the scene uses; %.0f with every effect (`%s`): %.0f left out\n\n",
            used->total, full->total, full_text, full->total - used->total);
    fprintf(f, "| box | trains | rays | points | visible | cycles a frame | saved if culled |\n");
    fprintf(f, "| ---: | ---: | ---: | ---: | --- | ---: | ---: |\n");
    for (unsigned k = 0; k < s->nbox; k++) {
        np_wave_plan q = *p, one = none;
        q.visible[k] = 0;
        q.sel[k] = 0;
        one.visible[k] = p->visible[k];
        one.sel[k] = p->sel[k];
        one.noise = 0;
        const np_wave_box *b = &s->box[k];
        uint64_t own = np_wave_plan_cycles(s, &one) - np_wave_plan_cycles(s, &none) + NP_WAVE_CYC_CULL;
        fprintf(f, "| %u | %u | %u | %zu | %s | %llu | %llu |\n", k, b->unit.r.n, b->rays, b->npts,
                p->visible[k] ? "yes" : "culled", (unsigned long long)own,
                (unsigned long long)(np_wave_plan_cycles(s, p) - np_wave_plan_cycles(s, &q)));
    }
    fprintf(f, "\n**Frame:** %llu cycles (culling %u, the noise pass %s); every box culled: %llu.\n\n",
            (unsigned long long)cyc, NP_WAVE_CYC_CULL * s->nbox, p->noise ? "included" : "not used",
            (unsigned long long)np_wave_plan_cycles(s, &none));
    /* The unit's tables (the same format as gates.md), without its title. */
    char *buf = NULL;
    size_t len = 0;
    FILE *m = open_memstream(&buf, &len);
    if (m) {
        np_report_gates_md(m, used, 1, "wave");
        fclose(m);
        const char *body = strstr(buf, "\n| unit |");
        fputs(body ? body + 1 : buf, f);
        free(buf);
    }
}

static int write_wave_scene(const char *dir, const char *path)
{
    static np_wave_scene s;
    char err[512] = "", spec[96], cfg_text[256], full_text[256];
    unsigned dropped = 0;
    if (np_wave_scene_read(path, &s, NULL, err, sizeof err) != 0) {
        np_err("report", "%s", err);
        return NP_EXIT_USAGE;
    }
    if (np_wave_scene_prepare(&s, &dropped, err, sizeof err) != 0) {
        np_err("report", "%s: %s", path, err);
        np_wave_scene_free(&s);
        return NP_EXIT_USAGE;
    }
    const np_unit *u = np_unit_find("wave");
    np_unit_cfg cu, cf;
    np_unit_cost used, full;
    np_wave_plan p;
    np_wave_plan_full(&s, &p);
    int rc = NP_EXIT_OK;
    snprintf(spec, sizeof spec, "trains=%u,irr=%u,cap=%u,normals=%u,fold=%u", s.lanes,
             (s.effects & NP_WAVE_FX_IRREGULAR) ? 1u : 0u, (s.effects & NP_WAVE_FX_NOISE) ? 1u : 0u,
             s.reads_normals ? 1u : 0u, s.reads_fold ? 1u : 0u);
    if (!u || np_unit_configure(u, &cu, spec, err, sizeof err) != 0 ||
        np_unit_cost_compute(u, &cu, &np_cost_default, &used, err, sizeof err) != 0) {
        np_err("report", "%s: wave %s: %s", path, spec, u ? err : "no wave unit");
        rc = NP_EXIT_USAGE;
    }
    snprintf(spec, sizeof spec, "trains=%u,irr=1,cap=1,normals=1,fold=1", s.lanes);
    if (rc == NP_EXIT_OK && (np_unit_configure(u, &cf, spec, err, sizeof err) != 0 ||
                             np_unit_cost_compute(u, &cf, &np_cost_default, &full, err, sizeof err) != 0)) {
        np_err("report", "%s: wave %s: %s", path, spec, err);
        rc = NP_EXIT_USAGE;
    }
    if (rc == NP_EXIT_OK) {
        np_unit_cfg_format(u, &cu, cfg_text, sizeof cfg_text);
        np_unit_cfg_format(u, &cf, full_text, sizeof full_text);
        if (!dir)
            wave_scene_md(stdout, path, &s, &p, cfg_text, &used, &full, full_text);
        else {
            char tmp[1024], fin[1024], name[256];
            const char *bn = strrchr(path, '/');
            snprintf(name, sizeof name, "scene-%s", bn ? bn + 1 : path);
            char *dot = strrchr(name, '.');
            if (dot)
                *dot = '\0';
            strncat(name, "-gates.md", sizeof name - strlen(name) - 1);
            FILE *f = open_tmp(dir, name, tmp, fin, sizeof tmp);
            if (!f)
                rc = NP_EXIT_USAGE;
            else {
                wave_scene_md(f, path, &s, &p, cfg_text, &used, &full, full_text);
                rc = commit(f, tmp, fin) ? NP_EXIT_USAGE : rc;
            }
        }
    }
    np_wave_scene_free(&s);
    return rc;
}

/* A wave scene: a JSON file with a "waves" section (np_wave_json.h); else a texture scene (np_scene.h). */
static int is_wave_scene(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return 0;
    char buf[65536];
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    fclose(f);
    buf[n] = '\0';
    return strstr(buf, "\"waves\"") != NULL;
}

static int write_scene(const char *dir, const char *path)
{
    enum { MAXU = 16 };
    np_scene sc;
    np_render_frame fr;
    char err[512];
    if (np_scene_load(path, &sc, err, sizeof err) != 0) {
        np_err("report", "%s", err);
        return NP_EXIT_USAGE;
    }
    sc.size_registers = g_sized;
    if (np_render_prepare(&sc, &fr, err, sizeof err) != 0) {
        np_err("report", "%s", err);
        np_scene_free(&sc);
        return NP_EXIT_USAGE;
    }
    np_unit_cost *costs = calloc(MAXU, sizeof *costs);
    scene_unit *su = calloc(MAXU, sizeof *su);
    const np_unit *left[MAXU];
    size_t n = 0, nleft = 0;
    int rc = costs && su ? NP_EXIT_OK : NP_EXIT_USAGE;
    const np_unit *u;
    for (size_t i = 0; (u = np_unit_at(i)) != NULL && rc == NP_EXIT_OK && n < MAXU; i++) {
        if (!u->datapath)
            continue;
        int used = np_scene_cfg_unit(u, &su[n].cfg, &sc, err, sizeof err);
        if (used < 0) {
            np_err("report", "%s: %s: %s", path, u->name, err);
            rc = NP_EXIT_USAGE;
        } else if (used == 0) {
            if (nleft < MAXU)
                left[nleft++] = u;
        } else {
            su[n].u = u;
            su[n].renders = u->span != NULL;
            if (np_unit_cost_compute(u, &su[n].cfg, &np_cost_default, &costs[n], err, sizeof err) != 0) {
                np_err("report", "%s: %s", u->name, err);
                rc = NP_EXIT_USAGE;
            } else {
                /* The hatching unit's coverage logic is set by the scene (not a key): say so in its configuration. */
                const np_hatch_cfg *hc = (const void *)su[n].cfg.bytes;
                if (strcmp(u->name, "hatch") == 0 && hc->cover_slots)
                    snprintf(costs[n].cfg + strlen(costs[n].cfg), sizeof costs[n].cfg - strlen(costs[n].cfg),
                             " mode=coverage slots=%u", hc->cover_slots);
                if (u->stream && su[n].renders)
                    scene_frame(&su[n], &fr);
                err[0] = '\0';
                if (g_sized && u->stream && su[n].renders && scene_choose_p(&su[n], &costs[n], &fr, err, sizeof err) != 0) {
                    np_err("report", "%s: %s", u->name, err);
                    rc = NP_EXIT_USAGE;
                    break;
                }
                n++;
                /* A unit with a serial variant (aacount): priced beside the parallel one. */
                if (!su[n - 1].renders && n < MAXU) {
                    su[n] = su[n - 1];
                    char e2[256];
                    if (np_unit_cfg_set(u, &su[n].cfg, "serial", "1", e2, sizeof e2) == 0) {
                        if (np_unit_cost_compute(u, &su[n].cfg, &np_cost_default, &costs[n], err, sizeof err) != 0) {
                            np_err("report", "%s serial: %s", u->name, err);
                            rc = NP_EXIT_USAGE;
                        } else
                            n++;
                    }
                }
            }
        }
    }
    if (rc == NP_EXIT_OK && n == 0) {
        np_err("report", "%s: no unit declares what this scene needs", path);
        rc = NP_EXIT_USAGE;
    }
    if (rc == NP_EXIT_OK) {
        if (!dir) {
            scene_md(stdout, &sc, &fr, su, costs, n, left, nleft);
        } else {
            char name[128], tmp[1024], fin[1024];
            snprintf(name, sizeof name, "scene-%s%s-gates.md", sc.name, g_sized ? "-sized" : "");
            FILE *f = open_tmp(dir, name, tmp, fin, sizeof tmp);
            if (f) {
                scene_md(f, &sc, &fr, su, costs, n, left, nleft);
                rc = commit(f, tmp, fin) ? NP_EXIT_USAGE : rc;
            } else
                rc = NP_EXIT_USAGE;
            snprintf(name, sizeof name, "scene-%s%s-gates.json", sc.name, g_sized ? "-sized" : "");
            f = rc ? NULL : open_tmp(dir, name, tmp, fin, sizeof tmp);
            if (f) {
                scene_json(f, &sc, &fr, su, costs, n, left, nleft);
                rc = commit(f, tmp, fin) ? NP_EXIT_USAGE : rc;
            } else
                rc = NP_EXIT_USAGE;
            if (rc == NP_EXIT_OK)
                printf("wrote %s/scene-%s%s-gates.md and .json (%zu units)\n", dir, sc.name, g_sized ? "-sized" : "", n);
        }
    }
    free(costs);
    free(su);
    np_render_frame_free(&fr);
    np_scene_free(&sc);
    return rc;
}

static int write_pareto(const char *dir, const np_unit *only, uint64_t samples, uint64_t seed)
{
    int any = 0;
    for (const np_dse_space *sp = np_dse_spaces; sp->unit; sp++) {
        if (only && strcmp(only->name, sp->unit) != 0)
            continue;
        any = 1;
        np_dse_result r;
        char err[256];
        double t0 = np_now();
        if (np_dse_run(sp, samples, seed, &r, err, sizeof err) != 0) {
            np_err("report", "pareto %s: %s", sp->unit, err);
            return NP_EXIT_USAGE;
        }
        char name[64], svg[64], tmp[1024], fin[1024];
        snprintf(svg, sizeof svg, "pareto-%s.svg", sp->unit);
        const char *d = dir ? dir : ".";
        int rc = 0;
        snprintf(name, sizeof name, "pareto-%s.md", sp->unit);
        FILE *f = open_tmp(d, name, tmp, fin, sizeof tmp);
        if (f) {
            np_dse_write_md(f, &r, svg);
            rc |= commit(f, tmp, fin);
        } else
            rc = -1;
        snprintf(name, sizeof name, "pareto-%s.json", sp->unit);
        f = rc ? NULL : open_tmp(d, name, tmp, fin, sizeof tmp);
        if (f) {
            np_dse_write_json(f, &r);
            rc |= commit(f, tmp, fin);
        } else
            rc = -1;
        f = rc ? NULL : open_tmp(d, svg, tmp, fin, sizeof tmp);
        if (f) {
            np_dse_write_svg(f, &r);
            rc |= commit(f, tmp, fin);
        } else
            rc = -1;
        printf("pareto %s: %zu configurations, a search of up to %llu inputs each, %.1f s; wrote "
               "%s/pareto-%s.{md,json,svg}\n",
               sp->unit, r.n, (unsigned long long)r.samples, np_now() - t0, d, sp->unit);
        np_dse_free(&r);
        if (rc)
            return NP_EXIT_USAGE;
    }
    if (!any) {
        np_err("report", "no design space is defined for unit %s", only ? only->name : "?");
        return NP_EXIT_USAGE;
    }
    return NP_EXIT_OK;
}

int np_cmd_report(int argc, char **argv)
{
    if (argc < 2 || strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0) {
        fputs(usage_text, argc < 2 ? stderr : stdout);
        return argc < 2 ? NP_EXIT_USAGE : NP_EXIT_OK;
    }
    const char *what = argv[1], *dir = NULL, *spec = NULL, *scene = NULL, *rtl = NULL, *rtl_param = NULL;
    const np_unit *unit = NULL;
    int synth = 0, per_stage = 0;
    np_fpga_opts fpga;
    np_fpga_opts_init(&fpga);
    int seed_set = 0;
    double tolerance = -1.0;
    uint64_t samples = 262144, seed = 1, repeat = 3, frames = 8;
    for (int i = 2; i < argc; i++) {
        const char *a = argv[i];
        const char *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (strcmp(a, "--help") == 0) {
            fputs(usage_text, stdout);
            return NP_EXIT_OK;
        }
        if (strcmp(a, "--synth") == 0) {
            synth = 1;
            continue;
        }
        if (strcmp(a, "--retime") == 0) {
            fpga.retime = 1;
            continue;
        }
        if (strcmp(a, "--sized") == 0) {
            g_sized = 1;
            continue;
        }
        if (strcmp(a, "--per-stage") == 0) {
            per_stage |= NP_SYNTH_PER_STAGE;
            continue;
        }
        if (strcmp(a, "--abc-full") == 0) {
            per_stage |= NP_SYNTH_ABC_FULL;
            continue;
        }
        if (!v) {
            np_err("report", "%s needs a value (or unknown option)", a);
            return NP_EXIT_USAGE;
        }
        if (strcmp(a, "-o") == 0)
            dir = v;
        else if (strcmp(a, "--config") == 0)
            spec = v;
        else if (strcmp(a, "--scene") == 0)
            scene = v;
        else if (strcmp(a, "--frames") == 0) {
            if (np_parse_u64(v, 1, 100, &frames) != 0) {
                np_err("report", "--frames %s: expected an integer in 1..100", v);
                return NP_EXIT_USAGE;
            }
        }
        else if (strcmp(a, "--rtl") == 0)
            rtl = v;
        else if (strcmp(a, "--rtl-param") == 0)
            rtl_param = v;
        else if (strcmp(a, "--device") == 0)
            fpga.device = v;
        else if (strcmp(a, "--package") == 0)
            fpga.package = v;
        else if (strcmp(a, "--freq") == 0) {
            char *end;
            fpga.freq_mhz = strtod(v, &end);
            if (end == v || *end || !(fpga.freq_mhz >= 1.0 && fpga.freq_mhz <= 1000.0)) {
                np_err("report", "--freq %s: expected a clock in MHz, 1..1000", v);
                return NP_EXIT_USAGE;
            }
        }
        else if (strcmp(a, "--tolerance") == 0) {
            char *end;
            tolerance = strtod(v, &end);
            if (end == v || *end || !(tolerance >= 0.0 && tolerance <= 1000.0)) {
                np_err("report", "--tolerance %s: expected a percentage in 0..1000", v);
                return NP_EXIT_USAGE;
            }
        }
        else if (strcmp(a, "--unit") == 0) {
            unit = np_unit_find(v);
            if (!unit) {
                np_err("report", "unknown unit '%s' (noisepipe units lists them)", v);
                return NP_EXIT_USAGE;
            }
        } else if (strcmp(a, "--samples") == 0) {
            if (np_parse_u64(v, 4096, 1000000000u, &samples) != 0) {
                np_err("report", "--samples %s: expected 4096..1000000000", v);
                return NP_EXIT_USAGE;
            }
        } else if (strcmp(a, "--levels") == 0) {
            uint64_t lv;
            if (np_parse_u64(v, 4, 100000, &lv) != 0) {
                np_err("report", "--levels %s: expected gate levels per clock, 4..100000", v);
                return NP_EXIT_USAGE;
            }
            g_levels = (unsigned)lv;
        } else if (strcmp(a, "--repeat") == 0) {
            if (np_parse_u64(v, 1, 1000, &repeat) != 0) {
                np_err("report", "--repeat %s: expected an integer in 1..1000", v);
                return NP_EXIT_USAGE;
            }
        } else if (strcmp(a, "--seed") == 0) {
            if (np_parse_u64(v, 0, UINT64_MAX, &seed) != 0) {
                np_err("report", "--seed %s: expected an unsigned integer", v);
                return NP_EXIT_USAGE;
            }
            seed_set = 1;
        } else {
            np_err("report", "unknown option '%s'", a);
            return NP_EXIT_USAGE;
        }
        i++;
    }
    int fpga_only = fpga.retime || fpga.package || fpga.freq_mhz != 12.0 || strcmp(fpga.device, "hx8k") != 0;
    if (fpga_only && strcmp(what, "fpga") != 0) {
        np_err("report", "--device, --package, --freq and --retime go with fpga");
        return NP_EXIT_USAGE;
    }
    if (spec && !unit) {
        np_err("report", "--config needs --unit");
        return NP_EXIT_USAGE;
    }
    int known = strcmp(what, "gates") == 0 || strcmp(what, "pareto") == 0 || strcmp(what, "runtime") == 0 ||
                strcmp(what, "all") == 0 || strcmp(what, "tradeoff") == 0 || strcmp(what, "dims") == 0 ||
                strcmp(what, "anim4d") == 0 || strcmp(what, "fpga") == 0;
    if (dir && known) { /* created as render creates its folder */
        struct stat st;
        if (stat(dir, &st) == 0 && !S_ISDIR(st.st_mode)) {
            np_err("report", "-o %s: not a folder: a report writes several files into a folder", dir);
            return NP_EXIT_USAGE;
        }
        if (np_mkdir_p(dir) != 0) {
            np_err("report", "-o %s: cannot create: %s", dir, strerror(errno));
            return NP_EXIT_USAGE;
        }
    }
    if (strcmp(what, "runtime") == 0) {
        if (!dir || unit || spec) {
            np_err("report", "runtime takes -o DIR and no --unit/--config (the scene configures the units)");
            return NP_EXIT_USAGE;
        }
        return np_report_runtime(dir, &scene, scene ? 1u : 0u, (unsigned)repeat, NULL, NULL);
    }
    if (strcmp(what, "tradeoff") == 0) /* fdiff against texel on a scene (np_tradeoff.h) */
        return unit || spec ? (np_err("report", "tradeoff takes --scene and no --unit/--config"), NP_EXIT_USAGE)
                            : np_report_tradeoff(dir, scene);
    if (scene && (strcmp(what, "gates") != 0 || unit || spec)) {
        np_err("report", "--scene goes with gates or runtime, without --unit/--config (the scene configures the units)");
        return NP_EXIT_USAGE;
    }
    if (strcmp(what, "anim4d") == 0) {
        char err[512];
        if (!dir || unit || spec || scene) {
            np_err("report", "anim4d takes -o DIR and --frames N only");
            return NP_EXIT_USAGE;
        }
        if (np_anim4d_frames(dir, (unsigned)frames, err, sizeof err) != 0) {
            np_err("report", "anim4d: %s", err);
            return NP_EXIT_USAGE;
        }
        printf("wrote %s/anim4d-00.png .. anim4d-%02u.png\n", dir, (unsigned)frames - 1u);
        return NP_EXIT_OK;
    }
    if (strcmp(what, "fpga") == 0) {
        char err[512];
        if (scene || synth || per_stage || tolerance >= 0.0) {
            np_err("report", "fpga takes --unit, --config, --rtl-param, --device, --package, --freq, --seed, --retime, --rtl, -o");
            return NP_EXIT_USAGE;
        }
        if (seed_set) {
            if (seed > 999999999u) {
                np_err("report", "fpga --seed %llu: nextpnr takes a seed up to 999999999", (unsigned long long)seed);
                return NP_EXIT_USAGE;
            }
            fpga.seed = seed;
        }
        if (rtl_param && np_synth_set_rtl_params(unit, rtl_param, err, sizeof err) != 0) {
            np_err("report", "%s", err);
            return NP_EXIT_USAGE;
        }
        fpga.rtl_dir = rtl;
        fpga.out_dir = dir;
        return np_report_fpga(unit, spec, &fpga);
    }
    if (strcmp(what, "dims") == 0) {
        if (spec || scene || rtl_param || (!synth && (unit || rtl || per_stage || tolerance >= 0.0))) {
            np_err("report", "dims takes -o DIR, and --synth with --unit, --rtl, --per-stage, --abc-full, --tolerance "
                             "(it configures every n-D unit itself)");
            return NP_EXIT_USAGE;
        }
        np_report_dims_synth ds = { unit, rtl, per_stage, tolerance };
        return np_report_dims(dir, synth ? &ds : NULL);
    }
    if ((synth || rtl || per_stage || tolerance >= 0.0) && (strcmp(what, "gates") != 0 || scene || dir || !synth)) {
        np_err("report", "--synth (with --rtl, --per-stage, --abc-full, --tolerance) goes with gates, without --scene or -o (Markdown on stdout)");
        return NP_EXIT_USAGE;
    }
    if (rtl_param) { /* --rtl-param: a variant of the RTL, which the cost model does not declare */
        char err[512];
        if (!synth || tolerance >= 0.0) {
            np_err("report", "--rtl-param goes with --synth and without --tolerance (no model of the variant)");
            return NP_EXIT_USAGE;
        }
        if (np_synth_set_rtl_params(unit, rtl_param, err, sizeof err) != 0) {
            np_err("report", "%s", err);
            return NP_EXIT_USAGE;
        }
    }
    if (synth)
        return np_report_gates_synth(unit, spec, rtl, per_stage, tolerance);
    if (strcmp(what, "gates") == 0)
        return !scene ? write_gates(dir, unit, spec)
               : is_wave_scene(scene) ? write_wave_scene(dir, scene)
                                      : write_scene(dir, scene);
    if (strcmp(what, "pareto") == 0)
        return write_pareto(dir, unit, samples, seed);
    if (strcmp(what, "all") == 0) {
        if (!dir || unit || spec) {
            np_err("report", "all takes -o DIR and no --unit/--config");
            return NP_EXIT_USAGE;
        }
        int rc = write_gates(dir, NULL, NULL);
        rc = rc ? rc : write_pareto(dir, NULL, samples, seed);
        if (rc == NP_EXIT_OK) {
            char plots[4096];
            snprintf(plots, sizeof plots, "%s/plots", dir);
            rc = np_report_runtime(plots, NULL, 0, (unsigned)repeat, NULL, NULL);
        }
        return rc;
    }
    np_err("report", "unknown report '%s' (gates, pareto, runtime, all, dims, anim4d, fpga)", what);
    return NP_EXIT_USAGE;
}
