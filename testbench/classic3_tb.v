// SPDX-License-Identifier: MIT
// classic3_tb - checks a device's results against golden vectors of the
// classic noise unit (np_classic.h): inputs x, y, z (u16 Q8.8), output f
// (sOUT_W Q2.(OUT_W-2), 8 bits by default). The checking is np_vec_check.v.
//
//   noisepipe vectors --unit classic3 --format readmemh > vectors.memh
//   (device results, one hex word per vector)           > results.hex
//   iverilog -g2012 -o classic3_tb.vvp testbench/classic3_tb.v testbench/np_vec_check.v
//   vvp -n classic3_tb.vvp +vectors=vectors.memh +results=results.hex
//
// For another output width (out_bits=N): iverilog -Pclassic3_tb.OUT_W=N ...
module classic3_tb #(
    parameter integer OUT_W = 8,
    parameter integer DEPTH = 1 << 21,
    parameter integer MAX_ERRORS = 20
);
    np_vec_check #(
        .UNIT("classic3"),
        .N_IN(3),
        .IN_W(16),
        .N_OUT(1),
        .OUT_W(OUT_W),
        .DEPTH(DEPTH),
        .MAX_ERRORS(MAX_ERRORS)
    ) check ();
endmodule
