/* SPDX-License-Identifier: MIT */
/* The G-buffer renderer (src/render/np_gbuf.h): samples, deferred shading, resolve, references, meshes. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "np_aacount.h"
#include "np_common.h"
#include "np_gbuf.h"
#include "np_golden.h"
#include "np_image.h"
#include "np_render.h"
#include "np_test.h"
#include "np_texel.h"

/* The units that render scene sc (the registry), configured for it. */
static int units(const np_scene *sc, np_render_unit_cfg *us)
{
    char err[512];
    int n = np_render_units(sc, NULL, NULL, us, err, sizeof err);
    NP_CHECK(n > 0, "np_render_units: %s", n < 0 ? err : "none");
    return n;
}

static const np_render_unit_cfg *unit_named(const np_render_unit_cfg *us, int n, const char *name)
{
    for (int i = 0; i < n; i++)
        if (strcmp(us[i].u->name, name) == 0)
            return &us[i];
    return NULL;
}

/* The hash of scene image in the checked-in list vectors/images/FILE (np_golden_hash); a missing one fails. */
static int golden_in(const char *file, const char *scene, const char *image, char hex[65])
{
    int rc = np_golden_hash(NP_SOURCE_DIR, file, scene, image, hex);
    NP_CHECK(rc == 0, "%s for %s %s in %s/vectors/images/%s", rc == -1 ? "cannot open the list" : "no golden hash",
             scene, image, NP_SOURCE_DIR, file);
    return rc == 0 ? 0 : -1;
}

/* The golden hash of scene image (vectors/images/hashes.txt). */
static int golden(const char *scene, const char *image, char hex[65]) { return golden_in("hashes.txt", scene, image, hex); }

static int build(const np_scene *s, unsigned m, np_gbuf *g)
{
    char err[1024];
    if (np_gbuf_build(s, m, g, err, sizeof err)) {
        NP_CHECK(0, "np_gbuf_build m=%u: %s", m, err);
        return -1;
    }
    return 0;
}

static int parse(const char *json, np_scene *s)
{
    char err[1024];
    if (np_scene_parse(json, "test.json", s, err, sizeof err)) {
        NP_CHECK(0, "%s", err);
        return -1;
    }
    return 0;
}

/*
 * A test scene: an orthographic camera looking down -z from (0, 0, 10), one
 * world unit per pixel, so screen (X, Y) is world (X - w/2, h/2 - Y); the
 * geometry text geom; wood's texture.
 */
static int flat_scene(unsigned w, unsigned h, const char *geom, const char *extra, np_scene *s)
{
    char json[8192];
    snprintf(json, sizeof json,
             "{\"noisepipe_scene\": 1, \"name\": \"t\", \"image\": {\"width\": %u, \"height\": %u},"
             "\"camera\": {\"projection\": \"orthographic\", \"eye\": [0, 0, 10], \"target\": [0, 0, 0],"
             "\"up\": [0, 1, 0], \"height\": %u %s}, \"geometry\": [%s],"
             "\"texture\": {\"quadric\": {\"A\": 10, \"H\": 10}, \"octaves\": [{\"amplitude\": 1, \"scale\": [5, 5, 1]}],"
             "\"colormap\": {\"mode\": \"repeat\", \"domain\": [0, 1], \"colors\": [[226, 176, 116], [204, 146, 86],"
             "[150, 96, 50], [204, 146, 86]]}}, \"allow_empty\": true}",
             w, h, h, extra ? extra : "", geom);
    return parse(json, s);
}

/* A rectangle [X0, X1) x [Y0, Y1) in screen coordinates at world z, counter-clockwise seen from +z. */
static void rect(char *buf, size_t n, unsigned w, unsigned h, double X0, double X1, double Y0, double Y1, double z)
{
    double x0 = X0 - w / 2.0, x1 = X1 - w / 2.0, y0 = h / 2.0 - Y1, y1 = h / 2.0 - Y0;
    snprintf(buf, n,
             "{\"type\": \"polygon\", \"vertices\": [[%.17g, %.17g, %.17g], [%.17g, %.17g, %.17g], [%.17g, %.17g, %.17g],"
             "[%.17g, %.17g, %.17g]], \"texcoords\": [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]}",
             x0, y0, z, x1, y0, z, x1, y1, z, x0, y1, z);
}

/*
 * Image borders and edges through sample points, at every m: the covered
 * samples are exactly those whose point lies in [X0, X1) x [Y0, Y1) (edges
 * half-open: a sample on the left or top edge is in, on the right or bottom
 * edge out), each covered once; a rectangle larger than the image covers
 * every sample, in sub-spans from x = 0 over the whole width.
 */
static int borders(void)
{
    const unsigned w = 16, h = 12;
    for (unsigned m = 1; m <= 4; m++) {
        /* Edges on sample points where (a + 1/2)/m is exact in binary (m = 1, 2, 4), between samples for m = 3. */
        const double e = m == 3 ? 1.0 / 3.0 : 0.5 / m, last = m == 3 ? 2.0 / 3.0 : (m - 0.5) / m;
        const double R[][4] = {
            { -3, w + 3.0, -2, h + 2.0 },           /* the whole image */
            { 5 + e, 11 + e, 3 + e, 9 + e },        /* inside, edges on sample points */
            { w - 1 + last, w + 5.0, -1, h + 1.0 }, /* only the last sample column of the last pixel */
            { -5, e, -1, h + 1.0 },                 /* the first sample column: on the right edge, so none */
            { -1, w + 1.0, h - 1 + last, h + 3.0 }, /* the last sample row */
        };
        for (size_t r = 0; r < sizeof R / sizeof R[0]; r++) {
            char geom[1024];
            rect(geom, sizeof geom, w, h, R[r][0], R[r][1], R[r][2], R[r][3], 0);
            np_scene s;
            np_gbuf g;
            if (flat_scene(w, h, geom, NULL, &s) || build(&s, m, &g))
                return 1;
            uint64_t want = 0, bad = 0;
            for (size_t i = 0; i < (size_t)w * h * g.n; i++) {
                double sx, sy;
                np_gbuf_position(&g, i, &sx, &sy);
                int in = sx >= R[r][0] && sx < R[r][1] && sy >= R[r][2] && sy < R[r][3];
                want += (uint64_t)in;
                if ((g.poly[i] != NP_GBUF_NONE) != in || g.hits[i] != (uint8_t)in)
                    bad++;
            }
            NP_CHECK(bad == 0, "m=%u rect %zu: %llu samples covered wrongly (of %llu)", m, r, (unsigned long long)bad,
                     (unsigned long long)want);
            NP_CHECK(g.covered_samples == want, "m=%u rect %zu: %llu covered, want %llu", m, r,
                     (unsigned long long)g.covered_samples, (unsigned long long)want);
            if (r == 0) {
                NP_CHECK(g.n_spans == (size_t)h * g.n, "m=%u: %zu sub-spans, want %u", m, g.n_spans, h * g.n);
                for (size_t k = 0; k < g.n_spans; k++)
                    NP_CHECK(g.spans[k].r.hw.x0 == 0 && g.spans[k].r.hw.n == w, "m=%u: sub-span %zu at %u, %u", m,
                             k, g.spans[k].r.hw.x0, g.spans[k].r.hw.n);
                for (size_t p = 0; p < (size_t)w * h; p++)
                    NP_CHECK(g.cover[p] == g.n, "m=%u: pixel %zu covered %u of %u", m, p, g.cover[p], g.n);
            }
            if (r == 1) {
                /* Texture (0, 0) at the bottom-left corner, s right and t up over 6 pixels: ds/dx = 1/6, dt/dy = -1/6. */
                const np_gbuf_span *sp = &g.spans[0];
                NP_CHECK(fabs(sp->r.ds[0] - 1.0 / 6.0) < 1e-12 && fabs(sp->r.ds[1]) < 1e-12 && fabs(sp->dsdy[0]) < 1e-12 &&
                             fabs(sp->dsdy[1] + 1.0 / 6.0) < 1e-12 && sp->uv[0] == 0 && sp->uv[1] == 1,
                         "m=%u: gradient (%g, %g) per x, (%g, %g) per y, uv axes %u %u", m, sp->r.ds[0], sp->r.ds[1],
                         sp->dsdy[0], sp->dsdy[1], sp->uv[0], sp->uv[1]);
                /* The sample's UV: the texture coordinate at its point. */
                for (size_t i = 0; i < (size_t)w * h * g.n; i++)
                    if (g.poly[i] != NP_GBUF_NONE) {
                        double sx, sy, uv[2];
                        int64_t q[2];
                        np_gbuf_position(&g, i, &sx, &sy);
                        np_gbuf_uv_f(&g, i, uv);
                        np_gbuf_uv(&g, i, q);
                        NP_CHECK(fabs(uv[0] - (sx - R[r][0]) / 6.0) < 1e-12 && fabs(uv[1] - (R[r][3] - sy) / 6.0) < 1e-12 &&
                                     fabs((double)q[0] / 4294967296.0 - uv[0]) <= 0x1p-30,
                                 "m=%u: sample %zu at (%g, %g): uv (%g, %g)", m, i, sx, sy, uv[0], uv[1]);
                    }
            }
            if (r == 2)
                NP_CHECK(want == (uint64_t)h * m, "m=%u: the last column holds %llu samples", m, (unsigned long long)want);
            np_gbuf_free(&g);
            np_scene_free(&s);
        }
    }
    return 0;
}

/*
 * Shared edges: a square split along its diagonal into two triangles, the
 * diagonal through sample points (a = b) at every m - each sample in the
 * square covered exactly once, none outside; then the same on a fan of 8
 * triangles around the centre.
 */
static int shared_edges(void)
{
    const unsigned w = 16, h = 16;
    const double lo = 2 - w / 2.0, hi = 14 - w / 2.0; /* screen 2 .. 14 */
    for (int fan = 0; fan < 2; fan++)
        for (unsigned m = 1; m <= 4; m++) {
            char geom[4096];
            size_t at = 0;
            if (!fan) {
                at += (size_t)snprintf(geom, sizeof geom,
                                       "{\"type\": \"polygon\", \"vertices\": [[%g, %g, 0], [%g, %g, 0], [%g, %g, 0]],"
                                       "\"texcoords\": [[0,0,0],[1,0,0],[1,1,0]]},"
                                       "{\"type\": \"polygon\", \"vertices\": [[%g, %g, 0], [%g, %g, 0], [%g, %g, 0]],"
                                       "\"texcoords\": [[0,0,0],[1,1,0],[0,1,0]]}",
                                       lo, hi, lo, lo, hi, lo, lo, hi, hi, lo, hi, hi);
            } else {
                const double P[8][2] = { { lo, lo }, { 0, lo }, { hi, lo }, { hi, 0 }, { hi, hi }, { 0, hi }, { lo, hi }, { lo, 0 } };
                for (int t = 0; t < 8; t++)
                    at += (size_t)snprintf(geom + at, sizeof geom - at,
                                           "%s{\"type\": \"polygon\", \"vertices\": [[0.3, 0.1, 0], [%g, %g, 0], [%g, %g, 0]],"
                                           "\"texcoords\": [[0,0,0],[1,0,0],[1,1,0]]}",
                                           t ? "," : "", P[t][0], P[t][1], P[(t + 1) % 8][0], P[(t + 1) % 8][1]);
            }
            np_scene s;
            np_gbuf g;
            if (flat_scene(w, h, geom, NULL, &s) || build(&s, m, &g))
                return 1;
            uint64_t twice = 0, missed = 0, outside = 0;
            for (size_t i = 0; i < (size_t)w * h * g.n; i++) {
                double sx, sy;
                np_gbuf_position(&g, i, &sx, &sy);
                int in = sx >= 2 && sx < 14 && sy >= 2 && sy < 14;
                twice += g.hits[i] > 1;
                missed += in && g.hits[i] == 0;
                outside += !in && g.hits[i] != 0;
            }
            printf("%s m=%u: %llu samples covered, twice %llu, missed %llu, outside %llu\n", fan ? "fan" : "diagonal", m,
                   (unsigned long long)g.covered_samples, (unsigned long long)twice, (unsigned long long)missed,
                   (unsigned long long)outside);
            NP_CHECK(twice == 0 && missed == 0 && outside == 0, "%s m=%u: twice %llu missed %llu outside %llu",
                     fan ? "fan" : "diagonal", m, (unsigned long long)twice, (unsigned long long)missed,
                     (unsigned long long)outside);
            np_gbuf_free(&g);
            np_scene_free(&s);
        }
    return 0;
}

/*
 * Depth quantisation at the far end: depth range [9, 10] from the eye at
 * z = 10, so the plane z = 0 is code 2^24 - 1 and z = 1/(2^24 - 1) is
 * 2^24 - 2. The nearer by one LSB wins in either order; equal codes: the
 * later polygon wins; beyond the far end clamps to 2^24 - 1 (never wraps).
 */
static int depth_far(void)
{
    const unsigned w = 8, h = 8;
    const double one = 1.0 / (double)NP_GBUF_DEPTH_FAR;
    struct { double za, zb; uint32_t want_code; int want_b; } C[] = {
        { 0, one, NP_GBUF_DEPTH_FAR - 1, 1 },   /* B nearer by 1 LSB, drawn second */
        { one, 0, NP_GBUF_DEPTH_FAR - 1, 0 },   /* A nearer by 1 LSB, drawn first */
        { 0, 0, NP_GBUF_DEPTH_FAR, 1 },         /* equal: the later */
        { 0, -1, NP_GBUF_DEPTH_FAR, 1 },        /* B beyond far: clamped, equal, the later */
        { -1, -2, NP_GBUF_DEPTH_FAR, 1 },
        { 1, 0.5, 0, 0 },                       /* at near: code 0 */
    };
    for (size_t c = 0; c < sizeof C / sizeof C[0]; c++) {
        char a[1024], b[1024], geom[2100];
        rect(a, sizeof a, w, h, -1, w + 1.0, -1, h + 1.0, C[c].za);
        rect(b, sizeof b, w, h, -1, w + 1.0, -1, h + 1.0, C[c].zb);
        snprintf(geom, sizeof geom, "%s, %s", a, b);
        np_scene s;
        np_gbuf g;
        if (flat_scene(w, h, geom, ", \"depth_range\": [9, 10]", &s) || build(&s, 2, &g))
            return 1;
        uint64_t bad = 0;
        for (size_t i = 0; i < (size_t)w * h * g.n; i++)
            bad += g.depth[i] != C[c].want_code || g.poly[i] != (uint32_t)C[c].want_b || g.depth[i] > NP_GBUF_DEPTH_FAR;
        NP_CHECK(bad == 0, "case %zu: %llu samples: depth %u poly %u, want %u poly %d", c, (unsigned long long)bad,
                 g.depth[0], g.poly[0], C[c].want_code, C[c].want_b);
        np_gbuf_free(&g);
        np_scene_free(&s);
    }
    return 0;
}

/* Shading full runs: the cost model's cycles equal the engine's cycle-accurate model fed the same descriptors. */
static int shade_cycles(void)
{
    np_scene s;
    if (np_golden_scene_load(NP_SOURCE_DIR, "wood", &s))
        return 1;
    np_render_unit_cfg us[NP_RENDER_MAX_UNITS];
    int nu = units(&s, us);
    for (unsigned m = 2; m <= 3; m++) {
        np_gbuf g;
        if (build(&s, m, &g))
            return 1;
        uint8_t *rgb = malloc((size_t)g.w * g.h * g.n * 3);
        for (int k = 0; k < nu; k++) {
            np_gbuf_cost c;
            np_gbuf_shade(&g, us[k].u, us[k].cfg.bytes, NULL, rgb, &c);
            const np_span_engine *e = us[k].u->span->engine;
            np_span_sim sim;
            NP_CHECK(np_span_sim_init(&sim, e, np_unit_span_cfg(us[k].u->span, us[k].cfg.bytes), &g.regs) == 0, "sim");
            size_t next = 0;
            while ((next < g.n_spans || !np_span_sim_idle(&sim)) && sim.stats.cycles < 100000000u) {
                np_span_port p;
                memset(&p, 0, sizeof p);
                p.in_valid = next < g.n_spans;
                p.in = p.in_valid ? &g.spans[next].r.hw : NULL;
                p.out_ready = 1;
                np_span_sim_eval(&sim, &p);
                if (p.in_valid && p.in_ready)
                    next++;
                np_span_sim_clock(&sim, &p);
            }
            printf("wood m=%u %s: cost model %llu cycles (%llu runs, %llu set-up), cycle-accurate model %llu\n", m,
                   us[k].u->name, (unsigned long long)c.cycles, (unsigned long long)c.runs, (unsigned long long)c.setup,
                   (unsigned long long)sim.stats.cycles);
            NP_CHECK(c.runs == g.n_spans, "every sub-span one run (%llu of %zu)", (unsigned long long)c.runs, g.n_spans);
            NP_CHECK(c.cycles == sim.stats.cycles, "m=%u %s: %llu cycles, the cycle model %llu", m,
                     us[k].u->name, (unsigned long long)c.cycles, (unsigned long long)sim.stats.cycles);
            np_span_sim_free(&sim);
        }
        /* A partial mask: texel seeks, fdiff steps over the skipped pixels. */
        const size_t npx = (size_t)g.w * g.h;
        uint16_t *mask = malloc(npx * sizeof *mask);
        for (size_t p = 0; p < npx; p++)
            mask[p] = np_aacount_mask(m, (unsigned)(p % g.n) + 1u);
        const np_render_unit_cfg *tx = unit_named(us, nu, "texel"), *fd = unit_named(us, nu, "fdiff");
        np_gbuf_cost ct, cf;
        np_gbuf_shade(&g, tx->u, tx->cfg.bytes, mask, rgb, &ct);
        np_gbuf_shade(&g, fd->u, fd->cfg.bytes, mask, rgb, &cf);
        printf("wood m=%u adaptive mask: texel %llu samples %llu runs %llu seek clocks %llu cycles; fdiff %llu skipped "
               "pixels %llu cycles\n", m, (unsigned long long)ct.samples, (unsigned long long)ct.runs,
               (unsigned long long)ct.seek, (unsigned long long)ct.cycles, (unsigned long long)cf.skipped,
               (unsigned long long)cf.cycles);
        NP_CHECK(ct.samples == cf.samples && ct.seek > 0 && ct.skipped == 0 && cf.skipped > 0 && cf.seek == 0,
                 "seek and skip accounted");
        free(mask);
        free(rgb);
        np_gbuf_free(&g);
    }
    np_scene_free(&s);
    return 0;
}

/*
 * The renderer's pixel resolve (np_gbuf_resolve, which sums a pixel's masked
 * samples and calls the unit's resolve, np_aacount_resolve through np_unit.samples) over every (s, sum): one
 * pixel of m = 4 per pair, mask = the first s of B4, the sum spread over the s
 * samples (each <= 255), each channel a different sum; the result is
 * round_half_up(sum / s). Background (s = 0) is the scene's colour, rounded.
 */
static int resolve_exhaustive(void)
{
    size_t npx = 0;
    for (unsigned s = 1; s <= NP_GBUF_N_MAX; s++)
        npx += 255u * s + 1u;
    npx++; /* one uncovered pixel */
    np_scene sc;
    memset(&sc, 0, sizeof sc);
    sc.background[0] = 63.5; /* 0..255: round half up 64, 128, 255 */
    sc.background[1] = 128.4;
    sc.background[2] = 255.0;
    np_gbuf g;
    memset(&g, 0, sizeof g);
    g.sc = &sc;
    g.m = 4;
    g.n = 16;
    g.w = (unsigned)npx;
    g.h = 1;
    g.samples = np_unit_find("aacount")->samples; /* as np_gbuf_build takes it from the registry */
    uint16_t *mask = calloc(npx, sizeof *mask);
    uint8_t *rgb = calloc(npx * 16 * 3, 1), *out = calloc(npx * 3, 1);
    uint32_t *want_sum = calloc(npx, sizeof *want_sum);
    uint8_t *want_s = calloc(npx, 1);
    NP_CHECK(mask && rgb && out && want_sum && want_s, "out of memory");
    if (!mask || !rgb || !out || !want_sum || !want_s)
        return 1;
    size_t p = 0;
    for (unsigned s = 1; s <= NP_GBUF_N_MAX; s++)
        for (uint32_t sum = 0; sum <= 255u * s; sum++, p++) {
            mask[p] = np_aacount_mask(4, s);
            want_sum[p] = sum;
            want_s[p] = (uint8_t)s;
            for (unsigned ch = 0; ch < 3; ch++) {
                /* channel ch carries sum, 255 s - sum, sum / 2: three sums a pixel */
                uint32_t left = ch == 0 ? sum : ch == 1 ? 255u * s - sum : sum / 2u;
                for (unsigned j = 0; j < 16; j++) {
                    /* samples outside the mask carry 255: they must not count */
                    uint8_t v = 255;
                    if (((unsigned)mask[p] >> j) & 1u) {
                        v = (uint8_t)(left > 255u ? 255u : left);
                        left -= v;
                    }
                    rgb[3 * (p * 16 + j) + ch] = v;
                }
            }
        }
    np_gbuf_resolve(&g, mask, rgb, out);
    uint64_t checked = 0;
    for (p = 0; p + 1 < npx; p++) {
        const unsigned s = want_s[p], sum = want_sum[p];
        const unsigned sums[3] = { sum, 255u * s - sum, sum / 2u };
        for (unsigned ch = 0; ch < 3; ch++, checked++) {
            unsigned want = (2u * sums[ch] + s) / (2u * s); /* floor(sum / s + 1/2) */
            if (out[3 * p + ch] != want) {
                NP_CHECK(0, "resolve s=%u sum=%u: %u, want %u", s, sums[ch], out[3 * p + ch], want);
                break;
            }
        }
    }
    NP_CHECK(out[3 * p] == 64 && out[3 * p + 1] == 128 && out[3 * p + 2] == 255, "background pixel %u %u %u",
             out[3 * p], out[3 * p + 1], out[3 * p + 2]);
    printf("renderer resolve: %llu (s, sum) channel values exact (round half up of the masked mean), background "
           "rounded\n", (unsigned long long)checked);
    free(mask);
    free(rgb);
    free(out);
    free(want_sum);
    free(want_s);
    return 0;
}

/*
 * Acceptance: with m = 3 the centre sample (B3's index 0) is today's 1x1
 * image bit for bit on every unit that renders the seed scenes (golden
 * hashes), and so is m = 1.
 */
static int centre_golden(void)
{
    const char *names[2] = { "wood", "marble" };
    for (int i = 0; i < 2; i++) {
        np_scene s;
        if (np_golden_scene_load(NP_SOURCE_DIR, names[i], &s))
            return 1;
        np_render_unit_cfg us[NP_RENDER_MAX_UNITS];
        int nu = units(&s, us);
        NP_CHECK(unit_named(us, nu, "texel") && unit_named(us, nu, "fdiff"), "texel and fdiff render %s", names[i]);
        for (unsigned m = 1; m <= 3; m += 2) {
            np_gbuf g;
            if (build(&s, m, &g))
                return 1;
            uint8_t *rgb = malloc((size_t)g.w * g.h * 3);
            for (int k = 0; k < nu; k++) {
                char want[65], hex[65];
                if (golden(names[i], us[k].u->name, want))
                    continue;
                np_gbuf_cost c;
                NP_CHECK(np_gbuf_shade_first(&g, us[k].u, us[k].cfg.bytes, rgb, &c) == 0, "shade");
                np_image_hash(g.w, g.h, rgb, hex);
                printf("%s m=%u %s: S %s %s (%llu samples, %llu runs, %llu cycles)\n", names[i], m, us[k].u->name,
                       hex, strcmp(hex, want) == 0 ? "= golden" : "CHANGED", (unsigned long long)c.samples,
                       (unsigned long long)c.runs, (unsigned long long)c.cycles);
                NP_CHECK(strcmp(hex, want) == 0, "%s m=%u %s: S is %s, golden %s", names[i], m, us[k].u->name, hex,
                         want);
            }
            /* The reference's centre samples, rounded, are the golden reference image. */
            char want[65], hex[65];
            double *ref = malloc((size_t)g.w * g.h * g.n * 3 * sizeof *ref);
            np_gbuf_reference_samples(&g, ref);
            const unsigned j0 = (unsigned)__builtin_ctz(np_aacount_mask(m, 1));
            for (size_t p = 0; p < (size_t)g.w * g.h; p++)
                for (int ch = 0; ch < 3; ch++)
                    rgb[3 * p + (size_t)ch] = (uint8_t)floor(ref[3 * (p * g.n + j0) + (size_t)ch] + 0.5);
            np_image_hash(g.w, g.h, rgb, hex);
            if (golden(names[i], "ref", want) == 0)
                NP_CHECK(strcmp(hex, want) == 0, "%s m=%u ref: %s, golden %s", names[i], m, hex, want);
            free(ref);
            free(rgb);
            np_gbuf_free(&g);
        }
        np_scene_free(&s);
    }
    return 0;
}

/*
 * Full m x m supersampling (every sample shaded, resolved) on texel: each
 * sample is the unit's pixel k of its sub-span (the same bits as the span
 * model), the image deterministic (two builds and shades agree) and hashed
 * (vectors/images/gbuf_hashes.txt),
 * and shading the samples in two halves gives the same bits as at once.
 */
static int full_ssaa(void)
{
    np_scene s;
    if (np_golden_scene_load(NP_SOURCE_DIR, "marble", &s))
        return 1;
    np_render_unit_cfg us[NP_RENDER_MAX_UNITS];
    int nu = units(&s, us);
    const np_render_unit_cfg *tx = unit_named(us, nu, "texel");
    NP_CHECK(tx != NULL, "texel renders marble");
    if (!tx)
        return 1;
    for (unsigned m = 2; m <= 4; m++) {
        np_gbuf g, g2;
        if (build(&s, m, &g) || build(&s, m, &g2))
            return 1;
        const size_t npx = (size_t)g.w * g.h, ns = npx * g.n;
        uint8_t *a = malloc(ns * 3), *b = malloc(ns * 3), *img = malloc(npx * 3), *img2 = malloc(npx * 3);
        uint16_t *mask = malloc(npx * sizeof *mask);
        np_gbuf_cost c, c2;
        NP_CHECK(np_gbuf_shade(&g, tx->u, tx->cfg.bytes, NULL, a, &c) == 0, "shade");
        /* The same samples in two halves (B index < n/2, then the rest), from a second build. */
        memset(b, 0xA5, ns * 3);
        uint16_t lo = np_aacount_mask(m, g.n / 2), all = (uint16_t)((1u << g.n) - 1u);
        for (size_t p = 0; p < npx; p++)
            mask[p] = lo;
        np_gbuf_shade(&g2, tx->u, tx->cfg.bytes, mask, b, &c2);
        for (size_t p = 0; p < npx; p++)
            mask[p] = (uint16_t)(all & ~lo);
        np_gbuf_shade(&g2, tx->u, tx->cfg.bytes, mask, b, NULL);
        NP_CHECK(memcmp(a, b, ns * 3) == 0, "m=%u: samples shaded in two halves differ", m);
        np_gbuf_resolve(&g, NULL, a, img);
        np_gbuf_resolve(&g2, NULL, b, img2);
        NP_CHECK(memcmp(img, img2, npx * 3) == 0, "m=%u: resolve not deterministic", m);
        NP_CHECK(c.samples == g.covered_samples, "m=%u: %llu samples shaded of %llu covered", m,
                 (unsigned long long)c.samples, (unsigned long long)g.covered_samples);
        /* Against the float references: within 1 LSB per sample, and the resolve near the double SSAA. */
        double *ref = malloc(ns * 3 * sizeof *ref), *ss = malloc(npx * 3 * sizeof *ss);
        np_gbuf_reference_samples(&g, ref);
        double worst = 0;
        for (size_t i = 0; i < ns * 3; i++)
            worst = fmax(worst, fabs((double)a[i] - ref[i]));
        NP_CHECK(worst <= 1.0, "m=%u: a sample differs from the reference by %.3f LSB", m, worst);
        np_gbuf_reference_ssaa(&g, ss);
        double worst_px = 0;
        for (size_t i = 0; i < npx * 3; i++)
            worst_px = fmax(worst_px, fabs((double)img[i] - ss[i]));
        NP_CHECK(worst_px <= 1.5, "m=%u: resolved pixel %.3f LSB from the double SSAA", m, worst_px);
        char hex[65], want[65], key[16];
        np_image_hash(g.w, g.h, img, hex);
        snprintf(key, sizeof key, "ssaa%u", m);
        if (golden_in("gbuf_hashes.txt", "marble", key, want) == 0)
            NP_CHECK(strcmp(hex, want) == 0, "marble %s on texel: %s, checked in %s", key, hex, want);
        double mse = np_gbuf_mse(img, ss, g.cover, npx);
        printf("marble m=%u full SSAA on texel: %s, %llu samples, %llu runs, %llu cycles; max sample error %.3f LSB, "
               "pixel vs double SSAA %.3f LSB, MSE %.3e (PSNR %.2f dB paper / %.2f dB)\n",
               m, hex, (unsigned long long)c.samples, (unsigned long long)c.runs, (unsigned long long)c.cycles, worst,
               worst_px, mse, np_gbuf_psnr_paper(mse), np_gbuf_psnr(mse));
        free(ref);
        free(ss);
        free(a);
        free(b);
        free(img);
        free(img2);
        free(mask);
        np_gbuf_free(&g);
        np_gbuf_free(&g2);
    }
    np_scene_free(&s);
    return 0;
}

/*
 * The ground truth: at q = m it is the double SSAA of the G-buffer bit for
 * bit (same sample points, same span arithmetic); at q = 16 (256 samples a
 * pixel) on wood at 64 x 64, full 4x4 supersampling is closer to it than 2x2,
 * and 2x2 than one sample (the MSEs printed with both PSNRs).
 */
static int ground_truth(void)
{
    np_scene s;
    char err[512];
    if (np_golden_scene_load(NP_SOURCE_DIR, "marble", &s))
        return 1;
    const size_t npx = (size_t)s.width * s.height;
    double *gt = malloc(npx * 3 * sizeof *gt), *ss = malloc(npx * 3 * sizeof *ss);
    for (unsigned m = 2; m <= 4; m += 2) {
        np_gbuf g;
        if (build(&s, m, &g))
            return 1;
        np_gbuf_reference_ssaa(&g, ss);
        NP_CHECK(np_gbuf_ground_truth(&s, m, gt, err, sizeof err) == 0, "%s", err);
        NP_CHECK(memcmp(gt, ss, npx * 3 * sizeof *gt) == 0, "m=%u: ground truth at q = m differs from the SSAA", m);
        np_gbuf_free(&g);
    }
    np_scene_free(&s);
    free(gt);
    free(ss);
    if (np_golden_scene_load(NP_SOURCE_DIR, "wood", &s))
        return 1;
    s.width = s.height = 64; /* the same view, 4x coarser pixels: the ground truth stays quick */
    const size_t n64 = 64 * 64;
    gt = malloc(n64 * 3 * sizeof *gt);
    ss = malloc(n64 * 3 * sizeof *ss);
    double t0 = np_now();
    NP_CHECK(np_gbuf_ground_truth(&s, 16, gt, err, sizeof err) == 0, "%s", err);
    double tgt = np_now() - t0, mse[5] = { 0 };
    for (unsigned m = 1; m <= 4; m++) {
        np_gbuf g;
        if (build(&s, m, &g))
            return 1;
        np_gbuf_reference_ssaa(&g, ss);
        mse[m] = np_gbuf_mse_f(ss, gt, NULL, n64);
        printf("wood 64x64: double SSAA %ux%u against the 16x16 ground truth: MSE %.3e, PSNR %.2f dB (paper's) "
               "%.2f dB\n", m, m, mse[m], np_gbuf_psnr_paper(mse[m]), np_gbuf_psnr(mse[m]));
        np_gbuf_free(&g);
    }
    printf("bench ground truth 16x16, 64x64 pixels: %.3f s\n", tgt);
    NP_CHECK(mse[4] < mse[2] && mse[2] < mse[1] && mse[4] > 0, "SSAA does not converge: %g %g %g", mse[1], mse[2],
             mse[4]);
    /* The error helpers: MSE on [0, 1], the paper's PSNR and the consistent one differ by 10 log10(255^2). */
    uint8_t a[3] = { 10, 20, 30 };
    double b[3] = { 11, 20, 27 };
    double e = np_gbuf_mse(a, b, NULL, 1);
    NP_CHECK(fabs(e - 10.0 / 3.0 / 65025.0) < 1e-18, "mse %g", e);
    NP_CHECK(fabs(np_gbuf_psnr_paper(e) - np_gbuf_psnr(e) - 20.0 * log10(255.0)) < 1e-9, "psnr definitions");
    NP_CHECK(fabs(np_gbuf_psnr_paper(5.0e-5) - 91.14) < 0.01, "the paper's 2x2 row: MSE 5.0e-5 prints %.2f dB, "
             "the paper 91.14", np_gbuf_psnr_paper(5.0e-5));
    free(gt);
    free(ss);
    np_scene_free(&s);
    return 0;
}

/*
 * Lighting (np_gbuf.h "Lighting"): the factor L against the exact formula on
 * the quantised inputs (|error| <= 1 LSB of Q1.16) over random normals and
 * lights and the axes; the lit colour within 1/2 LSB + 255 2^-16 of c L;
 * boxes.json (light.image) on texel, every sample at m = 3 within 1 LSB of
 * the reference; a scene without light.image is not lit.
 */
static int light(void)
{
    np_scene s;
    if (np_golden_scene_load(NP_SOURCE_DIR, "boxes", &s))
        return 1;
    NP_CHECK(s.light_image == 1, "boxes.json lights its image");
    np_gbuf_lightq q;
    np_gbuf_light_setup(&s, &q);
    uint64_t st = 0x9E3779B97F4A7C15u;
    double worst_L = 0, worst_c = 0;
    for (int it = 0; it < 200000; it++) {
        int8_t n[3];
        for (int a = 0; a < 3; a++) {
            st += 0x9E3779B97F4A7C15u;
            uint64_t z = st;
            z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9u;
            z = (z ^ (z >> 27)) * 0x94D049BB133111EBu;
            z ^= z >> 31;
            n[a] = it < 6 ? (int8_t)(a == it / 2 ? (it % 2 ? -127 : 127) : 0) : (int8_t)((int)(z % 255u) - 127);
        }
        double dot = ((double)n[0] * q.l[0] + (double)n[1] * q.l[1] + (double)n[2] * q.l[2]) / 4194304.0;
        double a = (double)q.a / 65536.0;
        double L = a + (1 - a) * fmin(1.0, fmax(0.0, dot));
        double Lq = (double)np_gbuf_light_factor(&q, n) / 65536.0;
        worst_L = fmax(worst_L, fabs(Lq - L) * 65536.0);
        uint8_t c[3] = { (uint8_t)(it & 255), 255, 0 };
        np_gbuf_light(&q, n, c);
        worst_c = fmax(worst_c, fabs((double)c[0] - (double)(it & 255) * Lq));
        worst_c = fmax(worst_c, fabs((double)c[1] - 255.0 * Lq));
    }
    printf("light: L within %.3f LSB of Q1.16, lit colour within %.4f LSB of c L\n", worst_L, worst_c);
    NP_CHECK(worst_L <= 1.0, "L off by %.3f LSB", worst_L);
    NP_CHECK(worst_c <= 0.5, "lit colour off by %.4f LSB", worst_c);
    np_render_unit_cfg us[NP_RENDER_MAX_UNITS];
    int nu = units(&s, us);
    const np_render_unit_cfg *tx = unit_named(us, nu, "texel");
    np_gbuf g;
    if (!tx || build(&s, 3, &g))
        return 1;
    const size_t ns = (size_t)g.w * g.h * g.n;
    uint8_t *rgb = malloc(ns * 3);
    double *ref = malloc(ns * 3 * sizeof *ref);
    np_gbuf_shade(&g, tx->u, tx->cfg.bytes, NULL, rgb, NULL);
    np_gbuf_reference_samples(&g, ref);
    double worst = 0, mean = 0;
    for (size_t i = 0; i < ns * 3; i++) {
        worst = fmax(worst, fabs((double)rgb[i] - ref[i]));
        mean += (double)rgb[i] - ref[i];
    }
    printf("boxes m=3 lit on texel: max %.3f LSB, mean %+.4f LSB over %zu samples\n", worst, mean / (double)(ns * 3), ns);
    NP_CHECK(worst <= 1.0, "lit samples %.3f LSB from the reference", worst);
    /* Its full 3x3 supersampling, resolved, is checked in (depth edges and light together). */
    uint8_t *img = malloc((size_t)g.w * g.h * 3);
    char hex[65], want[65];
    np_gbuf_resolve(&g, NULL, rgb, img);
    np_image_hash(g.w, g.h, img, hex);
    printf("boxes ssaa3 %s\n", hex);
    if (golden_in("gbuf_hashes.txt", "boxes", "ssaa3", want) == 0)
        NP_CHECK(strcmp(hex, want) == 0, "boxes ssaa3 on texel: %s, checked in %s", hex, want);
    free(img);
    /* The normals: unit length within the code's rounding, turned to the camera (no lit colour above unlit). */
    uint64_t longn = 0;
    for (size_t i = 0; i < ns; i++)
        if (g.poly[i] != NP_GBUF_NONE) {
            double n[3];
            np_gbuf_normal_decode(g.normal[i], n);
            double l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            longn += fabs(l - 1.0) > 1.5 * sqrt(3.0) / 254.0;
        }
    NP_CHECK(longn == 0, "%llu normals off unit length", (unsigned long long)longn);
    free(rgb);
    free(ref);
    np_gbuf_free(&g);
    s.light_image = 0;
    np_gbuf_light_setup(&s, &q);
    int8_t n0[3] = { 0, 127, 0 };
    uint8_t c0[3] = { 200, 100, 50 };
    np_gbuf_light(&q, n0, c0);
    NP_CHECK(c0[0] == 200 && c0[1] == 100 && c0[2] == 50, "unlit scene lit");
    np_scene_free(&s);
    return 0;
}

/*
 * A mesh of 101,760 triangles (a sphere of 160 rings, radius 100 pixels) renders: the winding
 * faces out, no sample is covered twice (front faces of a convex mesh), every
 * sample inside the outline is covered and none outside, the depth is the
 * sphere's within the tessellation's sag; the 1x1 render (noisepipe render's
 * path) covers the same pixels on texel. The time is printed (bench line).
 */
static int mesh_sphere(void)
{
    const unsigned w = 256, h = 256;
    const char *geom = "{\"type\": \"sphere\", \"center\": [0, 0, -150], \"radius\": 100, \"subdivisions\": 160,"
                       "\"texture_min\": [0, 0, 0], \"texture_max\": [2, 2, 2]}";
    np_scene s;
    if (flat_scene(w, h, geom, NULL, &s))
        return 1;
    NP_CHECK(s.n_prims == 4u * 160u * 159u && s.n_mesh == 1, "%u polygons", s.n_prims);
    uint64_t inward = 0;
    np_scene_poly tmp;
    for (uint32_t id = 0; id < s.n_prims; id++) {
        const np_scene_poly *p = np_scene_poly_get(&s, id, &tmp);
        double n[3] = { 0, 0, 0 }, c[3] = { 0, 0, 0 };
        for (unsigned k = 0; k < 3; k++) {
            const double *a = p->p[k], *b = p->p[(k + 1) % 3];
            n[0] += (a[1] - b[1]) * (a[2] + b[2]);
            n[1] += (a[2] - b[2]) * (a[0] + b[0]);
            n[2] += (a[0] - b[0]) * (a[1] + b[1]);
            for (int x = 0; x < 3; x++)
                c[x] += a[x] - (x == 2 ? -150.0 : 0.0); /* from the centre */
        }
        inward += n[0] * c[0] + n[1] * c[1] + n[2] * c[2] <= 0;
    }
    NP_CHECK(inward == 0, "%llu triangles wound inwards", (unsigned long long)inward);
    for (unsigned m = 1; m <= 2; m++) {
        np_gbuf g;
        double t0 = np_now();
        if (build(&s, m, &g))
            return 1;
        double tb = np_now() - t0;
        uint64_t twice = 0, missed = 0, outside = 0, far = 0;
        double worst_z = 0;
        for (size_t i = 0; i < (size_t)w * h * g.n; i++) {
            double sx, sy;
            np_gbuf_position(&g, i, &sx, &sy);
            double x = sx - w / 2.0, y = h / 2.0 - sy, r = sqrt(x * x + y * y);
            twice += g.hits[i] > 1;
            missed += r < 99.5 && g.hits[i] != 1;
            outside += r > 100.0 && g.hits[i] != 0;
            if (g.poly[i] != NP_GBUF_NONE && r < 99.0) {
                double z = 160.0 - sqrt(1e4 - r * r); /* the eye at z = 10, the sphere's front at -150 + sqrt */
                double got = np_gbuf_depth_f(&g, g.depth[i]);
                worst_z = fmax(worst_z, fabs(got - z));
                far += got < z - 1e-6; /* the facets lie inside the sphere: never nearer than it */
            }
        }
        printf("bench mesh: %u triangles, %ux%u at m=%u: G-buffer %.3f s, %zu sub-spans, %llu samples covered; depth "
               "within %.4f of the sphere\n", s.n_prims, w, h, m, tb, g.n_spans, (unsigned long long)g.covered_samples,
               worst_z);
        NP_CHECK(twice == 0 && missed == 0 && outside == 0, "m=%u: twice %llu, missed %llu, outside %llu", m,
                 (unsigned long long)twice, (unsigned long long)missed, (unsigned long long)outside);
        /* Sag of a facet: R (1 - cos(pi / 160)) = 0.019; across a facet at the rim the depth changes fast. */
        NP_CHECK(far == 0 && worst_z < 1.0, "m=%u: depth off the sphere by %.4f (%llu nearer)", m, worst_z,
                 (unsigned long long)far);
        if (m == 1) {
            np_render_frame fr;
            char err[512];
            NP_CHECK(np_render_prepare(&s, &fr, err, sizeof err) == 0, "%s", err);
            NP_CHECK(fr.pixels == g.covered_pixels, "1x1 frame: %llu pixels, the G-buffer %llu",
                     (unsigned long long)fr.pixels, (unsigned long long)g.covered_pixels);
            np_render_unit_cfg us[NP_RENDER_MAX_UNITS];
            int nu = units(&s, us);
            const np_render_unit_cfg *tx = unit_named(us, nu, "texel");
            np_render_run run;
            t0 = np_now();
            NP_CHECK(tx && np_render_reference(&fr) == 0 && np_render_unit(&fr, tx->u, tx->cfg.bytes, 0, &run) == 0,
                     "render");
            printf("bench mesh: 1x1 frame %zu spans, reference and texel %.3f s, texel max %.3f LSB\n", fr.n_spans,
                   np_now() - t0, run.err.max_lsb);
            NP_CHECK(run.err.max_lsb <= 1.0, "texel %.3f LSB", run.err.max_lsb);
            np_render_run_free(&run);
            np_render_frame_free(&fr);
        }
        np_gbuf_free(&g);
    }
    np_scene_free(&s);
    /* sphere.json: 998,000 triangles (the time is printed, not asserted). */
    if (np_golden_scene_load(NP_SOURCE_DIR, "sphere", &s))
        return 1;
    np_gbuf g;
    double t0 = np_now();
    if (build(&s, 1, &g))
        return 1;
    printf("bench mesh: sphere.json, %u polygons (%llu drawn), %ux%u at m=1: G-buffer %.3f s, %llu pixels covered\n",
           s.n_prims, (unsigned long long)g.polys_drawn, g.w, g.h, np_now() - t0,
           (unsigned long long)g.covered_pixels);
    NP_CHECK(s.n_prims == 6u + 4u * 500u * 499u && g.covered_pixels > 0, "sphere.json: %u polygons", s.n_prims);
    np_gbuf_free(&g);
    np_scene_free(&s);
    return 0;
}

/* The new scene keys: aa, light.image, camera.depth_range, sphere; each malformed one refused naming the field. */
static int scene_keys(void)
{
    np_scene s;
    if (np_golden_scene_load(NP_SOURCE_DIR, "boxes", &s))
        return 1;
    NP_CHECK(s.aa.present && s.aa.m == 3 && !s.aa.have_cd && s.aa.luma_taps == 4 && s.aa.tile == 0 &&
                 fabs(s.aa.t_min - 16.0 / 255.0) < 1e-15 && s.aa.t_edge == 0.125,
             "boxes aa defaults");
    np_scene_free(&s);
    if (np_golden_scene_load(NP_SOURCE_DIR, "wood", &s))
        return 1;
    NP_CHECK(!s.aa.present && !s.light_image && !s.cam.have_depth_range && s.n_prims == 6, "wood has none");
    np_scene_free(&s);
    char geom[1024];
    rect(geom, sizeof geom, 8, 8, 1, 7, 1, 7, 0);
    /* Each: a top-level field, a camera field, the geometry (NULL: the rectangle), the message wanted. */
    const char *B[][4] = {
        { "", ", \"depth_range\": [2, 1]", NULL, "field 'camera.depth_range': far must exceed near" },
        { "", ", \"depth_range\": 1", NULL, "field 'camera.depth_range': expected [near, far]" },
        { "\"aa\": {\"m\": 5},", "", NULL, "field 'aa.m'" },
        { "\"aa\": {\"tile\": 4},", "", NULL, "field 'aa.tile': expected 0 (off) or 6" },
        { "\"aa\": {\"c_x\": 1},", "", NULL, "field 'aa.c_x': unknown field" },
        { "\"aa\": {\"c_d\": -1},", "", NULL, "field 'aa.c_d'" },
        { "\"light\": {\"image\": 1},", "", NULL, "field 'light.image': expected true or false" },
        { "", "",
          "{\"type\": \"sphere\", \"center\": [0,0,0], \"radius\": 1, \"subdivisions\": 1, \"texture_min\": [0,0,0],"
          "\"texture_max\": [1,1,1]}", "field 'geometry[0].subdivisions'" },
        { "", "",
          "{\"type\": \"sphere\", \"center\": [0,0,0], \"radius\": 0, \"subdivisions\": 8, \"texture_min\": [0,0,0],"
          "\"texture_max\": [1,1,1]}", "field 'geometry[0].radius'" },
        { "", "",
          "{\"type\": \"sphere\", \"center\": [0,0,0], \"radius\": 1, \"subdivisions\": 8, \"texture_min\": [0,0,0],"
          "\"texture_max\": [1,1,1], \"cull\": 3}", "field 'geometry[0].cull'" },
    };
    for (size_t i = 0; i < sizeof B / sizeof B[0]; i++) {
        char json[8192], err[1024];
        snprintf(json, sizeof json,
                 "{\"noisepipe_scene\": 1, \"name\": \"t\", \"image\": {\"width\": 8, \"height\": 8}, %s"
                 "\"camera\": {\"projection\": \"orthographic\", \"eye\": [0, 0, 10], \"target\": [0, 0, 0],"
                 "\"up\": [0, 1, 0], \"height\": 8 %s}, \"geometry\": [%s], \"texture\": {\"quadric\": {\"A\": 1},"
                 "\"colormap\": {\"mode\": \"clamp\", \"domain\": [0, 1], \"colors\": [[0,0,0],[255,255,255]]}}}",
                 B[i][0], B[i][1], B[i][2] ? B[i][2] : geom);
        int rc = np_scene_parse(json, "t.json", &s, err, sizeof err);
        NP_CHECK(rc != 0 && strstr(err, B[i][3]), "want \"%s\", got \"%s\"", B[i][3], rc ? err : "(accepted)");
        if (rc == 0)
            np_scene_free(&s);
    }
    return 0;
}

/*
 * Depth under perspective: on boxes.json every sample of a horizontal face
 * (the slab's top y = 0, the boxes' tops y = 1, 1.6, 0.5) lifted back along
 * its ray by its decoded depth lands on that plane (within the u24 step),
 * and those faces' UV axes are s and r (t is constant on them).
 */
static int perspective_depth(void)
{
    np_scene s;
    if (np_golden_scene_load(NP_SOURCE_DIR, "boxes", &s))
        return 1;
    np_gbuf g;
    if (build(&s, 2, &g))
        return 1;
    /* The camera frame, as the renderer builds it: f forward, r = f x up, u = r x f. */
    double f[3], r[3], u[3], l = 0;
    for (int a = 0; a < 3; a++) {
        f[a] = s.cam.target[a] - s.cam.eye[a];
        l += f[a] * f[a];
    }
    for (int a = 0; a < 3; a++)
        f[a] /= sqrt(l);
    r[0] = f[1] * s.cam.up[2] - f[2] * s.cam.up[1];
    r[1] = f[2] * s.cam.up[0] - f[0] * s.cam.up[2];
    r[2] = f[0] * s.cam.up[1] - f[1] * s.cam.up[0];
    l = sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
    for (int a = 0; a < 3; a++)
        r[a] /= l;
    u[0] = r[1] * f[2] - r[2] * f[1];
    u[1] = r[2] * f[0] - r[0] * f[2];
    u[2] = r[0] * f[1] - r[1] * f[0];
    const double tops[4] = { 0, 1, 1.6, 0.5 }; /* face 3 (y = max) of each cube */
    const double step = (g.z_far - g.z_near) / (double)NP_GBUF_DEPTH_FAR;
    uint64_t n = 0;
    double worst = 0;
    for (size_t i = 0; i < (size_t)g.w * g.h * g.n; i++) {
        if (g.poly[i] == NP_GBUF_NONE || g.poly[i] % 6 != 3)
            continue;
        double sx, sy;
        np_gbuf_position(&g, i, &sx, &sy);
        const double k = s.cam.focal * g.h / 2.0, xd = (sx - g.w / 2.0) / k, yd = (g.h / 2.0 - sy) / k;
        const double z = np_gbuf_depth_f(&g, g.depth[i]);
        const double y = s.cam.eye[1] + z * (xd * r[1] + yd * u[1] + f[1]);
        /* The depth is within half a step of the true one; y moves by at most |dir_y| per unit of z. */
        const double dir = fabs(xd * r[1] + yd * u[1] + f[1]);
        worst = fmax(worst, fabs(y - tops[g.poly[i] / 6]) / (dir * step));
        const np_gbuf_span *sp = &g.spans[g.span[i]];
        NP_CHECK(sp->uv[0] == 0 && sp->uv[1] == 2, "a top face's UV axes are %u %u", sp->uv[0], sp->uv[1]);
        n++;
    }
    printf("boxes m=2: %llu samples on horizontal faces, lifted back within %.3f depth steps of their planes "
           "(depth range %.4f .. %.4f)\n", (unsigned long long)n, worst, g.z_near, g.z_far);
    NP_CHECK(n > 1000 && worst <= 0.5 + 1e-6, "perspective depth off its plane by %.3f steps", worst);
    np_gbuf_free(&g);
    np_scene_free(&s);
    return 0;
}

static const np_test_case cases[] = {
    { "resolve_exhaustive", resolve_exhaustive },
    { "centre_golden", centre_golden },
    { "full_ssaa", full_ssaa },
    { "borders", borders },
    { "shared_edges", shared_edges },
    { "depth_far", depth_far },
    { "shade_cycles", shade_cycles },
    { "ground_truth", ground_truth },
    { "light", light },
    { "mesh_sphere", mesh_sphere },
    { "perspective_depth", perspective_depth },
    { "scene_keys", scene_keys },
    { NULL, NULL },
};

NP_TEST_MAIN(cases)
