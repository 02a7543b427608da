/* SPDX-License-Identifier: MIT */
/*
 * np_ref.h - float (double precision) references of the hardware units.
 *
 * Each reference is the same mathematical function as its unit, computed in
 * double from the exact input value, with no fixed-point anywhere. The
 * library is built with -ffp-contract=off and without -ffast-math, so every
 * result is identical across compilers and machines (IEEE-754 binary64,
 * round to nearest even, each operation rounded once).
 */
#ifndef NP_REF_H
#define NP_REF_H

#include <stdint.h>

/*
 * Classic 3-D gradient noise (Perlin, "Noise Hardware"): lattice tile of
 * 256, the table-free hash np_hash6, the Appendix B gradient written out in
 * double (independently of np_grad_decode), the s-curve 3t^2 - 2t^3 and seven
 * linear interpolations a + s (b - a). Any real input; |result| <= 1.5.
 */
double np_ref_classic3(double x, double y, double z);

/* The same at a u16 Q8.8 input: x/256, y/256, z/256. */
double np_ref_classic3_q88(uint16_t x, uint16_t y, uint16_t z);

/*
 * The same within one cell: h[c] the corner hashes (corner c = 4cz + 2cy + cx)
 * and (u, v, w) in [0, 1) the position in the cell. np_ref_classic3 is this
 * function after the lattice step; sweeps call it directly to hoist the hash.
 */
double np_ref_classic3_in_cell(const uint8_t h[8], double u, double v, double w);

/* Appendix B's gradient of 6-bit index h at (x, y, z), in double. */
double np_ref_grad(unsigned h, double x, double y, double z);

#endif /* NP_REF_H */
