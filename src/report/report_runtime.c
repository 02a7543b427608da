/* SPDX-License-Identifier: MIT */
/*
 * noisepipe report runtime: error against run time. Every unit that renders
 * a scene (np_render_units) is rendered over each of its sweeps
 * (np_unit_span.sweeps): max error against the float reference, cycles per
 * frame from the cycle-accurate model, bit-exact model time; a table, plots
 * and images for docs/plots (docs/render.md). Also `noisepipe render --report`.
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "np_common.h"
#include "np_outfile.h"
#include "np_image.h"
#include "np_plot.h"
#include "np_report_runtime.h"
#include "np_report_scan.h"

/*
 * The table's configuration columns: every key a registered unit's sweeps
 * set (swept or fixed), "-" where a row's unit has no such key. The keys
 * of the seed units come first, in this order and with these headings;
 * any other key follows under its own name. The CSV heading is the key.
 */
static const struct { const char *key, *md; } known[] = {
    { "guard", "guard G" },
    { "resetup", "K" },
    { "weight_frac", "weight bits" },
    { "setup_mults", "set-up mults P" },
};
enum { N_KNOWN = sizeof known / sizeof known[0], MAX_COLS = 16, MAX_SERIES = 16 };

static struct {
    char key[32];
    const char *md;
} cols[MAX_COLS];
static unsigned n_cols;

/* Does some sweep of a registered unit set key (as its key or in fixed)? */
static int swept(const char *key, size_t len)
{
    const np_unit *u;
    for (size_t i = 0; (u = np_unit_at(i)) != NULL; i++)
        for (unsigned s = 0; u->span && s < u->span->n_sweeps; s++) {
            const np_unit_sweep *w = &u->span->sweeps[s];
            if (strlen(w->key) == len && strncmp(w->key, key, len) == 0)
                return 1;
            for (const char *p = w->fixed; p && *p; p += strcspn(p, ","), p += *p == ',')
                if (strcspn(p, "=") == len && strncmp(p, key, len) == 0)
                    return 1;
        }
    return 0;
}

static void add_col(const char *key, size_t len, const char *md)
{
    for (unsigned c = 0; c < n_cols; c++)
        if (strlen(cols[c].key) == len && strncmp(cols[c].key, key, len) == 0)
            return;
    if (n_cols < MAX_COLS && len < sizeof cols[0].key) {
        snprintf(cols[n_cols].key, sizeof cols[n_cols].key, "%.*s", (int)len, key);
        cols[n_cols].md = md ? md : cols[n_cols].key;
        n_cols++;
    }
}

static void find_cols(void)
{
    n_cols = 0;
    for (unsigned k = 0; k < N_KNOWN; k++)
        if (swept(known[k].key, strlen(known[k].key)))
            add_col(known[k].key, strlen(known[k].key), known[k].md);
    const np_unit *u;
    for (size_t i = 0; (u = np_unit_at(i)) != NULL; i++)
        for (unsigned s = 0; u->span && s < u->span->n_sweeps; s++) {
            const np_unit_sweep *w = &u->span->sweeps[s];
            add_col(w->key, strlen(w->key), NULL);
            for (const char *p = w->fixed; p && *p; p += strcspn(p, ","), p += *p == ',')
                add_col(p, strcspn(p, "="), NULL);
        }
}

typedef struct row {
    char scene[64];
    const char *unit;
    char val[MAX_COLS][16]; /* "" where the unit has no such key */
    unsigned plot;        /* the series (np_unit_sweep.plot) */
    np_render_err e;
    uint64_t cycles, setups;
    double seconds;
} row;

/* The value of key in "key=value,key=value" (cfg text), or "". */
static void cfg_value(const char *text, const char *key, char *v, size_t n)
{
    size_t kl = strlen(key);
    v[0] = '\0';
    for (const char *p = text; p && *p; p = strchr(p, ',') ? strchr(p, ',') + 1 : NULL)
        if (strncmp(p, key, kl) == 0 && p[kl] == '=') {
            size_t l = strcspn(p + kl + 1, ",");
            snprintf(v, n, "%.*s", (int)l, p + kl + 1);
            return;
        }
}

/* One row: the unit's configuration (cfg text) and what its run measured. */
static void put_row(row *w, const char *scene, const np_render_unit_cfg *uc, unsigned plot, const np_render_run *r,
                    uint64_t cycles, double seconds)
{
    snprintf(w->scene, sizeof w->scene, "%s", scene);
    w->unit = uc->u->name;
    for (unsigned c = 0; c < n_cols; c++)
        cfg_value(uc->text, cols[c].key, w->val[c], sizeof w->val[c]);
    w->plot = plot;
    w->e = r->err;
    w->cycles = cycles;
    w->setups = r->span_setups + r->cell_setups + r->interval_setups;
    w->seconds = seconds;
}

/* Output files go through np_outfile (temporary + rename): an interrupted report leaves no half-written file. */
static int open_out(const char *dir, const char *name, np_outfile *o)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    if (np_outfile_open(o, path, "w") != 0) {
        np_err("report", "%s", o->err);
        return -1;
    }
    return 0;
}

static int close_out(np_outfile *o, int ok)
{
    if (np_outfile_close(o, ok) != 0) {
        np_err("report", "%s", o->err);
        return -1;
    }
    return ok ? 0 : -1;
}

static double floor_log(double v) { return v < 0.01 ? 0.01 : v; }


/* The sweeps' legends, by plot index: "LABEL first..last". */
static unsigned series_labels(const np_render_unit_cfg *us, int nu, char (*labels)[64])
{
    unsigned n = 0;
    for (int i = 0; i < nu; i++)
        for (unsigned s = 0; s < us[i].u->span->n_sweeps; s++) {
            const np_unit_sweep *w = &us[i].u->span->sweeps[s];
            if (w->plot >= MAX_SERIES)
                continue;
            snprintf(labels[w->plot], 64, "%s %u..%u", w->label, w->values[0], w->values[w->n_values - 1]);
            n = w->plot + 1u > n ? w->plot + 1u : n;
        }
    return n;
}

static int plot_errors(const char *dir, const char *scene, const np_render_unit_cfg *us, int nu, const row *rows,
                       size_t n, int by_seconds)
{
    static const char *const colours[] = { "#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                                           "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf" };
    char labels[MAX_SERIES][64];
    np_plot_series s[MAX_SERIES];
    unsigned ns = series_labels(us, nu, labels);
    double *xs = malloc((n + 1) * sizeof *xs), *ys = malloc((n + 1) * sizeof *ys);
    if (!xs || !ys) {
        free(xs);
        free(ys);
        return -1;
    }
    size_t m = 0;
    for (unsigned k = 0; k < ns; k++) {
        size_t m0 = m;
        for (size_t i = 0; i < n; i++) {
            const row *r = &rows[i];
            if (strcmp(r->scene, scene) != 0 || r->plot != k)
                continue;
            xs[m] = by_seconds ? r->seconds * 1e3 : (double)r->cycles;
            ys[m] = floor_log(r->e.max_lsb);
            m++;
        }
        s[k] = (np_plot_series){ labels[k], colours[k % (sizeof colours / sizeof colours[0])], xs + m0, ys + m0,
                                 m - m0, 0, 1 };
    }
    char title[160], name[128];
    snprintf(title, sizeof title, "%s: max error against %s", scene, by_seconds ? "model time" : "cycles per frame");
    np_plot p = { title, by_seconds ? "bit-exact model time per frame (ms)" : "cycles per frame",
                  "max error vs float reference (8-bit LSB)", 0, 0, 0.01, 1000.0, 1, NAN, 1.0, NULL,
                  "1 LSB" };
    snprintf(name, sizeof name, "%s_error_vs_%s.svg", scene, by_seconds ? "seconds" : "cycles");
    np_outfile o;
    int rc = -1;
    if (open_out(dir, name, &o) == 0) {
        np_plot_svg(o.f, &p, s, ns);
        rc = close_out(&o, 1);
    }
    free(xs);
    free(ys);
    return rc;
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
        char lab[96], title[200], name[128], ylab[128];
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
        np_outfile o;
        if (open_out(dir, name, &o) != 0)
            rc = -1;
        else {
            np_plot_svg(o.f, &p, ser, 2);
            rc = close_out(&o, 1);
        }
        free(cx);
        free(cy);
        free(y);
    }
    np_render_scan_free(&s);
    return rc;
}

/* The best bit-exact model time of rep renders; *keep is the first render. NAN on failure. */
static double time_model(const np_render_frame *fr, const np_render_unit_cfg *uc, unsigned rep, np_render_run *keep)
{
    double best = HUGE_VAL;
    for (unsigned i = 0; i < rep; i++) {
        np_render_run r;
        if (np_render_unit(fr, uc->u, &uc->cfg, 0, &r))
            return NAN;
        best = fmin(best, r.model_seconds);
        if (i == 0)
            *keep = r;
        else
            np_render_run_free(&r);
    }
    return best;
}

/* uc: base with "fixed" and (with_key) key = value over its keys; 0, or -1 when that is not a valid configuration. */
static int sweep_cfg(const np_render_unit_cfg *base, const np_unit_sweep *w, int with_key, unsigned value,
                     np_render_unit_cfg *uc)
{
    char err[256], more[256];
    *uc = *base;
    if (with_key)
        snprintf(more, sizeof more, "%s%s%s=%u", w->fixed ? w->fixed : "", w->fixed ? "," : "", w->key, value);
    else
        snprintf(more, sizeof more, "%s", w->fixed ? w->fixed : "");
    return np_render_unit_reconfigure(uc, more, err, sizeof err);
}

/* One unit's sweeps on the frame: rows appended at rows[*n]. 0, or -1. */
static int sweep_unit(const np_render_frame *fr, const np_render_unit_cfg *base, unsigned rep, row *rows, size_t *n)
{
    const np_unit_span *sp = base->u->span;
    for (unsigned s = 0; s < sp->n_sweeps; s++) {
        const np_unit_sweep *w = &sp->sweeps[s];
        np_render_unit_cfg uc;
        np_render_run cyc;
        if (w->cycles_fixed) { /* the cycles of every value: one cycle run at the fixed configuration */
            if (sweep_cfg(base, w, 0, 0, &uc) || np_render_unit(fr, uc.u, &uc.cfg, 1, &cyc))
                return -1;
        }
        for (unsigned v = 0; v < w->n_values; v++) {
            if (sweep_cfg(base, w, 1, w->values[v], &uc))
                continue;
            np_render_run r;
            row *o = &rows[(*n)++];
            if (w->cycles_fixed) {
                double t = time_model(fr, &uc, rep, &r);
                put_row(o, fr->sc->name, &uc, w->plot, &r, cyc.cycles, t);
            } else {
                if (np_render_unit(fr, uc.u, &uc.cfg, 1, &r))
                    return -1;
                put_row(o, fr->sc->name, &uc, w->plot, &r, r.cycles, 0.0);
                np_render_run_free(&r);
                o->seconds = time_model(fr, &uc, rep, &r);
            }
            np_render_run_free(&r);
        }
        if (w->cycles_fixed)
            np_render_run_free(&cyc);
    }
    return 0;
}

/* The error heat map of unit uc as DIR/SCENE_NAME_err.png (docs keep the PNG only). */
static void error_png(const char *dir, const np_render_frame *fr, const char *name, const uint8_t *rgb)
{
    char base[4096], err[1024];
    snprintf(base, sizeof base, "%s/%s_%s_err", dir, fr->sc->name, name);
    np_render_write_error(base, fr, name, rgb, 0, err, sizeof err);
    snprintf(base, sizeof base, "%s/%s_%s_err.exr", dir, fr->sc->name, name);
    remove(base);
}

/* Images of the units at their report configurations: DIR/SCENE_{ref,UNIT,UNIT_err,UNIT_EXTRA_err}.png. */
static int report_images(const char *dir, const np_render_frame *fr, const np_render_unit_cfg *us, int nu)
{
    const np_scene *sc = fr->sc;
    char base[4096], err[1024];
    uint8_t *ref8 = malloc((size_t)sc->width * sc->height * 3);
    if (ref8) {
        np_render_ref_rgb8(fr, ref8);
        snprintf(base, sizeof base, "%s/%s_ref.png", dir, sc->name);
        np_image_write_png(base, sc->width, sc->height, ref8, err, sizeof err);
        free(ref8);
    }
    for (int i = 0; i < nu; i++) {
        np_render_run r;
        if (np_render_unit(fr, us[i].u, &us[i].cfg, 0, &r))
            return -1;
        snprintf(base, sizeof base, "%s/%s_%s.png", dir, sc->name, us[i].u->name);
        np_image_write_png(base, sc->width, sc->height, r.rgb, err, sizeof err);
        error_png(dir, fr, us[i].u->name, r.rgb);
        np_render_run_free(&r);
    }
    /* What a unit looks like with too few bits, where it names such a configuration. */
    for (int i = 0; i < nu; i++) {
        const np_unit_span *sp = us[i].u->span;
        np_render_unit_cfg few = us[i];
        np_render_run r;
        char name[96];
        if (!sp->extra_cfg || np_render_unit_reconfigure(&few, sp->extra_cfg, err, sizeof err) ||
            np_render_unit(fr, few.u, &few.cfg, 0, &r))
            continue;
        snprintf(name, sizeof name, "%s_%s", us[i].u->name, sp->extra_name);
        error_png(dir, fr, name, r.rgb);
        np_render_run_free(&r);
    }
    return 0;
}

static int write_table(const char *dir, const row *rows, size_t n)
{
    np_outfile omd, ocsv;
    if (open_out(dir, "error_runtime.md", &omd) != 0)
        return -1;
    if (open_out(dir, "error_runtime.csv", &ocsv) != 0) {
        close_out(&omd, 0);
        return -1;
    }
    FILE *md = omd.f, *csv = ocsv.f;
    fputs("<!-- generated by `noisepipe report runtime -o docs/plots` (part of `noisepipe report all -o docs`) -->\n| scene | unit |", md);
    for (unsigned c = 0; c < n_cols; c++)
        fprintf(md, " %s |", cols[c].md);
    fputs(" max LSB | RMS LSB | PSNR dB | >1 LSB samples | cycles/frame | set-ups | model ms |\n| --- | --- |", md);
    for (unsigned c = 0; c < n_cols; c++)
        fputs(" ---: |", md);
    fputs(" ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n", md);
    fputs("scene,unit", csv);
    for (unsigned c = 0; c < n_cols; c++)
        fprintf(csv, ",%s", cols[c].key);
    fputs(",max_lsb,rms_lsb,psnr_db,over_1lsb,cycles,setups,model_s\n", csv);
    for (size_t i = 0; i < n; i++) {
        const row *r = &rows[i];
        fprintf(md, "| %s | %s |", r->scene, r->unit);
        fprintf(csv, "%s,%s", r->scene, r->unit);
        for (unsigned c = 0; c < n_cols; c++) {
            fprintf(md, " %s |", r->val[c][0] ? r->val[c] : "-");
            fprintf(csv, ",%s", r->val[c]);
        }
        fprintf(md, " %.3f | %.4f | %.2f | %llu | %llu | %llu | %.2f |\n", r->e.max_lsb, r->e.rms_lsb, r->e.psnr_db,
                (unsigned long long)r->e.over_one, (unsigned long long)r->cycles, (unsigned long long)r->setups,
                r->seconds * 1e3);
        fprintf(csv, ",%.6f,%.6f,%.4f,%llu,%llu,%llu,%.6f\n", r->e.max_lsb, r->e.rms_lsb, r->e.psnr_db,
                (unsigned long long)r->e.over_one, (unsigned long long)r->cycles, (unsigned long long)r->setups,
                r->seconds);
    }
    int rc = close_out(&omd, 1);
    return (close_out(&ocsv, rc == 0) | rc) != 0 ? -1 : 0;
}

/* Is unit name among the units that render the scene? */
static int renders(const np_render_unit_cfg *us, int nu, const char *name)
{
    for (int i = 0; i < nu; i++)
        if (strcmp(us[i].u->name, name) == 0)
            return 1;
    return 0;
}

/* Rows the sweeps of the units that render scene sc can write. */
static size_t max_rows(const np_render_unit_cfg *us, int nu)
{
    size_t n = 0;
    for (int i = 0; i < nu; i++)
        for (unsigned s = 0; s < us[i].u->span->n_sweeps; s++)
            n += us[i].u->span->sweeps[s].n_values;
    return n;
}

int np_report_runtime(const char *dir, const char *const *scenes, unsigned n_scenes, unsigned rep,
                      np_render_spec_fn spec, const void *ctx)
{
    static const char *const seeds[2] = { "embedded:wood", "embedded:marble" };
    if (n_scenes == 0) { /* default: both seed scenes */
        scenes = seeds;
        n_scenes = 2;
    }
    if (np_mkdir_p(dir) != 0) {
        np_err("report", "%s: cannot create", dir);
        return NP_EXIT_USAGE;
    }
    row *rows = NULL;
    size_t n = 0;
    int rc = NP_EXIT_OK;
    find_cols();
    for (unsigned si = 0; si < n_scenes && rc == NP_EXIT_OK; si++) {
        np_scene sc;
        np_render_frame fr;
        np_render_unit_cfg us[NP_RENDER_MAX_UNITS];
        char err[1024];
        if (np_scene_load(scenes[si], &sc, err, sizeof err)) {
            np_err("report", "%s", err);
            rc = NP_EXIT_USAGE;
            break;
        }
        int nu = -1;
        if (np_render_prepare(&sc, &fr, err, sizeof err) == 0 &&
            ((nu = np_render_units(&sc, spec, ctx, us, err, sizeof err)) < 0 || np_render_reference(&fr)))
            np_render_frame_free(&fr), nu = -1;
        row *more = nu < 0 ? NULL : realloc(rows, (n + max_rows(us, nu) + 1) * sizeof *rows);
        if (!more) {
            np_err("report", "%s", nu < 0 ? err : "out of memory");
            np_scene_free(&sc);
            rc = NP_EXIT_USAGE;
            break;
        }
        rows = more;
        fprintf(stderr, "report: %s ...\n", sc.name);
        if (report_images(dir, &fr, us, nu))
            rc = NP_EXIT_USAGE;
        for (int i = 0; i < nu && rc == NP_EXIT_OK; i++)
            if (sweep_unit(&fr, &us[i], rep, rows, &n))
                rc = NP_EXIT_USAGE;
        if (rc == NP_EXIT_OK &&
            (plot_errors(dir, sc.name, us, nu, rows, n, 0) || plot_errors(dir, sc.name, us, nu, rows, n, 1)))
            rc = NP_EXIT_USAGE;
        /* The seed's figures 10 and 11: forward differences against per pixel, where the scene has both. */
        if (rc == NP_EXIT_OK && renders(us, nu, "fdiff") && renders(us, nu, "texel") &&
            (plot_scan(dir, &sc, &fr, 0) || plot_scan(dir, &sc, &fr, np_fdiff_cfg_default().guard)))
            rc = NP_EXIT_USAGE;
        np_render_frame_free(&fr);
        np_scene_free(&sc);
    }
    if (rc == NP_EXIT_OK) {
        if (write_table(dir, rows, n))
            rc = NP_EXIT_USAGE;
        else
            printf("report: %zu configurations; %s/error_runtime.{md,csv}, *_error_vs_{cycles,seconds}.svg, "
                   "*_scanline*.svg, images\n",
                   n, dir);
    }
    free(rows);
    return rc;
}
