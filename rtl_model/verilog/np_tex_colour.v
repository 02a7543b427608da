// SPDX-License-Identifier: MIT
// np_tex_colour - the colour map of np_texture.h as the three banks C1 C2 C3
// that every span texturing unit ends with (np_texel.v, np_fdiff.v; the
// declarations' stages C1..C3): C1 split (np_tex_colour_split), C2 mix
// (np_tex_colour_mix), C3 round (np_tex_colour_round). The unit drives the
// banks' load enables from its handshake (np_pipe_ctrl.v).
// Verilog-2005, synthesizable; Verilator -Wall clean (waiver below).
//
// Parameters: W, F (x is s(W) QI.F, W = 1 + I + F), FW (Fw: colour weight bits).
// Ports:
//   x               s(W) QI.F  the texture's value, C1's input (loaded at ld_c1)
//   ld_c1, ld_c2, ld_c3        bank C1 / C2 / C3 loads at this edge
//   cmap [6144], cmap_n u9, cmap_rep   the colour map (np_span_ports.vh)
//   cr, cg, cb      u8         bank C3: the pixel's colour
// Banks: C1 seg u8, cw u(Fw+1); C2 prod u(8+Fw) x 3; C3 rgb u8 x 3.
// x is sign-extended to XW bits: (N - 1) 2^F fits below bit XW - 1 unless
// XW = 128, where it wraps modulo 2^128 as np_shl128 does.
// Fault copy: NP_FAULT_FLIP flips bit 0 of cr when x's 4 low bits are 0101
// (1 pixel in 16; it rides along C1 and C2 beside the pixel).
// Lint waiver (Verilator -Wall): UNUSEDSIGNAL the wide temporaries of which
// each bank keeps its declared bits, and cmap_n[8] (N = 256 is cmap_n[7:0] = 0).
/* verilator lint_off UNUSEDSIGNAL */
module np_tex_colour #(
    parameter integer W = 33,
    parameter integer F = 32,
    parameter integer FW = 12
) (
    input wire clk,
    input wire [W-1:0] x,
    input wire ld_c1,
    input wire ld_c2,
    input wire ld_c3,
    input wire [6143:0] cmap,
    input wire [8:0] cmap_n,
    input wire cmap_rep,
    output wire [7:0] cr,
    output wire [7:0] cg,
    output wire [7:0] cb
);
    localparam integer PW = 8 + FW;               // prod
    localparam integer XW = W + 9 < 128 ? W + 9 : 128;
    localparam integer RW = (F > FW ? F : FW) + 1;

    // ---------------------------------------------------------------- C1: split (np_tex_colour_split)
    wire [XW-1:0] xs = {{(XW - W){x[W-1]}}, x};
    wire [7:0] nm1 = cmap_n[7:0] - 8'd1;          // N - 1 (N = 256: 255)
    wire [XW-1:0] top = {{(XW - 8){1'b0}}, nm1} << F;
    wire [RW-1:0] xfr = {{(RW - F){1'b0}}, x[F-1:0]};
    wire [XW-1:0] xint = xs >> F;
    wire [RW-1:0] wround;
    generate
        if (F > FW) begin : g_wround
            assign wround = (xfr + ({{(RW - 1){1'b0}}, 1'b1} << (F - FW - 1))) >> (F - FW);
        end else begin : g_wshift
            assign wround = xfr << (FW - F);
        end
    endgenerate
    wire neg = x[W-1];
    wire over = $signed(xs) >= $signed(top);
    wire [7:0] seg_w = cmap_rep ? xint[7:0] & nm1 : neg ? 8'd0 : over ? cmap_n[7:0] - 8'd2 : xint[7:0];
    wire [FW:0] cw_w = cmap_rep ? wround[FW:0] : neg ? {(FW + 1){1'b0}} : over ? {1'b1, {FW{1'b0}}} : wround[FW:0];
`ifdef NP_FAULT_FLIP
    wire flip = x[3:0] == 4'h5;  // fault: bit 0 of cr, 1 pixel in 16
`else
    wire flip = 1'b0;
`endif
    reg [7:0] seg1;
    reg [FW:0] cw1;
    reg flip1, flip2;
    always @(posedge clk) if (ld_c1) begin seg1 <= seg_w; cw1 <= cw_w; flip1 <= flip; end

    // ---------------------------------------------------------------- C2: mix (np_tex_colour_mix)
    wire [7:0] nxt = cmap_rep ? (seg1 + 8'd1) & nm1 : seg1 + 8'd1;
    reg [PW-1:0] prod2[0:2];
    genvar chn;
    generate
        for (chn = 0; chn < 3; chn = chn + 1) begin : g_mix
            wire [7:0] c0 = cmap[24*seg1 + 8*chn +: 8], c1 = cmap[24*nxt + 8*chn +: 8];
            wire signed [63:0] c0s = {56'd0, c0}, c1s = {56'd0, c1};
            wire signed [63:0] cws = {{(63 - FW){1'b0}}, cw1};
            wire signed [63:0] pv = (c0s <<< FW) + cws * (c1s - c0s);  // s(10+Fw), in [0, 255 2^Fw]
            always @(posedge clk) if (ld_c2) prod2[chn] <= pv[PW-1:0];
        end
    endgenerate
    always @(posedge clk) if (ld_c2) flip2 <= flip1;

    // ---------------------------------------------------------------- C3: round (np_tex_colour_round)
    reg [7:0] rgb3[0:2];
    generate
        for (chn = 0; chn < 3; chn = chn + 1) begin : g_round
            wire [PW:0] pr = {1'b0, prod2[chn]} + ({{PW{1'b0}}, 1'b1} << (FW - 1));
            wire [7:0] rv = pr[FW +: 8];
            always @(posedge clk) if (ld_c3) rgb3[chn] <= chn == 0 ? {rv[7:1], rv[0] ^ flip2} : rv;
        end
    endgenerate
    assign cr = rgb3[0];
    assign cg = rgb3[1];
    assign cb = rgb3[2];
endmodule
/* verilator lint_on UNUSEDSIGNAL */
