/* SPDX-License-Identifier: MIT */
/* A water grid with wave train boxes through the wave unit (np_wave_scene.h, docs/wave.md "Scenes"). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "np_classic.h"
#include "np_math.h"
#include "np_wave_host.h"
#include "np_wave_scene.h"

static const double TWO_PI = 6.283185307179586;

enum {
    RECOVER = 16,     /* PIN: grid units of linear recovery behind land */
    KTAB = 1024       /* refraction: k(D) tabulated over [0, D_ref] */
};
static const double GAIN_CAP = 1.3; /* PIN: Green's law capped at 1.3x */

void np_wave_scene_init(np_wave_scene *s)
{
    memset(s, 0, sizeof *s);
    s->grid = 256;
    s->extent = 512.0;
    s->dt = 1.0 / 60.0;
    s->effects = NP_WAVE_FX_REFRACTION;
    s->lanes = 1;
    s->noise_amp = 0.05;
    s->noise_rate = 4.0;
    s->sea_depth = 30.0;
    s->isl_scale = 64.0;
}

void np_wave_scene_free(np_wave_scene *s)
{
    for (unsigned k = 0; k < s->nbox; k++) {
        free(s->box[k].pts);
        free(s->box[k].gpts);
        s->box[k].pts = s->box[k].gpts = NULL;
    }
    free(s->depth);
    free(s->rate);
    s->depth = NULL;
    s->rate = NULL;
}

/* The classic3 unit (8-bit output, s8 Q2.6) at (x, z) metres / scale, slice zs: in [-1.5, 1.5]. */
static double noise_at(double x, double z, double scale, uint16_t zs)
{
    static const np_classic_cfg *cp;
    static np_classic_cfg c;
    if (!cp) {
        c = np_classic_cfg_default(8);
        cp = &c;
    }
    double u = fmod(x / scale, 256.0), v = fmod(z / scale, 256.0);
    uint16_t qx = (uint16_t)(u * 256.0), qz = (uint16_t)(v * 256.0);
    return (double)np_classic_eval(cp, qx, qz, zs) / 64.0;
}

static void terrain(np_wave_scene *s)
{
    unsigned n = s->grid;
    for (unsigned j = 0; j < n; j++)
        for (unsigned i = 0; i < n; i++) {
            double x = i * s->spacing, z = j * s->spacing, h = -s->sea_depth;
            if (s->isl_radius > 0.0) {
                double r = hypot(x - s->isl_x, z - s->isl_z), cone = 1.0 - r / s->isl_radius;
                h += (s->isl_height + s->sea_depth) * (cone > 0.0 ? cone : 0.0);
                double fall = 1.0 - r / (1.5 * s->isl_radius);
                h += s->isl_noise * noise_at(x, z, s->isl_scale, 0x0080) * (fall > 0.0 ? fall : 0.0);
            }
            s->depth[(size_t)j * n + i] = (float)-h;
            double r8 = (noise_at(x, z, s->isl_scale / 4.0, 0x3380) + 1.5) / 3.0 * 256.0;
            s->rate[(size_t)j * n + i] = (uint8_t)(r8 < 0.0 ? 0 : r8 > 255.0 ? 255 : r8);
        }
}

static double depth_at(const np_wave_scene *s, double x, double z)
{
    long i = lround(x / s->spacing), j = lround(z / s->spacing);
    if (i < 0 || j < 0 || i >= (long)s->grid || j >= (long)s->grid)
        return s->sea_depth;
    return (double)s->depth[(size_t)j * s->grid + (size_t)i];
}

void np_wave_box_axes(np_wave_box *b) { np_sincos_turns(b->angle / TWO_PI, &b->uz, &b->ux); }

/* Box coordinates of grid point (i, j) in grid units: s along u, w along v. */
static void box_coords(const np_wave_box *b, double spacing, unsigned i, unsigned j, double *s, double *w)
{
    double px = i * spacing - b->ox, pz = j * spacing - b->oz;
    *s = (px * b->ux + pz * b->uz) / spacing;
    *w = (-px * b->uz + pz * b->ux) / spacing;
}

int np_wave_cell_of(const np_wave_box *b, double spacing, unsigned i, unsigned j, unsigned *a, unsigned *r)
{
    double s, w;
    box_coords(b, spacing, i, j, &s, &w);
    double ca = ceil(s) - 1.0, cb = floor(w);
    if (ca < 0.0 || cb < 0.0 || ca >= (double)b->steps || cb >= (double)b->rays)
        return 0;
    *a = (unsigned)ca;
    *r = (unsigned)cb;
    return 1;
}

/* The grid points of cell (a, r): every grid point of the cell corners' bounding box (+-1) kept when it is the cell's. */
static size_t cell_points(const np_wave_box *b, double spacing, unsigned grid, unsigned a, unsigned r,
                          void (*f)(void *ctx, unsigned i, unsigned j, unsigned a, unsigned r), void *ctx)
{
    const double ux = b->ux, uz = b->uz;
    double x0 = b->ox / spacing, z0 = b->oz / spacing, lo_x = 1e300, hi_x = -1e300, lo_z = 1e300, hi_z = -1e300;
    size_t n = 0;
    for (unsigned c = 0; c < 4; c++) {
        double s = a + (c & 1u), w = r + (c >> 1);
        double x = x0 + s * ux - w * uz, z = z0 + s * uz + w * ux;
        lo_x = x < lo_x ? x : lo_x;
        hi_x = x > hi_x ? x : hi_x;
        lo_z = z < lo_z ? z : lo_z;
        hi_z = z > hi_z ? z : hi_z;
    }
    long i0 = (long)floor(lo_x) - 1, i1 = (long)ceil(hi_x) + 1, j0 = (long)floor(lo_z) - 1, j1 = (long)ceil(hi_z) + 1;
    i0 = i0 < 0 ? 0 : i0;
    j0 = j0 < 0 ? 0 : j0;
    i1 = i1 >= (long)grid ? (long)grid - 1 : i1;
    j1 = j1 >= (long)grid ? (long)grid - 1 : j1;
    for (long j = j0; j <= j1; j++)
        for (long i = i0; i <= i1; i++) {
            unsigned ca, cr;
            if (np_wave_cell_of(b, spacing, (unsigned)i, (unsigned)j, &ca, &cr) && ca == a && cr == r) {
                if (f)
                    f(ctx, (unsigned)i, (unsigned)j, a, r);
                n++;
            }
        }
    return n;
}

size_t np_wave_box_walk(const np_wave_box *b, double spacing, unsigned grid,
                        void (*f)(void *ctx, unsigned i, unsigned j, unsigned a, unsigned r), void *ctx)
{
    size_t n = 0;
    for (unsigned r = 0; r < b->rays; r++)
        for (unsigned a = 0; a < b->steps; a++)
            n += cell_points(b, spacing, grid, a, r, f, ctx);
    return n;
}

/* --- a box's point list, with its rays' gain and phase --- */

typedef struct ray_state {
    np_wave_box *b;
    const np_wave_scene *s;
    size_t cap;
    uint32_t ph;
    uint16_t g;
} ray_state;

static void add_pt(void *ctx, unsigned i, unsigned j, unsigned a, unsigned r)
{
    ray_state *q = ctx;
    np_wave_box *b = q->b;
    if (b->npts == q->cap) {
        q->cap = q->cap ? 2 * q->cap : 1024;
        np_wave_pt *p = realloc(b->pts, q->cap * sizeof *p);
        if (!p)
            return;
        b->pts = p;
    }
    np_wave_pt *p = &b->pts[b->npts++];
    p->i = (uint16_t)i;
    p->j = (uint16_t)j;
    p->a = (uint16_t)a;
    p->b = (uint16_t)r;
    p->ph = q->ph;
    /* The ray's gain, and 0 on a land point whatever the cell's action point says. */
    p->g = q->s->depth[(size_t)j * q->s->grid + i] <= 0.0f ? 0u : q->g;
}

static uint32_t turns_u32(double x)
{
    double f = x - floor(x), v = floor(f * 4294967296.0 + 0.5);
    return v >= 4294967296.0 ? 0u : (uint32_t)v;
}

/* Walk ray by ray, cell by cell: the action points (depth) set the gain and the refraction phase. */
/* Grid order: j, then i. */
static int pt_grid_order(const void *a, const void *b)
{
    const np_wave_pt *p = a, *q = b;
    uint32_t ka = (uint32_t)p->j << 16 | p->i, kb = (uint32_t)q->j << 16 | q->i;
    return (ka > kb) - (ka < kb);
}

static int build_points(const np_wave_scene *s, np_wave_box *b)
{
    unsigned dom = 0;
    for (unsigned k = 1; k < b->n; k++)
        if (b->tr[k].amp > b->tr[dom].amp)
            dom = k;
    double kd = TWO_PI / b->tr[dom].lambda, w = np_wave_omega(kd, 1e9), dref = b->tr[dom].lambda / 2.0;
    double ktab[KTAB + 1];
    for (unsigned q = 0; q <= KTAB; q++)
        ktab[q] = q == 0 ? 0.0 : np_wave_k_of_omega(w, dref * q / KTAB);
    double ux = b->ux, uz = b->uz, sp = s->spacing;
    ray_state st = { b, s, 0, 0, 0 };
    free(b->pts);
    free(b->gpts);
    b->pts = b->gpts = NULL;
    b->npts = 0;
    for (unsigned r = 0; r < b->rays; r++) {
        double acc = 0.0, phr = 0.0;
        unsigned since = RECOVER;
        if (s->effects & NP_WAVE_FX_ROUND) {
            double v = r + 0.5 - 0.5 * b->rays; /* eq. (10), PIN: a delay of k (v - V/2)^2 / V grid units */
            phr = kd * sp * v * v / (double)b->rays;
        }
        for (unsigned a = 0; a < b->steps; a++) {
            double sx = (a + 0.5), wv = (r + 0.5);
            double x = b->ox + (sx * ux - wv * uz) * sp, z = b->oz + (sx * uz + wv * ux) * sp;
            double d = depth_at(s, x, z), g;
            if (d <= 0.0) {
                g = 0.0;
                since = 0;
            } else {
                double green = d >= dref ? 1.0 : np_exp2(-0.25 * np_log2(d / dref));
                green = green > GAIN_CAP ? GAIN_CAP : green;
                if (since < RECOVER)
                    since++;
                g = green * (double)since / RECOVER;
                if (s->effects & NP_WAVE_FX_REFRACTION) {
                    double kk = d >= dref ? kd : ktab[(unsigned)(d / dref * KTAB)];
                    acc += (kk - kd) * sp;
                }
            }
            st.ph = turns_u32((acc + phr) / TWO_PI);
            double gq = floor(g * 16384.0 + 0.5);
            st.g = (uint16_t)(gq > 32767.0 ? 32767.0 : gq);
            cell_points(b, sp, s->grid, a, r, add_pt, &st);
        }
    }
    if (st.cap != 0 && !b->pts)
        return -1;
    /* The grid-order copy: a box's points are distinct grid points, so (j, i) orders them totally. */
    if (b->npts) {
        b->gpts = malloc(b->npts * sizeof *b->gpts);
        if (!b->gpts)
            return -1;
        memcpy(b->gpts, b->pts, b->npts * sizeof *b->gpts);
        qsort(b->gpts, b->npts, sizeof *b->gpts, pt_grid_order);
    }
    return 0;
}

/* --- prepare --- */

static int box_registers(const np_wave_scene *s, np_wave_box *b, unsigned *dropped, char *err, size_t errlen, unsigned bi)
{
    np_wave_phys p;
    memset(&p, 0, sizeof p);
    p.n = b->n;
    p.spacing = s->spacing;
    p.dt = s->dt;
    double sum_a = 0.0;
    unsigned dom = 0;
    for (unsigned k = 0; k < b->n; k++) {
        sum_a += b->tr[k].amp;
        if (b->tr[k].amp > b->tr[dom].amp)
            dom = k;
    }
    for (unsigned k = 0; k < b->n; k++) {
        const np_wave_train_spec *t = &b->tr[k];
        double kk = TWO_PI / t->lambda, sd, cd;
        np_sincos_turns((b->angle + t->angle) / TWO_PI, &sd, &cd);
        p.tr[k].kx = kk * cd;
        p.tr[k].kz = kk * sd;
        p.tr[k].omega = np_wave_omega(kk, 1e9); /* deep water: refraction is a phase shift (section 2.1) */
        p.tr[k].phi = t->phase;
        p.tr[k].amp = t->amp;
        p.tr[k].airr = (s->effects & NP_WAVE_FX_IRREGULAR) && sum_a > 0.0 ? b->irr_a * t->amp / sum_a : 0.0;
    }
    memset(&b->unit, 0, sizeof b->unit);
    b->unit.c = np_wave_cfg_default();
    b->unit.c.trains = b->n;
    b->unit.c.irr = (s->effects & NP_WAVE_FX_IRREGULAR) ? 1u : 0u;
    b->unit.c.cap = 0; /* eq. (9) is the frame's own pass over every water point */
    np_wave_regs *r = &b->unit.r;
    unsigned drop = 0;
    np_wave_quantise(&p, r, &drop);
    *dropped += drop;
    r->width = (uint16_t)b->rays;
    r->mlog2 = NP_WAVE_MLOG2_DEF;
    r->gcap = NP_WAVE_GCAP_DEF;
    /* Eq. (8), PIN: sin(2 pi (t / 8 s + u / (4 lambda))) sin(2 pi v / 64 rays). */
    double ld = b->tr[dom].lambda;
    r->pt = turns_u32(s->dt / 8.0);
    r->pu = turns_u32(s->spacing / (4.0 * ld));
    r->pv = turns_u32(1.0 / 64.0);
    if (r->n == 0) {
        snprintf(err, errlen, "waves.boxes[%u]: every train is above the grid's Nyquist limit (lambda <= 2 x %.3g m)", bi,
                 s->spacing);
        return -1;
    }
    const char *why = np_wave_regs_check(&b->unit.c, r);
    if (why) {
        snprintf(err, errlen, "waves.boxes[%u]: %s", bi, why);
        return -1;
    }
    b->sum_ka = 0.0;
    for (unsigned k = 0; k < b->n; k++)
        b->sum_ka += GAIN_CAP * (TWO_PI / b->tr[k].lambda) * (b->tr[k].amp + p.tr[k].airr);
    return 0;
}

int np_wave_scene_prepare(np_wave_scene *s, unsigned *dropped, char *err, size_t errlen)
{
    size_t n2 = (size_t)s->grid * s->grid;
    unsigned drop = 0;
    s->spacing = s->extent / s->grid;
    free(s->depth);
    free(s->rate);
    s->depth = malloc(n2 * sizeof *s->depth);
    s->rate = malloc(n2);
    uint16_t *mask = calloc(n2, sizeof *mask);
    if (!s->depth || !s->rate || !mask) {
        free(mask);
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    terrain(s);
    for (unsigned k = 0; k < s->nbox; k++) {
        np_wave_box *b = &s->box[k];
        np_wave_box_axes(b);
        b->steps = (unsigned)lround(b->length / s->spacing);
        b->rays = (unsigned)lround(b->width / s->spacing);
        if (b->steps < 1 || b->rays < 1 || b->rays > 65535u || b->steps > 65535u) {
            free(mask);
            snprintf(err, errlen, "waves.boxes[%u]: length and width give %u x %u grid units (1 .. 65535 each)", k,
                     b->steps, b->rays);
            return -1;
        }
        if (box_registers(s, b, &drop, err, errlen, k) != 0 || build_points(s, b) != 0) {
            free(mask);
            if (!*err)
                snprintf(err, errlen, "waves.boxes[%u]: out of memory", k);
            return -1;
        }
        for (size_t q = 0; q < b->npts; q++)
            mask[(size_t)b->pts[q].j * s->grid + b->pts[q].i] |= (uint16_t)(1u << k);
    }
    /* Overlaps: the OBB holds its own and every overlapping box's 1.3 sum (A + a); sum k A where they overlap. */
    uint16_t over[NP_WAVE_MAX_BOXES] = { 0 };
    double worst = 0.0;
    size_t worst_at = 0;
    for (size_t q = 0; q < n2; q++) {
        double ka = 0.0;
        for (unsigned k = 0; k < s->nbox; k++)
            if (mask[q] & (1u << k)) {
                over[k] |= mask[q];
                ka += s->box[k].sum_ka;
            }
        if (ka > worst) {
            worst = ka;
            worst_at = q;
        }
    }
    free(mask);
    for (unsigned k = 0; k < s->nbox; k++) {
        np_wave_box *b = &s->box[k];
        double h = 0.0;
        for (unsigned o = 0; o < s->nbox; o++)
            if ((over[k] & (1u << o)) || o == k)
                h += (double)np_wave_range_lsb(&s->box[o].unit.r, 0) / 1024.0;
        b->grow = h;
        b->hmax = h + ((s->effects & NP_WAVE_FX_NOISE) ? s->noise_amp : 0.0);
    }
    if (dropped)
        *dropped = drop;
    if (worst > 1.0 && !s->allow_fold) {
        snprintf(err, errlen,
                 "waves: the surface folds: 1.3 x sum k (A + a) = %.3f > 1 at grid point (%zu, %zu) (boxes overlapping "
                 "there summed; set \"allow_fold\": true to accept it)",
                 worst, worst_at % s->grid, worst_at / s->grid);
        return -1;
    }
    return 0;
}

/* --- culling --- */

static void normalize3(double v[3])
{
    double l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (unsigned k = 0; k < 3; k++)
        v[k] /= l;
}

/* The six planes (a, b, c, d: inside when a x + b y + c z + d >= 0) of the camera's frustum (Gribb and Hartmann). */
static void frustum_planes(const np_wave_camera *c, double pl[6][4])
{
    double f[3], r[3], u[3];
    for (unsigned k = 0; k < 3; k++)
        f[k] = c->target[k] - c->eye[k];
    normalize3(f);
    r[0] = f[1] * c->up[2] - f[2] * c->up[1];
    r[1] = f[2] * c->up[0] - f[0] * c->up[2];
    r[2] = f[0] * c->up[1] - f[1] * c->up[0];
    normalize3(r);
    u[0] = r[1] * f[2] - r[2] * f[1];
    u[1] = r[2] * f[0] - r[0] * f[2];
    u[2] = r[0] * f[1] - r[1] * f[0];
    /* View matrix rows (column vectors): x_v = r.(p - e), y_v = u.(p - e), z_v = -f.(p - e). */
    double V[4][4] = { { r[0], r[1], r[2], 0 }, { u[0], u[1], u[2], 0 }, { -f[0], -f[1], -f[2], 0 }, { 0, 0, 0, 1 } };
    for (unsigned k = 0; k < 3; k++)
        V[k][3] = -(V[k][0] * c->eye[0] + V[k][1] * c->eye[1] + V[k][2] * c->eye[2]);
    double hs, hc;
    np_sincos_turns(c->fov_y / 2.0 / TWO_PI, &hs, &hc);
    double t = hc / hs, n = c->znear, fa = c->zfar;
    double P[4][4] = { { t / c->aspect, 0, 0, 0 }, { 0, t, 0, 0 }, { 0, 0, (fa + n) / (n - fa), 2 * fa * n / (n - fa) },
                       { 0, 0, -1, 0 } };
    double M[4][4];
    for (unsigned i = 0; i < 4; i++)
        for (unsigned j = 0; j < 4; j++) {
            M[i][j] = 0.0;
            for (unsigned k = 0; k < 4; k++)
                M[i][j] += P[i][k] * V[k][j];
        }
    for (unsigned k = 0; k < 4; k++) {
        pl[0][k] = M[3][k] + M[0][k];
        pl[1][k] = M[3][k] - M[0][k];
        pl[2][k] = M[3][k] + M[1][k];
        pl[3][k] = M[3][k] - M[1][k];
        pl[4][k] = M[3][k] + M[2][k];
        pl[5][k] = M[3][k] - M[2][k];
    }
}

int np_wave_box_visible(const np_wave_scene *s, const np_wave_box *b)
{
    if (!s->has_camera)
        return 1;
    double pl[6][4];
    frustum_planes(&s->cam, pl);
    double ux = b->ux, uz = b->uz;
    double ax[3][3] = { { ux, 0, uz }, { -uz, 0, ux }, { 0, 1, 0 } };
    /* The OBB: the rectangle grown by the horizontal displacement, the height of every box overlapping it. */
    double e[3] = { b->length / 2.0 + b->grow, b->width / 2.0 + b->grow, b->hmax };
    double c[3] = { b->ox + ux * b->length / 2.0 - uz * b->width / 2.0, 0.0,
                    b->oz + uz * b->length / 2.0 + ux * b->width / 2.0 };
    for (unsigned p = 0; p < 6; p++) {
        double dist = pl[p][0] * c[0] + pl[p][1] * c[1] + pl[p][2] * c[2] + pl[p][3], rad = 0.0;
        for (unsigned k = 0; k < 3; k++)
            rad += e[k] * fabs(pl[p][0] * ax[k][0] + pl[p][1] * ax[k][1] + pl[p][2] * ax[k][2]);
        if (dist < -rad)
            return 0; /* wholly outside this plane (touching it counts as inside) */
    }
    return 1;
}

/* --- plans, cycles, the budget --- */

static unsigned popcount(unsigned v)
{
    unsigned n = 0;
    for (; v; v &= v - 1u)
        n++;
    return n;
}

void np_wave_plan_full(const np_wave_scene *s, np_wave_plan *p)
{
    memset(p, 0, sizeof *p);
    for (unsigned k = 0; k < s->nbox; k++) {
        p->visible[k] = np_wave_box_visible(s, &s->box[k]);
        p->sel[k] = p->visible[k] ? (1u << s->box[k].unit.r.n) - 1u : 0u;
    }
    p->noise = (s->effects & NP_WAVE_FX_NOISE) != 0;
}

static uint64_t box_cycles(const np_wave_scene *s, const np_wave_box *b, unsigned nsel)
{
    if (nsel == 0)
        return 0;
    uint64_t passes = (nsel + s->lanes - 1u) / s->lanes;
    return NP_WAVE_CYC_BOX + (uint64_t)NP_WAVE_CYC_TRAIN * nsel +
           passes * ((uint64_t)NP_WAVE_CYC_RAY * b->rays + b->npts) + np_wave_stage_count();
}

static uint64_t noise_cycles(const np_wave_scene *s) { return (uint64_t)s->grid * s->grid + np_wave_stage_count(); }

uint64_t np_wave_plan_cycles(const np_wave_scene *s, const np_wave_plan *p)
{
    uint64_t c = (uint64_t)NP_WAVE_CYC_CULL * s->nbox;
    for (unsigned k = 0; k < s->nbox; k++)
        c += box_cycles(s, &s->box[k], popcount(p->sel[k]));
    return c + (p->noise ? noise_cycles(s) : 0u);
}

void np_wave_plan_budget(const np_wave_scene *s, uint64_t budget, np_wave_plan *p)
{
    memset(p, 0, sizeof *p);
    unsigned cand[NP_WAVE_MAX_BOXES * NP_WAVE_MAX_TRAINS], nc = 0;
    for (unsigned k = 0; k < s->nbox; k++) {
        p->visible[k] = np_wave_box_visible(s, &s->box[k]);
        for (unsigned t = 0; p->visible[k] && t < s->box[k].unit.r.n; t++)
            cand[nc++] = k * NP_WAVE_MAX_TRAINS + t;
    }
    /* PIN: descending A (ties: box, then train, in order); insertion sort, stable. */
    for (unsigned x = 1; x < nc; x++)
        for (unsigned y = x; y > 0; y--) {
            unsigned a = cand[y - 1], b = cand[y];
            uint16_t aa = s->box[a / NP_WAVE_MAX_TRAINS].unit.r.tr[a % NP_WAVE_MAX_TRAINS].amp;
            uint16_t ab = s->box[b / NP_WAVE_MAX_TRAINS].unit.r.tr[b % NP_WAVE_MAX_TRAINS].amp;
            if (ab <= aa)
                break;
            cand[y - 1] = b;
            cand[y] = a;
        }
    uint64_t used = np_wave_plan_cycles(s, p);
    for (unsigned q = 0; q < nc; q++) {
        unsigned k = cand[q] / NP_WAVE_MAX_TRAINS, t = cand[q] % NP_WAVE_MAX_TRAINS;
        unsigned ns = popcount(p->sel[k]);
        uint64_t more = box_cycles(s, &s->box[k], ns + 1u) - box_cycles(s, &s->box[k], ns);
        if (used + more <= budget) {
            p->sel[k] |= 1u << t;
            used += more;
        }
    }
    if ((s->effects & NP_WAVE_FX_NOISE) && used + noise_cycles(s) <= budget)
        p->noise = 1;
}

/* --- a frame --- */

uint64_t np_wave_frame(const np_wave_scene *s, const np_wave_plan *p, uint32_t t, int32_t *y, int32_t *dx, int32_t *dz)
{
    size_t n2 = (size_t)s->grid * s->grid;
    memset(y, 0, n2 * sizeof *y);
    memset(dx, 0, n2 * sizeof *dx);
    memset(dz, 0, n2 * sizeof *dz);
    for (unsigned k = 0; k < s->nbox; k++) {
        const np_wave_box *b = &s->box[k];
        unsigned sel = p->sel[k], np = 0;
        np_wave_unit pass[NP_WAVE_MAX_TRAINS];
        while (sel) {
            /* One pass: up to `lanes` of the selected trains. */
            np_wave_unit *u = &pass[np++];
            *u = b->unit;
            u->r.n = 0;
            for (unsigned q = 0; q < b->unit.r.n && u->r.n < s->lanes; q++)
                if (sel & (1u << q)) {
                    u->r.tr[u->r.n++] = b->unit.r.tr[q];
                    sel &= ~(1u << q);
                }
            u->c.trains = u->r.n;
        }
        /* Runs of points, every pass over a run (the sums do not depend on the order). */
        enum { RUN = 256 };
        np_wave_in in[RUN];
        np_wave_out o[RUN];
        for (size_t q0 = 0; np && q0 < b->npts; q0 += RUN) {
            size_t m = b->npts - q0 < RUN ? b->npts - q0 : RUN;
            for (size_t q = 0; q < m; q++) {
                const np_wave_pt *pt = &b->gpts[q0 + q];
                np_wave_in x = { pt->i, pt->j, t, pt->ph, pt->a, pt->b, 0, pt->g };
                in[q] = x;
            }
            for (unsigned e = 0; e < np; e++) {
                np_wave_eval_n(&pass[e], in, o, m);
                for (size_t q = 0; q < m; q++) {
                    size_t at = (size_t)in[q].j * s->grid + in[q].i;
                    y[at] += o[q].y;
                    dx[at] += o[q].dx;
                    dz[at] += o[q].dz;
                }
            }
        }
    }
    if (p->noise) {
        /*
         * Eq. (9) over every water point: the unit's transaction with no train in effect (Y G = 0),
         * y = round(b sc / 2^17), sc the ROM's sin of pc = r omc t (np_wave.h, stage G).
         */
        double bq = floor(s->noise_amp * 1024.0 + 0.5);
        int64_t b = (int64_t)(bq > 32767.0 ? 32767.0 : bq);
        uint32_t omc = turns_u32(s->noise_rate * s->dt / TWO_PI / 256.0);
        for (size_t q = 0; q < n2; q++)
            if (s->depth[q] > 0.0f) {
                uint32_t pc = (uint32_t)s->rate[q] * omc * t;
                y[q] += (int32_t)np_shr_round_half_up(b * np_wave_sin(pc, NP_WAVE_ROM_DEF), NP_WAVE_SIN_FRAC);
            }
    }
    return np_wave_plan_cycles(s, p);
}
