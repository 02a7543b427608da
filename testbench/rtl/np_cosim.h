/* SPDX-License-Identifier: MIT */
/*
 * np_cosim.h - the C side of the RTL co-simulation (cosim_main.cpp): a unit's
 * cycle model (np_pipe) and the stimulus both sides get, from the project's
 * generator (np_rng): random inputs, and random input bubbles and output
 * stalls in phases of 16..271 cycles whose densities are each one of none,
 * 1/8, 1/2 and 7/8 (the traffic of `noisepipe verify`). A presented input
 * stays presented until it is accepted.
 *
 * A cycle: np_cosim_drive (stimulus), np_cosim_eval (the model's outputs),
 * then the caller compares with the RTL, then np_cosim_clock (the edge).
 * Plain C (compiled with the project's flags); the C++ harness includes it.
 */
#ifndef NP_COSIM_H
#define NP_COSIM_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Outputs of a cycle: 1 (classic3), 4 (simplex3), 3..7 (wave: y, dx, dz, [nx, ny, nz], [fold]),
 * 5 (aacount: s, mask, sd, sn, ss; a metric that is not built has its count 0 on both sides), or
 * a registry unit's output fields (np_cosim_open_spec). Inputs of a registry unit: up to NP_COSIM_INS. */
enum { NP_COSIM_OUTS = 7, NP_COSIM_WAVE_INS = 8, NP_COSIM_AAC_WORDS = 8, NP_COSIM_INS = 8 };

struct np_wave_regs;

typedef struct np_cosim_cycle {
    /* stimulus, from np_cosim_drive */
    int in_valid;
    uint16_t x, y, z;
    uint32_t win[NP_COSIM_WAVE_INS]; /* wave: i, j, t, ph, u, v, r, g (x, y, z unused) */
    uint64_t bus[NP_COSIM_AAC_WORDS]; /* aacount: the window bus, np_aacount_bus_pack's words (x, y, z unused) */
    uint64_t in[NP_COSIM_INS];        /* a registry unit: its input fields' words, in field order (x, y, z unused) */
    int out_ready;
    /* the cycle model's outputs, from np_cosim_eval (out: outputs' words masked to their widths) */
    int in_ready;
    int out_valid;
    uint32_t out[NP_COSIM_OUTS];
} np_cosim_cycle;

typedef struct np_cosim np_cosim;

/*
 * unit "classic3": p[0..2] = out_bits, s_frac, lerp_frac.
 * unit "simplex3": p[0..5] = out_bits, dout_bits, deriv, t_frac, p_frac, k_frac.
 * unit "wave": p[0..5] = trains, irr, cap, rom_log2, normals, fold; the
 * register set is the test set regs=1 (np_wave_regs_test, or _jac with
 * normals or fold: what `noisepipe vectors` uses), np_cosim_wave_regs gives it.
 * unit "aacount": p[0..9] = m, depth, normal, luma, luma_taps, c_d, c_n, c_s,
 * t_min, t_edge (the parallel variant, tile 0); the windows are random with
 * edges (np_cosim.c, random_window) and travel as the window bus.
 * in_reg, out_skid: the pipe options (np_pipe.h). Returns NULL with a message
 * in err (size errn) on a bad unit or configuration.
 */
np_cosim *np_cosim_open(const char *unit, const unsigned *p, unsigned np, int in_reg, int out_skid,
                        uint64_t seed, char *err, unsigned errn);
/*
 * Any unit of the registry (np_unit_find; also the unregistered n-D unit at
 * n = 3, simplexn3, unit_ndim.h) through its np_unit entries: pipe_init,
 * sig_set_in, sig_get_out and fields. spec gives every key of the unit once
 * ("key=value,...", np_unit_configure_all), so a run names the whole
 * configuration the RTL was built with. Inputs: each field a random word of
 * its width; a u16 Q8.8 field as random_word (np_cosim.c), and a tie of
 * two axes (an equal word, 1/8 of the inputs) or of all of them (1/64).
 * The n-D RTL (np_simplexn.v, np_classicn.v) co-simulates this way.
 */
np_cosim *np_cosim_open_spec(const char *unit, const char *spec, int in_reg, int out_skid, uint64_t seed, char *err,
                             unsigned errn);
/*
 * A stream unit of the registry (np_unit.stream: the span units texel and
 * fdiff) opens the same way: its stream model (np_span_sim) against the RTL,
 * inputs the descriptor's fields (np_unit_stream.n_desc: s t r ds dt dr n)
 * from its random_desc, 1 in 16 made empty (n = 0); outputs the pixel's
 * fields (cr cg cb); counts: descriptors accepted, pixels delivered. The spec
 * must name the texture (texture=NAME); np_cosim_tex_regs gives its
 * registers, the RTL's register inputs (NULL for another unit).
 */
struct np_tex_regs;
const struct np_tex_regs *np_cosim_tex_regs(const np_cosim *c);
/* A registry unit's configuration is spec (0, or -1: another one, or a bad spec; why in err). */
int np_cosim_spec_is(const np_cosim *c, const char *spec, char *err, unsigned errn);
/* Number of inputs of a registry unit and the width of input k (0 for another unit). */
unsigned np_cosim_inputs(const np_cosim *c);
unsigned np_cosim_in_bits(const np_cosim *c, unsigned k);
void np_cosim_close(np_cosim *c);
/* The wave unit's register set (NULL for another unit): the RTL's register inputs. */
const struct np_wave_regs *np_cosim_wave_regs(const np_cosim *c);
/* 1 when the unit is wave (its inputs are win[], not x, y, z). */
int np_cosim_is_wave(const np_cosim *c);
/* 1 when the unit is aacount (its input is bus[], not x, y, z); bits of its bus (0 for another unit). */
int np_cosim_is_aacount(const np_cosim *c);
unsigned np_cosim_aac_bus_bits(const np_cosim *c);
/* Number of outputs of the unit (1, 4, 3..7, 5, or a registry unit's) and the width of output k. */
unsigned np_cosim_outputs(const np_cosim *c);
unsigned np_cosim_out_bits(const np_cosim *c, unsigned k);
/* Stimulus of this cycle; traffic 0 streams without bubbles or stalls. */
void np_cosim_drive(np_cosim *c, np_cosim_cycle *cy, int traffic);
void np_cosim_eval(np_cosim *c, np_cosim_cycle *cy);
/* The edge: the model's clock and the stimulus's bookkeeping (np_cosim_accept). */
void np_cosim_clock(np_cosim *c, const np_cosim_cycle *cy);
/* The stimulus's bookkeeping alone (an input with in_valid && in_ready is
 * taken), for a run of the RTL without the model. */
void np_cosim_accept(np_cosim *c, const np_cosim_cycle *cy);
/* Counts so far: cycles, accepted inputs, delivered outputs, bubbles, stalls. */
void np_cosim_counts(const np_cosim *c, uint64_t counts[5]);

#ifdef __cplusplus
}
#endif

#endif /* NP_COSIM_H */
