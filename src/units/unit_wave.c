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
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "np_unit.h"
#include "unit_entry.h"
#include "np_wave.h"
#include "np_wave_host.h"
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
    if (np_wave_has_jac(&b->u.c))
        np_wave_regs_test_jac(seed, n, &b->u.r);
    else
        np_wave_regs_test(seed, n, &b->u.r);
    if (b->u.c.sincos == NP_WAVE_SINCOS_RECURRENCE) {
        /*
         * The recurrence's bound is larger than the ROM's (sqrt(2) e_s + the
         * drift): amp and airr halved (floor) keep the error under 1 LSB up to
         * a reset of a few thousand; the step registers from kx (np_wave_steps).
         */
        for (unsigned k = 0; k < n; k++) {
            b->u.r.tr[k].amp = (uint16_t)(b->u.r.tr[k].amp >> 1);
            b->u.r.tr[k].airr = (uint16_t)(b->u.r.tr[k].airr >> 1);
        }
        np_wave_steps(&b->u.r);
    }
}

static unsigned regs_default(const void *cfg)
{
    complete(cfg, REGS_DEFAULT);
    return REGS_DEFAULT;
}

static const char *sincos_word(unsigned v)
{
    return v == NP_WAVE_SINCOS_ROM ? "rom" : v == NP_WAVE_SINCOS_RECURRENCE ? "recurrence" : NULL;
}

static const np_unit_key keys[] = {
    NP_UNIT_KEY("trains", wave_block, u.c.trains, 1, NP_WAVE_MAX_TRAINS, 2, "train lanes (Gerstner trains summed per point)"),
    NP_UNIT_KEY("irr", wave_block, u.c.irr, 0, 1, 1, "1: eq. (8) irregular height present"),
    NP_UNIT_KEY("cap", wave_block, u.c.cap, 0, 1, 1, "1: eq. (9) capillary noise present"),
    NP_UNIT_KEY("rom_log2", wave_block, u.c.rom_log2, NP_WAVE_ROM_MIN, NP_WAVE_ROM_MAX, NP_WAVE_ROM_DEF,
                "L: quarter-wave ROM of 2^L x 18 bits, linear interpolation"),
    NP_UNIT_KEY_ADDED_LATER("normals", wave_block, u.c.normals, 0, 1, 0,
                "1: outputs nx, ny, nz, the displaced surface's normal (s20 Q9.10, not normalised)"),
    NP_UNIT_KEY_ADDED_LATER("fold", wave_block, u.c.fold, 0, 1, 0, "1: output fold, det J <= 0 exact on the Jacobian terms"),
    NP_UNIT_KEY_WORDS("sincos", wave_block, u.c.sincos, NP_WAVE_SINCOS_ROM, NP_WAVE_SINCOS_RECURRENCE,
                      NP_WAVE_SINCOS_ROM, "the trains' sin and cos: rom (interpolated) or recurrence (rotated along i)",
                      sincos_word, NP_UNIT_KEY_ADDED),
    NP_UNIT_KEY_ADDED_LATER("reset", wave_block, u.c.reset, 1, NP_WAVE_RESET_MAX, NP_WAVE_RESET_DEF,
                            "N: with sincos=recurrence, a lane re-sets up from the ROM every N points along i"),
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
    const np_wave_cfg *c = &((const wave_block *)cfg)->u.c;
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
    if (c->normals) {
        np_unit_set_field(&f->out[f->n_out++], "nx", NP_WAVE_N_BITS, 1, NP_WAVE_N_FRAC, "s20 Q9.10");
        np_unit_set_field(&f->out[f->n_out++], "ny", NP_WAVE_N_BITS, 1, NP_WAVE_N_FRAC, "s20 Q9.10");
        np_unit_set_field(&f->out[f->n_out++], "nz", NP_WAVE_N_BITS, 1, NP_WAVE_N_FRAC, "s20 Q9.10");
    }
    if (c->fold)
        np_unit_set_field(&f->out[f->n_out++], "fold", 1, 0, 0, "u1");
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

/* The outputs in field order: y, dx, dz, then nx, ny, nz (normals), then fold. */
static void put_out(const np_wave_cfg *c, const np_wave_out *o, const np_wave_jac *j, uint64_t *out)
{
    unsigned n = 0;
    out[n++] = np_trunc_u((uint64_t)(int64_t)o->y, 16);
    out[n++] = np_trunc_u((uint64_t)(int64_t)o->dx, 16);
    out[n++] = np_trunc_u((uint64_t)(int64_t)o->dz, 16);
    if (c->normals) {
        out[n++] = np_trunc_u((uint64_t)(int64_t)j->nx, NP_WAVE_N_BITS);
        out[n++] = np_trunc_u((uint64_t)(int64_t)j->ny, NP_WAVE_N_BITS);
        out[n++] = np_trunc_u((uint64_t)(int64_t)j->nz, NP_WAVE_N_BITS);
    }
    if (c->fold)
        out[n++] = j->fold;
}

static void eval(const void *cfg, const uint64_t *in, uint64_t *out)
{
    const np_wave_unit *u = &((const wave_block *)cfg)->u;
    np_wave_in x;
    np_wave_out o;
    np_wave_jac j;
    in_of(in, &x);
    np_wave_eval_jac(u, &x, &o, &j);
    put_out(&u->c, &o, &j, out);
}

/*
 * np_unit.eval_n: without normals or fold, np_wave_eval_n over chunks (its
 * loops with the lanes and effects as constants for irr=0 cap=0 and 1 or 2
 * ROM trains, eval per point otherwise); with them, the generic fallback.
 */
extern const np_unit np_unit_wave;
static void eval_n(const void *cfg, const uint64_t *in, uint64_t *out, size_t n)
{
    enum { CHUNK = 256 };
    const np_wave_unit *u = &((const wave_block *)cfg)->u;
    if (np_wave_has_jac(&u->c)) {
        np_unit_eval_n_generic(&np_unit_wave, cfg, in, out, n);
        return;
    }
    np_wave_in x[CHUNK];
    np_wave_out o[CHUNK];
    np_wave_jac j;
    memset(&j, 0, sizeof j);
    for (size_t i0 = 0; i0 < n; i0 += CHUNK) {
        size_t m = n - i0 < CHUNK ? n - i0 : CHUNK;
        for (size_t i = 0; i < m; i++) {
            uint64_t w[NP_UNIT_MAX_FIELDS];
            for (unsigned f = 0; f < 8; f++)
                w[f] = in[f * n + i0 + i];
            in_of(w, &x[i]);
        }
        np_wave_eval_n(u, x, o, m);
        for (size_t i = 0; i < m; i++) {
            uint64_t w[NP_UNIT_MAX_FIELDS];
            put_out(&u->c, &o[i], &j, w);
            for (unsigned f = 0; f < 3; f++)
                out[f * n + i0 + i] = w[f];
        }
    }
}

/*
 * The reference: y, dx, dz; the normal from the double terms; the fold flag
 * as the reference's ny <= 0 (the model's flag may differ only where the
 * reference's |ny| is within the normal's error bound: wave.jac_vs_ref).
 */
static void ref(const void *cfg, const uint64_t *in, double *out)
{
    const np_wave_unit *u = &((const wave_block *)cfg)->u;
    np_wave_in x;
    in_of(in, &x);
    np_ref_wave(u, &x, out);
    if (!np_wave_has_jac(&u->c))
        return;
    double j[6], n[3];
    unsigned k = 3;
    np_ref_wave_jac(u, &x, j, n);
    if (u->c.normals)
        for (unsigned q = 0; q < 3; q++)
            out[k++] = n[q];
    if (u->c.fold)
        out[k++] = n[1] <= 0.0 ? 1.0 : 0.0;
}

static double error_bound(const void *cfg)
{
    const np_wave_unit *u = &((const wave_block *)cfg)->u;
    double e = np_wave_error_bound_lsb(u);
    if (u->c.normals) {
        np_wave_jac_bound b = np_wave_jac_error_bound(u);
        for (unsigned q = 0; q < 3; q++)
            e = fmax(e, b.nb[q] * 1024.0);
    }
    return e;
}

static int pipe_init(np_pipe *p, const void *cfg) { return np_wave_pipe_init(p, &((const wave_block *)cfg)->u); }

static void sig_set_in(void *sig, const uint64_t *in)
{
    np_wave_sig *s = sig;
    memset(s, 0, sizeof *s);
    in_of(in, &s->in);
}

static void sig_get_out(const void *cfg, const void *sig, uint64_t *out)
{
    const np_wave_sig *s = sig;
    put_out(&((const wave_block *)cfg)->u.c, &s->out, &s->jac, out);
}

static size_t datapath(const void *cfg, np_op *ops, size_t max)
{
    return np_wave_datapath(&((const wave_block *)cfg)->u, ops, max);
}

static void trace(const void *cfg, unsigned k, const void *sig, np_trace *t, size_t n)
{
    np_wave_trace(&((const wave_block *)cfg)->u, k, sig, t, n);
}

/* The bit-exact pipe's stages run on one input: its signals (for the rounding probes below). */
static void sig_of(const np_wave_unit *u, const np_wave_in *in, np_wave_sig *s)
{
    const np_stage_desc *st = np_wave_stage_table();
    memset(s, 0, sizeof *s);
    s->in = *in;
    for (unsigned k = 0; k < np_wave_stage_count_of(&u->c); k++)
        st[k].fn(u, s);
}

/* The stage G outputs from (possibly altered) sums: y, dx, dz as out_of in np_wave.c. */
static np_wave_out out_from(const np_wave_regs *r, int64_t ys, int64_t xs, int64_t zs, int64_t bc, uint32_t gm)
{
    unsigned ml = r->mlog2;
    np_wave_out o;
    o.y = (int16_t)np_sat_s(np_shr_round_half_up(ys * (int64_t)gm + bc * ((int64_t)1 << (NP_WAVE_GAIN_FRAC + ml)),
                                                 31u + ml),
                            NP_WAVE_OUT_BITS);
    o.dx = (int16_t)np_sat_s(np_shr_round_half_up(xs * (int64_t)gm, 35u + ml), NP_WAVE_OUT_BITS);
    o.dz = (int16_t)np_sat_s(np_shr_round_half_up(zs * (int64_t)gm, 35u + ml), NP_WAVE_OUT_BITS);
    return o;
}

static uint64_t probe_mix(uint64_t x)
{
    x += UINT64_C(0x9e3779b97f4a7c15);
    x = (x ^ (x >> 30)) * UINT64_C(0xbf58476d1ce4e5b9);
    x = (x ^ (x >> 27)) * UINT64_C(0x94d049bb133111eb);
    return x ^ (x >> 31);
}

/*
 * A ROM-read probe: train 0's sin (cosine = 0) or cos (cosine = 1) read at
 * phase th, where a misreading of the ROM read gives the value vm instead (the
 * one's-complement mirror: th + 1's in quadrants 1 and 3; f rounded from the
 * dropped bits: th rounded up to the next f's; the interpolation's tie
 * rounded down). Searches i = 0 .. 1023 (j = u =
 * t = r = 0, mid-box, gain 1, ph putting train 0 at its phase) for a point
 * whose output changes under that misreading; 1 and the input when found.
 */
static int rom_probe(const np_wave_unit *u, uint32_t th, int64_t vm, int cosine, np_wave_in *in)
{
    const np_wave_regs *r = &u->r;
    const np_wave_train *t0 = &r->tr[0];
    if (vm == np_wave_sin(th, u->c.rom_log2))
        return 0;
    for (uint16_t i = 0; i < 1024; i++) {
        np_wave_sig s;
        const uint32_t th0 = cosine ? th - (UINT32_C(1) << 30) : th;
        *in = (np_wave_in){ .i = i, .ph = th0 - (uint32_t)t0->kx * i - t0->phi, .v = (uint16_t)(r->width / 2u), .g = 16384 };
        sig_of(u, in, &s);
        int64_t ys = s.ys, xs = s.xs, zs = s.zs;
        if (cosine) {
            ys += np_shr_round_half_up((int64_t)s.ap[0] * vm, 7) - s.yc[0];
        } else {
            const int64_t d = np_shr_round_half_up((int64_t)s.ap[0] * vm, NP_WAVE_SIN_FRAC) - s.sa[0];
            xs -= d * t0->cx;
            zs -= d * t0->cz;
        }
        const np_wave_out o = out_from(r, ys, xs, zs, s.bc, s.gm);
        if (o.y != s.out.y || o.dx != s.out.dx || o.dz != s.out.dz)
            return 1;
    }
    return 0;
}

/* y, dx, dz's sums (stage T) of a transaction. */
typedef struct wave_sums {
    int64_t ys, xs, zs;
} wave_sums;

/* Lane k's yc and sa replaced by those of (ap, c, s) in the sums m. */
static void relane(const np_wave_unit *u, const np_wave_sig *s, unsigned k, int64_t ap, int64_t c, int64_t sv,
                   wave_sums *m)
{
    const np_wave_train *t = &u->r.tr[k];
    const int64_t sa = np_shr_round_half_up(ap * sv, NP_WAVE_SIN_FRAC);
    m->ys += np_shr_round_half_up(ap * c, 7) - s->yc[k];
    m->xs -= (sa - s->sa[k]) * t->cx;
    m->zs -= (sa - s->sa[k]) * t->cz;
}

/* The first gain g = 1 .. gcap (mid-box: sm = M) at which the outputs of the sums m differ from the spec's; 0 if none. */
static uint16_t flip_gain(const np_wave_unit *u, const np_wave_sig *s, const wave_sums *m)
{
    const uint32_t M = UINT32_C(1) << u->r.mlog2;
    for (uint32_t g = 1; g <= u->r.gcap && g < 0x8000u; g++) {
        const np_wave_out a = out_from(&u->r, s->ys, s->xs, s->zs, s->bc, M * g);
        const np_wave_out b = out_from(&u->r, m->ys, m->xs, m->zs, s->bc, M * g);
        if (a.y != b.y || a.dx != b.dx || a.dz != b.dz)
            return (uint16_t)g;
    }
    return 0;
}

/*
 * 1 when v / 2^sh is a tie that a misread rounding takes down where the
 * spec's half-up takes it up under both misreadings: negative (ties away
 * from zero) and an even floor (ties to even).
 */
static int low_tie(int64_t v, unsigned sh)
{
    const int64_t half = (int64_t)1 << (sh - 1u);
    return v < 0 && ((uint64_t)v & (((uint64_t)1 << sh) - 1u)) == (uint64_t)half &&
           (((v - half) / ((int64_t)1 << sh)) & 1) == 0;
}

/*
 * Internal-rounding tie probes (ROM configurations): points at which one of
 * the roundings w, ap (lane k), yc, sa, or dx/dz's final one, is at a tie
 * that ties to even and ties away from zero both take down, with the gain
 * chosen so that the output changes by it (flip_gain; for dx/dz the exact
 * tie). A tie in yc is also where yc truncated differs. At most two each;
 * the searches are bounded (about 2^18 points each), so a register set may
 * give fewer.
 */
static size_t tie_probes(const np_wave_unit *u, uint64_t (*in)[NP_UNIT_MAX_FIELDS], size_t max, size_t n)
{
    const np_wave_regs *r = &u->r;
    const unsigned L = u->c.rom_log2, lanes = r->n < u->c.trains ? r->n : u->c.trains;
    const uint16_t mid = (uint16_t)(r->width / 2u);
    enum { P_W, P_AP, P_YC, P_SA, P_DXZ, P_KINDS }; /* P_DXZ: its own search, first */
    unsigned found[P_KINDS] = { 0, 0, 0, 0, 0 };
    if (!u->c.irr)
        found[P_W] = found[P_AP] = 2; /* no w, ap = A 2^7 */
    /*
     * dx's or dz's exact tie needs X (or Z) with e >= 20 trailing zeros: with
     * two lanes, ph puts lane 1's phase at 0 (its sa = 0), so X = -sa0 cx0 and
     * the test sets' cx0 = 2^14 leaves 6 bits to find in sa0.
     */
    for (uint64_t k = 0; k < (UINT64_C(1) << 16) && found[P_DXZ] < 2; k++) {
        const uint64_t h = probe_mix(UINT64_C(0x64787a) ^ k);
        np_wave_in x = { .i = (uint16_t)h, .u = (uint16_t)(h >> 16), .v = (uint16_t)(mid - ((h >> 32) & 255u)),
                         .ph = (uint32_t)(h >> 32) * UINT32_C(0x9e3779b9), .g = 16384 };
        if (lanes == 2)
            x.ph = 0u - (uint32_t)r->tr[1].kx * x.i - r->tr[1].phi;
        np_wave_sig s;
        sig_of(u, &x, &s);
        for (unsigned c = 0; c < 2 && found[P_DXZ] < 2; c++) {
            /* X G / 2^(35+mlog2) with G = M g, g = 2^(34-e) h (h odd): an exact tie. */
            const int64_t X = c ? s.zs : s.xs;
            unsigned e = 0;
            while (X != 0 && e < 40 && !((X >> e) & 1))
                e++;
            if (X >= 0 || e < 20 || e > 34)
                continue;
            const uint32_t gb = UINT32_C(1) << (34u - e);
            for (uint32_t hh = 1; gb * hh <= r->gcap; hh += 2)
                if (low_tie(X * gb * hh, 35)) {
                    if (n < max) {
                        const uint64_t w_[8] = { x.i, x.j, x.t, x.ph, x.u, x.v, x.r, gb * hh };
                        memcpy(in[n], w_, sizeof w_);
                    }
                    n++;
                    found[P_DXZ]++;
                    break;
                }
        }
    }
    for (uint64_t k = 0; k < (UINT64_C(1) << 18); k++) {
        int more = 0;
        for (unsigned q = 0; q < P_DXZ; q++)
            more |= found[q] < 2;
        if (!more)
            break;
        const uint64_t h = probe_mix(UINT64_C(0x7761766574696573) ^ k);
        np_wave_in x = { .i = (uint16_t)h, .u = (uint16_t)(h >> 16), .v = (uint16_t)(mid - ((h >> 32) & 255u)),
                         .ph = (uint32_t)(h >> 32) * UINT32_C(0x9e3779b9), .g = 16384 };
        const int64_t s1 = u->c.irr ? np_wave_sin(r->pu * x.u, L) : 0, s2 = u->c.irr ? np_wave_sin(r->pv * x.v, L) : 0;
        const int w_tie = u->c.irr && found[P_W] < 2 && low_tie(s1 * s2, NP_WAVE_SIN_FRAC);
        if (k % 64u != 0 && !w_tie && found[P_YC] >= 2 && found[P_SA] >= 2 && found[P_AP] >= 2)
            continue;
        np_wave_sig s;
        sig_of(u, &x, &s);
        for (unsigned q = 0; q < P_DXZ; q++) {
            if (found[q] >= 2)
                continue;
            for (unsigned lk = 0; lk < (q == P_W ? 1u : lanes); lk++) {
                wave_sums m = { s.ys, s.xs, s.zs };
                const np_wave_train *t = &r->tr[lk];
                if (q == P_W) {
                    if (!w_tie)
                        continue;
                    for (unsigned kk = 0; kk < lanes; kk++) {
                        const np_wave_train *tk = &r->tr[kk];
                        const int64_t ap = (int64_t)tk->amp * 128 -
                                           np_shr_round_half_up((int64_t)tk->airr * (s.w - 1), NP_WAVE_AMP_FRAC);
                        relane(u, &s, kk, ap, s.c[kk], s.s[kk], &m);
                    }
                } else if (q == P_AP) {
                    if (!low_tie((int64_t)t->airr * s.w, NP_WAVE_AMP_FRAC))
                        continue;
                    relane(u, &s, lk, s.ap[lk] + 1, s.c[lk], s.s[lk], &m);
                } else if (q == P_YC) {
                    if (!low_tie((int64_t)s.ap[lk] * s.c[lk], 7))
                        continue;
                    m.ys -= 1;
                } else {
                    if (!low_tie((int64_t)s.ap[lk] * s.s[lk], NP_WAVE_SIN_FRAC))
                        continue;
                    m.xs += t->cx;
                    m.zs += t->cz;
                }
                const uint16_t g = flip_gain(u, &s, &m);
                if (!g)
                    continue;
                if (n < max) {
                    const uint64_t w_[8] = { x.i, x.j, x.t, x.ph, x.u, x.v, x.r, g };
                    memcpy(in[n], w_, sizeof w_);
                }
                n++;
                found[q]++;
                break;
            }
        }
    }
    return n;
}

/*
 * Rounding and ROM-read probes (appended to the boundary table; the ROM's
 * sin/cos configurations only): inputs where a plausible misreading of
 * docs/wave.md changes an output, found by search from the register set.
 *  - y's rounding at a tie from the capillary term alone: g = 0, r = 1, t
 *    with b sc = 2^16 mod 2^17 (3 positive, 3 negative);
 *  - y's rounding at a tie from the trains: r = 0 (bc = 0), ph with Y having
 *    e >= 16 trailing zeros, g = 2^(30-e), so Y G / 2^(31+mlog2) is odd/2
 *    (3 positive, 3 negative);
 *  - the ROM mirror: train 0's sin and cos in quadrants 1 and 3 at an x' whose
 *    dropped bits are 0, where 2^30 - 1 - x (the one's complement) reads
 *    another value (2 each);
 *  - the dropped phase bits: train 0's sin and cos in quadrants 0 and 2 with
 *    dropped bits >= half of f's LSB, where rounding them into f reads another
 *    value (2 each).
 */
static size_t probes(const np_wave_unit *u, uint64_t (*in)[NP_UNIT_MAX_FIELDS], size_t max, size_t n)
{
    const np_wave_regs *r = &u->r;
    const unsigned L = u->c.rom_log2, drop = 30u - L - NP_WAVE_IFRAC;
    const uint16_t mid = (uint16_t)(r->width / 2u);
    np_wave_in x;
#define PUTIN(X)                                                                                                 \
    do {                                                                                                         \
        if (n < max) {                                                                                           \
            const uint64_t w_[8] = { (X).i, (X).j, (X).t, (X).ph, (X).u, (X).v, (X).r, (X).g };                 \
            memcpy(in[n], w_, sizeof w_);                                                                        \
        }                                                                                                        \
        n++;                                                                                                     \
    } while (0)
    if (u->c.cap && r->b) {
        unsigned pos = 0, neg = 0;
        for (uint32_t t = 0; t < (UINT32_C(1) << 22) && (pos < 3 || neg < 3); t++) {
            const int64_t bc = (int64_t)r->b * np_wave_sin(r->omc * t, L);
            if ((bc & 0x1ffff) != 0x10000 || (bc > 0 ? pos >= 3 : neg >= 3))
                continue;
            *(bc > 0 ? &pos : &neg) += 1;
            x = (np_wave_in){ .t = t, .v = mid, .r = 1, .g = 0 };
            PUTIN(x);
        }
    }
    {
        unsigned pos = 0, neg = 0;
        for (uint32_t k = 0; k < (UINT32_C(1) << 20) && (pos < 3 || neg < 3); k++) {
            np_wave_sig s;
            x = (np_wave_in){ .ph = k * UINT32_C(0x9e3779b9), .v = mid, .g = 16384 };
            sig_of(u, &x, &s);
            if (s.ys == 0 || (s.ys > 0 ? pos >= 3 : neg >= 3))
                continue;
            unsigned e = 0;
            while (!((s.ys >> e) & 1))
                e++;
            if (e < 16 || e > 30 || (UINT32_C(1) << (30 - e)) > r->gcap)
                continue;
            *(s.ys > 0 ? &pos : &neg) += 1;
            x.g = (uint16_t)(1u << (30 - e));
            PUTIN(x);
        }
    }
    for (unsigned kind = 0; kind < 8; kind++) {
        /* kind: bit 0 cos, bit 1 the second quadrant of the pair, bit 2 dropped bits (else mirror). */
        const int cosine = (int)(kind & 1u), dropped = (int)(kind >> 2);
        const uint32_t q = dropped ? (kind & 2u) : 1u + (kind & 2u);
        unsigned found = 0;
        for (uint64_t k = 0; k < 4096 && found < 2; k++) {
            const uint32_t h = (uint32_t)probe_mix(((uint64_t)kind << 32) | k) & UINT32_C(0x3fffffff);
            uint32_t th, thm;
            if (dropped) {
                const uint32_t m = (UINT32_C(1) << drop) - 1u;
                const uint32_t xv = (h & ~m) | (UINT32_C(1) << (drop - 1)) | (h & (m >> 1));
                if ((xv | m) + 1u >= (UINT32_C(1) << 30))
                    continue;
                th = (q << 30) + xv;
                thm = (q << 30) + (xv | m) + 1u;
            } else {
                const uint32_t xp = h & ~((UINT32_C(1) << drop) - 1u);
                if (xp == 0)
                    continue;
                th = (q << 30) + ((UINT32_C(1) << 30) - xp);
                thm = th + 1u;
            }
            if (rom_probe(u, th, np_wave_sin(thm, L), cosine, &x)) {
                PUTIN(x);
                found++;
            }
        }
    }
    /* The interpolation's tie, taken down by ties to even: train 0's sin and cos at f = 2^(15-e) h (h odd, D = 2^e o). */
    for (unsigned cosine = 0; cosine < 2; cosine++) {
        unsigned found = 0;
        for (uint64_t k = 0; k < 4096 && found < 2; k++) {
            const uint32_t hk = (uint32_t)probe_mix(UINT64_C(0x696e74657270) + 2 * k + cosine);
            const uint32_t a = hk & ((UINT32_C(1) << L) - 1u), sh = 30u - L;
            const int64_t D = (int64_t)np_wave_rom((a + 1u) << (10u - L)) - (int64_t)np_wave_rom(a << (10u - L));
            unsigned e = 0;
            while (D > 0 && e < 16 && !((D >> e) & 1))
                e++;
            if (D <= 0 || e > 15)
                continue;
            const uint32_t f = (UINT32_C(1) << (15u - e)) * (((hk >> 12) | 1u) & ((UINT32_C(1) << (e + 1u)) - 1u));
            if (f >= (UINT32_C(1) << 16) || !(((D * f) >> 16) % 2 == 0) || (D * f) % 65536 != 32768)
                continue;
            const uint32_t th = (a << sh) | (f << (sh - NP_WAVE_IFRAC));
            if (rom_probe(u, th, np_wave_sin(th, L) - 1, (int)cosine, &x)) {
                PUTIN(x);
                found++;
            }
        }
    }
#undef PUTIN
    return tie_probes(u, in, max, n);
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
    if (((const wave_block *)cfg)->u.c.sincos == NP_WAVE_SINCOS_ROM)
        n = probes(&((const wave_block *)cfg)->u, in, max, n);
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
        static const char *const nm[] = { "kx", "kz", "phi", "om", "amp", "airr", "cx", "cz", "kmx", "kmz", "dc", "ds" };
        const uint64_t v[] = { (uint64_t)(int64_t)t->kx,  (uint64_t)(int64_t)t->kz,  t->phi, t->om, t->amp,
                               t->airr, (uint64_t)(int64_t)t->cx, (uint64_t)(int64_t)t->cz,
                               (uint64_t)(int64_t)t->kmx, (uint64_t)(int64_t)t->kmz, (uint64_t)(int64_t)t->dc,
                               (uint64_t)(int64_t)t->ds };
        static const unsigned bits[] = { 32, 32, 32, 32, 15, 15, 16, 16, 16, 16, 32, 32 };
        static const char *const fmt[] = { "s32 Q0.32", "s32 Q0.32", "u32 Q0.32", "u32 Q0.32", "u15 Q5.10", "u15 Q5.10",
                                           "s16 Q1.14", "s16 Q1.14", "s16 Q3.12", "s16 Q3.12", "s32 Q1.30", "s32 Q1.30" };
        /* kmx, kmz only with normals or fold, dc, ds only with recurrence (the default's lines are as they were). */
        const np_wave_cfg *c = &((const wave_block *)cfg)->u.c;
        for (unsigned m = 0; m < 12; m++) {
            if ((m == 8 || m == 9) && !np_wave_has_jac(c))
                continue;
            if ((m == 10 || m == 11) && c->sincos != NP_WAVE_SINCOS_RECURRENCE)
                continue;
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
                                                   "rom_log2=10,trains=3,regs=2", "normals=1,fold=1",
                                                   "trains=3,irr=0,fold=1,regs=5", "sincos=recurrence",
                                                   "sincos=recurrence,reset=7,trains=3,regs=2,normals=1", NULL };

const np_unit np_unit_wave = {
    .name = "wave",
    .summary = "Gerstner waves, one grid point a transaction: exact integer phase in turns, quarter-wave "
               "ROM sin/cos, per-train products (Yrjola and Larsson, seed 004)",
    NP_UNIT_MODEL_ENTRY,
    .tolerance_lsb = 1.0,
    .regs = regs,
    .eval_n = eval_n,
};
