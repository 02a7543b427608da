/* SPDX-License-Identifier: MIT */
/* The simplex unit's bit-exact model: pinned outputs, accuracy over random inputs, the
 * division by 3, f without the derivative, error bounds by configuration, the registry entry. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "simplex_test.h"

/* ------------------------------------------------------------------------ */

typedef struct kat_row {
    uint16_t x, y, z;
    int32_t f, dfdx, dfdy, dfdz; /* default unit: f s16, df s16 Q1.14 */
    int32_t f8;                  /* out_bits=8 deriv=0: f s8 */
} kat_row;

static const kat_row KAT[] = {
#include "simplex3_kat.inc"
};

/* The KAT inputs: the unit's boundary table, then seeded random ones. */
static unsigned kat_inputs(uint16_t (*in)[3], unsigned max)
{
    uint64_t b[64][NP_UNIT_MAX_FIELDS];
    np_unit_cfg ucfg;
    np_unit_cfg_default(&np_unit_simplex3, &ucfg);
    size_t nb = np_unit_simplex3.boundary(&ucfg, b, 64);
    unsigned n = 0;
    for (size_t i = 0; i < nb && i < 64 && n < max; i++, n++)
        for (unsigned a = 0; a < 3; a++)
            in[n][a] = (uint16_t)b[i][a];
    np_rng r;
    np_rng_seed(&r, 2024);
    while (n < max) {
        for (unsigned a = 0; a < 3; a++)
            in[n][a] = rnd16(&r);
        n++;
    }
    return n;
}

int simplex_kat(void)
{
    uint16_t in[96][3];
    unsigned n = kat_inputs(in, 96);
    unsigned nk = sizeof KAT / sizeof KAT[0];
    NP_CHECK(nk == n, "KAT has %u rows, expected %u (regenerate: gen_kat, see simplex3_kat.inc line 1)", nk, n);
    np_simplex_cfg c = default_cfg(), c8 = np_simplex_cfg_default(8, 8, 0);
    for (unsigned i = 0; i < nk && i < n; i++) {
        const kat_row *k = &KAT[i];
        NP_CHECK(k->x == in[i][0] && k->y == in[i][1] && k->z == in[i][2], "row %u inputs", i);
        np_simplex_out o, o8;
        np_simplex_eval(&c, k->x, k->y, k->z, &o);
        np_simplex_eval(&c8, k->x, k->y, k->z, &o8);
        NP_CHECK(o.f == k->f && o.df[0] == k->dfdx && o.df[1] == k->dfdy && o.df[2] == k->dfdz,
                 "(%04x,%04x,%04x) = %d %d %d %d, pinned %d %d %d %d", k->x, k->y, k->z, o.f, o.df[0], o.df[1],
                 o.df[2], k->f, k->dfdx, k->dfdy, k->dfdz);
        NP_CHECK(o8.f == k->f8, "(%04x,%04x,%04x) 8-bit f = %d, pinned %d", k->x, k->y, k->z, o8.f, k->f8);
        errs e;
        measure(&c, k->x, k->y, k->z, &e);
        for (unsigned f = 0; f < 4; f++)
            NP_CHECK(e.e[f] <= 1.0, "(%04x,%04x,%04x) %s %.3f LSB from the reference", k->x, k->y, k->z, FIELD[f], e.e[f]);
    }
    printf("%u pinned outputs (4 fields of the default unit + 8-bit f) match\n", nk);
    return 0;
}

int simplex_random_1e7(void)
{
    np_simplex_cfg cfg = default_cfg();
    np_rng r;
    np_rng_seed(&r, 10000000);
    emax m;
    memset(&m, 0, sizeof m);
    const uint64_t n = 10000000;
    for (uint64_t i = 0; i < n; i++) {
        uint64_t v = np_rng_next(&r);
        uint16_t x = (uint16_t)v, y = (uint16_t)(v >> 16), z = (uint16_t)(v >> 32);
        errs e;
        measure(&cfg, x, y, z, &e);
        emax_add(&m, &e, x, y, z);
    }
    printf("default unit (out_bits=16 dout_bits=16 t_frac=%u p_frac=%u k_frac=%u), %llu random inputs:\n",
           cfg.t_frac, cfg.p_frac, cfg.k_frac, (unsigned long long)n);
    for (unsigned k = 0; k < 4; k++)
        printf("  %-4s max error %.4f LSB (bound %.4f) at (%04x,%04x,%04x), correctly rounded %.4f%%\n", FIELD[k],
               m.e[k], np_simplex_error_bound_lsb(&cfg, k > 0), m.at[k][0], m.at[k][1], m.at[k][2],
               100.0 * (double)m.cr[k] / (double)n);
    emax_check("random", &m, &cfg);
    return 0;
}


/* ------------------------------------------------------------------------ */

int simplex_div3_exhaustive(void)
{
    for (uint32_t n = 0; n < 2048; n++)
        NP_CHECK(np_simplex_div3(n) == n / 3u, "div3(%u) = %u", n, np_simplex_div3(n));
    /* and the skewed cell over every value of 4x + y + z */
    for (uint32_t sx = 0; sx <= 6u * 65535u; sx++)
        NP_CHECK(np_simplex_cell(sx) == sx / NP_SIMPLEX_SKEW_CELL, "cell(%u)", sx);
    puts("floor(n/3) = (683 n) >> 11 for n < 2048; cell = floor(SX/768) for every SX 0..393210");
    return 0;
}

int simplex_deriv_off_same_f(void)
{
    /* With the same widths, omitting the derivative datapath changes no bit of f. */
    np_simplex_cfg d = default_cfg(), f = d;
    f.deriv = 0;
    np_rng r;
    np_rng_seed(&r, 8);
    for (unsigned it = 0; it < 300000; it++) {
        uint16_t x = rnd16(&r), y = rnd16(&r), z = rnd16(&r);
        np_simplex_out a, b;
        np_simplex_eval(&d, x, y, z, &a);
        np_simplex_eval(&f, x, y, z, &b);
        NP_CHECK(a.f == b.f && b.df[0] == 0 && b.df[1] == 0 && b.df[2] == 0, "(%04x,%04x,%04x)", x, y, z);
    }
    /* and the f-only default is faithful on its own */
    np_simplex_cfg f16 = np_simplex_cfg_default(16, 16, 0);
    emax m;
    memset(&m, 0, sizeof m);
    for (unsigned it = 0; it < 1000000; it++) {
        uint16_t x = rnd16(&r), y = rnd16(&r), z = rnd16(&r);
        errs e;
        measure(&f16, x, y, z, &e);
        emax_add(&m, &e, x, y, z);
    }
    printf("deriv=0 with the deriv=1 widths: f bit-identical on 3e5 inputs; f-only default (t_frac=%u p_frac=%u "
           "k_frac=%u, bound %.4f LSB): ",
           f16.t_frac, f16.p_frac, f16.k_frac, np_simplex_error_bound_lsb(&f16, 0));
    emax_print("f", &m, 0);
    emax_check("f only", &m, &f16);
    return 0;
}

int simplex_error_bound_configs(void)
{
    /*
     * The error argument of np_simplex.h, measured: the max error over random
     * inputs stays within the bound for each configuration; cheap ones exceed
     * 1 LSB (so the check can fail).
     */
    static const np_simplex_cfg cfgs[] = {
        { 16, 16, 1, 24, 22, 22 }, { 8, 8, 1, 16, 14, 13 }, { 12, 12, 1, 20, 18, 17 }, { 20, 20, 1, 27, 26, 26 },
        { 16, 16, 1, 18, 22, 22 }, { 16, 16, 1, 24, 15, 22 }, { 16, 16, 1, 24, 22, 12 }, { 8, 8, 1, 8, 8, 8 },
    };
    np_rng r;
    np_rng_seed(&r, 3);
    double worst_cheap = 0.0;
    for (unsigned c = 0; c < sizeof cfgs / sizeof cfgs[0]; c++) {
        const np_simplex_cfg *cfg = &cfgs[c];
        NP_CHECK(np_simplex_cfg_check(cfg) == NULL, "cfg %u invalid", c);
        emax m;
        memset(&m, 0, sizeof m);
        for (unsigned i = 0; i < 200000; i++) {
            uint16_t x = rnd16(&r), y = rnd16(&r), z = rnd16(&r);
            errs e;
            measure(cfg, x, y, z, &e);
            emax_add(&m, &e, x, y, z);
        }
        double bf = np_simplex_error_bound_lsb(cfg, 0), bd = np_simplex_error_bound_lsb(cfg, 1);
        double ed = fmax(m.e[1], fmax(m.e[2], m.e[3]));
        printf("out=%2u dout=%2u t_frac=%2u p_frac=%2u k_frac=%2u: f %.4f LSB (bound %.4f, CR %.2f%%), "
               "df %.4f LSB (bound %.4f, CR %.2f%%)\n",
               cfg->out_bits, cfg->dout_bits, cfg->t_frac, cfg->p_frac, cfg->k_frac, m.e[0], bf,
               100.0 * (double)m.cr[0] / (double)m.n, ed, bd, 100.0 * (double)m.cr[1] / (double)m.n);
        NP_CHECK(m.e[0] <= bf && ed <= bd, "measured error above the argument's bound");
        if (bf > 1.0 || bd > 1.0)
            worst_cheap = fmax(worst_cheap, fmax(m.e[0], ed));
        else
            NP_CHECK(m.e[0] <= 1.0 && ed <= 1.0, "faithful config not faithful");
    }
    NP_CHECK(worst_cheap > 1.0, "cheap configurations should show errors above 1 LSB (got %.3f)", worst_cheap);
    for (unsigned o = NP_SIMPLEX_OUT_MIN; o <= NP_SIMPLEX_OUT_MAX; o++)
        for (unsigned d = NP_SIMPLEX_DOUT_MIN; d <= NP_SIMPLEX_OUT_MAX; d++)
            for (unsigned dv = 0; dv < 2; dv++) {
                np_simplex_cfg k = np_simplex_cfg_default(o, d, dv);
                NP_CHECK(np_simplex_cfg_check(&k) == NULL, "default %u %u %u invalid", o, d, dv);
                NP_CHECK(np_simplex_error_bound_lsb(&k, 0) < 1.0, "default %u %u %u: f not faithful by argument", o, d, dv);
                if (dv)
                    NP_CHECK(np_simplex_error_bound_lsb(&k, 1) < 1.0, "default %u %u: df not faithful by argument", o, d);
            }
    puts("every default configuration (out_bits 4..20, dout_bits 5..20, deriv 0/1) is faithful by the argument");
    return 0;
}

int simplex_registry(void)
{
    /* The unit through the registry: configuration keys, fields, words, pipe. */
    const np_unit *u = np_unit_find("simplex3");
    NP_CHECK(u == &np_unit_simplex3, "simplex3 registered");
    np_unit_cfg cfg;
    char err[256];
    NP_CHECK(np_unit_configure(u, &cfg, "", err, sizeof err) == 0, "defaults: %s", err);
    char buf[256];
    np_unit_cfg_format(u, &cfg, buf, sizeof buf);
    puts(buf);
    NP_CHECK(strcmp(buf, "out_bits=16 dout_bits=16 deriv=1 t_frac=24 p_frac=22 k_frac=22") == 0, "default format");
    np_unit_fields f;
    u->fields(&cfg, &f);
    NP_CHECK(f.n_in == 3 && f.n_out == 4, "fields");
    NP_CHECK(strcmp(f.out[0].format, "s16 Q-1.16") == 0 && strcmp(f.out[3].format, "s16 Q1.14") == 0 &&
                 strcmp(f.out[2].name, "dfdy") == 0, "formats %s %s", f.out[0].format, f.out[3].format);
    uint64_t in[3] = { 0x1234, 0x5678, 0x9abc }, out[4];
    double rv[4];
    u->eval(&cfg, in, out);
    u->ref(&cfg, in, rv);
    for (unsigned k = 0; k < 4; k++)
        NP_CHECK(fabs(np_unit_field_value(&f.out[k], out[k]) - rv[k]) <= ldexp(1.0, -(int)f.out[k].frac),
                 "field %u", k);
    NP_CHECK(np_unit_configure(u, &cfg, "deriv=0,out_bits=8", err, sizeof err) == 0, "%s", err);
    np_unit_cfg_format(u, &cfg, buf, sizeof buf);
    puts(buf);
    u->fields(&cfg, &f);
    NP_CHECK(f.n_out == 1 && f.out[0].bits == 8, "deriv=0 fields");
    NP_CHECK(np_unit_configure(u, &cfg, "t_frac=20,out_bits=12", err, sizeof err) == 0, "%s", err);
    np_unit_cfg_format(u, &cfg, buf, sizeof buf);
    NP_CHECK(strstr(buf, "t_frac=20") != NULL, "hand-set width kept: %s", buf);
    NP_CHECK(np_unit_configure(u, &cfg, "out_bits=21", err, sizeof err) != 0, "out_bits 21 accepted");
    NP_CHECK(np_unit_configure(u, &cfg, "deriv=2", err, sizeof err) != 0, "deriv 2 accepted");
    NP_CHECK(np_unit_configure(u, &cfg, "bogus=1", err, sizeof err) != 0, "unknown key accepted");
    size_t nb = u->boundary(&cfg, NULL, 0);
    NP_CHECK(nb > 20, "boundary table");
    printf("registry: simplex3 configures, formats, evaluates; %zu boundary inputs\n", nb);
    return 0;
}

