// SPDX-License-Identifier: MIT
// hatch_lane - one seed lane of np_hatch.v (np_hatch_seed) as np_hatch.v
// feeds it, for synthesising a lane alone (docs/hatch.md, "Synthesis"): the
// whole unit is millions of gates, one lane is one G P-th of its S row.
// The inputs are narrowed to the live bits the unit's banks carry, so that
// Yosys sees what it sees inside np_hatch.v (where the bank's constant bits
// are propagated): al = clamp(4 A - l 2^30, 0, 2^30) has its two low bits 0;
// ku = pm inv_len and kv = pm inv_wid hold KU_BITS and KV_BITS bits
// (np_hatch_k_bits per axis: the bits of 0x1FFFF times the constant).
// Parameters: np_hatch_seed's, which np_hatch.v computes for (layer, seed)
// (testbench/synth/hatch_lane.ys names the lanes synthesised), and the widths.
module hatch_lane #(
    parameter [31:0] ST_U = 32'd0,
    parameter [31:0] ST_V = 32'd0,
    parameter [0:0] W0_U = 1'b0,
    parameter [0:0] W0_V = 1'b0,
    parameter [15:0] RC = 16'd16384,
    parameter [15:0] RS = 16'd0,
    parameter integer FADE = 0,
    parameter integer N = 16,
    parameter integer I = 0,
    parameter integer F = 17,
    parameter integer KU_BITS = 33,
    parameter integer KV_BITS = 33
) (
    input wire [32:0] xu,
    input wire [32:0] xv,
    input wire [28:0] al_hi,
    input wire [16:0] oms,
    input wire [KU_BITS-1:0] ku,
    input wire [KV_BITS-1:0] kv,
    input wire [F:0] c_in,
    output wire [F:0] c_out
);
    wire [30:0] alpha;
    np_hatch_seed #(.ST_U(ST_U), .ST_V(ST_V), .W0_U(W0_U), .W0_V(W0_V), .RC(RC), .RS(RS), .FADE(FADE), .N(N),
                    .I(I), .F(F)) u_seed (
        .xu(xu), .xv(xv), .al({al_hi, 2'b00}), .oms(oms),
        .ku({{(33 - KU_BITS){1'b0}}, ku}), .kv({{(33 - KV_BITS){1'b0}}, kv}),
        .c_in(c_in), .c_out(c_out), .alpha(alpha));
endmodule
