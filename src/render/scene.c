/* SPDX-License-Identifier: MIT */
/* Scene files (np_scene.h), read with cJSON. */
#include "np_scene.h"

#include "np_math.h"

#include <cjson/cJSON.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Parser state: the file name for messages and the first error. */
typedef struct ctx {
    const char *file;
    char *err;
    size_t errlen;
    int failed;
    unsigned poly_cap; /* np_scene.poly's allocated entries */
} ctx;

static int fail(ctx *c, const char *field, const char *fmt, ...) __attribute__((format(printf, 3, 4)));

static int fail(ctx *c, const char *field, const char *fmt, ...)
{
    if (!c->failed) {
        char what[256];
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(what, sizeof what, fmt, ap);
        va_end(ap);
        snprintf(c->err, c->errlen, "%s: field '%s': %s", c->file, field, what);
        c->failed = 1;
    }
    return -1;
}

/* "parent.key" or "parent[i]" into buf. */
static const char *path_key(char *buf, size_t n, const char *parent, const char *key)
{
    int w = snprintf(buf, n, "%s%s%s", parent, *parent ? "." : "", key);
    if (w < 0 || (size_t)w >= n)
        buf[n - 1] = '\0'; /* a deep path is cut short in the message only */
    return buf;
}

static const char *path_idx(char *buf, size_t n, const char *parent, int i)
{
    int w = snprintf(buf, n, "%s[%d]", parent, i);
    if (w < 0 || (size_t)w >= n)
        buf[n - 1] = '\0';
    return buf;
}

/* Refuse keys an object must not have (typos) and duplicates. */
static int check_keys(ctx *c, const cJSON *obj, const char *where, const char *const *allowed)
{
    for (const cJSON *it = obj->child; it; it = it->next) {
        int ok = 0;
        for (const char *const *a = allowed; *a; a++)
            ok |= strcmp(*a, it->string) == 0;
        char f[256];
        if (!ok) {
            char list[256] = "";
            for (const char *const *a = allowed; *a; a++)
                snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", a == allowed ? "" : ", ", *a);
            return fail(c, path_key(f, sizeof f, where, it->string), "unknown field (expected one of: %s)", list);
        }
        for (const cJSON *jt = obj->child; jt != it; jt = jt->next)
            if (strcmp(jt->string, it->string) == 0)
                return fail(c, path_key(f, sizeof f, where, it->string), "appears twice");
    }
    return 0;
}

static const cJSON *get(const cJSON *obj, const char *key) { return cJSON_GetObjectItemCaseSensitive(obj, key); }

static int need_object(ctx *c, const cJSON *v, const char *field)
{
    if (!v)
        return fail(c, field, "missing (expected an object)");
    if (!cJSON_IsObject(v))
        return fail(c, field, "expected an object");
    return 0;
}

static int read_number(ctx *c, const cJSON *v, const char *field, double lo, double hi, double *out)
{
    if (!v)
        return fail(c, field, "missing (expected a number in [%g, %g])", lo, hi);
    if (!cJSON_IsNumber(v) || !isfinite(v->valuedouble))
        return fail(c, field, "expected a number in [%g, %g]", lo, hi);
    if (v->valuedouble < lo || v->valuedouble > hi)
        return fail(c, field, "%g is out of range: expected a number in [%g, %g]", v->valuedouble, lo, hi);
    *out = v->valuedouble;
    return 0;
}

static int read_uint(ctx *c, const cJSON *v, const char *field, unsigned lo, unsigned hi, unsigned *out)
{
    if (!v)
        return fail(c, field, "missing (expected an integer in %u..%u)", lo, hi);
    if (!cJSON_IsNumber(v) || v->valuedouble != floor(v->valuedouble) || v->valuedouble < lo ||
        v->valuedouble > hi)
        return fail(c, field, "expected an integer in %u..%u", lo, hi);
    *out = (unsigned)v->valuedouble;
    return 0;
}

static int read_vec3(ctx *c, const cJSON *v, const char *field, double lo, double hi, double out[3])
{
    if (!v)
        return fail(c, field, "missing (expected an array of 3 numbers)");
    if (!cJSON_IsArray(v) || cJSON_GetArraySize(v) != 3)
        return fail(c, field, "expected an array of 3 numbers");
    for (int i = 0; i < 3; i++) {
        char f[256];
        if (read_number(c, cJSON_GetArrayItem(v, i), path_idx(f, sizeof f, field, i), lo, hi, &out[i]))
            return -1;
    }
    return 0;
}

static int read_rgb(ctx *c, const cJSON *v, const char *field, double out[3])
{
    if (!v || !cJSON_IsArray(v) || cJSON_GetArraySize(v) != 3)
        return fail(c, field, "%s (expected an array of 3 integers 0..255)", v ? "wrong type" : "missing");
    for (int i = 0; i < 3; i++) {
        char f[256];
        unsigned u = 0;
        if (read_uint(c, cJSON_GetArrayItem(v, i), path_idx(f, sizeof f, field, i), 0, 255, &u))
            return -1;
        out[i] = (double)u;
    }
    return 0;
}

static int read_string(ctx *c, const cJSON *v, const char *field, const char *const *choices, int *idx)
{
    char list[128] = "";
    for (const char *const *a = choices; *a; a++)
        snprintf(list + strlen(list), sizeof list - strlen(list), "%s\"%s\"", a == choices ? "" : " or ", *a);
    if (!v || !cJSON_IsString(v))
        return fail(c, field, "%s (expected %s)", v ? "expected a string" : "missing", list);
    for (int i = 0; choices[i]; i++)
        if (strcmp(v->valuestring, choices[i]) == 0) {
            *idx = i;
            return 0;
        }
    return fail(c, field, "\"%s\" is not one of %s", v->valuestring, list);
}

enum { COORD_MAX = 1000000 };

static int parse_image(ctx *c, const cJSON *root, np_scene *s)
{
    static const char *const keys[] = { "width", "height", "background", NULL };
    const cJSON *im = get(root, "image");
    if (need_object(c, im, "image") || check_keys(c, im, "image", keys))
        return -1;
    if (read_uint(c, get(im, "width"), "image.width", 1, NP_SCENE_MAX_SIZE, &s->width) ||
        read_uint(c, get(im, "height"), "image.height", 1, NP_SCENE_MAX_SIZE, &s->height))
        return -1;
    if (get(im, "background"))
        return read_rgb(c, get(im, "background"), "image.background", s->background);
    return 0;
}

static int parse_camera(ctx *c, const cJSON *root, np_scene *s)
{
    static const char *const keys[] = { "projection", "eye", "target", "up", "height", "focal", "depth_range", NULL };
    static const char *const proj[] = { "orthographic", "perspective", NULL };
    const cJSON *cam = get(root, "camera");
    np_scene_camera *k = &s->cam;
    int p;
    if (need_object(c, cam, "camera") || check_keys(c, cam, "camera", keys) ||
        read_string(c, get(cam, "projection"), "camera.projection", proj, &p) ||
        read_vec3(c, get(cam, "eye"), "camera.eye", -COORD_MAX, COORD_MAX, k->eye) ||
        read_vec3(c, get(cam, "target"), "camera.target", -COORD_MAX, COORD_MAX, k->target) ||
        read_vec3(c, get(cam, "up"), "camera.up", -COORD_MAX, COORD_MAX, k->up))
        return -1;
    k->perspective = p == 1;
    if (k->perspective) {
        if (get(cam, "height"))
            return fail(c, "camera.height", "only for an orthographic camera (a perspective one has \"focal\")");
        if (read_number(c, get(cam, "focal"), "camera.focal", 1e-3, 1e3, &k->focal))
            return -1;
    } else {
        if (get(cam, "focal"))
            return fail(c, "camera.focal", "only for a perspective camera (an orthographic one has \"height\")");
        if (read_number(c, get(cam, "height"), "camera.height", 1e-6, COORD_MAX, &k->height))
            return -1;
    }
    double d[3], n2 = 0, u2 = 0, dot = 0;
    for (int a = 0; a < 3; a++) {
        d[a] = k->target[a] - k->eye[a];
        n2 += d[a] * d[a];
        u2 += k->up[a] * k->up[a];
        dot += d[a] * k->up[a];
    }
    if (!(n2 > 0))
        return fail(c, "camera.target", "must differ from camera.eye");
    if (!(u2 * n2 - dot * dot > 1e-12 * u2 * n2))
        return fail(c, "camera.up", "must not be parallel to the viewing direction");
    const cJSON *dr = get(cam, "depth_range");
    if (dr) {
        if (!cJSON_IsArray(dr) || cJSON_GetArraySize(dr) != 2)
            return fail(c, "camera.depth_range", "expected [near, far]");
        if (read_number(c, cJSON_GetArrayItem(dr, 0), "camera.depth_range[0]", -COORD_MAX, COORD_MAX,
                        &k->depth_range[0]) ||
            read_number(c, cJSON_GetArrayItem(dr, 1), "camera.depth_range[1]", -COORD_MAX, COORD_MAX,
                        &k->depth_range[1]))
            return -1;
        if (!(k->depth_range[1] > k->depth_range[0]))
            return fail(c, "camera.depth_range", "far must exceed near");
        k->have_depth_range = 1;
    }
    return 0;
}

static int check_polygon(ctx *c, const np_scene_poly *p, const char *field);

/* "light" (np_scene.h): after the camera, whose frame gives the default direction. */
static int parse_light(ctx *c, const cJSON *root, np_scene *s)
{
    static const char *const keys[] = { "direction", "ambient", "image", NULL };
    const cJSON *li = get(root, "light");
    const np_scene_camera *k = &s->cam;
    double f[3], u[3], r[3], fu = 0, *d = s->light_dir, n2 = 0;
    s->ambient = 0.3;
    if (li && (need_object(c, li, "light") || check_keys(c, li, "light", keys)))
        return -1;
    if (li && get(li, "ambient") && read_number(c, get(li, "ambient"), "light.ambient", 0, 1, &s->ambient))
        return -1;
    const cJSON *im = li ? get(li, "image") : NULL;
    if (im && !cJSON_IsBool(im))
        return fail(c, "light.image", "expected true or false");
    s->light_image = im && cJSON_IsTrue(im);
    if (li && get(li, "direction")) {
        if (read_vec3(c, get(li, "direction"), "light.direction", -COORD_MAX, COORD_MAX, d))
            return -1;
    } else {
        /* The camera frame: forward f, up u (orthogonal to f), right r = f x u. */
        for (int a = 0; a < 3; a++)
            f[a] = k->target[a] - k->eye[a];
        double fl = sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
        for (int a = 0; a < 3; a++)
            f[a] /= fl;
        for (int a = 0; a < 3; a++)
            fu += k->up[a] * f[a];
        for (int a = 0; a < 3; a++)
            u[a] = k->up[a] - fu * f[a];
        r[0] = f[1] * u[2] - f[2] * u[1];
        r[1] = f[2] * u[0] - f[0] * u[2];
        r[2] = f[0] * u[1] - f[1] * u[0];
        double ul = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
        for (int a = 0; a < 3; a++)
            d[a] = -2.0 * f[a] + (u[a] - r[a]) / ul;
    }
    for (int a = 0; a < 3; a++)
        n2 += d[a] * d[a];
    if (!(n2 > 1e-18))
        return fail(c, "light.direction", "must not be zero");
    for (int a = 0; a < 3; a++)
        d[a] /= sqrt(n2);
    return 0;
}

/* "aa" (np_scene.h np_scene_aa): the adaptive supersampling's constants; a metric without its constant is off. */
static int parse_aa(ctx *c, const cJSON *root, np_scene *s)
{
    static const char *const keys[] = { "m", "c_d", "c_n", "c_s", "t_min", "t_edge", "luma_taps", "tile", NULL };
    const cJSON *aa = get(root, "aa");
    np_scene_aa *q = &s->aa;
    q->m = 3;
    q->t_min = 16.0 / 255.0;
    q->t_edge = 1.0 / 8.0;
    q->luma_taps = 4;
    if (!aa)
        return 0;
    if (need_object(c, aa, "aa") || check_keys(c, aa, "aa", keys))
        return -1;
    q->present = 1;
    if (get(aa, "m") && read_uint(c, get(aa, "m"), "aa.m", 1, 4, &q->m))
        return -1;
    struct { const char *key, *field; int *have; double *v; } cs[] = {
        { "c_d", "aa.c_d", &q->have_cd, &q->c_d }, { "c_n", "aa.c_n", &q->have_cn, &q->c_n },
        { "c_s", "aa.c_s", &q->have_cs, &q->c_s },
    };
    for (size_t i = 0; i < sizeof cs / sizeof cs[0]; i++)
        if (get(aa, cs[i].key)) {
            if (read_number(c, get(aa, cs[i].key), cs[i].field, 0, 1e15, cs[i].v))
                return -1;
            *cs[i].have = 1;
        }
    if ((get(aa, "t_min") && read_number(c, get(aa, "t_min"), "aa.t_min", 0, 1, &q->t_min)) ||
        (get(aa, "t_edge") && read_number(c, get(aa, "t_edge"), "aa.t_edge", 0, 1, &q->t_edge)) ||
        (get(aa, "luma_taps") && read_uint(c, get(aa, "luma_taps"), "aa.luma_taps", 4, 5, &q->luma_taps)) ||
        (get(aa, "tile") && read_uint(c, get(aa, "tile"), "aa.tile", 0, 6, &q->tile)))
        return -1;
    if (q->tile != 0 && q->tile != 6)
        return fail(c, "aa.tile", "expected 0 (off) or 6 (the 6x6 tile maximum)");
    return 0;
}

/* "hatch" (np_scene.h np_scene_hatch): the hatching unit's scene keys. */
static int parse_hatch(ctx *c, const cJSON *root, np_scene *s)
{
    static const char *const keys[] = { "set", "layers", "fade", "mode", "lanes", "tile_pixels", NULL };
    static const char *const sets[] = { "fkm16", "best16", "fkm64", "best64", NULL };
    static const char *const fades[] = { "smooth", "onebyone", NULL };
    static const char *const modes[] = { "brute", "coverage", NULL };
    const cJSON *h = get(root, "hatch");
    np_scene_hatch *q = &s->hatch;
    int set = 1, fade = 0, mode = 1;
    q->layers = 4;
    q->lanes = 1;
    q->tile_pixels = 64;
    if (!h) {
        q->set = 1;
        q->coverage = 1;
        return 0;
    }
    if (need_object(c, h, "hatch") || check_keys(c, h, "hatch", keys))
        return -1;
    q->present = 1;
    if ((get(h, "set") && read_string(c, get(h, "set"), "hatch.set", sets, &set)) ||
        (get(h, "fade") && read_string(c, get(h, "fade"), "hatch.fade", fades, &fade)) ||
        (get(h, "mode") && read_string(c, get(h, "mode"), "hatch.mode", modes, &mode)) ||
        (get(h, "layers") && read_uint(c, get(h, "layers"), "hatch.layers", 1, 4, &q->layers)) ||
        (get(h, "lanes") && read_uint(c, get(h, "lanes"), "hatch.lanes", 1, 16, &q->lanes)) ||
        (get(h, "tile_pixels") &&
         read_number(c, get(h, "tile_pixels"), "hatch.tile_pixels", 1.0 / 1024.0, 1e6, &q->tile_pixels)))
        return -1;
    q->set = (unsigned)set;
    q->fade = (unsigned)fade;
    q->coverage = (unsigned)mode;
    unsigned n = q->set >= 2 ? 64u : 16u;
    if ((q->lanes & (q->lanes - 1u)) != 0 || n % q->lanes != 0)
        return fail(c, "hatch.lanes", "%u: expected a power of two dividing the set's %u seeds", q->lanes, n);
    return 0;
}

/* The explicit polygons grow by doubling: no cap but NP_SCENE_MAX_PRIMS over all ids. */
static np_scene_poly *add_poly(ctx *c, np_scene *s, const char *field)
{
    if (s->n_prims >= NP_SCENE_MAX_PRIMS) {
        fail(c, field, "too many polygons (at most %d in a scene)", NP_SCENE_MAX_PRIMS);
        return NULL;
    }
    if (s->n_poly == c->poly_cap) {
        unsigned nc = c->poly_cap ? 2 * c->poly_cap : 64;
        np_scene_poly *np = realloc(s->poly, (size_t)nc * sizeof *np);
        if (!np) {
            fail(c, field, "out of memory");
            return NULL;
        }
        s->poly = np;
        c->poly_cap = nc;
    }
    s->n_prims++;
    np_scene_poly *p = &s->poly[s->n_poly++];
    memset(p, 0, sizeof *p);
    p->cull = 1;
    return p;
}

/* The six faces of an axis-aligned box, counter-clockwise seen from outside. */
static const unsigned char cube_faces[6][4] = {
    { 0, 4, 6, 2 }, /* x = min */ { 1, 3, 7, 5 }, /* x = max */
    { 0, 1, 5, 4 }, /* y = min */ { 2, 6, 7, 3 }, /* y = max */
    { 0, 2, 3, 1 }, /* z = min */ { 4, 5, 7, 6 }, /* z = max */
};

/*
 * {"type": "sphere", "center", "radius", "subdivisions" N, "texture_min",
 * "texture_max", "cull"}: a tessellated sphere, N rings of latitude by 2N
 * segments of longitude (vertex (i, j) at polar angle i/(2N) turns from +y,
 * azimuth j/(2N) turns; np_sin_turns and np_cos_turns, so every machine
 * builds the same points), 4 N (N - 1) triangles, texture coordinates affine
 * in position (texture_min at center - radius, texture_max at center +
 * radius, per axis). N = 2..1024 (4.2 million triangles; a scene holds at
 * most NP_SCENE_MAX_PRIMS polygons in all, so a fuzzed scene stays in memory).
 */
static int parse_sphere(ctx *c, const cJSON *o, const char *where, np_scene *s)
{
    static const char *const keys[] = { "type", "center", "radius", "subdivisions", "texture_min", "texture_max",
                                        "cull", NULL };
    char f[256];
    double ce[3], r = 0, tmn[3], tmx[3];
    unsigned N = 0;
    if (check_keys(c, o, where, keys) ||
        read_vec3(c, get(o, "center"), path_key(f, sizeof f, where, "center"), -COORD_MAX, COORD_MAX, ce) ||
        read_number(c, get(o, "radius"), path_key(f, sizeof f, where, "radius"), 1e-6, COORD_MAX, &r) ||
        read_uint(c, get(o, "subdivisions"), path_key(f, sizeof f, where, "subdivisions"), 2, 1024, &N) ||
        read_vec3(c, get(o, "texture_min"), path_key(f, sizeof f, where, "texture_min"), -COORD_MAX, COORD_MAX,
                  tmn) ||
        read_vec3(c, get(o, "texture_max"), path_key(f, sizeof f, where, "texture_max"), -COORD_MAX, COORD_MAX,
                  tmx))
        return -1;
    int cull = 1;
    const cJSON *cu = get(o, "cull");
    if (cu) {
        if (!cJSON_IsBool(cu))
            return fail(c, path_key(f, sizeof f, where, "cull"), "expected true or false");
        cull = cJSON_IsTrue(cu);
    }
    const uint64_t seg = 2u * (uint64_t)N, nv = 2u + (uint64_t)(N - 1u) * seg, nt = 4u * (uint64_t)N * (N - 1u);
    if ((uint64_t)s->n_prims + nt > NP_SCENE_MAX_PRIMS)
        return fail(c, path_key(f, sizeof f, where, "subdivisions"), "too many polygons (at most %d in a scene)",
                    NP_SCENE_MAX_PRIMS);
    np_scene_mesh *nm = realloc(s->mesh, (s->n_mesh + 1u) * sizeof *nm);
    if (!nm)
        return fail(c, where, "out of memory");
    s->mesh = nm;
    np_scene_mesh *m = &s->mesh[s->n_mesh++];
    memset(m, 0, sizeof *m);
    m->n_vert = (uint32_t)nv;
    m->n_tri = (uint32_t)nt;
    m->cull = cull;
    m->first_id = s->n_prims;
    m->p = malloc((size_t)nv * sizeof *m->p);
    m->t = malloc((size_t)nv * sizeof *m->t);
    m->tri = malloc((size_t)nt * sizeof *m->tri);
    if (!m->p || !m->t || !m->tri)
        return fail(c, where, "out of memory");
    /* Vertex 0: the pole +y; 1 + (i - 1) seg + j: ring i (1..N-1), segment j; nv - 1: the pole -y. */
    for (uint64_t v = 0; v < nv; v++) {
        double dir[3];
        if (v == 0 || v == nv - 1) {
            dir[0] = dir[2] = 0;
            dir[1] = v == 0 ? 1.0 : -1.0;
        } else {
            uint64_t i = 1 + (v - 1) / seg, j = (v - 1) % seg;
            double st, ct, sp, cp;
            np_sincos_turns((double)i / (double)seg, &st, &ct);
            np_sincos_turns((double)j / (double)seg, &sp, &cp);
            dir[0] = st * cp;
            dir[1] = ct;
            dir[2] = st * sp;
        }
        for (int a = 0; a < 3; a++) {
            m->p[v][a] = ce[a] + r * dir[a];
            m->t[v][a] = tmn[a] + (tmx[a] - tmn[a]) * (dir[a] + 1.0) / 2.0;
        }
    }
    /* Seen from outside, counter-clockwise (the azimuth turns from +x towards +z, i.e. clockwise seen from +y). */
    uint64_t t = 0;
    for (uint64_t j = 0; j < seg; j++) {
        uint32_t a = (uint32_t)(1 + j), b = (uint32_t)(1 + (j + 1) % seg);
        m->tri[t][0] = 0, m->tri[t][1] = b, m->tri[t][2] = a, t++;
        uint32_t lo = (uint32_t)(1 + (N - 2u) * seg);
        m->tri[t][0] = (uint32_t)(nv - 1), m->tri[t][1] = lo + a - 1u, m->tri[t][2] = lo + b - 1u, t++;
    }
    for (uint64_t i = 1; i + 1 < N; i++)
        for (uint64_t j = 0; j < seg; j++) {
            uint32_t a = (uint32_t)(1 + (i - 1) * seg + j), b = (uint32_t)(1 + (i - 1) * seg + (j + 1) % seg);
            uint32_t a2 = (uint32_t)(a + seg), b2 = (uint32_t)(b + seg);
            m->tri[t][0] = a, m->tri[t][1] = b, m->tri[t][2] = b2, t++;
            m->tri[t][0] = a, m->tri[t][1] = b2, m->tri[t][2] = a2, t++;
        }
    s->n_prims += m->n_tri;
    return 0;
}

const np_scene_poly *np_scene_poly_get(const np_scene *s, uint32_t id, np_scene_poly *tmp)
{
    if (id < s->n_poly)
        return &s->poly[id];
    for (unsigned i = 0; i < s->n_mesh; i++) {
        const np_scene_mesh *m = &s->mesh[i];
        if (id >= m->first_id && id - m->first_id < m->n_tri) {
            const uint32_t *v = m->tri[id - m->first_id];
            tmp->n = 3;
            tmp->cull = m->cull;
            for (int k = 0; k < 3; k++)
                for (int a = 0; a < 3; a++) {
                    tmp->p[k][a] = m->p[v[k]][a];
                    tmp->t[k][a] = m->t[v[k]][a];
                }
            return tmp;
        }
    }
    return NULL;
}

static int parse_geometry(ctx *c, const cJSON *root, np_scene *s)
{
    static const char *const types[] = { "cube", "polygon", "sphere", NULL };
    static const char *const cube_keys[] = { "type", "min", "max", "texture_min", "texture_max", NULL };
    static const char *const poly_keys[] = { "type", "vertices", "texcoords", "cull", NULL };
    const cJSON *g = get(root, "geometry");
    if (!g || !cJSON_IsArray(g) || cJSON_GetArraySize(g) < 1)
        return fail(c, "geometry", "%s (expected a non-empty array of objects)", g ? "wrong type" : "missing");
    int n = cJSON_GetArraySize(g);
    for (int i = 0; i < n; i++) {
        char where[64], f[256];
        const cJSON *o = cJSON_GetArrayItem(g, i);
        int type;
        path_idx(where, sizeof where, "geometry", i);
        if (need_object(c, o, where) ||
            read_string(c, get(o, "type"), path_key(f, sizeof f, where, "type"), types, &type))
            return -1;
        if (type == 2) {
            if (parse_sphere(c, o, where, s))
                return -1;
        } else if (type == 0) {
            double mn[3], mx[3], tmn[3], tmx[3];
            if (check_keys(c, o, where, cube_keys) ||
                read_vec3(c, get(o, "min"), path_key(f, sizeof f, where, "min"), -COORD_MAX, COORD_MAX, mn) ||
                read_vec3(c, get(o, "max"), path_key(f, sizeof f, where, "max"), -COORD_MAX, COORD_MAX, mx) ||
                read_vec3(c, get(o, "texture_min"), path_key(f, sizeof f, where, "texture_min"), -COORD_MAX,
                          COORD_MAX, tmn) ||
                read_vec3(c, get(o, "texture_max"), path_key(f, sizeof f, where, "texture_max"), -COORD_MAX,
                          COORD_MAX, tmx))
                return -1;
            for (int a = 0; a < 3; a++)
                if (!(mx[a] > mn[a]))
                    return fail(c, path_key(f, sizeof f, where, "max"), "must exceed \"min\" on every axis");
            for (int face = 0; face < 6; face++) {
                np_scene_poly *p = add_poly(c, s, where);
                if (!p)
                    return -1;
                p->n = 4;
                for (int v = 0; v < 4; v++) {
                    unsigned b = cube_faces[face][v];
                    for (unsigned a = 0; a < 3; a++) {
                        double w = (double)((b >> a) & 1u);
                        p->p[v][a] = mn[a] + (mx[a] - mn[a]) * w;
                        p->t[v][a] = tmn[a] + (tmx[a] - tmn[a]) * w;
                    }
                }
            }
        } else {
            const cJSON *vs = get(o, "vertices"), *ts = get(o, "texcoords");
            if (check_keys(c, o, where, poly_keys))
                return -1;
            if (!vs || !cJSON_IsArray(vs) || cJSON_GetArraySize(vs) < 3 ||
                cJSON_GetArraySize(vs) > NP_SCENE_MAX_VERTS)
                return fail(c, path_key(f, sizeof f, where, "vertices"),
                            "expected an array of 3..%d points [x, y, z]", NP_SCENE_MAX_VERTS);
            if (!ts || !cJSON_IsArray(ts) || cJSON_GetArraySize(ts) != cJSON_GetArraySize(vs))
                return fail(c, path_key(f, sizeof f, where, "texcoords"),
                            "expected an array of [s, t, r], one per vertex (%d)", cJSON_GetArraySize(vs));
            np_scene_poly *p = add_poly(c, s, where);
            if (!p)
                return -1;
            p->n = (unsigned)cJSON_GetArraySize(vs);
            for (unsigned v = 0; v < p->n; v++) {
                char fv[256];
                path_key(f, sizeof f, where, "vertices");
                if (read_vec3(c, cJSON_GetArrayItem(vs, (int)v), path_idx(fv, sizeof fv, f, (int)v), -COORD_MAX,
                              COORD_MAX, p->p[v]))
                    return -1;
                path_key(f, sizeof f, where, "texcoords");
                if (read_vec3(c, cJSON_GetArrayItem(ts, (int)v), path_idx(fv, sizeof fv, f, (int)v), -COORD_MAX,
                              COORD_MAX, p->t[v]))
                    return -1;
            }
            const cJSON *cull = get(o, "cull");
            if (cull) {
                if (!cJSON_IsBool(cull))
                    return fail(c, path_key(f, sizeof f, where, "cull"), "expected true or false");
                p->cull = cJSON_IsTrue(cull);
            }
            if (check_polygon(c, p, path_key(f, sizeof f, where, "vertices")))
                return -1;
        }
    }
    return 0;
}

/*
 * A polygon must be what the scan converter assumes (docs/render.md): planar,
 * convex, with area, and no two consecutive vertices at the same point.
 * Tolerances are relative to the polygon's size L (its bounding-box
 * diagonal): a point closer than 1e-12 L is the same point, a vertex farther
 * than 1e-9 L from the plane is off it, a turn against the winding larger
 * than 1e-12 L^2 (cross product of the two edges) is a reflex corner.
 */
static int check_polygon(ctx *c, const np_scene_poly *p, const char *field)
{
    double mn[3], mx[3], cen[3] = { 0, 0, 0 };
    for (unsigned a = 0; a < 3; a++)
        mn[a] = mx[a] = p->p[0][a];
    for (unsigned v = 0; v < p->n; v++)
        for (unsigned a = 0; a < 3; a++) {
            mn[a] = fmin(mn[a], p->p[v][a]);
            mx[a] = fmax(mx[a], p->p[v][a]);
            cen[a] += p->p[v][a] / (double)p->n;
        }
    double L = sqrt((mx[0] - mn[0]) * (mx[0] - mn[0]) + (mx[1] - mn[1]) * (mx[1] - mn[1]) +
                    (mx[2] - mn[2]) * (mx[2] - mn[2]));
    for (unsigned v = 0; v < p->n; v++) {
        const double *a = p->p[v], *b = p->p[(v + 1) % p->n];
        double d = sqrt((b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]) + (b[2] - a[2]) * (b[2] - a[2]));
        if (!(d > 1e-12 * L))
            return fail(c, field, "vertices %u and %u are the same point", v, (v + 1) % p->n);
    }
    /* Newell's normal: its length is twice the area. */
    double nrm[3] = { 0, 0, 0 };
    for (unsigned v = 0; v < p->n; v++) {
        const double *a = p->p[v], *b = p->p[(v + 1) % p->n];
        nrm[0] += (a[1] - b[1]) * (a[2] + b[2]);
        nrm[1] += (a[2] - b[2]) * (a[0] + b[0]);
        nrm[2] += (a[0] - b[0]) * (a[1] + b[1]);
    }
    double nl = sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
    if (!(nl > 1e-12 * L * L))
        return fail(c, field, "the polygon has no area (its vertices are collinear)");
    for (unsigned v = 0; v < p->n; v++) {
        double off = ((p->p[v][0] - cen[0]) * nrm[0] + (p->p[v][1] - cen[1]) * nrm[1] +
                      (p->p[v][2] - cen[2]) * nrm[2]) / nl;
        if (fabs(off) > 1e-9 * L)
            return fail(c, field, "vertex %u is %.3g off the plane of the polygon: polygons must be planar", v, off);
    }
    for (unsigned v = 0; v < p->n; v++) {
        const double *a = p->p[(v + p->n - 1) % p->n], *b = p->p[v], *d = p->p[(v + 1) % p->n];
        double e0[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] }, e1[3] = { d[0] - b[0], d[1] - b[1], d[2] - b[2] };
        double cr[3] = { e0[1] * e1[2] - e0[2] * e1[1], e0[2] * e1[0] - e0[0] * e1[2], e0[0] * e1[1] - e0[1] * e1[0] };
        double turn = (cr[0] * nrm[0] + cr[1] * nrm[1] + cr[2] * nrm[2]) / nl;
        if (turn < -1e-12 * L * L)
            return fail(c, field, "the polygon is not convex at vertex %u: polygons must be convex", v);
    }
    return 0;
}

static int parse_octave(ctx *c, const cJSON *o, const char *where, np_ref_octave *oc)
{
    static const char *const keys[] = { "amplitude", "scale", "matrix", "offset", NULL };
    char f[256];
    if (need_object(c, o, where) || check_keys(c, o, where, keys) ||
        read_number(c, get(o, "amplitude"), path_key(f, sizeof f, where, "amplitude"), -1e5, 1e5, &oc->amp))
        return -1;
    memset(oc->m, 0, sizeof oc->m);
    const cJSON *sc = get(o, "scale"), *mx = get(o, "matrix");
    if (sc && mx)
        return fail(c, path_key(f, sizeof f, where, "matrix"), "give either \"scale\" or \"matrix\", not both");
    if (mx) {
        if (!cJSON_IsArray(mx) || cJSON_GetArraySize(mx) != 3)
            return fail(c, path_key(f, sizeof f, where, "matrix"), "expected 3 rows of 3 numbers");
        for (int a = 0; a < 3; a++) {
            char fr[256];
            path_key(f, sizeof f, where, "matrix");
            if (read_vec3(c, cJSON_GetArrayItem(mx, a), path_idx(fr, sizeof fr, f, a), -127.0, 127.0, oc->m[a]))
                return -1;
        }
    } else if (sc) {
        double d[3];
        if (read_vec3(c, sc, path_key(f, sizeof f, where, "scale"), -127.0, 127.0, d))
            return -1;
        for (int a = 0; a < 3; a++)
            oc->m[a][a] = d[a];
    } else {
        for (int a = 0; a < 3; a++)
            oc->m[a][a] = 1.0;
    }
    memset(oc->o, 0, sizeof oc->o);
    if (get(o, "offset") &&
        read_vec3(c, get(o, "offset"), path_key(f, sizeof f, where, "offset"), -16384.0, 16384.0, oc->o))
        return -1;
    return 0;
}

/* A number that is a multiple of 1/256 in [0, 256), as its u16 Q8.8 word. */
static int read_q88(ctx *c, const cJSON *v, const char *field, uint16_t *out)
{
    double d = 0.0;
    if (read_number(c, v, field, 0.0, 255.99609375, &d))
        return -1;
    double w = d * 256.0;
    if (w != floor(w))
        return fail(c, field, "%g is not a multiple of 1/256 (the register is u16 Q8.8)", d);
    *out = (uint16_t)w;
    return 0;
}

/* "texture.noise" (np_scene_noise). */
static int parse_noise(ctx *c, const cJSON *t, np_scene *s)
{
    static const char *const keys[] = { "unit", "w0", "dw", "frames", NULL };
    static const char *const units[] = { "simplex4", "classic4", NULL };
    const cJSON *n = get(t, "noise");
    np_scene_noise *q = &s->noise;
    int u;
    if (!n)
        return 0;
    if (need_object(c, n, "texture.noise") || check_keys(c, n, "texture.noise", keys) ||
        read_string(c, get(n, "unit"), "texture.noise.unit", units, &u))
        return -1;
    q->present = 1;
    snprintf(q->unit, sizeof q->unit, "%s", units[u]);
    q->frames = 8;
    if ((get(n, "w0") && read_q88(c, get(n, "w0"), "texture.noise.w0", &q->w0)) ||
        (get(n, "dw") && read_q88(c, get(n, "dw"), "texture.noise.dw", &q->dw)) ||
        (get(n, "frames") && read_uint(c, get(n, "frames"), "texture.noise.frames", 1, 100, &q->frames)))
        return -1;
    return 0;
}

static int parse_texture(ctx *c, const cJSON *root, np_scene *s)
{
    static const char *const keys[] = { "quadric", "octaves", "colormap", "noise", NULL };
    static const char *const qkeys[] = { "A", "B", "C", "D", "E", "F", "G", "H", "I", "J", NULL };
    static const char *const ckeys[] = { "mode", "domain", "colors", NULL };
    static const char *const modes[] = { "repeat", "clamp", NULL };
    const cJSON *t = get(root, "texture");
    np_ref_texture *tx = &s->tex;
    char f[256];
    if (need_object(c, t, "texture") || check_keys(c, t, "texture", keys) || parse_noise(c, t, s))
        return -1;
    const cJSON *q = get(t, "quadric");
    if (q) {
        if (need_object(c, q, "texture.quadric") || check_keys(c, q, "texture.quadric", qkeys))
            return -1;
        for (int i = 0; i < 10; i++)
            if (get(q, qkeys[i]) && read_number(c, get(q, qkeys[i]), path_key(f, sizeof f, "texture.quadric", qkeys[i]),
                                                -1e6, 1e6, &tx->quad[i]))
                return -1;
    }
    const cJSON *oc = get(t, "octaves");
    if (oc) {
        if (!cJSON_IsArray(oc) || cJSON_GetArraySize(oc) > NP_REF_MAX_OCTAVES)
            return fail(c, "texture.octaves", "expected an array of at most %d octaves", NP_REF_MAX_OCTAVES);
        tx->n_oct = (unsigned)cJSON_GetArraySize(oc);
        for (unsigned i = 0; i < tx->n_oct; i++)
            if (parse_octave(c, cJSON_GetArrayItem(oc, (int)i), path_idx(f, sizeof f, "texture.octaves", (int)i),
                             &tx->oct[i]))
                return -1;
    }
    const cJSON *cm = get(t, "colormap");
    np_ref_colormap *m = &tx->cmap;
    int mode;
    double dom[2] = { 0, 0 };
    if (need_object(c, cm, "texture.colormap") || check_keys(c, cm, "texture.colormap", ckeys) ||
        read_string(c, get(cm, "mode"), "texture.colormap.mode", modes, &mode))
        return -1;
    m->repeat = mode == 0;
    const cJSON *d = get(cm, "domain");
    if (!d || !cJSON_IsArray(d) || cJSON_GetArraySize(d) != 2)
        return fail(c, "texture.colormap.domain", "%s (expected [f0, f1] with f0 < f1)", d ? "wrong type" : "missing");
    if (read_number(c, cJSON_GetArrayItem(d, 0), "texture.colormap.domain[0]", -1e6, 1e6, &dom[0]) ||
        read_number(c, cJSON_GetArrayItem(d, 1), "texture.colormap.domain[1]", -1e6, 1e6, &dom[1]))
        return -1;
    if (!(dom[1] > dom[0]))
        return fail(c, "texture.colormap.domain", "expected [f0, f1] with f0 < f1");
    m->f0 = dom[0];
    m->f1 = dom[1];
    const cJSON *cols = get(cm, "colors");
    int nc = cols && cJSON_IsArray(cols) ? cJSON_GetArraySize(cols) : -1;
    if (nc < 2 || nc > NP_REF_CMAP_MAX)
        return fail(c, "texture.colormap.colors", "expected an array of 2..%d colours [r, g, b]", NP_REF_CMAP_MAX);
    if (m->repeat && (nc & (nc - 1)) != 0)
        return fail(c, "texture.colormap.colors",
                    "%d entries: a repeating map needs a power of two (the unit wraps the index with a mask)", nc);
    m->n = (unsigned)nc;
    for (int i = 0; i < nc; i++)
        if (read_rgb(c, cJSON_GetArrayItem(cols, i), path_idx(f, sizeof f, "texture.colormap.colors", i), m->c[i]))
            return -1;
    return 0;
}

int np_scene_parse(const char *json, const char *name, np_scene *s, char *err, size_t errlen)
{
    static const char *const keys[] = { "noisepipe_scene", "name", "description", "image", "camera",
                                        "geometry", "texture", "probe_row", "allow_empty", "light", "aa", "hatch", NULL };
    ctx c = { name, err, errlen, 0, 0 };
    memset(s, 0, sizeof *s);
    snprintf(s->path, sizeof s->path, "%s", name);
    const char *end = NULL;
    cJSON *root = cJSON_ParseWithOpts(json, &end, 1);
    if (!root) {
        /* Line and column of the point where parsing stopped. */
        unsigned line = 1, col = 1;
        long depth = 0, deepest = 0;
        int in_str = 0;
        for (const char *p = json; end && p < end && *p; p++, col++) {
            if (*p == '\n')
                line++, col = 0;
            /* Nesting depth outside strings: cJSON stops at CJSON_NESTING_LIMIT. */
            if (in_str)
                in_str = !(*p == '"' && p[-1] != '\\');
            else if (*p == '"')
                in_str = 1;
            else if (*p == '[' || *p == '{')
                deepest = ++depth > deepest ? depth : deepest;
            else if (*p == ']' || *p == '}')
                depth--;
        }
        if (deepest >= CJSON_NESTING_LIMIT)
            snprintf(err, errlen, "%s:%u:%u: JSON nested deeper than %d levels (a scene needs at most 5)", name,
                     line, col, CJSON_NESTING_LIMIT);
        else
            snprintf(err, errlen, "%s:%u:%u: not valid JSON", name, line, col);
        return -1;
    }
    unsigned version = 0;
    if (!cJSON_IsObject(root)) {
        fail(&c, "(top level)", "expected an object");
        goto out;
    }
    if (check_keys(&c, root, "", keys) ||
        read_uint(&c, get(root, "noisepipe_scene"), "noisepipe_scene", 1, 1, &version))
        goto out;
    const cJSON *nm = get(root, "name");
    if (!nm || !cJSON_IsString(nm) || strlen(nm->valuestring) == 0 || strlen(nm->valuestring) >= sizeof s->name) {
        fail(&c, "name", "expected a string of 1..%zu characters", sizeof s->name - 1);
        goto out;
    }
    for (const char *p = nm->valuestring; *p; p++)
        if (!((*p >= 'a' && *p <= 'z') || (*p >= 'A' && *p <= 'Z') || (*p >= '0' && *p <= '9') || *p == '_' ||
              *p == '-')) {
            fail(&c, "name", "expected letters, digits, '_' or '-' (it names the output files)");
            goto out;
        }
    snprintf(s->name, sizeof s->name, "%s", nm->valuestring);
    const cJSON *desc = get(root, "description");
    if (desc && !cJSON_IsString(desc)) {
        fail(&c, "description", "expected a string");
        goto out;
    }
    if (parse_image(&c, root, s) || parse_camera(&c, root, s) || parse_light(&c, root, s) ||
        parse_aa(&c, root, s) || parse_hatch(&c, root, s) || parse_geometry(&c, root, s) || parse_texture(&c, root, s))
        goto out;
    s->probe_row = s->height / 2u;
    if (get(root, "probe_row"))
        read_uint(&c, get(root, "probe_row"), "probe_row", 0, s->height - 1u, &s->probe_row);
    const cJSON *ae = get(root, "allow_empty");
    if (ae && !cJSON_IsBool(ae))
        fail(&c, "allow_empty", "expected true or false");
    s->allow_empty = ae && cJSON_IsTrue(ae);
out:
    cJSON_Delete(root);
    if (c.failed) {
        np_scene_free(s);
        return -1;
    }
    return 0;
}

int np_scene_load(const char *path, np_scene *s, char *err, size_t errlen)
{
    memset(s, 0, sizeof *s);
    if (strncmp(path, "embedded:", 9) == 0) {
        for (const np_scene_embedded *e = np_scenes_embedded; e->name; e++)
            if (strcmp(e->name, path + 9) == 0)
                return np_scene_parse(e->json, path, s, err, errlen);
        snprintf(err, errlen, "%s: no such embedded scene (", path);
        for (const np_scene_embedded *e = np_scenes_embedded; e->name; e++)
            snprintf(err + strlen(err), errlen - strlen(err), "%sembedded:%s", e == np_scenes_embedded ? "" : ", ",
                     e->name);
        snprintf(err + strlen(err), errlen - strlen(err), ")");
        return -1;
    }
    FILE *f = fopen(path, "rb");
    if (!f) {
        snprintf(err, errlen, "%s: cannot open: %s", path, strerror(errno));
        return -1;
    }
    size_t cap = 1 << 16, n = 0;
    char *buf = malloc(cap);
    for (;;) {
        if (!buf) {
            fclose(f);
            snprintf(err, errlen, "%s: out of memory", path);
            return -1;
        }
        n += fread(buf + n, 1, cap - n - 1, f);
        if (n < cap - 1)
            break;
        if (cap >= ((size_t)1 << 26)) {
            free(buf);
            fclose(f);
            snprintf(err, errlen, "%s: larger than 64 MiB: not a scene", path);
            return -1;
        }
        cap *= 2;
        char *nb = realloc(buf, cap);
        if (!nb)
            free(buf);
        buf = nb;
    }
    int bad = ferror(f);
    fclose(f);
    if (bad) {
        free(buf);
        snprintf(err, errlen, "%s: read error", path);
        return -1;
    }
    buf[n] = '\0';
    if (strlen(buf) != n) {
        free(buf);
        snprintf(err, errlen, "%s: contains a NUL byte: not a JSON text", path);
        return -1;
    }
    int rc = np_scene_parse(buf, path, s, err, errlen);
    free(buf);
    return rc;
}

void np_scene_free(np_scene *s)
{
    for (unsigned i = 0; i < s->n_mesh; i++) {
        free(s->mesh[i].p);
        free(s->mesh[i].t);
        free(s->mesh[i].tri);
    }
    free(s->mesh);
    s->mesh = NULL;
    s->n_mesh = 0;
    s->n_prims = 0;
    free(s->poly);
    s->poly = NULL;
    s->n_poly = 0;
}

/* --- The scene as the units see it (np_unit_scene) --- */

void np_scene_for_units(const np_scene *s, np_unit_scene *us)
{
    memset(us, 0, sizeof *us);
    us->name = s->name;
    us->width = s->width;
    us->tex = &s->tex;
    for (int a = 0; a < 3; a++) {
        us->tex_lo[a] = (double)INFINITY;
        us->tex_hi[a] = -(double)INFINITY;
    }
    for (unsigned p = 0; p < s->n_poly; p++)
        for (unsigned v = 0; v < s->poly[p].n; v++)
            for (int a = 0; a < 3; a++) {
                us->tex_lo[a] = fmin(us->tex_lo[a], s->poly[p].t[v][a]);
                us->tex_hi[a] = fmax(us->tex_hi[a], s->poly[p].t[v][a]);
            }
    if (s->n_poly == 0)
        for (int a = 0; a < 3; a++)
            us->tex_lo[a] = us->tex_hi[a] = 0;
    us->size_registers = s->size_registers;
    us->noise_unit = s->noise.present ? s->noise.unit : NULL;
    us->aa = s->aa.present ? &s->aa : NULL;
    us->hatch = s->hatch.present ? &s->hatch : NULL;
}

int np_scene_cfg_unit(const np_unit *u, void *cfg, const np_scene *s, char *err, size_t errlen)
{
    if (!u->cfg_scene)
        return 0;
    np_unit_scene us;
    np_scene_for_units(s, &us);
    return u->cfg_scene(cfg, &us, err, errlen);
}
