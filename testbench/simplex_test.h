/* SPDX-License-Identifier: MIT */
/*
 * simplex_test.h - what the files of test_simplex share: the Appendix B
 * transcription, seeded inputs, error measurement against the reference,
 * the enumeration of local configurations, and the cases themselves
 * (registered by name in test_simplex.c).
 *
 *   simplex_common.c     the shared helpers below
 *   simplex_reference.c  float reference: Appendix B, derivative, face jumps
 *   simplex_model.c      bit-exact model: pinned outputs, accuracy, widths by configuration, registry
 *   simplex_pipeline.c   cycle-accurate model and the datapath declaration
 *   simplex_stiff.c      stability cases: faces, t = 0, extremes, magnitudes, wrap
 */
#ifndef SIMPLEX_TEST_H
#define SIMPLEX_TEST_H

#include <math.h>
#include <stdint.h>

#include "np_ref.h"
#include "np_rng.h"
#include "np_simplex.h"
#include "np_test.h"
#include "np_unit.h"

extern const np_unit np_unit_simplex3;

/* Appendix B's noise(x, y, z), transcribed (simplex_common.c says how). */
double J_noise(double x, double y, double z);
/* The derivative of the last J_noise() from the transcription's own terms (not in Appendix B). */
extern double J_dK[3];

static inline uint16_t rnd16(np_rng *r) { return (uint16_t)(np_rng_next(r) >> 48); }
static inline double rnd01(np_rng *r) { return (double)(np_rng_next(r) >> 11) * 0x1p-53; }
/* Three words in a fixed order (an initializer list's order of evaluation is unspecified). */
static inline void rnd3(np_rng *r, uint16_t in[3])
{
    for (unsigned a = 0; a < 3; a++)
        in[a] = rnd16(r);
}

static inline np_simplex_cfg default_cfg(void) { return np_simplex_cfg_default(16, 16, 1); }

/* 2^n as a double, exact. */
static inline double p2(unsigned n) { return ldexp(1.0, (int)n); }

/* Model and reference at one input, errors in output LSB (f, dfdx, dfdy, dfdz). */
typedef struct errs {
    double e[4];      /* |model - 2^F ref| */
    int cr[4];        /* model == floor(2^F ref + 1/2) */
    np_simplex_out o; /* the model's outputs */
    double ref[4];    /* the reference's values */
} errs;

void measure(const np_simplex_cfg *cfg, uint16_t x, uint16_t y, uint16_t z, errs *r);

/* Running maximum of errors over a set of inputs. */
typedef struct emax {
    double e[4];
    uint64_t n, cr[4];
    uint16_t at[4][3];
} emax;

void emax_add(emax *m, const errs *r, uint16_t x, uint16_t y, uint16_t z);
extern const char *const FIELD[4];
void emax_print(const char *what, const emax *m, int deriv);
/* Every field within 1 LSB (and within the argument's bound). */
void emax_check(const char *what, const emax *m, const np_simplex_cfg *cfg);

/*
 * Local configurations. Every input is, relative to its skewed cell,
 * one of 25,165,824 configurations (U, V, W) (offsets from corner 0 in units
 * of 1/1536): U = V = W = 4n (mod 6) with n = i + j + k, and the skewed
 * offsets U + (U+V+W)/3 etc. in [0, 1536). The enumeration below visits all
 * of them; input_of() maps one back to an 8.8 input in cell (i0, i0, i0+dn).
 */
typedef void (*config_fn)(void *ctx, int32_t u, int32_t v, int32_t w);
uint64_t for_each_config(config_fn fn, void *ctx);
/*
 * An 8.8 input whose local configuration is (U, V, W), in cell (i0, i0, i0 + dn);
 * 0 when no input in range has it (not the case for i0 in 30..200).
 */
int input_of(int32_t u, int32_t v, int32_t w, int32_t i0, uint16_t in[3]);
/* The front end of the model (primitives of stages SK and RK) on one input. */
void front_end(uint16_t x, uint16_t y, uint16_t z, uint32_t cell[3], int32_t off[3]);
/* Skewed fractional offsets and the smallest distance to a simplex or cell face, in skewed units. */
double face_distance(double x, double y, double z);

/* The cases (test_simplex.c registers them as simplex.<name>). */
int simplex_ref_vs_appendix_b(void);
int simplex_deriv_vs_central_diff(void);
int simplex_kat(void);
int simplex_random_1e7(void);
int simplex_cycle_vs_model_1e6(void);
int simplex_faces_uv(void);
int simplex_faces_vw(void);
int simplex_faces_uw(void);
int simplex_faces_uvw(void);
int simplex_kernel_t_zero(void);
int simplex_extremes_0_and_max(void);
int simplex_max_magnitude(void);
int simplex_reference_face_jump(void);
int simplex_wrap(void);
int simplex_div3_exhaustive(void);
int simplex_deriv_off_same_f(void);
int simplex_error_bound_configs(void);
int simplex_registry(void);
int simplex_datapath_widths(void);
int simplex_rtl_widths(void);

#endif /* SIMPLEX_TEST_H */
