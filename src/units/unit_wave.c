/* SPDX-License-Identifier: MIT */
/*
 * The Gerstner wave unit (rtl_model/np_wave.h) in the unit registry.
 *
 * The keys are the datapath's (lanes, effects present, ROM size) and `regs`,
 * the seed of the test register set (np_wave_regs_test) the registry's tools
 * run the unit on: vectors, verify, conformance, the gate report. A scene
 * loads its own registers through the model's API (src/wave/). The register
 * set is a function of the keys; the block holds it, completed whenever the
 * keys are set (cfg_check, and the derived default of `regs` for
 * np_unit_cfg_default), so every tool sees the same registers.
 */
#include <stdio.h>
#include <string.h>

#include "np_unit.h"
#include "np_wave.h"
#include "np_wave_ref.h"

typedef struct wave_block {
    np_wave_unit u; /* first: the pipe's cfg is the block */
    unsigned regs;
} wave_block;
_Static_assert(sizeof(wave_block) <= NP_UNIT_CFG_MAX, "configuration block too large");

enum { REGS_DEFAULT = 1 };

/* The block's registers from its keys. The block is the caller's (np_unit_cfg storage), never a const object. */
static void complete(const void *cfg, unsigned seed)
{
    wave_block *b = (wave_block *)(void *)(uintptr_t)cfg;
    unsigned n = b->u.c.trains >= 1 && b->u.c.trains <= NP_WAVE_MAX_TRAINS ? b->u.c.trains : 1u;
    np_wave_regs_test(seed, n, &b->u.r);
}

static unsigned regs_default(const void *cfg)
{
    complete(cfg, REGS_DEFAULT);
    return REGS_DEFAULT;
}

static const np_unit_key keys[] = {
    NP_UNIT_KEY("trains", wave_block, u.c.trains, 1, NP_WAVE_MAX_TRAINS, 2, "train lanes (Gerstner trains summed per point)"),
    NP_UNIT_KEY("irr", wave_block, u.c.irr, 0, 1, 1, "1: eq. (8) irregular height present"),
    NP_UNIT_KEY("cap", wave_block, u.c.cap, 0, 1, 1, "1: eq. (9) capillary noise present"),
    NP_UNIT_KEY("rom_log2", wave_block, u.c.rom_log2, NP_WAVE_ROM_MIN, NP_WAVE_ROM_MAX, NP_WAVE_ROM_DEF,
                "L: quarter-wave ROM of 2^L x 18 bits, linear interpolation"),
    NP_UNIT_KEY_DERIVED("regs", wave_block, regs, 0, 65535, regs_default,
                        "seed of the test register set the tools run (scenes load their own)"),
    NP_UNIT_KEY_END,
};

static const char *cfg_check(const void *cfg)
{
    const wave_block *b = cfg;
    const char *why = np_wave_cfg_check(&b->u.c);
    if (why)
        return why;
    complete(cfg, b->regs);
    return np_wave_regs_check(&b->u.c, &b->u.r);
}

static void fields(const void *cfg, np_unit_fields *f)
{
    (void)cfg;
    memset(f, 0, sizeof *f);
    f->n_in = 8;
    f->n_out = 3;
    np_unit_set_field(&f->in[0], "i", 16, 0, 0, "u16");
    np_unit_set_field(&f->in[1], "j", 16, 0, 0, "u16");
    np_unit_set_field(&f->in[2], "t", 32, 0, 0, "u32");
    np_unit_set_field(&f->in[3], "ph", 32, 0, 32, "u32 Q0.32");
    np_unit_set_field(&f->in[4], "u", 16, 0, 0, "u16");
    np_unit_set_field(&f->in[5], "v", 16, 0, 0, "u16");
    np_unit_set_field(&f->in[6], "r", 8, 0, 0, "u8");
    np_unit_set_field(&f->in[7], "g", 15, 0, 14, "u15 Q1.14");
    np_unit_set_field(&f->out[0], "y", 16, 1, 10, "s16 Q5.10");
    np_unit_set_field(&f->out[1], "dx", 16, 1, 10, "s16 Q5.10");
    np_unit_set_field(&f->out[2], "dz", 16, 1, 10, "s16 Q5.10");
}

static void in_of(const uint64_t *w, np_wave_in *in)
{
    in->i = (uint16_t)w[0];
    in->j = (uint16_t)w[1];
    in->t = (uint32_t)w[2];
    in->ph = (uint32_t)w[3];
    in->u = (uint16_t)w[4];
    in->v = (uint16_t)w[5];
    in->r = (uint8_t)w[6];
    in->g = (uint16_t)(w[7] & 0x7fffu);
}

static void put_out(const np_wave_out *o, uint64_t *out)
{
    out[0] = np_trunc_u((uint64_t)(int64_t)o->y, 16);
    out[1] = np_trunc_u((uint64_t)(int64_t)o->dx, 16);
    out[2] = np_trunc_u((uint64_t)(int64_t)o->dz, 16);
}

static void eval(const void *cfg, const uint64_t *in, uint64_t *out)
{
    np_wave_in x;
    np_wave_out o;
    in_of(in, &x);
    np_wave_eval(&((const wave_block *)cfg)->u, &x, &o);
    put_out(&o, out);
}

static void ref(const void *cfg, const uint64_t *in, double *out)
{
    np_wave_in x;
    in_of(in, &x);
    np_ref_wave(&((const wave_block *)cfg)->u, &x, out);
}

static double error_bound(const void *cfg) { return np_wave_error_bound_lsb(&((const wave_block *)cfg)->u); }

static int pipe_init(np_pipe *p, const void *cfg) { return np_wave_pipe_init(p, &((const wave_block *)cfg)->u); }

static void sig_set_in(void *sig, const uint64_t *in)
{
    np_wave_sig *s = sig;
    memset(s, 0, sizeof *s);
    in_of(in, &s->in);
}

static void sig_get_out(const void *cfg, const void *sig, uint64_t *out)
{
    (void)cfg;
    put_out(&((const np_wave_sig *)sig)->out, out);
}

static size_t datapath(const void *cfg, np_op *ops, size_t max)
{
    return np_wave_datapath(&((const wave_block *)cfg)->u, ops, max);
}

static void trace(const void *cfg, unsigned k, const void *sig, np_trace *t, size_t n)
{
    np_wave_trace(&((const wave_block *)cfg)->u, k, sig, t, n);
}

/*
 * Hand-annotated boundary inputs, from the register set: train 0's phase
 * put at 0, 1/4, 1/2 and 3/4 turn and one phase LSB (2^-32 turn) either side
 * through ph, at the point (0, 0) in the middle of the box (full smoothing,
 * gain 1); the frame counter's wrap; the gain's and the smoothing's ends.
 */
static size_t boundary(const void *cfg, uint64_t (*in)[NP_UNIT_MAX_FIELDS], size_t max)
{
    const np_wave_regs *r = &((const wave_block *)cfg)->u.r;
    const np_wave_train *t0 = &r->tr[0];
    const uint16_t mid = (uint16_t)(r->width / 2u);
    size_t n = 0;
#define PUT(I, J, T, PH, U, V, R, G)                                                                      \
    do {                                                                                                  \
        if (n < max) {                                                                                    \
            const uint64_t w_[8] = { (I), (J), (T), (uint32_t)(PH), (U), (V), (R), (G) };                \
            memcpy(in[n], w_, sizeof w_);                                                                 \
        }                                                                                                 \
        n++;                                                                                              \
    } while (0)
    static const uint32_t frames[] = { 0u, 1u, 216000u, 0xfffffffeu, 0xffffffffu };
    for (unsigned f = 0; f < sizeof frames / sizeof frames[0]; f++) {
        uint32_t t = frames[f];
        for (uint32_t q = 0; q < 4; q++) {
            /* ph such that th0 = q/4 turn + e, e = -1, 0, +1 LSB. */
            uint32_t base = (q << 30) - t0->phi + t0->om * t;
            PUT(0, 0, t, base - 1u, 0, mid, 0, 16384);
            PUT(0, 0, t, base, 0, mid, 0, 16384);
            PUT(0, 0, t, base + 1u, 0, mid, 0, 16384);
        }
    }
    /* The frame counter wraps: t = 2^32 - 1 then t = 0 at the same ph: th moves by exactly -om, as between any two frames. */
    PUT(123, 456, 0xffffffffu, 0, 7, mid, 200, 16384);
    PUT(123, 456, 0u, 0, 7, mid, 200, 16384);
    /* Gain: 0, 1, the cap 1.3 exactly, over the cap (clamped to it), the largest word. */
    PUT(1, 2, 3, 0, 4, mid, 5, 0);
    PUT(1, 2, 3, 0, 4, mid, 5, r->gcap);
    PUT(1, 2, 3, 0, 4, mid, 5, r->gcap + 1u);
    PUT(1, 2, 3, 0, 4, mid, 5, 0x7fff);
    /* Smoothing: the side rays (0 and V-1: weight 0), 1 and 7 rays in (1/8, 7/8), 8 (full), past the box (0). */
    PUT(9, 9, 9, 0, 9, 0, 9, 16384);
    PUT(9, 9, 9, 0, 9, 1, 9, 16384);
    PUT(9, 9, 9, 0, 9, 7, 9, 16384);
    PUT(9, 9, 9, 0, 9, 8, 9, 16384);
    PUT(9, 9, 9, 0, 9, r->width - 1u, 9, 16384);
    PUT(9, 9, 9, 0, 9, r->width - 2u, 9, 16384);
    PUT(9, 9, 9, 0, 9, r->width, 9, 16384);
    PUT(9, 9, 9, 0, 9, 0xffff, 9, 16384);
    /* Grid and box coordinates at their ends. */
    PUT(0xffff, 0xffff, 0xffffffffu, 0xffffffffu, 0xffff, mid, 0xff, 0x7fff);
    PUT(0, 0, 0, 0, 0, mid, 0, 0x4000);
#undef PUT
    return n;
}

/*
 * The register set the block holds, as the vector files' '# reg' lines carry
 * it (np_unit.regs): n, then per train k < n tr<k>.kx kz phi om amp airr cx
 * cz, then the box's width mlog2 pu pv pt omc b gcap (formats of np_wave.h).
 */
static size_t regs(const void *cfg, np_unit_reg *out, size_t max)
{
    const np_wave_regs *r = &((const wave_block *)cfg)->u.r;
    np_unit_reg g[NP_UNIT_MAX_REGS];
    size_t n = 0;
    char name[16];
    np_unit_set_reg(&g[n++], "n", 3, r->n, "u3");
    for (unsigned k = 0; k < r->n && k < NP_WAVE_MAX_TRAINS; k++) {
        const np_wave_train *t = &r->tr[k];
        static const char *const nm[] = { "kx", "kz", "phi", "om", "amp", "airr", "cx", "cz" };
        const uint64_t v[] = { (uint64_t)(int64_t)t->kx, (uint64_t)(int64_t)t->kz, t->phi, t->om, t->amp,
                               t->airr, (uint64_t)(int64_t)t->cx, (uint64_t)(int64_t)t->cz };
        static const unsigned bits[] = { 32, 32, 32, 32, 15, 15, 16, 16 };
        static const char *const fmt[] = { "s32 Q0.32", "s32 Q0.32", "u32 Q0.32", "u32 Q0.32",
                                           "u15 Q5.10", "u15 Q5.10", "s16 Q1.14", "s16 Q1.14" };
        for (unsigned m = 0; m < 8; m++) {
            snprintf(name, sizeof name, "tr%u.%s", k, nm[m]);
            np_unit_set_reg(&g[n++], name, bits[m], v[m], fmt[m]);
        }
    }
    np_unit_set_reg(&g[n++], "width", 16, r->width, "u16");
    np_unit_set_reg(&g[n++], "mlog2", 3, r->mlog2, "u3");
    np_unit_set_reg(&g[n++], "pu", 32, r->pu, "u32 Q0.32");
    np_unit_set_reg(&g[n++], "pv", 32, r->pv, "u32 Q0.32");
    np_unit_set_reg(&g[n++], "pt", 32, r->pt, "u32 Q0.32");
    np_unit_set_reg(&g[n++], "omc", 32, r->omc, "u32 Q0.32");
    np_unit_set_reg(&g[n++], "b", 15, r->b, "u15 Q5.10");
    np_unit_set_reg(&g[n++], "gcap", 15, r->gcap, "u15 Q1.14");
    memcpy(out, g, (n < max ? n : max) * sizeof *out);
    return n;
}

static const char *const conformance_configs[] = { "trains=1,irr=0,cap=0", "trains=4,regs=7", "rom_log2=6",
                                                   "rom_log2=10,trains=3,regs=2", NULL };

const np_unit np_unit_wave = {
    .name = "wave",
    .summary = "Gerstner waves, one grid point a transaction: exact integer phase in turns, quarter-wave "
               "ROM sin/cos, per-train products (Yrjola and Larsson, seed 004)",
    .keys = keys,
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
    .datapath = datapath,
    .trace = trace,
    .conformance_configs = conformance_configs,
    .regs = regs,
};
