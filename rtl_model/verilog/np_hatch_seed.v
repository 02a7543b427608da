// SPDX-License-Identifier: MIT
// np_hatch_seed - one seed lane of the hatching unit (np_hatch.v): the
// datapath of np_hatch_seed() in rtl_model/np_hatch.c for one (layer l,
// seed i) fixed at elaboration, and the blend of its alpha into the colour.
// Combinational; np_hatch.v puts LANES of them in series in each seed stage.
// Verilog-2005, synthesizable; Verilator -Wall clean.
//
// Parameters (constants of the seed; np_hatch.v computes them from the
// configuration keys, np_hatch.h's wiring):
//   ST_U, ST_V  u32 Q0.32  st: the first 32 bits of the periodic fraction
//                          0.WWW... of W = rotl_N(b, i) (per axis)
//   W0_U, W0_V  1 bit      W[0], the last bit of W (survival)
//   RC, RS      s16 Q1.14  the layer's R = [[RC, RS], [-RS, RC]]
//   FADE        0 smooth, 1 one by one (the key fade)
//   N           seeds per layer (16, 64): the ramps' N + 1
//   I           the seed index i (0..N-1), the ramps' i
//   F           colour fraction bits, 8 + guard
// Ports (formats of np_hatch.h's signal table):
//   xu, xv  u33 Q1.32   seed-space position mod 2
//   al      u31 Q1.30   the layer's tone al[l] = clamp(4A - l, 0, 1)
//   oms     u17 Q1.16   min(om, 1)
//   ku, kv  u33 Q9.24   pm inv_len, pm inv_wid
//   c_in    u(F+1) Q1.F colour before this seed's blend
//   c_out   u(F+1) Q1.F after: c_in - floor(alpha c_in / 2^30)
//   alpha   u31 Q1.30   this seed's alpha (for traces and the fault bench)
// Every product "rounded half up" in Q1.30 is mul30: floor((x y + 2^29) / 2^30).
// Lint waiver (Verilator -Wall), for the whole file:
//   UNUSEDSIGNAL  the bits of wide products and of the 32-bit mul30 results
//                 that are provably 0 (values <= 2^30) are not read.
/* verilator lint_off UNUSEDSIGNAL */
module np_hatch_seed #(
    parameter [31:0] ST_U = 32'd0,
    parameter [31:0] ST_V = 32'd0,
    parameter [0:0] W0_U = 1'b0,
    parameter [0:0] W0_V = 1'b0,
    parameter [15:0] RC = 16'd16384,
    parameter [15:0] RS = 16'd0,
    parameter integer FADE = 0,
    parameter integer N = 16,
    parameter integer I = 0,
    parameter integer F = 17
) (
    input wire [32:0] xu,
    input wire [32:0] xv,
    input wire [30:0] al,
    input wire [16:0] oms,
    input wire [32:0] ku,
    input wire [32:0] kv,
    input wire [F:0] c_in,
    output wire [F:0] c_out,
    output wire [30:0] alpha
);
    localparam [31:0] ONE30 = 32'h40000000;
    // d = x + NOT33(st) + 2^31 (mod 2^33): NOT33(st) + 2^31 is a constant of the seed.
    localparam [32:0] KU = (33'h1ffffffff ^ {1'b0, ST_U}) + 33'h080000000;
    localparam [32:0] KV = (33'h1ffffffff ^ {1'b0, ST_V}) + 33'h080000000;

    // x y rounded half up to Q1.30; x, y < 2^32 with x y < 2^62 (every use: Q1.30 words <= 2^30, or
    // S's second factor 3 - 2t <= 3); the result is kept in 32 bits as the C model's uint32_t.
    function [31:0] mul30;
        input [31:0] x;
        input [31:0] y;
        reg [63:0] p;
        begin
            p = {32'd0, x} * {32'd0, y} + 64'h20000000;
            mul30 = p[61:30];
        end
    endfunction
    // S(t) = round(round(t^2) (3 - 2t)), t in [0, 1] Q1.30.
    function [31:0] smooth30;
        input [31:0] t;
        begin
            smooth30 = mul30(mul30(t, t), 32'hc0000000 - {t[30:0], 1'b0});
        end
    endfunction
    // clamp((N + 1) x - i, 0, 1) in Q1.30, x <= 2^30 (exact: (N + 1) x < 2^37).
    localparam [39:0] NP1 = {8'd0, N[31:0] + 32'd1};
    localparam [39:0] IOFF = {I[9:0], 30'd0};
    function [31:0] ramp30;
        input [30:0] x;
        reg signed [39:0] v;
        begin
            v = $signed(NP1 * {9'd0, x}) - $signed(IOFF);
            ramp30 = v < 0 ? 32'd0 : (v > $signed({8'd0, ONE30}) ? ONE30 : v[31:0]);
        end
    endfunction

    // d u33 Q1.32; surv; r s33 Q0.32 = frac(d) - 1/2 (the top fraction bit inverted, sign-extended)
    wire [32:0] du = xu + KU;
    wire [32:0] dv = xv + KV;
    wire surv = du[32] == W0_U && dv[32] == W0_V;
    wire signed [48:0] ru = $signed({{18{~du[31]}}, du[30:0]});
    wire signed [48:0] rv = $signed({{18{~dv[31]}}, dv[30:0]});
    // q = R r, s49 Q3.46, exact (|q| <= (|RC| + |RS|) 2^31 < 2^46)
    wire signed [48:0] rc = $signed({{33{RC[15]}}, RC});
    wire signed [48:0] rs = $signed({{33{RS[15]}}, RS});
    wire signed [48:0] qu = rc * ru + rs * rv;
    wire signed [48:0] qv = rc * rv - rs * ru;
    // Q = 2 q k rounded half up: (q k + 2^38) >> 39 (arithmetic), s44 Q14.30 here: the 83-bit
    // product's top bits (np_hatch_bigq_bits: s42 Q11.30 holds every value; two bits to spare)
    wire signed [82:0] pu = $signed({{34{qu[48]}}, qu}) * $signed({50'd0, ku}) + 83'sh4000000000;
    wire signed [82:0] pv = $signed({{34{qv[48]}}, qv}) * $signed({50'd0, kv}) + 83'sh4000000000;
    wire [43:0] bqu = pu[82:39];
    wire [43:0] bqv = pv[82:39];
    wire [43:0] mu = bqu[43] ? ~bqu + 44'd1 : bqu;  // |Q| (|Q| < 2^41: no overflow)
    wire [43:0] mv = bqv[43] ? ~bqv + 44'd1 : bqv;
    wire in_box = mu[43:30] == 14'd0 && mv[43:30] == 14'd0;  // |Qu| < 1 and |Qv| < 1
    // the stroke profile y_alpha = (1 - Qu^8)(1 - Qv^4), u31 Q1.30, 0 outside
    wire [31:0] u2 = mul30({2'd0, mu[29:0]}, {2'd0, mu[29:0]});
    wire [31:0] u4 = mul30(u2, u2);
    wire [31:0] u8 = mul30(u4, u4);
    wire [31:0] v2 = mul30({2'd0, mv[29:0]}, {2'd0, mv[29:0]});
    wire [31:0] v4 = mul30(v2, v2);
    wire [31:0] prof = in_box ? mul30(ONE30 - u8, ONE30 - v4) : 32'd0;
    // the fades: at (tone), am (level), u31 Q1.30
    wire [31:0] at, am;
    generate
        if (FADE != 0) begin : g_obo
            wire [30:0] m30 = {14'd0, 17'h10000 - oms} << 14;  // m = 1 - oms as Q1.30
            assign at = smooth30(ramp30(al));
            assign am = surv ? ONE30 : ONE30 - smooth30(ramp30(m30));
        end else begin : g_smooth
            assign at = {1'b0, al};
            assign am = surv ? ONE30 : {1'b0, oms, 14'd0};
        end
    endgenerate
    wire [31:0] a = mul30(mul30(at, am), prof);  // <= 2^30
    assign alpha = a[30:0];
    // the blend with black ink: c - floor(alpha c / 2^30), alpha <= 1 keeps c >= 0
    wire [63:0] ac = {33'd0, a[30:0]} * {{(63 - F){1'b0}}, c_in};
    assign c_out = c_in - ac[F+30:30];
endmodule
/* verilator lint_on UNUSEDSIGNAL */
