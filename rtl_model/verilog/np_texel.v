// SPDX-License-Identifier: MIT
// np_texel - reference RTL of the per-pixel scanline texturing unit `texel`
// (rtl_model/np_texel.h; docs/fdiff.md, "The per-pixel unit"): span
// descriptors in, one pixel per clock out, the texture of np_texture.h
// evaluated at every pixel. Written from np_texel.h, np_texture.h, np_span.h
// and np_fixed.h; the sequencer is np_span_seq.v (np_span_sim), the engine
// (np_texel_engine: front end, DDAs, pipeline) is this module.
// Verilog-2005, synthesizable; Verilator -Wall clean (waiver below).
//
// Parameters: the unit's configuration keys (noisepipe units, texel)
//   IDX_INT      idx_int      I: index integer bits, 1..11 (10)
//   W_FRAC       w_frac       Fw: colour weight bits, 1..24 (12)
//   GUARD        guard        G: F = Fw + G index fraction bits (20)
//   WEIGHT_FRAC  weight_frac  WT: trilinear weight bits, 1..32 (16)
//   SETUP_MULTS  setup_mults  P: multipliers of the span front end (2)
//   MULT_LAT     mult_lat     Lm: their latency, clocks (2)
// and the texture's octave count (the `texture` key's registers):
//   N_OCT        np_tex_regs.n_oct, 1..8 (wood 1, marble 4): the lanes built.
// The register formats are the defaults (np_tex_regs.k_bits = m_bits = 0:
// k s48 Q23.24, m s24 Q7.16); a scene-sized texture is not supported here.
// Derived: F = Fw + G, W = 1 + I + F (x, N, q: s(W) QI.F), the quadric's
// window QW = 88 + W - F (np_texel_q_window), the amplitude product's
// ALW = 20 + 3 WT + W - F (np_texel_al_window), the weight u(WB) Q1.WT with
// WB = WT + 1 (32 at WT = 32: u32, exact).
//
// Ports: np_span_ports.vh (the texture registers, the span descriptor in,
// the pixel out; shared with np_fdiff.v).
//
// Timing (np_span.h, np_texel.h): 1 clock to accept a descriptor, the front
// end's set-up stall, then one pixel per clock into the nine banks
//   L  I1  I2  I3  A  S  C1  C2  C3
// (np_texel_stages; np_pipe's handshake: bank k loads when it is empty or
// its content moves on). The set-up takes
//   C = quad + N_OCT * oct,  quad = 2 + (ceil(18/P) + Lm - 1) + (ceil(15/P) + Lm - 1),
//   oct = 1 + ceil(p/P) + Lm - 1, p = 6 when every octave's M is diagonal, else 18
// clocks on the front end's engine (np_texel_span_setup_cycles), which runs
// one job at a time: a span begun from idle has its job start in the next
// clock; a descriptor taken into the buffer while a span steps has its job
// start in the next clock or when the engine frees, and the span waits at its
// begin only for what remains (front_begin, front_prefetch). The engine's
// timeline is kept relative to the current clock: fe_rem = clocks until the
// engine is free, nx_rem = clocks until the buffered span's set-up is done.
//
// What the RTL computes where (the bits are the C model's):
//   set-up (at begin, from the descriptor): per octave and axis
//     u0 = round(M s + o) u40 Q8.32 (mod 256), du = round(M ds) s40 Q7.32,
//     each exact at 48 fraction bits and rounded once (half up, np_round_wrap128);
//     the quadric q, dq, d2q (np_tex_quadric_exact) modulo 2^QW (the window
//     the rounding in A reads). NOTE: this RTL computes the set-up as one
//     combinational datapath of the descriptor, loaded at begin; its timing
//     is the schedule's count above. The engine of P pipelined multipliers
//     that the datapath declaration prices (stage FE) is not built here.
//   D (per issued pixel): u += du (mod 2^40), q += dq, dq += d2q (mod 2^QW).
//     (The declaration's s DDA, 3 x s48, is not built: nothing reads s.)
//   L : n[c] u6 = np_hash6(cell + corner) / 64, c = 4cz + 2cy + cx; w[a] =
//       round_half_up(frac(u_a), 32 - WT) u(WB); qx = q (QW bits)
//   I1: l1[p] = n[2p] 2^WT + w0 (n[2p+1] - n[2p])       u(6 + WT), exact
//   I2: l2[p] = l1[2p] 2^WT + w1 (l1[2p+1] - l1[2p])    u(6 + 2 WT), exact
//   I3: l3 = l2[0] 2^WT + w2 (l2[1] - l2[0])            u(6 + 3 WT), exact
//   A : N = a' l3 (mod 2^ALW) rounded once to F bits, s(W); q rounded to F, s(W)
//   S : x = q + sum N (mod 2^W)
//   C1: seg u8, cw u(Fw+1) (np_tex_colour_split)  C2: prod u(8+Fw) x3  C3: rgb u8 x3
//       (np_tex_colour.v, shared with np_fdiff.v)
// Fault copies (the benches and the co-simulation must catch them): NP_FAULT_FLIP
// flips bit 0 of cr when x's 4 low bits are 0101; NP_FAULT_STALL lets bank I2
// overwrite its content under a stall; np_span_seq.v's NP_FAULT_SETUP ends a
// set-up stall after one clock (the bits stay right, the timing does not).
// Lint waivers (Verilator -Wall), each for the whole file:
//   UNUSEDSIGNAL the 128-bit modular temporaries (np_s128 arithmetic, as the
//                C model's) of which each register keeps its declared bits.
/* verilator lint_off UNUSEDSIGNAL */
module np_texel #(
    parameter integer IDX_INT = 10,
    parameter integer W_FRAC = 12,
    parameter integer GUARD = 20,
    parameter integer WEIGHT_FRAC = 16,
    parameter integer SETUP_MULTS = 2,
    parameter integer MULT_LAT = 2,
    parameter integer N_OCT = 1
) (
`include "np_span_ports.vh"
);
    localparam integer WT = WEIGHT_FRAC;
    localparam integer FW = W_FRAC;
    localparam integer F = W_FRAC + GUARD;
    localparam integer W = 1 + IDX_INT + F;
    localparam integer QF = 88;                   // np_tex_q_frac at the default k_frac 24
    localparam integer QW = QF + W - F;           // np_texel_q_window
    localparam integer WB = WT < 32 ? WT + 1 : 32;
    localparam integer L1 = 6 + WT, L2 = 6 + 2 * WT, L3 = 6 + 3 * WT;
    localparam integer NF = 20 + 3 * WT;          // fraction bits of a' l3: 6 + 3 WT + 14
    localparam integer ALW = NF + W - F;          // np_texel_al_window
    localparam integer STALL_W = 16;
    localparam integer PAY_W = 3 * 48 + 3 * 41;
    localparam integer P = SETUP_MULTS, LM = MULT_LAT;
    // np_tex_sched_cycles of np_texel_sched_quad {2; 18, 15} and np_tex_sched_octave{,_diag} {1; 18 | 6}
    localparam integer C_QUAD = 2 + ((18 + P - 1) / P + LM - 1) + ((15 + P - 1) / P + LM - 1);
    localparam integer C_OCT = 1 + (18 + P - 1) / P + LM - 1;
    localparam integer C_OCT_DIAG = 1 + (6 + P - 1) / P + LM - 1;
    localparam integer C_FULL_I = C_QUAD + N_OCT * C_OCT, C_DIAG_I = C_QUAD + N_OCT * C_OCT_DIAG;
    localparam [STALL_W-1:0] C_FULL = C_FULL_I[STALL_W-1:0];
    localparam [STALL_W-1:0] C_DIAG = C_DIAG_I[STALL_W-1:0];
    localparam integer NB = 9;
    localparam integer B_L = 0, B_I1 = 1, B_I2 = 2, B_I3 = 3, B_A = 4, B_S = 5, B_C1 = 6, B_C2 = 7;

`include "np_hash.vh"

    // ---------------------------------------------------------------- sequencer
    wire iss_valid, iss_ready, bg, bg_pf, pf, adv, seq_busy;
    wire [15:0] iss_x, iss_y;
    wire [16:0] bg_n;
    wire [PAY_W-1:0] bg_pay;
    wire [STALL_W-1:0] bg_stall;
    np_span_seq #(.PAY_W(PAY_W), .PREFETCH(1), .STALL_W(STALL_W)) u_seq (
        .clk(clk), .rst(rst),
        .in_valid(in_valid), .in_ready(in_ready), .in_y(in_y), .in_x0(in_x0), .in_n(in_n),
        .in_pay({in_dr, in_dt, in_ds, in_r, in_t, in_s}),
        .iss_valid(iss_valid), .iss_ready(iss_ready), .iss_x(iss_x), .iss_y(iss_y),
        .bg(bg), .bg_pf(bg_pf), .bg_n(bg_n), .bg_pay(bg_pay), .bg_stall(bg_stall),
        .pf(pf), .adv(adv), .adv_stall({STALL_W{1'b0}}), .busy(seq_busy));

    // ---------------------------------------------------------------- set-up timing
    // Every octave's M diagonal: the front end needs 6 products per octave, not 18.
    wire [N_OCT-1:0] offdiag;
    wire diag = offdiag == {N_OCT{1'b0}};
    wire [STALL_W-1:0] c_setup = diag ? C_DIAG : C_FULL;
    reg [STALL_W-1:0] fe_rem, nx_rem;   // clocks until the engine is free / the buffered span's set-up is done
    reg fetched;                        // the buffered span's job is on the engine
    wire [STALL_W-1:0] one = {{(STALL_W - 1){1'b0}}, 1'b1};
    wire [STALL_W-1:0] fe_dec = fe_rem != {STALL_W{1'b0}} ? fe_rem - one : fe_rem;
    wire [STALL_W-1:0] nx_dec = nx_rem != {STALL_W{1'b0}} ? nx_rem - one : nx_rem;
    wire pf_job = pf && in_n != 17'd0;                 // front_prefetch of a non-empty span
    wire [STALL_W-1:0] pf_done = fe_dec + c_setup;     // its job: from max(now + 1, free), C clocks
    wire bg_job = bg && bg_n != 17'd0;                 // front_begin of a non-empty span
    wire bg_fetched = fetched || pf_job;
    wire [STALL_W-1:0] bg_wait = bg_fetched ? (pf_job ? pf_done : nx_dec) : fe_dec + c_setup;
    assign bg_stall = bg_job ? bg_wait : {STALL_W{1'b0}};
    always @(posedge clk) begin
        if (rst) begin
            fe_rem <= {STALL_W{1'b0}};
            nx_rem <= {STALL_W{1'b0}};
            fetched <= 1'b0;
        end else if (bg_job) begin
            fe_rem <= bg_wait;
            nx_rem <= nx_dec;
            fetched <= 1'b0;
        end else if (pf_job) begin
            fe_rem <= pf_done;
            nx_rem <= pf_done;
            fetched <= 1'b1;
        end else begin
            fe_rem <= fe_dec;
            nx_rem <= nx_dec;
        end
    end

    // ---------------------------------------------------------------- handshake (np_pipe)
    reg [NB-1:0] bv;
    wire [NB-1:0] en, bv_next;  // NP_FAULT_STALL: bank I2 overwrites its content when its successor stalls
    np_pipe_ctrl #(.NB(NB), .STALL_BANK(B_I2)) u_ctrl (.v(bv), .in_valid(iss_valid), .out_ready(out_ready),
        .en(en), .v_next(bv_next), .in_ready(iss_ready), .out_valid(out_valid));
    always @(posedge clk) if (rst) bv <= {NB{1'b0}}; else bv <= bv_next;
    wire ld_l = en[B_L] && iss_valid, ld_i1 = en[B_I1] && bv[B_L], ld_i2 = en[B_I2] && bv[B_I1];
    wire ld_i3 = en[B_I3] && bv[B_I2], ld_a = en[B_A] && bv[B_I3], ld_s = en[B_S] && bv[B_A];
    wire ld_c1 = en[B_C1] && bv[B_S], ld_c2 = en[B_C2] && bv[B_C1], ld_c3 = en[NB-1] && bv[B_C2];

    // The pixel's position rides along every bank.
    reg [15:0] xb[0:NB-1], yb[0:NB-1];
    always @(posedge clk) begin
        if (ld_l) begin xb[0] <= iss_x; yb[0] <= iss_y; end
        if (ld_i1) begin xb[1] <= xb[0]; yb[1] <= yb[0]; end
        if (ld_i2) begin xb[2] <= xb[1]; yb[2] <= yb[1]; end
        if (ld_i3) begin xb[3] <= xb[2]; yb[3] <= yb[2]; end
        if (ld_a) begin xb[4] <= xb[3]; yb[4] <= yb[3]; end
        if (ld_s) begin xb[5] <= xb[4]; yb[5] <= yb[4]; end
        if (ld_c1) begin xb[6] <= xb[5]; yb[6] <= yb[5]; end
        if (ld_c2) begin xb[7] <= xb[6]; yb[7] <= yb[6]; end
        if (ld_c3) begin xb[8] <= xb[7]; yb[8] <= yb[7]; end
    end

    // ---------------------------------------------------------------- the begun descriptor, the quadric's set-up
`include "np_tex_quad.vh"
    reg [QW-1:0] q_r, dq_r, d2q_r;
    always @(posedge clk) begin
        if (bg_job) begin
            q_r <= q0_w[QW-1:0];
            dq_r <= q1_w[QW-1:0];
            d2q_r <= q2_w[QW-1:0];
        end else if (adv) begin
            q_r <= q_r + dq_r;
            dq_r <= dq_r + d2q_r;
        end
    end

    // ---------------------------------------------------------------- pipeline: the quadric's banks
    reg [QW-1:0] qx0, qx1, qx2, qx3;
    always @(posedge clk) begin
        if (ld_l) qx0 <= q_r;
        if (ld_i1) qx1 <= qx0;
        if (ld_i2) qx2 <= qx1;
        if (ld_i3) qx3 <= qx2;
    end
    // A: np_tex_to_index(qx, 88, F, W)
    // (QW = QF - F + W: rounding, the top W bits of qx3 + 1/2 LSB; else qx3 shifted up to W bits.)
    wire [W-1:0] q_idx;
    generate
        if (QF > F) begin : g_qround
            wire [QW-1:0] qh = qx3 + ({{(QW - 1){1'b0}}, 1'b1} << (QF - F - 1));
            assign q_idx = qh[QW-1:QF-F];
        end else if (QF == F) begin : g_qexact
            assign q_idx = qx3;
        end else begin : g_qshift
            assign q_idx = {qx3, {(F - QF){1'b0}}};
        end
    endgenerate
    reg [W-1:0] q4;
    always @(posedge clk) if (ld_a) q4 <= q_idx;

    // ---------------------------------------------------------------- octaves
    wire [W*N_OCT-1:0] n_all;   // bank A's N of every octave
    genvar o, ab, a, pp;
    generate
        for (o = 0; o < N_OCT; o = o + 1) begin : g_oct
            // --- octave o's registers and front end (mv, offdiag, amp; u0, du0)
`include "np_tex_front.vh"
            // --- the DDA
            wire [39:0] u_r[0:2];
            for (a = 0; a < 3; a = a + 1) begin : g_axis
                reg [39:0] u_q, du_q;
                always @(posedge clk) begin
                    if (bg_job) begin
                        u_q <= u0[a];
                        du_q <= du0[a];
                    end else if (adv) begin
                        u_q <= u_q + du_q;  // the DDA, mod 256 (u40 Q8.32)
                    end
                end
                assign u_r[a] = u_q;
            end
            // --- L: lattice values and weights
            wire [7:0] ci = u_r[0][39:32], cj = u_r[1][39:32], ck = u_r[2][39:32];
            reg [5:0] n0[0:7];
            wire [WB-1:0] w0[0:2];
            integer c;
            for (a = 0; a < 3; a = a + 1) begin : g_w
                wire [32:0] fr = {1'b0, u_r[a][31:0]};
                wire [32:0] wr;
                if (WT < 32) begin : g_round
                    assign wr = (fr + (33'd1 << (31 - WT))) >> (32 - WT);
                end else begin : g_exact
                    assign wr = fr;
                end
                reg [WB-1:0] w_q;
                always @(posedge clk) if (ld_l) w_q <= wr[WB-1:0];
                assign w0[a] = w_q;
            end
            // (each corner's hash a net of the cell: simulators evaluate it when the cell changes,
            // not every clock)
            genvar cn;
            for (cn = 0; cn < 8; cn = cn + 1) begin : g_corner
                wire [7:0] hi = ci + cn % 2, hj = cj + (cn / 2) % 2, hk = ck + cn / 4;
                wire [5:0] h = hash6(hi, hj, hk);
                always @(posedge clk) if (ld_l) n0[cn] <= h;
            end
            // --- I1: l1[p] = n[2p] 2^WT + w0 (n[2p+1] - n[2p])
            wire [L1-1:0] l1[0:3];
            reg [WB-1:0] w1[1:2];
            for (pp = 0; pp < 4; pp = pp + 1) begin : g_l1
                wire [L1-1:0] la = {{(L1 - 6){1'b0}}, n0[2*pp]}, lb = {{(L1 - 6){1'b0}}, n0[2*pp+1]};
                wire [L1-1:0] lv = (la << WT) + {{(L1 - WB){1'b0}}, w0[0]} * (lb - la);
                reg [L1-1:0] l_q;
                always @(posedge clk) if (ld_i1) l_q <= lv[L1-1:0];
                assign l1[pp] = l_q;
            end
            always @(posedge clk) if (ld_i1) begin w1[1] <= w0[1]; w1[2] <= w0[2]; end
            // --- I2: l2[p] = l1[2p] 2^WT + w1 (l1[2p+1] - l1[2p])
            wire [L2-1:0] l2[0:1];
            reg [WB-1:0] w2;
            for (pp = 0; pp < 2; pp = pp + 1) begin : g_l2
                wire [L2-1:0] la = {{(L2 - L1){1'b0}}, l1[2*pp]}, lb = {{(L2 - L1){1'b0}}, l1[2*pp+1]};
                wire [L2-1:0] lv = (la << WT) + {{(L2 - WB){1'b0}}, w1[1]} * (lb - la);
                reg [L2-1:0] l_q;
                always @(posedge clk) if (ld_i2) l_q <= lv[L2-1:0];
                assign l2[pp] = l_q;
            end
            always @(posedge clk) if (ld_i2) w2 <= w1[2];
            // --- I3: l3 = l2[0] 2^WT + w2 (l2[1] - l2[0])
            reg [L3-1:0] l3;
            wire [L3-1:0] l3a = {{(L3 - L2){1'b0}}, l2[0]}, l3b = {{(L3 - L2){1'b0}}, l2[1]};
            wire [L3-1:0] l3v = (l3a << WT) + {{(L3 - WB){1'b0}}, w2} * (l3b - l3a);
            always @(posedge clk) if (ld_i3) l3 <= l3v[L3-1:0];
            // --- A: N = a' l3 (mod 2^ALW) rounded once to F bits (np_tex_to_index)
            wire [ALW-1:0] alw = {{(ALW - 32){amp[31]}}, amp} * {{(ALW - L3){1'b0}}, l3};
            wire [W-1:0] n_idx;  // ALW = NF - F + W, as q_idx
            if (NF > F) begin : g_nround
                wire [ALW-1:0] nh = alw + ({{(ALW - 1){1'b0}}, 1'b1} << (NF - F - 1));
                assign n_idx = nh[ALW-1:NF-F];
            end else if (NF == F) begin : g_nexact
                assign n_idx = alw;
            end else begin : g_nshift
                assign n_idx = {alw, {(F - NF){1'b0}}};
            end
            reg [W-1:0] n4;
            always @(posedge clk) if (ld_a) n4 <= n_idx;
            assign n_all[W*o +: W] = n4;
        end
    endgenerate

    // ---------------------------------------------------------------- S: x = q + sum N (mod 2^W)
    reg [W-1:0] xsum;
    integer oi;
    always @(*) begin
        xsum = q4;
        for (oi = 0; oi < N_OCT; oi = oi + 1) xsum = xsum + n_all[W*oi +: W];
    end
    reg [W-1:0] x5;
    always @(posedge clk) if (ld_s) x5 <= xsum;

    // ---------------------------------------------------------------- C1 C2 C3: the colour map
    np_tex_colour #(.W(W), .F(F), .FW(FW)) u_colour (.clk(clk), .x(x5), .ld_c1(ld_c1), .ld_c2(ld_c2), .ld_c3(ld_c3),
        .cmap(cmap), .cmap_n(cmap_n), .cmap_rep(cmap_rep), .cr(cr), .cg(cg), .cb(cb));
    assign px = xb[NB-1];
    assign py = yb[NB-1];
endmodule
/* verilator lint_on UNUSEDSIGNAL */
