/* SPDX-License-Identifier: MIT */
/*
 * Scenes, the reference renderer, the units' renders of the seed scenes,
 * golden-image hashes and the image files (OpenEXR, PNG, SHA-256).
 */
#include <math.h>
#include <openexr.h>
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "np_golden.h"
#include "np_image.h"
#include "np_fdiff.h"
#include "np_render.h"
#include "np_report_scan.h"
#include "np_vec_stream.h"
#include "np_test.h"
#include "np_texel.h"
#include "np_texreg.h"
#include "unit_span.h"
#include "np_vec.h"

#ifndef NP_SOURCE_DIR
#define NP_SOURCE_DIR "."
#endif

/* --- Image files --- */

static int sha256_kat(void)
{
    static const struct { const char *msg, *hex; } k[] = {
        { "", "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855" },
        { "abc", "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad" },
        { "abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq",
          "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1" },
    };
    for (unsigned i = 0; i < 3; i++) {
        np_sha256 s;
        uint8_t d[32];
        char hex[65];
        np_sha256_init(&s);
        /* Feed byte by byte too, to cross block boundaries in every way. */
        for (const char *p = k[i].msg; *p; p++)
            np_sha256_update(&s, p, 1);
        np_sha256_final(&s, d);
        for (int b = 0; b < 32; b++)
            snprintf(hex + 2 * b, 3, "%02x", d[b]);
        NP_CHECK(strcmp(hex, k[i].hex) == 0, "sha256(\"%s\") = %s", k[i].msg, hex);
    }
    /* One million 'a' (FIPS 180-2 appendix). */
    np_sha256 s;
    uint8_t d[32], a[1000];
    char hex[65];
    memset(a, 'a', sizeof a);
    np_sha256_init(&s);
    for (int i = 0; i < 1000; i++)
        np_sha256_update(&s, a, sizeof a);
    np_sha256_final(&s, d);
    for (int b = 0; b < 32; b++)
        snprintf(hex + 2 * b, 3, "%02x", d[b]);
    NP_CHECK(strcmp(hex, "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0") == 0, "million a: %s", hex);
    printf("SHA-256 known answers pass\n");
    return 0;
}

static int exr_roundtrip(void)
{
    /* Channels given out of alphabetical order, a partial last chunk, special values: FLOAT is bit-exact. */
    const unsigned w = 19, h = 37;
    const char *const names[3] = { "Z", "A", "M" };
    float *pl = malloc(3 * w * h * sizeof *pl);
    for (unsigned c = 0; c < 3; c++)
        for (unsigned i = 0; i < w * h; i++)
            pl[c * w * h + i] = (float)(c + 1) * 1000.0f + (float)i * 0.125f - 3.0f;
    pl[0] = -0.0f;
    pl[1] = 1e-40f; /* denormal */
    pl[2] = 3.4e38f;
    char path[256], err[512];
    snprintf(path, sizeof path, "test_render_roundtrip.exr");
    NP_CHECK(np_image_write_exr(path, w, h, 3, names, pl, err, sizeof err) == 0, "write: %s", err);
    unsigned rw, rh, rn;
    char rnames[NP_IMAGE_MAX_CHANNELS][NP_IMAGE_NAME];
    float *rp = NULL;
    NP_CHECK(np_image_read_exr(path, &rw, &rh, &rn, rnames, &rp, err, sizeof err) == 0, "read: %s", err);
    if (rp) {
        NP_CHECK(rw == w && rh == h && rn == 3, "shape %ux%u x%u", rw, rh, rn);
        /* The file lists the channels sorted (A, M, Z): map by name. */
        NP_CHECK(strcmp(rnames[0], "A") == 0 && strcmp(rnames[1], "M") == 0 && strcmp(rnames[2], "Z") == 0,
                 "names %s %s %s", rnames[0], rnames[1], rnames[2]);
        unsigned bad = 0;
        for (unsigned c = 0; c < 3; c++) {
            unsigned k = 0;
            while (strcmp(names[k], rnames[c]) != 0)
                k++;
            bad += memcmp(rp + (size_t)c * w * h, pl + (size_t)k * w * h, w * h * sizeof(float)) != 0;
        }
        NP_CHECK(bad == 0, "%u channels differ", bad);
        printf("EXR %ux%u, 3 FLOAT channels written out of order and read back by name: bit-exact\n", w, h);
    }
    free(rp);
    free(pl);
    remove(path);
    NP_CHECK(np_image_read_exr("no-such-file.exr", &rw, &rh, &rn, rnames, &rp, err, sizeof err) != 0, "missing file read");
    return 0;
}

static int png_roundtrip(void)
{
    const unsigned w = 33, h = 17;
    uint8_t *rgb = malloc(w * h * 3);
    for (unsigned i = 0; i < w * h * 3; i++)
        rgb[i] = (uint8_t)(i * 37u + 11u);
    char err[512];
    const char *path = "test_render_roundtrip.png";
    NP_CHECK(np_image_write_png(path, w, h, rgb, err, sizeof err) == 0, "write: %s", err);
    png_image im;
    memset(&im, 0, sizeof im);
    im.version = PNG_IMAGE_VERSION;
    NP_CHECK(png_image_begin_read_from_file(&im, path) != 0, "libpng cannot read it back");
    im.format = PNG_FORMAT_RGB;
    uint8_t *back = malloc(PNG_IMAGE_SIZE(im));
    NP_CHECK(im.width == w && im.height == h, "size %ux%u", im.width, im.height);
    NP_CHECK(png_image_finish_read(&im, NULL, back, 0, NULL) != 0, "decode");
    NP_CHECK(memcmp(back, rgb, w * h * 3) == 0, "pixels differ");
    printf("PNG %ux%u RGB written and read back by libpng: identical\n", w, h);
    free(back);
    free(rgb);
    remove(path);
    return 0;
}

/* --- Scenes --- */

static const char good[] =
    "{ \"noisepipe_scene\": 1, \"name\": \"t\",\n"
    "  \"image\": { \"width\": 64, \"height\": 48 },\n"
    "  \"camera\": { \"projection\": \"orthographic\", \"eye\": [0, 0, 5], \"target\": [0, 0, 0],\n"
    "              \"up\": [0, 1, 0], \"height\": 2 },\n"
    "  \"geometry\": [ { \"type\": \"polygon\", \"vertices\": [[-1,-1,0],[1,-1,0],[1,1,0],[-1,1,0]],\n"
    "                  \"texcoords\": [[0,0,0],[4,0,0],[4,4,0],[0,4,0]] } ],\n"
    "  \"texture\": { \"octaves\": [ { \"amplitude\": 1 } ],\n"
    "               \"colormap\": { \"mode\": \"clamp\", \"domain\": [0, 1], \"colors\": [[0,0,0],[255,255,255]] } } }\n";

/* Replace the first occurrence of from by to in good. */
static void variant(char *buf, size_t n, const char *from, const char *to)
{
    const char *p = strstr(good, from);
    if (!p) {
        snprintf(buf, n, "%s", good);
        return;
    }
    snprintf(buf, n, "%.*s%s%s", (int)(p - good), good, to, p + strlen(from));
}

static int scene_errors(void)
{
    static const struct { const char *from, *to, *want; } k[] = {
        { "\"name\": \"t\",", "\"name\": \"t\"", "bad.json:2:" },                       /* missing comma */
        { "\"width\": 64, ", "", "field 'image.width': missing (expected an integer in 1..4096)" },
        { "\"eye\": [0, 0, 5]", "\"eye\": [0, 5]", "field 'camera.eye': expected an array of 3 numbers" },
        { "\"colormap\"", "\"colourmap\"", "field 'texture.colourmap': unknown field (expected one of: quadric, octaves, colormap, noise)" },
        { "[[0,0,0],[255,255,255]]", "[[0,0,0],[300,0,0]]", "field 'texture.colormap.colors[1][0]': expected an integer in 0..255" },
        { "\"clamp\"", "\"repeat\"", "ok" },
        { "[[0,0,0],[255,255,255]]", "[[0,0,0],[1,1,1],[2,2,2]]", "ok" },
        { "\"amplitude\": 1", "\"amplitude\": 1, \"scale\": [1,1,1], \"matrix\": [[1,0,0],[0,1,0],[0,0,1]]",
          "field 'texture.octaves[0].matrix': give either \"scale\" or \"matrix\", not both" },
        { "\"noisepipe_scene\": 1", "\"noisepipe_scene\": 2", "field 'noisepipe_scene': expected an integer in 1..1" },
        { "[[0,0,0],[4,0,0],[4,4,0],[0,4,0]]", "[[0,0,0],[4,0,0]]", "field 'geometry[0].texcoords': expected an array of [s, t, r], one per vertex (4)" },
        { "\"height\": 48", "\"height\": 48, \"height\": 49", "field 'image.height': appears twice" },
        { "\"orthographic\"", "\"fisheye\"", "field 'camera.projection': \"fisheye\" is not one of \"orthographic\" or \"perspective\"" },
        { "\"up\": [0, 1, 0]", "\"up\": [0, 0, 1]", "field 'camera.up': must not be parallel to the viewing direction" },
        { "\"domain\": [0, 1]", "\"domain\": [1, 1]", "field 'texture.colormap.domain': expected [f0, f1] with f0 < f1" },
    };
    char buf[4096], err[1024];
    np_scene s;
    NP_CHECK(np_scene_parse(good, "good.json", &s, err, sizeof err) == 0, "the good scene fails: %s", err);
    np_scene_free(&s);
    for (unsigned i = 0; i < sizeof k / sizeof k[0]; i++) {
        variant(buf, sizeof buf, k[i].from, k[i].to);
        int rc = np_scene_parse(buf, "bad.json", &s, err, sizeof err);
        if (strcmp(k[i].want, "ok") == 0) {
            NP_CHECK(rc == 0, "case %u should load: %s", i, err);
            if (rc == 0)
                np_scene_free(&s);
            continue;
        }
        NP_CHECK(rc != 0, "case %u accepted", i);
        NP_CHECK(strstr(err, k[i].want) != NULL && strncmp(err, "bad.json", 8) == 0, "case %u: '%s', want '%s'", i, err,
                 k[i].want);
        printf("  %s\n", err);
    }
    /* A repeat map of 3 entries: the file, the field, why. */
    variant(buf, sizeof buf, "[[0,0,0],[255,255,255]]", "[[0,0,0],[1,1,1],[2,2,2]]");
    char two[4096];
    snprintf(two, sizeof two, "%s", buf);
    const char *p = strstr(two, "\"clamp\"");
    snprintf(buf, sizeof buf, "%.*s\"repeat\"%s", (int)(p - two), two, p + 7);
    NP_CHECK(np_scene_parse(buf, "bad.json", &s, err, sizeof err) != 0 &&
                 strstr(err, "field 'texture.colormap.colors': 3 entries: a repeating map needs a power of two"),
             "repeat of 3: %s", err);
    printf("  %s\n", err);
    NP_CHECK(np_scene_load("/nonexistent/scene.json", &s, err, sizeof err) != 0 &&
                 strstr(err, "/nonexistent/scene.json: cannot open"),
             "missing file: %s", err);
    printf("  %s\n", err);
    return 0;
}

static int scene_seed(void)
{
    char path[1024], err[1024];
    np_scene s;
    np_golden_scene_path(NP_SOURCE_DIR, "wood", path, sizeof path);
    NP_CHECK(np_scene_load(path, &s, err, sizeof err) == 0, "%s", err);
    NP_CHECK(s.width == 256 && s.height == 256 && s.n_poly == 6, "wood image/geometry");
    NP_CHECK(s.tex.quad[0] == 10 && s.tex.quad[7] == 10 && s.tex.n_oct == 1 && s.tex.oct[0].m[0][0] == 5 &&
                 s.tex.oct[0].m[1][1] == 5 && s.tex.oct[0].m[2][2] == 1 && s.tex.oct[0].amp == 1,
             "wood is not equation 23");
    np_render_frame fr;
    NP_CHECK(np_render_prepare(&s, &fr, err, sizeof err) == 0, "%s", err);
    /* Faces share edges but no pixel: the mask counts each pixel once. */
    uint64_t covered = 0;
    for (unsigned i = 0; i < s.width * s.height; i++)
        covered += fr.mask[i];
    printf("wood: %zu spans, %llu pixels (covered %llu), longest span %u\n", fr.n_spans, (unsigned long long)fr.pixels,
           (unsigned long long)covered, fr.longest);
    NP_CHECK(covered == fr.pixels, "overlapping spans: %llu covered, %llu in spans", (unsigned long long)covered,
             (unsigned long long)fr.pixels);
    /* The bottom vertex (texture origin) and the top vertex ((1,1,1)) are the lowest and highest covered rows. */
    unsigned top = 0, bot = 0;
    double stop = 0, sbot = 0;
    for (size_t i = 0; i < fr.n_spans; i++) {
        const np_rspan *sp = &fr.spans[i];
        if (i == 0 || sp->hw.y < top) {
            top = sp->hw.y;
            stop = sp->s0[0] + sp->s0[1] + sp->s0[2];
        }
        if (i == 0 || sp->hw.y > bot) {
            bot = sp->hw.y;
            sbot = sp->s0[0] + sp->s0[1] + sp->s0[2];
        }
    }
    printf("top row %u: s + t + r = %.3f (vertex (1,1,1): 3); bottom row %u: %.3f (origin: 0)\n", top, stop, bot, sbot);
    NP_CHECK(stop > 2.9 && sbot < 0.1, "texture origin / top vertex misplaced");
    np_render_frame_free(&fr);
    np_scene_free(&s);
    np_golden_scene_path(NP_SOURCE_DIR, "marble", path, sizeof path);
    NP_CHECK(np_scene_load(path, &s, err, sizeof err) == 0, "%s", err);
    NP_CHECK(s.tex.n_oct == 4 && s.tex.quad[8] == 0.5 && s.tex.oct[3].m[0][0] == 8, "marble is not equation 24");
    NP_CHECK(np_render_prepare(&s, &fr, err, sizeof err) == 0, "%s", err);
    /* The seed: 16^2 cells of the finest octave per face, 768 in all. Count the distinct cells the frame touches. */
    static unsigned char seen[17][17][17];
    memset(seen, 0, sizeof seen);
    unsigned cells = 0;
    for (size_t i = 0; i < fr.n_spans; i++) {
        const np_rspan *sp = &fr.spans[i];
        for (uint32_t k = 0; k < sp->hw.n; k++) {
            int c[3];
            for (int a = 0; a < 3; a++)
                c[a] = (int)floor(8.0 * (sp->s0[a] + (double)k * sp->ds[a]));
            if (c[0] >= 0 && c[0] <= 16 && c[1] >= 0 && c[1] <= 16 && c[2] >= 0 && c[2] <= 16 && !seen[c[0]][c[1]][c[2]]) {
                seen[c[0]][c[1]][c[2]] = 1;
                cells++;
            }
        }
    }
    printf("marble: finest octave (scale 8) touches %u lattice cells (the seed: 16^2 per face, 768 for three faces; "
           "a face at s = 2 lies in cell 16)\n",
           cells);
    NP_CHECK(cells > 600 && cells <= 768, "cells %u", cells);
    np_render_frame_free(&fr);
    np_scene_free(&s);
    return 0;
}

/* Render a seed scene with the default configurations. */
static int render_default(const char *name, np_scene *s, np_render_frame *fr, np_render_run *fd, np_render_run *tx)
{
    char path[1024], err[1024];
    np_golden_scene_path(NP_SOURCE_DIR, name, path, sizeof path);
    if (np_scene_load(path, s, err, sizeof err) || np_render_prepare(s, fr, err, sizeof err)) {
        NP_CHECK(0, "%s", err);
        return -1;
    }
    np_fdiff_cfg fc = np_fdiff_cfg_default();
    np_texel_cfg tc = np_texel_cfg_default();
    if (np_render_reference(fr) || np_render_engine(fr, &np_fdiff_engine, &fc, 1, fd) || np_render_engine(fr, &np_texel_engine, &tc, 1, tx)) {
        NP_CHECK(0, "out of memory");
        return -1;
    }
    return 0;
}

static int seed_scenes_1lsb(void)
{
    const char *names[2] = { "wood", "marble" };
    for (int i = 0; i < 2; i++) {
        np_scene s;
        np_render_frame fr;
        np_render_run fd, tx;
        if (render_default(names[i], &s, &fr, &fd, &tx))
            return 1;
        printf("%s: fdiff max %.3f LSB RMS %.4f PSNR %.2f dB, %llu cycles (%llu cell set-ups, %llu stall cycles); "
               "texel max %.3f LSB RMS %.4f, %llu cycles\n",
               names[i], fd.err.max_lsb, fd.err.rms_lsb, fd.err.psnr_db, (unsigned long long)fd.cycles,
               (unsigned long long)fd.cell_setups, (unsigned long long)fd.setup_stalls, tx.err.max_lsb, tx.err.rms_lsb,
               (unsigned long long)tx.cycles);
        NP_CHECK(fd.err.max_lsb <= 1.0, "%s: fdiff %.3f LSB", names[i], fd.err.max_lsb);
        NP_CHECK(tx.err.max_lsb <= 1.0, "%s: texel %.3f LSB", names[i], tx.err.max_lsb);
        NP_CHECK(fd.cycle_mismatch == 0 && tx.cycle_mismatch == 0, "%s: cycle model differs", names[i]);
        /* fdiff reads each later descriptor while the span before it steps: one accepting clock in all. */
        NP_CHECK(fd.cycles == 1u + fr.pixels + fd.setup_stalls + NP_FDIFF_TAIL_STAGES, "%s: cycle count", names[i]);
        np_render_run_free(&fd);
        np_render_run_free(&tx);
        np_render_frame_free(&fr);
        np_scene_free(&s);
    }
    return 0;
}

/*
 * Registers sized by the scene (issue 10; np_scene.size_registers, render
 * --sized): every unit that renders the scene, with the widths its
 * cfg_scene chose, stays within its predicted bound (the unit's own over
 * the scene's widest span plus the registers' rounding), which is <= 1 LSB,
 * measured against the float reference on every covered pixel. The seed
 * scenes get narrower registers than the defaults (and the pixels that
 * change against the default images are counted); the issue's four scenes,
 * refused at the default widths (render.render_refuses_reg_*), render with
 * wider ones.
 */
static int sized_registers(void)
{
    static const struct {
        const char *dir, *name;
        int wider; /* 1: needs wider registers than the defaults; 0: the seed scenes, narrower */
    } scenes[] = {
        { "vectors/scenes", "wood", 0 },        { "vectors/scenes", "marble", 0 },
        { "testbench/scenes", "reg_scale01_near1000", 1 }, { "testbench/scenes", "reg_scale1e6", 1 },
        { "testbench/scenes", "reg_quadric_a1e6", 1 },     { "testbench/scenes", "reg_clamp_j1023", 1 },
    };
    for (size_t i = 0; i < sizeof scenes / sizeof scenes[0]; i++) {
        char path[1024], err[1024];
        snprintf(path, sizeof path, "%s/%s/%s.json", NP_SOURCE_DIR, scenes[i].dir, scenes[i].name);
        np_scene s;
        np_render_frame fr;
        np_render_unit_cfg us[NP_RENDER_MAX_UNITS];
        if (np_scene_load(path, &s, err, sizeof err) || np_render_prepare(&s, &fr, err, sizeof err)) {
            NP_CHECK(0, "%s", err);
            return 1;
        }
        /* At the default widths: the seed scenes render (golden), the others are refused. */
        int nd = np_render_units(&s, NULL, NULL, us, err, sizeof err);
        NP_CHECK(scenes[i].wider ? nd < 0 : nd == 2, "%s: at the default widths %d units (%s)", scenes[i].name, nd,
                 nd < 0 ? err : "");
        np_render_run def[NP_RENDER_MAX_UNITS];
        memset(def, 0, sizeof def);
        NP_CHECK(np_render_reference(&fr) == 0, "out of memory");
        for (int k = 0; k < nd; k++)
            NP_CHECK(np_render_unit(&fr, us[k].u, &us[k].cfg, 0, &def[k]) == 0, "out of memory");
        s.size_registers = 1;
        int n = np_render_units(&s, NULL, NULL, us, err, sizeof err);
        NP_CHECK(n == 2, "%s: sized: %d units (%s)", scenes[i].name, n, n < 0 ? err : "");
        for (int k = 0; k < n; k++) {
            np_render_run run;
            NP_CHECK(np_render_unit(&fr, us[k].u, &us[k].cfg, 1, &run) == 0, "out of memory");
            const np_tex_regs *r = np_ut_regs(np_su_texture(us[k].u->span, &us[k].cfg));
            const double pred = np_su_predicted_lsb(us[k].u, &us[k].cfg, s.width);
            unsigned long long diff = 0;
            if (k < nd)
                for (size_t p = 0; p < (size_t)s.width * s.height * 3u; p++)
                    diff += run.rgb[p] != def[k].rgb[p];
            char note[96];
            if (k < nd)
                snprintf(note, sizeof note, "%llu channel values differ from the default widths' image", diff);
            else
                snprintf(note, sizeof note, "refused at the default widths");
            printf("%-22s %-5s %s; quadric s%u Q.%u, transform s%u Q.%u: predicted %.3f LSB, measured %.3f; "
                   "cycle model %s; %s\n",
                   scenes[i].name, us[k].u->name, us[k].text, np_tex_k_bits(r), np_tex_k_frac(r), np_tex_m_bits(r),
                   np_tex_m_frac(r), pred, run.err.max_lsb, run.cycle_mismatch ? "DIFFERS" : "agrees", note);
            NP_CHECK(pred <= 1.0, "%s %s: predicted %.3f > 1", scenes[i].name, us[k].u->name, pred);
            /* The fewest guard bits: one fewer takes the predicted bound over 1 LSB. */
            for (const np_unit_key *key = us[k].u->keys; key && key->name; key++) {
                unsigned g;
                if (strcmp(key->name, "guard") != 0)
                    continue;
                memcpy(&g, us[k].cfg.bytes + key->offset, sizeof g);
                if (g == 0)
                    break;
                np_unit_cfg c2 = us[k].cfg;
                char v[16];
                snprintf(v, sizeof v, "%u", g - 1u);
                NP_CHECK(np_unit_cfg_set(us[k].u, &c2, "guard", v, err, sizeof err) == 0, "%s", err);
                const double p1 = np_su_predicted_lsb(us[k].u, &c2, s.width);
                printf("%-22s %-5s guard=%u: predicted %.3f LSB > 1\n", scenes[i].name, us[k].u->name, g - 1u, p1);
                NP_CHECK(p1 > 1.0, "%s %s: guard=%u is not the fewest (guard=%u predicts %.3f)", scenes[i].name,
                         us[k].u->name, g, g - 1u, p1);
            }
            NP_CHECK(run.err.max_lsb <= pred, "%s %s: measured %.4f above the predicted %.4f", scenes[i].name,
                     us[k].u->name, run.err.max_lsb, pred);
            NP_CHECK(!run.cycle_mismatch, "%s %s: the cycle model differs", scenes[i].name, us[k].u->name);
            if (scenes[i].wider)
                NP_CHECK(np_tex_m_frac(r) > NP_TEX_M_FRAC || np_tex_k_frac(r) > NP_TEX_K_FRAC ||
                             strstr(us[k].text, "idx_int=11") != NULL,
                         "%s: no register wider than the default", scenes[i].name);
            else
                NP_CHECK(np_tex_k_bits(r) < NP_TEX_K_BITS && np_tex_m_bits(r) < NP_TEX_M_BITS &&
                             strstr(us[k].text, "idx_int=10") == NULL,
                         "%s: the seed scene's registers should be narrower than the defaults", scenes[i].name);
            np_render_run_free(&run);
        }
        for (int k = 0; k < nd; k++)
            np_render_run_free(&def[k]);
        np_render_frame_free(&fr);
        np_scene_free(&s);
    }
    return 0;
}

static int golden_hashes(void)
{
    /* The checked-in hashes of the default renders (vectors/images/hashes.txt) must match: a change fails here. */
    char path[1024];
    snprintf(path, sizeof path, "%s/vectors/images/hashes.txt", NP_SOURCE_DIR);
    FILE *f = fopen(path, "r");
    NP_CHECK(f != NULL, "cannot open %s", path);
    if (!f)
        return 1;
    char line[1024], want[3][2][65];
    memset(want, 0, sizeof want);
    unsigned n = 0;
    const char *names[2] = { "wood", "marble" }, *images[3] = { "ref", "fdiff", "texel" };
    while (fgets(line, sizeof line, f)) {
        char sc[64], im[16], h[65], cfg[256];
        if (line[0] == '#' || sscanf(line, "%63s %15s %64s %255s", sc, im, h, cfg) != 4)
            continue;
        for (int i = 0; i < 2; i++)
            for (int k = 0; k < 3; k++)
                if (strcmp(sc, names[i]) == 0 && strcmp(im, images[k]) == 0) {
                    snprintf(want[k][i], 65, "%s", h);
                    n++;
                }
    }
    fclose(f);
    NP_CHECK(n == 6, "%u of 6 golden hashes in %s", n, path);
    for (int i = 0; i < 2; i++) {
        np_scene s;
        np_render_frame fr;
        np_render_run fd, tx;
        if (render_default(names[i], &s, &fr, &fd, &tx))
            return 1;
        uint8_t *ref8 = malloc((size_t)s.width * s.height * 3);
        np_render_ref_rgb8(&fr, ref8);
        const uint8_t *img[3] = { ref8, fd.rgb, tx.rgb };
        for (int k = 0; k < 3; k++) {
            char hex[65];
            np_image_hash(s.width, s.height, img[k], hex);
            printf("%s %s %s %s\n", names[i], images[k], hex, strcmp(hex, want[k][i]) == 0 ? "matches" : "CHANGED");
            NP_CHECK(strcmp(hex, want[k][i]) == 0, "%s %s: %s, golden %s", names[i], images[k], hex, want[k][i]);
        }
        free(ref8);
        np_render_run_free(&fd);
        np_render_run_free(&tx);
        np_render_frame_free(&fr);
        np_scene_free(&s);
    }
    return 0;
}

static int scanline(void)
{
    /* Figures 10 and 11: along the probe row, FD - per pixel is 0 at every set-up and grows inside a cell. */
    np_scene s;
    np_render_frame fr;
    char path[1024], err[1024];
    np_golden_scene_path(NP_SOURCE_DIR, "wood", path, sizeof path);
    if (np_scene_load(path, &s, err, sizeof err) || np_render_prepare(&s, &fr, err, sizeof err)) {
        NP_CHECK(0, "%s", err);
        return 1;
    }
    for (unsigned guard = 0; guard <= 44; guard += 44) {
        np_fdiff_cfg c = np_fdiff_cfg_default();
        c.guard = guard;
        np_render_scan sc;
        NP_CHECK(np_render_scanline(&fr, &c, s.probe_row, &sc) == 0, "scanline");
        double worst = 0;
        unsigned nonzero_at_edge = 0;
        for (size_t i = 0, e = 0; i < sc.n; i++) {
            worst = fmax(worst, fabs(sc.last[i]));
            while (e < sc.n_edge_last && sc.edge_last[e] < sc.x[i])
                e++;
            if (e < sc.n_edge_last && sc.edge_last[e] == sc.x[i] && sc.last[i] != 0.0)
                nonzero_at_edge++;
        }
        printf("wood row %u, guard %u: %zu pixels, %zu set-ups; max |FD - per pixel| %.3g (noise units); "
               "non-zero at a set-up pixel: %u\n",
               s.probe_row, guard, sc.n, sc.n_edge_last, worst, nonzero_at_edge);
        NP_CHECK(nonzero_at_edge == 0, "the difference must vanish where the unit sets up");
        if (guard == 0)
            NP_CHECK(worst > 0, "no drift visible at guard 0");
        else
            NP_CHECK(worst < 1e-9, "drift %.3g at the default guard", worst);
        np_render_scan_free(&sc);
    }
    np_render_frame_free(&fr);
    np_scene_free(&s);
    return 0;
}

static int perspective_polygon(void)
{
    /* A perspective camera over a textured floor polygon, with an octave rotated by a full matrix. */
    static const char json[] =
        "{ \"noisepipe_scene\": 1, \"name\": \"floor\",\n"
        "  \"image\": { \"width\": 160, \"height\": 120, \"background\": [10, 20, 30] },\n"
        "  \"camera\": { \"projection\": \"perspective\", \"eye\": [0, -6, 2.5], \"target\": [0, 0, 0],\n"
        "              \"up\": [0, 0, 1], \"focal\": 1.5 },\n"
        "  \"geometry\": [ { \"type\": \"polygon\", \"vertices\": [[-4,-4,0],[4,-4,0],[4,4,0],[-4,4,0]],\n"
        "                  \"texcoords\": [[0,0,0],[8,0,0],[8,8,0],[0,8,0]] } ],\n"
        "  \"texture\": { \"quadric\": { \"A\": 0.05, \"E\": 0.05 },\n"
        "               \"octaves\": [ { \"amplitude\": 1, \"matrix\": [[0.8,-0.6,0],[0.6,0.8,0],[0,0,1]],\n"
        "                                \"offset\": [0.5, 0.25, 0] },\n"
        "                              { \"amplitude\": 0.5, \"scale\": [2, 2, 2] } ],\n"
        "               \"colormap\": { \"mode\": \"repeat\", \"domain\": [0, 1.5],\n"
        "                             \"colors\": [[250,240,200],[200,120,60],[90,40,20],[200,120,60]] } } }\n";
    np_scene s;
    np_render_frame fr;
    np_render_run fd, tx;
    char err[1024];
    NP_CHECK(np_scene_parse(json, "floor.json", &s, err, sizeof err) == 0, "%s", err);
    NP_CHECK(np_render_prepare(&s, &fr, err, sizeof err) == 0, "%s", err);
    np_fdiff_cfg fc = np_fdiff_cfg_default();
    np_texel_cfg tc = np_texel_cfg_default();
    NP_CHECK(np_render_reference(&fr) == 0 && np_render_engine(&fr, &np_fdiff_engine, &fc, 1, &fd) == 0 &&
                 np_render_engine(&fr, &np_texel_engine, &tc, 1, &tx) == 0,
             "render");
    printf("perspective floor: %llu pixels in %zu spans; fdiff max %.3f LSB, texel max %.3f LSB; cycles %llu / %llu\n",
           (unsigned long long)fr.pixels, fr.n_spans, fd.err.max_lsb, tx.err.max_lsb, (unsigned long long)fd.cycles,
           (unsigned long long)tx.cycles);
    NP_CHECK(fr.pixels > 5000, "floor too small: %llu pixels", (unsigned long long)fr.pixels);
    NP_CHECK(fd.err.max_lsb <= 1.0 && tx.err.max_lsb <= 1.0, "errors %.3f %.3f", fd.err.max_lsb, tx.err.max_lsb);
    NP_CHECK(fd.cycle_mismatch == 0 && tx.cycle_mismatch == 0, "cycle model differs");
    np_render_run_free(&fd);
    np_render_run_free(&tx);
    np_render_frame_free(&fr);
    np_scene_free(&s);
    return 0;
}


/* --- Built-in textures and the stream units' golden vectors --- */

static int builtin_textures(void)
{
    /* The registry's built-in wood and marble are the scenes' textures, field by field. */
    const char *names[2] = { "wood", "marble" };
    for (int i = 0; i < 2; i++) {
        char path[1024], err[1024];
        np_scene s;
        np_golden_scene_path(NP_SOURCE_DIR, names[i], path, sizeof path);
        NP_CHECK(np_scene_load(path, &s, err, sizeof err) == 0, "%s", err);
        const np_ref_texture *b = np_texreg_builtin(names[i]);
        NP_CHECK(b && memcmp(b, &s.tex, sizeof *b) == 0, "built-in %s differs from %s", names[i], path);
        np_tex_regs r;
        NP_CHECK(np_texreg_compile(b, &r, err, sizeof err) == 0, "%s: %s", names[i], err);
        np_scene_free(&s);
    }
    const np_ref_texture *ramp = np_texreg_builtin("ramp");
    np_tex_regs r;
    char err[256];
    NP_CHECK(ramp && np_texreg_compile(ramp, &r, err, sizeof err) == 0 && r.oct[0].amp == 1 << NP_TEX_AMP_FRAC &&
                 r.cmap_n == 2 && !r.cmap_repeat,
             "ramp");
    NP_CHECK(np_texreg_builtin("nope") == NULL, "unknown texture found");
    printf("built-in textures wood and marble equal the scene files; ramp compiles\n");
    return 0;
}

typedef struct vcheck {
    const np_vec_header *h;
    uint64_t n, bits_bad, acc_bad;
    double worst;
} vcheck;

static int vsink(void *ctx, const np_vec_rec *rec, const uint64_t *out, const np_vec_timing *t)
{
    (void)t;
    vcheck *c = ctx;
    c->n++;
    for (unsigned f = 0; f < c->h->fields.n_out; f++) {
        c->bits_bad += out[f] != rec->w[NP_VEC_OUT][f];
        double e = fabs((double)out[f] - np_vec_ref_value(rec->w[NP_VEC_REF][f]));
        c->worst = fmax(c->worst, e);
        c->acc_bad += !(e <= c->h->unit->tolerance_lsb);
    }
    return 0;
}

static int vsource(void *ctx, np_vec_rec *rec) { return np_vec_read(ctx, rec); }

/*
 * Golden vectors of a stream unit: generated by np_stream_generate (in the
 * one vector format), read back by the vector reader, driven through the
 * stream model with random gaps and stalls by np_stream_drive: bits equal,
 * accuracy within the unit's tolerance; and the file equals the checked-in
 * vectors/UNIT/UNIT-l1-seed1.vec byte for byte.
 */
static int stream_vectors_unit(const char *unit)
{
    np_vec_header h;
    char err[NP_VEC_ERRLEN], path[512], golden[1024];
    NP_CHECK(np_vec_header_init(&h, np_unit_find(unit), NULL, err, sizeof err) == 0, "%s", err);
    snprintf(path, sizeof path, "%s-l1-seed1.vec", unit);
    np_vec_output out = { path, NP_VEC_TEXT };
    NP_CHECK(np_stream_generate(&h, 1, 1, UINT64_MAX, &out, 1, err, sizeof err) == 0, "generate: %s", err);
    np_vec_reader rd;
    NP_CHECK(np_vec_open(&rd, path) == 0, "read: %s", rd.L.err);
    vcheck c = { &rd.h, 0, 0, 0, 0 };
    np_vec_drive_stats st;
    int rc = np_stream_drive(&rd.h, vsource, &rd, vsink, &c, 1, 7, &st, err, sizeof err);
    np_vec_close(&rd);
    printf("%s: %llu vectors (%s); stream model with random gaps and stalls: %llu cycles, %llu beats checked, "
           "%llu bit mismatches, worst |error| %.4f LSB, %llu beyond tolerance\n",
           unit, (unsigned long long)h.count, h.sources, (unsigned long long)st.cycles, (unsigned long long)c.n,
           (unsigned long long)c.bits_bad, c.worst, (unsigned long long)c.acc_bad);
    NP_CHECK(rc == NP_DRIVE_DONE, "drive: %d %s", rc, err);
    NP_CHECK(c.n == h.count && c.bits_bad == 0 && c.acc_bad == 0, "%s: vectors fail", unit);
    snprintf(golden, sizeof golden, "%s/vectors/%s/%s-l1-seed1.vec", NP_SOURCE_DIR, unit, unit);
    FILE *a = fopen(path, "rb"), *b = fopen(golden, "rb");
    NP_CHECK(b != NULL, "no checked-in %s (copy %s there)", golden, path);
    int same = a && b;
    while (same) {
        int x = fgetc(a), y = fgetc(b);
        same = x == y;
        if (x == EOF || y == EOF)
            break;
    }
    NP_CHECK(same, "%s differs from the checked-in %s: the model's bits changed", path, golden);
    if (a)
        fclose(a);
    if (b)
        fclose(b);
    return 0;
}

static int stream_vectors(void)
{
    stream_vectors_unit("fdiff");
    stream_vectors_unit("texel");
    return 0;
}

/* --- Images a person can read (issue 11, item 8) --- */

/* Read an RGB PNG back through libpng with its text chunks: pixels (malloc'd) and the value of key (or ""). */
static uint8_t *png_read_back(const char *path, unsigned *w, unsigned *h, const char *key, char *val, size_t n)
{
    FILE *f = fopen(path, "rb");
    val[0] = '\0';
    if (!f)
        return NULL;
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    png_infop info = png_create_info_struct(png);
    uint8_t *px = NULL;
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_read_struct(&png, &info, NULL);
        fclose(f);
        free(px);
        return NULL;
    }
    png_init_io(png, f);
    png_read_info(png, info);
    *w = png_get_image_width(png, info);
    *h = png_get_image_height(png, info);
    NP_CHECK(png_get_color_type(png, info) == PNG_COLOR_TYPE_RGB && png_get_bit_depth(png, info) == 8, "%s: not RGB8",
             path);
    px = malloc((size_t)*w * *h * 3);
    for (unsigned y = 0; y < *h; y++)
        png_read_row(png, px + (size_t)y * *w * 3, NULL);
    png_read_end(png, info);
    png_textp text;
    int nt = 0;
    png_get_text(png, info, &text, &nt);
    for (int i = 0; i < nt; i++)
        if (strcmp(text[i].key, key) == 0)
            snprintf(val, n, "%s", text[i].text);
    png_destroy_read_struct(&png, &info, NULL);
    fclose(f);
    return px;
}

/* A seed scene rendered by both units at their defaults (render_default), and its release. */
typedef struct seed_render {
    np_scene s;
    np_render_frame fr;
    np_render_run fd, tx;
} seed_render;

static void seed_close(seed_render *r)
{
    np_render_run_free(&r->fd);
    np_render_run_free(&r->tx);
    np_render_frame_free(&r->fr);
    np_scene_free(&r->s);
}

/* Runs a case on the seed scene `name` (render_default), then releases it: 1 when it cannot be rendered. */
static int with_seed(const char *name, int (*body)(const np_scene *, const np_render_frame *, const np_render_run *,
                                                   const np_render_run *))
{
    seed_render R;
    if (render_default(name, &R.s, &R.fr, &R.fd, &R.tx))
        return 1;
    int rc = body(&R.s, &R.fr, &R.fd, &R.tx);
    seed_close(&R);
    return rc;
}

/* Every error PNG carries the colour bar: the heat map's end colours at its documented ends, and the scale as text. */
static int error_colour_bar_seed(const np_scene *s, const np_render_frame *fr, const np_render_run *fd, const np_render_run *tx)
{
    (void)tx;
    char err[512], val[512];
    np_render_legend lg;
    np_render_legend_layout(s->width, &lg);
    NP_CHECK(lg.height > 0 && (lg.x1 - lg.x0) % 4 == 0 && lg.x0 < lg.x1 && lg.x1 < s->width && lg.y0 < lg.y1 && lg.y1 <= lg.height,
             "legend layout %u rows, x %u..%u, y %u..%u", lg.height, lg.x0, lg.x1, lg.y0, lg.y1);
    for (int rounded = 0; rounded < 2; rounded++) {
        const char *base = rounded ? "test_render_bar_cr" : "test_render_bar";
        char path[256];
        NP_CHECK(np_render_write_error(base, fr, "fdiff", fd->rgb, rounded, err, sizeof err) == 0, "%s", err);
        snprintf(path, sizeof path, "%s.png", base);
        unsigned w = 0, h = 0;
        uint8_t *px = png_read_back(path, &w, &h, "noisepipe:scale", val, sizeof val);
        NP_CHECK(px && w == s->width && h == s->height + lg.height, "%s: %ux%u, want %ux%u", path, w, h, s->width,
                 s->height + lg.height);
        if (!px)
            continue;
        unsigned top = s->height;
        for (unsigned y = lg.y0; y < lg.y1; y++) {
            const uint8_t *lo = px + ((size_t)(top + y) * w + lg.x0) * 3, *hi = px + ((size_t)(top + y) * w + lg.x1) * 3;
            const uint8_t *mid = px + ((size_t)(top + y) * w + (lg.x0 + lg.x1) / 2) * 3;
            NP_CHECK(lo[0] == 0 && lo[1] == 0 && lo[2] == 0, "row %u: 0 LSB end is %u,%u,%u, want black", y, lo[0], lo[1],
                     lo[2]);
            NP_CHECK(hi[0] == 255 && hi[1] == 0 && hi[2] == 0, "row %u: 2 LSB end is %u,%u,%u, want red", y, hi[0],
                     hi[1], hi[2]);
            /* The middle column is 1 LSB (x1 - x0 is a multiple of 4): green. */
            NP_CHECK(mid[0] == 0 && mid[1] == 255 && mid[2] == 0, "1 LSB is %u,%u,%u", mid[0], mid[1], mid[2]);
        }
        /* Tick labels: some ink under the bar. */
        unsigned ink = 0;
        for (unsigned y = lg.y1; y < lg.height; y++)
            for (unsigned x = 0; x < w; x++)
                ink += px[((size_t)(top + y) * w + x) * 3] > 200;
        NP_CHECK(ink > 50, "no tick labels under the bar (%u ink pixels)", ink);
        NP_CHECK(strstr(val, "0 .. 2 LSB") && strstr(val, "heat map"), "noisepipe:scale = '%s'", val);
        printf("%s: %ux%u (colour bar %u rows: black at x=%u, red at x=%u); %u ink pixels of labels; "
               "noisepipe:scale = \"%s\"\n",
               path, w, h, lg.height, lg.x0, lg.x1, ink, val);
        free(px);
        unsigned w2, h2;
        px = png_read_back(path, &w2, &h2, "noisepipe:unit", val, sizeof val);
        NP_CHECK(strcmp(val, "fdiff") == 0, "noisepipe:unit = '%s'", val);
        free(px);
        remove(path);
        snprintf(path, sizeof path, "%s.exr", base);
        remove(path);
    }
    return 0;
}
static int error_colour_bar(void) { return with_seed("wood", error_colour_bar_seed); }

/*
 * The error beyond correct rounding: zero everywhere for an image equal to the
 * correctly rounded reference; for the units, non-zero exactly at the samples
 * the summary counts (np_render_err.over_cr).
 */
static int error_rounded_seed(const np_scene *s, const np_render_frame *fr, const np_render_run *fd, const np_render_run *tx)
{
    size_t n = (size_t)s->width * s->height;
    uint8_t *ref8 = malloc(3 * n);
    np_render_ref_rgb8(fr, ref8);
    const struct { const char *name; const uint8_t *rgb; uint64_t want; } k[3] = {
        { "ref8", ref8, 0 }, { "fdiff", fd->rgb, fd->err.over_cr }, { "texel", tx->rgb, tx->err.over_cr } };
    np_render_err e;
    np_render_error(fr, ref8, &e);
    NP_CHECK(e.over_cr == 0 && e.max_cr == 0 && e.max_lsb <= 0.5, "ref8: %llu differ, max %.3f",
             (unsigned long long)e.over_cr, e.max_lsb);
    for (int i = 0; i < 3; i++) {
        char err[512], rn[NP_IMAGE_MAX_CHANNELS][NP_IMAGE_NAME];
        unsigned w, h, nc;
        float *pl = NULL;
        NP_CHECK(np_render_write_error("test_render_cr", fr, k[i].name, k[i].rgb, 1, err, sizeof err) == 0, "%s", err);
        NP_CHECK(np_image_read_exr("test_render_cr.exr", &w, &h, &nc, rn, &pl, err, sizeof err) == 0, "%s", err);
        if (!pl)
            continue;
        uint64_t nonzero = 0, bad = 0;
        for (size_t c = 0; c < 3; c++)
            for (size_t p = 0; p < n; p++) {
                float v = pl[c * n + p];
                nonzero += v != 0.0f;
                bad += v != floorf(v) || fabsf(v) > 1.0f;
            }
        printf("%s: error beyond correct rounding non-zero at %llu samples (summary: %llu); non-integer or > 1 LSB: "
               "%llu\n",
               k[i].name, (unsigned long long)nonzero, (unsigned long long)k[i].want, (unsigned long long)bad);
        NP_CHECK(nonzero == k[i].want && bad == 0, "%s: %llu non-zero, want %llu; %llu bad", k[i].name,
                 (unsigned long long)nonzero, (unsigned long long)k[i].want, (unsigned long long)bad);
        free(pl);
    }
    NP_CHECK(fd->err.over_cr > 0 && fd->err.over_cr < fd->err.samples / 100, "fdiff: %llu of %llu",
             (unsigned long long)fd->err.over_cr, (unsigned long long)fd->err.samples);
    remove("test_render_cr.exr");
    remove("test_render_cr.png");
    free(ref8);
    return 0;
}
static int error_rounded(void) { return with_seed("wood", error_rounded_seed); }

/* The golden hash of image `image` of scene `scene` in vectors/images/hashes.txt (np_golden_hash). */
static int golden_hash(const char *scene, const char *image, char hex[65])
{
    return np_golden_hash(NP_SOURCE_DIR, "hashes.txt", scene, image, hex) == 0 ? 0 : -1;
}

/*
 * Shading changes the view (NAME_UNIT_lit.png: three faces, three brightnesses)
 * but not the data: the unit's image, its PNG and its golden hash stay as they
 * were; the scene's light section is read and checked.
 */
static int shading_view_seed(const np_scene *s, const np_render_frame *fr, const np_render_run *fd, const np_render_run *tx)
{
    (void)tx;
    size_t n = (size_t)s->width * s->height;
    char err[512], val[256], hex[65], want[65];
    uint8_t *copy = malloc(3 * n);
    memcpy(copy, fd->rgb, 3 * n);
    NP_CHECK(np_render_write_rgb8("test_render_view", fr, "fdiff", fd->rgb, err, sizeof err) == 0, "%s", err);
    NP_CHECK(memcmp(copy, fd->rgb, 3 * n) == 0, "writing the views changed the unit's image");
    np_image_hash(s->width, s->height, fd->rgb, hex);
    NP_CHECK(golden_hash("wood", "fdiff", want) == 0 && strcmp(hex, want) == 0, "hash %s, golden %s", hex, want);
    unsigned w, h;
    uint8_t *png = png_read_back("test_render_view.png", &w, &h, "noisepipe:scene", val, sizeof val);
    NP_CHECK(png && w == s->width && h == s->height && memcmp(png, fd->rgb, 3 * n) == 0, "the PNG is not the unit's image");
    NP_CHECK(strcmp(val, "wood") == 0, "noisepipe:scene = '%s'", val);
    uint8_t *lit = png_read_back("test_render_view_lit.png", &w, &h, "noisepipe:view", val, sizeof val);
    NP_CHECK(lit && w == s->width && h == s->height, "no lit view");
    NP_CHECK(strstr(val, "not the unit's output") != NULL, "noisepipe:view = '%s'", val);
    /* Per face: the mean ratio lit / unlit over its pixels (its Lambert factor). */
    double sum[6] = { 0 }, cnt[6] = { 0 };
    uint64_t changed = 0, bg_changed = 0;
    for (size_t i = 0; lit && i < fr->n_spans; i++) {
        const np_rspan *sp = &fr->spans[i];
        for (uint32_t x = 0; x < sp->hw.n && sp->poly < 6; x++) {
            size_t p = ((size_t)sp->hw.y * s->width + sp->hw.x0 + x) * 3;
            for (int c = 0; c < 3; c++)
                if (fd->rgb[p + (size_t)c] >= 64) {
                    sum[sp->poly] += (double)lit[p + (size_t)c] / fd->rgb[p + (size_t)c];
                    cnt[sp->poly]++;
                }
            changed += memcmp(lit + p, fd->rgb + p, 3) != 0;
        }
    }
    for (size_t i = 0; lit && i < n; i++)
        bg_changed += !fr->mask[i] && memcmp(lit + 3 * i, fd->rgb + 3 * i, 3) != 0;
    double f[6];
    unsigned faces = 0;
    printf("wood, light (%.3f, %.3f, %.3f), ambient %.2f; Lambert factor per visible face:", s->light_dir[0],
           s->light_dir[1], s->light_dir[2], s->ambient);
    for (int p = 0; p < 6; p++)
        if (cnt[p] > 0) {
            f[faces++] = sum[p] / cnt[p];
            printf(" %.3f", sum[p] / cnt[p]);
        }
    printf("; %llu of %llu covered pixels changed, background changed: %llu\n", (unsigned long long)changed,
           (unsigned long long)fr->pixels, (unsigned long long)bg_changed);
    NP_CHECK(faces == 3, "%u faces visible", faces);
    NP_CHECK(faces == 3 && fabs(f[0] - f[1]) > 0.1 && fabs(f[1] - f[2]) > 0.1 && fabs(f[0] - f[2]) > 0.1,
             "faces not told apart by the light");
    NP_CHECK(changed > fr->pixels / 2 && bg_changed == 0, "shading changed %llu pixels, background %llu",
             (unsigned long long)changed, (unsigned long long)bg_changed);
    free(png);
    free(lit);
    free(copy);
    remove("test_render_view.png");
    remove("test_render_view_lit.png");
    remove("test_render_view.exr");
    /* The light section: given, normalised; zero and unknown keys refused with the field. */
    char buf[4096];
    np_scene t;
    variant(buf, sizeof buf, "\"image\"", "\"light\": { \"direction\": [0, 0, 2], \"ambient\": 0.5 }, \"image\"");
    NP_CHECK(np_scene_parse(buf, "light.json", &t, err, sizeof err) == 0, "%s", err);
    NP_CHECK(t.light_dir[2] == 1.0 && t.ambient == 0.5, "light %g %g %g ambient %g", t.light_dir[0], t.light_dir[1],
             t.light_dir[2], t.ambient);
    np_scene_free(&t);
    variant(buf, sizeof buf, "\"image\"", "\"light\": { \"direction\": [0, 0, 0] }, \"image\"");
    NP_CHECK(np_scene_parse(buf, "light.json", &t, err, sizeof err) != 0 &&
                 strstr(err, "field 'light.direction': must not be zero"),
             "zero light: %s", err);
    printf("  %s\n", err);
    variant(buf, sizeof buf, "\"image\"", "\"light\": { \"ambient\": 2 }, \"image\"");
    NP_CHECK(np_scene_parse(buf, "light.json", &t, err, sizeof err) != 0 && strstr(err, "field 'light.ambient'"),
             "ambient 2: %s", err);
    printf("  %s\n", err);
    return 0;
}
static int shading_view(void) { return with_seed("wood", shading_view_seed); }

/* Colour EXRs hold linear light with the chromaticities attribute; error EXRs say they hold LSB data. */
static int exr_colour_attributes_seed(const np_scene *s, const np_render_frame *fr, const np_render_run *fd, const np_render_run *tx)
{
    (void)s; (void)fd;
    char err[512];
    NP_CHECK(np_render_write_rgb8("test_render_attr", fr, "texel", tx->rgb, err, sizeof err) == 0, "%s", err);
    NP_CHECK(np_render_write_error("test_render_attr_err", fr, "texel", tx->rgb, 0, err, sizeof err) == 0, "%s", err);
    const char *files[2] = { "test_render_attr.exr", "test_render_attr_err.exr" };
    for (int i = 0; i < 2; i++) {
        exr_context_t ctx = NULL;
        exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
        NP_CHECK(exr_start_read(&ctx, files[i], &init) == EXR_ERR_SUCCESS, "cannot read %s", files[i]);
        exr_attr_chromaticities_t c;
        exr_result_t rc = exr_attr_get_chromaticities(ctx, 0, "chromaticities", &c);
        const char *v = NULL;
        int32_t len = 0;
        exr_result_t rs = exr_attr_get_string(ctx, 0, "noisepipe:values", &len, &v);
        if (i == 0) {
            NP_CHECK(rc == EXR_ERR_SUCCESS && c.red_x == 0.64f && c.red_y == 0.33f && c.green_x == 0.30f &&
                         c.green_y == 0.60f && c.blue_x == 0.15f && c.blue_y == 0.06f && c.white_x == 0.3127f &&
                         c.white_y == 0.3290f,
                     "%s: chromaticities missing or not Rec. 709 / D65", files[i]);
            if (rc == EXR_ERR_SUCCESS)
                printf("%s: chromaticities R (%g %g) G (%g %g) B (%g %g) W (%g %g)\n", files[i], (double)c.red_x,
                       (double)c.red_y, (double)c.green_x, (double)c.green_y, (double)c.blue_x, (double)c.blue_y,
                       (double)c.white_x, (double)c.white_y);
            NP_CHECK(rs == EXR_ERR_SUCCESS && strstr(v, "linear light"), "%s: noisepipe:values", files[i]);
        } else {
            NP_CHECK(rc != EXR_ERR_SUCCESS, "%s: an error image has chromaticities", files[i]);
            NP_CHECK(rs == EXR_ERR_SUCCESS && strstr(v, "error in 8-bit LSB (data, not colour)"), "%s: noisepipe:values",
                     files[i]);
        }
        if (rs == EXR_ERR_SUCCESS)
            printf("%s: noisepipe:values = \"%.*s\"\n", files[i], (int)len, v);
        exr_finish(&ctx);
    }
    /* The values: the sRGB EOTF of code / 255, e.g. code 255 is 1.0 and code 128 is 0.2158605. */
    unsigned w, h, nc;
    char rn[NP_IMAGE_MAX_CHANNELS][NP_IMAGE_NAME];
    float *pl = NULL;
    NP_CHECK(np_image_read_exr(files[0], &w, &h, &nc, rn, &pl, err, sizeof err) == 0, "%s", err);
    size_t n = (size_t)w * h;
    double worst = 0;
    for (size_t i = 0; pl && i < n; i++) {
        double v = tx->rgb[3 * i] / 255.0; /* R: the file's channels are B, G, R */
        double lin = v <= 0.04045 ? v / 12.92 : pow((v + 0.055) / 1.055, 2.4);
        worst = fmax(worst, fabs((double)pl[2 * n + i] - lin));
    }
    NP_CHECK(pl && strcmp(rn[2], "R") == 0 && worst < 1e-6, "R differs from the sRGB EOTF by %g", worst);
    free(pl);
    remove("test_render_attr.exr");
    remove("test_render_attr.png");
    remove("test_render_attr_lit.png");
    remove("test_render_attr_err.exr");
    remove("test_render_attr_err.png");
    return 0;
}
static int exr_colour_attributes(void) { return with_seed("marble", exr_colour_attributes_seed); }

static const np_test_case cases[] = {
    { "sha256_kat", sha256_kat },
    { "exr_roundtrip", exr_roundtrip },
    { "png_roundtrip", png_roundtrip },
    { "scene_errors", scene_errors },
    { "scene_seed", scene_seed },
    { "seed_scenes_1lsb", seed_scenes_1lsb },
    { "golden_hashes", golden_hashes },
    { "sized_registers", sized_registers },
    { "scanline", scanline },
    { "perspective_polygon", perspective_polygon },
    { "builtin_textures", builtin_textures },
    { "stream_vectors", stream_vectors },
    { "error_colour_bar", error_colour_bar },
    { "error_rounded", error_rounded },
    { "shading_view", shading_view },
    { "exr_colour_attributes", exr_colour_attributes },
    { NULL, NULL },
};

NP_TEST_MAIN(cases)
