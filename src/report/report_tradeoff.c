/* SPDX-License-Identifier: MIT */
/* `noisepipe report tradeoff --scene S` (np_tradeoff.h). */
#include "np_tradeoff.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "np_common.h"
#include "np_fdiff.h"
#include "np_texreg.h"
#include "unit_span.h"
#include "np_outfile.h"
#include "np_plot.h"
#include "np_render.h"
#include "np_report.h"
#include "np_scene.h"
#include "np_unit.h"

/* The set-up engine sizes swept (P = setup_mults); texel's engine only sets up spans. */
static const unsigned fd_p[] = { 1, 2, 4, 8, 16 };
static const unsigned tx_p[] = { 1, 2, 4 };
static const unsigned sizes[] = { 256, 512, 1024, 2048 };
static const unsigned octaves[] = { 1, 2, 4, 8 };
enum { N_SIZE = sizeof sizes / sizeof sizes[0], N_OCT = sizeof octaves / sizeof octaves[0] };

/* One unit at one set-up engine size on one frame. */
typedef struct point {
    unsigned P;
    double gates, bound, measured; /* measured: max error against the float reference, LSB */
    uint64_t cycles, stalls;
} point;

/* The best (least gates x cycles) of a unit over its P values on one frame. */
typedef struct best {
    point p;
    double gc;
} best;

/*
 * Unit u configured by the scene (at the widths it sizes when
 * sc->size_registers, else the defaults) with setup_mults = P: gates, the
 * predicted bound (the unit's own over the scene's widest span plus the
 * registers'), cycles on frame fr. 0 or -1 with err.
 */
static int measure(const np_unit *u, const np_scene *sc, const np_render_frame *fr, unsigned P, point *pt,
                   char *err, size_t errlen)
{
    np_unit_cfg cfg;
    memset(&cfg, 0, sizeof cfg);
    int used = np_scene_cfg_unit(u, &cfg, sc, err, errlen);
    if (used <= 0) {
        if (used == 0)
            snprintf(err, errlen, "the unit does not render the scene");
        return -1;
    }
    char p[16];
    snprintf(p, sizeof p, "%u", P);
    if (np_unit_cfg_set(u, &cfg, "setup_mults", p, err, errlen) != 0)
        return -1;
    np_unit_cost c;
    if (np_unit_cost_compute(u, &cfg, &np_cost_default, &c, err, errlen) != 0)
        return -1;
    np_render_run run;
    memset(&run, 0, sizeof run);
    if (np_render_unit(fr, u, &cfg, 1, &run) != 0 || !run.have_cycles) {
        np_render_run_free(&run);
        snprintf(err, errlen, "the cycle model did not run");
        return -1;
    }
    pt->P = P;
    pt->gates = c.total;
    pt->bound = np_su_predicted_lsb(u, &cfg, sc->width);
    pt->cycles = run.cycles;
    pt->stalls = run.setup_stalls;
    pt->measured = run.err.max_lsb;
    np_render_run_free(&run);
    return 0;
}

/* Every P of unit u on frame fr; the best by gates x cycles (all within 1 LSB by their bound). */
static int sweep(const np_unit *u, const unsigned *ps, size_t nps, const np_scene *sc, const np_render_frame *fr,
                 point *all, best *b, char *err, size_t errlen)
{
    b->gc = (double)INFINITY;
    for (size_t i = 0; i < nps; i++) {
        if (measure(u, sc, fr, ps[i], &all[i], err, errlen) != 0)
            return -1;
        double gc = all[i].gates * (double)all[i].cycles;
        if (all[i].bound <= 1.0 && gc < b->gc) {
            b->gc = gc;
            b->p = all[i];
        }
    }
    if (!isfinite(b->gc)) {
        snprintf(err, errlen, "%s: no configuration within 1 LSB by its bound", u->name);
        return -1;
    }
    return 0;
}

/* The scene's texture with n octaves: its own first ones, then each further one at twice the last's scale. */
static void with_octaves(np_ref_texture *t, const np_ref_texture *src, unsigned n)
{
    *t = *src;
    t->n_oct = n;
    for (unsigned i = src->n_oct; i < n; i++) {
        t->oct[i] = t->oct[i - 1u];
        for (int a = 0; a < 3; a++)
            for (int b = 0; b < 3; b++)
                t->oct[i].m[a][b] *= 2.0;
    }
}

static void row(FILE *f, const char *what, const np_render_frame *fr, const best *fd, const best *tx)
{
    fprintf(f,
            "| %s | %llu | %u | %.0f | %llu | %llu | %.3g | %u | %.0f | %llu | %.3g | **%.2f** |\n", what,
            (unsigned long long)fr->pixels, fd->p.P, fd->p.gates, (unsigned long long)fd->p.cycles,
            (unsigned long long)fd->p.stalls, fd->gc, tx->p.P, tx->p.gates, (unsigned long long)tx->p.cycles, tx->gc,
            tx->gc / fd->gc);
}

static const char head[] = "| frame | pixels | fdiff P | gates | cycles | stalls | gates x cycles | texel P | gates | "
                           "cycles | gates x cycles | texel / fdiff |\n"
                           "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n";

static int write_svg(const char *dir, const char *name, const char *suffix, const char *xlabel, const double *x,
                     const double *yf, const double *yt, size_t n)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/tradeoff-%s-%s.svg", dir, name, suffix);
    np_outfile o;
    if (np_outfile_open(&o, path, "w") != 0) {
        np_err("report", "%s", o.err);
        return -1;
    }
    char title[160];
    snprintf(title, sizeof title, "%s: gates x cycles per frame (least over P), both within 1 LSB", name);
    np_plot p = { title, xlabel, "gates x cycles", 0, 0, 0, 0, 1, (double)NAN, (double)NAN, NULL, NULL };
    np_plot_series s[2] = { { "fdiff (forward differences)", "#1f77b4", x, yf, n, 1, 1 },
                            { "texel (per pixel)", "#d62728", x, yt, n, 1, 1 } };
    np_plot_svg(o.f, &p, s, 2);
    if (np_outfile_close(&o, 1) != 0) {
        np_err("report", "%s", o.err);
        return -1;
    }
    return 0;
}

int np_report_tradeoff(const char *dir, const char *scene_path)
{
    const np_unit *fd = np_unit_find("fdiff"), *tx = np_unit_find("texel");
    np_scene sc;
    char err[1024];
    if (!scene_path) {
        np_err("report", "tradeoff needs --scene SCENE.json");
        return NP_EXIT_USAGE;
    }
    if (!fd || !tx || !fd->cfg_scene || !tx->cfg_scene) {
        np_err("report", "tradeoff needs the fdiff and texel units");
        return NP_EXIT_USAGE;
    }
    if (np_scene_load(scene_path, &sc, err, sizeof err) != 0) {
        np_err("report", "%s", err);
        return NP_EXIT_USAGE;
    }
    np_outfile o;
    char path[4096];
    snprintf(path, sizeof path, "%s/tradeoff-%s.md", dir ? dir : ".", sc.name);
    if (np_outfile_open(&o, dir ? path : "-", "w") != 0) {
        np_err("report", "%s", o.err);
        np_scene_free(&sc);
        return NP_EXIT_USAGE;
    }
    FILE *f = o.f;
    const np_ref_texture tex0 = sc.tex;
    const unsigned w0 = sc.width, h0 = sc.height;
    sc.size_registers = 1; /* the tradeoff prices the scene-sized widths */
    point fdp[N_SIZE][5], txp[N_SIZE][3];
    best fb[N_SIZE + N_OCT], tb[N_SIZE + N_OCT];
    int skipped[N_SIZE + N_OCT] = { 0 };
    point dw[2][2];               /* 256²: [fdiff, texel][default widths, scene-sized] at P = 2 */
    char cfg_text[2][256] = { "", "" };
    char refused[2][1024] = { "", "" }; /* the default widths' refusal of the scene, per unit */
    double xs[N_SIZE], xo[N_OCT], yf[N_SIZE + N_OCT], yt[N_SIZE + N_OCT];
    uint64_t npx[N_SIZE];
    int rc = NP_EXIT_OK;
    fprintf(f, "# Forward differences against per-pixel evaluation: scene %s\n\n", sc.name);
    fprintf(f, "Generated by `noisepipe report tradeoff --scene %s`. Gates: NAND2 equivalents of the units' datapath "
               "declarations (cost model: [cost-model.md](cost-model.md)); cycles: the cycle-accurate models on the "
               "frame's span descriptors, back to back, no backpressure. Both units with their **registers sized by "
               "the scene** (`render --sized`: the fewest transform, quadric, index and guard bits whose predicted "
               "bound is <= 1 LSB; column bound: the unit's own over the frame's width plus the registers'); P = the "
               "set-up engine's multipliers (`setup_mults`), the one area-for-time knob of both, chosen per frame "
               "by the least gates x cycles.\n\n",
            scene_path);
    for (size_t i = 0; i < N_SIZE + N_OCT && rc == NP_EXIT_OK; i++) {
        np_render_frame fr;
        int by_size = i < N_SIZE;
        if (by_size) {
            sc.width = sc.height = sizes[i];
            sc.tex = tex0;
        } else {
            sc.width = w0;
            sc.height = h0;
            with_octaves(&sc.tex, &tex0, octaves[i - N_SIZE]);
            double mmax = 0;
            for (unsigned oc = 0; oc < sc.tex.n_oct; oc++)
                for (int a = 0; a < 3; a++)
                    for (int b = 0; b < 3; b++)
                        mmax = fmax(mmax, fabs(sc.tex.oct[oc].m[a][b]));
            if (mmax >= 128.0) { /* the transform register has at most 7 integer bits (|m| < 128) */
                skipped[i] = 1;
                xo[i - N_SIZE] = octaves[i - N_SIZE];
                yf[i] = yt[i] = (double)NAN;
                continue;
            }
        }
        if (np_render_prepare(&sc, &fr, err, sizeof err) != 0) {
            np_err("report", "%s: %s", scene_path, err);
            rc = NP_EXIT_USAGE;
            break;
        }
        if (np_render_reference(&fr) != 0) { /* the units' measured error is against it */
            np_err("report", "out of memory");
            np_render_frame_free(&fr);
            rc = NP_EXIT_USAGE;
            break;
        }
        point fa[5], ta[3];
        if (sweep(fd, fd_p, 5, &sc, &fr, fa, &fb[i], err, sizeof err) != 0 ||
            sweep(tx, tx_p, 3, &sc, &fr, ta, &tb[i], err, sizeof err) != 0) {
            np_err("report", "%s: %s", scene_path, err);
            rc = NP_EXIT_USAGE;
        }
        if (rc == NP_EXIT_OK && i == 0) {
            /* The default widths against the scene-sized ones, P = 2 (the default engine). */
            for (int k = 0; k < 2 && rc == NP_EXIT_OK; k++) {
                const np_unit *u = k ? tx : fd;
                for (int sized = 0; sized < 2 && rc == NP_EXIT_OK; sized++) {
                    sc.size_registers = sized;
                    if (measure(u, &sc, &fr, 2, &dw[k][sized], err, sizeof err) != 0) {
                        if (!sized) { /* a scene only the scene-sized registers render */
                            snprintf(refused[k], sizeof refused[k], "%s", err);
                            memset(&dw[k][0], 0, sizeof dw[k][0]);
                            continue;
                        }
                        np_err("report", "%s: %s", scene_path, err);
                        rc = NP_EXIT_USAGE;
                    }
                }
                sc.size_registers = 1;
                np_unit_cfg c;
                memset(&c, 0, sizeof c);
                if (rc == NP_EXIT_OK && np_scene_cfg_unit(u, &c, &sc, err, sizeof err) > 0)
                    np_unit_cfg_format_opt(u, &c, NP_UNIT_FMT_COMMAS | NP_UNIT_FMT_NO_SCENE, cfg_text[k],
                                           sizeof cfg_text[k]);
            }
        }
        if (by_size) {
            memcpy(fdp[i], fa, sizeof fa);
            memcpy(txp[i], ta, sizeof ta);
            xs[i] = sizes[i];
            npx[i] = fr.pixels;
        } else {
            xo[i - N_SIZE] = octaves[i - N_SIZE];
        }
        yf[i] = fb[i].gc;
        yt[i] = tb[i].gc;
        if (rc == NP_EXIT_OK)
            fprintf(stderr, "report tradeoff %s: %ux%u, %u octave%s done\n", sc.name, sc.width, sc.height,
                    sc.tex.n_oct, sc.tex.n_oct == 1 ? "" : "s");
        np_render_frame_free(&fr);
    }
    if (rc == NP_EXIT_OK) {
        const np_fdiff_cfg dflt = np_fdiff_cfg_default();
        fprintf(f, "## Image size (%u octave%s, the scene's texture)\n\n%s", tex0.n_oct, tex0.n_oct == 1 ? "" : "s",
                head);
        for (size_t i = 0; i < N_SIZE; i++) {
            char what[32];
            snprintf(what, sizeof what, "%u²", sizes[i]);
            sc.width = sc.height = sizes[i];
            np_render_frame fake = { 0 };
            fake.pixels = npx[i];
            row(f, what, &fake, &fb[i], &tb[i]);
        }
        fprintf(f, "\n## Default widths against scene-sized ones (%ux%u, P = 2)\n\n"
                   "fdiff's default guard bits (%u) are sized for 65,536-pixel spans; the scene-sized configuration "
                   "is fdiff `%s`, texel `%s`. The set-up engine's multiplier keeps the 117 + I bits the single exact "
                   "rounding of the set-up values reads, whatever G; I shrinks it a little.\n\n"
                   "| unit | widths | gates | cycles | set-up stalls | gates x cycles | bound (LSB) | measured max (LSB) |\n"
                   "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: |\n",
                sizes[0], sizes[0], dflt.guard, cfg_text[0], cfg_text[1]);
        for (int k = 0; k < 2; k++)
            for (int sized = 0; sized < 2; sized++)
                if (!sized && refused[k][0])
                    fprintf(f, "| %s | default | refused: %s | | | | | |\n", k ? "texel" : "fdiff", refused[k]);
                else
                    fprintf(f, "| %s | %s | %.0f | %llu | %llu | %.3g | %.3f | %.3f |\n", k ? "texel" : "fdiff",
                        sized ? "scene-sized" : "default", dw[k][sized].gates, (unsigned long long)dw[k][sized].cycles,
                        (unsigned long long)dw[k][sized].stalls, dw[k][sized].gates * (double)dw[k][sized].cycles,
                        dw[k][sized].bound, dw[k][sized].measured);
        /*
         * Set-up multipliers (issue 14): fdiff's stall cycles and gates at
         * each P with the scene-sized widths, against the default unit (P = 2,
         * default widths); the P with the least gates x cycles is chosen.
         */
        fprintf(f, "\n## Set-up multipliers (fdiff, %ux%u, scene-sized widths)\n\n"
                   "| P | gates | gates / default unit | set-up stall cycles | stalls / default unit's | cycles | "
                   "gates x cycles |\n| ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n"
                   "| 2, default widths | %.0f | 1.00 | %llu | 1.00 | %llu | %.3g |\n",
                sizes[0], sizes[0], dw[0][0].gates, (unsigned long long)dw[0][0].stalls,
                (unsigned long long)dw[0][0].cycles, dw[0][0].gates * (double)dw[0][0].cycles);
        for (size_t k = 0; k < 5; k++) {
            const point *q = &fdp[0][k];
            fprintf(f, "| %s%u%s | %.0f | %.2f | %llu | %.3g | %llu | %.3g |\n", q->P == fb[0].p.P ? "**" : "", q->P,
                    q->P == fb[0].p.P ? " (chosen)**" : "", q->gates, dw[0][0].gates ? q->gates / dw[0][0].gates : 0.0,
                    (unsigned long long)q->stalls, dw[0][0].stalls ? (double)q->stalls / (double)dw[0][0].stalls : 0.0,
                    (unsigned long long)q->cycles, q->gates * (double)q->cycles);
        }
        fprintf(f, "\n## Octave count (%ux%u; octaves beyond the scene's at twice the previous scale)\n\n%s", w0, h0,
                head);
        for (size_t i = 0; i < N_OCT; i++) {
            char what[32];
            snprintf(what, sizeof what, "%u octave%s", octaves[i], octaves[i] == 1 ? "" : "s");
            if (skipped[N_SIZE + i]) {
                fprintf(f, "| %s | — | the octaves' scale reaches 128 or more: outside the transform register (at "
                           "most 7 integer bits) | | | | | | | | | |\n",
                        what);
                continue;
            }
            np_render_frame fake = { 0 };
            fake.pixels = npx[0];
            row(f, what, &fake, &fb[N_SIZE + i], &tb[N_SIZE + i]);
        }
        fprintf(f, "\n## Every P at each image size\n\n| frame | unit | P | gates | cycles | set-up stalls | gates x "
                   "cycles | bound (LSB) | measured max (LSB) |\n| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
        for (size_t i = 0; i < N_SIZE; i++) {
            for (size_t k = 0; k < 5; k++)
                fprintf(f, "| %u² | fdiff | %u | %.0f | %llu | %llu | %.3g | %.3f | %.3f |\n", sizes[i], fdp[i][k].P,
                        fdp[i][k].gates, (unsigned long long)fdp[i][k].cycles, (unsigned long long)fdp[i][k].stalls,
                        fdp[i][k].gates * (double)fdp[i][k].cycles, fdp[i][k].bound, fdp[i][k].measured);
            for (size_t k = 0; k < 3; k++)
                fprintf(f, "| %u² | texel | %u | %.0f | %llu | %llu | %.3g | %.3f | %.3f |\n", sizes[i], txp[i][k].P,
                        txp[i][k].gates, (unsigned long long)txp[i][k].cycles, (unsigned long long)txp[i][k].stalls,
                        txp[i][k].gates * (double)txp[i][k].cycles, txp[i][k].bound, txp[i][k].measured);
        }
        if (dir) {
            fprintf(f, "\nPlots: [tradeoff-%s-size.svg](tradeoff-%s-size.svg), [tradeoff-%s-octaves.svg]"
                       "(tradeoff-%s-octaves.svg).\n",
                    sc.name, sc.name, sc.name, sc.name);
            double ox[N_OCT], of[N_OCT], ot[N_OCT];
            size_t no = 0;
            for (size_t i = 0; i < N_OCT; i++)
                if (!skipped[N_SIZE + i]) {
                    ox[no] = xo[i];
                    of[no] = yf[N_SIZE + i];
                    ot[no++] = yt[N_SIZE + i];
                }
            if (write_svg(dir, sc.name, "size", "image width = height (pixels)", xs, yf, yt, N_SIZE) != 0 ||
                write_svg(dir, sc.name, "octaves", "octaves", ox, of, ot, no) != 0)
                rc = NP_EXIT_USAGE;
        }
    }
    if (np_outfile_close(&o, rc == NP_EXIT_OK) != 0) {
        np_err("report", "%s", o.err);
        rc = NP_EXIT_USAGE;
    }
    if (rc == NP_EXIT_OK && dir)
        fprintf(stderr, "wrote %s\n", path);
    sc.tex = tex0;
    np_scene_free(&sc);
    return rc;
}
