/* SPDX-License-Identifier: MIT */
/*
 * np_wave_ref.h - the wave unit's float references (ref_wave.c) and its
 * physical parameters (the host's, src/wave/, before quantisation).
 */
#ifndef NP_WAVE_REF_H
#define NP_WAVE_REF_H

#include "np_wave.h"

#ifdef __cplusplus
extern "C" {
#endif

/* One Gerstner train in physical units. */
typedef struct np_wave_phys_train {
    double kx, kz;  /* wave vector, rad/m */
    double omega;   /* rad/s */
    double phi;     /* rad */
    double amp;     /* A, m */
    double airr;    /* eq. (8)'s a, m */
} np_wave_phys_train;

typedef struct np_wave_phys {
    unsigned n;
    np_wave_phys_train tr[NP_WAVE_MAX_TRAINS];
    double spacing; /* grid spacing, m */
    double dt;      /* seconds per frame */
} np_wave_phys;

/* The ROM word a (0..1024) as np_math gives it: round(2^17 sin(2 pi a / 4096)). */
double np_ref_wave_rom_word(unsigned a);

/* y, dx, dz in metres, in double from the registers of u (the model's contract). */
void np_ref_wave(const np_wave_unit *u, const np_wave_in *in, double out[3]);

/*
 * Eqs. (6), (7) from physical parameters: y, dx, dz (m) at grid point
 * (i, j), frame number frame, plus a phase shift ph_turns; no gain, no
 * effects (the Gerstner sum alone).
 */
/*
 * The Jacobian terms jxx, jxz, jzx, jzz, yx, yz (np_wave.h, normals or fold)
 * and the normal (nx, ny, nz) = dP/dz0 x dP/dx0 in double from the same
 * registers (ny = det J: the surface folds where ny <= 0).
 */
void np_ref_wave_jac(const np_wave_unit *u, const np_wave_in *in, double j[6], double n[3]);

void np_ref_wave_phys(const np_wave_phys *p, double i, double j, double frame, double ph_turns, double out[3]);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* NP_WAVE_REF_H */
