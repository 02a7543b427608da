/* SPDX-License-Identifier: MIT */
/*
 * np_dpi.h - the bit-exact models and the cycle models of classic3 and
 * simplex3 as DPI-C functions, for a SystemVerilog scoreboard
 * (np_dpi_pkg.sv imports them). Plain C with C linkage; DPI "int" is C int,
 * "chandle" is void *. Outputs are the unit's output words masked to their
 * widths (two's complement bits, as the RTL ports carry them). A
 * configuration that np_*_cfg_check rejects gives -1 / NULL.
 */
#ifndef NP_DPI_H
#define NP_DPI_H

#ifdef __cplusplus
extern "C" {
#endif

/* classic3 bit-exact model: f of (x, y, z); -1 on a bad configuration. */
int np_dpi_classic3_eval(int out_bits, int s_frac, int lerp_frac, int x, int y, int z);

/* simplex3 bit-exact model: f and df/dx, df/dy, df/dz (0 when deriv = 0); returns 0, or -1. */
int np_dpi_simplex3_eval(int out_bits, int dout_bits, int deriv, int t_frac, int p_frac, int k_frac,
                         int x, int y, int z, int *f, int *dfdx, int *dfdy, int *dfdz);

/* Cycle models (np_pipe with the options in_reg, out_skid). NULL on a bad configuration. */
void *np_dpi_classic3_pipe_new(int out_bits, int s_frac, int lerp_frac, int in_reg, int out_skid);
void *np_dpi_simplex3_pipe_new(int out_bits, int dout_bits, int deriv, int t_frac, int p_frac,
                               int k_frac, int in_reg, int out_skid);
/*
 * One cycle's combinational evaluation: the inputs of the ports, then the
 * pipe's in_ready, out_valid and (when out_valid) its outputs (f; df unused
 * for classic3). Call np_dpi_pipe_clock for the edge after it.
 */
void np_dpi_pipe_eval(void *pipe, int in_valid, int x, int y, int z, int out_ready, int *in_ready,
                      int *out_valid, int *f, int *dfdx, int *dfdy, int *dfdz);
void np_dpi_pipe_clock(void *pipe);
void np_dpi_pipe_free(void *pipe);

#ifdef __cplusplus
}
#endif

#endif /* NP_DPI_H */
