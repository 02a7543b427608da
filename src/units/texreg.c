/* SPDX-License-Identifier: MIT */
/* Float textures into unit registers, and the built-in textures (np_texreg.h). */
#include "np_texreg.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

int np_texreg_quantize(double v, int frac, unsigned bits, int64_t *out)
{
    double x = ldexp(v, frac);
    double lim = ldexp(1.0, (int)bits - 1);
    if (!(fabs(x) < 0x1p52))
        return -1;
    double r = floor(x + 0.5);
    if (!(r >= -lim && r < lim))
        return -1;
    *out = (int64_t)r;
    return 0;
}

double np_texreg_index_scale(const np_ref_colormap *c)
{
    double segs = c->repeat ? (double)c->n : (double)(c->n - 1u);
    return segs / (c->f1 - c->f0);
}

int np_texreg_compile(const np_ref_texture *t, np_tex_regs *r, char *err, size_t errlen)
{
    return np_texreg_compile_fmt(t, NULL, r, err, errlen);
}

int np_texreg_compile_fmt(const np_ref_texture *t, const np_texreg_fmt *fmt, np_tex_regs *r, char *err, size_t errlen)
{
    static const char qn[] = "ABCDEFGHIJ";
    memset(r, 0, sizeof *r);
    if (fmt) {
        r->k_frac = fmt->k_frac;
        r->k_bits = fmt->k_bits;
        r->m_frac = fmt->m_frac;
        r->m_bits = fmt->m_bits;
    }
    const unsigned kf = np_tex_k_frac(r), kb = np_tex_k_bits(r), mf = np_tex_m_frac(r), mb = np_tex_m_bits(r);
    double S = np_texreg_index_scale(&t->cmap);
    for (unsigned i = 0; i < 10; i++) {
        double v = S * (i == 9 ? t->quad[9] - t->cmap.f0 : t->quad[i]);
        if (np_texreg_quantize(v, (int)kf, kb, &r->k[i])) {
            snprintf(err, errlen, "quadric coefficient %c scaled by the colour map (%g) does not fit s%u Q%u.%u", qn[i],
                     v, kb, kb - 1u - kf, kf);
            return -1;
        }
    }
    if (t->n_oct > NP_TEX_MAX_OCTAVES) {
        snprintf(err, errlen, "%u octaves: the units have at most %d", t->n_oct, NP_TEX_MAX_OCTAVES);
        return -1;
    }
    r->n_oct = t->n_oct;
    for (unsigned o = 0; o < t->n_oct; o++) {
        const np_ref_octave *src = &t->oct[o];
        np_tex_octave *d = &r->oct[o];
        int64_t q;
        if (np_texreg_quantize(S * src->amp, NP_TEX_AMP_FRAC, NP_TEX_AMP_BITS, &q)) {
            snprintf(err, errlen, "octave %u: amplitude scaled by the colour map (%g) does not fit s32 Q17.14", o,
                     S * src->amp);
            return -1;
        }
        d->amp = (int32_t)q;
        for (unsigned a = 0; a < 3; a++) {
            for (unsigned b = 0; b < 3; b++) {
                if (np_texreg_quantize(src->m[a][b], (int)mf, mb, &q)) {
                    snprintf(err, errlen, "octave %u: transform entry %g does not fit s%u Q%u.%u", o, src->m[a][b], mb,
                             mb - 1u - mf, mf);
                    return -1;
                }
                d->m[a][b] = q;
            }
            if (np_texreg_quantize(src->o[a], NP_TEX_FC, NP_TEX_O_BITS, &d->o[a])) {
                snprintf(err, errlen, "octave %u: offset %g does not fit s48 Q15.32", o, src->o[a]);
                return -1;
            }
        }
    }
    r->cmap_n = t->cmap.n;
    r->cmap_repeat = t->cmap.repeat;
    for (unsigned k = 0; k < t->cmap.n && k < NP_TEX_CMAP_MAX; k++)
        for (unsigned ch = 0; ch < 3; ch++) {
            double c = t->cmap.c[k][ch];
            if (!(c >= 0 && c <= 255 && c == floor(c))) {
                snprintf(err, errlen, "colour map entry %u: %g is not an integer 0..255", k, c);
                return -1;
            }
            r->cmap[k][ch] = (uint8_t)c;
        }
    const char *why = np_tex_regs_check(r);
    if (why) {
        snprintf(err, errlen, "%s", why);
        return -1;
    }
    return 0;
}

/* --- Register rounding over a scene (np_texreg.h) --- */

typedef struct bound_acc {
    np_texreg_scene_bound *b;
    double slope;
} bound_acc;

/* One field's contribution: its rounding residual times mult (index units per unit); keep the worst. */
static void bound_add(bound_acc *a, double resid, double mult, const char *field, double value, unsigned frac,
                      unsigned bits)
{
    double c = resid * mult;
    a->b->reg_index += c;
    a->b->reg_lsb_bound += a->slope * mult * ldexp(1.0, -(int)frac - 1);
    if (c * a->slope > a->b->worst_lsb) {
        a->b->worst_lsb = c * a->slope;
        a->b->worst_mult = mult * a->slope;
        snprintf(a->b->worst, sizeof a->b->worst, "%s", field);
        a->b->worst_value = value;
        a->b->worst_frac = frac;
        a->b->worst_bits = bits;
    }
}

void np_texreg_scene_bound_compute(const np_ref_texture *t, const np_tex_regs *r, const double lo[3],
                                   const double hi[3], unsigned max_span, np_texreg_scene_bound *b)
{
    static const char qn[] = "ABCDEFGHIJ";
    memset(b, 0, sizeof *b);
    bound_acc a = { b, (double)np_tex_colour_slope(r) };
    const int kf = (int)np_tex_k_frac(r), mf = (int)np_tex_m_frac(r);
    const unsigned kb = np_tex_k_bits(r), mb = np_tex_m_bits(r);
    const double S = np_texreg_index_scale(&t->cmap), nmax = 63.0 / 64.0;
    double m[3];
    for (int k = 0; k < 3; k++)
        m[k] = fmax(fabs(lo[k]), fabs(hi[k]));
    /* The quadric's monomials' largest magnitudes over the box (A s^2, 2B st, 2C sr, 2D s, E t^2, ...). */
    const double mono[10] = { m[0] * m[0], 2 * m[0] * m[1], 2 * m[0] * m[2], 2 * m[0], m[1] * m[1],
                              2 * m[1] * m[2], 2 * m[1], m[2] * m[2], 2 * m[2], 1 };
    char f[96];
    for (int j = 0; j < 10; j++) {
        double want = S * (j == 9 ? t->quad[9] - t->cmap.f0 : t->quad[j]);
        double got = ldexp((double)r->k[j], -kf);
        snprintf(f, sizeof f, "texture.quadric.%c", qn[j]);
        bound_add(&a, fabs(got - want), mono[j], f, want, (unsigned)kf, kb);
        b->index_max += fabs(got) * mono[j];
        if (fabs(got) * mono[j] > b->index_worst_value) {
            b->index_worst_value = fabs(got) * mono[j];
            snprintf(b->index_worst, sizeof b->index_worst, "texture.quadric.%c", qn[j]);
        }
    }
    for (unsigned i = 0; i < t->n_oct && i < r->n_oct; i++) {
        const np_ref_octave *o = &t->oct[i];
        const np_tex_octave *ro = &r->oct[i];
        const double amp = ldexp((double)ro->amp, -NP_TEX_AMP_FRAC), g = fabs(amp) * nmax;
        snprintf(f, sizeof f, "texture.octaves[%u].amplitude", i);
        bound_add(&a, fabs(amp - S * o->amp), nmax, f, S * o->amp, NP_TEX_AMP_FRAC, NP_TEX_AMP_BITS);
        b->index_max += g;
        if (g > b->index_worst_value) {
            b->index_worst_value = g;
            snprintf(b->index_worst, sizeof b->index_worst, "texture.octaves[%u].amplitude", i);
        }
        for (int ax = 0; ax < 3; ax++) {
            for (int bx = 0; bx < 3; bx++) {
                double got = ldexp((double)ro->m[ax][bx], -mf);
                snprintf(f, sizeof f, "texture.octaves[%u] transform entry [%d][%d]", i, ax, bx);
                bound_add(&a, fabs(got - o->m[ax][bx]), g * m[bx], f, o->m[ax][bx], (unsigned)mf, mb);
            }
            snprintf(f, sizeof f, "texture.octaves[%u].offset[%d]", i, ax);
            bound_add(&a, fabs(ldexp((double)ro->o[ax], -NP_TEX_FC) - o->o[ax]), g, f, o->o[ax], NP_TEX_FC,
                      NP_TEX_O_BITS);
            /* The front end: u0 and du each rounded to 2^-33; du's error times the pixel. */
            b->reg_index += g * ldexp(1.0 + (double)max_span, -(NP_TEX_FC + 1));
            /* The descriptor's s and ds, rounded to Q.32 by the host, through the transform. */
            for (int bx = 0; bx < 3; bx++)
                b->reg_index += g * fabs(ldexp((double)ro->m[ax][bx], -mf)) *
                                ldexp(1.0 + (double)max_span, -(NP_TEX_FC + 1));
        }
    }
    /* The descriptor's rounding through the quadric: |grad q'|_1 over the box times 2^-33 (1 + n_max). */
    double k[10];
    for (int j = 0; j < 10; j++)
        k[j] = fabs(ldexp((double)r->k[j], -kf));
    const double grad = 2 * k[0] * m[0] + 2 * k[1] * (m[0] + m[1]) + 2 * k[2] * (m[0] + m[2]) + 2 * k[3] +
                        2 * k[4] * m[1] + 2 * k[5] * (m[1] + m[2]) + 2 * k[6] + 2 * k[7] * m[2] + 2 * k[8];
    b->reg_index += grad * ldexp(1.0 + (double)max_span, -(NP_TEX_FC + 1));
    b->reg_lsb = a.slope * b->reg_index;
    b->idx_int_need = 1;
    if (!r->cmap_repeat)
        while (b->idx_int_need < 64 && ldexp(1.0, (int)b->idx_int_need) <= b->index_max)
            b->idx_int_need++;
}

int np_texreg_scene_check(const char *scene, const np_texreg_scene_bound *b, double unit_lsb, unsigned idx_int,
                          unsigned idx_int_max, char *err, size_t errlen)
{
    if (b->idx_int_need > idx_int) {
        if (b->idx_int_need > idx_int_max)
            snprintf(err, errlen,
                     "scene %s: field %s: the colour index reaches %.6g on a clamped colour map over the scene's "
                     "coordinates: it needs %u index integer bits, the unit has at most %u; it would wrap",
                     scene, b->index_worst, b->index_max, b->idx_int_need, idx_int_max);
        else
            snprintf(err, errlen,
                     "scene %s: field %s: the colour index reaches %.6g on a clamped colour map over the scene's "
                     "coordinates: it needs idx_int=%u index integer bits (the unit's configuration has %u); it would "
                     "wrap",
                     scene, b->index_worst, b->index_max, b->idx_int_need, idx_int);
        return -1;
    }
    if (unit_lsb + b->reg_lsb > 1.0) {
        /*
         * How many more fraction bits every register would need: at e more,
         * each residual is at most 2^-(frac+e+1), so the registers add at
         * most reg_lsb_bound 2^-e.
         */
        unsigned e = 0;
        while (e < 100 && unit_lsb + b->reg_lsb_bound * ldexp(1.0, -(int)e) > 1.0)
            e++;
        snprintf(err, errlen,
                 "scene %s: field %s = %.6g rounds in its register (%u bits, %u fraction) and adds %.3g LSB over the "
                 "scene's coordinates; with the other registers the predicted bound is %.3g LSB > 1: not rendered "
                 "(the registers would need %u more fraction bits: %s with %u)",
                 scene, b->worst, b->worst_value, b->worst_bits, b->worst_frac, b->worst_lsb, unit_lsb + b->reg_lsb, e,
                 b->worst, b->worst_frac + e);
        return -1;
    }
    return 0;
}

/* --- Registers sized by the scene (np_texreg.h) --- */

/* Fewest bits of a two's-complement word holding q. */
static unsigned sbits(int64_t q)
{
    unsigned b = 1;
    while (b < 64 && !(q >= -((int64_t)1 << (b - 1)) && q < ((int64_t)1 << (b - 1))))
        b++;
    return b;
}

/* The formats at fractions kf, mf with the fewest integer bits: 0, or -1 when a value fits no width. */
static int size_fmt(const np_ref_texture *t, unsigned kf, unsigned mf, np_texreg_fmt *f)
{
    const double S = np_texreg_index_scale(&t->cmap);
    unsigned kb = kf + 1u, mb = mf + 1u;
    int64_t q;
    for (unsigned j = 0; j < 10; j++) {
        if (np_texreg_quantize(S * (j == 9 ? t->quad[9] - t->cmap.f0 : t->quad[j]), (int)kf, 64, &q))
            return -1;
        unsigned b = sbits(q);
        kb = b > kb ? b : kb;
    }
    for (unsigned o = 0; o < t->n_oct && o < NP_TEX_MAX_OCTAVES; o++)
        for (unsigned a = 0; a < 3; a++)
            for (unsigned c = 0; c < 3; c++) {
                if (np_texreg_quantize(t->oct[o].m[a][c], (int)mf, 64, &q))
                    return -1;
                unsigned b = sbits(q);
                mb = b > mb ? b : mb;
            }
    if (kb > NP_TEX_K_BITS_MAX || mb > NP_TEX_M_BITS_MAX || mb > 1u + NP_TEX_M_INT_MAX + mf)
        return -1;
    *f = (np_texreg_fmt){ kf, kb, mf, mb };
    return 0;
}

/* The registers' bound (colour LSB) at fractions kf, mf; +inf when they do not fit. */
static double size_try(const np_ref_texture *t, const double lo[3], const double hi[3], unsigned max_span, unsigned kf,
                       unsigned mf, np_texreg_fmt *f, np_tex_regs *r, np_texreg_scene_bound *b)
{
    char err[200];
    if (size_fmt(t, kf, mf, f) != 0 || np_texreg_compile_fmt(t, f, r, err, sizeof err) != 0)
        return (double)INFINITY;
    np_texreg_scene_bound_compute(t, r, lo, hi, max_span, b);
    return b->reg_lsb;
}

int np_texreg_size(const np_ref_texture *t, const double lo[3], const double hi[3], unsigned max_span, double budget,
                   np_texreg_fmt *fmt, np_tex_regs *r, np_texreg_scene_bound *b, char *err, size_t errlen)
{
    /* The widest quadric fraction the coefficients leave within 64 bits. */
    unsigned ktop = NP_TEX_K_FRAC_MAX;
    np_texreg_fmt f;
    while (size_fmt(t, ktop, NP_TEX_M_FRAC_MAX, &f) != 0) {
        if (ktop == 0) {
            /* A value no format holds: compile at the defaults for the message. */
            if (np_texreg_compile(t, r, err, errlen) == 0)
                snprintf(err, errlen, "a quadric coefficient or transform entry does not fit the widest registers "
                                      "(s64 quadric, s48 Q7.40 transform)");
            return -1;
        }
        ktop--;
    }
    unsigned mf = 0, kf = 0;
    while (mf < NP_TEX_M_FRAC_MAX && !(size_try(t, lo, hi, max_span, ktop, mf, &f, r, b) <= budget))
        mf++;
    while (kf < ktop && !(size_try(t, lo, hi, max_span, kf, mf, &f, r, b) <= budget))
        kf++;
    /* (ktop, mf) fits by the searches above, and k's format does not depend on mf: this fits. */
    if (!(size_try(t, lo, hi, max_span, kf, mf, fmt, r, b) < (double)INFINITY)) {
        snprintf(err, errlen, "no register format holds the texture (quadric Q.%u, transform Q.%u)", kf, mf);
        return -1;
    }
    return 0;
}

/* --- Built-in textures (keep wood and marble equal to vectors/scenes; render.builtin_textures checks) --- */

#define DIAG(a, b, c) { { (a), 0, 0 }, { 0, (b), 0 }, { 0, 0, (c) } }

static const np_ref_texture tex_wood = {
    .quad = { 10, 0, 0, 0, 0, 0, 0, 10, 0, 0 },
    .n_oct = 1,
    .oct = { { DIAG(5, 5, 1), { 0, 0, 0 }, 1 } },
    .cmap = { 0, 1, 4, 1, { { 226, 176, 116 }, { 204, 146, 86 }, { 150, 96, 50 }, { 204, 146, 86 } } },
};

static const np_ref_texture tex_marble = {
    .quad = { 0, 0, 0, 0, 0, 0, 0, 0, 0.5, 0 },
    .n_oct = 4,
    .oct = { { DIAG(1, 1, 1), { 0, 0, 0 }, 1 },
             { DIAG(2, 2, 2), { 0, 0, 0 }, 1 },
             { DIAG(4, 4, 4), { 0, 0, 0 }, 1 },
             { DIAG(8, 8, 8), { 0, 0, 0 }, 1 } },
    .cmap = { 0, 2, 8, 1,
              { { 236, 236, 230 }, { 226, 226, 222 }, { 210, 212, 210 }, { 172, 176, 182 },
                { 96, 100, 116 }, { 172, 176, 182 }, { 210, 212, 210 }, { 226, 226, 222 } } },
};

static const np_ref_texture tex_ramp = {
    .n_oct = 1,
    .oct = { { DIAG(1, 1, 1), { 0, 0, 0 }, 1 } },
    .cmap = { 0, 1, 2, 0, { { 0, 0, 0 }, { 255, 255, 255 } } },
};

static const struct {
    const char *name;
    const np_ref_texture *t;
} builtins[] = { { "wood", &tex_wood }, { "marble", &tex_marble }, { "ramp", &tex_ramp } };

const np_ref_texture *np_texreg_builtin(const char *name)
{
    for (unsigned i = 0; i < sizeof builtins / sizeof builtins[0]; i++)
        if (strcmp(builtins[i].name, name) == 0)
            return builtins[i].t;
    return NULL;
}

const char *np_texreg_builtin_name(unsigned i)
{
    return i < sizeof builtins / sizeof builtins[0] ? builtins[i].name : NULL;
}
