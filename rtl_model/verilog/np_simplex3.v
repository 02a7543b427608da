// SPDX-License-Identifier: MIT
// np_simplex3 - reference RTL of the 3-D simplex noise unit with analytic
// derivative, written from the bit-exact specification rtl_model/np_simplex.h
// (with np_hash.h and np_fixed.h) and the cycle model np_simplex_pipe_init
// (np_pipe.h). Verilog-2005, synthesizable; Icarus and Verilator -Wall clean.
//
// Parameters are the unit's configuration keys (noisepipe units):
//   OUT_BITS  N   f: sN Q-1.N                      4..20, default 16
//   DOUT_BITS ND  df/dx, df/dy, df/dz: sND Q1.(ND-2)  5..20, default 16
//   DERIV     1: derivative datapath (10 banks); 0: f only (9 banks, no M2;
//             dfdx..dfdz are driven 0)
//   T_FRAC WT, P_FRAC WP, K_FRAC WK   (np_simplex.h), defaults 24, 22, 22
// and the pipe options IN_REG and OUT_SKID (np_pipe.h, np_classic3.v).
//
// Banks: SK RK CH KT P2 P4 M [M2] A O; the handshake is np_pipe's (see
// np_classic3.v). Register contents are listed in docs/rtl.md.
//
// Widths. The front end (SK..KT) holds the exact integers at the widths that
// np_simplex.h proves (s12 offsets, s13 G.D, u23 T). From M on, when TIGHT
// (T_FRAC >= 9 and P_FRAC >= 9), the datapath declaration's widths
// (np_simplex_datapath's range argument, checked over every such
// configuration by simplex.rtl_widths) and no output saturation; otherwise
// every signal is held wide enough that it never wraps at ANY configuration
// (the model holds them in int64_t and never wraps; at t_frac = 1 the nominal
// ranges are exceeded and the output saturates): |fc|, |q| < 9 * 2^WP (|T^k|
// < 2^WT words times |G.D| <= 4608 = 9 * 2^9), |m| < 34 * 2^WP, |e| <= 2^WP,
// sums of four. The arithmetic is written as the declaration prices it (SK's
// shift-adds, KT's squares of |D_a|, O's signed-digit shift-adds), so that
// `noisepipe report gates --synth` compares one circuit with its estimate.
// The rounding rule everywhere is np_shr_round_half_up: add half an
// LSB, then an arithmetic shift (floor). A negative term is formed BEFORE its
// rounding: e_a = round(G_a * tau4), not -round(tau4).
// Lint waivers (Verilator -Wall), each for the whole file:
//   BLKSEQ       the clocked processes compute per-corner temporaries with
//                blocking assignments (written before read, local to one
//                process: wires of that stage, not registers); every register
//                is assigned with <=.
//   UNUSEDSIGNAL a temporary wider than what is kept (the skew's fraction
//                byte, the 96-bit M..O arithmetic whose value provably fits
//                the kept width): dropping those bits is the design.
/* verilator lint_off BLKSEQ */
/* verilator lint_off UNUSEDSIGNAL */
module np_simplex3 #(
    parameter integer OUT_BITS = 16,
    parameter integer DOUT_BITS = 16,
    parameter integer DERIV = 1,
    parameter integer T_FRAC = 24,
    parameter integer P_FRAC = 22,
    parameter integer K_FRAC = 22,
    parameter integer IN_REG = 0,
    parameter integer OUT_SKID = 0
) (
`include "np_pipe_ports.vh"
    input wire [15:0] x,
    input wire [15:0] y,
    input wire [15:0] z,
    output wire [OUT_BITS-1:0] f,
    output wire [DOUT_BITS-1:0] dfdx,
    output wire [DOUT_BITS-1:0] dfdy,
    output wire [DOUT_BITS-1:0] dfdz
);
    localparam integer N = OUT_BITS, ND = DOUT_BITS, WT = T_FRAC, WP = P_FRAC, WK = K_FRAC;
    localparam integer NB = DERIV != 0 ? 10 : 9;  // banks = latency
    localparam integer OW = N + 3 * ND;           // the output bundle
    localparam integer XW = 96;                   // width of the M..O arithmetic (never wraps)
    // TIGHT (WT >= 9 and WP >= 9): the widths of the datapath declaration
    // (np_simplex_datapath, its range argument; every configuration of the
    // key ranges with WT, WP >= 9 is checked to fit them by the test
    // simplex.rtl_widths), and neither output can leave its range, so the
    // saturation is left out. Otherwise the widths that never wrap at any
    // configuration (|tau^k| < 1, |G.D| <= 9) and the saturation.
    localparam integer TIGHT = (WT >= 9 && WP >= 9) ? 1 : 0;
    localparam integer FW = TIGHT != 0 ? WP : WP + 6;       // fc: |.| < 9 * 2^WP (+ rounding)
    localparam integer QW = TIGHT != 0 ? WP + 1 : WP + 6;   // q: the same bound
    localparam integer Q5W = TIGHT != 0 ? WP + 3 : WP + 9;  // 5q
    localparam integer MW = TIGHT != 0 ? WP + 1 : WP + 8;   // m: |.| < 34 * 2^WP
    localparam integer EW = TIGHT != 0 ? WP + 1 : WP + 2;   // e: |.| <= 2^WP
    localparam integer DW = TIGHT != 0 ? WP + 1 : WP + 9;   // e_a - m_a: |.| < 35 * 2^WP
    localparam integer SW = TIGHT != 0 ? WP + 1 : WP + 10;  // S, Q_a: sums of four
    // The constants Kf' = round(Kf 2^WK), Kd' = round(Kd 2^WK) (np_simplex_kf/kd).
    localparam [63:0] KF = ((64'd8388608 << WK) + 64'd6150937) / 64'd12301875;
    localparam [63:0] KD = ((64'd8388608 << WK) + 64'd2050312) / 64'd4100625;
    // Their canonical signed digits (non-adjacent form): the positions of the
    // +1 digits and of the -1 digits. O multiplies by a constant as the
    // declaration prices it: one shifted operand per non-zero digit.
    // csd_digits; requant = np_simplex_requant at XW bits
`include "np_fixed.vh"
    localparam [63:0] KF_P = csd_digits(KF, 0), KF_N = csd_digits(KF, 1);
    localparam [63:0] KD_P = csd_digits(KD, 0), KD_N = csd_digits(KD, 1);

    // ---------------------------------------------------------------- handshake
    wire core_in_valid, core_in_ready, core_out_valid, core_out_ready;
    wire [15:0] cx, cy, cz;
    wire [OW-1:0] core_out;
    reg [NB-1:0] v;
    wire [NB-1:0] en, v_next;  // NP_FAULT_STALL: bank KT overwrites its content when its successor stalls
    np_pipe_ctrl #(.NB(NB), .STALL_BANK(3)) u_ctrl (.v(v), .in_valid(core_in_valid), .out_ready(core_out_ready),
        .en(en), .v_next(v_next), .in_ready(core_in_ready), .out_valid(core_out_valid));
    always @(posedge clk) if (rst) v <= {NB{1'b0}}; else v <= v_next;
    // Bank indices.
    localparam integer B_M = 6, B_A = NB - 2, B_O = NB - 1;


    // ---------------------------------------------------------------- SK
    // Skewed numerators SX = 4X + (Y + Z) (u19) and cells floor(SX / 768) =
    // (683 nn) >> 11 with nn = SX >> 8 (u9; exact for nn < 2048), 683 nn as
    // the declaration's chain of shift-adds: 5 nn, 11 nn, 341 nn = 32 (11 nn)
    // - 11 nn, 683 nn = 2 (341 nn) + nn.
    function [8:0] cell_of;
        input [15:0] a, b, c;
        reg [16:0] bc;
        reg [18:0] sx;
        reg [12:0] n5;
        reg [14:0] n11;
        reg [19:0] n341;
        reg [19:0] n683;
        begin
            bc = {1'b0, b} + {1'b0, c};
            sx = {1'b0, a, 2'b00} + {2'b00, bc};
            n5 = {sx[18:8], 2'b00} + {2'b00, sx[18:8]};
            n11 = {1'b0, n5, 1'b0} + {4'd0, sx[18:8]};
            n341 = {n11, 5'd0} - {5'd0, n11};  // < 2^19: bit 19 is 0
            n683 = {n341[18:0], 1'b0} + {9'd0, sx[18:8]};
            cell_of = n683[19:11];
        end
    endfunction
    reg [15:0] r0_x, r0_y, r0_z;
    reg [8:0] r0_i, r0_j, r0_k;
    always @(posedge clk) if (en[0] && core_in_valid) begin
        r0_x <= cx;
        r0_y <= cy;
        r0_z <= cz;
        r0_i <= cell_of(cx, cy, cz);
        r0_j <= cell_of(cy, cz, cx);
        r0_k <= cell_of(cz, cx, cy);
    end

    // ---------------------------------------------------------------- RK
    // U = 6X - 1536 i + 256 n (s12, exact), then Appendix B's ranking.
    wire [10:0] n_sum = {2'b00, r0_i} + {2'b00, r0_j} + {2'b00, r0_k};
    function signed [11:0] offset;
        input [15:0] a;
        input [8:0] i;
        input [10:0] n;
        reg signed [23:0] t;
        begin
            t = $signed({8'd0, a} * 24'd6) - $signed({15'd0, i} * 24'd1536) + $signed({13'd0, n} * 24'd256);
            offset = t[11:0];
        end
    endfunction
    wire signed [11:0] ou = offset(r0_x, r0_i, n_sum), ov = offset(r0_y, r0_j, n_sum),
                       ow = offset(r0_z, r0_k, n_sum);
    wire uw = ou >= ow, uv = ou >= ov, vw = ov >= ow;
    wire [1:0] hi = uw ? (uv ? 2'd0 : 2'd1) : (vw ? 2'd1 : 2'd2);
    wire [1:0] lo = !uw ? (!uv ? 2'd0 : 2'd1) : (!vw ? 2'd1 : 2'd2);
    reg signed [11:0] r1_off[0:2];
    reg [1:0] r1_hi, r1_lo;
    reg [7:0] r1_cell[0:2];  // the hash reads the skewed corner mod 256
    always @(posedge clk) if (en[1] && v[0]) begin
        r1_off[0] <= ou;
        r1_off[1] <= ov;
        r1_off[2] <= ow;
        r1_hi <= hi;
        r1_lo <= lo;
        r1_cell[0] <= r0_i[7:0];
        r1_cell[1] <= r0_j[7:0];
        r1_cell[2] <= r0_k[7:0];
    end

    // ---------------------------------------------------------------- CH
    // The hash (hash6) and the gradient decode (grad_fields): np_hash.vh.
`include "np_hash.vh"
    // np_grad_decode as three coefficients in {-1, 0, 1} (s2 each): {cz, cy, cx}.
    function [5:0] coefs;
        input [5:0] h;
        reg [10:0] gf;
        reg signed [1:0] cc[0:2];
        integer a;
        begin
            gf = grad_fields(h);
            for (a = 0; a < 3; a = a + 1) cc[a] = 2'sd0;
            cc[gf[1:0]] = gf[6] ? -2'sd1 : 2'sd1;  // p, q and r are distinct axes
            if (gf[9]) cc[gf[3:2]] = gf[7] ? -2'sd1 : 2'sd1;
            if (gf[10]) cc[gf[5:4]] = gf[8] ? -2'sd1 : 2'sd1;
            coefs = {cc[2], cc[1], cc[0]};
        end
    endfunction
    // The corner's skewed offset as a_ch mask (bit a_ch = axis a_ch): 0, e_hi, 7 - e_lo, 7.
    function [2:0] corner_mask;
        input [1:0] hi_, lo_;
        input integer c;
        begin
            case (c)
                0: corner_mask = 3'b000;
                1: corner_mask = 3'b001 << hi_;
                2: corner_mask = 3'b111 & ~(3'b001 << lo_);
                default: corner_mask = 3'b111;
            endcase
        end
    endfunction
    reg signed [11:0] r2_d[0:11];    // D of corner c_ch, axis a_ch at [3c + a_ch]: s12
    reg [5:0] r2_g[0:3];             // coefficients {cz, cy, cx}
    reg signed [12:0] r2_gd[0:3];    // G . D: s13 (|G . D| <= |D|_1 <= sqrt(3) 1536 < 2661)
    integer c_ch, a_ch;  // loop variables: one pair per process
    reg [2:0] msk;
    reg signed [12:0] dsum;
    reg signed [11:0] dd[0:2];
    reg [5:0] gg;
    always @(posedge clk) if (en[2] && v[1]) begin
        for (c_ch = 0; c_ch < 4; c_ch = c_ch + 1) begin
            msk = corner_mask(r1_hi, r1_lo, c_ch);
            for (a_ch = 0; a_ch < 3; a_ch = a_ch + 1) begin
                dd[a_ch] = r1_off[a_ch] - (msk[a_ch] ? 12'sd1536 : 12'sd0) + $signed(12'd256 * c_ch[11:0]);
                r2_d[3*c_ch+a_ch] <= dd[a_ch];
            end
            gg = coefs(hash6(r1_cell[0] + {7'd0, msk[0]}, r1_cell[1] + {7'd0, msk[1]},
                             r1_cell[2] + {7'd0, msk[2]}));
            dsum = 13'sd0;
            for (a_ch = 0; a_ch < 3; a_ch = a_ch + 1)
                if (gg[2*a_ch+:2] == 2'b01) dsum = dsum + {dd[a_ch][11], dd[a_ch]};
                else if (gg[2*a_ch+:2] == 2'b11) dsum = dsum - {dd[a_ch][11], dd[a_ch]};
            r2_g[c_ch] <= gg;
            r2_gd[c_ch] <= dsum;
        end
    end

    // ---------------------------------------------------------------- KT
    // R2 = |D|^2 (u22), T = max(0, 7077888 - 5 R2) (u23). Each D_a^2 is the
    // square of |D_a| <= 1536 (u11): a conditional negate, then an 11-bit squarer.
    integer c_kt, a_kt;
    reg [22:0] r3_t[0:3];
    reg signed [11:0] r3_d[0:11];
    reg [5:0] r3_g[0:3];
    reg signed [12:0] r3_gd[0:3];
    reg [21:0] r2sq;
    reg signed [24:0] td;
    reg [21:0] sq[0:2];
    reg signed [11:0] dn;
    reg [10:0] dab;
    always @(posedge clk) if (en[3] && v[2]) begin
        for (c_kt = 0; c_kt < 4; c_kt = c_kt + 1) begin
            for (a_kt = 0; a_kt < 3; a_kt = a_kt + 1) begin
                dn = r2_d[3*c_kt+a_kt][11] ? -r2_d[3*c_kt+a_kt] : r2_d[3*c_kt+a_kt];
                dab = dn[10:0];
                sq[a_kt] = {11'd0, dab} * {11'd0, dab};
            end
            r2sq = sq[0] + sq[1] + sq[2];
            td = 25'sd7077888 - $signed({3'd0, r2sq} * 25'd5);
            r3_t[c_kt] <= td > 25'sd0 ? td[22:0] : 23'd0;
            r3_g[c_kt] <= r2_g[c_kt];
            r3_gd[c_kt] <= r2_gd[c_kt];
        end
        for (a_kt = 0; a_kt < 12; a_kt = a_kt + 1) r3_d[a_kt] <= r2_d[a_kt];
    end

    // ---------------------------------------------------------------- P2
    // tau2 = round(T^2 / 2^(46 - WT)), u(WT).
    integer c_p2, a_p2;
    reg [WT-1:0] r4_tau2[0:3];
    reg [22:0] r4_t[0:3];
    reg signed [11:0] r4_d[0:11];
    reg [5:0] r4_g[0:3];
    reg signed [12:0] r4_gd[0:3];
    reg [46:0] tsq;
    always @(posedge clk) if (en[4] && v[3]) begin
        for (c_p2 = 0; c_p2 < 4; c_p2 = c_p2 + 1) begin
            tsq = {24'd0, r3_t[c_p2]} * {24'd0, r3_t[c_p2]};
            tsq = (tsq + (47'd1 << (45 - WT))) >> (46 - WT);
            r4_tau2[c_p2] <= tsq[WT-1:0];
            r4_t[c_p2] <= r3_t[c_p2];
            r4_g[c_p2] <= r3_g[c_p2];
            r4_gd[c_p2] <= r3_gd[c_p2];
        end
        for (a_p2 = 0; a_p2 < 12; a_p2 = a_p2 + 1) r4_d[a_p2] <= r3_d[a_p2];
    end

    // ---------------------------------------------------------------- P4
    // tau4 = round(tau2^2 / 2^WT), tau3 = round(tau2 T / 2^23), u(WT).
    integer c_p4, a_p4;
    reg [WT-1:0] r5_tau4[0:3], r5_tau3[0:3];
    reg signed [11:0] r5_d[0:11];
    reg [5:0] r5_g[0:3];
    reg signed [12:0] r5_gd[0:3];
    reg [61:0] pp;
    always @(posedge clk) if (en[5] && v[4]) begin
        for (c_p4 = 0; c_p4 < 4; c_p4 = c_p4 + 1) begin
            pp = {{(62-WT){1'b0}}, r4_tau2[c_p4]} * {{(62-WT){1'b0}}, r4_tau2[c_p4]};
            pp = (pp + (62'd1 << (WT - 1))) >> WT;
            r5_tau4[c_p4] <= pp[WT-1:0];
            pp = {{(62-WT){1'b0}}, r4_tau2[c_p4]} * {39'd0, r4_t[c_p4]};
            pp = (pp + (62'd1 << 22)) >> 23;
            r5_tau3[c_p4] <= DERIV != 0 ? pp[WT-1:0] : {WT{1'b0}};
            r5_g[c_p4] <= r4_g[c_p4];
            r5_gd[c_p4] <= r4_gd[c_p4];
        end
        for (a_p4 = 0; a_p4 < 12; a_p4 = a_p4 + 1) r5_d[a_p4] <= r4_d[a_p4];
    end

    // ---------------------------------------------------------------- M
    // fc = round(tau4 gd) and q = round(tau3 gd) from WT + 9 to WP bits;
    // e_a = round(G_a tau4) from WT to WP bits (the sign applied first).
    integer c_mm, a_mm;
    reg signed [FW-1:0] r6_fc[0:3];
    reg signed [QW-1:0] r6_q[0:3];
    reg signed [EW-1:0] r6_e[0:11];
    reg signed [11:0] r6_d[0:11];
    reg signed [XW-1:0] wt4, wt3, wgd, wr;
    always @(posedge clk) if (en[B_M] && v[B_M-1]) begin
        for (c_mm = 0; c_mm < 4; c_mm = c_mm + 1) begin
            wt4 = {{(XW-WT){1'b0}}, r5_tau4[c_mm]};
            wt3 = {{(XW-WT){1'b0}}, r5_tau3[c_mm]};
            wgd = {{(XW-13){r5_gd[c_mm][12]}}, r5_gd[c_mm]};
            wr = requant(wt4 * wgd, WT + 9, WP);
            r6_fc[c_mm] <= wr[FW-1:0];
            wr = requant(wt3 * wgd, WT + 9, WP);
            r6_q[c_mm] <= DERIV != 0 ? wr[QW-1:0] : {QW{1'b0}};
            for (a_mm = 0; a_mm < 3; a_mm = a_mm + 1) begin
                if (r5_g[c_mm][2*a_mm+:2] == 2'b01) wr = requant(wt4, WT, WP);
                else if (r5_g[c_mm][2*a_mm+:2] == 2'b11) wr = requant(-wt4, WT, WP);
                else wr = 0;
                r6_e[3*c_mm+a_mm] <= DERIV != 0 ? wr[EW-1:0] : {EW{1'b0}};
            end
        end
        for (a_mm = 0; a_mm < 12; a_mm = a_mm + 1) r6_d[a_mm] <= r5_d[a_mm];
    end

    // ---------------------------------------------------------------- M2 (DERIV)
    // 5q = 4q + q (Q5W bits); m_a = round(5 q D_a / 2^11), WP bits.
    wire signed [FW-1:0] a_fc[0:3];
    wire signed [EW-1:0] a_e[0:11];
    wire signed [MW-1:0] a_m[0:11];
    genvar gc;
    generate
        if (DERIV != 0) begin : g_m2
            reg signed [FW-1:0] r7_fc[0:3];
            reg signed [EW-1:0] r7_e[0:11];
            reg signed [MW-1:0] r7_m[0:11];
            reg signed [Q5W-1:0] q5n;
            reg signed [XW-1:0] q5, md;
            integer c2, a2;
            always @(posedge clk) if (en[7] && v[6]) begin
                for (c2 = 0; c2 < 4; c2 = c2 + 1) begin
                    q5n = {{(Q5W-QW){r6_q[c2][QW-1]}}, r6_q[c2]};
                    q5n = (q5n <<< 2) + q5n;
                    q5 = {{(XW-Q5W){q5n[Q5W-1]}}, q5n};
                    for (a2 = 0; a2 < 3; a2 = a2 + 1) begin
                        md = {{(XW-12){r6_d[3*c2+a2][11]}}, r6_d[3*c2+a2]};
                        md = requant(q5 * md, 11, 0);
                        r7_m[3*c2+a2] <= md[MW-1:0];
                        r7_e[3*c2+a2] <= r6_e[3*c2+a2];
                    end
                    r7_fc[c2] <= r6_fc[c2];
                end
            end
            for (gc = 0; gc < 12; gc = gc + 1) begin : g_em
                assign a_e[gc] = r7_e[gc];
                assign a_m[gc] = r7_m[gc];
            end
            for (gc = 0; gc < 4; gc = gc + 1) begin : g_fc
                assign a_fc[gc] = r7_fc[gc];
            end
        end else begin : g_no_m2
            for (gc = 0; gc < 12; gc = gc + 1) begin : g_em
                assign a_e[gc] = {EW{1'b0}};
                assign a_m[gc] = {MW{1'b0}};
            end
            for (gc = 0; gc < 4; gc = gc + 1) begin : g_fc
                assign a_fc[gc] = r6_fc[gc];
            end
            wire unused_m = &{1'b0, r6_q[0], r6_q[1], r6_q[2], r6_q[3], r6_e[0], r6_d[0]};
        end
    endgenerate

    // ---------------------------------------------------------------- A
    // S = the sum of the four fc; Q_a = the sum of the four e_a - m_a (each
    // difference fits DW bits). Computed in XW bits and kept mod 2^SW (only
    // the low bits of a sum depend on the low bits of its terms): the sum
    // fits SW bits (the range argument when TIGHT), so it is exact.
    integer c_a, a_a;
    reg signed [SW-1:0] r8_s;
    reg [3*SW-1:0] r8_q;  // Q_x, Q_y, Q_z: [SW*a +: SW]
    reg signed [XW-1:0] acc, dem;
    always @(posedge clk) if (en[B_A] && v[B_A-1]) begin
        acc = 0;
        for (c_a = 0; c_a < 4; c_a = c_a + 1) acc = acc + {{(XW-FW){a_fc[c_a][FW-1]}}, a_fc[c_a]};
        r8_s <= acc[SW-1:0];
        for (a_a = 0; a_a < 3; a_a = a_a + 1) begin
            acc = 0;
            for (c_a = 0; c_a < 4; c_a = c_a + 1) begin
                dem = {{(XW-EW){a_e[3*c_a+a_a][EW-1]}}, a_e[3*c_a+a_a]}
                    - {{(XW-MW){a_m[3*c_a+a_a][MW-1]}}, a_m[3*c_a+a_a]};
                acc = acc + {{(XW-DW){dem[DW-1]}}, dem[DW-1:0]};
            end
            r8_q[SW*a_a+:SW] <= acc[SW-1:0];
        end
    end

    // ---------------------------------------------------------------- O
    // f = round(Kf' S) to sN Q-1.N; df_a = round(Kd' Q_a) to sND Q1.(ND-2),
    // Kf' S and Kd' Q_a as sums of the operand shifted to each signed digit;
    // each saturated unless TIGHT (then the rounded word always fits).
    function [N-1:0] sat_f;
        input signed [XW-1:0] val;
        reg signed [XW-1:0] hi_, lo_;
        begin
            hi_ = (96'sd1 <<< (N - 1)) - 96'sd1;
            lo_ = -(96'sd1 <<< (N - 1));
            sat_f = TIGHT != 0 ? val[N-1:0] : val > hi_ ? hi_[N-1:0] : val < lo_ ? lo_[N-1:0] : val[N-1:0];
        end
    endfunction
    function [ND-1:0] sat_d;
        input signed [XW-1:0] val;
        reg signed [XW-1:0] hi_, lo_;
        begin
            hi_ = (96'sd1 <<< (ND - 1)) - 96'sd1;
            lo_ = -(96'sd1 <<< (ND - 1));
            sat_d = TIGHT != 0 ? val[ND-1:0] : val > hi_ ? hi_[ND-1:0] : val < lo_ ? lo_[ND-1:0] : val[ND-1:0];
        end
    endfunction
    integer a_o, k_o;
    reg [OW-1:0] r9_out;
    reg signed [XW-1:0] kprod, ws;
    reg [OW-1:0] o_w;
    always @(*) begin
        ws = {{(XW-SW){r8_s[SW-1]}}, r8_s};
        kprod = 0;
        for (k_o = 0; k_o < 64; k_o = k_o + 1) begin
            if (KF_P[k_o]) kprod = kprod + (ws <<< k_o);
            if (KF_N[k_o]) kprod = kprod - (ws <<< k_o);
        end
        o_w[OW-1-:N] = sat_f(requant(kprod, WK + WP, N));
        for (a_o = 0; a_o < 3; a_o = a_o + 1) begin
            ws = {{(XW-SW){r8_q[SW*a_o+SW-1]}}, r8_q[SW*a_o+:SW]};
            kprod = 0;
            for (k_o = 0; k_o < 64; k_o = k_o + 1) begin
                if (KD_P[k_o]) kprod = kprod + (ws <<< k_o);
                if (KD_N[k_o]) kprod = kprod - (ws <<< k_o);
            end
            o_w[ND*(2-a_o)+:ND] = DERIV != 0 ? sat_d(requant(kprod, WK + WP, ND - 2)) : {ND{1'b0}};
        end
`ifdef NP_FAULT_FLIP
        if (r8_s[3:0] == 4'h5) o_w[OW-N] = !o_w[OW-N];  // fault: bit 0 of f, 1 input in 16
`endif
    end
    always @(posedge clk) if (en[B_O] && v[B_O-1]) r9_out <= o_w;
    assign core_out = r9_out;

    // ---------------------------------------------------------------- options
    wire [OW-1:0] out_w;
    np_pipe_opts #(.IW(48), .OW(OW), .IN_REG(IN_REG), .OUT_SKID(OUT_SKID)) u_opts (.clk(clk), .rst(rst),
        .in_valid(in_valid), .in_ready(in_ready), .in_data({x, y, z}),
        .core_in_valid(core_in_valid), .core_in_ready(core_in_ready), .core_in_data({cx, cy, cz}),
        .core_out_valid(core_out_valid), .core_out_ready(core_out_ready), .core_out_data(core_out),
        .out_valid(out_valid), .out_ready(out_ready), .out_data(out_w));
    assign {f, dfdx, dfdy, dfdz} = out_w;
endmodule
/* verilator lint_on UNUSEDSIGNAL */
/* verilator lint_on BLKSEQ */
