/* SPDX-License-Identifier: MIT */
/*
 * The 4-D noise texture as a scene (vectors/scenes/anim4d.json; np_noisetex.h,
 * docs/noise-nd.md "A 4-D texture in a scene"): frames move and move
 * continuously, the unit within 1 LSB of the reference, the cycle model
 * agreeing, scene keys checked. The frames' golden hashes: ndim.scene_hashes
 * (noisepipe render --hashes vectors/images/anim4d_hashes.txt).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "np_gbuf.h"
#include "np_noisetex.h"
#include "np_scene.h"
#include "np_test.h"
#include "np_texreg.h"

#define SCENE NP_SOURCE_DIR "/vectors/scenes/anim4d.json"

/*
 * Consecutive frames differ and change boundedly. The noise unit's output at
 * a fixed point moves by at most L dw 2^N + 2e LSB between frames
 * (np_noisetex_step_bound_lsb: the Lipschitz bound along w); the colour by at
 * most slope S sum|a_i| L dw (the exact texture's change: colour-map slope,
 * index scale, amplitudes; the light factor is <= 1 and the same in both
 * frames) plus the two frames' measured errors against their references.
 */
static int scene_continuity(void)
{
    static np_scene sc;
    char err[512];
    NP_CHECK(np_scene_load(SCENE, &sc, err, sizeof err) == 0, "%s", err);
    np_noisetex t;
    NP_CHECK(np_noisetex_init(&t, &sc, NULL, err, sizeof err) == 0, "%s", err);
    np_gbuf g;
    NP_CHECK(np_gbuf_build(&sc, 1, &g, err, sizeof err) == 0, "%s", err);
    size_t npix = (size_t)sc.width * sc.height;
    uint8_t *rgb[2] = { malloc(npix * 3), malloc(npix * 3) };
    int32_t *code[2] = { malloc(npix * sizeof(int32_t)), malloc(npix * sizeof(int32_t)) };
    NP_CHECK(rgb[0] && rgb[1] && code[0] && code[1], "out of memory");
    const double nbound = np_noisetex_step_bound_lsb(&t);
    double amps = 0.0;
    for (unsigned o = 0; o < sc.tex.n_oct; o++)
        amps += fabs(sc.tex.oct[o].amp);
    const double lip = 6.0 * 5.0 * sqrt(3.0) * 27.0 / 343.0;
    const double cslope = (double)np_tex_colour_slope(&g.regs) * np_texreg_index_scale(&sc.tex.cmap) * amps * lip *
                          (sc.noise.dw / 256.0);
    NP_CHECK(nbound > 0.0, "no step bound for %s", t.u->name);
    double prev_err = 0.0;
    for (unsigned f = 0; f < sc.noise.frames; f++) {
        np_noisetex_stats st;
        unsigned cur = f & 1u;
        NP_CHECK(np_noisetex_frame(&t, &g, f, f < 2, rgb[cur], NULL, code[cur], &st, err, sizeof err) == 0, "%s", err);
        NP_CHECK(st.max_lsb <= 1.0 && st.max_lit_lsb <= 1.0, "frame %u: error %.3f (lit %.3f) LSB", f, st.max_lsb,
                 st.max_lit_lsb);
        NP_CHECK(f >= 2 || (st.cycle_mismatch == 0 && st.cycles == st.transactions + 9u),
                 "frame %u: cycle model %llu mismatches, %llu clocks for %llu transactions", f,
                 (unsigned long long)st.cycle_mismatch, (unsigned long long)st.cycles,
                 (unsigned long long)st.transactions);
        if (f > 0) {
            int32_t dn = 0;
            unsigned dc = 0;
            uint64_t moved = 0;
            for (size_t p = 0; p < npix; p++) {
                int32_t d = abs(code[cur][p] - code[!cur][p]);
                dn = d > dn ? d : dn;
                for (unsigned k = 0; k < 3; k++) {
                    unsigned e = (unsigned)abs((int)rgb[cur][3 * p + k] - (int)rgb[!cur][3 * p + k]);
                    dc = e > dc ? e : dc;
                    moved += e > 0;
                }
            }
            double cb = cslope + prev_err + st.max_lit_lsb;
            printf("frames %u -> %u: noise max |change| %d LSB (bound %.1f), colour max |change| %u LSB (bound %.1f),"
                   " %llu channels changed\n",
                   f - 1u, f, dn, nbound, dc, cb, (unsigned long long)moved);
            NP_CHECK(dn > 0 && moved > npix / 4u, "frames %u and %u: nothing moved", f - 1u, f);
            NP_CHECK(dn <= nbound, "frames %u -> %u: noise change %d over the bound %.1f", f - 1u, f, dn, nbound);
            NP_CHECK(dc <= cb, "frames %u -> %u: colour change %u over the bound %.1f", f - 1u, f, dc, cb);
            NP_CHECK(cb < 255.0, "the colour bound %.1f says nothing", cb);
        }
        prev_err = st.max_lit_lsb;
    }
    free(rgb[0]), free(rgb[1]), free(code[0]), free(code[1]);
    np_gbuf_free(&g);
    np_scene_free(&sc);
    return 0;
}

/* The scene's noise keys: read, and bad values refused naming the field; the span units leave such a scene out. */
static int scene_keys(void)
{
    static np_scene sc;
    char err[512];
    NP_CHECK(np_scene_load(SCENE, &sc, err, sizeof err) == 0, "%s", err);
    NP_CHECK(sc.noise.present && strcmp(sc.noise.unit, "simplex4") == 0 && sc.noise.w0 == 0x0400 &&
                 sc.noise.dw == 0x0002 && sc.noise.frames == 12,
             "anim4d.json's noise section read as %s w0 %04x dw %04x frames %u", sc.noise.unit, sc.noise.w0,
             sc.noise.dw, sc.noise.frames);
    const np_unit *u;
    for (size_t i = 0; (u = np_unit_at(i)) != NULL; i++)
        if (u->cfg_scene) {
            /* No span unit renders it; the gate report's cfg_scene names simplex4 alone. */
            np_unit_cfg c;
            int want = strcmp(u->name, "simplex4") == 0;
            NP_CHECK(np_scene_cfg_unit(u, &c, &sc, err, sizeof err) == want, "%s: cfg_scene is not %d on anim4d", u->name,
                     want);
        }
    np_scene_free(&sc);
    static const struct {
        const char *noise, *msg;
    } bad[] = {
        { "{\"unit\": \"simplex3\"}", "field 'texture.noise.unit'" },
        { "{\"unit\": \"simplex4\", \"w0\": 0.001}", "field 'texture.noise.w0': 0.001 is not a multiple of 1/256" },
        { "{\"unit\": \"simplex4\", \"dw\": 256}", "field 'texture.noise.dw'" },
        { "{\"unit\": \"simplex4\", \"frames\": 0}", "field 'texture.noise.frames'" },
        { "{\"unit\": \"simplex4\", \"speed\": 1}", "field 'texture.noise.speed': unknown field" },
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        char json[1024];
        snprintf(json, sizeof json,
                 "{\"noisepipe_scene\": 1, \"name\": \"n\", \"image\": {\"width\": 8, \"height\": 8},"
                 " \"camera\": {\"projection\": \"orthographic\", \"eye\": [0,0,5], \"target\": [0,0,0],"
                 " \"up\": [0,1,0], \"height\": 2}, \"geometry\": [{\"type\": \"cube\", \"min\": [-1,-1,-1],"
                 " \"max\": [1,1,1], \"texture_min\": [0,0,0], \"texture_max\": [1,1,1]}],"
                 " \"texture\": {\"noise\": %s, \"colormap\": {\"mode\": \"clamp\", \"domain\": [0, 1],"
                 " \"colors\": [[0,0,0],[255,255,255]]}}}",
                 bad[i].noise);
        NP_CHECK(np_scene_parse(json, "bad.json", &sc, err, sizeof err) != 0, "%s accepted", bad[i].noise);
        NP_CHECK(strstr(err, bad[i].msg) != NULL, "%s: message '%s' lacks '%s'", bad[i].noise, err, bad[i].msg);
        printf("%s\n", err);
    }
    return 0;
}

/*
 * The same scene through classic4 (texture.noise.unit = "classic4", at
 * out_bits=16: its 8-bit default's LSB is 1/32, which the colour map's
 * slope would magnify past 1 colour LSB): within 1 LSB of the reference,
 * its cycle model agreeing (latency 11), the frames moving.
 */
static int scene_classic4(void)
{
    static char json[1 << 14];
    static np_scene sc;
    char err[512];
    FILE *f = fopen(SCENE, "rb");
    NP_CHECK(f != NULL, "cannot open %s", SCENE);
    if (!f)
        return 0;
    size_t n = fread(json, 1, sizeof json - 1, f);
    fclose(f);
    json[n] = '\0';
    char *at = strstr(json, "\"unit\": \"simplex4\"");
    NP_CHECK(at != NULL, "anim4d.json names no simplex4");
    if (!at)
        return 0;
    memcpy(at + 9, "classic4", 8);
    NP_CHECK(np_scene_parse(json, "anim4d-classic4", &sc, err, sizeof err) == 0, "%s", err);
    const np_unit *u = np_unit_find("classic4");
    np_unit_cfg cfg;
    NP_CHECK(u && np_unit_configure(u, &cfg, "out_bits=16", err, sizeof err) == 0, "%s", err);
    np_noisetex t;
    NP_CHECK(np_noisetex_init(&t, &sc, &cfg, err, sizeof err) == 0, "%s", err);
    NP_CHECK(np_noisetex_step_bound_lsb(&t) < 0.0, "a Lipschitz bound claimed for classic4");
    np_gbuf g;
    NP_CHECK(np_gbuf_build(&sc, 1, &g, err, sizeof err) == 0, "%s", err);
    size_t npix = (size_t)sc.width * sc.height;
    uint8_t *rgb[2] = { malloc(npix * 3), malloc(npix * 3) };
    NP_CHECK(rgb[0] && rgb[1], "out of memory");
    for (unsigned fr = 0; fr < 2; fr++) {
        np_noisetex_stats st;
        NP_CHECK(np_noisetex_frame(&t, &g, fr, 1, rgb[fr], NULL, NULL, &st, err, sizeof err) == 0, "%s", err);
        printf("classic4 frame %u: w 0x%04x, max %.3f LSB (lit %.3f), %llu transactions, %llu clocks\n", fr, st.w,
               st.max_lsb, st.max_lit_lsb, (unsigned long long)st.transactions, (unsigned long long)st.cycles);
        NP_CHECK(st.max_lsb <= 1.0 && st.over_one == 0, "frame %u: %.3f LSB", fr, st.max_lsb);
        NP_CHECK(st.cycle_mismatch == 0 && st.cycles == st.transactions + 11u, "frame %u: %llu mismatches, %llu clocks",
                 fr, (unsigned long long)st.cycle_mismatch, (unsigned long long)st.cycles);
    }
    NP_CHECK(memcmp(rgb[0], rgb[1], npix * 3) != 0, "classic4: frames 0 and 1 are the same");
    free(rgb[0]), free(rgb[1]);
    np_gbuf_free(&g);
    np_scene_free(&sc);
    return 0;
}

static const np_test_case cases[] = {
    { "scene_continuity", scene_continuity },
    { "scene_keys", scene_keys },
    { "scene_classic4", scene_classic4 },
    { NULL, NULL },
};

NP_TEST_MAIN(cases)
