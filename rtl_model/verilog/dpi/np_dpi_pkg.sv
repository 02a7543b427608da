// SPDX-License-Identifier: MIT
// np_dpi_pkg - noisepipe's bit-exact models and cycle models of classic3 and
// simplex3 for SystemVerilog testbenches, through DPI-C (np_dpi.h, np_dpi.c;
// link np_dpi.c and the rtl_model library, libnoisepipe_rtl.a). Typical use:
// a scoreboard that computes each accepted input's expected output with
// np_dpi_classic3_eval and compares it with the DUT's (dpi_classic3_tb.sv).
// Output words are masked to the unit's widths; -1 / null for a configuration
// the model rejects.
package np_dpi_pkg;
    import "DPI-C" function int np_dpi_classic3_eval(
        input int out_bits, input int s_frac, input int lerp_frac, input int x, input int y, input int z);
    import "DPI-C" function int np_dpi_simplex3_eval(
        input int out_bits, input int dout_bits, input int deriv, input int t_frac, input int p_frac,
        input int k_frac, input int x, input int y, input int z,
        output int f, output int dfdx, output int dfdy, output int dfdz);
    import "DPI-C" function chandle np_dpi_classic3_pipe_new(
        input int out_bits, input int s_frac, input int lerp_frac, input int in_reg, input int out_skid);
    import "DPI-C" function chandle np_dpi_simplex3_pipe_new(
        input int out_bits, input int dout_bits, input int deriv, input int t_frac, input int p_frac,
        input int k_frac, input int in_reg, input int out_skid);
    import "DPI-C" function void np_dpi_pipe_eval(
        input chandle pipe, input int in_valid, input int x, input int y, input int z, input int out_ready,
        output int in_ready, output int out_valid, output int f, output int dfdx, output int dfdy,
        output int dfdz);
    import "DPI-C" function void np_dpi_pipe_clock(input chandle pipe);
    import "DPI-C" function void np_dpi_pipe_free(input chandle pipe);
endpackage
