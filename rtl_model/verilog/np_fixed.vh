// SPDX-License-Identifier: MIT
// np_fixed.vh - the named rounding and constant helpers of np_fixed.h for the
// noise units' RTL (np_simplex3.v; np_simplexn.v still holds its own copy of
// both functions and np_classicn.v of requant).
// Verilog-2005 functions: `include this file inside a module body, after the
// module's localparam XW (the width of requant's operand and result).
//
//   requant(val, from, to)  a signed XW-bit value with FROM fraction bits
//                           rescaled to TO: shift right rounding half up
//                           (np_shr_round_half_up, np_simplex_requant,
//                           np_simplexn_requant), or an exact shift left
//   csd_digits(k, neg)      the canonical signed digits (non-adjacent form)
//                           of the constant k: the positions of its +1 digits
//                           (neg = 0) or of its -1 digits (neg = 1); a constant
//                           multiply is one shifted operand per non-zero digit

function signed [XW-1:0] requant;
    input signed [XW-1:0] val;
    input integer from, to;
    reg signed [XW-1:0] one;
    begin
        one = 1;
        if (from > to) requant = (val + (one <<< (from - to - 1))) >>> (from - to);
        else requant = val <<< (to - from);
    end
endfunction
function [63:0] csd_digits;
    input [63:0] k;
    input integer negative;  // 0: the +1 digits; 1: the -1 digits
    reg [64:0] kk;
    integer i;
    begin
        kk = {1'b0, k};
        csd_digits = 64'd0;
        for (i = 0; i < 64; i = i + 1) begin
            if (kk[0]) begin
                csd_digits[i] = kk[1] ? negative != 0 : negative == 0;
                kk = kk[1] ? kk + 65'd1 : kk - 65'd1;
            end
            kk = kk >> 1;
        end
    end
endfunction
