/* SPDX-License-Identifier: MIT */
/*
 * The Gerstner wave unit (rtl_model/np_wave.h, docs/wave.md): its ROM, the
 * sin/cos error bound, the bit-exact model against the double reference over
 * long times and the frame counter's wrap, the named stiff cases (frequency
 * quantisation drift, folding, Nyquist drop, a > A, the output range,
 * shallow water, 65,536 recurrence steps) and the host's eq. (1) and
 * dispersion. Every case prints what it measured.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "np_math.h"
#include "np_rng.h"
#include "np_test.h"
#include "np_unit.h"
#include "np_wave.h"
#include "np_wave_host.h"
#include "np_wave_ref.h"
#include "np_wave_json.h"
#include "np_wave_scene.h"

static const double TWO_PI = 6.283185307179586;

/* Frames at 60 per second. */
#define F_HOUR 216000u
#define F_DAY 5184000u
#define F_30D 155520000u
#define F_YEAR 1892160000u

/* The ROM is round(2^17 sin(2 pi a / 4096)) from np_math, every word. */
static int rom(void)
{
    unsigned bad = 0;
    for (unsigned a = 0; a <= 1024; a++)
        if ((double)np_wave_rom(a) != np_ref_wave_rom_word(a)) {
            NP_CHECK(0, "ROM word %u: %u, np_math gives %.0f", a, np_wave_rom(a), np_ref_wave_rom_word(a));
            bad++;
        }
    NP_CHECK(np_wave_rom(0) == 0 && np_wave_rom(1024) == 131072u, "ends");
    /*
     * The read edge (docs/wave.md): 1/4 and 3/4 turn mirror to x' = 2^30, a = 2^L, f = 0: exactly
     * +-R[2^L] = +-2^17 (no R[2^L + 1]); 0 and 1/2 turn read R[0] = 0; one LSB either side of a
     * quarter mirror onto the same x' = 2^30 - 1, so both sides are equal, within 1 LSB of 2^17.
     */
    for (unsigned L = NP_WAVE_ROM_MIN; L <= NP_WAVE_ROM_MAX; L++) {
        const uint32_t q1 = UINT32_C(1) << 30, q3 = UINT32_C(3) << 30;
        NP_CHECK(np_wave_sin(0, L) == 0 && np_wave_sin(UINT32_C(1) << 31, L) == 0, "L=%u: sin 0, 1/2 turn", L);
        NP_CHECK(np_wave_sin(q1, L) == 131072 && np_wave_sin(q3, L) == -131072, "L=%u: sin 1/4 = %d, 3/4 = %d", L,
                 np_wave_sin(q1, L), np_wave_sin(q3, L));
        NP_CHECK(np_wave_sin(q1 - 1u, L) == np_wave_sin(q1 + 1u, L) && np_wave_sin(q3 - 1u, L) == np_wave_sin(q3 + 1u, L) &&
                     np_wave_sin(q1 + 1u, L) >= 131071 && np_wave_sin(q3 + 1u, L) <= -131071,
                 "L=%u: a quarter turn +-1 LSB: %d %d, %d %d", L, np_wave_sin(q1 - 1u, L), np_wave_sin(q1 + 1u, L),
                 np_wave_sin(q3 - 1u, L), np_wave_sin(q3 + 1u, L));
        NP_CHECK(np_wave_cos(0, L) == 131072 && np_wave_cos(UINT32_C(1) << 31, L) == -131072, "L=%u: cos 0, 1/2", L);
    }
    printf("1025 ROM words regenerated from np_math, %u differ; the read edge: sin(1/4 turn) = R[2^L] = 2^17, "
           "sin(3/4) = -2^17 for L = 6..10\n", bad);
    return 0;
}

/* |np_wave_sin - sin| and |np_wave_cos - cos| (in units of 1) at phase th. */
static double sin_err(uint32_t th, unsigned L)
{
    double t = ldexp((double)th, -32), s, c;
    np_sincos_turns(t, &s, &c);
    double es = fabs(ldexp((double)np_wave_sin(th, L), -17) - s);
    double ec = fabs(ldexp((double)np_wave_cos(th, L), -17) - c);
    return es > ec ? es : ec;
}

/*
 * The stated bound e_s (np_wave.h) holds at every ROM interval's midpoint
 * (the chord's worst) and ends, one phase LSB either side, every quadrant
 * edge, 2^22 random phases per ROM size, and a local search around the worst.
 */
static int sincos_bound(void)
{
    np_rng g;
    np_rng_seed(&g, 17);
    for (unsigned L = NP_WAVE_ROM_MIN; L <= NP_WAVE_ROM_MAX; L++) {
        double worst = 0.0, bound = np_wave_sin_bound(L);
        uint32_t at = 0;
        uint64_t pts = 0;
#define TRY(th)                                                                                                    \
    do {                                                                                                           \
        uint32_t th_ = (th);                                                                                       \
        double e_ = sin_err(th_, L);                                                                               \
        pts++;                                                                                                     \
        if (e_ > worst) {                                                                                          \
            worst = e_;                                                                                            \
            at = th_;                                                                                              \
        }                                                                                                          \
    } while (0)
        uint32_t step = UINT32_C(1) << (30 - L);
        for (uint32_t q = 0; q < 4; q++)
            for (uint32_t a = 0; a < (UINT32_C(1) << L); a++) {
                uint32_t base = (q << 30) + a * step;
                for (int d = -2; d <= 2; d++) {
                    TRY(base + (uint32_t)d);
                    TRY(base + step / 2u + (uint32_t)d);
                    TRY(base + step / 4u + (uint32_t)d);
                    TRY(base + 3u * step / 4u + (uint32_t)d);
                }
            }
        for (unsigned k = 0; k < (1u << 22); k++)
            TRY((uint32_t)np_rng_next(&g));
        uint32_t c = at;
        for (int d = -4096; d <= 4096; d++)
            TRY(c + (uint32_t)d);
#undef TRY
        printf("rom_log2=%u: max |error| %.4g (2^%.2f) at th=0x%08x over %llu phases; bound %.4g (2^%.2f)\n", L, worst,
               log2(worst), at, (unsigned long long)pts, bound, log2(bound));
        NP_CHECK(worst <= bound, "rom_log2=%u: %.6g over the bound %.6g", L, worst, bound);
        /* The bound is not loose by more than the ROM's share: the chord term is met. */
        NP_CHECK(worst > 0.5 * bound, "rom_log2=%u: %.6g, bound %.6g: bound looser than 2x", L, worst, bound);
    }
    /* The exact points: sin 0 = 0, sin 1/4 = 1, sin 1/2 = 0, sin 3/4 = -1. */
    NP_CHECK(np_wave_sin(0, 8) == 0 && np_wave_sin(1u << 30, 8) == 131072 && np_wave_sin(2u << 30, 8) == 0 &&
                 np_wave_sin(3u << 30, 8) == -131072,
             "quarter turns");
    return 0;
}

/* A unit with the test register set of seed s, n trains, both effects. */
static np_wave_unit unit_of(uint64_t s, unsigned n, unsigned irr, unsigned cap)
{
    np_wave_unit u;
    memset(&u, 0, sizeof u);
    u.c = np_wave_cfg_default();
    u.c.trains = n;
    u.c.irr = irr;
    u.c.cap = cap;
    np_wave_regs_test(s, n, &u.r);
    return u;
}

typedef struct err_stats {
    double max;
    uint64_t hist[9]; /* |error| in eighths of an LSB, the last bin >= 1 */
    uint64_t n;
} err_stats;

static void grid_errors(const np_wave_unit *u, unsigned size, uint32_t t, uint32_t ph, err_stats *e)
{
    for (unsigned j = 0; j < size; j++)
        for (unsigned i = 0; i < size; i++) {
            np_wave_in in = { (uint16_t)(i * 7u), (uint16_t)(j * 5u), t, ph + i * 977u, (uint16_t)i,
                              (uint16_t)(64u + j), (uint8_t)(i ^ j), 16384 };
            np_wave_out o;
            double r[3];
            np_wave_eval(u, &in, &o);
            np_ref_wave(u, &in, r);
            const int16_t got[3] = { o.y, o.dx, o.dz };
            for (unsigned k = 0; k < 3; k++) {
                double d = fabs((double)got[k] - r[k] * 1024.0);
                e->max = d > e->max ? d : e->max;
                unsigned b = (unsigned)(d * 8.0);
                e->hist[b > 8 ? 8 : b]++;
                e->n++;
            }
        }
}

static const uint32_t long_frames[] = { 0u, 1u, 60u, F_HOUR, F_DAY, F_30D, F_YEAR, 0x80000000u, 0xfffffffeu, 0xffffffffu };

/*
 * y, dx, dz within 1 LSB (and within the unit's own bound) of the double
 * reference from the same registers: 128^2 points at the frames of
 * long_frames (0 .. 2^32 - 1: 1 h, 1 day, 30 days, 1 year at 60 fps), four
 * register sets of 1 .. 4 trains. (`noisepipe wave check` runs 512^2 x N.)
 */
static int vs_ref(void)
{
    for (unsigned n = 1; n <= NP_WAVE_MAX_TRAINS; n++) {
        np_wave_unit u = unit_of(n, n, 1, 1);
        double bound = np_wave_error_bound_lsb(&u);
        err_stats all;
        memset(&all, 0, sizeof all);
        for (unsigned f = 0; f < sizeof long_frames / sizeof long_frames[0]; f++) {
            err_stats e;
            memset(&e, 0, sizeof e);
            grid_errors(&u, 128, long_frames[f], 0x9e3779b9u, &e);
            NP_CHECK(e.max <= 1.0 && e.max <= bound, "trains=%u t=%u: %.4f LSB (bound %.4f)", n, long_frames[f], e.max,
                     bound);
            all.max = e.max > all.max ? e.max : all.max;
            all.n += e.n;
        }
        printf("trains=%u: max |model - reference| %.4f LSB over %llu outputs at %zu frames up to 2^32 - 1; bound %.4f\n",
               n, all.max, (unsigned long long)all.n, sizeof long_frames / sizeof long_frames[0], bound);
    }
    return 0;
}

/*
 * Time enters only through the exact phase om t (mod 2^32): the frame at
 * t = 1 year is, bit for bit, the frame at t = 0 of the same unit with every
 * phase register advanced by -om t (and eq. (8)'s, (9)'s phases likewise),
 * so its error histogram is the t = 0 histogram of that unit; both are printed.
 */
static int hist_year(void)
{
    np_wave_unit u = unit_of(3, 2, 1, 1), v = u;
    const uint32_t T = F_YEAR;
    err_stats e0, e1;
    memset(&e0, 0, sizeof e0);
    memset(&e1, 0, sizeof e1);
    grid_errors(&u, 128, 0, 0, &e0);
    grid_errors(&u, 128, T, 0, &e1);
    for (unsigned k = 0; k < v.r.n; k++)
        v.r.tr[k].phi -= v.r.tr[k].om * T;
    unsigned diff = 0;
    for (unsigned j = 0; j < 128; j++)
        for (unsigned i = 0; i < 128; i++) {
            /* t = 0 on v needs eq. (8)'s and (9)'s phase at T: u = 0, r = 0 keep them out of the comparison. */
            np_wave_in a = { (uint16_t)i, (uint16_t)j, T, 0, 0, 100, 0, 16384 }, b = a;
            b.t = 0;
            np_wave_unit uu = u, vv = v;
            uu.c.irr = vv.c.irr = 0;
            uu.c.cap = vv.c.cap = 0;
            np_wave_out oa, ob;
            np_wave_eval(&uu, &a, &oa);
            np_wave_eval(&vv, &b, &ob);
            diff += oa.y != ob.y || oa.dx != ob.dx || oa.dz != ob.dz;
        }
    NP_CHECK(diff == 0, "%u points differ between t = 1 year and t = 0 with the phases advanced", diff);
    printf("|error| histogram in 1/8 LSB bins (last: >= 1 LSB), 128^2 points x 3 outputs:\n  t = 0:      ");
    for (unsigned b = 0; b < 9; b++)
        printf(" %6llu", (unsigned long long)e0.hist[b]);
    printf("  max %.4f\n  t = 1 year: ", e0.max);
    for (unsigned b = 0; b < 9; b++)
        printf(" %6llu", (unsigned long long)e1.hist[b]);
    printf("  max %.4f\nt = 1 year is t = 0 with the phases advanced: %u of 16384 points differ\n", e1.max, diff);
    NP_CHECK(e0.hist[8] == 0 && e1.hist[8] == 0, "an error of 1 LSB or more");
    return 0;
}

/*
 * Frequency quantisation drift: om = round(omega dt / 2 pi * 2^32) is off by
 * at most 1/2 LSB, so the phase against the physical one drifts by at most
 * t 2^-33 turns; printed at 1 h .. 2^32 - 1 frames beside float32's ulp of
 * omega t (lambda = 10 m), and the model's y against the physical reference.
 */
static int freq_drift(void)
{
    const double lambda = 10.0, k = TWO_PI / lambda, omega = np_wave_omega(k, 1e9), dt = 1.0 / 60.0;
    np_wave_phys p;
    memset(&p, 0, sizeof p);
    p.n = 1;
    p.spacing = 0.25;
    p.dt = dt;
    p.tr[0].kx = k;
    p.tr[0].omega = omega;
    p.tr[0].amp = 1.0;
    np_wave_unit u;
    memset(&u, 0, sizeof u);
    u.c = np_wave_cfg_default();
    u.c.trains = 1;
    u.c.irr = u.c.cap = 0;
    u.r.width = 1000;
    u.r.mlog2 = 3;
    u.r.gcap = NP_WAVE_GCAP_DEF;
    NP_CHECK(np_wave_quantise(&p, &u.r, NULL) == 1, "quantise");
    long double exact = (long double)omega * dt / (2.0L * 3.14159265358979323846264338327950288L) * 4294967296.0L;
    exact -= floorl(exact / 4294967296.0L) * 4294967296.0L;
    long double delta = (long double)u.r.tr[0].om - exact; /* LSB of 2^-32 turn a frame */
    NP_CHECK(fabsl(delta) <= 0.5L, "om off by %Lg LSB", delta);
    printf("lambda 10 m, omega %.6f rad/s, om = %u: off by %.4Lf LSB (2^-32 turn) a frame, bound 1/2\n", omega,
           u.r.tr[0].om, delta);
    static const uint32_t ts[] = { F_HOUR, F_DAY, F_30D, F_YEAR, 0xffffffffu };
    static const char *const names[] = { "1 h", "1 day", "30 days", "1 year", "2^32-1 frames" };
    for (unsigned q = 0; q < 5; q++) {
        double drift = (double)(fabsl(delta) * ts[q] / 4294967296.0L), lim = ldexp((double)ts[q], -33);
        float wt = (float)(omega * ts[q] * dt);
        double ulp32 = (double)(nextafterf(wt, INFINITY) - wt);
        /* The model against the physical reference (no effects, gain 1) at one point. */
        np_wave_in in = { 40, 0, ts[q], 0, 0, 500, 0, 16384 };
        np_wave_out o;
        double ph[3];
        np_wave_eval(&u, &in, &o);
        np_ref_wave_phys(&p, 40.0, 0.0, (double)ts[q], 0.0, ph);
        double dy = fabs((double)o.y / 1024.0 - ph[0]);
        /* |dy| <= A 2 pi (drift + K's rounding i 2^-33) + amplitude 2^-11 + the unit's own 1 LSB. */
        double lim_y = 1.0 * TWO_PI * (lim + 40.0 * ldexp(1.0, -33)) + ldexp(1.0, -11) + ldexp(1.0, -10);
        printf("  %-14s drift %.3g turns (bound %.3g); float32 omega t ulp %.3g rad; |y - physical| %.3g m (bound %.3g)\n",
               names[q], drift, lim, ulp32, dy, lim_y);
        NP_CHECK(drift <= lim, "%s: drift %.3g over %.3g", names[q], drift, lim);
        NP_CHECK(dy <= lim_y, "%s: |y - physical| %.3g over %.3g", names[q], dy, lim_y);
    }
    return 0;
}

/*
 * Folded fraction along x: the steps where x(i + 1) < x(i) - 1 LSB with
 * x = i spacing + dx (model outputs): beyond the two outputs' roundings, so
 * the surface has certainly turned back there.
 */
static double folded_fraction(const np_wave_unit *u, double spacing, unsigned total)
{
    unsigned folded = 0;
    double xprev = 0.0;
    for (unsigned i = 0; i <= total; i++) {
        np_wave_in in = { (uint16_t)i, 0, 0, 0, 0, 500, 0, 16384 };
        np_wave_out o;
        np_wave_eval(u, &in, &o);
        double x = i * spacing + (double)o.dx / 1024.0;
        if (i > 0 && x < xprev - 1.0 / 1024.0)
            folded++;
        xprev = x;
    }
    return (double)folded / total;
}

/* Three aligned trains (lambda, lambda/2, lambda/3, kA 0.4 each): where 1 - sum kA cos th < 0 in double. */
static double three_trains_theory(void)
{
    unsigned neg = 0, tot = 4096 * 8;
    for (unsigned i = 0; i < tot; i++) {
        double x = (double)i / 4096.0, j = 1.0; /* one period of the longest train */
        for (unsigned q = 0; q < 3; q++)
            j -= 0.4 * np_cos_turns((q + 1.0) * x + 1.234 * q / TWO_PI);
        neg += j < 0.0;
    }
    return (double)neg / tot;
}

static np_wave_unit fold_unit(const double *kA, unsigned n, double lambda, double spacing)
{
    np_wave_phys p;
    memset(&p, 0, sizeof p);
    p.n = n;
    p.spacing = spacing;
    p.dt = 1.0 / 60.0;
    for (unsigned q = 0; q < n; q++) {
        double lq = lambda / (double)(q + 1u), k = TWO_PI / lq;
        p.tr[q].kx = k;
        p.tr[q].amp = kA[q] / k;
        p.tr[q].phi = 1.234 * q;
    }
    np_wave_unit u;
    memset(&u, 0, sizeof u);
    u.c = np_wave_cfg_default();
    u.c.trains = n;
    u.c.irr = u.c.cap = 0;
    u.r.width = 1000;
    u.r.mlog2 = 3;
    u.r.gcap = 16384; /* gain 1 */
    np_wave_quantise(&p, &u.r, NULL);
    return u;
}

/*
 * Folding (no steepness factor: the surface folds when sum k A > 1): one
 * train with kA = 0.5, 0.99, 1.0, 1.01, 1.5 folds over arccos(1/kA)/pi of
 * its period (0 up to 1); measured from the model's dx along x, lambda =
 * 26.9 m (A from eq. (1) at 20 m/s), 64.79 grid steps a wavelength (430 LSB
 * a step: the 1 LSB threshold moves the fold's edge by 1/430 in the
 * Jacobian), 16,384 steps, so the steps sample the phase evenly. Three aligned
 * trains (lambda, lambda/2, lambda/3) with sum kA = 1.2 against the fraction
 * where 1 - sum k_i A_i cos th_i < 0 in double.
 */
static int fold(void)
{
    const double lambda = 26.9, spacing = lambda / 64.79;
    static const double kas[] = { 0.5, 0.99, 1.0, 1.01, 1.5 };
    for (unsigned q = 0; q < 5; q++) {
        np_wave_unit u = fold_unit(&kas[q], 1, lambda, spacing);
        double got = folded_fraction(&u, spacing, 16384);
        double want = kas[q] > 1.0 ? acos(1.0 / kas[q]) / (TWO_PI / 2.0) : 0.0;
        printf("kA = %.2f: folded %.4f of the period, arccos(1/kA)/pi = %.4f\n", kas[q], got, want);
        NP_CHECK(fabs(got - want) <= 0.01, "kA %.2f: %.4f against %.4f", kas[q], got, want);
    }
    const double three[3] = { 0.4, 0.4, 0.4 };
    np_wave_unit u = fold_unit(three, 3, lambda, spacing);
    double got = folded_fraction(&u, spacing, 16384), want = three_trains_theory();
    printf("three aligned trains, sum kA = 1.2: folded %.4f, 1 - sum kA cos < 0 over %.4f\n", got, want);
    NP_CHECK(fabs(got - want) <= 0.01 && want > 0.0, "three trains: %.4f against %.4f", got, want);
    return 0;
}

/* lambda <= 2 grid spacings is above the grid's Nyquist limit: the host drops the train. */
static int nyquist(void)
{
    const double spacing = 1.0;
    static const double lambdas[] = { 1.5, 2.0, 2.0000001, 2.01, 64.0 };
    static const unsigned keep[] = { 0, 0, 1, 1, 1 };
    for (unsigned q = 0; q < 5; q++) {
        np_wave_phys p;
        np_wave_regs r;
        memset(&p, 0, sizeof p);
        memset(&r, 0, sizeof r);
        p.n = 1;
        p.spacing = spacing;
        p.dt = 1.0 / 60.0;
        p.tr[0].kx = TWO_PI / lambdas[q] * 0.6;
        p.tr[0].kz = TWO_PI / lambdas[q] * 0.8;
        p.tr[0].amp = 0.1;
        unsigned dropped = 9, kept = np_wave_quantise(&p, &r, &dropped);
        printf("lambda = %.7g spacings: %s\n", lambdas[q], kept ? "kept" : "dropped");
        NP_CHECK(kept == keep[q] && dropped == 1u - keep[q], "lambda %.7g: kept %u", lambdas[q], kept);
    }
    return 0;
}

/* Eq. (8) requires a <= A: a register set with airr > amp is refused by name, airr = amp accepted. */
static int a_gt_A(void)
{
    np_wave_unit u = unit_of(5, 2, 1, 1);
    NP_CHECK(np_wave_regs_check(&u.c, &u.r) == NULL, "the test set is refused");
    u.r.tr[1].airr = u.r.tr[1].amp;
    NP_CHECK(np_wave_regs_check(&u.c, &u.r) == NULL, "a = A refused");
    u.r.tr[1].airr = (uint16_t)(u.r.tr[1].amp + 1u);
    const char *why = np_wave_regs_check(&u.c, &u.r);
    NP_CHECK(why && strstr(why, "a > A"), "a > A: %s", why ? why : "accepted");
    printf("a = A accepted; a = A + 1 LSB refused: %s\n", why ? why : "(accepted)");
    return 0;
}

/*
 * The output range: (gcap / 2^14) sum (A + a) + b <= 2^15 - 1 LSB is accepted
 * and reached without saturation (every train at cos = 1, w = -1, sc = 1, the
 * gain at its cap); one LSB more is refused.
 */
static int range(void)
{
    np_wave_unit u;
    memset(&u, 0, sizeof u);
    u.c = np_wave_cfg_default();
    u.c.trains = 2;
    u.r.n = 2;
    u.r.width = 1000;
    u.r.mlog2 = 3;
    u.r.gcap = 16384;
    u.r.b = 767;
    u.r.tr[0].amp = 12000;
    u.r.tr[0].airr = 4000;
    u.r.tr[1].amp = 12000;
    u.r.tr[1].airr = 4000;
    u.r.tr[0].cx = u.r.tr[1].cx = 16384;
    u.r.pu = 0;
    u.r.pt = 3u << 30; /* p1 = 3/4 turn at t = 1: s1 = -1 */
    u.r.pv = 1u << 24; /* p2 = v / 256 turn: 1/4 turn at v = 64: s2 = 1 */
    u.r.omc = 1u << 30;
    NP_CHECK(np_wave_range_lsb(&u.r, 1) == 32767, "range %lld", (long long)np_wave_range_lsb(&u.r, 1));
    NP_CHECK(np_wave_regs_check(&u.c, &u.r) == NULL, "32767 refused");
    np_wave_in in = { 0, 0, 1, 0, 0, 64, 1, 16384 }; /* th = 0 for both; pc = 1/4 turn: sc = 1 */
    np_wave_out o;
    np_wave_eval(&u, &in, &o);
    printf("bound 32767 LSB reached: y = %d\n", o.y);
    NP_CHECK(o.y == 32767, "y = %d", o.y);
    u.r.b = 768;
    const char *why = np_wave_regs_check(&u.c, &u.r);
    NP_CHECK(why && strstr(why, "output range"), "32768 accepted");
    printf("one LSB more: %s\n", why ? why : "(accepted)");
    return 0;
}

/*
 * Shallow water and land (eq. (4)): lambda = 50 m, omega / omega_deep = 0.35
 * at D = 1 m; omega = 0 on land (D <= 0); k_of_omega inverts eq. (4).
 */
static int shallow(void)
{
    double k = TWO_PI / 50.0, wd = np_wave_omega(k, 1e9), w1 = np_wave_omega(k, 1.0);
    printf("lambda 50 m: omega deep %.5f, at D = 1 m %.5f, ratio %.4f\n", wd, w1, w1 / wd);
    NP_CHECK(fabs(w1 / wd - 0.35) < 0.005, "ratio %.4f", w1 / wd);
    NP_CHECK(np_wave_omega(k, 0.0) == 0.0 && np_wave_omega(k, -3.0) == 0.0, "land");
    static const double depths[] = { 0.01, 0.5, 1.0, 5.0, 50.0, 1000.0 };
    for (unsigned q = 0; q < 6; q++) {
        double kd = np_wave_k_of_omega(wd, depths[q]), back = np_wave_omega(kd, depths[q]);
        printf("  D = %7.2f m: k(omega_deep) = %.6f rad/m (deep %.6f), omega(k) rel. error %.2g\n", depths[q], kd, k,
               fabs(back - wd) / wd);
        NP_CHECK(fabs(back - wd) <= 1e-12 * wd && kd >= k * (1.0 - 1e-12), "D %.2f", depths[q]);
    }
    return 0;
}

/* Eq. (1): H = 0.21 h^2 / g: 2.14 m at 10 m/s, 8.56 m at 20 m/s; the folding wavelength 2 pi A with A = H/2. */
static int wind(void)
{
    double h10 = np_wave_height(10.0), h20 = np_wave_height(20.0);
    double f10 = TWO_PI * np_wave_amp_of_wind(10.0), f20 = TWO_PI * np_wave_amp_of_wind(20.0);
    printf("H(10 m/s) = %.3f m, H(20 m/s) = %.3f m; lambda below which kA > 1: %.2f m, %.2f m\n", h10, h20, f10, f20);
    NP_CHECK(fabs(h10 - 2.14) < 0.005 && fabs(h20 - 8.56) < 0.005, "H");
    NP_CHECK(fabs(f10 - 6.7) < 0.05 && fabs(f20 - 26.9) < 0.05, "fold wavelength");
    return 0;
}

/*
 * The frame counter's wrap: across t = 2^32 - 1 -> 0 every output moves as
 * between any two frames (the phase is exact modulo 2^32): the frames
 * 2^32 - 3 .. 2 equal the frames 7 .. 12 of the unit with its phase registers
 * advanced by om (2^32 - 10), bit for bit, over a 64^2 grid.
 */
static int frame_wrap(void)
{
    np_wave_unit u = unit_of(9, 3, 0, 0), v = u;
    const uint32_t shift = 0xfffffff6u; /* frames t on u are frames t - shift on v */
    for (unsigned k = 0; k < v.r.n; k++)
        v.r.tr[k].phi -= v.r.tr[k].om * shift;
    unsigned diff = 0, n = 0;
    for (uint32_t t = 0xfffffffdu, f = 0; f < 6; f++, t++)
        for (unsigned j = 0; j < 64; j++)
            for (unsigned i = 0; i < 64; i++) {
                np_wave_in a = { (uint16_t)i, (uint16_t)j, t, 0, 0, 100, 0, 16384 }, b = a;
                b.t = t - shift;
                np_wave_out oa, ob;
                np_wave_eval(&u, &a, &oa);
                np_wave_eval(&v, &b, &ob);
                diff += oa.y != ob.y || oa.dx != ob.dx || oa.dz != ob.dz;
                n++;
            }
    printf("frames 2^32-3 .. 2 against 7 .. 12 with the phases advanced: %u of %u points differ\n", diff, n);
    NP_CHECK(diff == 0, "%u differ", diff);
    return 0;
}

/*
 * sincos=recurrence: (c, s) in Q1.30 rotated by a fixed step, 65,536 steps
 * from an exact set-up, against np_math at the exact phase. Each step adds
 * at most 2 roundings of 2^-31 and the step's own quantisation error
 * (|d - e^(i delta)| <= 2^-31 sqrt 2), so after N steps the error is at most
 * N 2^-30 sqrt 2 (+ the set-up's 2^-31 sqrt 2); a re-set-up every R steps
 * caps it at R 2^-30 sqrt 2.
 */
static int recurrence(void)
{
    const uint32_t th0 = 0x12345678u, dth = 0x00a3d70au; /* step about 1/400 turn */
    np_wave_recur q;
    double s, c, ds, dc;
    np_sincos_turns(ldexp((double)th0, -32), &s, &c);
    np_sincos_turns(ldexp((double)dth, -32), &ds, &dc);
    np_wave_recur_setup(&q, (int64_t)floor(c * 1073741824.0 + 0.5), (int64_t)floor(s * 1073741824.0 + 0.5),
                        (int64_t)floor(dc * 1073741824.0 + 0.5), (int64_t)floor(ds * 1073741824.0 + 0.5));
    double worst = 0.0, at1k = 0.0;
    const unsigned N = 65536;
    for (unsigned k = 1; k <= N; k++) {
        np_wave_recur_step(&q);
        np_sincos_turns(ldexp((double)(uint32_t)(th0 + dth * k), -32), &s, &c);
        double e = hypot(ldexp((double)q.c, -30) - c, ldexp((double)q.s, -30) - s);
        worst = e > worst ? e : worst;
        if (k == 1024)
            at1k = worst;
        double lim = (k + 1.0) * ldexp(1.0, -30) * sqrt(2.0);
        NP_CHECK(e <= lim, "step %u: %.3g over %.3g", k, e, lim);
        if (e > lim)
            break;
    }
    printf("recurrence: max |error| %.3g after 1,024 steps, %.3g after 65,536 (bound %.3g = 65,537 x 2^-30 sqrt 2);\n"
           "  the ROM's bound is %.3g: a re-set-up every %u steps keeps the recurrence within it\n",
           at1k, worst, (N + 1.0) * ldexp(1.0, -30) * sqrt(2.0), np_wave_sin_bound(8),
           (unsigned)(np_wave_sin_bound(8) / (ldexp(1.0, -30) * sqrt(2.0))) - 1u);
    return 0;
}

/*
 * 64 random transactions through u's pipe (seed g0; v_lo: the smallest ray,
 * so that the gain is not 0): the count of outputs that differ from
 * np_wave_eval_jac's (y, dx, dz and, with normals or fold, the Jacobian's),
 * the cycle of the first output and the folds seen.
 */
static unsigned pipe_run(const np_wave_unit *u, uint64_t g0, uint16_t v_lo, unsigned *first, unsigned *got,
                         unsigned *folds)
{
    np_pipe p;
    NP_CHECK(np_wave_pipe_init(&p, u) == 0, "init");
    np_wave_sig in;
    np_wave_out want[64];
    np_wave_jac wj[64];
    unsigned sent = 0, bad = 0;
    *got = *folds = 0;
    *first = ~0u;
    np_rng g;
    np_rng_seed(&g, g0);
    for (unsigned cyc = 0; *got < 64 && cyc < 200; cyc++) {
        np_pipe_port port;
        memset(&port, 0, sizeof port);
        memset(&in, 0, sizeof in);
        if (sent < 64) {
            uint64_t r = np_rng_next(&g);
            np_wave_in x = { (uint16_t)r, (uint16_t)(r >> 16), (uint32_t)(r >> 32), (uint32_t)r, (uint16_t)(r >> 8),
                             (uint16_t)(v_lo + (uint16_t)(r >> 40)), (uint8_t)(r >> 3), (uint16_t)((r >> 20) & 0x7fff) };
            in.in = x;
            np_wave_eval_jac(u, &x, &want[sent], &wj[sent]);
            port.in_valid = 1;
            port.in_sig = &in;
        }
        port.out_ready = 1;
        np_pipe_eval(&p, &port);
        if (port.out_valid) {
            const np_wave_sig *o = port.out_sig;
            bad += o->out.y != want[*got].y || o->out.dx != want[*got].dx || o->out.dz != want[*got].dz ||
                   (np_wave_has_jac(&u->c) && memcmp(&o->jac, &wj[*got], sizeof wj[*got]) != 0);
            *folds += o->jac.fold;
            if (*got == 0)
                *first = cyc;
            (*got)++;
        }
        if (port.in_valid && port.in_ready)
            sent++;
        np_pipe_clock(&p, &port);
    }
    np_pipe_free(&p);
    return bad;
}

/* The pipe delivers eval's outputs, one a clock after a latency of 6. */
static int pipe(void)
{
    np_wave_unit u = unit_of(4, 4, 1, 1);
    unsigned first, got, folds, bad = pipe_run(&u, 5, 0, &first, &got, &folds);
    NP_CHECK(first == 6, "first output at cycle %u", first);
    printf("pipe: 64 transactions, %u mismatches, latency %u\n", bad, np_wave_stage_count());
    NP_CHECK(bad == 0 && got == 64, "bad %u got %u", bad, got);
    return 0;
}

/* --- the host: boxes, rays, culling, the cycle model, the budget --- */

#ifndef NP_WAVE_SCENES
#define NP_WAVE_SCENES "vectors/scenes"
#endif

static int load_scene(const char *name, np_wave_scene *s, unsigned grid)
{
    char path[512], err[512] = "";
    unsigned dropped = 0;
    snprintf(path, sizeof path, "%s/%s", NP_WAVE_SCENES, name);
    if (np_wave_scene_read(path, s, NULL, err, sizeof err) != 0) {
        NP_CHECK(0, "%s", err);
        return -1;
    }
    if (grid)
        s->grid = grid;
    if (np_wave_scene_prepare(s, &dropped, err, sizeof err) != 0) {
        NP_CHECK(0, "%s", err);
        return -1;
    }
    return 0;
}

typedef struct claims {
    unsigned char *n;
    unsigned grid;
} claims;

static void claim(void *ctx, unsigned i, unsigned j, unsigned a, unsigned r)
{
    (void)a;
    (void)r;
    claims *c = ctx;
    c->n[j * c->grid + i]++;
}

/*
 * Every grid point in exactly one ray (PIN half-open cells: s in (a, a + 1],
 * w in [b, b + 1)): a small box at 3,600 angles (0.1 degree
 * apart) x 16 sub-grid offsets of its origin, and at 0, 45, 90 degrees and
 * 1e-6 rad: the walk claims each point of the box once and no other point
 * (the box 8 x 8 on a 20^2 grid).
 */
static int ray_partition(void)
{
    enum { G = 20 };
    unsigned char n[G * G];
    claims c = { n, G };
    unsigned long long configs = 0, points = 0, bad = 0;
    static const double named[] = { 0.0, 0.7853981633974483, 1.5707963267948966, 1e-6 };
    for (unsigned k = 0; k < 3600 + 4; k++) {
        double ang = k < 3600 ? (double)k * TWO_PI / 3600.0 : named[k - 3600];
        for (unsigned o = 0; o < 16; o++) {
            np_wave_box b;
            memset(&b, 0, sizeof b);
            b.angle = ang;
            np_wave_box_axes(&b);
            b.steps = b.rays = 8;
            /* The box's centre near the grid's centre, the origin at quarter offsets. */
            b.ox = 10.0 - 4.0 * (b.ux - b.uz) + (o % 4u) * 0.25;
            b.oz = 10.0 - 4.0 * (b.uz + b.ux) + (o / 4u) * 0.25;
            memset(n, 0, sizeof n);
            size_t got = np_wave_box_walk(&b, 1.0, G, claim, &c);
            size_t want = 0;
            for (unsigned j = 0; j < G; j++)
                for (unsigned i = 0; i < G; i++) {
                    unsigned a, r;
                    unsigned in = (unsigned)np_wave_cell_of(&b, 1.0, i, j, &a, &r);
                    want += in;
                    if (n[j * G + i] != in) {
                        bad++;
                        NP_CHECK(bad > 5, "angle %.9g offset %u: point (%u, %u) claimed %u times, in the box: %u", ang, o,
                                 i, j, n[j * G + i], in);
                    }
                }
            NP_CHECK(got == want && want >= 36 && want <= 100, "angle %.9g: %zu claimed, %zu in the box", ang, got, want);
            configs++;
            points += got;
        }
    }
    printf("%llu boxes (3,600 angles x 16 offsets, and 0, 45, 90 degrees, 1e-6 rad): %llu points, %llu claimed other "
           "than once\n",
           configs, points, bad);
    NP_CHECK(bad == 0, "%llu", bad);
    return 0;
}

/*
 * Culling: scenario 2's camera sees all seven boxes; turned away it sees none,
 * and the frame then costs the six plane tests a box, 42 cycles, O(k); a
 * culled box costs zero per-point cycles (the full frame less the box's own
 * set-up, rays and points) and its points are not computed. A box touching a
 * frustum plane is kept; 1e-6 m further out it is culled.
 */
static int culling(void)
{
    static np_wave_scene s;
    if (load_scene("wave_scenario2.json", &s, 128) != 0)
        return 0;
    np_wave_plan full, p;
    np_wave_plan_full(&s, &full);
    unsigned vis = 0;
    for (unsigned k = 0; k < s.nbox; k++)
        vis += (unsigned)full.visible[k];
    NP_CHECK(vis == 7, "%u of 7 visible", vis);
    uint64_t cf = np_wave_plan_cycles(&s, &full);
    size_t n2 = (size_t)s.grid * s.grid;
    int32_t *y = calloc(n2, 4), *dx = calloc(n2, 4), *dz = calloc(n2, 4);
    for (unsigned k = 0; k < s.nbox; k++) {
        p = full;
        p.visible[k] = 0;
        p.sel[k] = 0;
        uint64_t c = np_wave_plan_cycles(&s, &p);
        uint64_t own = NP_WAVE_CYC_BOX + NP_WAVE_CYC_TRAIN + (uint64_t)s.box[k].rays * NP_WAVE_CYC_RAY + s.box[k].npts +
                       np_wave_stage_count();
        NP_CHECK(cf - c == own, "box %u: culling saves %llu, its own cost is %llu", k, (unsigned long long)(cf - c),
                 (unsigned long long)own);
        np_wave_frame(&s, &p, 77, y, dx, dz);
        unsigned nonzero = 0;
        for (size_t q = 0; q < s.box[k].npts; q++) {
            size_t at = (size_t)s.box[k].pts[q].j * s.grid + s.box[k].pts[q].i;
            int covered = 0; /* a point another visible box also covers may move */
            for (unsigned o = 0; o < s.nbox; o++)
                for (size_t r = 0; o != k && !covered && r < s.box[o].npts; r++)
                    covered = s.box[o].pts[r].i == s.box[k].pts[q].i && s.box[o].pts[r].j == s.box[k].pts[q].j;
            nonzero += !covered && y[at] != 0;
        }
        NP_CHECK(nonzero == 0, "box %u culled: %u of its points moved", k, nonzero);
    }
    /* Turned away: the camera looks up and back. */
    s.cam.target[0] = s.cam.eye[0];
    s.cam.target[1] = s.cam.eye[1] + 100.0;
    s.cam.target[2] = s.cam.eye[2] - 100.0;
    np_wave_plan_full(&s, &p);
    vis = 0;
    for (unsigned k = 0; k < s.nbox; k++)
        vis += (unsigned)p.visible[k];
    uint64_t cn = np_wave_plan_cycles(&s, &p);
    printf("scenario 2 at 128^2: 7 boxes visible, %llu cycles; camera turned away: %u visible, %llu cycles (7 x %d)\n",
           (unsigned long long)cf, vis, (unsigned long long)cn, NP_WAVE_CYC_CULL);
    NP_CHECK(vis == 0 && cn == 7u * NP_WAVE_CYC_CULL, "turned away: %u visible, %llu cycles", vis, (unsigned long long)cn);
    /* Tangent: looking straight down from 100 m with a 90 degree field of view: the plane x = 100 at y = 0. */
    s.cam.eye[0] = 0.0;
    s.cam.eye[1] = 100.0;
    s.cam.eye[2] = 0.0;
    s.cam.target[0] = s.cam.target[1] = s.cam.target[2] = 0.0;
    s.cam.up[0] = 0.0;
    s.cam.up[1] = 0.0;
    s.cam.up[2] = 1.0;
    s.cam.fov_y = TWO_PI / 4.0;
    s.cam.aspect = 1.0;
    np_wave_box b;
    memset(&b, 0, sizeof b);
    b.angle = 0.0;
    np_wave_box_axes(&b);
    b.length = b.width = 100.0;
    b.oz = -50.0;
    b.ox = 100.0 - 1e-6;
    int in = np_wave_box_visible(&s, &b);
    b.ox = 100.0 + 1e-6;
    int out = np_wave_box_visible(&s, &b);
    printf("a box 1e-6 m inside the frustum's plane: %s; 1e-6 m outside: %s\n", in ? "kept" : "culled",
           out ? "kept" : "culled");
    NP_CHECK(in && !out, "tangent: %d %d", in, out);
    /* The box grows sideways by the horizontal displacement: 0.5 m of it keeps a box 0.4 m outside. */
    b.ox = 100.4;
    b.grow = 0.5;
    NP_CHECK(np_wave_box_visible(&s, &b), "grown box culled");
    free(y);
    free(dx);
    free(dz);
    np_wave_scene_free(&s);
    return 0;
}

/*
 * Cycles for 64^2 to 512^2 (scenario 1: two boxes of one and two trains, one
 * lane: a train a pass) linear in points x trains within +-10 %; the bit-exact
 * frame's heights are the unit's (every box point checked at 64^2 against eval).
 */
static int scaling(void)
{
    static np_wave_scene s;
    double lo = 1e30, hi = 0.0;
    for (unsigned g = 64; g <= 512; g *= 2) {
        if (load_scene("wave_scenario1.json", &s, g) != 0)
            return 0;
        np_wave_plan p;
        np_wave_plan_full(&s, &p);
        uint64_t pt = 0;
        for (unsigned k = 0; k < s.nbox; k++)
            pt += (uint64_t)s.box[k].npts * s.box[k].unit.r.n;
        double r = (double)np_wave_plan_cycles(&s, &p) / (double)pt;
        printf("%u^2: %llu points x trains, %llu cycles: %.4f a point and train\n", g, (unsigned long long)pt,
               (unsigned long long)np_wave_plan_cycles(&s, &p), r);
        lo = r < lo ? r : lo;
        hi = r > hi ? r : hi;
        np_wave_scene_free(&s);
    }
    NP_CHECK(hi <= lo * 1.1, "cycles per point and train from %.4f to %.4f", lo, hi);
    return 0;
}

/*
 * The time budget: for budgets from the culling's floor (7 x 6 cycles) to the
 * full frame, the scheduled frame's cycles never exceed the budget, and the
 * RMS height error against the full field never grows as the budget grows
 * (0 at the full budget).
 */
static int budget(void)
{
    static np_wave_scene s;
    if (load_scene("wave_scenario2.json", &s, 128) != 0)
        return 0;
    s.effects |= NP_WAVE_FX_NOISE;
    np_wave_plan full;
    np_wave_plan_full(&s, &full);
    uint64_t fc = np_wave_plan_cycles(&s, &full), floor_c = (uint64_t)NP_WAVE_CYC_CULL * s.nbox;
    size_t n2 = (size_t)s.grid * s.grid;
    int32_t *y = calloc(n2, 4), *yf = calloc(n2, 4), *dx = calloc(n2, 4), *dz = calloc(n2, 4);
    np_wave_frame(&s, &full, 300, yf, dx, dz);
    double prev = 1e30;
    unsigned over = 0, rises = 0;
    for (unsigned q = 0; q <= 64; q++) {
        uint64_t b = floor_c + (fc - floor_c) * q / 64u;
        np_wave_plan p;
        np_wave_plan_budget(&s, b, &p);
        uint64_t c = np_wave_frame(&s, &p, 300, y, dx, dz);
        double e = 0.0;
        for (size_t k = 0; k < n2; k++)
            e += (double)(y[k] - yf[k]) * (double)(y[k] - yf[k]);
        e = sqrt(e / (double)n2) / 1024.0;
        over += c > b;
        rises += e > prev;
        if (q % 16 == 0)
            printf("budget %6llu cycles: %6llu used, RMS height error %.4f m\n", (unsigned long long)b,
                   (unsigned long long)c, e);
        prev = e;
        if (q == 64)
            NP_CHECK(e == 0.0, "full budget: RMS %.4g", e);
        if (q == 0)
            NP_CHECK(e > 0.0, "the floor leaves nothing out");
    }
    NP_CHECK(over == 0 && rises == 0, "%u budgets exceeded, %u rises of the error", over, rises);
    free(y);
    free(yf);
    free(dx);
    free(dz);
    np_wave_scene_free(&s);
    return 0;
}

/*
 * Overlapping boxes: scenario 1's two boxes overlap almost everywhere; the
 * frame with both is, point for point, the sum of the frames of each alone,
 * and each OBB holds both boxes' heights.
 */
static int overlap(void)
{
    static np_wave_scene s;
    if (load_scene("wave_scenario1.json", &s, 96) != 0)
        return 0;
    size_t n2 = (size_t)s.grid * s.grid;
    int32_t *y = calloc(n2, 4), *dx = calloc(n2, 4), *dz = calloc(n2, 4), *ya = calloc(n2, 4), *yb = calloc(n2, 4);
    np_wave_plan p, a, b;
    np_wave_plan_full(&s, &p);
    a = p;
    b = p;
    a.sel[1] = 0;
    b.sel[0] = 0;
    np_wave_frame(&s, &p, 1234, y, dx, dz);
    np_wave_frame(&s, &a, 1234, ya, dx, dz);
    np_wave_frame(&s, &b, 1234, yb, dx, dz);
    unsigned diff = 0;
    for (size_t q = 0; q < n2; q++)
        diff += y[q] != ya[q] + yb[q];
    double h0 = (double)np_wave_range_lsb(&s.box[0].unit.r, 0) / 1024.0, h1 = (double)np_wave_range_lsb(&s.box[1].unit.r, 0) / 1024.0;
    printf("two overlapping boxes: %u of %zu points differ from the sum of each alone; OBB heights %.3f and %.3f m "
           "(own %.3f + %.3f)\n",
           diff, n2, s.box[0].hmax, s.box[1].hmax, h0, h1);
    NP_CHECK(diff == 0, "%u", diff);
    NP_CHECK(fabs(s.box[0].hmax - (h0 + h1)) < 1e-12 && fabs(s.box[1].hmax - (h0 + h1)) < 1e-12, "OBB heights");
    free(y);
    free(dx);
    free(dz);
    free(ya);
    free(yb);
    np_wave_scene_free(&s);
    return 0;
}

/*
 * Shallow water and land: over land (depth <= 0) a ray's gain is 0 and no box
 * moves the point; behind the island it recovers linearly over 16 grid units
 * (PIN: the first cell after the last land action point has 1/16 of its
 * Green's law gain); in shallow water it rises (Green's law) up to the 1.3 cap.
 */
static int land(void)
{
    static np_wave_scene s;
    if (load_scene("wave_scenario1.json", &s, 256) != 0)
        return 0;
    size_t n2 = (size_t)s.grid * s.grid;
    int32_t *y = calloc(n2, 4), *dx = calloc(n2, 4), *dz = calloc(n2, 4);
    np_wave_plan p;
    np_wave_plan_full(&s, &p);
    np_wave_frame(&s, &p, 99, y, dx, dz);
    unsigned land_pts = 0, moved = 0;
    for (size_t q = 0; q < n2; q++)
        if (s.depth[q] <= 0.0f) {
            land_pts++;
            moved += y[q] != 0 || dx[q] != 0 || dz[q] != 0;
        }
    /* Along box 0's rays (along +x): the gains after the last land cell. */
    unsigned ramps = 0, bad_ramp = 0, gmax = 0;
    const np_wave_box *b = &s.box[0];
    for (size_t q = 1; q < b->npts; q++) {
        gmax = b->pts[q].g > gmax ? b->pts[q].g : gmax;
        const np_wave_pt *pp = &b->pts[q - 1];
        /* A water point of gain 0 is in a cell whose action point is on land; the next cell starts the recovery. */
        if (pp->b == b->pts[q].b && pp->g == 0 && s.depth[(size_t)pp->j * s.grid + pp->i] > 0.0f && b->pts[q].g > 0 &&
            b->pts[q].a == pp->a + 1u) {
            ramps++;
            /* The first water cell after land: 1/16 of its Green's law gain, at most 1.3/16. */
            bad_ramp += b->pts[q].g > (uint16_t)(1.3 * 16384.0 / 16.0 + 1.0);
        }
    }
    printf("%u land points, %u moved by a box; %u rays leave the island, %u of them not at 1/16 gain; largest gain %.3f\n",
           land_pts, moved, ramps, bad_ramp, gmax / 16384.0);
    NP_CHECK(land_pts > 1000 && moved == 0, "%u of %u land points moved", moved, land_pts);
    NP_CHECK(ramps >= 5 && bad_ramp == 0, "ramps %u bad %u", ramps, bad_ramp);
    NP_CHECK(gmax > 16384 && gmax <= NP_WAVE_GCAP_DEF, "largest gain %u", gmax);
    free(y);
    free(dx);
    free(dz);
    np_wave_scene_free(&s);
    return 0;
}

/* A scene whose surface may fold (1.3 sum k (A + a) > 1) is refused unless it sets allow_fold; bad fields are named. */
static int scene_refusals(void)
{
    static np_wave_scene s;
    char path[512], err[512] = "";
    unsigned d = 0;
    snprintf(path, sizeof path, "%s/wave_fold.json", NP_WAVE_SCENES);
    NP_CHECK(np_wave_scene_read(path, &s, NULL, err, sizeof err) == 0, "%s", err);
    NP_CHECK(s.allow_fold == 0, "the file allows folding");
    int rc = np_wave_scene_prepare(&s, &d, err, sizeof err);
    printf("wave_fold.json: %s\n", rc ? err : "accepted");
    NP_CHECK(rc != 0 && strstr(err, "folds") && strstr(err, "allow_fold"), "refusal: %s", err);
    np_wave_scene_free(&s);
    NP_CHECK(np_wave_scene_read(path, &s, NULL, err, sizeof err) == 0, "%s", err);
    s.allow_fold = 1;
    NP_CHECK(np_wave_scene_prepare(&s, &d, err, sizeof err) == 0, "with allow_fold: %s", err);
    np_wave_scene_free(&s);
    /* Bad fields, named by path. */
    static const char *const bad[][2] = {
        { "{\"waves\": {\"boxes\": [{\"origin\": [0, 0], \"length\": 10, \"width\": 10, \"trains\": [{\"lambda\": 5, \"amp\": 0.1}]}], \"gird\": 64}}", "waves.gird" },
        { "{\"waves\": {\"boxes\": [{\"origin\": [0, 0], \"length\": 10, \"width\": 10, \"trains\": [{\"lambda\": -5}]}]}}", "waves.boxes[0].trains[0].lambda" },
        { "{\"waves\": {\"boxes\": [{\"origin\": [0, 0], \"length\": 10, \"width\": 10, \"trains\": []}]}}", "waves.boxes[0].trains" },
        { "{\"waves\": {\"boxes\": [{\"origin\": [0, 0], \"length\": 10, \"width\": 10, \"trains\": [{\"lambda\": 5, \"amp\": 40}]}]}}", "waves.boxes[0].trains[0].amp" },
    };
    for (unsigned k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        snprintf(path, sizeof path, "wave_bad_%u.json", k);
        FILE *f = fopen(path, "w");
        NP_CHECK(f != NULL, "%s", path);
        if (!f)
            continue;
        fputs(bad[k][0], f);
        fclose(f);
        err[0] = '\0';
        NP_CHECK(np_wave_scene_read(path, &s, NULL, err, sizeof err) != 0, "%s accepted", bad[k][0]);
        NP_CHECK(strstr(err, bad[k][1]) != NULL, "message '%s' does not name %s", err, bad[k][1]);
        printf("  %s\n", err);
        remove(path);
    }
    return 0;
}

/*
 * The checked-in level-1 set's '# reg' header lines are the register set:
 * read as an RTL testbench would (names, hex of the declared width, signed
 * fields sign-extended), they equal np_wave_regs_test(1, 2) register for
 * register, and the model loaded from them alone gives every vector's
 * expected outputs.
 */
static int vector_regs(void)
{
    const char *path = NP_WAVE_VECTORS "/wave-l1-seed1.vec";
    FILE *f = fopen(path, "r");
    NP_CHECK(f != NULL, "cannot open %s", path);
    if (!f)
        return 0;
    np_wave_unit u;
    memset(&u, 0, sizeof u);
    u.c = np_wave_cfg_default();
    char line[512];
    unsigned n_regs = 0, n_vec = 0, bad = 0, cfg_seen = 0;
    while (fgets(line, sizeof line, f)) {
        char name[32], fmt1[16];
        unsigned long long v;
        if (strncmp(line, "# config ", 9) == 0) {
            cfg_seen = 1;
            NP_CHECK(strcmp(line, "# config trains=2 irr=1 cap=1 rom_log2=8 regs=1\n") == 0, "config: %s", line);
            continue;
        }
        if (sscanf(line, "# reg %31s %llx %15s", name, &v, fmt1) == 3) {
            /* The format's sign and width: sN sign-extends. */
            unsigned bits = (unsigned)atoi(fmt1 + 1);
            int64_t x = (int64_t)v;
            if (fmt1[0] == 's' && bits < 64 && (v >> (bits - 1u)) & 1u)
                x -= (int64_t)1 << bits;
            unsigned k = 0;
            const char *fld = name;
            if (name[0] == 't' && name[1] == 'r' && name[3] == '.') {
                k = (unsigned)(name[2] - '0');
                fld = name + 4;
            }
            np_wave_train *t = &u.r.tr[k < NP_WAVE_MAX_TRAINS ? k : 0];
            if (!strcmp(fld, "kx")) t->kx = (int32_t)x;
            else if (!strcmp(fld, "kz")) t->kz = (int32_t)x;
            else if (!strcmp(fld, "phi")) t->phi = (uint32_t)x;
            else if (!strcmp(fld, "om")) t->om = (uint32_t)x;
            else if (!strcmp(fld, "amp")) t->amp = (uint16_t)x;
            else if (!strcmp(fld, "airr")) t->airr = (uint16_t)x;
            else if (!strcmp(fld, "cx")) t->cx = (int16_t)x;
            else if (!strcmp(fld, "cz")) t->cz = (int16_t)x;
            else if (!strcmp(name, "n")) u.r.n = (unsigned)x;
            else if (!strcmp(name, "width")) u.r.width = (uint16_t)x;
            else if (!strcmp(name, "mlog2")) u.r.mlog2 = (unsigned)x;
            else if (!strcmp(name, "pu")) u.r.pu = (uint32_t)x;
            else if (!strcmp(name, "pv")) u.r.pv = (uint32_t)x;
            else if (!strcmp(name, "pt")) u.r.pt = (uint32_t)x;
            else if (!strcmp(name, "omc")) u.r.omc = (uint32_t)x;
            else if (!strcmp(name, "b")) u.r.b = (uint16_t)x;
            else if (!strcmp(name, "gcap")) u.r.gcap = (uint16_t)x;
            else
                NP_CHECK(0, "unknown register %s", name);
            n_regs++;
            continue;
        }
        if (line[0] == '#')
            continue;
        unsigned i, j, uu, vv, r, g, y, dx, dz;
        unsigned long t, ph;
        if (sscanf(line, "%x %x %lx %lx %x %x %x %x %x %x %x", &i, &j, &t, &ph, &uu, &vv, &r, &g, &y, &dx, &dz) != 11) {
            NP_CHECK(0, "bad vector line %s", line);
            continue;
        }
        np_wave_in in = { (uint16_t)i, (uint16_t)j, (uint32_t)t, (uint32_t)ph, (uint16_t)uu, (uint16_t)vv, (uint8_t)r,
                          (uint16_t)g };
        np_wave_out o;
        np_wave_eval(&u, &in, &o);
        if ((uint16_t)o.y != y || (uint16_t)o.dx != dx || (uint16_t)o.dz != dz)
            bad++;
        n_vec++;
    }
    fclose(f);
    np_wave_regs w;
    np_wave_regs_test(1, 2, &w);
    NP_CHECK(cfg_seen && n_regs == 1u + 8u * 2u + 8u, "%u register lines, expected 25", n_regs);
    NP_CHECK(u.r.n == w.n && u.r.width == w.width && u.r.mlog2 == w.mlog2 && u.r.pu == w.pu && u.r.pv == w.pv &&
                 u.r.pt == w.pt && u.r.omc == w.omc && u.r.b == w.b && u.r.gcap == w.gcap,
             "the box's registers differ from np_wave_regs_test(1, 2)");
    for (unsigned k = 0; k < 2; k++) {
        const np_wave_train *a = &u.r.tr[k], *b = &w.tr[k];
        NP_CHECK(a->kx == b->kx && a->kz == b->kz && a->phi == b->phi && a->om == b->om && a->amp == b->amp &&
                     a->airr == b->airr && a->cx == b->cx && a->cz == b->cz,
                 "train %u's registers differ from np_wave_regs_test(1, 2)", k);
    }
    NP_CHECK(np_wave_regs_check(&u.c, &u.r) == NULL, "the header's registers are refused");
    NP_CHECK(n_vec == 2514 && bad == 0, "%u of %u vectors differ from the model loaded from the header", bad, n_vec);
    printf("%s: %u registers from the header = np_wave_regs_test(1, 2); the model on them gives %u of %u vectors' "
           "outputs\n", path, n_regs, n_vec - bad, n_vec);
    return 0;
}

/* --- normals and the fold flag (keys normals, fold) --- */

/* A unit with the test register set of seed s for normals and fold (kmx, kmz drawn). */
static np_wave_unit unit_jac(uint64_t s, unsigned n, unsigned irr, unsigned cap)
{
    np_wave_unit u = unit_of(s, n, irr, cap);
    u.c.normals = u.c.fold = 1;
    np_wave_regs_test_jac(s, n, &u.r);
    return u;
}

/*
 * The Jacobian terms, the normal and the fold flag against the double
 * reference from the same registers (np_ref_wave_jac): 96^2 points at frames
 * 0, 1 h, 1 year and 2^32 - 1 for 1 .. 4 trains with both effects: every term
 * within its bound e[m] (internal signals: printed in LSB of s18 Q3.14), every
 * normal component within nb (below 1 LSB of s20 Q9.10), and the fold flag equal to the
 * reference's ny <= 0 wherever the reference's |ny| exceeds ny's bound (the
 * points inside that band are counted, not excused silently).
 */
static int jac_vs_ref(void)
{
    static const uint32_t frames[] = { 0u, F_HOUR, F_YEAR, 0xffffffffu };
    for (unsigned n = 1; n <= 4; n++) {
        np_wave_unit u = unit_jac(10u + n, n, 1, 1);
        NP_CHECK(np_wave_regs_check(&u.c, &u.r) == NULL, "test set %u refused: %s", n,
                 np_wave_regs_check(&u.c, &u.r));
        np_wave_jac_bound b = np_wave_jac_error_bound(&u);
        double ej = 0.0, en = 0.0, bj = 0.0, bn = 0.0;
        unsigned long folds = 0, band = 0, wrong = 0, pts = 0;
        for (unsigned m = 0; m < NP_WAVE_NJ; m++)
            bj = fmax(bj, b.e[m] * 16384.0);
        for (unsigned m = 0; m < 3; m++)
            bn = fmax(bn, b.nb[m] * 1024.0);
        for (unsigned f = 0; f < 4; f++)
            for (unsigned j = 0; j < 96; j++)
                for (unsigned i = 0; i < 96; i++) {
                    np_wave_in in = { (uint16_t)(i * 3u), (uint16_t)(j * 5u), frames[f], i * 7919u, (uint16_t)i,
                                      (uint16_t)(8u + j), (uint8_t)(i + j), (uint16_t)(16384u + 64u * (i & 127u)) };
                    np_wave_out o;
                    np_wave_jac q;
                    double rj[6], rn[3];
                    np_wave_eval_jac(&u, &in, &o, &q);
                    np_ref_wave_jac(&u, &in, rj, rn);
                    for (unsigned m = 0; m < NP_WAVE_NJ; m++) {
                        double d = fabs((double)q.j[m] / 16384.0 - rj[m]);
                        ej = fmax(ej, d * 16384.0);
                        NP_CHECK(d <= b.e[m], "n %u term %u: %.3g over its bound %.3g", n, m, d, b.e[m]);
                    }
                    const int32_t nv[3] = { q.nx, q.ny, q.nz };
                    for (unsigned m = 0; m < 3; m++) {
                        double d = fabs((double)nv[m] / 1024.0 - rn[m]);
                        en = fmax(en, d * 1024.0);
                        NP_CHECK(d <= b.nb[m], "n %u normal %u: %.3g over its bound %.3g", n, m, d, b.nb[m]);
                    }
                    int want = rn[1] <= 0.0;
                    folds += q.fold;
                    if (fabs(rn[1]) <= b.nb[1])
                        band++;
                    else
                        wrong += (unsigned)want != q.fold;
                    pts++;
                }
        printf("trains %u: terms max %.4f LSB (bound %.4f), normal max %.4f LSB (bound %.4f); fold on %lu of %lu "
               "points, %lu disagree with the reference, %lu within ny's bound of 0\n",
               n, ej, bj, en, bn, folds, pts, wrong, band);
        NP_CHECK(bn < 1.0, "the normal's bound %.4f not below 1 LSB", bn);
        NP_CHECK(wrong == 0, "%lu fold flags disagree", wrong);
        NP_CHECK(folds > 0 && folds < pts, "the test set should fold at some points and not at others (%lu)", folds);
    }
    return 0;
}

/* The fold flag's fraction along x (16,384 steps sample the phase evenly; docs/wave.md). */
static double fold_flag_fraction(const np_wave_unit *u, unsigned total)
{
    unsigned folded = 0;
    for (unsigned i = 0; i < total; i++) {
        np_wave_in in = { (uint16_t)i, 0, 0, 0, 0, 500, 0, 16384 };
        np_wave_out o;
        np_wave_jac q;
        np_wave_eval_jac(u, &in, &o, &q);
        folded += q.fold;
    }
    return (double)folded / total;
}

/*
 * The fold flag on the named folding cases of wave.fold (the host's
 * registers, kmx from k in rad/m): one train, kA = 0.5, 0.99: never; 1.0:
 * within 1 % (theory 0); 1.01, 1.5: arccos(1/kA)/pi within +-1 %; three
 * aligned trains with sum kA = 1.2 against 1 - sum kA cos < 0 in double.
 */
static int fold_flag(void)
{
    const double lambda = 26.9, spacing = lambda / 64.79;
    static const double kas[] = { 0.5, 0.99, 1.0, 1.01, 1.5 };
    for (unsigned q = 0; q < 5; q++) {
        np_wave_unit u = fold_unit(&kas[q], 1, lambda, spacing);
        u.c.fold = 1;
        NP_CHECK(np_wave_regs_check(&u.c, &u.r) == NULL, "kA %.2f refused: %s", kas[q], np_wave_regs_check(&u.c, &u.r));
        double got = fold_flag_fraction(&u, 16384), dx = folded_fraction(&u, spacing, 16384);
        double want = kas[q] > 1.0 ? acos(1.0 / kas[q]) / (TWO_PI / 2.0) : 0.0;
        printf("kA = %.2f (registers: A kmx = %.5f): fold flag on %.4f of the period, from dx %.4f, arccos(1/kA)/pi = "
               "%.4f\n", kas[q], u.r.tr[0].amp / 1024.0 * u.r.tr[0].kmx / 4096.0, got, dx, want);
        NP_CHECK(fabs(got - want) <= 0.01, "kA %.2f: %.4f against %.4f", kas[q], got, want);
        if (kas[q] < 1.0)
            NP_CHECK(got == 0.0, "kA %.2f folds at %.4f", kas[q], got);
    }
    const double three[3] = { 0.4, 0.4, 0.4 };
    np_wave_unit u = fold_unit(three, 3, lambda, spacing);
    u.c.fold = 1;
    double got = fold_flag_fraction(&u, 16384), want = three_trains_theory();
    printf("three aligned trains, sum kA = 1.2: fold flag on %.4f, 1 - sum kA cos < 0 over %.4f\n", got, want);
    NP_CHECK(fabs(got - want) <= 0.01 && got > 0.0, "three trains: %.4f against %.4f", got, want);
    return 0;
}

/* With normals and fold the pipe has a seventh stage: eval_jac's outputs, first at cycle 7, one a clock. */
static int jac_pipe(void)
{
    np_wave_unit u = unit_jac(4, 4, 1, 1);
    unsigned first, got, folds, bad = pipe_run(&u, 6, 64, &first, &got, &folds);
    NP_CHECK(first == 7, "first output at cycle %u", first);
    printf("pipe with normals and fold: 64 transactions, %u mismatches, latency %u (%u folded)\n", bad,
           np_wave_stage_count_of(&u.c), folds);
    NP_CHECK(bad == 0 && got == 64 && np_wave_stage_count_of(&u.c) == 7 && np_wave_stage_count() == 6, "bad %u got %u",
             bad, got);
    return 0;
}

/*
 * The test register sets for normals and fold are accepted (seeds 0 .. 499,
 * 1 .. 4 trains, every effect setting) and leave the other registers as the
 * default set's; a set whose Jacobian reaches 8 or whose normal's bound
 * reaches 1 LSB is refused by name.
 */
static int jac_regs(void)
{
    unsigned ok = 0, total = 0;
    double worst = 0.0;
    for (unsigned s = 0; s < 500; s++)
        for (unsigned n = 1; n <= 4; n++)
            for (unsigned fx = 0; fx < 4; fx++) {
                np_wave_unit u = unit_jac(s, n, fx & 1u, fx >> 1);
                np_wave_regs r0;
                np_wave_regs_test(s, n, &r0);
                for (unsigned k = 0; k < n; k++)
                    r0.tr[k].kmx = u.r.tr[k].kmx, r0.tr[k].kmz = u.r.tr[k].kmz;
                const char *why = np_wave_regs_check(&u.c, &u.r);
                NP_CHECK(why == NULL, "seed %u trains %u fx %u: %s", s, n, fx, why);
                NP_CHECK(memcmp(&r0, &u.r, sizeof r0) == 0, "seed %u: the other registers differ", s);
                np_wave_jac_bound b = np_wave_jac_error_bound(&u);
                for (unsigned m = 0; m < 3; m++)
                    worst = fmax(worst, b.nb[m] * 1024.0);
                ok += why == NULL;
                total++;
            }
    printf("%u of %u test register sets for normals and fold accepted; largest normal bound %.4f LSB\n", ok, total,
           worst);
    np_wave_unit u = unit_jac(1, 1, 0, 0);
    u.r.tr[0].kmx = INT16_MAX; /* A k far over 8 */
    const char *why = np_wave_regs_check(&u.c, &u.r);
    printf("kmx = 0x7fff: %s\n", why ? why : "(accepted)");
    NP_CHECK(why && strstr(why, "Jacobian range"), "a Jacobian over 8 accepted");
    u = unit_jac(1, 1, 0, 0);
    /* One train along the diagonal, G A |k| = 4 at the cap: every term in range (2), the normal's bound over 1 LSB. */
    u.r.tr[0].cx = u.r.tr[0].cz = 11585;
    double km = 4.0 / (u.r.gcap / 16384.0 * u.r.tr[0].amp / 1024.0 * sqrt(2.0));
    u.r.tr[0].kmx = u.r.tr[0].kmz = (int16_t)(km * 4096.0);
    np_wave_jac_bound jb = np_wave_jac_error_bound(&u);
    printf("one train along the diagonal, G A |k| = 4: jxx up to %.3f, ny's bound %.4f LSB\n", jb.m[0],
           jb.nb[1] * 1024.0);
    why = np_wave_regs_check(&u.c, &u.r);
    printf("  %s\n", why ? why : "(accepted)");
    NP_CHECK(why && strstr(why, "normal"), "a normal bound over 1 LSB accepted");
    u.c.normals = u.c.fold = 0;
    NP_CHECK(np_wave_regs_check(&u.c, &u.r) == NULL, "kmx is read only with normals or fold");
    return 0;
}

/* --- sincos=recurrence (keys sincos, reset) --- */

/* The wave unit as the registry configures it from spec (its block starts with the np_wave_unit); NULL if refused. */
static const np_wave_unit *registry_unit(const char *spec, np_unit_cfg *cfg, char *err, size_t len)
{
    const np_unit *w = np_unit_find("wave");
    if (!w || np_unit_configure(w, cfg, spec, err, len) != 0)
        return NULL;
    return (const np_wave_unit *)(const void *)cfg;
}

/* The ROM's set-up and the stateful walk of lane k along i from i0 (what lane_rec's value must equal). */
static void walk_setup(const np_wave_unit *u, unsigned k, const np_wave_in *in, np_wave_recur *q)
{
    const np_wave_train *t = &u->r.tr[k];
    uint32_t th = (uint32_t)t->kx * in->i + (uint32_t)t->kz * in->j + t->phi + in->ph - t->om * in->t;
    np_wave_recur_setup(q, (int64_t)np_wave_cos(th, u->c.rom_log2) * 8192, (int64_t)np_wave_sin(th, u->c.rom_log2) * 8192,
                        t->dc, t->ds);
}

static int32_t q17(int64_t v)
{
    int64_t r = (v + 4096) >> 13; /* round half up, Q1.30 to Q1.17 */
    return (int32_t)(r > 131072 ? 131072 : r < -131072 ? -131072 : r);
}

/*
 * The recurrence as the unit computes it, per transaction, equals a lane
 * that walks the row: at reset = 64 for every point of a 4,096-point row and
 * both lanes (the lanes re-set up in turn, (i + k) mod N = 0). Its drift over
 * 65,536 steps (reset = 65,536, one set-up a row) against the exact sin and
 * cos of the exact phase stays within np_wave_recur_bound(m) = sqrt(2) e_s +
 * m 2^-29 + 2^-18 at every step m (the per-transaction model checked at 40
 * points of that walk). With the registry's test set the outputs stay within
 * 1 LSB of the reference up to the largest reset the check accepts.
 */
static int recur_unit(void)
{
    np_unit_cfg cfg;
    char err[256] = "";
    const np_wave_unit *ru = registry_unit("sincos=recurrence", &cfg, err, sizeof err);
    NP_CHECK(ru != NULL, "sincos=recurrence refused: %s", err);
    if (!ru)
        return 0;
    np_wave_unit u = *ru;
    unsigned bad = 0;
    for (unsigned k = 0; k < 2; k++) {
        np_wave_recur q;
        for (unsigned i = 0; i < 4096; i++) {
            np_wave_in in = { (uint16_t)i, 77, 4321, 0x9e3779b9u, 0, 100, 0, 16384 };
            if ((i + k) % 64 == 0 || i == 0) {
                if (i == 0) { /* the walk's first set-up is m = (0 + k) mod 64 steps before i = 0: start there */
                    np_wave_in b = in;
                    b.ph = in.ph - (uint32_t)u.r.tr[k].kx * (k % 64u);
                    walk_setup(&u, k, &b, &q);
                    for (unsigned m = 0; m < k % 64u; m++)
                        np_wave_recur_step(&q);
                } else {
                    walk_setup(&u, k, &in, &q);
                }
            } else {
                np_wave_recur_step(&q);
            }
            int32_t c, s;
            np_wave_lane_sincos(&u, k, &in, &c, &s);
            bad += c != q17(q.c) || s != q17(q.s);
        }
    }
    printf("reset 64: %u of 8,192 lane values differ from a lane walking the row\n", bad);
    NP_CHECK(bad == 0, "%u differ", bad);

    /* 65,536 steps: one set-up at i = 0, lane 0. */
    u.c.reset = NP_WAVE_RESET_MAX;
    np_wave_recur q;
    np_wave_in in = { 0, 5, 1234, 0, 0, 100, 0, 16384 };
    walk_setup(&u, 0, &in, &q);
    double worst = 0.0, at1k = 0.0, ratio = 0.0;
    unsigned diff = 0;
    for (unsigned i = 0; i < 65536; i++) {
        if (i)
            np_wave_recur_step(&q);
        in.i = (uint16_t)i;
        int32_t c = q17(q.c), s = q17(q.s);
        if (i % 1681u == 0 || i == 65535) { /* the per-transaction model at 40 points of the walk */
            int32_t c2, s2;
            np_wave_lane_sincos(&u, 0, &in, &c2, &s2);
            diff += c2 != c || s2 != s;
        }
        const np_wave_train *t = &u.r.tr[0];
        uint32_t th = (uint32_t)t->kx * in.i + (uint32_t)t->kz * in.j + t->phi + in.ph - t->om * in.t;
        double es, ec;
        np_sincos_turns(ldexp((double)th, -32), &es, &ec);
        double e = fmax(fabs(c / 131072.0 - ec), fabs(s / 131072.0 - es)), lim = np_wave_recur_bound(8, i);
        worst = fmax(worst, e);
        ratio = fmax(ratio, e / lim);
        if (i == 1024)
            at1k = worst;
        NP_CHECK(e <= lim, "step %u: %.3g over its bound %.3g", i, e, lim);
        if (e > lim)
            break;
    }
    printf("reset 65,536: max |error| %.3g by step 1,024 (bound %.3g), %.3g by step 65,535 (bound %.3g); largest "
           "error / bound %.3f; the unit's per-transaction values differ from the walk at %u of 40 points\n",
           at1k, np_wave_recur_bound(8, 1024), worst, np_wave_recur_bound(8, 65535), ratio, diff);
    NP_CHECK(diff == 0, "per transaction and walk differ at %u points", diff);

    /* The largest reset the check accepts for the test set (regs=1, 2 trains), and the outputs there. */
    unsigned lo = 64, hi = NP_WAVE_RESET_MAX + 1u;
    while (hi - lo > 1) {
        unsigned mid = (lo + hi) / 2;
        char spec[64];
        snprintf(spec, sizeof spec, "sincos=recurrence,reset=%u", mid);
        if (registry_unit(spec, &cfg, err, sizeof err))
            lo = mid;
        else
            hi = mid;
    }
    printf("the check accepts reset up to %u for the test set (%s for %u)\n", lo, err, hi);
    NP_CHECK(hi <= NP_WAVE_RESET_MAX && strstr(err, "recurrence"), "reset 65536 accepted, or refused for another reason");
    static const unsigned resets[] = { 64, 0 };
    for (unsigned r = 0; r < 2; r++) {
        char spec[64];
        snprintf(spec, sizeof spec, "sincos=recurrence,reset=%u", resets[r] ? resets[r] : lo);
        const np_wave_unit *vu = registry_unit(spec, &cfg, err, sizeof err);
        NP_CHECK(vu != NULL, "%s: %s", spec, err);
        if (!vu)
            continue;
        err_stats e;
        memset(&e, 0, sizeof e);
        grid_errors(vu, 128, 0, 0, &e);
        grid_errors(vu, 128, F_YEAR, 0, &e);
        double bound = np_wave_error_bound_lsb(vu);
        printf("%s: max |model - reference| %.4f LSB over %llu outputs (bound %.6f)\n", spec, e.max,
               (unsigned long long)e.n, bound);
        NP_CHECK(e.max <= bound && bound < 1.0, "%s: %.4f against %.4f", spec, e.max, bound);
    }
    return 0;
}

static const np_test_case cases[] = {
    { "rom", rom },
    { "sincos_bound", sincos_bound },
    { "vs_ref", vs_ref },
    { "hist_year", hist_year },
    { "freq_drift", freq_drift },
    { "fold", fold },
    { "nyquist", nyquist },
    { "a_gt_A", a_gt_A },
    { "range", range },
    { "shallow", shallow },
    { "wind", wind },
    { "frame_wrap", frame_wrap },
    { "recurrence", recurrence },
    { "pipe", pipe },
    { "ray_partition", ray_partition },
    { "culling", culling },
    { "scaling", scaling },
    { "budget", budget },
    { "overlap", overlap },
    { "land", land },
    { "scene_refusals", scene_refusals },
    { "vector_regs", vector_regs },
    { "jac_vs_ref", jac_vs_ref },
    { "fold_flag", fold_flag },
    { "jac_pipe", jac_pipe },
    { "jac_regs", jac_regs },
    { "recur_unit", recur_unit },
    { NULL, NULL },
};
NP_TEST_MAIN(cases)
