/* SPDX-License-Identifier: MIT */
/* Gate and latency reports: the cost model against Yosys, latency against the cycle models. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "np_pareto.h"
#include "np_report.h"
#include "np_stream.h"
#include "np_test.h"
#include "np_unit.h"

/* The calibration circuits: $NP_COST_CALIB (set by CTest), else ./cost_calib.v. */
static const char *calib_file(void)
{
    const char *f = getenv("NP_COST_CALIB");
    return f ? f : "cost_calib.v";
}

/* Synthesize module m of calib_file; NAND2 equivalents (transistors / 4), or -1. */
static double yosys_nand2(const char *m)
{
    char cmd[1024], line[512];
    snprintf(cmd, sizeof cmd,
             "yosys -q -p 'read_verilog %s; synth -top %s -flatten; dfflegalize -cell $_DFF_P_ 01; "
             "abc -g NAND; opt_clean; tee -o /dev/stdout stat -tech cmos' 2>&1",
             calib_file(), m);
    FILE *p = popen(cmd, "r");
    if (!p)
        return -1.0;
    double t = -1.0;
    while (fgets(line, sizeof line, p)) {
        const char *k = strstr(line, "Estimated number of transistors:");
        if (k)
            t = atof(k + strlen("Estimated number of transistors:"));
    }
    pclose(p);
    return t < 0 ? -1.0 : t / 4.0;
}

static int cost_model_calibration(void)
{
    if (system("yosys -V >/dev/null 2>&1") != 0) {
        puts("yosys not installed: skipped");
        return NP_TEST_SKIP;
    }
    const np_cost_model *m = &np_cost_default;
    /* Each circuit with the ops the model prices it as. */
    static const struct { const char *module; np_op ops[8]; unsigned n; } c[] = {
        { "add16", { { "S", NULL, NP_OP_ADD, 1, 16, 0, 0, 0, 0 } }, 1 },
        { "add24", { { "S", NULL, NP_OP_ADD, 1, 24, 0, 0, 0, 0 } }, 1 },
        { "cmp16", { { "S", NULL, NP_OP_CMP, 1, 16, 0, 0, 0, 0 } }, 1 },
        { "mux16", { { "S", NULL, NP_OP_MUX, 1, 16, 2, 0, 0, 0 } }, 1 },
        { "neg12", { { "S", NULL, NP_OP_NEG, 1, 12, 0, 0, 0, 0 } }, 1 },
        { "mul8", { { "S", NULL, NP_OP_MUL, 1, 8, 8, 0, 0, 0 } }, 1 },
        { "mul13", { { "S", NULL, NP_OP_MUL, 1, 13, 13, 0, 0, 0 } }, 1 },
        { "smul12x8", { { "S", NULL, NP_OP_SMUL, 1, 12, 8, 0, 0, 0 } }, 1 },
        { "dffe16", { { "S", NULL, NP_OP_REG, 1, 16, 0, 0, 0, 0 } }, 1 },
        { "inc16", { { "S", NULL, NP_OP_INC, 1, 16, 0, 0, 0, 0 } }, 1 },
        { "cmpk16", { { "S", NULL, NP_OP_CMPK, 1, 16, 0, 0, 0, 0 } }, 1 },
        { "sqr8", { { "S", NULL, NP_OP_SQR, 1, 8, 0, 0, 0, 0 } }, 1 },
        { "carry10", { { "S", NULL, NP_OP_CARRY, 1, 10, 0, 0, 0, 0 } }, 1 },
        /* A pattern lookup alone (lut3x6) is not what the model prices: feeding an adder it merges into it. */
        { "hash6", { { "S", NULL, NP_OP_LUT, 8, 3, 6, 0, 0, 0 }, { "S", NULL, NP_OP_ADD, 7, 6, 0, 0, 0, 0 } }, 2 },
    };
    printf("%-8s %10s %10s %8s\n", "circuit", "yosys", "model", "model/y");
    for (unsigned i = 0; i < sizeof c / sizeof c[0]; i++) {
        double y = yosys_nand2(c[i].module), e = 0.0;
        for (unsigned k = 0; k < c[i].n; k++)
            e += np_cost_op_gates(m, &c[i].ops[k]);
        printf("%-8s %10.1f %10.1f %8.3f\n", c[i].module, y, e, y > 0 ? e / y : 0.0);
        NP_CHECK(y > 0, "%s: yosys gave no count", c[i].module);
        NP_CHECK(fabs(e / y - 1.0) <= 0.25, "%s: model %.1f vs yosys %.1f: more than 25%% apart", c[i].module, e, y);
    }
    return 0;
}

/* Cycles from an accepted input to its output on an empty, unstalled pipe. */
static unsigned measured_latency(const np_unit *u, const void *cfg)
{
    np_pipe p;
    if (u->pipe_init(&p, cfg) != 0)
        return 0;
    unsigned char sig[4096];
    memset(sig, 0, sizeof sig);
    NP_CHECK(p.sig_size <= sizeof sig, "bundle too large");
    uint64_t in[NP_UNIT_MAX_FIELDS] = { 0x1234, 0x5678, 0x9abc, 0, 0, 0, 0, 0 };
    u->sig_set_in(sig, in);
    np_pipe_port port = { 1, sig, 1, 0, 0, NULL };
    unsigned cyc = 0, lat = 0;
    for (; cyc < 200 && !lat; cyc++) {
        np_pipe_eval(&p, &port);
        if (port.out_valid)
            lat = cyc;
        np_pipe_clock(&p, &port);
        port.in_valid = 0;
    }
    np_pipe_free(&p);
    return lat;
}

/*
 * A stream unit: drive descriptor desc alone through its stream model, no
 * backpressure. *lat = clocks from the descriptor's transfer to its first
 * beat; *rate = (beats - 1) / (clocks from the first beat to the last), the
 * peak rate along it (1 when it has one beat). 0, or -1 when it never ends.
 */
static int stream_run(const np_unit *u, const void *cfg, const uint64_t *desc, unsigned *lat, double *rate)
{
    const np_unit_stream *st = u->stream;
    void *state = calloc(1, st->state_size);
    if (!state || st->init(state, cfg) != 0) {
        free(state);
        return -1;
    }
    uint64_t beats = st->beats(cfg, desc), got = 0, t_in = 0, t_first = 0, t_last = 0;
    int sent = 0;
    for (uint64_t cyc = 0; cyc < 10000000u; cyc++) {
        np_unit_stream_port p;
        memset(&p, 0, sizeof p);
        p.in_valid = !sent;
        p.in = desc;
        p.out_ready = 1;
        st->eval(state, &p);
        if (p.in_valid && p.in_ready) {
            sent = 1;
            t_in = cyc;
        }
        if (p.out_valid) {
            if (got == 0)
                t_first = cyc;
            t_last = cyc;
            got++;
        }
        st->clock(state, &p);
        if (sent && got == beats && st->idle(state))
            break;
    }
    st->free(state);
    free(state);
    if (got != beats || beats == 0)
        return -1;
    *lat = (unsigned)(t_first - t_in);
    *rate = beats > 1 ? (double)(beats - 1u) / (double)(t_last - t_first) : 1.0;
    return 0;
}

static int stream_latency(const np_unit *u, const void *cfg, const np_unit_cost *c)
{
    /* Latency on the first annotated descriptor; peak rate over those of at most 4096 beats. */
    uint64_t (*d)[NP_UNIT_MAX_FIELDS] = calloc(64, sizeof *d);
    NP_CHECK(d != NULL, "out of memory");
    size_t nd = u->stream->descriptors(cfg, d, 64);
    unsigned lat0 = 0;
    double best = 0.0;
    int have = 0;
    for (size_t i = 0; i < nd && i < 64; i++) {
        if (u->stream->beats(cfg, d[i]) == 0 || u->stream->beats(cfg, d[i]) > 4096)
            continue;
        unsigned lat = 0;
        double rate = 0.0;
        NP_CHECK(stream_run(u, cfg, d[i], &lat, &rate) == 0, "%s: descriptor %zu did not complete", u->name, i);
        if (!have)
            lat0 = lat;
        have = 1;
        if (rate > best)
            best = rate;
    }
    free(d);
    NP_CHECK(have, "%s: no descriptor to drive", u->name);
    printf("%s (stream): reported latency %u clocks, stream model %u clocks; throughput reported %g, "
           "stream model's peak %g per clock (%s); %.0f gates, %u register bits\n",
           u->name, c->latency, lat0, c->throughput, best, c->timing.throughput_note, c->total, c->reg_bits);
    NP_CHECK(lat0 == c->latency, "%s: reported %u, model %u", u->name, c->latency, lat0);
    NP_CHECK(fabs(best - c->throughput) < 1e-9, "%s: throughput reported %g, model %g", u->name, c->throughput, best);
    return 0;
}

static int latency_matches_model(void)
{
    unsigned n = 0;
    const np_unit *u;
    for (size_t i = 0; (u = np_unit_at(i)) != NULL; i++) {
        if (!u->datapath)
            continue;
        np_unit_cfg cfg;
        np_unit_cost c;
        char err[256];
        np_unit_cfg_default(u, &cfg);
        NP_CHECK(np_unit_cost_compute(u, &cfg, &np_cost_default, &c, err, sizeof err) == 0, "%s: %s", u->name, err);
        for (unsigned k = 0; k < c.n_stages; k++)
            NP_CHECK(c.st[k].reg_bits > 0, "%s: stage %s declares no register bank", u->name, c.st[k].name);
        n++;
        if (u->stream) {
            /* Every built-in texture: the set-up stall depends on the octaves and transforms. */
            static const char *const tex[] = { "texture=wood", "texture=marble", "texture=ramp",
                                               "texture=marble,setup_mults=5,mult_lat=3" };
            for (unsigned t = 0; t < sizeof tex / sizeof tex[0]; t++) {
                NP_CHECK(np_unit_configure(u, &cfg, tex[t], err, sizeof err) == 0, "%s: %s", u->name, err);
                NP_CHECK(np_unit_cost_compute(u, &cfg, &np_cost_default, &c, err, sizeof err) == 0, "%s: %s",
                         u->name, err);
                if (stream_latency(u, &cfg, &c) != 0)
                    return 1;
            }
            continue;
        }
        unsigned lat = measured_latency(u, &cfg);
        printf("%s: reported latency %u clocks, cycle model %u clocks; %.0f gates, %u register bits\n", u->name,
               c.latency, lat, c.total, c.reg_bits);
        NP_CHECK(lat == c.latency, "%s: reported %u, model %u", u->name, c.latency, lat);
    }
    NP_CHECK(n > 0, "no unit declares a datapath");
    return 0;
}

static int unknown_stage_rejected(void)
{
    /* The pricing refuses a declaration whose stage names do not match the pipe. */
    const np_unit *u = np_unit_find("classic3");
    NP_CHECK(u != NULL, "classic3");
    np_unit tampered = *u;
    tampered.datapath = NULL;
    np_unit_cfg cfg;
    np_unit_cost c;
    char err[256] = "";
    np_unit_cfg_default(u, &cfg);
    NP_CHECK(np_unit_cost_compute(&tampered, &cfg, &np_cost_default, &c, err, sizeof err) != 0, "no datapath");
    printf("no declaration: \"%s\"\n", err);
    return 0;
}

/*
 * --levels (np_report_retime): for every unit and a range of targets, a
 * stage that meets the target has every clock's path within it after its
 * cuts; a tighter target never needs fewer cuts; a stage named as not
 * meeting it says why; a target above every path needs no cut.
 */
static int levels_retime(void)
{
    static const unsigned targets[] = { 10, 20, 40, 80, 160, 100000 };
    const np_unit *u;
    unsigned checked = 0;
    for (size_t i = 0; (u = np_unit_at(i)) != NULL; i++) {
        if (!u->datapath)
            continue;
        np_unit_cfg cfg;
        np_unit_cost c;
        char err[256];
        np_unit_cfg_default(u, &cfg);
        if (np_unit_cost_compute(u, &cfg, &np_cost_default, &c, err, sizeof err) != 0)
            continue;
        unsigned prev[NP_REPORT_MAX_STAGES];
        for (size_t t = 0; t < sizeof targets / sizeof targets[0]; t++) {
            np_stage_retime r[NP_REPORT_MAX_STAGES];
            np_report_retime(&c, targets[t], r);
            for (unsigned k = 0; k < c.n_stages; k++) {
                if (r[k].meets)
                    NP_CHECK(r[k].per_clock <= (double)targets[t] + 1e-9, "%s %s at %u: %.1f per clock", u->name,
                             c.st[k].name, targets[t], r[k].per_clock);
                else
                    NP_CHECK(r[k].why[0] != '\0', "%s %s: no reason", u->name, c.st[k].name);
                if (t > 0)
                    NP_CHECK(r[k].cuts <= prev[k], "%s %s: %u cuts at %u, %u at a tighter target", u->name,
                             c.st[k].name, r[k].cuts, targets[t], prev[k]);
                if (targets[t] == 100000)
                    NP_CHECK(r[k].cuts == 0 && r[k].meets, "%s %s: cut at a target above every path", u->name,
                             c.st[k].name);
                prev[k] = r[k].cuts;
                checked++;
            }
        }
    }
    printf("%u stage x target checks\n", checked);
    NP_CHECK(checked > 0, "no unit checked");
    return 0;
}

/* The DSE sweeps take their keys and ranges from the unit's key table (np_dse_axis). */
static int dse_axes_from_keys(void)
{
    char err[256] = "";
    np_dse_result r;
    /* A range narrowed by the space must lie inside the key's; an unknown key is named. */
    const np_dse_space bad_key = { "classic3", "out_bits=8", { { "s_fracc", 3, 4 }, { "lerp_frac", 6, 7 } }, 0 };
    NP_CHECK(np_dse_run(&bad_key, 10, 1, &r, err, sizeof err) != 0, "unknown key accepted");
    NP_CHECK(strstr(err, "'s_fracc'") != NULL, "message names the key: %s", err);
    printf("unknown key: \"%s\"\n", err);
    const np_dse_space wide = { "classic3", "out_bits=8", { { "s_frac", 3, 25 }, { "lerp_frac", 6, 7 } }, 0 };
    NP_CHECK(np_dse_run(&wide, 10, 1, &r, err, sizeof err) != 0, "s_frac 3..25 accepted (the key's range is 1..24)");
    NP_CHECK(strstr(err, "s_frac") && strstr(err, "1..24"), "message names the key and its range: %s", err);
    printf("outside the key's range: \"%s\"\n", err);
    /* 0..0: the key's whole range from the table (classic3 s_frac 1..24), swept against a narrowed one. */
    const np_dse_space whole = { "classic3", "out_bits=8", { { "s_frac", 0, 0 }, { "lerp_frac", 11, 11 } }, 0 };
    const np_unit_key *k = np_unit_key_find(np_unit_find("classic3"), "s_frac");
    NP_CHECK(k != NULL, "classic3 has s_frac");
    NP_CHECK(np_dse_run(&whole, 10, 1, &r, err, sizeof err) == 0, "%s", err);
    NP_CHECK(k && r.axis[0].lo == k->lo && r.axis[0].hi == k->hi, "s_frac swept over %u..%u, the table has %u..%u",
             r.axis[0].lo, r.axis[0].hi, k ? k->lo : 0, k ? k->hi : 0);
    NP_CHECK(r.axis[1].lo == 11 && r.axis[1].hi == 11, "lerp_frac narrowed to 11");
    NP_CHECK(k && r.n == k->hi - k->lo + 1, "%zu points, expected one per s_frac", r.n);
    printf("s_frac from the table: %u..%u, %zu points\n", r.axis[0].lo, r.axis[0].hi, r.n);
    np_dse_free(&r);
    /* The shipped spaces sweep numeric keys of their units inside the keys' ranges. */
    for (const np_dse_space *sp = np_dse_spaces; sp->unit; sp++) {
        const np_unit *u = np_unit_find(sp->unit);
        NP_CHECK(u != NULL, "space of unknown unit %s", sp->unit);
        for (unsigned a = 0; u && a < 2; a++) {
            const np_unit_key *q = np_unit_key_find(u, sp->axis[a].key);
            NP_CHECK(q && !q->word, "%s: %s is not a numeric key", sp->unit, sp->axis[a].key);
            NP_CHECK(!q || (sp->axis[a].lo == 0 && sp->axis[a].hi == 0) ||
                         (q->lo <= sp->axis[a].lo && sp->axis[a].lo <= sp->axis[a].hi && sp->axis[a].hi <= q->hi),
                     "%s: %s %u..%u outside the key's range", sp->unit, sp->axis[a].key, sp->axis[a].lo,
                     sp->axis[a].hi);
        }
    }
    return 0;
}

static const np_test_case cases[] = {
    { "dse_axes_from_keys", dse_axes_from_keys },
    { "cost_model_calibration", cost_model_calibration },
    { "latency_matches_model", latency_matches_model },
    { "unknown_stage_rejected", unknown_stage_rejected },
    { "levels_retime", levels_retime },
    { NULL, NULL },
};

NP_TEST_MAIN(cases)
