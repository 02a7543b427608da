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
    static const char qn[] = "ABCDEFGHIJ";
    memset(r, 0, sizeof *r);
    double S = np_texreg_index_scale(&t->cmap);
    for (unsigned i = 0; i < 10; i++) {
        double v = S * (i == 9 ? t->quad[9] - t->cmap.f0 : t->quad[i]);
        if (np_texreg_quantize(v, NP_TEX_K_FRAC, NP_TEX_K_BITS, &r->k[i])) {
            snprintf(err, errlen, "quadric coefficient %c scaled by the colour map (%g) does not fit s48 Q23.24", qn[i], v);
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
                if (np_texreg_quantize(src->m[a][b], NP_TEX_M_FRAC, NP_TEX_M_BITS, &q)) {
                    snprintf(err, errlen, "octave %u: transform entry %g does not fit s24 Q7.16", o, src->m[a][b]);
                    return -1;
                }
                d->m[a][b] = (int32_t)q;
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
