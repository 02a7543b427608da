/* SPDX-License-Identifier: MIT */
/* The classic noise unit (rtl_model/np_classic.h) in the unit registry. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "np_classic.h"
#include "np_ref.h"
#include "np_unit.h"

/* The registry's configuration block: the model's, plus which widths were set by hand. */
typedef struct classic_cfg {
    np_classic_cfg c;
    unsigned char s_set, l_set;
} classic_cfg;
_Static_assert(sizeof(classic_cfg) <= NP_UNIT_CFG_MAX, "configuration block too large");

static void cfg_default(void *cfg)
{
    classic_cfg *k = cfg;
    memset(k, 0, sizeof *k);
    k->c = np_classic_cfg_default(8);
}

static int parse_uint(const char *v, unsigned lo, unsigned hi, unsigned *out)
{
    char *end;
    unsigned long n = strtoul(v, &end, 10);
    if (*v == '\0' || *end != '\0' || *v == '-' || n < lo || n > hi)
        return -1;
    *out = (unsigned)n;
    return 0;
}

static int cfg_set(void *cfg, const char *key, const char *value, char *err, size_t errlen)
{
    classic_cfg *k = cfg;
    unsigned n;
    if (strcmp(key, "out_bits") == 0) {
        if (parse_uint(value, NP_CLASSIC_OUT_MIN, NP_CLASSIC_OUT_MAX, &n) != 0)
            goto range;
        np_classic_cfg d = np_classic_cfg_default(n);
        k->c.out_bits = n;
        if (!k->s_set)
            k->c.s_frac = d.s_frac;
        if (!k->l_set)
            k->c.lerp_frac = d.lerp_frac;
        return 0;
    }
    if (strcmp(key, "s_frac") == 0) {
        if (parse_uint(value, NP_CLASSIC_WS_MIN, NP_CLASSIC_WS_MAX, &n) != 0)
            goto range;
        k->c.s_frac = n;
        k->s_set = 1;
        return 0;
    }
    if (strcmp(key, "lerp_frac") == 0) {
        if (parse_uint(value, 0, NP_CLASSIC_WL_MAX, &n) != 0)
            goto range;
        k->c.lerp_frac = n;
        k->l_set = 1;
        return 0;
    }
    snprintf(err, errlen, "unknown configuration key '%s' for unit classic3 (keys: out_bits, s_frac, lerp_frac)", key);
    return -1;
range:
    snprintf(err, errlen, "%s=%s: out of range (out_bits 2..16, s_frac 1..24, lerp_frac out_bits-2..30)",
             key, value);
    return -1;
}

static void cfg_format(const void *cfg, char *buf, size_t len)
{
    const classic_cfg *k = cfg;
    snprintf(buf, len, "out_bits=%u s_frac=%u lerp_frac=%u", k->c.out_bits, k->c.s_frac,
             k->c.lerp_frac);
}

static const char *cfg_check(const void *cfg) { return np_classic_cfg_check(&((const classic_cfg *)cfg)->c); }

static void set_field(np_field *f, const char *name, unsigned bits, int sgn, unsigned frac,
                      const char *fmt)
{
    snprintf(f->name, sizeof f->name, "%s", name);
    f->bits = bits;
    f->is_signed = sgn;
    f->frac = frac;
    snprintf(f->format, sizeof f->format, "%s", fmt);
}

static void fields(const void *cfg, np_unit_fields *f)
{
    const classic_cfg *k = cfg;
    char fmt[32];
    memset(f, 0, sizeof *f);
    f->n_in = 3;
    f->n_out = 1;
    set_field(&f->in[0], "x", 16, 0, 8, "u16 Q8.8");
    set_field(&f->in[1], "y", 16, 0, 8, "u16 Q8.8");
    set_field(&f->in[2], "z", 16, 0, 8, "u16 Q8.8");
    snprintf(fmt, sizeof fmt, "s%u Q2.%u", k->c.out_bits, k->c.out_bits - 2u);
    set_field(&f->out[0], "f", k->c.out_bits, 1, k->c.out_bits - 2u, fmt);
}

static void eval(const void *cfg, const uint64_t *in, uint64_t *out)
{
    const classic_cfg *k = cfg;
    int32_t v = np_classic_eval(&k->c, (uint16_t)in[0], (uint16_t)in[1], (uint16_t)in[2]);
    out[0] = np_trunc_u((uint64_t)(int64_t)v, k->c.out_bits);
}

static void ref(const void *cfg, const uint64_t *in, double *out)
{
    (void)cfg;
    out[0] = np_ref_classic3_q88((uint16_t)in[0], (uint16_t)in[1], (uint16_t)in[2]);
}

static double error_bound(const void *cfg) { return np_classic_error_bound_lsb(&((const classic_cfg *)cfg)->c); }

static int pipe_init(np_pipe *p, const void *cfg) { return np_classic_pipe_init(p, &((const classic_cfg *)cfg)->c); }

static void sig_set_in(void *sig, const uint64_t *in)
{
    np_classic_sig *s = sig;
    memset(s, 0, sizeof *s);
    s->x = (uint16_t)in[0];
    s->y = (uint16_t)in[1];
    s->z = (uint16_t)in[2];
}

static void sig_get_out(const void *cfg, const void *sig, uint64_t *out)
{
    const classic_cfg *k = cfg;
    const np_classic_sig *s = sig;
    out[0] = np_trunc_u((uint64_t)(int64_t)s->out, k->c.out_bits);
}

/*
 * Boundary values of one 8.8 coordinate, each with the reason it is there.
 * The generator takes every combination over x, y and z.
 */
static const uint16_t boundary_axis[] = {
    0x0000, /* origin: every corner-relative offset is 0 or -1 */
    0x0001, /* smallest non-zero fraction: s(1/256) rounds to almost 0 */
    0x0080, /* fraction 1/2: s = 1/2 exactly, largest |noise| bound */
    0x00ff, /* fraction 255/256: s rounds near 1 (can reach 1.0 when WS <= 13) */
    0x0100, /* next cell, fraction 0: continuity across the face */
    0x7f80, /* mid-tile, fraction 1/2 */
    0x8000, /* cell 128: top bit of the cell index set, all others clear */
    0x5555, /* alternating bits in cell and fraction */
    0xaaaa, /* the other alternating pattern */
    0xfeff, /* last fraction before cell 255 */
    0xff00, /* cell 255, fraction 0: the far corners wrap to cell 0 */
    0xff01, /* cell 255, smallest fraction: wrap with s near 0 */
    0xff80, /* cell 255, fraction 1/2: wrap, equal weights */
    0xffff, /* 255 + 255/256, the largest input: wrap, s near 1 */
};
enum { N_AXIS = sizeof boundary_axis / sizeof boundary_axis[0] };

static size_t boundary(const void *cfg, uint64_t (*in)[NP_UNIT_MAX_FIELDS], size_t max)
{
    (void)cfg;
    size_t n = 0;
    for (unsigned a = 0; a < N_AXIS; a++)
        for (unsigned b = 0; b < N_AXIS; b++)
            for (unsigned c = 0; c < N_AXIS; c++, n++)
                if (n < max) {
                    in[n][0] = boundary_axis[a];
                    in[n][1] = boundary_axis[b];
                    in[n][2] = boundary_axis[c];
                }
    return n;
}

const np_unit np_unit_classic3 = {
    .name = "classic3",
    .summary = "classic 3-D gradient noise, 8.8 inputs, L/H/S/I pipeline (Perlin, Noise Hardware)",
    .cfg_default = cfg_default,
    .cfg_set = cfg_set,
    .cfg_format = cfg_format,
    .cfg_check = cfg_check,
    .fields = fields,
    .eval = eval,
    .ref = ref,
    .tolerance_lsb = 1.0,
    .error_bound_lsb = error_bound,
    .pipe_init = pipe_init,
    .sig_set_in = sig_set_in,
    .sig_get_out = sig_get_out,
    .boundary = boundary,
};
