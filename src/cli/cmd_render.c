/* SPDX-License-Identifier: MIT */
/*
 * noisepipe render: the float reference renderer and the scanline texturing
 * units (forward differences, per pixel) on a scene; images, error summary,
 * golden-image hashes, the error-against-run-time report and the benchmark.
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "np_cli.h"
#include "np_cmd.h"
#include "np_image.h"
#include "np_plot.h"
#include "np_render.h"
#include "np_unit.h"
#include "unit_tex.h"


static const char *const CMD = "render";
enum { MAX_SCENES = 16 };

static void usage(FILE *f)
{
    fputs("usage: noisepipe render [options] [SCENE.json ...]\n"
          "\n"
          "Render each scene (default: the wood scene built into the program, a copy of\n"
          "vectors/scenes/wood.json; --report: wood and marble; a SCENE may be a file or\n"
          "embedded:wood / embedded:marble)\n"
          "with the float reference and with both scanline texturing units - fdiff (forward\n"
          "differences, Kameya & Hart) and texel (per pixel) - from the same span\n"
          "descriptors, write the images (OpenEXR float + PNG) and error images, and print\n"
          "the error of each unit against the reference (8-bit colour LSB) with its cycles\n"
          "per frame and model time.\n"
          "\n"
          "options:\n"
          "  -o, --out DIR        output directory (default render-out; created)\n"
          "  --unit-config U:K=V,...  configuration of unit U over its defaults (keys and\n"
          "                       ranges: noisepipe units; the scene sets the texture);\n"
          "                       repeatable, a key given twice is an error\n"
          "  --fdiff K=V,...      the same as --unit-config fdiff:K=V,...\n"
          "  --texel K=V,...      the same as --unit-config texel:K=V,...\n"
          "  --tolerance LSB      fail (exit 1) when a unit's max error exceeds LSB (default 1)\n"
          "  --no-check           do not compare the errors with the tolerance\n"
          "  --no-cycles          skip the cycle-accurate models\n"
          "  --hashes FILE        compare the images' hashes with FILE (vectors/images/hashes.txt);\n"
          "                       exit 1 on any change\n"
          "  --write-hashes FILE  write the images' hashes to FILE\n"
          "  --ppm                also write PPM files (their sha256sum is the hash)\n"
          "  --report DIR         error against run time over configurations, scanline\n"
          "                       plots and images, for docs (DIR: docs/plots)\n"
          "  --bench              time the float reference and both models side by side\n"
          "  --repeat N           runs per timing in --bench and --report (default 5 / 3)\n"
          "\n"
          "exit status: 0 ok, 1 a check failed, 2 bad usage or bad input\n",
          f);
}

enum { MAX_UNITS = 16, UNIT_SPEC_MAX = 512 };

typedef struct opts {
    const char *out;
    /* --unit-config: the keys given for np_units[i], joined by commas; the unit's block configured from them. */
    char unit_spec[MAX_UNITS][UNIT_SPEC_MAX];
    np_unit_cfg ucfg[MAX_UNITS];
    /* The models' configurations inside the blocks of fdiff and texel (the render calls the models). */
    np_fdiff_cfg fc;
    np_texel_cfg tc;
    double tolerance;
    int check, cycles, ppm, bench;
    const char *hashes, *write_hashes, *report;
    unsigned repeat;
    const char *scenes[MAX_SCENES];
    unsigned n_scenes;
} opts;

/* "--name VALUE" or "--name=VALUE". */
static int opt_value(int argc, char **argv, int *i, const char *name, const char **val)
{
    size_t n = strlen(name);
    if (strncmp(argv[*i], name, n) != 0)
        return 0;
    if (argv[*i][n] == '=') {
        *val = argv[*i] + n + 1;
        return 1;
    }
    if (argv[*i][n] != '\0')
        return 0;
    if (*i + 1 >= argc) {
        np_err(CMD, "%s needs a value", name);
        return -1;
    }
    *val = argv[++*i];
    return 1;
}

static int mkdir_p(const char *dir)
{
    char buf[4096];
    snprintf(buf, sizeof buf, "%s", dir);
    for (char *p = buf + 1; *p; p++)
        if (*p == '/') {
            *p = '\0';
            if (mkdir(buf, 0777) != 0 && errno != EEXIST)
                return -1;
            *p = '/';
        }
    if (mkdir(buf, 0777) != 0 && errno != EEXIST)
        return -1;
    return 0;
}

/* Index of unit name in np_units[], or -1. */
static int unit_index(const char *name)
{
    for (int i = 0; np_units[i] && i < MAX_UNITS; i++)
        if (strcmp(np_units[i]->name, name) == 0)
            return i;
    return -1;
}

/* "U:K=V,..." of --unit-config (or the keys of --fdiff / --texel for unit, then arg is "K=V,..."): added to U's keys. */
static int add_unit_config(opts *o, const char *unit, const char *arg)
{
    char name[64];
    const char *keys = arg;
    if (!unit) {
        const char *colon = strchr(arg, ':');
        if (!colon || colon == arg || (size_t)(colon - arg) >= sizeof name) {
            np_err(CMD, "--unit-config %s: expected UNIT:KEY=VALUE,...", arg);
            return -1;
        }
        memcpy(name, arg, (size_t)(colon - arg));
        name[colon - arg] = '\0';
        unit = name;
        keys = colon + 1;
    }
    int i = unit_index(unit);
    if (i < 0) {
        char known[256] = "";
        for (size_t k = 0; np_units[k]; k++)
            snprintf(known + strlen(known), sizeof known - strlen(known), "%s%s", k ? ", " : "", np_units[k]->name);
        np_err(CMD, "--unit-config: unknown unit '%s' (units: %s)", unit, known);
        return -1;
    }
    char *spec = o->unit_spec[i];
    if (strlen(spec) + 1 + strlen(keys) >= UNIT_SPEC_MAX) {
        np_err(CMD, "--unit-config %s: configuration too long", unit);
        return -1;
    }
    snprintf(spec + strlen(spec), UNIT_SPEC_MAX - strlen(spec), "%s%s", *spec ? "," : "", keys);
    return 0;
}

/* Configure every unit from its --unit-config keys (the scene's keys are the scene's, not the user's). */
static int configure_units(opts *o)
{
    for (int i = 0; np_units[i] && i < MAX_UNITS; i++) {
        const np_unit *u = np_units[i];
        char err[512], key[64];
        if (np_unit_configure(u, &o->ucfg[i], o->unit_spec[i], err, sizeof err) != 0) {
            np_err(CMD, "--unit-config %s: %s", u->name, err);
            return -1;
        }
        for (const char *p = o->unit_spec[i]; *p;) {
            size_t n = strcspn(p, "=, ");
            snprintf(key, sizeof key, "%.*s", (int)n, p);
            const np_unit_key *k = np_unit_key_find(u, key);
            if (k && (k->flags & NP_UNIT_KEY_SCENE)) {
                np_err(CMD, "--unit-config %s:%s: the scene sets %s", u->name, key, key);
                return -1;
            }
            p += strcspn(p, ", ");
            p += strspn(p, ", ");
        }
    }
    int f = unit_index("fdiff"), t = unit_index("texel");
    o->fc = *np_ut_fdiff_cfg(&o->ucfg[f]);
    o->tc = *np_ut_texel_cfg(&o->ucfg[t]);
    return 0;
}

/* A unit's configuration as the golden image hashes name it: "k=v,k=v", without the keys the scene sets. */
static void unit_cfg_text(const opts *o, const char *unit, char *buf, size_t len)
{
    int i = unit_index(unit);
    np_unit_cfg_format_opt(np_units[i], &o->ucfg[i], NP_UNIT_FMT_COMMAS | NP_UNIT_FMT_NO_SCENE, buf, len);
}

/* A seed scene by name: the copy built into the program (vectors/scenes/NAME.json). */
static const char *seed_scene(const char *name, char *path, size_t n)
{
    snprintf(path, n, "embedded:%s", name);
    return path;
}

static int parse_opts(int argc, char **argv, opts *o)
{
    memset(o, 0, sizeof *o);
    o->out = "render-out";
    o->tolerance = 1.0;
    o->check = 1;
    o->cycles = 1;
    for (int i = 1; i < argc; i++) {
        const char *v = NULL;
        int r;
        if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
            usage(stdout);
            return 1;
        }
        if ((r = opt_value(argc, argv, &i, "--out", &v)) || (r = opt_value(argc, argv, &i, "-o", &v))) {
            if (r < 0)
                return -1;
            o->out = v;
        } else if ((r = opt_value(argc, argv, &i, "--unit-config", &v))) {
            if (r < 0 || add_unit_config(o, NULL, v) != 0)
                return -1;
        } else if ((r = opt_value(argc, argv, &i, "--fdiff", &v))) {
            if (r < 0 || add_unit_config(o, "fdiff", v) != 0)
                return -1;
        } else if ((r = opt_value(argc, argv, &i, "--texel", &v))) {
            if (r < 0 || add_unit_config(o, "texel", v) != 0)
                return -1;
        } else if ((r = opt_value(argc, argv, &i, "--tolerance", &v))) {
            char *end;
            if (r < 0)
                return -1;
            o->tolerance = strtod(v, &end);
            if (*v == '\0' || *end != '\0' || !(o->tolerance >= 0)) {
                np_err(CMD, "--tolerance %s: expected a number >= 0 (LSB)", v);
                return -1;
            }
        } else if ((r = opt_value(argc, argv, &i, "--hashes", &v))) {
            if (r < 0)
                return -1;
            o->hashes = v;
        } else if ((r = opt_value(argc, argv, &i, "--write-hashes", &v))) {
            if (r < 0)
                return -1;
            o->write_hashes = v;
        } else if ((r = opt_value(argc, argv, &i, "--report", &v))) {
            if (r < 0)
                return -1;
            o->report = v;
        } else if ((r = opt_value(argc, argv, &i, "--repeat", &v))) {
            uint64_t n;
            if (r < 0)
                return -1;
            if (np_parse_u64(v, 1, 1000, &n)) {
                np_err(CMD, "--repeat %s: expected an integer in 1..1000", v);
                return -1;
            }
            o->repeat = (unsigned)n;
        } else if (strcmp(argv[i], "--no-check") == 0) {
            o->check = 0;
        } else if (strcmp(argv[i], "--no-cycles") == 0) {
            o->cycles = 0;
        } else if (strcmp(argv[i], "--ppm") == 0) {
            o->ppm = 1;
        } else if (strcmp(argv[i], "--bench") == 0) {
            o->bench = 1;
        } else if (argv[i][0] == '-' && argv[i][1] != '\0') {
            np_err(CMD, "unknown option '%s' (noisepipe render --help)", argv[i]);
            return -1;
        } else {
            if (o->n_scenes >= MAX_SCENES) {
                np_err(CMD, "at most %d scenes", MAX_SCENES);
                return -1;
            }
            o->scenes[o->n_scenes++] = argv[i];
        }
    }
    /* Default: the seed's wood; the report covers both seed scenes. */
    static char wood[4096], marble[4096];
    if (o->n_scenes == 0) {
        o->scenes[o->n_scenes++] = seed_scene("wood", wood, sizeof wood);
        if (o->report)
            o->scenes[o->n_scenes++] = seed_scene("marble", marble, sizeof marble);
    }
    return configure_units(o);
}

/* --- Golden hashes --- */

typedef struct hash_rec {
    char scene[64], image[16], hash[65], cfg[256];
} hash_rec;

typedef struct hash_list {
    hash_rec *r;
    size_t n, cap;
} hash_list;

static int hash_add(hash_list *l, const char *scene, const char *image, const char *hash, const char *cfg)
{
    if (l->n == l->cap) {
        size_t nc = l->cap ? 2 * l->cap : 16;
        hash_rec *nr = realloc(l->r, nc * sizeof *nr);
        if (!nr)
            return -1;
        l->r = nr;
        l->cap = nc;
    }
    hash_rec *h = &l->r[l->n++];
    snprintf(h->scene, sizeof h->scene, "%s", scene);
    snprintf(h->image, sizeof h->image, "%s", image);
    snprintf(h->hash, sizeof h->hash, "%s", hash);
    snprintf(h->cfg, sizeof h->cfg, "%s", cfg);
    return 0;
}

/* Lines "scene image sha256 configuration"; '#' comments. 0, or -1 with a message. */
static int hash_read(const char *path, hash_list *l)
{
    FILE *f = fopen(path, "r");
    if (!f) {
        np_err(CMD, "%s: cannot open: %s", path, strerror(errno));
        return -1;
    }
    char line[1024];
    unsigned no = 0;
    while (fgets(line, sizeof line, f)) {
        no++;
        char *p = line;
        while (*p == ' ' || *p == '\t')
            p++;
        if (*p == '#' || *p == '\n' || *p == '\0')
            continue;
        char sc[64], im[16], h[65], cfg[256];
        if (sscanf(p, "%63s %15s %64s %255s", sc, im, h, cfg) != 4 || strlen(h) != 64) {
            np_err(CMD, "%s:%u: expected 'scene image sha256 configuration'", path, no);
            fclose(f);
            return -1;
        }
        if (hash_add(l, sc, im, h, cfg)) {
            fclose(f);
            return -1;
        }
    }
    fclose(f);
    return 0;
}

static int hash_write(const char *path, const hash_list *l)
{
    FILE *f = fopen(path, "w");
    if (!f) {
        np_err(CMD, "%s: cannot create: %s", path, strerror(errno));
        return -1;
    }
    fputs("# noisepipe golden images: SHA-256 of each image as a binary PPM (np_image_hash;\n"
          "# `noisepipe render --ppm` writes the PPM files, `sha256sum` of them gives these).\n"
          "# Written by `noisepipe render --write-hashes`; checked by `noisepipe render --hashes`\n"
          "# and by the test render.golden_hashes. A change to any bit of an image shows here.\n"
          "# scene image sha256 configuration\n",
          f);
    for (size_t i = 0; i < l->n; i++)
        fprintf(f, "%s %s %s %s\n", l->r[i].scene, l->r[i].image, l->r[i].hash, l->r[i].cfg);
    return fclose(f) == 0 ? 0 : -1;
}

/* Compare got with the golden list; prints each difference. Returns the number of failures. */
static unsigned hash_check(const hash_list *golden, const hash_list *got, const char *path)
{
    unsigned bad = 0;
    for (size_t i = 0; i < got->n; i++) {
        const hash_rec *g = &got->r[i], *w = NULL;
        for (size_t k = 0; k < golden->n; k++)
            if (strcmp(golden->r[k].scene, g->scene) == 0 && strcmp(golden->r[k].image, g->image) == 0)
                w = &golden->r[k];
        if (!w) {
            printf("hash: %s %s: no golden hash in %s\n", g->scene, g->image, path);
            bad++;
        } else if (strcmp(w->cfg, g->cfg) != 0) {
            printf("hash: %s %s: configuration %s differs from the golden one %s\n", g->scene, g->image, g->cfg,
                   w->cfg);
            bad++;
        } else if (strcmp(w->hash, g->hash) != 0) {
            printf("hash: %s %s: CHANGED: %s, golden %s\n", g->scene, g->image, g->hash, w->hash);
            bad++;
        } else {
            printf("hash: %s %s: matches %s\n", g->scene, g->image, path);
        }
    }
    return bad;
}

/* --- One scene --- */

static void print_run(const char *unit, const char *cfg, const np_render_run *r)
{
    char psnr[32];
    if (isinf(r->err.psnr_db))
        snprintf(psnr, sizeof psnr, "inf");
    else
        snprintf(psnr, sizeof psnr, "%.2f", r->err.psnr_db);
    printf("  %-6s max %.3f LSB (at %u,%u), RMS %.4f LSB, mean %+.4f LSB, PSNR %s dB, >1 LSB: %llu of %llu samples\n",
           unit, r->err.max_lsb, r->err.max_x, r->err.max_y, r->err.rms_lsb, r->err.mean_lsb, psnr,
           (unsigned long long)r->err.over_one, (unsigned long long)r->err.samples);
    printf("         config %s\n", cfg);
    if (r->have_cycles)
        printf("         cycles/frame %llu, set-up stall cycles %llu, set-ups: %llu span, %llu cell, %llu interval;"
               " bit-exact model %.4f s, cycle model %.4f s%s\n",
               (unsigned long long)r->cycles, (unsigned long long)r->setup_stalls,
               (unsigned long long)r->span_setups, (unsigned long long)r->cell_setups,
               (unsigned long long)r->interval_setups, r->model_seconds, r->cycle_seconds,
               r->cycle_mismatch ? "  CYCLE MODEL DIFFERS" : "");
    else
        printf("         set-ups: %llu span, %llu cell, %llu interval; bit-exact model %.4f s\n",
               (unsigned long long)r->span_setups, (unsigned long long)r->cell_setups,
               (unsigned long long)r->interval_setups, r->model_seconds);
}

static int write_outputs(const opts *o, const np_render_frame *fr, const np_render_run *fd, const np_render_run *tx,
                         char *err, size_t errlen)
{
    const np_scene *sc = fr->sc;
    char base[4096];
    snprintf(base, sizeof base, "%s/%s_ref", o->out, sc->name);
    if (np_render_write_ref(base, fr, err, errlen))
        return -1;
    const struct { const char *n; const np_render_run *r; } u[2] = { { "fdiff", fd }, { "texel", tx } };
    for (int i = 0; i < 2; i++) {
        snprintf(base, sizeof base, "%s/%s_%s", o->out, sc->name, u[i].n);
        if (np_render_write_rgb8(base, sc->width, sc->height, u[i].r->rgb, err, errlen))
            return -1;
        snprintf(base, sizeof base, "%s/%s_%s_err", o->out, sc->name, u[i].n);
        if (np_render_write_error(base, fr, u[i].r->rgb, err, errlen))
            return -1;
        if (o->ppm) {
            snprintf(base, sizeof base, "%s/%s_%s.ppm", o->out, sc->name, u[i].n);
            if (np_image_write_ppm(base, sc->width, sc->height, u[i].r->rgb, err, errlen))
                return -1;
        }
    }
    if (o->ppm) {
        uint8_t *rgb = malloc((size_t)sc->width * sc->height * 3);
        if (!rgb)
            return -1;
        np_render_ref_rgb8(fr, rgb);
        snprintf(base, sizeof base, "%s/%s_ref.ppm", o->out, sc->name);
        int rc = np_image_write_ppm(base, sc->width, sc->height, rgb, err, errlen);
        free(rgb);
        if (rc)
            return -1;
    }
    printf("  images: %s/%s_{ref,fdiff,texel,fdiff_err,texel_err}.{exr,png}\n", o->out, sc->name);
    return 0;
}

/* Render one scene; appends its hashes. Returns NP_EXIT_*. */
static int render_scene(const opts *o, const char *path, hash_list *hashes)
{
    np_scene sc;
    np_render_frame fr;
    np_render_run fd, tx;
    char err[1024], fcfg[256], tcfg[256], hex[65];
    if (np_scene_load(path, &sc, err, sizeof err)) {
        np_err(CMD, "%s", err);
        return NP_EXIT_USAGE;
    }
    if (np_render_prepare(&sc, &fr, err, sizeof err)) {
        np_err(CMD, "%s", err);
        np_scene_free(&sc);
        return NP_EXIT_USAGE;
    }
    int rc = NP_EXIT_OK;
    memset(&fd, 0, sizeof fd);
    memset(&tx, 0, sizeof tx);
    if (np_render_reference(&fr) || np_render_fdiff(&fr, &o->fc, o->cycles, &fd) ||
        np_render_texel(&fr, &o->tc, o->cycles, &tx)) {
        np_err(CMD, "out of memory");
        rc = NP_EXIT_USAGE;
        goto out;
    }
    unit_cfg_text(o, "fdiff", fcfg, sizeof fcfg);
    unit_cfg_text(o, "texel", tcfg, sizeof tcfg);
    printf("scene %s (%s): %ux%u, %llu pixels in %zu spans (longest %u), %u octave%s; reference %.4f s\n",
           sc.name, path, sc.width, sc.height, (unsigned long long)fr.pixels, fr.n_spans, fr.longest,
           sc.tex.n_oct, sc.tex.n_oct == 1 ? "" : "s", fr.ref_seconds);
    print_run("fdiff", fcfg, &fd);
    print_run("texel", tcfg, &tx);
    if (fd.cycle_mismatch || tx.cycle_mismatch) {
        np_err(CMD, "%s: the cycle-accurate model differs from the bit-exact model", sc.name);
        rc = NP_EXIT_FAIL;
    }
    if (o->check)
        for (int i = 0; i < 2; i++) {
            const np_render_run *r = i ? &tx : &fd;
            if (r->err.max_lsb > o->tolerance) {
                printf("  FAIL: %s max error %.3f LSB exceeds the tolerance %.3f LSB\n", i ? "texel" : "fdiff",
                       r->err.max_lsb, o->tolerance);
                rc = NP_EXIT_FAIL;
            }
        }
    if (mkdir_p(o->out) != 0) {
        np_err(CMD, "%s: cannot create: %s", o->out, strerror(errno));
        rc = NP_EXIT_USAGE;
        goto out;
    }
    if (write_outputs(o, &fr, &fd, &tx, err, sizeof err)) {
        np_err(CMD, "%s", err);
        rc = NP_EXIT_USAGE;
        goto out;
    }
    uint8_t *ref8 = malloc((size_t)sc.width * sc.height * 3);
    if (!ref8) {
        rc = NP_EXIT_USAGE;
        goto out;
    }
    np_render_ref_rgb8(&fr, ref8);
    np_image_hash(sc.width, sc.height, ref8, hex);
    hash_add(hashes, sc.name, "ref", hex, "-");
    free(ref8);
    np_image_hash(sc.width, sc.height, fd.rgb, hex);
    hash_add(hashes, sc.name, "fdiff", hex, fcfg);
    np_image_hash(sc.width, sc.height, tx.rgb, hex);
    hash_add(hashes, sc.name, "texel", hex, tcfg);
out:
    np_render_run_free(&fd);
    np_render_run_free(&tx);
    np_render_frame_free(&fr);
    np_scene_free(&sc);
    return rc;
}

/* --- Benchmark --- */

static double best_of(unsigned n, int (*fn)(void *), void *ctx)
{
    double best = HUGE_VAL;
    for (unsigned i = 0; i < n; i++) {
        double t0 = np_now();
        if (fn(ctx))
            return NAN;
        best = fmin(best, np_now() - t0);
    }
    return best;
}

typedef struct bench_ctx {
    np_render_frame *fr;
    const opts *o;
} bench_ctx;

static int b_ref(void *c) { return np_render_reference(((bench_ctx *)c)->fr); }

static int b_fdiff(void *c)
{
    bench_ctx *b = c;
    np_render_run r;
    int rc = np_render_fdiff(b->fr, &b->o->fc, 0, &r);
    np_render_run_free(&r);
    return rc;
}

static int b_texel(void *c)
{
    bench_ctx *b = c;
    np_render_run r;
    int rc = np_render_texel(b->fr, &b->o->tc, 0, &r);
    np_render_run_free(&r);
    return rc;
}

static int bench_scene(const opts *o, const char *path)
{
    np_scene sc;
    np_render_frame fr;
    char err[1024];
    unsigned rep = o->repeat ? o->repeat : 5;
    if (np_scene_load(path, &sc, err, sizeof err)) {
        np_err(CMD, "%s", err);
        return NP_EXIT_USAGE;
    }
    if (np_render_prepare(&sc, &fr, err, sizeof err)) {
        np_err(CMD, "%s", err);
        np_scene_free(&sc);
        return NP_EXIT_USAGE;
    }
    bench_ctx b = { &fr, o };
    double tr = best_of(rep, b_ref, &b), tf = best_of(rep, b_fdiff, &b), tt = best_of(rep, b_texel, &b);
    np_render_run fd, tx;
    if (np_render_fdiff(&fr, &o->fc, 1, &fd) || np_render_texel(&fr, &o->tc, 1, &tx)) {
        np_err(CMD, "out of memory");
        np_render_frame_free(&fr);
        np_scene_free(&sc);
        return NP_EXIT_USAGE;
    }
    printf("bench %s: %ux%u, %llu pixels, %zu spans, %u octave%s (best of %u runs)\n", sc.name, sc.width, sc.height,
           (unsigned long long)fr.pixels, fr.n_spans, sc.tex.n_oct, sc.tex.n_oct == 1 ? "" : "s", rep);
    printf("  %-34s %12s %12s %10s\n", "", "fdiff", "texel", "texel/fdiff");
    printf("  %-34s %12.5f %12.5f %10.2f\n", "bit-exact model, s per frame", tf, tt, tt / tf);
    printf("  %-34s %12.1f %12.1f\n", "  ns per pixel", tf * 1e9 / (double)fr.pixels, tt * 1e9 / (double)fr.pixels);
    printf("  %-34s %12llu %12llu %10.2f\n", "hardware cycles per frame", (unsigned long long)fd.cycles,
           (unsigned long long)tx.cycles, (double)tx.cycles / (double)fd.cycles);
    printf("  %-34s %12.3f %12.3f\n", "  cycles per pixel", (double)fd.cycles / (double)fr.pixels,
           (double)tx.cycles / (double)fr.pixels);
    printf("  %-34s %12llu %12llu\n", "  set-up stall cycles", (unsigned long long)fd.setup_stalls,
           (unsigned long long)tx.setup_stalls);
    printf("  %-34s %12.5f %12.5f\n", "cycle-accurate model, s per frame", fd.cycle_seconds, tx.cycle_seconds);
    printf("  %-34s %12.3f %12.3f\n", "max error vs float reference, LSB", fd.err.max_lsb, tx.err.max_lsb);
    printf("  float reference (double) renderer: %.5f s per frame\n", tr);
    printf("  model speed-up of forward differencing over per-pixel evaluation: %.0f%% less time "
           "(the seed reports about 10%% in software)\n",
           100.0 * (1.0 - tf / tt));
    np_render_run_free(&fd);
    np_render_run_free(&tx);
    np_render_frame_free(&fr);
    np_scene_free(&sc);
    return NP_EXIT_OK;
}

/* --- Report: error against run time over configurations --- */

typedef struct row {
    char scene[64];
    const char *unit;
    unsigned guard, resetup, wt, mults;
    np_render_err e;
    uint64_t cycles, setups;
    double seconds;
} row;

/*
 * One row of the error-against-run-time table: the unit's configuration
 * (fc for fdiff, tc for texel) and what its run measured.
 */
static void put_row(row *w, const char *scene, const np_fdiff_cfg *fc, const np_texel_cfg *tc,
                    const np_render_run *r, uint64_t cycles, double seconds)
{
    snprintf(w->scene, sizeof w->scene, "%s", scene);
    w->unit = fc ? "fdiff" : "texel";
    w->guard = fc ? fc->guard : tc->guard;
    w->resetup = fc ? fc->resetup : 0u;
    w->wt = fc ? 0u : tc->weight_frac;
    w->mults = fc ? fc->setup_mults : tc->setup_mults;
    w->e = r->err;
    w->cycles = cycles;
    w->setups = r->span_setups + r->cell_setups + r->interval_setups;
    w->seconds = seconds;
}

static const unsigned rep_guard[] = { 0, 2, 4, 6, 8, 10, 12, 16, 20, 24, 32, 44 };
static const unsigned rep_k[] = { 0, 8, 32 };
static const unsigned rep_wt[] = { 2, 4, 6, 8, 10, 12, 16, 32 };
static const unsigned rep_p[] = { 1, 4, 16 }; /* set-up multipliers, besides the default */
enum {
    N_P = sizeof rep_p / sizeof rep_p[0],
    N_G = sizeof rep_guard / sizeof rep_guard[0],
    N_K = sizeof rep_k / sizeof rep_k[0],
    N_WT = sizeof rep_wt / sizeof rep_wt[0]
};

static FILE *open_out(const char *dir, const char *name, char *path, size_t n)
{
    snprintf(path, n, "%s/%s", dir, name);
    FILE *f = fopen(path, "w");
    if (!f)
        np_err(CMD, "%s: cannot create: %s", path, strerror(errno));
    return f;
}

static double floor_log(double v) { return v < 0.01 ? 0.01 : v; }

static int plot_errors(const char *dir, const char *scene, const row *rows, size_t n, int by_seconds)
{
    static const char *const colours[] = { "#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd" };
    double xs[N_K + 2][N_G + N_WT], ys[N_K + 2][N_G + N_WT];
    char labels[N_K + 2][64];
    np_plot_series s[N_K + 2];
    size_t ns = 0;
    for (unsigned k = 0; k < N_K + 2; k++) {
        size_t m = 0;
        for (size_t i = 0; i < n; i++) {
            const row *r = &rows[i];
            if (strcmp(r->scene, scene) != 0)
                continue;
            int fd = strcmp(r->unit, "fdiff") == 0, p2 = r->mults == 2;
            int mine = k < N_K ? fd && p2 && r->resetup == rep_k[k] : k == N_K ? !fd : fd && !p2;
            if (!mine)
                continue;
            xs[k][m] = by_seconds ? r->seconds * 1e3 : (double)r->cycles;
            ys[k][m] = floor_log(r->e.max_lsb);
            m++;
        }
        if (k < N_K)
            snprintf(labels[k], sizeof labels[k], "fdiff K=%u, guard %u..%u", rep_k[k], rep_guard[0], rep_guard[N_G - 1]);
        else if (k == N_K)
            snprintf(labels[k], sizeof labels[k], "texel, weight bits %u..%u", rep_wt[0], rep_wt[N_WT - 1]);
        else
            snprintf(labels[k], sizeof labels[k], "fdiff K=0, set-up multipliers %u..%u", rep_p[0], rep_p[N_P - 1]);
        s[ns] = (np_plot_series){ labels[k], colours[k], xs[k], ys[k], m, 0, 1 };
        ns++;
    }
    char title[160], name[128], path[4096];
    snprintf(title, sizeof title, "%s: max error against %s", scene, by_seconds ? "model time" : "cycles per frame");
    np_plot p = { title, by_seconds ? "bit-exact model time per frame (ms)" : "cycles per frame",
                  "max error vs float reference (8-bit LSB)", 0, 0, 0.01, 1000.0, 1, NAN, 1.0, NULL,
                  "1 LSB" };
    snprintf(name, sizeof name, "%s_error_vs_%s.svg", scene, by_seconds ? "seconds" : "cycles");
    FILE *f = open_out(dir, name, path, sizeof path);
    if (!f)
        return -1;
    np_plot_svg(f, &p, s, ns);
    return fclose(f) == 0 ? 0 : -1;
}

/* A comb of vertical lines at xs (drawn as one polyline along the frame's top and bottom edges). */
static size_t comb(const double *xs, size_t n, double y0, double y1, double *cx, double *cy)
{
    size_t m = 0;
    for (size_t i = 0; i < n; i++) {
        int up = (int)(i % 2u) == 0;
        cx[m] = xs[i], cy[m++] = up ? y0 : y1;
        cx[m] = xs[i], cy[m++] = up ? y1 : y0;
    }
    return m;
}

static int plot_scan(const char *dir, const np_scene *sc, const np_render_frame *fr, unsigned guard)
{
    np_fdiff_cfg c = np_fdiff_cfg_default();
    c.guard = guard;
    np_render_scan s;
    if (np_render_scanline(fr, &c, sc->probe_row, &s) || s.n == 0) {
        np_render_scan_free(&s);
        return -1;
    }
    int rc = 0;
    for (int which = 0; which < (sc->tex.n_oct > 1 ? 2 : 1) && rc == 0; which++) {
        const double *edges = which ? s.edge_last : s.edge_any;
        size_t ne = which ? s.n_edge_last : s.n_edge_any;
        /*
         * Scale the data to O(1): np_plot_svg's ticks assume ranges far above 1e-9,
         * and the drift spans 1e-3 (no guard bits) to 1e-17 (the default).
         */
        double amax = 0;
        for (size_t i = 0; i < s.n; i++)
            amax = fmax(amax, fabs(which ? s.last[i] : s.sum[i]));
        int ex = amax > 0 ? (int)floor(log10(amax)) : 0;
        double scale = pow(10.0, -ex);
        double *y = malloc(s.n * sizeof *y);
        if (!y) {
            rc = -1;
            break;
        }
        for (size_t i = 0; i < s.n; i++)
            y[i] = (which ? s.last[i] : s.sum[i]) * scale;
        double lo = -1.0, hi = 1.0;
        for (size_t i = 0; i < s.n; i++) {
            lo = fmin(lo, y[i]);
            hi = fmax(hi, y[i]);
        }
        lo -= 0.08 * (hi - lo);
        hi += 0.08 * (hi - lo);
        double *cx = malloc(2 * (ne + 1) * sizeof *cx), *cy = malloc(2 * (ne + 1) * sizeof *cy);
        if (!cx || !cy) {
            free(cx);
            free(cy);
            free(y);
            rc = -1;
            break;
        }
        size_t m = comb(edges, ne, lo, hi, cx, cy);
        char lab[96], title[200], name[128], path[4096], ylab[128];
        snprintf(lab, sizeof lab, "FD - per pixel (guard %u, F = %u)", guard, np_fdiff_frac(&c));
        np_plot_series ser[2] = {
            { "cell edges (set-up)", "#bbbbbb", cx, cy, m, 1, 0 },
            { lab, "#d62728", s.x, y, s.n, 1, 0 },
        };
        if (which)
            snprintf(title, sizeof title, "%s, scanline %u: noise difference, octave %u only (seed fig. 11)", sc->name,
                     sc->probe_row, sc->tex.n_oct);
        else
            snprintf(title, sizeof title, "%s, scanline %u: noise difference %s(seed fig. 10)", sc->name, sc->probe_row,
                     sc->tex.n_oct > 1 ? "of the octave sum " : "");
        snprintf(ylab, sizeof ylab, "%s (x 1e%d)", which ? "difference of n (noise range 0..1)" : "difference of sum a_i n_i (units of f)", ex);
        np_plot p = { title, "pixel x", ylab, s.x[0] - 1.0, s.x[s.n - 1] + 1.0, lo, hi, 0, NAN, NAN, NULL, NULL };
        snprintf(name, sizeof name, "%s_scanline%s_g%u.svg", sc->name, which ? "_last" : "", guard);
        FILE *f = open_out(dir, name, path, sizeof path);
        if (!f)
            rc = -1;
        else {
            np_plot_svg(f, &p, ser, 2);
            rc = fclose(f) == 0 ? 0 : -1;
        }
        free(cx);
        free(cy);
        free(y);
    }
    np_render_scan_free(&s);
    return rc;
}

static double time_model(const np_render_frame *fr, const np_fdiff_cfg *fc, const np_texel_cfg *tc, unsigned rep,
                         np_render_run *keep)
{
    double best = HUGE_VAL;
    for (unsigned i = 0; i < rep; i++) {
        np_render_run r;
        if (fc ? np_render_fdiff(fr, fc, 0, &r) : np_render_texel(fr, tc, 0, &r))
            return NAN;
        best = fmin(best, r.model_seconds);
        if (i == 0)
            *keep = r;
        else
            np_render_run_free(&r);
    }
    return best;
}

static int report(const opts *o)
{
    const char *dir = o->report;
    unsigned rep = o->repeat ? o->repeat : 3;
    size_t cap = (size_t)o->n_scenes * (N_G * N_K + N_WT + N_P), n = 0;
    row *rows = calloc(cap, sizeof *rows);
    if (!rows || mkdir_p(dir) != 0) {
        free(rows);
        np_err(CMD, "%s: cannot create", dir);
        return NP_EXIT_USAGE;
    }
    int rc = NP_EXIT_OK;
    for (unsigned si = 0; si < o->n_scenes && rc == NP_EXIT_OK; si++) {
        np_scene sc;
        np_render_frame fr;
        char err[1024], base[4096];
        if (np_scene_load(o->scenes[si], &sc, err, sizeof err)) {
            np_err(CMD, "%s", err);
            rc = NP_EXIT_USAGE;
            break;
        }
        if (np_render_prepare(&sc, &fr, err, sizeof err) || np_render_reference(&fr)) {
            np_err(CMD, "%s", err);
            np_scene_free(&sc);
            rc = NP_EXIT_USAGE;
            break;
        }
        fprintf(stderr, "report: %s ...\n", sc.name);
        /* Images of the default configurations. */
        np_render_run fd, tx;
        if (np_render_fdiff(&fr, &o->fc, 0, &fd) || np_render_texel(&fr, &o->tc, 0, &tx)) {
            rc = NP_EXIT_USAGE;
        } else {
            uint8_t *ref8 = malloc((size_t)sc.width * sc.height * 3);
            if (ref8) {
                np_render_ref_rgb8(&fr, ref8);
                snprintf(base, sizeof base, "%s/%s_ref.png", dir, sc.name);
                np_image_write_png(base, sc.width, sc.height, ref8, err, sizeof err);
                free(ref8);
            }
            const struct { const char *n; np_render_run *r; } u[2] = { { "fdiff", &fd }, { "texel", &tx } };
            for (int i = 0; i < 2; i++) {
                snprintf(base, sizeof base, "%s/%s_%s.png", dir, sc.name, u[i].n);
                np_image_write_png(base, sc.width, sc.height, u[i].r->rgb, err, sizeof err);
                snprintf(base, sizeof base, "%s/%s_%s_err", dir, sc.name, u[i].n);
                np_render_write_error(base, &fr, u[i].r->rgb, err, sizeof err);
                snprintf(base, sizeof base, "%s/%s_%s_err.exr", dir, sc.name, u[i].n);
                remove(base); /* docs keep the PNG heat map only */
            }
            np_render_run_free(&fd);
            np_render_run_free(&tx);
            /* What too few guard bits look like: the error heat map at G = 4. */
            np_fdiff_cfg few = o->fc;
            few.guard = 4;
            if (np_render_fdiff(&fr, &few, 0, &fd) == 0) {
                snprintf(base, sizeof base, "%s/%s_fdiff_g4_err", dir, sc.name);
                np_render_write_error(base, &fr, fd.rgb, err, sizeof err);
                snprintf(base, sizeof base, "%s/%s_fdiff_g4_err.exr", dir, sc.name);
                remove(base);
                np_render_run_free(&fd);
            }
        }
        /* Forward differences: guard bits x re-set-up interval. */
        for (unsigned k = 0; k < N_K && rc == NP_EXIT_OK; k++) {
            np_fdiff_cfg c = o->fc;
            c.resetup = rep_k[k];
            np_render_run cyc;
            if (np_render_fdiff(&fr, &c, 1, &cyc)) {
                rc = NP_EXIT_USAGE;
                break;
            }
            for (unsigned g = 0; g < N_G; g++) {
                c.guard = rep_guard[g];
                if (np_fdiff_cfg_check(&c))
                    continue;
                np_render_run r;
                double t = time_model(&fr, &c, NULL, rep, &r);
                put_row(&rows[n++], sc.name, &c, NULL, &r, cyc.cycles, t);
                np_render_run_free(&r);
            }
            np_render_run_free(&cyc);
        }
        /* Forward differences: the set-up engine's multipliers (cycles only; the bits do not change). */
        for (unsigned k = 0; k < N_P && rc == NP_EXIT_OK; k++) {
            np_fdiff_cfg c = o->fc;
            c.setup_mults = rep_p[k];
            np_render_run r;
            if (np_render_fdiff(&fr, &c, 1, &r)) {
                rc = NP_EXIT_USAGE;
                break;
            }
            row *w = &rows[n++];
            put_row(w, sc.name, &c, NULL, &r, r.cycles, 0.0);
            np_render_run_free(&r);
            w->seconds = time_model(&fr, &c, NULL, rep, &r);
            np_render_run_free(&r);
        }
        /* Per pixel: weight bits. */
        for (unsigned k = 0; k < N_WT && rc == NP_EXIT_OK; k++) {
            np_texel_cfg c = o->tc;
            c.weight_frac = rep_wt[k];
            np_render_run r;
            if (np_render_texel(&fr, &c, 1, &r)) {
                rc = NP_EXIT_USAGE;
                break;
            }
            row *w = &rows[n++];
            put_row(w, sc.name, NULL, &c, &r, r.cycles, 0.0);
            np_render_run_free(&r);
            w->seconds = time_model(&fr, NULL, &c, rep, &r);
            np_render_run_free(&r);
        }
        if (rc == NP_EXIT_OK &&
            (plot_errors(dir, sc.name, rows, n, 0) || plot_errors(dir, sc.name, rows, n, 1) ||
             plot_scan(dir, &sc, &fr, 0) || plot_scan(dir, &sc, &fr, o->fc.guard)))
            rc = NP_EXIT_USAGE;
        np_render_frame_free(&fr);
        np_scene_free(&sc);
    }
    if (rc == NP_EXIT_OK) {
        char path[4096];
        FILE *md = open_out(dir, "error_runtime.md", path, sizeof path);
        FILE *csv = md ? open_out(dir, "error_runtime.csv", path, sizeof path) : NULL;
        if (!md || !csv) {
            if (md)
                fclose(md);
            rc = NP_EXIT_USAGE;
        } else {
            fputs("<!-- generated by `noisepipe render --report docs/plots` -->\n"
                  "| scene | unit | guard G | K | weight bits | set-up mults P | max LSB | RMS LSB | PSNR dB | "
                  ">1 LSB samples | cycles/frame | set-ups | model ms |\n"
                  "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n",
                  md);
            fputs("scene,unit,guard,resetup,weight_frac,setup_mults,max_lsb,rms_lsb,psnr_db,over_1lsb,cycles,setups,model_s\n",
                  csv);
            for (size_t i = 0; i < n; i++) {
                const row *r = &rows[i];
                char wt[16] = "-", k[16] = "-";
                if (strcmp(r->unit, "texel") == 0)
                    snprintf(wt, sizeof wt, "%u", r->wt);
                else
                    snprintf(k, sizeof k, "%u", r->resetup);
                fprintf(md, "| %s | %s | %u | %s | %s | %u | %.3f | %.4f | %.2f | %llu | %llu | %llu | %.2f |\n", r->scene,
                        r->unit, r->guard, k, wt, r->mults, r->e.max_lsb, r->e.rms_lsb, r->e.psnr_db,
                        (unsigned long long)r->e.over_one, (unsigned long long)r->cycles,
                        (unsigned long long)r->setups, r->seconds * 1e3);
                fprintf(csv, "%s,%s,%u,%s,%s,%u,%.6f,%.6f,%.4f,%llu,%llu,%llu,%.6f\n", r->scene, r->unit, r->guard,
                        strcmp(r->unit, "texel") == 0 ? "" : k, strcmp(r->unit, "texel") == 0 ? wt : "", r->mults,
                        r->e.max_lsb, r->e.rms_lsb, r->e.psnr_db, (unsigned long long)r->e.over_one,
                        (unsigned long long)r->cycles, (unsigned long long)r->setups, r->seconds);
            }
            if ((fclose(md) | fclose(csv)) != 0)
                rc = NP_EXIT_USAGE;
            else
                printf("report: %zu configurations; %s/error_runtime.{md,csv}, *_error_vs_{cycles,seconds}.svg, "
                       "*_scanline*.svg, images\n",
                       n, dir);
        }
    }
    free(rows);
    return rc;
}

int np_cmd_render(int argc, char **argv)
{
    opts o;
    int r = parse_opts(argc, argv, &o);
    if (r != 0)
        return r > 0 ? NP_EXIT_OK : NP_EXIT_USAGE;
    if (o.report)
        return report(&o);
    if (o.bench) {
        int rc = NP_EXIT_OK;
        for (unsigned i = 0; i < o.n_scenes && rc == NP_EXIT_OK; i++)
            rc = bench_scene(&o, o.scenes[i]);
        return rc;
    }
    hash_list got = { 0 }, golden = { 0 };
    int rc = NP_EXIT_OK;
    for (unsigned i = 0; i < o.n_scenes; i++) {
        int s = render_scene(&o, o.scenes[i], &got);
        if (s == NP_EXIT_USAGE) {
            rc = s;
            break;
        }
        if (s != NP_EXIT_OK)
            rc = s;
    }
    if (rc != NP_EXIT_USAGE && o.write_hashes) {
        if (hash_write(o.write_hashes, &got))
            rc = NP_EXIT_USAGE;
        else
            printf("hashes written to %s\n", o.write_hashes);
    }
    if (rc != NP_EXIT_USAGE && o.hashes) {
        if (hash_read(o.hashes, &golden))
            rc = NP_EXIT_USAGE;
        else if (hash_check(&golden, &got, o.hashes) > 0)
            rc = NP_EXIT_FAIL;
    }
    free(got.r);
    free(golden.r);
    if (rc == NP_EXIT_OK)
        printf("render: ok\n");
    else if (rc == NP_EXIT_FAIL)
        printf("render: FAILED\n");
    return rc;
}
