/* SPDX-License-Identifier: MIT */
/* Float reference of the scanline texture model (np_ref.h). */
#include <math.h>

#include "np_hash.h"
#include "np_ref.h"

/* (i mod 256) for any integral double, exact (fmod of an integer is exact). */
static uint8_t wrap256(double i)
{
    double m = fmod(i, 256.0);
    return (uint8_t)(m < 0 ? m + 256.0 : m);
}

double np_ref_lattice_value(int64_t i, int64_t j, int64_t k)
{
    return np_hash6((uint8_t)((uint64_t)i & 255u), (uint8_t)((uint64_t)j & 255u),
                    (uint8_t)((uint64_t)k & 255u)) / 64.0;
}

static double lerp(double t, double a, double b) { return a + (b - a) * t; }

double np_ref_value_noise(double x, double y, double z)
{
    double fx = floor(x), fy = floor(y), fz = floor(z);
    uint8_t i = wrap256(fx), j = wrap256(fy), k = wrap256(fz);
    uint8_t i1 = (uint8_t)(i + 1u), j1 = (uint8_t)(j + 1u), k1 = (uint8_t)(k + 1u);
    double u = x - fx, v = y - fy, w = z - fz;
    /* Seed, equations 9-11: along s, then t, then r. */
    double na = lerp(u, np_hash6(i, j, k) / 64.0, np_hash6(i1, j, k) / 64.0);
    double nb = lerp(u, np_hash6(i, j1, k) / 64.0, np_hash6(i1, j1, k) / 64.0);
    double nc = lerp(u, np_hash6(i, j, k1) / 64.0, np_hash6(i1, j, k1) / 64.0);
    double nd = lerp(u, np_hash6(i, j1, k1) / 64.0, np_hash6(i1, j1, k1) / 64.0);
    double ne = lerp(v, na, nb), nf = lerp(v, nc, nd);
    return lerp(w, ne, nf);
}

double np_ref_quadric(const double k[10], const double s[3])
{
    double S = s[0], T = s[1], R = s[2];
    /* Equation 2, term by term, left to right. */
    return k[0] * S * S + 2.0 * k[1] * S * T + 2.0 * k[2] * S * R + 2.0 * k[3] * S + k[4] * T * T +
           2.0 * k[5] * T * R + 2.0 * k[6] * T + k[7] * R * R + 2.0 * k[8] * R + k[9];
}

double np_ref_texture_f(const np_ref_texture *t, const double s[3], double *noise)
{
    double f = np_ref_quadric(t->quad, s);
    for (unsigned i = 0; i < t->n_oct; i++) {
        const np_ref_octave *o = &t->oct[i];
        double p[3];
        for (unsigned a = 0; a < 3; a++)
            p[a] = o->m[a][0] * s[0] + o->m[a][1] * s[1] + o->m[a][2] * s[2] + o->o[a];
        double n = np_ref_value_noise(p[0], p[1], p[2]);
        if (noise)
            noise[i] = n;
        f += o->amp * n;
    }
    return f;
}

double np_ref_colour_index(const np_ref_colormap *c, double f)
{
    double segs = c->repeat ? (double)c->n : (double)(c->n - 1u);
    return (f - c->f0) * (segs / (c->f1 - c->f0));
}

void np_ref_colour(const np_ref_colormap *c, double f, double rgb[3])
{
    double x = np_ref_colour_index(c, f);
    unsigned n = c->n, seg, next;
    double w;
    if (c->repeat) {
        x -= (double)n * floor(x / (double)n);
        seg = x >= (double)n ? n - 1u : (unsigned)floor(x);
        w = x - (double)seg;
        next = (seg + 1u) % n;
    } else if (x <= 0.0) {
        seg = 0, next = 1, w = 0.0;
    } else if (x >= (double)(n - 1u)) {
        seg = n - 2u, next = n - 1u, w = 1.0;
    } else {
        seg = (unsigned)floor(x);
        next = seg + 1u;
        w = x - (double)seg;
    }
    for (unsigned ch = 0; ch < 3; ch++)
        rgb[ch] = lerp(w, c->c[seg][ch], c->c[next][ch]);
}
