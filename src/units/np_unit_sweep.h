/* SPDX-License-Identifier: MIT */
/*
 * np_unit_sweep.h - what a unit's fast sweep kernel (np_unit.sweep_rows) is
 * written against: the kernel's contract belongs to the registry, so a unit
 * brings its kernel without depending on the sweep (src/sweep/np_sweep.h,
 * which includes this header, runs the kernels).
 */
#ifndef NP_UNIT_SWEEP_H
#define NP_UNIT_SWEEP_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/*
 * NP_SWEEP_CLONES on a hot loop of the sweep: GCC compiles it three times,
 * for x86-64 (SSE2), x86-64-v3 (AVX2) and x86-64-v4 (AVX-512), and picks
 * one when the program loads, by the CPU it runs on (an ifunc). The binary
 * stays portable. Integer results cannot differ between the clones; double
 * ones cannot either, because every clone is built with -ffp-contract=off
 * and without fast-math (no FMA, no reassociation) and the vector units
 * round each IEEE operation exactly as the scalar ones. The sweep's tests
 * compare every bit with the plain model and reference on the clone the
 * machine picks. -DNP_SWEEP_NO_CLONES builds the baseline only.
 * NP_SWEEP_INLINE: always inline (so that a caller's constants fold).
 */
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__linux__) && \
    !defined(NP_SWEEP_NO_CLONES)
#define NP_SWEEP_CLONES __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define NP_SWEEP_CLONES
#endif
#if defined(__GNUC__)
#define NP_SWEEP_INLINE static inline __attribute__((always_inline))
#else
#define NP_SWEEP_INLINE static inline
#endif

/* What np_unit.sweep_rows computes (bit mask). */
enum { NP_SWEEP_MODEL = 1u, NP_SWEEP_REF = 2u };

/* Inputs per row of np_unit.sweep_rows: one x cell (x0 + t, 0 <= t < 256) at one y. */
enum { NP_SWEEP_ROW = 256 };

/*
 * simplex3's kernel (src/units/sweep_simplex.c): np_unit.sweep_rows' contract
 * for np_simplex_cfg cfg (fields f and, with the derivative, df/dx, df/dy,
 * df/dz, field k at code/ref + k * rows * 256). The same bits as
 * np_simplex_eval and np_ref_simplex3_q88 per input.
 */
struct np_simplex_cfg;
void np_sweep_simplex3_rows(const struct np_simplex_cfg *cfg, uint16_t x0, uint16_t y0, uint16_t z,
                            unsigned rows, unsigned what, int32_t *code, double *ref);
/*
 * The reference row's selects: -1 by the CPU (AVX-512F: masked, else on bit
 * patterns; the default), 0 or 1 forced, process-wide (for the tests, which
 * check both forms on any CPU; not thread-safe against running sweeps).
 */
void np_sweep_simplex3_force_bits(int bits);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* NP_UNIT_SWEEP_H */
