/* SPDX-License-Identifier: MIT */
/* noisepipe render --bench: the float reference and every unit that renders the scene, side by side (render_cli.h). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "np_common.h"
#include "np_render_tools.h"

/* Best time of n calls of unit i's bit-exact render (i < 0: the float reference); NAN on failure. */
static double best_of(unsigned n, np_render_frame *fr, const np_render_unit_cfg *uc)
{
    double best = HUGE_VAL;
    for (unsigned i = 0; i < n; i++) {
        double t0 = np_now();
        np_render_run r;
        int rc = uc ? np_render_unit(fr, uc->u, &uc->cfg, 0, &r) : np_render_reference(fr);
        if (uc && rc == 0)
            np_render_run_free(&r);
        if (rc)
            return NAN;
        best = fmin(best, np_now() - t0);
    }
    return best;
}

/* One table row: a label, then a value per unit. */
static void row_u64(const char *label, const uint64_t *v, int n)
{
    printf("  %-34s", label);
    for (int i = 0; i < n; i++)
        printf(" %12llu", (unsigned long long)v[i]);
}

static void row_f(const char *label, const char *fmt, const double *v, int n)
{
    printf("  %-34s", label);
    for (int i = 0; i < n; i++)
        printf(fmt, v[i]);
}

int np_render_bench(const char *path, unsigned rep, np_render_spec_fn spec, const void *ctx)
{
    np_scene sc;
    np_render_frame fr;
    np_render_unit_cfg us[NP_RENDER_MAX_UNITS];
    np_render_run runs[NP_RENDER_MAX_UNITS];
    double t[NP_RENDER_MAX_UNITS], v[NP_RENDER_MAX_UNITS];
    uint64_t c[NP_RENDER_MAX_UNITS];
    char err[1024];
    if (np_scene_load(path, &sc, err, sizeof err)) {
        np_err("render", "%s", err);
        return NP_EXIT_USAGE;
    }
    int nu = np_render_prepare(&sc, &fr, err, sizeof err) ? -1 : np_render_units(&sc, spec, ctx, us, err, sizeof err);
    if (nu <= 0) {
        np_err("render", "%s", nu < 0 ? err : "no unit renders the scene");
        if (nu == 0)
            np_render_frame_free(&fr);
        np_scene_free(&sc);
        return NP_EXIT_USAGE;
    }
    double tr = best_of(rep, &fr, NULL);
    int ok = 1;
    for (int i = 0; i < nu; i++)
        t[i] = best_of(rep, &fr, &us[i]);
    for (int i = 0; i < nu; i++)
        ok &= np_render_unit(&fr, us[i].u, &us[i].cfg, 1, &runs[i]) == 0;
    if (!ok) {
        np_err("render", "out of memory");
        np_render_frame_free(&fr);
        np_scene_free(&sc);
        return NP_EXIT_USAGE;
    }
    const int z = nu - 1; /* the ratio column: the last unit over the first */
    char ratio[64];
    snprintf(ratio, sizeof ratio, "%s/%s", us[z].u->name, us[0].u->name);
    printf("bench %s: %ux%u, %llu pixels, %zu spans, %u octave%s (best of %u runs)\n", sc.name, sc.width, sc.height,
           (unsigned long long)fr.pixels, fr.n_spans, sc.tex.n_oct, sc.tex.n_oct == 1 ? "" : "s", rep);
    printf("  %-34s", "");
    for (int i = 0; i < nu; i++)
        printf(" %12s", us[i].u->name);
    printf(" %10s\n", ratio);
    row_f("bit-exact model, s per frame", " %12.5f", t, nu);
    printf(" %10.2f\n", t[z] / t[0]);
    for (int i = 0; i < nu; i++)
        v[i] = t[i] * 1e9 / (double)fr.pixels;
    row_f("  ns per pixel", " %12.1f", v, nu);
    printf("\n");
    for (int i = 0; i < nu; i++)
        c[i] = runs[i].cycles;
    row_u64("hardware cycles per frame", c, nu);
    printf(" %10.2f\n", (double)c[z] / (double)c[0]);
    for (int i = 0; i < nu; i++)
        v[i] = (double)runs[i].cycles / (double)fr.pixels;
    row_f("  cycles per pixel", " %12.3f", v, nu);
    printf("\n");
    for (int i = 0; i < nu; i++)
        c[i] = runs[i].setup_stalls;
    row_u64("  set-up stall cycles", c, nu);
    printf("\n");
    for (int i = 0; i < nu; i++)
        v[i] = runs[i].cycle_seconds;
    row_f("cycle-accurate model, s per frame", " %12.5f", v, nu);
    printf("\n");
    for (int i = 0; i < nu; i++)
        v[i] = runs[i].err.max_lsb;
    row_f("max error vs float reference, LSB", " %12.3f", v, nu);
    printf("\n");
    printf("  float reference (double) renderer: %.5f s per frame\n", tr);
    printf("  bit-exact model time of %s against %s: %.0f%% less\n", us[0].u->name, us[z].u->name,
           100.0 * (1.0 - t[0] / t[z]));
    for (int i = 0; i < nu; i++)
        np_render_run_free(&runs[i]);
    np_render_frame_free(&fr);
    np_scene_free(&sc);
    return NP_EXIT_OK;
}
