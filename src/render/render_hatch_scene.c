/* SPDX-License-Identifier: MIT */
/*
 * noisepipe render on a scene with a "hatch" section (docs/hatch.md, "Scenes"):
 * the hatched image through the unit hatch, its hash, the B/C table on the
 * scene (--hatch-table) and a zoom sequence (--zoom-frames).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <unistd.h>

#include "np_common.h"
#include "np_hatch_render.h"
#include "np_image.h"
#include "np_render_tools.h"

static const char *const CMD = "render";

/* The unit's configuration as text (the hash list's configuration column). */
static void cfg_text(const np_unit_cfg *c, unsigned coverage, double tile, char *s, size_t n)
{
    char k[192];
    np_hatch_render_cfg_text(c, k, sizeof k);
    snprintf(s, n, "%s,mode=%s,tile_pixels=%g", k, coverage ? "coverage" : "brute", tile);
}

static void print_frame(const np_scene_hatch *h, unsigned coverage, const np_hatch_frame *f)
{
    unsigned per = f->brute_cycles;
    printf("  hatch  %llu pixels, levels %d..%d; max %.4f LSB from the float reference (%llu over 1 LSB)\n",
           (unsigned long long)f->samples, f->level_min, f->level_max, f->ref_max, (unsigned long long)f->ref_over);
    printf("         iterative unit (P = %u): %llu cycles, %.3f a pixel (%s; brute force %u a pixel)\n", h->lanes,
           (unsigned long long)f->iter_cycles, f->samples ? (double)f->iter_cycles / (double)f->samples : 0.0,
           coverage ? "coverage lists" : "brute force", per);
    if (coverage)
        printf("         coverage lists at the pixels: mean %.3f entries a layer, max %u\n", f->list_mean, f->list_max);
    if (f->pipe_cycles)
        printf("         unrolled cycle model (%s): %llu cycles (%llu pixels + latency %u), outputs %s; bit-exact model %.3f s\n",
               coverage ? "coverage slots" : "every seed", (unsigned long long)f->pipe_cycles,
               (unsigned long long)f->samples, f->pipe_depth,
               f->pipe_mismatch ? "DIFFER" : "equal", f->seconds);
}

/*
 * B16 / C16 / B64 / C64 on the scene beside the paper's Table 1: both sets,
 * brute force and coverage, images compared bit for bit. 1 when they differ.
 */
static int table1(const np_scene *sc, const np_scene_hatch *h)
{
    static const double paper[4] = { 4.80, 1.66, 16.6, 1.81 };
    static const char *const sets[2] = { "best16", "best64" };
    double cpp[4] = { 0 };
    unsigned bad = 0;
    char err[512];
    printf("  Table 1 on %s (%u layers, %s, P = 1; cycles of an iterative unit a pixel; the paper: ms a frame at 1920x1200,"
           " GeForce 780):\n", sc->name, h->layers, h->fade ? "one by one" : "smooth");
    printf("  | | cycles/pixel | list mean (max) | differing pixels vs brute | paper ms |\n");
    for (unsigned si = 0; si < 2; si++) {
        np_scene_hatch q = *h;
        q.set = si ? 3u : 1u;
        q.lanes = 1;
        np_unit_cfg c;
        np_hatch_frame fb, fc;
        if (np_hatch_render_cfg(&q, NULL, &c, err, sizeof err) ||
            np_hatch_render(sc, &c, 0, h->tile_pixels, 0, &fb, err, sizeof err)) {
            np_err(CMD, "%s", err);
            return -1;
        }
        if (np_hatch_render(sc, &c, 1, h->tile_pixels, 0, &fc, err, sizeof err)) {
            np_err(CMD, "%s", err);
            np_hatch_frame_free(&fb);
            return -1;
        }
        size_t diff = 0;
        for (size_t p = 0; p < (size_t)fb.w * fb.h; p++)
            diff += fb.rgb[3 * p] != fc.rgb[3 * p];
        bad += diff != 0;
        cpp[2 * si] = (double)fb.iter_cycles / (double)fb.samples;
        cpp[2 * si + 1] = (double)fc.iter_cycles / (double)fc.samples;
        printf("  | B%s | %.2f | - | - | %.2f |\n", sets[si] + 4, cpp[2 * si], paper[2 * si]);
        printf("  | C%s | %.3f | %.3f (%u) | %zu of %llu | %.2f |\n", sets[si] + 4, cpp[2 * si + 1], fc.list_mean,
               fc.list_max, diff, (unsigned long long)fc.samples, paper[2 * si + 1]);
        np_hatch_frame_free(&fb);
        np_hatch_frame_free(&fc);
    }
    printf("  B/C: ours %.2fx (16 seeds) and %.2fx (64 seeds); the paper's 2.89x and 9.17x\n", cpp[0] / cpp[1],
           cpp[2] / cpp[3]);
    double rate = 1920.0 * 1200.0 * cpp[3] / 1.81e-3;
    printf("  C64 at 1920x1200 in the paper's 1.81 ms: %.3g seed-cycles a second, %.1f units at 1 GHz (%.1f at 500 MHz),"
           " P = 1\n", rate, rate / 1e9, rate / 5e8);
    printf("  coverage against brute force: %s\n", bad ? "IMAGES DIFFER" : "bit-identical (4 x 16 and 4 x 64 seeds)");
    return bad ? 1 : 0;
}

/* The rendered frames' measure of the tracked strokes (zoom, below). */
typedef struct zoom_stats {
    unsigned seen, over, blank;
    double max_px;
} zoom_stats;

/* A signed Q32.96 difference in UV as a double. */
static double uv_diff(np_u128 a, np_u128 b) { return ldexp((double)(np_s128)(a - b), -96); }

/*
 * One tracked stroke (layer 0, seed idx at this frame's level) in a rendered
 * frame: the covered pixel of polygon poly nearest its UV centre, and in the
 * (2R+1)^2 window around it the stroke's alpha at each pixel's own inputs
 * (x_s, tone, the polygon's level words, as the frame was hatched). Counted
 * when the window lies wholly on the polygon: the alpha-weighted centroid of
 * the pixels' UV against the centre, in pixels (a pixel's UV size: the
 * square root of the area its UV steps right and down span).
 */
static void rendered_centroid(const np_unit_cfg *c, const np_hatch_frame *fr, uint32_t poly, const np_hatch_lod *d,
                              np_u128 cu, np_u128 cv, unsigned idx, zoom_stats *st)
{
    enum { R = 12 };
    const np_unit_strokes *hs = np_hatch_unit()->strokes;
    size_t best = 0;
    double bd = -1;
    for (size_t p = 0; p < (size_t)fr->w * fr->h; p++)
        if (fr->poly[p] == poly) {
            double du = uv_diff(fr->uv[0][p], cu), dv = uv_diff(fr->uv[1][p], cv), e = du * du + dv * dv;
            if (bd < 0 || e < bd) {
                bd = e;
                best = p;
            }
        }
    unsigned x0 = (unsigned)(best % fr->w), y0 = (unsigned)(best / fr->w);
    if (bd < 0 || x0 < R + 1 || y0 < R + 1 || x0 + R + 1 >= fr->w || y0 + R + 1 >= fr->h)
        return;
    /* The pixel's size in UV: the steps to the right and down neighbours. */
    size_t pr = best + 1, pd = best + fr->w;
    if (fr->poly[pr] != poly || fr->poly[pd] != poly)
        return;
    double a = uv_diff(fr->uv[0][pr], fr->uv[0][best]), b = uv_diff(fr->uv[0][pd], fr->uv[0][best]);
    double e = uv_diff(fr->uv[1][pr], fr->uv[1][best]), g = uv_diff(fr->uv[1][pd], fr->uv[1][best]);
    double px = sqrt(fabs(a * g - b * e));
    double sw = 0, su = 0, sv = 0;
    for (unsigned y = y0 - R; y <= y0 + R; y++)
        for (unsigned x = x0 - R; x <= x0 + R; x++) {
            size_t q = (size_t)y * fr->w + x;
            if (fr->poly[q] != poly)
                return; /* not wholly on the face */
            const uint64_t in[5] = { hs->xs(fr->uv[0][q], d->level), hs->xs(fr->uv[1][q], d->level), fr->tone[q], d->pm,
                                     d->om };
            np_unit_stroke z;
            hs->stroke(c->bytes, in, 0, idx, &z);
            double w = (double)z.alpha;
            sw += w;
            su += w * uv_diff(fr->uv[0][q], cu);
            sv += w * uv_diff(fr->uv[1][q], cv);
        }
    st->seen++;
    if (!(sw > 0)) {
        st->blank++;
        return;
    }
    double off = sqrt((su / sw) * (su / sw) + (sv / sw) * (sv / sw)) / px;
    st->max_px = off > st->max_px ? off : st->max_px;
    st->over += off > 1.0;
}

/*
 * The zoom sequence: frames f = 0 .. n - 1 with the camera's height (or focal
 * length) scaled by 2^(levels f / n) about its target, each hatched and
 * written. Counted: the stroke centres of layer 0 at frame 0's level in the
 * seed tile under the image centre (N of them), each evaluated at every
 * frame's level and m of that polygon as the renderer computed them: a centre
 * off its UV point (|r| > 2 ulps at the seed it has become) or a level alpha
 * lower than the frame before is counted. And in the rendered frames
 * (rendered_centroid): each tracked stroke wholly on the face, its centroid
 * over its pixels against its UV centre; a centroid more than 1 px off, or a
 * stroke with no ink in its window, is counted.
 */
static int zoom(const np_scene *sc0, const np_unit_cfg *c, unsigned coverage, double tile, unsigned frames,
                double levels, const char *out, char *err, size_t errlen)
{
    np_scene sc = *sc0;
    const np_unit_strokes *st = np_hatch_unit()->strokes;
    np_unit_stroke_info info;
    st->info(c->bytes, &info);
    unsigned n = info.seeds;
    np_u128 cu[64], cvv[64];
    uint32_t prev[64];
    int level0 = 0;
    uint32_t poly0 = NP_GBUF_NONE;
    unsigned moved = 0, drops = 0, off = 0, lev_lo = 0, lev_hi = 0;
    zoom_stats rs = { 0, 0, 0, 0.0 };
    for (unsigned f = 0; f < frames; f++) {
        double s = exp2(-levels * (double)f / (double)frames);
        if (sc0->cam.perspective)
            sc.cam.focal = sc0->cam.focal / s;
        else
            sc.cam.height = sc0->cam.height * s;
        np_hatch_frame fr;
        if (np_hatch_render(&sc, c, coverage, tile, 0, &fr, err, errlen))
            return -1;
        size_t pc = (size_t)(fr.h / 2) * fr.w + fr.w / 2;
        char path[4096];
        snprintf(path, sizeof path, "%s/%s_hatch_zoom_%03u.png", out, sc.name, f);
        if (np_image_write_png(path, fr.w, fr.h, fr.rgb, err, errlen)) {
            np_hatch_frame_free(&fr);
            return -1;
        }
        if (f == 0) {
            if (!fr.covered[pc]) {
                snprintf(err, errlen, "%s: the image centre is not covered: nothing to zoom into", sc.name);
                np_hatch_frame_free(&fr);
                return -1;
            }
            poly0 = fr.poly[pc];
            level0 = fr.lod[poly0].level;
            /* The seed tile at level0 under the centre pixel: its N stroke centres in UV (Q32.96, rounded down). */
            unsigned sh = (unsigned)(64 + level0 + 32); /* tile index bits of x_uv at this level */
            for (unsigned i = 0; i < n; i++) {
                np_u128 tu = fr.uv[0][pc] >> sh << sh, tv = fr.uv[1][pc] >> sh << sh;
                np_u128 su, sv;
                st->centre(c->bytes, 0, i, &su, &sv);
                cu[i] = tu + (level0 >= 0 ? su << level0 : su >> -level0);
                cvv[i] = tv + (level0 >= 0 ? sv << level0 : sv >> -level0);
                prev[i] = 0;
            }
            lev_hi = (unsigned)(level0 + 64);
        }
        if (fr.lod[poly0].level == INT32_MIN) {
            off++;
            np_hatch_frame_free(&fr);
            continue;
        }
        const np_hatch_lod *d = &fr.lod[poly0];
        lev_lo = (unsigned)(d->level + 64);
        for (unsigned i = 0; i < n; i++) {
            const uint64_t in[5] = { st->xs(cu[i], d->level), st->xs(cvv[i], d->level), 255, d->pm, d->om };
            np_unit_stroke z;
            st->stroke(c->bytes, in, 0, (i + (unsigned)(level0 - d->level)) % n, &z);
            moved += z.ru < -2 || z.ru > 2 || z.rv < -2 || z.rv > 2;
            drops += z.am < prev[i];
            prev[i] = z.am;
            rendered_centroid(c, &fr, poly0, d, cu[i], cvv[i], (i + (unsigned)(level0 - d->level)) % n, &rs);
        }
        np_hatch_frame_free(&fr);
        if (isatty(2))
            fprintf(stderr, "\r  zoom frame %u of %u", f + 1, frames);
    }
    if (isatty(2))
        fprintf(stderr, "\n");
    printf("  zoom: %u frames over %g levels (levels %d .. %d on polygon %u) written as %s/%s_hatch_zoom_NNN.png\n",
           frames, levels, (int)lev_hi - 64, (int)lev_lo - 64, poly0, out, sc.name);
    printf("  zoom: %u stroke centres of layer 0 tracked: %u frame-centres off their UV point, %u alpha drops"
           " (%u frames without the polygon)\n", n, moved, drops, off);
    printf("  zoom: in the rendered frames, %u stroke-frames wholly on the face: the stroke's alpha-weighted centroid"
           " over its pixels at most %.3f px from its UV centre, %u over 1 px, %u without ink\n", rs.seen, rs.max_px,
           rs.over, rs.blank);
    return moved || drops || off || rs.over || rs.blank ? 1 : 0;
}

int np_render_hatch_scene(const np_scene *sc, const char *out, int ppm, int cycles, unsigned table, unsigned frames,
                          double levels, hash_list *hashes)
{
    char err[1024], cfgs[256], hex[65], path[4096];
    np_unit_cfg c;
    np_hatch_frame f;
    const np_scene_hatch *h = &sc->hatch;
    if (np_hatch_render_cfg(h, NULL, &c, err, sizeof err) ||
        np_hatch_render(sc, &c, h->coverage, h->tile_pixels, NP_HATCH_RENDER_REF | (cycles ? NP_HATCH_RENDER_PIPE : 0u),
                        &f, err, sizeof err)) {
        np_err(CMD, "%s: %s", sc->name, err);
        return NP_EXIT_USAGE;
    }
    int rc = NP_EXIT_OK;
    cfg_text(&c, h->coverage, h->tile_pixels, cfgs, sizeof cfgs);
    printf("  hatch  config %s\n", cfgs);
    print_frame(h, h->coverage, &f);
    if (f.pipe_mismatch) {
        np_err(CMD, "%s: hatch: the cycle-accurate model differs from the image", sc->name);
        rc = NP_EXIT_FAIL;
    }
    if (f.ref_over) {
        printf("  FAIL: hatch: %llu pixels more than 1 LSB from the float reference\n", (unsigned long long)f.ref_over);
        rc = NP_EXIT_FAIL;
    }
    snprintf(path, sizeof path, "%s/%s_hatch.png", out, sc->name);
    if (np_image_write_png(path, f.w, f.h, f.rgb, err, sizeof err)) {
        np_err(CMD, "%s", err);
        np_hatch_frame_free(&f);
        return NP_EXIT_USAGE;
    }
    if (ppm) {
        snprintf(path, sizeof path, "%s/%s_hatch.ppm", out, sc->name);
        if (np_image_write_ppm(path, f.w, f.h, f.rgb, err, sizeof err)) {
            np_err(CMD, "%s", err);
            np_hatch_frame_free(&f);
            return NP_EXIT_USAGE;
        }
    }
    printf("  images: %s/%s_hatch.png\n", out, sc->name);
    np_image_hash(f.w, f.h, f.rgb, hex);
    np_render_hash_add(hashes, sc->name, "hatch", hex, cfgs);
    np_hatch_frame_free(&f);
    if (table) {
        int t = table1(sc, h);
        if (t < 0)
            return NP_EXIT_USAGE;
        if (t > 0)
            rc = NP_EXIT_FAIL;
    }
    if (frames) {
        int z = zoom(sc, &c, h->coverage, h->tile_pixels, frames, levels, out, err, sizeof err);
        if (z < 0) {
            np_err(CMD, "%s", err);
            return NP_EXIT_USAGE;
        }
        if (z > 0)
            rc = NP_EXIT_FAIL;
    }
    return rc;
}
