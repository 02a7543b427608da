// SPDX-License-Identifier: MIT
// np_wave - reference RTL of the Gerstner wave unit `wave` (Yrjola and
// Larsson, shared/seeds/004), written from the bit-exact specification
// rtl_model/np_wave.h (docs/wave.md) and its cycle model np_wave_pipe_init
// (np_pipe.h). Verilog-2005, synthesizable; Icarus and Verilator -Wall clean.
// One water grid point a transaction, one a clock.
//
// Parameters: the unit's configuration keys (noisepipe units, wave)
//   TRAINS    trains   lanes, 1..4 (default 2)
//   IRR       irr      1: eq. (8)'s irregular height (s1, s2, w, ap's a w)
//   CAP       cap      1: eq. (9)'s capillary term (sc, bc)
//   ROM_LOG2  rom_log2 L: 2^L quarter-wave ROM words (6..10, default 8)
//   NORMALS   normals  1: outputs nx, ny, nz (driven 0 otherwise)
//   FOLD      fold     1: output fold (driven 0 otherwise)
// (sincos=recurrence has no RTL here: docs/wave.md, "Reference RTL".)
//   MLOG2     the box register mlog2 (smoothing margin M = 2^MLOG2, PIN 3),
//             fixed at elaboration: it sets G's width and the output shifts
//             (a variable shift otherwise); the bench checks the vector
//             file's register against it.
// and the widths of the register-dependent signals (np_wave.h's formats;
// the datapath declaration np_wave_datapath sizes them from a register set,
// `report gates --synth` passes its widths). The defaults hold every
// accepted register set (np_wave_regs_check: amp, airr u15, airr <= amp,
// |c| <= 1, |cx|, |cz| <= 2^14, b u15), so nothing here wraps:
//   W_AP 23  ap    u(W_AP)  Q6.17   <= (amp + airr) 2^7 < 2^23
//   W_YC 34  yc    s(W_YC)  Q6.27   |.| <= ap 2^10
//   W_SA 24  sa,yq s(W_SA)  Q6.17   |.| <= ap
//   W_XP 38  xp,zp s(W_XP)  Q8.31   |.| <= ap 2^14
//   W_YS 36  Y     s(W_YS)  Q10.27  four lanes of yc
//   W_XS 40  X, Z  s(W_XS)  Q10.31  four lanes of xp
//   W_BC 33  bc    s(W_BC)  Q6.27   b sc, |.| <= b 2^17
//   W_GM     G     u(W_GM)  Q1.(14+MLOG2), MLOG2 + 16 (sm <= 2^MLOG2, g' u15)
//   W_LJ 40  lj    s(W_LJ)  Q10.29  |yq e| / 2^14 <= 2^23 2^29 / 2^14
//   W_LY 39  ly    s(W_LY)  Q9.29   sa km
//   W_JS 42  js    s(W_JS)  Q12.29  four lanes
//   W_J  18  j     s(W_J)   Q3.14   the Jacobian terms, |.| < 8 (np_wave_regs_check)
// and the pipe options IN_REG, OUT_SKID (np_pipe.h, np_classic3.v).
//
// Ports. The box's registers (np_wave_regs) are inputs held constant while
// transactions run (a register file outside the unit; lane k's fields at
// [W*k +: W] of each packed vector):
//   n [2:0] u3 trains in use (lanes k >= n give ap = 0: they add nothing)
//   kx, kz s32 Q0.32; phi, om u32 Q0.32; amp, airr u15 Q5.10; cx, cz s16 Q1.14;
//   kmx, kmz s16 Q3.12 (read only with NORMALS or FOLD); width u16;
//   pu, pv, pt u32 Q0.32 (IRR); omc u32 Q0.32, b u15 Q5.10 (CAP); gcap u15 Q1.14.
// Transaction in: i, j u16; t u32; ph u32 Q0.32; u, v u16; r u8; g u15 Q1.14.
// Transaction out: y, dx, dz s16 Q5.10; nx, ny, nz s20 Q9.10; fold u1.
//
// Banks = stages of the cycle model: P S A M T G [N] (latency 6, 7 with
// NORMALS or FOLD); the handshake is np_pipe's (np_classic3.v): bank k loads
// when it is empty or its content moves on. What each bank holds:
//   P: th[k] u32, p1, p2 (IRR), pc (CAP) u32, sm u(MLOG2+1), g u15
//   S: c[k], s[k] s19, s1, s2 (IRR), sc (CAP) s19, sm, g
//   A: ap[k], c[k], s[k], sc, G
//   M: yc[k], xp[k], zp[k], bc, G; with the Jacobian lj[k][0..3], ly[k][0..1]
//   T: Y, X, Z, bc, G; js[0..3] (fold) or js[0..5] (normals)
//   G: y, dx, dz; the terms j[0..3] or j[0..5] (s18 Q3.14)
//   N: y, dx, dz, nx, ny, nz, fold
// The rounding rule everywhere is np_shr_round_half_up: add half an LSB,
// then an arithmetic shift (floor). The outputs are kept to their widths
// without saturation: np_wave_regs_check proves that an accepted register
// set never reaches the C model's saturation (docs/wave.md, "Output range").
// Lint waivers (Verilator -Wall), each for the whole file:
//   UNUSEDSIGNAL wide products of which only the provably sufficient bits
//                are kept, and the registers a configuration does not read.
/* verilator lint_off UNUSEDSIGNAL */
module np_wave #(
    parameter integer TRAINS = 2,
    parameter integer IRR = 1,
    parameter integer CAP = 1,
    parameter integer ROM_LOG2 = 8,
    parameter integer NORMALS = 0,
    parameter integer FOLD = 0,
    parameter integer MLOG2 = 3,
    parameter integer W_AP = 23,
    parameter integer W_YC = 34,
    parameter integer W_SA = 24,
    parameter integer W_XP = 38,
    parameter integer W_YS = 36,
    parameter integer W_XS = 40,
    parameter integer W_BC = 33,
    parameter integer W_GM = MLOG2 + 16,
    parameter integer W_LJ = 40,
    parameter integer W_LY = 39,
    parameter integer W_JS = 42,
    parameter integer W_J = 18,
    parameter integer IN_REG = 0,
    parameter integer OUT_SKID = 0
) (
`include "np_pipe_ports.vh"
    // the box's registers
    input wire [2:0] n,
    input wire [32*TRAINS-1:0] kx,
    input wire [32*TRAINS-1:0] kz,
    input wire [32*TRAINS-1:0] phi,
    input wire [32*TRAINS-1:0] om,
    input wire [15*TRAINS-1:0] amp,
    input wire [15*TRAINS-1:0] airr,
    input wire [16*TRAINS-1:0] cx,
    input wire [16*TRAINS-1:0] cz,
    input wire [16*TRAINS-1:0] kmx,
    input wire [16*TRAINS-1:0] kmz,
    input wire [15:0] width,
    input wire [31:0] pu,
    input wire [31:0] pv,
    input wire [31:0] pt,
    input wire [31:0] omc,
    input wire [14:0] b,
    input wire [14:0] gcap,
    // transactions
    input wire [15:0] i,
    input wire [15:0] j,
    input wire [31:0] t,
    input wire [31:0] ph,
    input wire [15:0] u,
    input wire [15:0] v,
    input wire [7:0] r,
    input wire [14:0] g,
    output wire [15:0] y,
    output wire [15:0] dx,
    output wire [15:0] dz,
    output wire [19:0] nx,
    output wire [19:0] ny,
    output wire [19:0] nz,
    output wire fold
);
    localparam integer K = TRAINS, ML = MLOG2;
    localparam integer JAC = (NORMALS != 0 || FOLD != 0) ? 1 : 0;
    localparam integer NT = NORMALS != 0 ? 6 : 4;  // Jacobian terms computed
    localparam integer NB = JAC != 0 ? 7 : 6;      // banks = latency
    localparam integer IW = 151;                   // the input bundle
    localparam integer OW = 3 * 16 + 3 * 20 + 1;   // the output bundle
    localparam integer B_P = 0, B_S = 1, B_A = 2, B_M = 3, B_T = 4, B_G = 5;

    // ---------------------------------------------------------------- handshake
    wire core_in_valid, core_in_ready, core_out_valid, core_out_ready;
    wire [15:0] ci, cj, cu, cv;
    wire [31:0] ct, cph;
    wire [7:0] cr;
    wire [14:0] cg;
    wire [OW-1:0] core_out;
    reg [NB-1:0] bv;  // each bank's valid bit
    wire [NB-1:0] en, bv_next;  // NP_FAULT_STALL: bank M overwrites its content when its successor stalls
    np_pipe_ctrl #(.NB(NB), .STALL_BANK(B_M)) u_ctrl (.v(bv), .in_valid(core_in_valid), .out_ready(core_out_ready),
        .en(en), .v_next(bv_next), .in_ready(core_in_ready), .out_valid(core_out_valid));
    always @(posedge clk) if (rst) bv <= {NB{1'b0}}; else bv <= bv_next;
    wire ld_p = en[B_P] && core_in_valid, ld_s = en[B_S] && bv[B_P], ld_a = en[B_A] && bv[B_S];
    wire ld_m = en[B_M] && bv[B_A], ld_t = en[B_T] && bv[B_M], ld_g = en[B_G] && bv[B_T];

    // ---------------------------------------------------------------- P
    // th[k] = kx i + kz j + phi + ph - om t (mod 2^32: the low 32 bits of
    // each product); p1 = pu u + pt t, p2 = pv v, pc = r (omc t) (mod 2^32);
    // d = v < V ? min(v, V - 1 - v) : 0, sm = min(d, M).
    wire [31:0] p1_w = pu * {16'd0, cu} + pt * ct;
    wire [31:0] p2_w = pv * {16'd0, cv};
    wire [31:0] omt = omc * ct;
    wire [31:0] pc_w = omt * {24'd0, cr};
    wire [15:0] far = width - 16'd1 - cv;
    wire [15:0] dside = cv < width ? (cv < far ? cv : far) : 16'd0;
    wire [16:0] mm = 17'd1 << ML;  // M
    wire [ML:0] sm_w = {1'b0, dside} < mm ? dside[ML:0] : mm[ML:0];
    reg [32*K-1:0] r0_th;
    reg [31:0] r0_p1, r0_p2, r0_pc;
    reg [ML:0] r0_sm;
    reg [14:0] r0_g;
    genvar k;
    generate
        for (k = 0; k < K; k = k + 1) begin : g_p
            wire [31:0] th = kx[32*k+:32] * {16'd0, ci} + kz[32*k+:32] * {16'd0, cj} + phi[32*k+:32] + cph
                             - om[32*k+:32] * ct;
            always @(posedge clk) if (ld_p) r0_th[32*k+:32] <= th;
        end
    endgenerate
    always @(posedge clk) if (ld_p) begin
        r0_p1 <= IRR != 0 ? p1_w : 32'd0;
        r0_p2 <= IRR != 0 ? p2_w : 32'd0;
        r0_pc <= CAP != 0 ? pc_w : 32'd0;
        r0_sm <= sm_w;
        r0_g <= cg;
    end

    // ---------------------------------------------------------------- S
    // c[k] = cos th[k] = sin(th[k] + 2^30), s[k] = sin th[k]; s1, s2, sc:
    // np_wave_sin.v (the quarter-wave ROM with linear interpolation).
    reg [19*K-1:0] r1_c, r1_s;
    reg [18:0] r1_s1, r1_s2, r1_sc;
    reg [ML:0] r1_sm;
    reg [14:0] r1_g;
    generate
        for (k = 0; k < K; k = k + 1) begin : g_s
            wire [18:0] cw, sw;
            np_wave_sin #(.ROM_LOG2(ROM_LOG2)) u_c (.th(r0_th[32*k+:32] + 32'h4000_0000), .s(cw));
            np_wave_sin #(.ROM_LOG2(ROM_LOG2)) u_s (.th(r0_th[32*k+:32]), .s(sw));
            always @(posedge clk) if (ld_s) begin
                r1_c[19*k+:19] <= cw;
                r1_s[19*k+:19] <= sw;
            end
        end
        if (IRR != 0) begin : g_s_irr
            wire [18:0] s1w, s2w;
            np_wave_sin #(.ROM_LOG2(ROM_LOG2)) u_s1 (.th(r0_p1), .s(s1w));
            np_wave_sin #(.ROM_LOG2(ROM_LOG2)) u_s2 (.th(r0_p2), .s(s2w));
            always @(posedge clk) if (ld_s) begin
                r1_s1 <= s1w;
                r1_s2 <= s2w;
            end
        end else begin : g_s_noirr
            always @(posedge clk) if (ld_s) begin
                r1_s1 <= 19'd0;
                r1_s2 <= 19'd0;
            end
        end
        if (CAP != 0) begin : g_s_cap
            wire [18:0] scw;
            np_wave_sin #(.ROM_LOG2(ROM_LOG2)) u_sc (.th(r0_pc), .s(scw));
            always @(posedge clk) if (ld_s) r1_sc <= scw;
        end else begin : g_s_nocap
            always @(posedge clk) if (ld_s) r1_sc <= 19'd0;
        end
    endgenerate
    always @(posedge clk) if (ld_s) begin
        r1_sm <= r0_sm;
        r1_g <= r0_g;
    end

    // ---------------------------------------------------------------- A
    // w = round(s1 s2 / 2^17) s19 Q1.17; ap[k] = amp 2^7 - round(airr w / 2^10)
    // (IRR; else amp 2^7), 0 for lanes k >= n; G = sm min(g, gcap), exact.
    wire signed [37:0] s12 = $signed(r1_s1) * $signed(r1_s2);
    wire signed [37:0] w_r = (s12 + 38'sd65536) >>> 17;
    wire signed [18:0] w = w_r[18:0];
    wire [14:0] gmin = r1_g < gcap ? r1_g : gcap;
    wire [ML+15:0] gm_w = {15'd0, r1_sm} * {{(ML + 1){1'b0}}, gmin};
    reg [W_AP*K-1:0] r2_ap;
    reg [19*K-1:0] r2_c, r2_s;
    reg [18:0] r2_sc;
    reg [W_GM-1:0] r2_gm;
    generate
        for (k = 0; k < K; k = k + 1) begin : g_a
            wire signed [34:0] aw = $signed({1'b0, airr[15*k+:15]}) * w;
            wire signed [35:0] aw_r = (aw + 36'sd512) >>> 10;
            wire signed [35:0] ap_full = $signed({14'd0, amp[15*k+:15], 7'd0}) - (IRR != 0 ? aw_r : 36'sd0);
            wire [W_AP-1:0] ap_w = n > k ? ap_full[W_AP-1:0] : {W_AP{1'b0}};
            always @(posedge clk) if (ld_a) r2_ap[W_AP*k+:W_AP] <= ap_w;
        end
    endgenerate
    always @(posedge clk) if (ld_a) begin
        r2_c <= r1_c;
        r2_s <= r1_s;
        r2_sc <= r1_sc;
        r2_gm <= gm_w[W_GM-1:0];
    end

    // ---------------------------------------------------------------- M
    // Per lane: yc = round(ap c / 2^7), sa = round(ap s / 2^17), xp = sa cx,
    // zp = sa cz (exact); bc = b sc (CAP; else 0). With the Jacobian: yq =
    // round(ap c / 2^17) (the same product ap c), e = cx kmx, cx kmz, cz kmx,
    // cz kmz (s31 Q4.26, exact), lj[0..3] = round(yq e / 2^14), ly[0, 1] =
    // sa kmx, sa kmz (exact).
    reg [W_YC*K-1:0] r3_yc;
    reg [W_XP*K-1:0] r3_xp, r3_zp;
    reg [W_LJ*4*K-1:0] r3_lj;
    reg [W_LY*2*K-1:0] r3_ly;
    reg [W_BC-1:0] r3_bc;
    reg [W_GM-1:0] r3_gm;
    wire signed [34:0] bc_w = $signed({1'b0, b}) * $signed(r2_sc);
    generate
        for (k = 0; k < K; k = k + 1) begin : g_m
            wire signed [W_AP+19:0] pc = $signed({1'b0, r2_ap[W_AP*k+:W_AP]}) * $signed(r2_c[19*k+:19]);
            wire signed [W_AP+19:0] ps = $signed({1'b0, r2_ap[W_AP*k+:W_AP]}) * $signed(r2_s[19*k+:19]);
            wire signed [W_AP+19:0] yc_r = (pc + 64) >>> 7;
            wire signed [W_AP+19:0] sa_r = (ps + 65536) >>> 17;
            wire signed [W_SA-1:0] sa = sa_r[W_SA-1:0];
            wire signed [W_SA+15:0] xp = sa * $signed(cx[16*k+:16]);
            wire signed [W_SA+15:0] zp = sa * $signed(cz[16*k+:16]);
            always @(posedge clk) if (ld_m) begin
                r3_yc[W_YC*k+:W_YC] <= yc_r[W_YC-1:0];
                r3_xp[W_XP*k+:W_XP] <= xp[W_XP-1:0];
                r3_zp[W_XP*k+:W_XP] <= zp[W_XP-1:0];
            end
            if (JAC == 0) begin : g_nojac
                always @(posedge clk) if (ld_m) r3_lj[W_LJ*4*k+:W_LJ*4] <= {(W_LJ * 4){1'b0}};
            end
            if (JAC == 0 || NORMALS == 0) begin : g_noly
                always @(posedge clk) if (ld_m) r3_ly[W_LY*2*k+:W_LY*2] <= {(W_LY * 2){1'b0}};
            end
            if (JAC != 0) begin : g_jac
                wire signed [W_AP+19:0] yq_r = (pc + 65536) >>> 17;
                wire signed [W_SA-1:0] yq = yq_r[W_SA-1:0];
                wire signed [31:0] e0 = $signed(cx[16*k+:16]) * $signed(kmx[16*k+:16]);
                wire signed [31:0] e1 = $signed(cx[16*k+:16]) * $signed(kmz[16*k+:16]);
                wire signed [31:0] e2 = $signed(cz[16*k+:16]) * $signed(kmx[16*k+:16]);
                wire signed [31:0] e3 = $signed(cz[16*k+:16]) * $signed(kmz[16*k+:16]);
                wire signed [W_SA+31:0] q0 = (yq * e0 + 8192) >>> 14;
                wire signed [W_SA+31:0] q1 = (yq * e1 + 8192) >>> 14;
                wire signed [W_SA+31:0] q2 = (yq * e2 + 8192) >>> 14;
                wire signed [W_SA+31:0] q3 = (yq * e3 + 8192) >>> 14;
                always @(posedge clk) if (ld_m) begin
                    r3_lj[W_LJ*(4*k+0)+:W_LJ] <= q0[W_LJ-1:0];
                    r3_lj[W_LJ*(4*k+1)+:W_LJ] <= q1[W_LJ-1:0];
                    r3_lj[W_LJ*(4*k+2)+:W_LJ] <= q2[W_LJ-1:0];
                    r3_lj[W_LJ*(4*k+3)+:W_LJ] <= q3[W_LJ-1:0];
                end
                if (NORMALS != 0) begin : g_ly
                    wire signed [W_SA+15:0] lx = sa * $signed(kmx[16*k+:16]);
                    wire signed [W_SA+15:0] lz = sa * $signed(kmz[16*k+:16]);
                    always @(posedge clk) if (ld_m) begin
                        r3_ly[W_LY*(2*k+0)+:W_LY] <= lx[W_LY-1:0];
                        r3_ly[W_LY*(2*k+1)+:W_LY] <= lz[W_LY-1:0];
                    end
                end
            end
        end
    endgenerate
    always @(posedge clk) if (ld_m) begin
        r3_bc <= CAP != 0 ? bc_w[W_BC-1:0] : {W_BC{1'b0}};
        r3_gm <= r2_gm;
    end

    // ---------------------------------------------------------------- T
    // Y = sum yc, X = -sum xp, Z = -sum zp; js[m] = -sum lj[m] (exact).
    reg signed [W_YS-1:0] ys_w;
    reg signed [W_XS-1:0] xs_w, zs_w;
    reg [6*W_JS-1:0] js_w;  // js[m] at [W_JS*m +: W_JS]
    integer q, m;
    always @(*) begin
        ys_w = {W_YS{1'b0}};
        xs_w = {W_XS{1'b0}};
        zs_w = {W_XS{1'b0}};
        js_w = {(6 * W_JS){1'b0}};
        for (q = 0; q < K; q = q + 1) begin
            // $signed(part) in a signed sum of the wider width: sign-extended
            ys_w = ys_w + $signed({{(W_YS - W_YC + 1){r3_yc[W_YC*q+W_YC-1]}}, r3_yc[W_YC*q+:W_YC-1]});
            xs_w = xs_w - $signed({{(W_XS - W_XP + 1){r3_xp[W_XP*q+W_XP-1]}}, r3_xp[W_XP*q+:W_XP-1]});
            zs_w = zs_w - $signed({{(W_XS - W_XP + 1){r3_zp[W_XP*q+W_XP-1]}}, r3_zp[W_XP*q+:W_XP-1]});
            if (JAC != 0) begin
                for (m = 0; m < 4; m = m + 1)
                    js_w[W_JS*m+:W_JS] = $signed(js_w[W_JS*m+:W_JS]) - $signed({{(W_JS - W_LJ + 1){r3_lj[W_LJ*(4*q+m)+W_LJ-1]}},
                                                 r3_lj[W_LJ*(4*q+m)+:W_LJ-1]});
                if (NORMALS != 0)
                    for (m = 0; m < 2; m = m + 1)
                        js_w[W_JS*(4+m)+:W_JS] = $signed(js_w[W_JS*(4+m)+:W_JS]) - $signed({{(W_JS - W_LY + 1){r3_ly[W_LY*(2*q+m)+W_LY-1]}},
                                                         r3_ly[W_LY*(2*q+m)+:W_LY-1]});
            end
        end
    end
    reg signed [W_YS-1:0] r4_ys;
    reg signed [W_XS-1:0] r4_xs, r4_zs;
    reg signed [W_JS-1:0] r4_js[0:5];
    reg signed [W_BC-1:0] r4_bc;
    reg [W_GM-1:0] r4_gm;
    always @(posedge clk) if (ld_t) begin
        r4_ys <= ys_w;
        r4_xs <= xs_w;
        r4_zs <= zs_w;
        r4_bc <= r3_bc;
        r4_gm <= r3_gm;
        for (m = 0; m < 6; m = m + 1) r4_js[m] <= (JAC != 0 && m < NT) ? $signed(js_w[W_JS*m+:W_JS]) : {W_JS{1'b0}};
    end

    // ---------------------------------------------------------------- G
    // y = round((Y G + bc 2^(14+MLOG2)) / 2^(31+MLOG2)), dx = round(X G /
    // 2^(35+MLOG2)), dz likewise (one rounding each); the terms j[m] =
    // round(js[m] G / 2^(29+MLOG2)) s18 Q3.14.
    localparam integer WY = (W_YS + W_GM > W_BC + 14 + ML ? W_YS + W_GM : W_BC + 14 + ML) + 2;
    localparam integer WX = W_XS + W_GM + 1, WJ = W_JS + W_GM + 1;
    wire signed [W_GM:0] gs = $signed({1'b0, r4_gm});
    wire signed [WY-1:0] yg = r4_ys * gs;
    wire signed [WY-1:0] bcs = $signed({{(WY - W_BC + 1){r4_bc[W_BC-1]}}, r4_bc[W_BC-2:0]}) <<< (14 + ML);
    wire signed [WY-1:0] yv = yg + bcs;
    wire signed [WY-1:0] y_r = (yv + ($signed({{(WY - 1){1'b0}}, 1'b1}) <<< (30 + ML))) >>> (31 + ML);
    wire signed [WX-1:0] xg = r4_xs * gs;
    wire signed [WX-1:0] zg = r4_zs * gs;
    wire signed [WX-1:0] half_x = $signed({{(WX - 1){1'b0}}, 1'b1}) <<< (34 + ML);
    wire signed [WX-1:0] dx_r = (xg + half_x) >>> (35 + ML);
    wire signed [WX-1:0] dz_r = (zg + half_x) >>> (35 + ML);
    reg [15:0] r5_y, r5_dx, r5_dz;
`ifdef NP_FAULT_FLIP
    wire flip = r4_ys[3:0] == 4'h5;  // fault: bit 0 of y, 1 input in 16
`else
    wire flip = 1'b0;
`endif
    always @(posedge clk) if (ld_g) begin
        r5_y <= {y_r[15:1], y_r[0] ^ flip};
        r5_dx <= dx_r[15:0];
        r5_dz <= dz_r[15:0];
    end
    wire [OW-1:0] o_core;
    generate
        if (JAC == 0) begin : g_nojac
            assign o_core = {r5_y, r5_dx, r5_dz, 61'd0};
        end else begin : g_jac
            wire signed [WJ-1:0] half_j = $signed({{(WJ - 1){1'b0}}, 1'b1}) <<< (28 + ML);
            reg signed [W_J-1:0] r5_j[0:5];
            genvar jm;
            for (jm = 0; jm < 6; jm = jm + 1) begin : g_term
                wire signed [WJ-1:0] jp = (r4_js[jm] * gs + half_j) >>> (29 + ML);
                always @(posedge clk) if (ld_g) r5_j[jm] <= jm < NT ? jp[W_J-1:0] : {W_J{1'b0}};
            end
            // ---------------------------------------------------------- N
            // a = 2^14 + jxx, d = 2^14 + jzz (s19 Q4.14); exact in Q8.28:
            // Nx = yz jzx - d yx, Ny = a d - jxz jzx, Nz = jxz yx - yz a (s38);
            // nx, ny, nz = round(N / 2^18) s20 Q9.10; fold = Ny <= 0.
            wire ld_n = en[NB-1] && bv[NB-2];
            // a, d s(W_J + 1); the products s(2 W_J + 2), exact (s38 at W_J = 18)
            localparam integer WN = 2 * W_J + 2;
            wire signed [W_J:0] ja = $signed({{(W_J - 14){1'b0}}, 15'd16384}) + r5_j[0];
            wire signed [W_J:0] jd = $signed({{(W_J - 14){1'b0}}, 15'd16384}) + r5_j[3];
            wire signed [WN-1:0] nxw = r5_j[5] * r5_j[2] - jd * r5_j[4];
`ifdef NP_FAULT_FOLD
            wire signed [WN-1:0] nyw = ja * jd;  // fault: det J without jxz jzx
`else
            wire signed [WN-1:0] nyw = ja * jd - r5_j[1] * r5_j[2];
`endif
            wire signed [WN-1:0] nzw = r5_j[1] * r5_j[4] - r5_j[5] * ja;
            wire signed [WN-1:0] half_n = $signed({{(WN - 18){1'b0}}, 18'd131072});
            wire signed [WN-1:0] nxr = (nxw + half_n) >>> 18;
            wire signed [WN-1:0] nyr = (nyw + half_n) >>> 18;
            wire signed [WN-1:0] nzr = (nzw + half_n) >>> 18;
            reg [15:0] r6_y, r6_dx, r6_dz;
            reg [19:0] r6_nx, r6_ny, r6_nz;
            reg r6_fold;
            always @(posedge clk) if (ld_n) begin
                r6_y <= r5_y;
                r6_dx <= r5_dx;
                r6_dz <= r5_dz;
                r6_nx <= NORMALS != 0 ? nxr[19:0] : 20'd0;
                r6_ny <= NORMALS != 0 ? nyr[19:0] : 20'd0;
                r6_nz <= NORMALS != 0 ? nzr[19:0] : 20'd0;
`ifdef NP_FAULT_FOLDSIGN
                r6_fold <= FOLD != 0 ? nyw <= {WN{1'b0}} : 1'b0;  // fault: the compare unsigned (fold = (ny == 0))
`else
                r6_fold <= FOLD != 0 ? nyw <= $signed({WN{1'b0}}) : 1'b0;  // signed: a bare {WN{0}} would make it unsigned
`endif
            end
            assign o_core = {r6_y, r6_dx, r6_dz, r6_nx, r6_ny, r6_nz, r6_fold};
        end
    endgenerate
    assign core_out = o_core;

    // ---------------------------------------------------------------- options
    np_pipe_opts #(.IW(IW), .OW(OW), .IN_REG(IN_REG), .OUT_SKID(OUT_SKID)) u_opts (.clk(clk), .rst(rst),
        .in_valid(in_valid), .in_ready(in_ready), .in_data({i, j, t, ph, u, v, r, g}),
        .core_in_valid(core_in_valid), .core_in_ready(core_in_ready), .core_in_data({ci, cj, ct, cph, cu, cv, cr, cg}),
        .core_out_valid(core_out_valid), .core_out_ready(core_out_ready), .core_out_data(core_out),
        .out_valid(out_valid), .out_ready(out_ready), .out_data({y, dx, dz, nx, ny, nz, fold}));
endmodule
/* verilator lint_on UNUSEDSIGNAL */
