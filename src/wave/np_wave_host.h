/* SPDX-License-Identifier: MIT */
/*
 * np_wave_host.h - the host side of the wave unit (seed 004): wind to wave
 * height (eq. (1)), dispersion (eqs. (4), (5)) through np_math, and the
 * quantisation of physical trains into the unit's registers (np_wave.h).
 * docs/wave.md names every PIN choice.
 */
#ifndef NP_WAVE_HOST_H
#define NP_WAVE_HOST_H

#include "np_wave.h"
#include "np_wave_ref.h"

#ifdef __cplusplus
extern "C" {
#endif

#define NP_WAVE_G 9.81        /* m/s^2 */
#define NP_WAVE_ALPHA 0.21    /* eq. (1), after Resio et al. */

/* Eq. (1): the fully developed wave height H = alpha h^2 / g (m) for wind speed h (m/s). */
double np_wave_height(double wind);
/* PIN: a train's amplitude A = H / 2. */
double np_wave_amp_of_wind(double wind);
/* Eq. (4) omega = sqrt(g k tanh(k D)) (rad/s); D = +inf (or >= 1e9) is eq. (5) sqrt(g k); D <= 0 (land): 0. */
double np_wave_omega(double k, double depth);
/* The wave number k (rad/m) with omega^2 = g k tanh(k D) at depth D > 0, by bisection to 1 ulp. */
double np_wave_k_of_omega(double omega, double depth);

/*
 * Quantise the physical trains of p into registers r (np_wave.h formats):
 * K = k spacing / 2 pi as s32 Q0.32, om = omega dt / 2 pi mod 1 as u32 Q0.32
 * (round to nearest: the phase error grows by at most 2^-33 turns a frame),
 * phi likewise, amp and airr to Q5.10, the direction to Q1.14. A train with
 * lambda <= 2 spacings (|K| >= 1/2 turn a step: above the grid's Nyquist
 * limit) is dropped. The box registers (width, margin, effects, gcap) are
 * left as they are in r. Returns the number of trains kept; *dropped gets the
 * number dropped.
 */
unsigned np_wave_quantise(const np_wave_phys *p, np_wave_regs *r, unsigned *dropped);

/*
 * sincos=recurrence's step registers from kx (np_wave.h): dc = round(2^30
 * cos(2 pi kx / 2^32)), ds = round(2^30 sin(...)), s32 Q1.30, from the
 * deterministic maths module (np_math), for every train k < r->n.
 */
void np_wave_steps(np_wave_regs *r);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* NP_WAVE_HOST_H */
