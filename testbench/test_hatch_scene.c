/* SPDX-License-Identifier: MIT */
/*
 * Scenes hatched by the unit hatch through the G-buffer renderer
 * (src/render/np_hatch_render.h, docs/hatch.md "Scenes"): coverage against
 * brute force on the hatched cube, the host's level of detail words, the
 * scene keys.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "np_hatch.h"
#include "np_hatch_render.h"
#include "np_report.h"
#include "np_rng.h"
#include "np_scene.h"
#include "np_golden.h"
#include "np_test.h"
#include "np_unit.h"

/*
 * The hatched wood cube with 4 x 16 and 4 x 64 seeds: the coverage unit's
 * image equals brute force's bit for bit; the unrolled cycle model reproduces
 * the image; the brute-force image within 1 LSB of the float reference.
 */
static int t_scene_cover_identical(void)
{
    np_scene sc;
    char err[512];
    if (np_golden_scene_load(NP_SOURCE_DIR, "hatch_wood", &sc))
        return 1;
    NP_CHECK(sc.hatch.present && sc.hatch.coverage == 1, "the scene's hatch section");
    int bad = 0;
    for (unsigned si = 0; si < 2 && !bad; si++) {
        np_scene_hatch h = sc.hatch;
        h.set = si ? 3u : 1u;
        np_unit_cfg c;
        np_hatch_frame fb, fc;
        if (np_hatch_render_cfg(&h, NULL, &c, err, sizeof err) ||
            np_hatch_render(&sc, &c, 0, h.tile_pixels, NP_HATCH_RENDER_PIPE | (si ? 0u : NP_HATCH_RENDER_REF), &fb,
                            err, sizeof err) ||
            np_hatch_render(&sc, &c, 1, h.tile_pixels, NP_HATCH_RENDER_PIPE, &fc, err, sizeof err)) {
            NP_CHECK(0, "%s", err);
            np_scene_free(&sc);
            return 1;
        }
        size_t diff = 0, ink = 0, tones[256] = { 0 };
        unsigned distinct = 0;
        for (size_t p = 0; p < (size_t)fb.w * fb.h; p++) {
            diff += memcmp(fb.rgb + 3 * p, fc.rgb + 3 * p, 3) != 0;
            ink += fb.covered[p] && fb.rgb[3 * p] < 128;
            tones[fb.tone[p]] += fb.covered[p];
            if (!fb.covered[p])
                bad |= fb.rgb[3 * p] != (uint8_t)sc.background[0];
        }
        for (unsigned t = 0; t < 256; t++)
            distinct += tones[t] != 0;
        printf("%s: %llu pixels, %zu inked (< 128), %u distinct tones, levels %d..%d: coverage against brute force "
               "%zu pixels differ; cycles a pixel B %.2f, C %.3f (lists mean %.3f, max %u); unrolled cycle model "
               "%llu cycles, %s; the coverage unit's (%u slot stages) %llu cycles, %s",
               si ? "4 x 64" : "4 x 16", (unsigned long long)fb.samples, ink, distinct, fb.level_min, fb.level_max,
               diff, (double)fb.iter_cycles / (double)fb.samples, (double)fc.iter_cycles / (double)fc.samples,
               fc.list_mean, fc.list_max, (unsigned long long)fb.pipe_cycles, fb.pipe_mismatch ? "DIFFERS" : "equal",
               fc.pipe_depth - 1u, (unsigned long long)fc.pipe_cycles, fc.pipe_mismatch ? "DIFFERS" : "equal");
        if (!si)
            printf("; max %.4f LSB from the float reference", fb.ref_max);
        printf("\n");
        NP_CHECK(diff == 0, "coverage bit-identical to brute force (%zu pixels differ)", diff);
        NP_CHECK(!fb.pipe_mismatch && fb.pipe_cycles == fb.samples + np_hatch_depth((const np_hatch_cfg *)(const void *)c.bytes), "cycle model");
        NP_CHECK(!fc.pipe_mismatch && fc.pipe_cycles == fc.samples + fc.pipe_depth && fc.pipe_depth < fb.pipe_depth,
                 "the coverage unit's cycle model (latency %u)", fc.pipe_depth);
        NP_CHECK(ink > 1000 && distinct > 10, "a hatched image with ink and tones");
        NP_CHECK(si || (fb.ref_max <= 1.0 && fb.ref_over == 0), "within 1 LSB of the reference");
        NP_CHECK(fc.iter_cycles < fb.iter_cycles, "coverage cheaper");
        bad |= diff != 0 || fb.pipe_mismatch || fc.pipe_mismatch || ink <= 1000;
        np_hatch_frame_free(&fb);
        np_hatch_frame_free(&fc);
    }
    NP_CHECK(!bad, "background where uncovered");
    np_scene_free(&sc);
    return 0;
}

/*
 * The host's level of detail words: at L = 2^k the level is k and m = 0
 * exactly; over 10^5 random L in [2^-60, 2^30] the level is floor(log2 L),
 * pm within 1 of 2^16 2^-m and om within 2 of 2^16 (1 - m) (m16 truncated
 * after 16 rounded squarings).
 */
static int t_scene_lod(void)
{
    for (int k = -64; k <= 31; k++) {
        np_hatch_lod d = np_hatch_lod_of(ldexp(1.0, k));
        NP_CHECK(d.level == k && d.pm == 0x10000u && d.om == 0x10000u, "L = 2^%d: level %d pm %u om %u", k, d.level,
                 d.pm, d.om);
        /* Within 2^-31 below 2^k, X rounds to 2^31: the next level at m = 0 (no m = 1 word). */
        d = np_hatch_lod_of(ldexp(1.0, k) * (1.0 - 0x1p-40));
        NP_CHECK(d.level == k && d.pm == 0x10000u && d.om == 0x10000u, "2^%d (1 - 2^-40): level %d pm %u om %u", k,
                 d.level, d.pm, d.om);
        d = np_hatch_lod_of(ldexp(1.0, k) * (1.0 - 0x1p-20));
        NP_CHECK(k == -64 || (d.level == k - 1 && d.pm == 0x8000u && d.om <= 1u),
                 "2^%d (1 - 2^-20): level %d pm %u om %u", k, d.level, d.pm, d.om);
    }
    np_rng g;
    np_rng_seed(&g, 16);
    double dpm = 0, dom = 0;
    for (unsigned n = 0; n < 100000; n++) {
        double L = ldexp(1.0 + (double)(np_rng_next(&g) >> 11) * 0x1p-53, (int)np_rng_below(&g, 90) - 60);
        np_hatch_lod d = np_hatch_lod_of(L);
        double M = log2(L), m = M - floor(M);
        NP_CHECK(d.level == (int)floor(M), "level of %.17g", L);
        double ep = fabs((double)d.pm - 65536.0 * exp2(-m)), eo = fabs((double)d.om - 65536.0 * (1.0 - m));
        dpm = ep > dpm ? ep : dpm;
        dom = eo > dom ? eo : dom;
    }
    printf("10^5 random L: max |pm - 2^16 2^-m| %.3f, max |om - 2^16 (1 - m)| %.3f (units of 2^-16)\n", dpm, dom);
    NP_CHECK(dpm <= 1.0 && dom <= 2.0, "words within their bounds");
    np_hatch_lod z = np_hatch_lod_of(0.0);
    NP_CHECK(z.level == -64 && z.pm == 0x10000u, "edge-on: the finest level");
    return 0;
}

/* A scene's start: one triangle, a two-colour map; the test adds its "hatch" section. */
static const char *const head = "{\"noisepipe_scene\": 1, \"name\": \"k\", \"image\": {\"width\": 8, \"height\": 8},"
                              "\"camera\": {\"projection\": \"orthographic\", \"eye\": [0, 0, 5], \"target\": [0, 0, 0],"
                              "\"up\": [0, 1, 0], \"height\": 2}, \"geometry\": [{\"type\": \"polygon\", \"vertices\": [[0, 0, 0], [1, 0, 0], [0, 1, 0]],"
                              "\"texcoords\": [[0, 0, 0], [1, 0, 0], [0, 1, 0]]}], \"texture\": {\"colormap\": {"
                              "\"mode\": \"clamp\", \"domain\": [0, 1], \"colors\": [[0, 0, 0], [255, 255, 255]]}}";

/* The scene keys: defaults, and each bad field refused with its name. */
static int t_scene_keys(void)
{
    static const struct { const char *hatch, *msg; } bad[] = {
        { "\"hatch\": {\"set\": \"best32\"}", "field 'hatch.set': \"best32\" is not one of" },
        { "\"hatch\": {\"layers\": 5}", "field 'hatch.layers': expected an integer in 1..4" },
        { "\"hatch\": {\"lanes\": 3}", "field 'hatch.lanes': 3: expected a power of two dividing the set's 16 seeds" },
        { "\"hatch\": {\"set\": \"fkm16\", \"lanes\": 16, \"mode\": \"fast\"}", "field 'hatch.mode'" },
        { "\"hatch\": {\"fade\": 1}", "field 'hatch.fade'" },
        { "\"hatch\": {\"tile_pixels\": 0}", "field 'hatch.tile_pixels'" },
        { "\"hatch\": {\"zoom\": 2}", "field 'hatch.zoom': unknown field" },
        { "\"hatch\": 3", "field 'hatch'" },
    };
    char json[2048], err[512];
    np_scene s;
    snprintf(json, sizeof json, "%s}", head);
    NP_CHECK(np_scene_parse(json, "k.json", &s, err, sizeof err) == 0, "%s", err);
    NP_CHECK(!s.hatch.present && s.hatch.layers == 4 && s.hatch.set == 1 && s.hatch.tile_pixels == 64, "defaults");
    np_scene_free(&s);
    snprintf(json, sizeof json, "%s, \"hatch\": {\"set\": \"best64\", \"layers\": 1, \"fade\": \"onebyone\", \"mode\": \"brute\","
             " \"lanes\": 8, \"tile_pixels\": 32}}", head);
    NP_CHECK(np_scene_parse(json, "k.json", &s, err, sizeof err) == 0, "%s", err);
    NP_CHECK(s.hatch.present && s.hatch.set == 3 && s.hatch.layers == 1 && s.hatch.fade == 1 && s.hatch.coverage == 0 &&
             s.hatch.lanes == 8 && s.hatch.tile_pixels == 32, "keys read");
    np_scene_free(&s);
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        snprintf(json, sizeof json, "%s, %s}", head, bad[i].hatch);
        int rc = np_scene_parse(json, "k.json", &s, err, sizeof err);
        NP_CHECK(rc != 0 && strstr(err, bad[i].msg) != NULL, "%s: got '%s'", bad[i].hatch, rc ? err : "accepted");
        if (rc == 0)
            np_scene_free(&s);
    }
    return 0;
}

/* The hatching unit as a scene configures it, priced (report gates --scene); 0, or -1. */
static int scene_cost(const char *hatch, np_unit_cost *cost, np_hatch_cfg *cfg)
{
    char json[2048], err[512];
    np_scene s;
    np_unit_cfg c;
    const np_unit *u = np_unit_find("hatch");
    snprintf(json, sizeof json, "%s, \"hatch\": %s}", head, hatch);
    if (!u || np_scene_parse(json, "gates.json", &s, err, sizeof err) != 0) {
        NP_CHECK(0, "%s", u ? err : "no unit hatch");
        return -1;
    }
    memset(&c, 0, sizeof c);
    int used = np_scene_cfg_unit(u, c.bytes, &s, err, sizeof err);
    np_scene_free(&s);
    NP_CHECK(used == 1, "the scene uses hatch: %s", used < 0 ? err : "no");
    if (used != 1 || np_unit_cost_compute(u, c.bytes, &np_cost_default, cost, err, sizeof err) != 0) {
        NP_CHECK(0, "%s", err);
        return -1;
    }
    memcpy(cfg, c.bytes, sizeof *cfg);
    return 0;
}

/* Does the declaration have signal name, or an op of kind k with widths a x b? */
static int has_signal(const np_unit_cost *c, const char *name)
{
    for (size_t i = 0; i < c->n_ops; i++)
        if (c->ops[i].signal && strcmp(c->ops[i].signal, name) == 0)
            return 1;
    return 0;
}
static unsigned signal_count(const np_unit_cost *c, const char *name)
{
    unsigned n = 0;
    for (size_t i = 0; i < c->n_ops; i++)
        n += c->ops[i].signal && strcmp(c->ops[i].signal, name) == 0 ? c->ops[i].count : 0u;
    return n;
}
static unsigned count_ops(const np_unit_cost *c, np_op_kind k, unsigned a, unsigned b)
{
    unsigned n = 0;
    for (size_t i = 0; i < c->n_ops; i++)
        n += c->ops[i].kind == k && c->ops[i].a == a && c->ops[i].b == b ? c->ops[i].count : 0u;
    return n;
}

/* The smoothstep of one-by-one fading: its level product t^2 (3 - 2t), 32 x 17 (np_hatch_datapath). */
static unsigned has_smoothstep(const np_unit_cost *c) { return count_ops(c, NP_OP_MUL, 32, 17) != 0; }

/*
 * report gates --scene prices the unit by its scene: brute force has no
 * coverage logic (no list memory, no rotators), fade smooth no smoothstep,
 * only the scene's layers; a 1-layer brute-force scene prices below a
 * 4-layer one, and each piece left out lowers the price.
 */
static int t_scene_gates(void)
{
    static const struct { const char *name, *hatch; } sc[] = {
        { "best16 1 layer brute smooth", "{\"layers\": 1, \"mode\": \"brute\"}" },
        { "best16 4 layers coverage smooth", "{\"mode\": \"coverage\"}" },
        { "best16 4 layers coverage one by one", "{\"mode\": \"coverage\", \"fade\": \"onebyone\"}" },
        { "best16 4 layers brute smooth", "{\"mode\": \"brute\"}" },
        { "best64 4 layers brute smooth", "{\"set\": \"best64\", \"mode\": \"brute\"}" },
        { "best64 4 layers coverage smooth", "{\"set\": \"best64\", \"mode\": \"coverage\"}" },
        { "best16 2 layers coverage smooth", "{\"layers\": 2, \"mode\": \"coverage\"}" },
    };
    enum { NS = sizeof sc / sizeof sc[0] };
    static np_unit_cost cost[NS];
    np_hatch_cfg cfg[NS];
    for (unsigned i = 0; i < NS; i++) {
        if (scene_cost(sc[i].hatch, &cost[i], &cfg[i]))
            return 1;
        printf("%-38s %12.0f gates, latency %3u clocks, coverage slots %u%s%s\n", sc[i].name, cost[i].total,
               cost[i].latency, cfg[i].cover_slots, has_signal(&cost[i], "list") ? ", list memory" : "",
               has_smoothstep(&cost[i]) ? ", smoothstep" : "");
    }
    /* What each scene leaves out. */
    for (unsigned i = 0; i < NS; i++) {
        int cov = cfg[i].cover_slots != 0, obo = cfg[i].fade == NP_HATCH_FADE_ONE_BY_ONE;
        NP_CHECK(has_signal(&cost[i], "list") == cov && has_signal(&cost[i], "W") == cov, "%s: coverage logic",
                 sc[i].name);
        NP_CHECK((int)has_smoothstep(&cost[i]) == obo, "%s: smoothstep", sc[i].name);
        NP_CHECK(signal_count(&cost[i], "al") == cfg[i].layers, "%s: one tone clamp per layer", sc[i].name);
    }
    NP_CHECK(cost[0].total < cost[3].total, "1-layer brute %.0f below 4-layer brute %.0f", cost[0].total,
             cost[3].total);
    NP_CHECK(cost[1].total < cost[2].total, "smoothstep left out with smooth fading");
    NP_CHECK(cost[6].total < cost[1].total, "unused layers left out");
    NP_CHECK(cfg[1].cover_slots == 4 && cfg[5].cover_slots == 4, "slots: the lists' longest (4)");
    /* Brute force with its every-seed stages against coverage's slots: the list logic buys fewer seed datapaths. */
    NP_CHECK(cost[5].total < cost[4].total && cost[1].total < cost[3].total, "coverage cheaper than unrolled brute force");
    return 0;
}

static const np_test_case cases[] = {
    { "scene_cover_identical", t_scene_cover_identical },
    { "scene_lod", t_scene_lod },
    { "scene_keys", t_scene_keys },
    { "scene_gates", t_scene_gates },
    { NULL, NULL },
};

NP_TEST_MAIN(cases)
