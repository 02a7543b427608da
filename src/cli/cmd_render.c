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

#include "np_common.h"
#include "np_outfile.h"
#include "np_cmd.h"
#include "np_image.h"
#include "np_noisetex.h"
#include "np_render.h"
#include "np_texreg.h"
#include "unit_span.h"
#include "np_unit.h"
#include "render_cli.h"


static const char *const CMD = "render";
enum { MAX_SCENES = 16 };

static void usage(FILE *f)
{
    fputs("usage: noisepipe render [options] [SCENE.json ...]\n"
          "\n"
          "Render each scene (default: the wood scene built into the program, a copy of\n"
          "vectors/scenes/wood.json; --report: wood and marble; a SCENE may be a file or\n"
          "embedded:wood / embedded:marble)\n"
          "with the float reference and with every unit that renders it (the registry's span\n"
          "units whose scene configuration accepts it: fdiff, forward differences after\n"
          "Kameya & Hart, and texel, per pixel) from the same span descriptors, write the\n"
          "images (OpenEXR float + PNG) and error images, and print the error of each unit\n"
          "against the reference (8-bit colour LSB) with its cycles per frame and model time.\n"
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
          "  --sized              registers sized by the scene: the fewest transform, quadric,\n"
          "                       index and guard bits whose bound is <= 1 LSB (default: the\n"
          "                       units' default widths, the golden images)\n"
          "  --hashes FILE        compare the images' hashes with FILE (vectors/images/hashes.txt);\n"
          "                       exit 1 on any change\n"
          "  --write-hashes FILE  write the images' hashes to FILE\n"
          "  --ppm                also write PPM files (their sha256sum is the hash)\n"
          "  --frames N           a scene whose texture reads a 4-D noise unit (texture.noise):\n"
          "                       render frames 0..N-1 (default: the scene's frames)\n"
          "  --aa m=2|3|4,...     the adaptive supersampling report of seed 001 instead\n"
          "                       (noisepipe render --aa m=3 --help; docs/aacount.md)\n"
          "  --report DIR         the same as noisepipe report runtime -o DIR (error against\n"
          "                       run time over each unit's sweeps, plots and images)\n"
          "  --bench              time the float reference and every unit's models side by side\n"
          "  --repeat N           runs per timing in --bench and --report (default 5 / 3)\n"
          "  --hatch-table        a scene with \"hatch\": B16/C16/B64/C64 cycles a pixel beside the\n"
          "                       paper's Table 1, coverage checked bit-identical to brute force\n"
          "  --zoom-frames N      a scene with \"hatch\": also a zoom sequence of N frames (PNG),\n"
          "                       the camera zoomed 2^L over it (--zoom-levels L, default 8)\n"
          "\n"
          "exit status: 0 ok, 1 a check failed, 2 bad usage or bad input\n",
          f);
}

enum { MAX_UNITS = 16, UNIT_SPEC_MAX = 512 };

typedef struct opts {
    const char *out;
    /* --unit-config: the keys given for registry unit i (np_unit_at), joined by commas; the unit's block configured from them. */
    char unit_spec[MAX_UNITS][UNIT_SPEC_MAX];
    np_unit_cfg ucfg[MAX_UNITS];
    double tolerance;
    int check, cycles, ppm, bench, sized, hatch_table;
    unsigned zoom_frames;
    double zoom_levels;
    const char *hashes, *write_hashes, *report;
    unsigned repeat;
    unsigned frames; /* --frames (0: the scene's) */
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

/* Index of unit name in the registry (np_unit_at), or -1. */
static int unit_index(const char *name)
{
    const np_unit *u;
    for (int i = 0; (u = np_unit_at((size_t)i)) != NULL && i < MAX_UNITS; i++)
        if (strcmp(u->name, name) == 0)
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
        const np_unit *u;
        for (size_t k = 0; (u = np_unit_at(k)) != NULL; k++)
            snprintf(known + strlen(known), sizeof known - strlen(known), "%s%s", k ? ", " : "", u->name);
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
    const np_unit *u;
    for (int i = 0; (u = np_unit_at((size_t)i)) != NULL && i < MAX_UNITS; i++) {
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
    return 0;
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
    o->zoom_levels = 8;
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
        } else if ((r = opt_value(argc, argv, &i, "--zoom-frames", &v))) {
            uint64_t n;
            if (r < 0)
                return -1;
            if (np_parse_u64(v, 1, 4096, &n)) {
                np_err(CMD, "--zoom-frames %s: expected an integer in 1..4096", v);
                return -1;
            }
            o->zoom_frames = (unsigned)n;
        } else if ((r = opt_value(argc, argv, &i, "--zoom-levels", &v))) {
            char *end;
            if (r < 0)
                return -1;
            o->zoom_levels = strtod(v, &end);
            if (*v == '\0' || *end != '\0' || !(o->zoom_levels > 0 && o->zoom_levels <= 60)) {
                np_err(CMD, "--zoom-levels %s: expected a number in (0, 60]", v);
                return -1;
            }
        } else if (strcmp(argv[i], "--hatch-table") == 0) {
            o->hatch_table = 1;
        } else if ((r = opt_value(argc, argv, &i, "--frames", &v))) {
            uint64_t n;
            if (r < 0)
                return -1;
            if (np_parse_u64(v, 1, 100, &n)) {
                np_err(CMD, "--frames %s: expected an integer in 1..100", v);
                return -1;
            }
            o->frames = (unsigned)n;
        } else if (strcmp(argv[i], "--no-check") == 0) {
            o->check = 0;
        } else if (strcmp(argv[i], "--sized") == 0) {
            o->sized = 1;
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

/* --- One scene --- */

/* The configuration --unit-config gives unit u (over the scene's). */
static const char *unit_spec(const void *ctx, const np_unit *u)
{
    const opts *o = ctx;
    int i = unit_index(u->name);
    return i < 0 ? NULL : o->unit_spec[i];
}

/*
 * A lit image's bound (scene light.image): the lighting stage's 0.513 LSB
 * plus the unlit colour's error (argued in np_gbuf.h, "Lighting").
 */
#define LIGHT_BOUND_LSB 0.513

/* The predicted bound of unit uc's image of scene sc (the texture's, plus the lighting when it shades the image). */
static double predicted_lsb(const np_render_unit_cfg *uc, const np_scene *sc)
{
    return np_su_predicted_lsb(uc->u, &uc->cfg, sc->width) + (sc->light_image ? LIGHT_BOUND_LSB : 0.0);
}

static void print_run(const np_render_unit_cfg *uc, const np_scene *sc, const np_render_run *r)
{
    const char *unit = uc->u->name, *cfg = uc->text;
    char psnr[32];
    if (isinf(r->err.psnr_db))
        snprintf(psnr, sizeof psnr, "inf");
    else
        snprintf(psnr, sizeof psnr, "%.2f", r->err.psnr_db);
    printf("  %-6s max %.3f LSB (at %u,%u), RMS %.4f LSB, mean %+.4f LSB, PSNR %s dB, >1 LSB: %llu of %llu samples\n",
           unit, r->err.max_lsb, r->err.max_x, r->err.max_y, r->err.rms_lsb, r->err.mean_lsb, psnr,
           (unsigned long long)r->err.over_one, (unsigned long long)r->err.samples);
    printf("         beyond correct rounding: %llu of %llu samples differ from the reference rounded to 8 bits"
           " (max %u LSB)\n",
           (unsigned long long)r->err.over_cr, (unsigned long long)r->err.samples, r->err.max_cr);
    printf("         config %s\n", cfg);
    /*
     * The predicted bound beside the measured error (issue 10): the unit's
     * own over the scene's widest span plus the registers' rounding over its
     * coordinates, the bound the scene check accepted.
     */
    const np_texreg_scene_bound *b = uc->u->span ? np_ut_texture_bound(np_su_texture(uc->u->span, &uc->cfg)) : NULL;
    const double pred = uc->u->span ? predicted_lsb(uc, sc) : (double)NAN;
    if (b && !isnan(pred)) {
        const np_tex_regs *rg = np_ut_regs(np_su_texture(uc->u->span, &uc->cfg));
        const double light = sc->light_image ? LIGHT_BOUND_LSB : 0.0;
        char lit[48] = "";
        if (sc->light_image)
            snprintf(lit, sizeof lit, " + lighting %.3f", light);
        printf("         bound: predicted %.3f LSB (unit %.3f + registers %.3g%s), measured max %.3f LSB%s;"
               " registers: quadric s%u Q.%u, transform s%u Q.%u\n",
               pred, pred - b->reg_lsb - light, b->reg_lsb, lit, r->err.max_lsb,
               r->err.max_lsb <= pred ? "" : "  OVER THE BOUND",
               np_tex_k_bits(rg), np_tex_k_frac(rg), np_tex_m_bits(rg), np_tex_m_frac(rg));
    }
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

/*
 * The images of one unit: base_UNIT.{exr,png}, base_UNIT_lit.png,
 * base_UNIT_err.{exr,png} (against the reference), base_UNIT_err_cr.{exr,png}
 * (against the correctly rounded reference), with --ppm base_UNIT.ppm.
 */
static int write_unit_images(const opts *o, const np_render_frame *fr, const char *unit, const uint8_t *rgb,
                             char *err, size_t errlen)
{
    const np_scene *sc = fr->sc;
    char base[4096];
    snprintf(base, sizeof base, "%s/%s_%s", o->out, sc->name, unit);
    if (np_render_write_rgb8(base, fr, unit, rgb, err, errlen))
        return -1;
    snprintf(base, sizeof base, "%s/%s_%s_err", o->out, sc->name, unit);
    if (np_render_write_error(base, fr, unit, rgb, 0, err, errlen))
        return -1;
    snprintf(base, sizeof base, "%s/%s_%s_err_cr", o->out, sc->name, unit);
    if (np_render_write_error(base, fr, unit, rgb, 1, err, errlen))
        return -1;
    if (o->ppm) {
        snprintf(base, sizeof base, "%s/%s_%s.ppm", o->out, sc->name, unit);
        if (np_image_write_ppm(base, sc->width, sc->height, rgb, err, errlen))
            return -1;
    }
    return 0;
}

static uint8_t round8(double v)
{
    double r = floor(v + 0.5);
    return (uint8_t)(r < 0.0 ? 0.0 : r > 255.0 ? 255.0 : r);
}

/*
 * A scene whose texture reads a 4-D noise unit (texture.noise, np_noisetex.h):
 * frames 0..N-1 through the G-buffer, each shaded on the unit's bit-exact
 * model (its cycle model cross-checked) and the float reference;
 * DIR/NAME_UNIT-fNN.png and DIR/NAME_ref-fNN.png, hashes "UNIT-fNN" and
 * "ref-fNN". Returns NP_EXIT_*.
 */
static int render_noise_scene(const opts *o, const np_scene *sc, const char *path, hash_list *hashes)
{
    np_noisetex t;
    np_gbuf g;
    char err[1024], base[4096], hex[65], img[16], cfgtxt[256];
    const np_unit *nu = np_unit_find(sc->noise.unit);
    int ui = nu ? unit_index(nu->name) : -1;
    if (np_noisetex_init(&t, sc, ui >= 0 ? &o->ucfg[ui] : NULL, err, sizeof err) != 0) {
        np_err(CMD, "%s", err);
        return NP_EXIT_USAGE;
    }
    if (np_gbuf_build(sc, 1, &g, err, sizeof err) != 0) {
        np_err(CMD, "%s: %s", path, err);
        return NP_EXIT_USAGE;
    }
    if (np_mkdir_p(o->out) != 0) {
        np_err(CMD, "%s: cannot create: %s", o->out, strerror(errno));
        np_gbuf_free(&g);
        return NP_EXIT_USAGE;
    }
    np_unit_cfg_format_opt(t.u, &t.cfg, NP_UNIT_FMT_COMMAS, cfgtxt, sizeof cfgtxt);
    unsigned frames = o->frames ? o->frames : sc->noise.frames;
    size_t npix = (size_t)sc->width * sc->height;
    uint8_t *rgb = malloc(npix * 3), *ref8 = malloc(npix * 3);
    double *ref = malloc(npix * 3 * sizeof *ref);
    int rc = NP_EXIT_OK;
    if (!rgb || !ref8 || !ref) {
        np_err(CMD, "out of memory");
        rc = NP_EXIT_USAGE;
        goto out;
    }
    printf("scene %s (%s): %ux%u, %llu pixels, %u octave%s of %s (%s), time w = 0x%04x + f * 0x%04x (u16 Q8.8), "
           "%u frame%s\n",
           sc->name, path, sc->width, sc->height, (unsigned long long)g.covered_pixels, sc->tex.n_oct,
           sc->tex.n_oct == 1 ? "" : "s", t.u->name, cfgtxt, sc->noise.w0, sc->noise.dw, frames,
           frames == 1 ? "" : "s");
    for (unsigned f = 0; f < frames; f++) {
        np_noisetex_stats st;
        if (np_noisetex_frame(&t, &g, f, o->cycles, rgb, ref, NULL, &st, err, sizeof err) != 0) {
            np_err(CMD, "%s", err);
            rc = NP_EXIT_USAGE;
            goto out;
        }
        for (size_t i = 0; i < npix * 3; i++)
            ref8[i] = round8(ref[i]);
        printf("  frame %2u  w 0x%04x  texture max %.3f LSB, >1 LSB: %llu of %llu channels", f, st.w, st.max_lsb,
               (unsigned long long)st.over_one, (unsigned long long)(3 * st.samples));
        if (sc->light_image)
            printf(" (lit %.3f)", st.max_lit_lsb);
        printf("; %llu %s transactions", (unsigned long long)st.transactions, t.u->name);
        if (o->cycles)
            printf(", cycle model %llu clocks%s", (unsigned long long)st.cycles,
                   st.cycle_mismatch ? "  CYCLE MODEL DIFFERS" : "");
        printf("\n");
        if (st.cycle_mismatch) {
            np_err(CMD, "%s: frame %u: %s's cycle-accurate model differs from its bit-exact model", sc->name, f,
                   t.u->name);
            rc = NP_EXIT_FAIL;
        }
        if (o->check && st.max_lsb > o->tolerance) {
            printf("  FAIL: frame %u max error %.3f LSB exceeds the tolerance %.3f LSB\n", f, st.max_lsb,
                   o->tolerance);
            rc = NP_EXIT_FAIL;
        }
        for (int k = 0; k < 2; k++) {
            const char *who = k ? "ref" : t.u->name;
            const uint8_t *im = k ? ref8 : rgb;
            snprintf(base, sizeof base, "%s/%s_%s-f%02u.png", o->out, sc->name, who, f);
            if (np_image_write_png(base, sc->width, sc->height, im, err, sizeof err) != 0) {
                np_err(CMD, "%s", err);
                rc = NP_EXIT_USAGE;
                goto out;
            }
            if (o->ppm) {
                snprintf(base, sizeof base, "%s/%s_%s-f%02u.ppm", o->out, sc->name, who, f);
                if (np_image_write_ppm(base, sc->width, sc->height, im, err, sizeof err) != 0) {
                    np_err(CMD, "%s", err);
                    rc = NP_EXIT_USAGE;
                    goto out;
                }
            }
            np_image_hash(sc->width, sc->height, im, hex);
            snprintf(img, sizeof img, "%.8s-f%02u", who, f % 100u);
            np_render_hash_add(hashes, sc->name, img, hex, k ? "-" : cfgtxt);
        }
    }
    printf("  images: %s/%s_{%s,ref}-f00..f%02u.png\n", o->out, sc->name, t.u->name, frames - 1u);
out:
    free(rgb);
    free(ref8);
    free(ref);
    np_gbuf_free(&g);
    return rc;
}

/* Render one scene with every unit that renders it; appends its hashes. Returns NP_EXIT_*. */
static int render_scene(const opts *o, const char *path, hash_list *hashes)
{
    np_scene sc;
    np_render_frame fr;
    np_render_unit_cfg us[NP_RENDER_MAX_UNITS];
    np_render_run runs[NP_RENDER_MAX_UNITS];
    char err[1024], hex[65];
    uint8_t *ref8 = NULL;
    int nu = 0;
    if (np_scene_load(path, &sc, err, sizeof err)) {
        np_err(CMD, "%s", err);
        return NP_EXIT_USAGE;
    }
    sc.size_registers = o->sized;
    if (o->frames && !sc.noise.present) {
        np_err(CMD, "--frames: scene %s has no time axis (its texture has no \"noise\" section)", sc.name);
        np_scene_free(&sc);
        return NP_EXIT_USAGE;
    }
    if (sc.noise.present) {
        int r = render_noise_scene(o, &sc, path, hashes);
        np_scene_free(&sc);
        return r;
    }
    if (np_render_prepare(&sc, &fr, err, sizeof err)) {
        np_err(CMD, "%s", err);
        np_scene_free(&sc);
        return NP_EXIT_USAGE;
    }
    int rc = NP_EXIT_OK;
    memset(runs, 0, sizeof runs);
    if ((nu = np_render_units(&sc, unit_spec, o, us, err, sizeof err)) < 0) {
        np_err(CMD, "%s", err);
        nu = 0;
        rc = NP_EXIT_USAGE;
        goto out;
    }
    if (np_render_reference(&fr)) {
        np_err(CMD, "out of memory");
        rc = NP_EXIT_USAGE;
        goto out;
    }
    for (int i = 0; i < nu; i++)
        if (np_render_unit(&fr, us[i].u, &us[i].cfg, o->cycles, &runs[i])) {
            np_err(CMD, "out of memory");
            rc = NP_EXIT_USAGE;
            goto out;
        }
    printf("scene %s (%s): %ux%u, %llu pixels in %zu spans (longest %u), %u octave%s; reference %.4f s\n",
           sc.name, path, sc.width, sc.height, (unsigned long long)fr.pixels, fr.n_spans, fr.longest,
           sc.tex.n_oct, sc.tex.n_oct == 1 ? "" : "s", fr.ref_seconds);
    for (int i = 0; i < nu; i++)
        print_run(&us[i], &sc, &runs[i]);
    for (int i = 0; i < nu; i++)
        if (runs[i].cycle_mismatch) {
            np_err(CMD, "%s: %s: the cycle-accurate model differs from the bit-exact model", sc.name, us[i].u->name);
            rc = NP_EXIT_FAIL;
        }
    if (o->check) {
        for (int i = 0; i < nu; i++) {
            if (runs[i].err.max_lsb > o->tolerance) {
                printf("  FAIL: %s max error %.3f LSB exceeds the tolerance %.3f LSB\n", us[i].u->name,
                       runs[i].err.max_lsb, o->tolerance);
                rc = NP_EXIT_FAIL;
            } else if (us[i].u->span && np_ut_texture_bound(np_su_texture(us[i].u->span, &us[i].cfg)) &&
                       runs[i].err.max_lsb > predicted_lsb(&us[i], &sc)) {
                /* A measured error above the predicted bound is a bug in the bound (or the model). */
                printf("  FAIL: %s max error %.3f LSB exceeds its predicted bound %.3f LSB\n", us[i].u->name,
                       runs[i].err.max_lsb, predicted_lsb(&us[i], &sc));
                rc = NP_EXIT_FAIL;
            }
        }
    }
    if (np_mkdir_p(o->out) != 0) {
        np_err(CMD, "%s: cannot create: %s", o->out, strerror(errno));
        rc = NP_EXIT_USAGE;
        goto out;
    }
    char base[4096], names[512] = "ref", errs[512] = "";
    snprintf(base, sizeof base, "%s/%s_ref", o->out, sc.name);
    int bad = np_render_write_ref(base, &fr, err, sizeof err);
    for (int i = 0; i < nu && !bad; i++) {
        bad = write_unit_images(o, &fr, us[i].u->name, runs[i].rgb, err, sizeof err);
        snprintf(names + strlen(names), sizeof names - strlen(names), ",%s", us[i].u->name);
        snprintf(errs + strlen(errs), sizeof errs - strlen(errs), ",%s_err,%s_err_cr", us[i].u->name, us[i].u->name);
    }
    ref8 = malloc((size_t)sc.width * sc.height * 3);
    if (bad || !ref8) {
        np_err(CMD, "%s", bad ? err : "out of memory");
        rc = NP_EXIT_USAGE;
        goto out;
    }
    np_render_ref_rgb8(&fr, ref8);
    if (o->ppm) {
        snprintf(base, sizeof base, "%s/%s_ref.ppm", o->out, sc.name);
        if (np_image_write_ppm(base, sc.width, sc.height, ref8, err, sizeof err)) {
            np_err(CMD, "%s", err);
            rc = NP_EXIT_USAGE;
            goto out;
        }
    }
    printf("  images: %s/%s_{%s%s}.{exr,png}, shaded views %s/%s_{%s}_lit.png\n", o->out, sc.name, names, errs,
           o->out, sc.name, names);
    np_image_hash(sc.width, sc.height, ref8, hex);
    np_render_hash_add(hashes, sc.name, "ref", hex, "-");
    for (int i = 0; i < nu; i++) {
        np_image_hash(sc.width, sc.height, runs[i].rgb, hex);
        np_render_hash_add(hashes, sc.name, us[i].u->name, hex, us[i].text);
    }
    if (sc.hatch.present) {
        int h = np_render_hatch_scene(&sc, o->out, o->ppm, o->cycles, (unsigned)o->hatch_table, o->zoom_frames,
                                      o->zoom_levels, hashes);
        if (h != NP_EXIT_OK && (rc == NP_EXIT_OK || h == NP_EXIT_USAGE))
            rc = h;
    } else if (o->hatch_table || o->zoom_frames) {
        np_err(CMD, "%s: --hatch-table and --zoom-frames need a scene with a \"hatch\" section", sc.name);
        rc = NP_EXIT_USAGE;
    }
out:
    free(ref8);
    for (int i = 0; i < nu; i++)
        np_render_run_free(&runs[i]);
    np_render_frame_free(&fr);
    np_scene_free(&sc);
    return rc;
}

int np_cmd_render(int argc, char **argv)
{
    for (int i = 1; i < argc; i++) /* the adaptive supersampling report has options of its own */
        if (strcmp(argv[i], "--aa") == 0)
            return np_render_aa_main(argc, argv);
    opts o;
    int r = parse_opts(argc, argv, &o);
    if (r != 0)
        return r > 0 ? NP_EXIT_OK : NP_EXIT_USAGE;
    if (o.report) /* the alias of `noisepipe report runtime` */
        return np_report_runtime(o.report, o.scenes, o.n_scenes, o.repeat ? o.repeat : 3, unit_spec, &o);
    if (o.bench) {
        int rc = NP_EXIT_OK;
        for (unsigned i = 0; i < o.n_scenes && rc == NP_EXIT_OK; i++)
            rc = np_render_bench(o.scenes[i], o.repeat ? o.repeat : 5, unit_spec, &o);
        return rc;
    }
    /* Before any work, and before the image library names a file inside it. */
    struct stat st;
    if (stat(o.out, &st) == 0 && !S_ISDIR(st.st_mode)) {
        np_err(CMD, "-o %s: not a folder: render writes several images into a folder", o.out);
        return NP_EXIT_USAGE;
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
        if (np_render_hash_write(o.write_hashes, &got))
            rc = NP_EXIT_USAGE;
        else
            printf("hashes written to %s\n", o.write_hashes);
    }
    if (rc != NP_EXIT_USAGE && o.hashes) {
        if (np_render_hash_read(o.hashes, &golden))
            rc = NP_EXIT_USAGE;
        else if (np_render_hash_check(&golden, &got, o.hashes) > 0)
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
