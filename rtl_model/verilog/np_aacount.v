// SPDX-License-Identifier: MIT
// np_aacount - reference RTL of the sample-count unit aacount (Hollaender,
// Boubekeur and Eisemann, "Adaptive Supersampling for Deferred Anti-Aliasing",
// JCGT 2013; shared/seeds/001), written from the bit-exact specification
// rtl_model/np_aacount.h and its parallel cycle model np_aacount_pipe_init
// (np_pipe.h). Verilog-2005, synthesizable; Icarus and Verilator -Wall clean.
//
// Parameters are the unit's configuration keys (noisepipe units --unit aacount):
//   M          1..4, n = M^2 samples a window
//   DEPTH      1: the depth-variance metric is built (sd), 0: sd = 0
//   NORMAL     1: the normal-cone metric is built (sn), 0: sn = 0
//   LUMA       1: the luma-range metric is built (ss), 0: ss = 0
//   LUMA_TAPS  4: the four neighbours (the paper), 5: and the centre
//   C_D        u32, c_d per (depth range)^2
//   C_N        u8 Q6.2, the code of 4 c_n
//   C_S        u16 Q12.4, the code of 16 c_s
//   T_MIN      u8, luma code;  T_EDGE  u8 Q0.8
//   SERIAL     must be 0: this module is the parallel variant (one window a
//              clock); the serial variant (one beat a clock) is not built here
//   TILE       not a parameter: the 6 x 6 tile maximum runs after the unit
// and the pipe options IN_REG and OUT_SKID (np_pipe.h, np_classic3.v).
// The host's threshold registers (np_aacount_regs_compute: vd[j] u57, na[j]
// u32, na_on[j], nd u32, rs[j] u9) are constants of the parameters here,
// computed by the same exact integer formulas (constant functions below).
//
// Ports:
//   bus   [BUS_BITS-1:0]  the window bus of np_aacount_bus_pack: beat i at
//                         bits [i B, (i+1) B), B = 24 DEPTH + 24 NORMAL, from
//                         its lowest bit up d (u24 Q0.24), nx, ny, nz (s8
//                         Q0.7 each); then at n B the five lumas (u8 each:
//                         centre, left, right, up, down) when LUMA
//   s     u5   samples to shade, 1..n
//   mask  u16  bit b*M + a set iff B_M[b][a] < s (the paper's matrices)
//   sd, sn, ss  u5  the count of each metric (0 when the metric is not built)
//
// Banks = latency 4: A (sums, luma extremes), V (variance, dots, norms, luma
// range and gate), P (squares p, q, the least ratio, sd, ss), C (sn, s, mask);
// the handshake is np_pipe's (see np_classic3.v). Signal formats are those of
// np_aacount.h; the widths are the datapath declaration's (np_aacount_datapath,
// widths_of: the window's extremes for this M).
// Lint waivers (Verilator -Wall), each for the whole file:
//   BLKSEQ       the clocked processes compute per-sample temporaries with
//                blocking assignments (written before read, local to one
//                process); every register is assigned with <=.
//   UNUSEDSIGNAL wide temporaries whose upper bits are provably 0, and the
//                padding of the bus.
/* verilator lint_off BLKSEQ */
/* verilator lint_off UNUSEDSIGNAL */
module np_aacount #(
    parameter integer M = 3,
    parameter integer DEPTH = 1,
    parameter integer NORMAL = 1,
    parameter integer LUMA = 1,
    parameter integer LUMA_TAPS = 4,
    parameter integer SERIAL = 0,
    parameter [31:0] C_D = 32'd1000000,
    parameter [7:0] C_N = 8'd32,
    parameter [15:0] C_S = 16'd128,
    parameter [7:0] T_MIN = 8'd16,
    parameter [7:0] T_EDGE = 8'd32,
    parameter integer IN_REG = 0,
    parameter integer OUT_SKID = 0,
    // derived (do not set): the bus width of np_aacount_bus_bits
    parameter integer BUS_BITS = M * M * ((DEPTH != 0 ? 24 : 0) + (NORMAL != 0 ? 24 : 0)) + (LUMA != 0 ? 40 : 0)
) (
`include "np_pipe_ports.vh"
    input wire [BUS_BITS-1:0] bus,
    output wire [4:0] s,
    output wire [15:0] mask,
    output wire [4:0] sd,
    output wire [4:0] sn,
    output wire [4:0] ss
);
    localparam integer N = M * M;
    localparam integer BEAT = (DEPTH != 0 ? 24 : 0) + (NORMAL != 0 ? 24 : 0);
    localparam integer NB = 4;   // banks = latency
    localparam integer OW = 36;  // {s, mask, sd, sn, ss}

    // bits of an unsigned value (np_bits_for_range(0, x, 0))
    function integer ubits;
        input [63:0] x;
        integer b;
        begin
            ubits = 1;
            for (b = 1; b < 63; b = b + 1) if ((x >> b) != 0) ubits = b + 1;
        end
    endfunction
    localparam [63:0] DMAX = 64'd16777215;
    localparam integer WSD = ubits(N * DMAX);                                  // sum_d
    localparam integer WSD2 = ubits(N * DMAX * DMAX);                          // sum_d2
    function [63:0] u64;
        input integer x;
        u64 = {32'd0, x};
    endfunction
    localparam [63:0] N64 = u64(N);
    localparam integer WV = ubits((N64 * N64 - (N64 % 64'd2)) / 64'd4 * DMAX * DMAX);  // v
    localparam integer WNB = ubits(128 * N) + 1;                               // nbar, signed
    localparam integer WDOT = ubits(3 * 128 * 128 * N) + 1;                    // dot, signed
    localparam integer WNB2 = ubits(3 * 128 * 128 * N * N);                    // nb2
    localparam integer WNN2 = 16;                                              // nn2
    // p, q: the product in 64-bit constants. Written as (3 128^2 N)^2 in integers it
    // overflows 32 bits (at M = 2 it is 9 2^32: 0 modulo 2^32); Icarus and Verilator
    // size it by the 64-bit formal, Yosys 0.23 evaluates it in 32 bits (WP = 32 at M = 3,
    // 1 at M = 2: a netlist narrower than the simulated RTL).
    localparam [63:0] DOTMAX = 64'd49152 * N64;
    localparam integer WP = ubits(DOTMAX * DOTMAX);

    // ---------------------------------------------------------------- thresholds
    // np_aacount_regs_compute, exactly: vd[j] u57 (2^56 = never), na[j] u32
    // with na_on[j], nd u32, rs[j] u9 (256 = never).
    function [56:0] vd_of;
        input integer j;
        reg [63:0] q, jn;
        begin
            if (C_D == 32'd0) vd_of = 57'h100000000000000;
            else begin
                jn = j * N * N;  // < 2^8: j n^2 2^48 < 2^60
                q = (jn << 48) / {32'd0, C_D} + 64'd1;
                vd_of = q < 64'h0100000000000000 ? q[56:0] : 57'h100000000000000;
            end
        end
    endfunction
    function [32:0] na_of;  // {na_on, na}
        input integer j;
        reg [63:0] c2, t, sq;
        begin
            c2 = {56'd0, C_N} * {56'd0, C_N};
            t = 16 * j * j;
            if (c2 > t) begin
                sq = (c2 - t) * (c2 - t);  // < 2^32
                na_of = {1'b1, sq[31:0]};
            end
            else na_of = 33'd0;
        end
    endfunction
    function [8:0] rs_of;
        input integer j;
        reg [31:0] q;
        begin
            if (C_S == 16'd0) rs_of = 9'd256;
            else begin
                q = 4080 * j / {16'd0, C_S} + 1;
                rs_of = q < 256 ? q[8:0] : 9'd256;
            end
        end
    endfunction
    localparam [63:0] C2 = {56'd0, C_N} * {56'd0, C_N};
    localparam [63:0] ND64 = C2 * C2;  // C^4 < 2^32
    localparam [31:0] ND = ND64[31:0];

    // the paper's matrices B_M[b][a] as the mask of s samples (np_aacount_mask)
    function [15:0] mask_of;
        input [4:0] sv;
        integer a, b;
        reg [3:0] bm;
        begin
            mask_of = 16'd0;
            for (b = 0; b < M; b = b + 1)
                for (a = 0; a < M; a = a + 1) begin
                    case (M)
                        2: bm = b == 0 ? (a == 0 ? 4'd0 : 4'd2) : (a == 0 ? 4'd3 : 4'd1);
                        3: case (b * 3 + a)
                               0: bm = 4'd2; 1: bm = 4'd6; 2: bm = 4'd3;
                               3: bm = 4'd5; 4: bm = 4'd0; 5: bm = 4'd8;
                               6: bm = 4'd1; 7: bm = 4'd7; default: bm = 4'd4;
                           endcase
                        4: case (b * 4 + a)
                               0: bm = 4'd1; 1: bm = 4'd8; 2: bm = 4'd2; 3: bm = 4'd10;
                               4: bm = 4'd12; 5: bm = 4'd4; 6: bm = 4'd14; 7: bm = 4'd6;
                               8: bm = 4'd3; 9: bm = 4'd11; 10: bm = 4'd0; 11: bm = 4'd9;
                               12: bm = 4'd15; 13: bm = 4'd7; 14: bm = 4'd13; default: bm = 4'd5;
                           endcase
                        default: bm = 4'd0;
                    endcase
                    if ({1'b0, bm} < sv) mask_of[b * M + a] = 1'b1;
                end
        end
    endfunction

    // ---------------------------------------------------------------- handshake
    wire core_in_valid, core_in_ready, core_out_valid, core_out_ready;
    wire [BUS_BITS-1:0] cbus;
    wire [OW-1:0] core_out;
    reg [NB-1:0] v;
    wire [NB-1:0] en, v_next;  // NP_FAULT_STALL: bank V overwrites its content when its successor stalls
    np_pipe_ctrl #(.NB(NB), .STALL_BANK(1)) u_ctrl (.v(v), .in_valid(core_in_valid), .out_ready(core_out_ready),
        .en(en), .v_next(v_next), .in_ready(core_in_ready), .out_valid(core_out_valid));
    always @(posedge clk) if (rst) v <= {NB{1'b0}}; else v <= v_next;

    // ---------------------------------------------------------------- A
    // sum_d u28, sum_d2 u52, nbar s12 (at M = 4; WSD, WSD2, WNB bits), any_n,
    // lmax, lmin u8; the normals (n x 3 x s8) wait in the bank for V.
    wire [BUS_BITS+63:0] bx = {64'd0, cbus};
    reg [WSD-1:0] ra_sum_d;
    reg [WSD2-1:0] ra_sum_d2;
    reg signed [WNB-1:0] ra_nbar0, ra_nbar1, ra_nbar2;
    reg ra_any_n;
    reg [7:0] ra_lmax, ra_lmin;
    reg [24*N-1:0] ra_nrm;  // sample i: {nz, ny, nx} at [24 i +: 24]
    integer i_a, k_a;
    reg [63:0] sd_a, sd2_a, d_a;
    reg signed [31:0] nb_a0, nb_a1, nb_a2;
    reg any_a;
    reg [7:0] lx_a, ln_a, l_a;
    reg [24*N-1:0] nrm_a;
    always @(*) begin
        sd_a = 64'd0;
        sd2_a = 64'd0;
        nb_a0 = 0;
        nb_a1 = 0;
        nb_a2 = 0;
        any_a = 1'b0;
        nrm_a = {24*N{1'b0}};
        for (i_a = 0; i_a < N; i_a = i_a + 1) begin
            if (DEPTH != 0) begin
                d_a = {40'd0, bx[i_a * BEAT +: 24]};
                sd_a = sd_a + d_a;
                sd2_a = sd2_a + d_a * d_a;
            end
            if (NORMAL != 0) begin
                nrm_a[24 * i_a +: 24] = bx[i_a * BEAT + (DEPTH != 0 ? 24 : 0) +: 24];
                nb_a0 = nb_a0 + {{24{bx[i_a * BEAT + (DEPTH != 0 ? 24 : 0) + 7]}}, bx[i_a * BEAT + (DEPTH != 0 ? 24 : 0) +: 8]};
                nb_a1 = nb_a1 + {{24{bx[i_a * BEAT + (DEPTH != 0 ? 24 : 0) + 15]}}, bx[i_a * BEAT + (DEPTH != 0 ? 24 : 0) + 8 +: 8]};
                nb_a2 = nb_a2 + {{24{bx[i_a * BEAT + (DEPTH != 0 ? 24 : 0) + 23]}}, bx[i_a * BEAT + (DEPTH != 0 ? 24 : 0) + 16 +: 8]};
                if (bx[i_a * BEAT + (DEPTH != 0 ? 24 : 0) +: 24] != 24'd0) any_a = 1'b1;
            end
        end
        lx_a = 8'd0;
        ln_a = 8'd0;
        if (LUMA != 0) begin
            lx_a = bx[N * BEAT + (LUMA_TAPS == 5 ? 0 : 8) +: 8];
            ln_a = lx_a;
            for (k_a = (LUMA_TAPS == 5 ? 1 : 2); k_a < 5; k_a = k_a + 1) begin
                l_a = bx[N * BEAT + 8 * k_a +: 8];
                if (l_a > lx_a) lx_a = l_a;
                if (l_a < ln_a) ln_a = l_a;
            end
        end
    end
    always @(posedge clk) if (en[0] && core_in_valid) begin
        ra_sum_d <= sd_a[WSD-1:0];
        ra_sum_d2 <= sd2_a[WSD2-1:0];
        ra_nbar0 <= nb_a0[WNB-1:0];
        ra_nbar1 <= nb_a1[WNB-1:0];
        ra_nbar2 <= nb_a2[WNB-1:0];
        ra_any_n <= any_a;
        ra_lmax <= lx_a;
        ra_lmin <= ln_a;
        ra_nrm <= nrm_a;
    end

    // ---------------------------------------------------------------- V
    // v = n sum_d2 - sum_d^2 (u53 at M = 3: WV bits, exact, >= 0); nb2 =
    // |nbar|^2 (u24); per sample dot = nbar . nrm (s21) and nn2 = |nrm|^2
    // (u16); r = lmax - lmin (u8) and the gate (r >= t_min and 256 r >=
    // t_edge lmax).
    reg [WV-1:0] rv_v;
    reg [WNB2-1:0] rv_nb2;
    reg [WDOT*N-1:0] rv_dot;
    reg [WNN2*N-1:0] rv_nn2;
    reg [7:0] rv_r;
    reg rv_gate, rv_any_n;
    integer i_v;
    reg [63:0] v_v, nb2_v;
    // The products at their own widths, so that synthesis builds a WNB x 8
    // signed multiplier and an unsigned squarer of a magnitude each (a
    // product written in 32 bits is one of 32-bit operands for Yosys's macc).
    reg [WNB-2:0] m0, m1, m2;             // |nbar_k| <= 128 n: u(WNB-1)
    reg [2*WNB-3:0] q0, q1, q2;           // |nbar_k|^2
    reg signed [7:0] x0, x1, x2;          // the sample's normal, s8 Q0.7
    reg [7:0] a0, a1, a2;                 // |x_k| <= 128: u8
    reg signed [WNB+7:0] pr0, pr1, pr2;   // nbar_k x_k, exact
    reg signed [WDOT-1:0] dot_v;
    reg [WNN2-1:0] nn_v;
    reg [WDOT*N-1:0] dots_v;
    reg [WNN2*N-1:0] nns_v;
    reg [7:0] r_v;
    reg gate_v;
    always @(*) begin
        v_v = 64'd0;
        if (DEPTH != 0)
            v_v = N * {{(64-WSD2){1'b0}}, ra_sum_d2} - {{(64-WSD){1'b0}}, ra_sum_d} * {{(64-WSD){1'b0}}, ra_sum_d};
        // |nbar_k|: a conditional negation; 128 n < 2^(WNB-1), so the top bit is 0
        m0 = ra_nbar0[WNB-1] ? ~ra_nbar0[WNB-2:0] + 1'b1 : ra_nbar0[WNB-2:0];
        m1 = ra_nbar1[WNB-1] ? ~ra_nbar1[WNB-2:0] + 1'b1 : ra_nbar1[WNB-2:0];
        m2 = ra_nbar2[WNB-1] ? ~ra_nbar2[WNB-2:0] + 1'b1 : ra_nbar2[WNB-2:0];
        nb2_v = 64'd0;
        dots_v = {WDOT*N{1'b0}};
        nns_v = {WNN2*N{1'b0}};
        if (NORMAL != 0) begin
            q0 = m0 * m0;
            q1 = m1 * m1;
            q2 = m2 * m2;
            nb2_v = {{(66-2*WNB){1'b0}}, q0} + {{(66-2*WNB){1'b0}}, q1} + {{(66-2*WNB){1'b0}}, q2};
            for (i_v = 0; i_v < N; i_v = i_v + 1) begin
                x0 = ra_nrm[24 * i_v +: 8];
                x1 = ra_nrm[24 * i_v + 8 +: 8];
                x2 = ra_nrm[24 * i_v + 16 +: 8];
                pr0 = ra_nbar0 * x0;
                pr1 = ra_nbar1 * x1;
                pr2 = ra_nbar2 * x2;
                dot_v = pr0[WDOT-1:0] + pr1[WDOT-1:0] + pr2[WDOT-1:0];  // |dot| <= 3 128^2 n: exact in WDOT bits
                a0 = x0[7] ? ~x0 + 8'd1 : x0;  // -128 -> 128 (8'h80 read unsigned)
                a1 = x1[7] ? ~x1 + 8'd1 : x1;
                a2 = x2[7] ? ~x2 + 8'd1 : x2;
                nn_v = {8'd0, a0} * {8'd0, a0} + {8'd0, a1} * {8'd0, a1} + {8'd0, a2} * {8'd0, a2};
                dots_v[WDOT * i_v +: WDOT] = dot_v;
                nns_v[WNN2 * i_v +: WNN2] = nn_v;
            end
        end
        r_v = 8'd0;
        gate_v = 1'b0;
        if (LUMA != 0) begin
            r_v = ra_lmax - ra_lmin;
            gate_v = !(r_v < T_MIN || {r_v, 8'd0} < {8'd0, T_EDGE} * {8'd0, ra_lmax});
        end
    end
    always @(posedge clk) if (en[1] && v[0]) begin
        rv_v <= v_v[WV-1:0];
        rv_nb2 <= nb2_v[WNB2-1:0];
        rv_dot <= dots_v;
        rv_nn2 <= nns_v;
        rv_r <= r_v;
        rv_gate <= gate_v;
        rv_any_n <= ra_any_n;
    end

    // ---------------------------------------------------------------- P
    // p = dot^2, q = nb2 nn2 (u40) per sample; the least p/q over the samples
    // with a normal (cross products p q' < p' q, u80, exact; ties keep the
    // earlier sample): pmin, qmin u40, have_min; sd = 1 + #{j : v >= vd[j]},
    // ss = 1 + gate #{j : r >= rs[j]} (u5).
    reg [WP-1:0] rp_pmin, rp_qmin;
    reg rp_have, rp_nb2_zero, rp_any_n;
    reg [4:0] rp_sd, rp_ss;
    integer i_p, j_p;
    reg [63:0] p_p, q_p, pm_p, qm_p;
    reg signed [31:0] dt_p;
    reg have_p;
    reg [4:0] sd_p, ss_p;
    always @(*) begin
        pm_p = 64'd0;
        qm_p = 64'd0;
        have_p = 1'b0;
        if (NORMAL != 0)
            for (i_p = 0; i_p < N; i_p = i_p + 1) begin
                dt_p = {{(32-WDOT){rv_dot[WDOT * i_p + WDOT - 1]}}, rv_dot[WDOT * i_p +: WDOT]};
                p_p = $signed({{32{dt_p[31]}}, dt_p}) * $signed({{32{dt_p[31]}}, dt_p});
                q_p = {{(64-WNB2){1'b0}}, rv_nb2} * {{(64-WNN2){1'b0}}, rv_nn2[WNN2 * i_p +: WNN2]};
                if (rv_nn2[WNN2 * i_p +: WNN2] != {WNN2{1'b0}} &&
                    (!have_p || {64'd0, p_p} * {64'd0, qm_p} < {64'd0, pm_p} * {64'd0, q_p})) begin
                    pm_p = p_p;
                    qm_p = q_p;
                    have_p = 1'b1;
                end
            end
        sd_p = 5'd0;
        if (DEPTH != 0) begin
            sd_p = 5'd1;
            for (j_p = 1; j_p < N; j_p = j_p + 1) if ({{(57-WV){1'b0}}, rv_v} >= vd_of(j_p)) sd_p = sd_p + 5'd1;
        end
        ss_p = 5'd0;
        if (LUMA != 0) begin
            ss_p = 5'd1;
            for (j_p = 1; j_p < N; j_p = j_p + 1) if (rv_gate && {1'b0, rv_r} >= rs_of(j_p)) ss_p = ss_p + 5'd1;
        end
    end
    always @(posedge clk) if (en[2] && v[1]) begin
        rp_pmin <= pm_p[WP-1:0];
        rp_qmin <= qm_p[WP-1:0];
        rp_have <= have_p;
        rp_nb2_zero <= rv_nb2 == {WNB2{1'b0}};
        rp_any_n <= rv_any_n;
        rp_sd <= sd_p;
        rp_ss <= ss_p;
    end

    // ---------------------------------------------------------------- C
    // sn = 1 + #{j : na_on[j] and pmin nd < na[j] qmin} (u72 products), n when
    // nbar = 0 with some normal (PIN; 1 when nd = 0), 1 with no normal at all;
    // s = max(1, sd, sn, ss); mask = the matrix's s entries.
    reg [OW-1:0] rc_out;
    integer j_c;
    reg [32:0] na_c;
    reg [4:0] sn_c, s_c;
    reg [OW-1:0] o_c;
    always @(*) begin
        na_c = 33'd0;
        sn_c = 5'd0;
        if (NORMAL != 0) begin
            sn_c = 5'd1;
            if (rp_nb2_zero) begin
                if (rp_any_n && ND != 32'd0) sn_c = N64[4:0];
            end else if (rp_have) begin
                for (j_c = 1; j_c < N; j_c = j_c + 1) begin
                    na_c = na_of(j_c);
                    if (na_c[32] && {{(72-WP){1'b0}}, rp_pmin} * {40'd0, ND} < {40'd0, na_c[31:0]} * {{(72-WP){1'b0}}, rp_qmin})
                        sn_c = sn_c + 5'd1;
                end
            end
        end
        s_c = 5'd1;
        if (rp_sd > s_c) s_c = rp_sd;
        if (sn_c > s_c) s_c = sn_c;
        if (rp_ss > s_c) s_c = rp_ss;
        o_c = {s_c, mask_of(s_c), rp_sd, sn_c, rp_ss};
`ifdef NP_FAULT_FLIP
        if (rp_qmin[2:0] == 3'h1) o_c[15] = !o_c[15];  // fault: mask bit 0 when qmin = 1 mod 8
`endif
    end
    always @(posedge clk) if (en[3] && v[2]) rc_out <= o_c;
    assign core_out = rc_out;

    // ---------------------------------------------------------------- options
    wire [OW-1:0] out_w;
    np_pipe_opts #(.IW(BUS_BITS), .OW(OW), .IN_REG(IN_REG), .OUT_SKID(OUT_SKID)) u_opts (.clk(clk), .rst(rst),
        .in_valid(in_valid), .in_ready(in_ready), .in_data(bus),
        .core_in_valid(core_in_valid), .core_in_ready(core_in_ready), .core_in_data(cbus),
        .core_out_valid(core_out_valid), .core_out_ready(core_out_ready), .core_out_data(core_out),
        .out_valid(out_valid), .out_ready(out_ready), .out_data(out_w));
    assign {s, mask, sd, sn, ss} = out_w;

    // SERIAL = 1 is the serial cycle model's circuit, not this one
    generate
        if (SERIAL != 0) begin : g_serial_unsupported
            initial $fatal(1, "np_aacount: SERIAL = 1 is not built by this module (the parallel variant)");
        end
    endgenerate
endmodule
/* verilator lint_on UNUSEDSIGNAL */
/* verilator lint_on BLKSEQ */
