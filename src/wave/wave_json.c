/* SPDX-License-Identifier: MIT */
/*
 * A wave scene file (vectors/scenes/wave-*.json, docs/wave.md "Scenes") into
 * np_wave_scene: the `waves`, `terrain` and `camera` sections. Every field is
 * checked; a bad one is named with its path ("waves.boxes[1].trains[0].lambda").
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cjson/cJSON.h>

#include "np_wave_json.h"

typedef struct jctx {
    const char *file;
    char *err;
    size_t errlen;
} jctx;

static int jfail(jctx *c, const char *field, const char *msg)
{
    snprintf(c->err, c->errlen, "%s: %s: %s", c->file, field, msg);
    return -1;
}

static int keys_ok(jctx *c, const cJSON *o, const char *where, const char *const *allowed)
{
    for (const cJSON *it = o->child; it; it = it->next) {
        int ok = 0;
        for (const char *const *a = allowed; *a; a++)
            ok |= strcmp(*a, it->string) == 0;
        if (!ok) {
            char f[160], list[320] = "";
            snprintf(f, sizeof f, "%s%s%s", where, *where ? "." : "", it->string);
            for (const char *const *a = allowed; *a; a++)
                snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", a == allowed ? "" : ", ", *a);
            char msg[400];
            snprintf(msg, sizeof msg, "unknown field (expected one of: %s)", list);
            return jfail(c, f, msg);
        }
    }
    return 0;
}

/* Optional number in [lo, hi]: 0 (absent: *v unchanged), or -1. */
static int num(jctx *c, const cJSON *o, const char *where, const char *key, double lo, double hi, double *v)
{
    const cJSON *x = cJSON_GetObjectItemCaseSensitive(o, key);
    if (!x)
        return 0;
    char f[160], msg[160];
    snprintf(f, sizeof f, "%s.%s", where, key);
    if (!cJSON_IsNumber(x) || !isfinite(x->valuedouble))
        return jfail(c, f, "expected a number");
    if (x->valuedouble < lo || x->valuedouble > hi) {
        snprintf(msg, sizeof msg, "%g out of range [%g, %g]", x->valuedouble, lo, hi);
        return jfail(c, f, msg);
    }
    *v = x->valuedouble;
    return 0;
}

static int vec3(jctx *c, const cJSON *o, const char *where, const char *key, double v[3])
{
    const cJSON *x = cJSON_GetObjectItemCaseSensitive(o, key);
    char f[160];
    snprintf(f, sizeof f, "%s.%s", where, key);
    if (!x)
        return jfail(c, f, "missing (expected [x, y, z])");
    if (!cJSON_IsArray(x) || cJSON_GetArraySize(x) != 3)
        return jfail(c, f, "expected [x, y, z]");
    for (int k = 0; k < 3; k++) {
        const cJSON *e = cJSON_GetArrayItem(x, k);
        if (!cJSON_IsNumber(e) || !isfinite(e->valuedouble))
            return jfail(c, f, "expected three numbers");
        v[k] = e->valuedouble;
    }
    return 0;
}

static int flag(jctx *c, const cJSON *o, const char *where, const char *key, int *v)
{
    const cJSON *x = cJSON_GetObjectItemCaseSensitive(o, key);
    if (!x)
        return 0;
    if (!cJSON_IsBool(x)) {
        char f[160];
        snprintf(f, sizeof f, "%s.%s", where, key);
        return jfail(c, f, "expected true or false");
    }
    *v = cJSON_IsTrue(x);
    return 0;
}

static const double DEG = 0.017453292519943295;

static int read_box(jctx *c, const cJSON *o, const char *where, np_wave_box *b)
{
    static const char *const bk[] = { "origin", "angle_deg", "length", "width", "wind", "irregular_a", "trains", NULL };
    static const char *const tk[] = { "lambda", "angle_deg", "amp", "amp_of_wind", "phase_deg", NULL };
    if (!cJSON_IsObject(o))
        return jfail(c, where, "expected an object");
    if (keys_ok(c, o, where, bk))
        return -1;
    const cJSON *org = cJSON_GetObjectItemCaseSensitive(o, "origin");
    char f[160];
    snprintf(f, sizeof f, "%s.origin", where);
    if (!cJSON_IsArray(org) || cJSON_GetArraySize(org) != 2 || !cJSON_IsNumber(cJSON_GetArrayItem(org, 0)) ||
        !cJSON_IsNumber(cJSON_GetArrayItem(org, 1)))
        return jfail(c, f, "expected [x, z] in metres");
    b->ox = cJSON_GetArrayItem(org, 0)->valuedouble;
    b->oz = cJSON_GetArrayItem(org, 1)->valuedouble;
    double ang = 0.0, wind = 10.0;
    b->length = b->width = -1.0;
    if (num(c, o, where, "angle_deg", -360.0, 360.0, &ang) || num(c, o, where, "length", 0.0, 1e6, &b->length) ||
        num(c, o, where, "width", 0.0, 1e6, &b->width) || num(c, o, where, "wind", 0.0, 60.0, &wind) ||
        num(c, o, where, "irregular_a", 0.0, 32.0, &b->irr_a))
        return -1;
    if (b->length <= 0.0 || b->width <= 0.0)
        return jfail(c, where, "length and width (m, > 0) are required");
    b->angle = ang * DEG;
    b->wind = wind;
    const cJSON *tr = cJSON_GetObjectItemCaseSensitive(o, "trains");
    snprintf(f, sizeof f, "%s.trains", where);
    if (!cJSON_IsArray(tr) || cJSON_GetArraySize(tr) < 1 || cJSON_GetArraySize(tr) > NP_WAVE_MAX_TRAINS)
        return jfail(c, f, "expected 1 to 4 trains");
    b->n = (unsigned)cJSON_GetArraySize(tr);
    for (unsigned k = 0; k < b->n; k++) {
        const cJSON *t = cJSON_GetArrayItem(tr, (int)k);
        char tw[160];
        snprintf(tw, sizeof tw, "%s.trains[%u]", where, k);
        if (!cJSON_IsObject(t))
            return jfail(c, tw, "expected an object");
        if (keys_ok(c, t, tw, tk))
            return -1;
        np_wave_train_spec *s = &b->tr[k];
        double la = -1.0, ta = 0.0, amp = -1.0, frac = 1.0, ph = 0.0;
        if (num(c, t, tw, "lambda", 1e-3, 1e5, &la) || num(c, t, tw, "angle_deg", -90.0, 90.0, &ta) ||
            num(c, t, tw, "amp", 0.0, 32.0, &amp) || num(c, t, tw, "amp_of_wind", 0.0, 1.0, &frac) ||
            num(c, t, tw, "phase_deg", -360.0, 360.0, &ph))
            return -1;
        if (la <= 0.0)
            return jfail(c, tw, "lambda (m) is required");
        s->lambda = la;
        s->angle = ta * DEG;
        /* Eq. (1) with A = H / 2 (PIN), scaled by amp_of_wind, unless amp is given. */
        s->amp = amp >= 0.0 ? amp : frac * np_wave_amp_of_wind(wind);
        s->phase = ph * DEG;
    }
    return 0;
}

int np_wave_scene_read(const char *path, np_wave_scene *s, unsigned *frames, char *err, size_t errlen)
{
    jctx c = { path, err, errlen };
    FILE *f = fopen(path, "rb");
    if (!f)
        return jfail(&c, "file", "cannot open");
    char *buf = NULL;
    size_t n = 0, cap = 0;
    for (;;) {
        if (n + 4096 > cap) {
            cap = cap ? 2 * cap : 65536;
            char *nb = realloc(buf, cap + 1);
            if (!nb) {
                free(buf);
                fclose(f);
                return jfail(&c, "file", "out of memory");
            }
            buf = nb;
        }
        size_t got = fread(buf + n, 1, 4096, f);
        n += got;
        if (got == 0)
            break;
    }
    fclose(f);
    buf[n] = '\0';
    cJSON *root = cJSON_Parse(buf);
    free(buf);
    if (!root)
        return jfail(&c, "file", "not valid JSON");
    int rc = -1;
    np_wave_scene_init(s);
    static const char *const rk[] = { "noisepipe_scene", "name", "description", "waves", "terrain", "camera", "frames", NULL };
    static const char *const wk[] = { "grid", "extent", "fps", "effects", "allow_fold", "lanes", "noise_amp", "noise_rate",
                                      "normals", "fold", "boxes", NULL };
    static const char *const ek[] = { "refraction", "irregular", "noise", "round", NULL };
    static const char *const tk[] = { "sea_depth", "island", NULL };
    static const char *const ik[] = { "center", "radius", "height", "noise_amp", "noise_scale", NULL };
    static const char *const ck[] = { "eye", "target", "up", "fov_deg", "aspect", "near", "far", NULL };
    static const char *const fk[] = { "count", "first", "step", NULL };
    if (!cJSON_IsObject(root) || keys_ok(&c, root, "", rk))
        goto done;
    const cJSON *w = cJSON_GetObjectItemCaseSensitive(root, "waves");
    if (!cJSON_IsObject(w)) {
        jfail(&c, "waves", "missing (expected an object)");
        goto done;
    }
    if (keys_ok(&c, w, "waves", wk))
        goto done;
    double grid = s->grid, fps = 1.0 / s->dt, lanes = s->lanes;
    if (num(&c, w, "waves", "grid", 8, 4096, &grid) || num(&c, w, "waves", "extent", 1.0, 1e6, &s->extent) ||
        num(&c, w, "waves", "fps", 1.0, 1000.0, &fps) || num(&c, w, "waves", "lanes", 1, NP_WAVE_MAX_TRAINS, &lanes) ||
        num(&c, w, "waves", "noise_amp", 0.0, 1.0, &s->noise_amp) ||
        num(&c, w, "waves", "noise_rate", 0.0, 100.0, &s->noise_rate) || flag(&c, w, "waves", "allow_fold", &s->allow_fold) ||
        flag(&c, w, "waves", "normals", &s->reads_normals) || flag(&c, w, "waves", "fold", &s->reads_fold))
        goto done;
    if (grid != floor(grid) || lanes != floor(lanes)) {
        jfail(&c, "waves.grid", "grid and lanes are whole numbers");
        goto done;
    }
    s->grid = (unsigned)grid;
    s->lanes = (unsigned)lanes;
    s->dt = 1.0 / fps;
    const cJSON *e = cJSON_GetObjectItemCaseSensitive(w, "effects");
    if (e) {
        if (!cJSON_IsObject(e) || keys_ok(&c, e, "waves.effects", ek))
            goto done;
        int fx[4] = { 0, 0, 0, 0 };
        for (unsigned k = 0; k < 4; k++)
            if (flag(&c, e, "waves.effects", ek[k], &fx[k]))
                goto done;
        s->effects = (fx[0] ? NP_WAVE_FX_REFRACTION : 0u) | (fx[1] ? NP_WAVE_FX_IRREGULAR : 0u) |
                     (fx[2] ? NP_WAVE_FX_NOISE : 0u) | (fx[3] ? NP_WAVE_FX_ROUND : 0u);
    }
    const cJSON *bx = cJSON_GetObjectItemCaseSensitive(w, "boxes");
    if (!cJSON_IsArray(bx) || cJSON_GetArraySize(bx) < 1 || cJSON_GetArraySize(bx) > NP_WAVE_MAX_BOXES) {
        jfail(&c, "waves.boxes", "expected 1 to 16 boxes");
        goto done;
    }
    s->nbox = (unsigned)cJSON_GetArraySize(bx);
    for (unsigned k = 0; k < s->nbox; k++) {
        char where[64];
        snprintf(where, sizeof where, "waves.boxes[%u]", k);
        if (read_box(&c, cJSON_GetArrayItem(bx, (int)k), where, &s->box[k]))
            goto done;
    }
    const cJSON *t = cJSON_GetObjectItemCaseSensitive(root, "terrain");
    if (t) {
        if (!cJSON_IsObject(t) || keys_ok(&c, t, "terrain", tk) || num(&c, t, "terrain", "sea_depth", 0.0, 1e4, &s->sea_depth))
            goto done;
        const cJSON *is = cJSON_GetObjectItemCaseSensitive(t, "island");
        if (is) {
            if (!cJSON_IsObject(is) || keys_ok(&c, is, "terrain.island", ik))
                goto done;
            const cJSON *ce = cJSON_GetObjectItemCaseSensitive(is, "center");
            if (!cJSON_IsArray(ce) || cJSON_GetArraySize(ce) != 2) {
                jfail(&c, "terrain.island.center", "expected [x, z] in metres");
                goto done;
            }
            s->isl_x = cJSON_GetArrayItem(ce, 0)->valuedouble;
            s->isl_z = cJSON_GetArrayItem(ce, 1)->valuedouble;
            if (num(&c, is, "terrain.island", "radius", 0.0, 1e6, &s->isl_radius) ||
                num(&c, is, "terrain.island", "height", 0.0, 1e4, &s->isl_height) ||
                num(&c, is, "terrain.island", "noise_amp", 0.0, 1e4, &s->isl_noise) ||
                num(&c, is, "terrain.island", "noise_scale", 1e-3, 1e6, &s->isl_scale))
                goto done;
        }
    }
    const cJSON *cam = cJSON_GetObjectItemCaseSensitive(root, "camera");
    if (cam) {
        double fov = 60.0;
        s->cam.up[1] = 1.0;
        s->cam.aspect = 1.0;
        s->cam.znear = 1.0;
        s->cam.zfar = 1e5;
        if (!cJSON_IsObject(cam) || keys_ok(&c, cam, "camera", ck) || vec3(&c, cam, "camera", "eye", s->cam.eye) ||
            vec3(&c, cam, "camera", "target", s->cam.target) ||
            (cJSON_GetObjectItemCaseSensitive(cam, "up") && vec3(&c, cam, "camera", "up", s->cam.up)) ||
            num(&c, cam, "camera", "fov_deg", 1.0, 179.0, &fov) || num(&c, cam, "camera", "aspect", 0.01, 100.0, &s->cam.aspect) ||
            num(&c, cam, "camera", "near", 1e-6, 1e9, &s->cam.znear) || num(&c, cam, "camera", "far", 1e-6, 1e12, &s->cam.zfar))
            goto done;
        s->cam.fov_y = fov * DEG;
        s->has_camera = 1;
    }
    const cJSON *fr = cJSON_GetObjectItemCaseSensitive(root, "frames");
    if (fr && frames) {
        double cnt = frames[0], first = frames[1], step = frames[2];
        if (!cJSON_IsObject(fr) || keys_ok(&c, fr, "frames", fk) || num(&c, fr, "frames", "count", 1, 100000, &cnt) ||
            num(&c, fr, "frames", "first", 0, 4294967295.0, &first) || num(&c, fr, "frames", "step", 0, 4294967295.0, &step))
            goto done;
        frames[0] = (unsigned)cnt;
        frames[1] = (unsigned)first;
        frames[2] = (unsigned)step;
    }
    rc = 0;
done:
    cJSON_Delete(root);
    return rc;
}
