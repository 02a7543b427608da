/* SPDX-License-Identifier: MIT */
/*
 * np_refn.h - float references of the n-D noise units (n = 2..5;
 * rtl_model/np_simplexn.h, np_classicn.h), in double, built like np_ref.h's
 * (no -ffast-math, -ffp-contract=off). For n = 3 each IS today's 3-D
 * reference (np_ref_simplex3, np_ref_classic3), called as it is.
 */
#ifndef NP_REFN_H
#define NP_REFN_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/*
 * Simplex noise f at the real point x[0..n) (|x_a| <= 2^20): the lattice of
 * np_simplexn_geom(n) (rational F = p/q, G = p/l), the ranking with
 * Appendix B's ties, kernel A max(0, r^2 - |d|^2)^4 (G . d) per corner, the
 * corners summed in order 0..n. The gradient is written out here from the
 * rules in np_hashn.h (independently of np_gradn_decode); the hash is
 * np_hashn of the corner mod 256.
 */
double np_ref_simplexn(unsigned n, const double *x);
double np_ref_simplexn_q88(unsigned n, const uint16_t *x);

/* Classic gradient noise on the hypercube lattice, tile 256, n levels of lerps (np_classicn.h). */
double np_ref_classicn(unsigned n, const double *x);
double np_ref_classicn_q88(unsigned n, const uint16_t *x);

/* The n-D gradient of index h at d[0..n), in double (np_hashn.h's rules, written out). */
double np_ref_gradn(unsigned n, unsigned h, const double *d);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* NP_REFN_H */
