// SPDX-License-Identifier: MIT
// np_classicn - reference RTL of the n-D classic gradient noise units
// classic2, classic4, classic5 (and, at DIMS = 3, classic3 bit for bit),
// written from the bit-exact specification rtl_model/np_classicn.h (with
// np_hashn.h and np_fixed.h) and the cycle model np_classicn_pipe_init
// (np_pipe.h); docs/noise-nd.md ("Classic in n dimensions") is the
// specification in prose. Verilog-2005, synthesizable; Icarus and Verilator
// -Wall clean.
//
// Parameters are the unit's configuration keys (noisepipe units classicN):
//   DIMS       n   2..5 (the key dims; n = 3 gives classic3's f bit for bit)
//   OUT_BITS   N   f: sN Q(I).(N-I), I = 2 (n <= 3), 3 (n = 4, 5), I counting
//                  the sign (classic3's s8 Q2.6, classic4's s8 Q3.5)      4..16
//   S_FRAC     WS  the s-curves: u(WS+1) Q1.WS                            1..24
//   LERP_FRAC  WL  the interpolators' fraction bits                  N-I..30
// (defaults np_classicn_cfg_default: WS = F + 6 (n <= 3), F + 7 (n >= 4),
// at most 24; WL = F + 5; F = N - I) and the pipe options IN_REG and
// OUT_SKID (np_pipe.h, np_classic3.v): both 0 = np_classicn_pipe exactly.
//
// Ports:
//   clk, rst (synchronous, active high: empties every bank)
//   in_valid / in_ready, out_valid / out_ready   np_pipe's handshake
//   x [16 DIMS - 1 : 0]   the inputs, field a (x, y, z, w, v; the first DIMS)
//                         at bits [16 (DIMS - 1 - a) +: 16], each u16 Q8.8
//                         (cell = high byte, tile 256; fraction u_a = low
//                         byte): field x at the top, as in the vector word
//   f [OUT_BITS - 1 : 0]  sN Q(I).(N-I)
//
// Banks (latency 2n + 3: 7, 9, 11, 13): L, H, then per level m = 1..n the
// multiply Im and the add Ia, then O: np_classicn_stage_table's stages. The
// handshake is np_pipe's (see np_classic3.v): en[k] = !v[k] | en[k+1],
// en[last] = !v[last] | out_ready, in_ready = en[0]. Corner c = 0..2^n - 1 is
// sum_a 2^a b_a (b_a = 1: the far side of axis a).
// Register contents per bank (widths at n; formats):
//   L    u_a u8; h_c = hashn(n, k_c) u6, k_ca = (cell_a + b_a) mod 256;
//        u_a^2 u16 Q0.16
//   H    g_c s(GB) Q.8 = sum_a G_ca d_ca, G_c = gradn(n, h_c), d_ca = u_a
//        (b_a = 0) or u_a - 256 (b_a = 1), s9: exact; GB = 11 (n <= 4),
//        12 (n = 5). s_a u(WS+1) Q1.WS = rescale(u_a^2 (768 - 2 u_a), 24 -> WS)
//   Im   (level m = L + 1, 2^(n-m) lerps along axis L) the first operands
//        a_p s(AW) and the products s_L (b_p - a_p) s(DW + WS), where a_p, b_p
//        are level m - 1's entries 2p and 2p + 1 (level 0: g, fraction bits
//        AF = 8; after: l_(m-1), AF = WL); AW = AF + 1 + ib(bound), DW = AF +
//        1 + ib(2 bound), bound = n (m = 1), (m - 1)/2 + (n - m + 1) after
//   Ia   l_m[p] s(WL + 1 + vi_m) Q.WL = rescale(a_p 2^WS + prod_p, AF + WS -> WL),
//        vi_m = ib(m/2 + (n - m)): |l_m| <= m/2 + (n - m)
//   O    f = sat(rescale(l_n, WL -> N - I)), sN
// (ib(b): the smallest v with b < 2^v.) The s-curve of axis a rides along
// banks H .. I(a)a until level a + 1's multiply reads it. Each bank's widths
// are np_classicn_datapath's (at n = 3 np_classic3.v's: g s11, l1 l2 s(WL+3),
// l3 s(WL+2)); every value provably fits its word (np_classicn.h's ranges),
// so the registers hold exact values and the arithmetic between them, done on
// 64-bit signed temporaries (never wrapping: at most WL + WS + 6 = 60 bits),
// is the model's exactly. Rescaling drops bits rounding half up (add half an
// LSB, then an arithmetic shift: ties toward +inf for negative values too),
// adds bits with the exact left shift (level 1 when WL > 8 + WS).
//
// Fault injection for the tests that must fail: `define NP_FAULT_FLIP flips
// bit 0 of f when l_n[3:0] == 4'h5 (a datapath fault, about 1 input in 16);
// `define NP_FAULT_STALL makes bank I2a (bank 5) load while its successor
// stalls (a handshake fault: a transaction is overwritten and lost).
// The per-corner and per-lerp registers are packed vectors ([w c +: w]), as
// the lint tool (5.006) refuses a non-blocking assignment to an unpacked
// array in a loop it does not unroll (BLKLOOPINIT; the 2^n-corner hash loop).
// Lint waivers (Verilator -Wall), each for the whole file:
//   BLKSEQ       the clocked processes compute per-corner temporaries with
//                blocking assignments (written before read, local to one
//                process: wires of that stage, not registers); every register
//                is assigned with <=.
//   UNUSEDSIGNAL the 64-bit temporaries (of which the provably sufficient low
//                bits are kept), the sign-extended words of the level buses,
//                and the level buses' entries a level does not drive or read.
/* verilator lint_off BLKSEQ */
/* verilator lint_off UNUSEDSIGNAL */
module np_classicn #(
    parameter integer DIMS = 4,
    parameter integer OUT_BITS = 8,
    parameter integer S_FRAC = OUT_BITS - (DIMS <= 3 ? 2 : 3) + (DIMS <= 3 ? 6 : 7) > 24 ? 24
                             : OUT_BITS - (DIMS <= 3 ? 2 : 3) + (DIMS <= 3 ? 6 : 7),
    parameter integer LERP_FRAC = OUT_BITS - (DIMS <= 3 ? 2 : 3) + 5,
    parameter integer IN_REG = 0,
    parameter integer OUT_SKID = 0
) (
`include "np_pipe_ports.vh"
    input wire [16*DIMS-1:0] x,
    output wire [OUT_BITS-1:0] f
);
    localparam integer NN = DIMS, N = OUT_BITS, WS = S_FRAC, WL = LERP_FRAC;
    localparam integer NC = 1 << NN;        // corners
    localparam integer NB = 2 * NN + 3;     // banks = latency
    localparam integer OI = NN <= 3 ? 2 : 3;  // I: integer bits of f with the sign
    localparam integer F = N - OI;          // fraction bits of f
    localparam integer SW = WS + 1;         // s: u(WS+1) Q1.WS
    localparam integer GB = NN == 5 ? 12 : 11;  // g: |g| <= K 256, K = 2, 3, 3, 5
    localparam integer XW = 64;             // the temporaries (never wrap)
    localparam integer LX = 64;             // the level buses' stride (sign-extended words)

    // ib2(b2): the smallest v with b2 / 2 < 2^v (b2 = twice a bound).
    function integer ib2;
        input integer b2;
        begin
            ib2 = 0;
            while (b2 >= (2 << ib2)) ib2 = ib2 + 1;
        end
    endfunction

    // requant(val, from, to): np_shr_round_half_up at XW bits (np_fixed.vh)
`include "np_fixed.vh"

    // ---------------------------------------------------------------- handshake
    wire core_in_valid, core_in_ready, core_out_valid, core_out_ready;
    wire [16*NN-1:0] cx;
    wire [N-1:0] core_out;
    reg [NB-1:0] v;
    wire [NB-1:0] en, v_next;  // NP_FAULT_STALL: bank I2a overwrites its content when its successor stalls
    np_pipe_ctrl #(.NB(NB), .STALL_BANK(5)) u_ctrl (.v(v), .in_valid(core_in_valid), .out_ready(core_out_ready),
        .en(en), .v_next(v_next), .in_ready(core_in_ready), .out_valid(core_out_valid));
    always @(posedge clk) if (rst) v <= {NB{1'b0}}; else v <= v_next;

    // ---------------------------------------------------------------- L
    // h_c = hashn(n, k_c), k_ca = cell_a + b_a mod 256 (the tile wraps); u_a^2.
`include "np_hashn.vh"
    reg [7:0] r0_u[0:NN-1];
    reg [15:0] r0_sq[0:NN-1];
    reg [6*NC-1:0] r0_h;  // h_c at [6 c +: 6]
    integer c_l, a_l;
    reg [39:0] kc;
    reg [7:0] fr;
    always @(posedge clk) if (en[0] && core_in_valid) begin
        for (c_l = 0; c_l < NC; c_l = c_l + 1) begin
            kc = 40'd0;
            for (a_l = 0; a_l < NN; a_l = a_l + 1)
                kc[8*a_l+:8] = cx[16*(NN-1-a_l)+8+:8] + {7'd0, c_l[a_l]};
            r0_h[6*c_l+:6] <= hashn(NN, kc);
        end
        for (a_l = 0; a_l < NN; a_l = a_l + 1) begin
            fr = cx[16*(NN-1-a_l)+:8];
            r0_u[a_l] <= fr;
            r0_sq[a_l] <= {8'd0, fr} * {8'd0, fr};
        end
    end

    // ---------------------------------------------------------------- H
    // g_c = sum_a G_ca d_ca: per axis the s9 offset u_a or u_a - 256, added,
    // subtracted or skipped as gradn's coefficient says (exact in s(GB)).
    reg [GB*NC-1:0] r1_g;  // g_c at [GB c +: GB]
    integer c_h, a_h;
    reg [9:0] gg;
    reg signed [XW-1:0] gsum, dd;
    always @(posedge clk) if (en[1] && v[0]) begin
        for (c_h = 0; c_h < NC; c_h = c_h + 1) begin
            gg = gradn(NN, r0_h[6*c_h+:6]);
            gsum = 0;
            for (a_h = 0; a_h < NN; a_h = a_h + 1) begin
                dd = {{(XW-9){c_h[a_h]}}, c_h[a_h], r0_u[a_h]};  // u_a, or u_a - 256 (s9)
                if (gg[2*a_h+:2] == 2'b01) gsum = gsum + dd;
                else if (gg[2*a_h+:2] == 2'b11) gsum = gsum - dd;
            end
            r1_g[GB*c_h+:GB] <= gsum[GB-1:0];
        end
    end
    // s-curve: round(u^2 (768 - 2u) / 2^(24 - WS)), u(WS+1). The numerator is
    // exact in u24; one extra bit holds the rounding carry (np_classic3.v's).
    function [SW-1:0] scurve;
        input [15:0] sq;
        input [7:0] t;
        reg [24:0] num;
        begin
            num = {9'd0, sq} * ({15'd0, 10'd768} - {16'd0, t, 1'b0});
            if (WS < 24) num = num + (25'd1 << (23 - WS));
            scurve = num[24-WS+:SW];
        end
    endfunction

    // The s-curve of axis a, computed in H (bank 1) and carried in banks
    // 2 .. 1 + 2a: level a + 1's multiply (bank 2 + 2a) reads bank 1 + 2a's.
    wire [SW*NN-1:0] s_use;  // s_a as level a + 1 reads it, at [SW a +: SW]
    genvar ga, gk;
    generate
        for (ga = 0; ga < NN; ga = ga + 1) begin : g_s
            reg [SW-1:0] q[1:1+2*ga];  // q[k]: s_a in bank k
            always @(posedge clk) if (en[1] && v[0]) q[1] <= scurve(r0_sq[ga], r0_u[ga]);
            for (gk = 2; gk <= 1 + 2 * ga; gk = gk + 1) begin : g_carry
                always @(posedge clk) if (en[gk] && v[gk-1]) q[gk] <= q[gk-1];
            end
            assign s_use[SW*ga+:SW] = q[1+2*ga];
        end
    endgenerate

    // ---------------------------------------------------------------- I1m .. Ina
    // lval: level m's entries (m = 0: g), sign-extended to LX bits, entry p at
    // lval[NC m + p]; entries p >= 2^(n-m) are 0 (not read). A net array, not
    // one wide bus: Icarus re-evaluates a bus of NC (n + 1) words (12,288 bits
    // at n = 5) on every change of any of its parts.
    wire [LX-1:0] lval[0:NC*(NN+1)-1];
    genvar gc;
    generate
        for (gc = 0; gc < NC; gc = gc + 1) begin : g_l0
            assign lval[gc] = {{(LX-GB){r1_g[GB*gc+GB-1]}}, r1_g[GB*gc+:GB]};
        end
    endgenerate
    genvar gl;
    generate
        for (gl = 0; gl < NN; gl = gl + 1) begin : g_lvl
            localparam integer CNT = 1 << (NN - 1 - gl);        // lerps of this level
            localparam integer AF = gl == 0 ? 8 : WL;            // operands' fraction bits
            localparam integer B2 = 2 * NN - gl;                 // twice the operands' bound
            localparam integer AW = AF + 1 + ib2(B2);            // a_p
            localparam integer DW = AF + 1 + ib2(2 * B2);        // b_p - a_p
            localparam integer PW = DW + WS;                     // s (b_p - a_p), s <= 1.0
            localparam integer VW = WL + 1 + ib2(2 * NN - gl - 1);  // l_(gl+1)
            localparam integer BM = 2 + 2 * gl;                  // the multiply's bank
            reg [AW*CNT-1:0] ra;  // a_p at [AW p +: AW]
            reg [PW*CNT-1:0] rp;  // the product of lerp p at [PW p +: PW]
            reg [VW*CNT-1:0] rl;  // l_(gl+1)[p] at [VW p +: VW]
            integer p;
            reg signed [XW-1:0] ta, tb, tp;
            always @(posedge clk) if (en[BM] && v[BM-1]) begin
                for (p = 0; p < CNT; p = p + 1) begin
                    ta = lval[NC*gl+2*p];
                    tb = lval[NC*gl+2*p+1];
                    tp = $signed({{(XW-SW){1'b0}}, s_use[SW*gl+:SW]}) * (tb - ta);
                    ra[AW*p+:AW] <= ta[AW-1:0];
                    rp[PW*p+:PW] <= tp[PW-1:0];
                end
            end
            integer q;
            reg signed [XW-1:0] ua, up, us;
            always @(posedge clk) if (en[BM+1] && v[BM]) begin
                for (q = 0; q < CNT; q = q + 1) begin
                    ua = {{(XW-AW){ra[AW*q+AW-1]}}, ra[AW*q+:AW]};
                    up = {{(XW-PW){rp[PW*q+PW-1]}}, rp[PW*q+:PW]};
                    us = requant((ua <<< WS) + up, AF + WS, WL);
                    rl[VW*q+:VW] <= us[VW-1:0];
                end
            end
            for (gc = 0; gc < NC; gc = gc + 1) begin : g_out
                if (gc < CNT) begin : g_val
                    assign lval[NC*(gl+1)+gc] = {{(LX-VW){rl[VW*gc+VW-1]}}, rl[VW*gc+:VW]};
                end else begin : g_zero
                    assign lval[NC*(gl+1)+gc] = {LX{1'b0}};
                end
            end
        end
    endgenerate

    // ---------------------------------------------------------------- O
    // f = sat(rescale(l_n, WL -> F)): round half up, clamp to [-2^(N-1), 2^(N-1) - 1].
    wire [LX-1:0] l_last = lval[NC*NN];  // l_n
    reg signed [XW-1:0] ol, orq, hi_, lo_;
    reg [N-1:0] o_w;
    always @(*) begin
        ol = l_last;
        orq = requant(ol, WL, F);
        hi_ = (64'sd1 <<< (N - 1)) - 64'sd1;
        lo_ = -(64'sd1 <<< (N - 1));
        o_w = orq > hi_ ? hi_[N-1:0] : orq < lo_ ? lo_[N-1:0] : orq[N-1:0];
`ifdef NP_FAULT_FLIP
        if (ol[3:0] == 4'h5) o_w[0] = !o_w[0];  // fault: bit 0 of f, 1 input in 16
`endif
    end
    reg [N-1:0] ro_f;
    always @(posedge clk) if (en[NB-1] && v[NB-2]) ro_f <= o_w;
    assign core_out = ro_f;

    // ---------------------------------------------------------------- options
    np_pipe_opts #(.IW(16 * NN), .OW(N), .IN_REG(IN_REG), .OUT_SKID(OUT_SKID)) u_opts (.clk(clk), .rst(rst),
        .in_valid(in_valid), .in_ready(in_ready), .in_data(x),
        .core_in_valid(core_in_valid), .core_in_ready(core_in_ready), .core_in_data(cx),
        .core_out_valid(core_out_valid), .core_out_ready(core_out_ready), .core_out_data(core_out),
        .out_valid(out_valid), .out_ready(out_ready), .out_data(f));
endmodule
/* verilator lint_on UNUSEDSIGNAL */
/* verilator lint_on BLKSEQ */
