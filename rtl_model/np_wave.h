/* SPDX-License-Identifier: MIT */
/*
 * np_wave.h - the Gerstner wave unit `wave` of Yrjola and Larsson, "Real-time
 * Generation of Plausible Surface Waves" (shared/seeds/004): one water grid
 * point per transaction, the N wave trains of one wave train box (WTB) summed
 * (eqs. (6), (7)), with the box's irregular height (eq. (8)), capillary noise
 * (eq. (9)), side smoothing and the wave ray's gain. Refraction and round
 * waves (eq. (10)) reach the unit as the ray's phase shift ph (host side,
 * src/wave/). docs/wave.md is the specification in prose; this header is the
 * bit-exact one.
 *
 * Phase is an exact integer in turns (Q0.32, modulo 2^32 = one turn), so
 * the phase of every train is exact at every frame t: no drift, ever, and the
 * frame counter may wrap (after 2^32 frames) without a jump.
 *
 * Inputs of a transaction (one grid point):
 *   i, j     u16          grid indices of the point (rest position p0 = (i, j) grid steps)
 *   t        u32          frame counter (wraps modulo 2^32)
 *   ph       u32 Q0.32    the wave ray's phase shift Phi_ray, turns (refraction, round waves)
 *   u        u16          the point's step along its ray (box coordinate along the wind)
 *   v        u16          its ray (box coordinate across the wind), 0 .. V-1
 *   r        u8           capillary rate index of the point (eq. (9): r = r/256 of the paper)
 *   g        u15 Q1.14    the ray's gain (shallow water, land 0, recovery); used as min(g, gcap)
 *
 * Registers of the box (np_wave_regs), per train k < n <= NP_WAVE_MAX_TRAINS:
 *   kx, kz   s32 Q0.32    wave vector in turns per grid step (K = k * spacing / 2pi)
 *   phi      u32 Q0.32    phase, turns
 *   om       u32 Q0.32    angular frequency in turns per frame (omega * dt / 2pi mod 1)
 *   amp      u15 Q5.10    amplitude A, metres
 *   airr     u15 Q5.10    irregular height amplitude a_k (eq. (8)); airr <= amp (refused otherwise)
 *   cx, cz   s16 Q1.14    direction of the horizontal displacement, any c with |c| <= 1: a
 *                         scene's host sets k/|k|; the test sets (np_wave_regs_test) draw c
 *                         independently of k (0.75 <= |c| <= 1; train 0's c = (1, 0))
 * and for the box:
 *   width    u16          V, rays across the box (the test sets: 2^15 .. 2^16 - 1)
 *   mlog2    u3           smoothing margin M = 2^mlog2 rays (PIN 8: mlog2 = 3)
 *   pu,pv,pt u32 Q0.32    eq. (8)'s phases: sin(pu u + pt t) sin(pv v), turns per step / frame
 *   omc      u32 Q0.32    eq. (9)'s rate: phase r * omc * t, turns
 *   b        u15 Q5.10    capillary amplitude, metres
 *   gcap     u15 Q1.14    the ray gain's cap (PIN Green's law capped at 1.3: 21299)
 *
 * Signals (stage: signal format - definition). All phases are exact modulo 2^32.
 *   P: th[k]   u32 Q0.32  kx i + kz j + phi + ph - om t          (mod 2^32)
 *      p1      u32 Q0.32  pu u + pt t;  p2 = pv v;  pc = r omc t  (mod 2^32)
 *      d       u16        v < V ? min(v, V-1-v) : 0; sm = min(d, M)  (u(mlog2+1)); weight sm / M
 *   S: c[k], s[k]  s19 Q1.17  cos th, sin th from the quarter-wave ROM (np_wave_sin); so s1, s2, sc
 *   A: w       s19 Q1.17  round(s1 s2 / 2^17)                    (|w| <= 1)
 *      ap[k]   u24 Q6.17  amp 2^7 - round(airr w / 2^10)         (0 <= ap <= amp + airr; irr=0: amp 2^7)
 *      G       u(15+mlog2+1) Q1.(14+mlog2)  sm * min(g, gcap)    exact
 *   M: yc[k]   s35 Q6.27  round(ap c / 2^7)
 *      sa[k]   s24 Q6.17  round(ap s / 2^17)
 *      xp[k]   s39 Q8.31  sa cx;  zp[k] = sa cz                   exact
 *      bc      s33 Q6.27  b sc                                    exact (cap=0: 0)
 *   T: Y       s37 Q10.27 sum yc;  X = -sum xp, Z = -sum zp (s41 Q10.31)  exact adder trees
 *   G: y       s16 Q5.10  round((Y G + bc 2^(14+mlog2)) / 2^(31+mlog2))   one rounding
 *      dx, dz  s16 Q5.10  round(X G / 2^(35+mlog2)), likewise Z
 * round() is np_shr_round_half_up (ties toward +infinity).
 *
 * Normals and the fold flag (keys normals=1, fold=1; absent otherwise). Two
 * more registers per train, read only then: kmx, kmz s16 Q3.12, the wave
 * vector in radians per metre (a scene's host sets k = 2 pi K / spacing; the
 * test sets draw them). The displaced surface P = p0 + G sum_k (-c_k ap_k sin,
 * ap_k cos, ...) has, with G and ap held constant over the point (the gain,
 * the smoothing and eq. (8)'s amplitude vary per ray and step: their slopes are
 * not in the terms), the Jacobian terms
 *   jxx = d(dx)/dx0 = -G sum ap c cx kmx,  jxz = d(dx)/dz0 = -G sum ap c cx kmz,
 *   jzx = d(dz)/dx0 = -G sum ap c cz kmx,  jzz = d(dz)/dz0 = -G sum ap c cz kmz,
 *   yx  = dy/dx0    = -G sum ap s kmx,     yz  = dy/dz0    = -G sum ap s kmz,
 * from the lane's products ap c and ap s:
 *   M: yq[k]     s24 Q6.17   round(ap c / 2^17)        (the same product ap c as yc, a second rounding)
 *      e[k]      s31 Q4.26   cx kmx, cx kmz, cz kmx, cz kmz   exact (register products)
 *      lj[k][0..3] s40 Q10.29  round(yq e / 2^14)
 *      lj[k][4,5]  s39 Q9.29   sa kmx, sa kmz            exact
 *   T: js[0..5]  s42 Q12.29  -sum over the lanes         exact
 *   G: j[0..5]   s18 Q3.14   round(js G / 2^(29+mlog2))  one rounding each
 *   N: (stage 7) a = 2^14 + jxx, d = 2^14 + jzz (s19 Q4.14); exact products and differences in Q8.28:
 *      Nx = yz jzx - d yx,  Ny = a d - jxz jzx,  Nz = jxz yx - yz a     s38 Q9.28 (exact)
 *      nx, ny, nz = round(N / 2^18)                                    s20 Q9.10, one rounding each
 *      fold = (Ny <= 0), on the exact Ny                                u1
 * (nx, ny, nz) = dP/dz0 x dP/dx0, the upward normal, not normalised (Ny is
 * det J of the horizontal map); fold is exact on the terms' integers. The
 * check refuses a register set whose terms could reach 8 (G sum (A + a) |e|,
 * G sum (A + a) |km|: the s18 Q3.14 range) or whose normal's error bound
 * against the double reference (np_wave_jac_error_bound) reaches 1 LSB of
 * s20 Q9.10 (the terms are internal; their bounds are stated, not held to an LSB).
 *
 * sin from the ROM (np_wave_sin). The ROM holds R[a] = round(2^17 sin(2 pi a / 2^(L+2))),
 * a = 0 .. 2^L - 1 (L = rom_log2, default 8: 2^8 x 18 bits), R[2^L] = 2^17 is a constant.
 * For a phase th: quadrant q = th[31:30], x = th[29:0]; quadrants 0 and 2
 * read x' = x, quadrants 1 and 3 the mirror x' = 2^30 - x (exact, x' in
 * [0, 2^30]); a = x' >> (30 - L), f = the next NP_WAVE_IFRAC bits of x' (the
 * bits below are dropped), value R[a] + round((R[a+1] - R[a]) f / 2^IFRAC),
 * negated in quadrants 2 and 3. cos th = sin(th + 2^30). The read edge:
 * x' = 2^30 (quadrants 1 and 3 with x = 0: th = 1/4 or 3/4 turn) gives
 * a = 2^L, f = 0 and exactly R[2^L] = 2^17; R[2^L + 1] is never read (a's
 * successor is a itself there).
 *
 * Error of sin (np_wave_sin_bound, asserted by wave.sincos_bound over every
 * ROM interval's worst points, 2^22 random phases and a local search): ROM rounding 2^-18, the
 * interpolation's rounding 2^-18, the chord's error h^2/8 (h = 2 pi / 2^(L+2)
 * radians per ROM step), and the dropped phase bits 2 pi (2^(30-L-IFRAC) - 1) / 2^32:
 *   e_s <= 2^-17 + (2 pi / 2^(L+2))^2 / 8 + 2 pi (2^(30-L-IFRAC) - 1) 2^-32.
 * For L = 8: 2^-17 + (2 pi/2^10)^2/8 + 9.2e-8 = 1.243e-5.
 *
 * Output range (np_wave_regs_check proves it and refuses a register set for
 * which it fails): |G| <= gcap / 2^14, |ap| <= amp + airr, |c|, |s|, |sc| <= 1,
 * |cx|, |cz| <= 1, so
 *   |y| <= (gcap / 2^14) sum (amp_k + airr_k) + b       (all in Q5.10 LSB: <= 2^15 - 1)
 * and the same without b for dx, dz: the outputs never saturate for an
 * accepted register set (the model still saturates, to keep the contract
 * if the check is bypassed).
 *
 * Error against the double reference from the same registers
 * (np_wave_error_bound_lsb): the final rounding 1/2 LSB plus, in LSB,
 *   2^10 [ Gm (sum (amp+airr) e_s + sum airr (2 e_s + 2^-18) + n (2^-18 + 2^-28)) + b e_s ]   for y,
 *   2^10 [ Gm (sum (amp+airr) e_s + sum airr (2 e_s + 2^-18) + n 2^-17) ]                     for dx, dz
 * Gm = gcap / 2^14: below 1 LSB whenever the sum of amplitudes fits the output.
 */
#ifndef NP_WAVE_H
#define NP_WAVE_H

#include <stddef.h>
#include <stdint.h>

#include "np_datapath.h"
#include "np_fixed.h"
#include "np_pipe.h"

#ifdef __cplusplus
extern "C" {
#endif

enum {
    NP_WAVE_MAX_TRAINS = 4,
    NP_WAVE_SIN_FRAC = 17,  /* sin, cos: s19 Q1.17 */
    NP_WAVE_AMP_FRAC = 10,  /* amp, airr, b, outputs: Q5.10 */
    NP_WAVE_DIR_FRAC = 14,  /* cx, cz: Q1.14 */
    NP_WAVE_GAIN_FRAC = 14, /* g, gcap: Q1.14 */
    NP_WAVE_IFRAC = 16,     /* interpolation fraction bits */
    NP_WAVE_ROM_MIN = 6,
    NP_WAVE_ROM_MAX = 10,
    NP_WAVE_ROM_DEF = 8,
    NP_WAVE_OUT_BITS = 16,
    NP_WAVE_GCAP_DEF = 21299, /* round(1.3 * 2^14) */
    NP_WAVE_MLOG2_DEF = 3,    /* PIN: an 8-ray smoothing margin */
    NP_WAVE_MLOG2_MAX = 6,
    NP_WAVE_KM_FRAC = 12,   /* kmx, kmz: s16 Q3.12 rad/m */
    NP_WAVE_JAC_FRAC = 14,  /* the Jacobian terms jxx .. yz: s18 Q3.14 */
    NP_WAVE_JAC_BITS = 18,
    NP_WAVE_LJ_FRAC = 29,   /* a lane's Jacobian products and their sums: Q.29 */
    NP_WAVE_N_FRAC = 10,    /* the normal nx, ny, nz: s20 Q9.10 */
    NP_WAVE_N_BITS = 20
};

/* The datapath's configuration (the registry's keys). */
typedef struct np_wave_cfg {
    unsigned trains;   /* lanes, 1 .. NP_WAVE_MAX_TRAINS */
    unsigned irr;      /* 1: eq. (8) irregular height present */
    unsigned cap;      /* 1: eq. (9) capillary noise present */
    unsigned rom_log2; /* L: 2^L ROM words a quarter wave */
    unsigned normals;  /* 1: the outputs nx, ny, nz (the displaced surface's normal, unnormalised) */
    unsigned fold;     /* 1: the output fold (det J <= 0) */
    unsigned sincos;   /* NP_WAVE_SINCOS_ROM (0) or NP_WAVE_SINCOS_RECURRENCE (1): the trains' sin and cos */
    unsigned reset;    /* recurrence: the re-set-up interval N along i, trains .. 65536 (default 64) */
} np_wave_cfg;

enum { NP_WAVE_SINCOS_ROM = 0, NP_WAVE_SINCOS_RECURRENCE = 1, NP_WAVE_RESET_DEF = 64, NP_WAVE_RESET_MAX = 65536 };

typedef struct np_wave_train {
    int32_t kx, kz;
    uint32_t phi, om;
    uint16_t amp, airr;
    int16_t cx, cz;
    int16_t kmx, kmz; /* s16 Q3.12 rad/m: read only with normals or fold */
    int32_t dc, ds;   /* s32 Q1.30: cos, sin of the step 2 pi kx / 2^32 along i; read only with sincos=recurrence */
} np_wave_train;

typedef struct np_wave_regs {
    unsigned n; /* trains in use, <= cfg.trains */
    np_wave_train tr[NP_WAVE_MAX_TRAINS];
    uint16_t width;
    unsigned mlog2;
    uint32_t pu, pv, pt, omc;
    uint16_t b, gcap;
} np_wave_regs;

/* The unit: datapath configuration and the box's registers. */
typedef struct np_wave_unit {
    np_wave_cfg c;
    np_wave_regs r;
} np_wave_unit;

typedef struct np_wave_in {
    uint16_t i, j;
    uint32_t t, ph;
    uint16_t u, v;
    uint8_t r;
    uint16_t g; /* u15 */
} np_wave_in;

typedef struct np_wave_out {
    int16_t y, dx, dz; /* s16 Q5.10 */
} np_wave_out;

/* The Jacobian's outputs, with normals or fold (np_wave_eval_jac). */
enum { NP_WAVE_JXX, NP_WAVE_JXZ, NP_WAVE_JZX, NP_WAVE_JZZ, NP_WAVE_YX, NP_WAVE_YZ, NP_WAVE_NJ };
typedef struct np_wave_jac {
    int32_t j[NP_WAVE_NJ]; /* s18 Q3.14: jxx, jxz, jzx, jzz, yx, yz (internal signals; traced) */
    int64_t ny28;          /* s38 Q8.28: det J exact from the terms (internal) */
    int32_t nx, ny, nz;    /* s20 Q9.10: outputs with normals */
    unsigned fold;         /* u1: ny28 <= 0: output with fold */
} np_wave_jac;

/* The pipe's signal bundle. */
typedef struct np_wave_sig {
    np_wave_in in;
    uint32_t th[NP_WAVE_MAX_TRAINS], p1, p2, pc;
    unsigned sm;
    int32_t c[NP_WAVE_MAX_TRAINS], s[NP_WAVE_MAX_TRAINS], s1, s2, sc;
    int32_t w, ap[NP_WAVE_MAX_TRAINS];
    uint32_t gm;
    int64_t yc[NP_WAVE_MAX_TRAINS], sa[NP_WAVE_MAX_TRAINS], xp[NP_WAVE_MAX_TRAINS], zp[NP_WAVE_MAX_TRAINS], bc;
    int64_t ys, xs, zs;
    int64_t yq[NP_WAVE_MAX_TRAINS], lj[NP_WAVE_MAX_TRAINS][6]; /* normals or fold: stage M */
    int64_t js[6];                                               /* stage T */
    np_wave_out out;
    np_wave_jac jac; /* stages G (the terms) and N */
} np_wave_sig;

np_wave_cfg np_wave_cfg_default(void);
/* NULL, or why the configuration is out of range. */
const char *np_wave_cfg_check(const np_wave_cfg *c);
/*
 * NULL, or why the register set is refused for configuration c: too many
 * trains, airr > amp ("a > A"), |c| > 1, a width or margin out of range, or
 * an output range over s16 (the range proof above).
 */
const char *np_wave_regs_check(const np_wave_cfg *c, const np_wave_regs *r);
/* The proven output bound (LSB of Q5.10) of y (with_b) or dx, dz. */
int64_t np_wave_range_lsb(const np_wave_regs *r, int with_b);
/* The proven bounds (LSB of Q3.12) of the Jacobian terms jxx, jxz, jzx, jzz, yx, yz; <= 0x7fff when accepted. */
void np_wave_jac_range_lsb(const np_wave_regs *r, int64_t jb[NP_WAVE_NJ]);

/* The ROM word a (0 .. 2^10), u18 Q1.17, at the finest resolution; R_L[a] = np_wave_rom(a << (10 - L)). */
uint32_t np_wave_rom(unsigned a);
/* sin(2 pi th / 2^32) as s19 Q1.17 through a 2^L-word ROM (above). */
int32_t np_wave_sin(uint32_t th, unsigned rom_log2);
static inline int32_t np_wave_cos(uint32_t th, unsigned rom_log2)
{
    return np_wave_sin(th + (UINT32_C(1) << 30), rom_log2);
}
/* The bound e_s of |np_wave_sin - sin| (above), in units of 1. */
double np_wave_sin_bound(unsigned rom_log2);
/*
 * sincos=recurrence: the trains' cos and sin (s19 Q1.17) as lane k holds
 * them at this transaction (np_wave_lane_sincos; docs/wave.md), and the bound
 * of their error after m rotations: sqrt(2) e_s + m 2^-29 + 2^-18
 * (np_wave_recur_bound); np_wave_lane_bound(c) is its largest, m = N - 1,
 * and e_s itself with the ROM.
 */
void np_wave_lane_sincos(const np_wave_unit *u, unsigned k, const np_wave_in *in, int32_t *c, int32_t *s);
double np_wave_recur_bound(unsigned rom_log2, uint64_t m);
double np_wave_lane_bound(const np_wave_cfg *c);

/* Bit-exact model of one transaction. */
void np_wave_eval(const np_wave_unit *u, const np_wave_in *in, np_wave_out *out);
/* The same for n transactions (the host's frames: one call a run of points). */
void np_wave_eval_n(const np_wave_unit *u, const np_wave_in *in, np_wave_out *out, size_t n);
/* The same with the Jacobian's outputs (jac: zeros when the configuration has neither normals nor fold). */
void np_wave_eval_jac(const np_wave_unit *u, const np_wave_in *in, np_wave_out *out, np_wave_jac *jac);
/* The error bound against the double reference from the same registers, LSB (max over y, dx, dz). */
double np_wave_error_bound_lsb(const np_wave_unit *u);

/*
 * Cycle-accurate model: stages P S A M T G over np_wave_sig; cfg = the
 * np_wave_unit. With normals or fold a seventh stage N follows G (the
 * normal's products and the fold compare), so the latency is 7 there;
 * np_wave_stage_count() is the default configuration's 6.
 */
const np_stage_desc *np_wave_stage_table(void);
unsigned np_wave_stage_count(void);
unsigned np_wave_stage_count_of(const np_wave_cfg *c);
/* 1 when the configuration has the Jacobian (normals or fold). */
static inline unsigned np_wave_has_jac(const np_wave_cfg *c) { return c->normals || c->fold; }
/*
 * The bounds against the double reference from the same registers, in units
 * of 1 (not LSB): e[m] of the Jacobian term m (jxx, jxz, jzx, jzz, yx, yz),
 * m[m] its largest magnitude, nb[0..2] of nx, ny, nz (each with its rounding).
 */
typedef struct np_wave_jac_bound {
    double e[NP_WAVE_NJ], m[NP_WAVE_NJ], nb[3];
} np_wave_jac_bound;
np_wave_jac_bound np_wave_jac_error_bound(const np_wave_unit *u);
int np_wave_pipe_init(np_pipe *p, const np_wave_unit *u);

/*
 * The declaration's widths of the register-dependent signals (bits, from the
 * register set's bounds): ap u, yc, sa, xp, ys (Y), xs (X, Z), bc (0 without
 * cap), gm u (G); with normals or fold lj, ly, js and j (the terms), else 0.
 * `report gates --synth` builds np_wave.v at them (its W_* parameters).
 */
typedef struct np_wave_dp_widths {
    unsigned ap, yc, sa, xp, ys, xs, bc, gm, lj, ly, js, j;
} np_wave_dp_widths;
void np_wave_datapath_widths(const np_wave_unit *u, np_wave_dp_widths *w);
/* Datapath declaration (np_datapath.h) for the unit's lanes and registers. */
size_t np_wave_datapath(const np_wave_unit *u, np_op *ops, size_t max);
/* Widen the traces of the signals stage k produced (np_datapath.h). */
void np_wave_trace(const np_wave_unit *u, unsigned k, const np_wave_sig *s, np_trace *t, size_t n);

/*
 * A test register set drawn from seed (splitmix64): n trains with random
 * wave vectors, phases, frequencies and directions (c drawn independently of
 * k, 0.75 <= |c| <= 1; train 0's c = (1, 0)), amplitudes that fill the
 * output range to between 1/2 and 1 of its proven bound, airr =
 * floor(m (amp + airr) / 16), m in 0..3, so airr <= 3 (amp + airr) / 16
 * (airr <= 3 amp / 13), width 2^15 .. 2^16 - 1, mlog2 = 3, gcap = 21299.
 * Always accepted by np_wave_regs_check for a configuration with >= n lanes.
 * docs/wave.md gives the draws bit for bit; the vector files carry the set
 * as '# reg' header lines (np_unit.regs), which are its specification.
 */
void np_wave_regs_test(uint64_t seed, unsigned n, np_wave_regs *r);
/* The same set with kmx, kmz drawn after it (for normals or fold; docs/wave.md gives the draws). */
void np_wave_regs_test_jac(uint64_t seed, unsigned n, np_wave_regs *r);

/*
 * The rotation of sincos=recurrence (np_wave_lane_sincos above): (c, s) in
 * s32 Q1.30 rotated by the step (dc, ds), c' = round((c dc - s ds) / 2^30),
 * s' = round((s dc + c ds) / 2^30); set up from the ROM (times 2^13) when
 * (i + k) mod reset = 0. docs/wave.md gives the drift bound.
 */
typedef struct np_wave_recur {
    int64_t c, s;   /* s32 Q1.30 */
    int64_t dc, ds; /* cos, sin of the step, s32 Q1.30 */
} np_wave_recur;
/* Load the state (c0, s0), s32 Q1.30 (the lane sets up from the ROM values times 2^13), and the step's cos and sin (dc, ds), s32 Q1.30. */
void np_wave_recur_setup(np_wave_recur *q, int64_t c0, int64_t s0, int64_t dc, int64_t ds);
void np_wave_recur_step(np_wave_recur *q);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* NP_WAVE_H */
