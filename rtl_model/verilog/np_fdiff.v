// SPDX-License-Identifier: MIT
// np_fdiff - reference RTL of the forward-difference scanline texturing unit
// `fdiff` (rtl_model/np_fdiff.h; docs/fdiff.md): span descriptors in, one
// pixel per clock out, the texture of np_texture.h stepped by forward
// differences (Kameya & Hart, equation 22). Written from np_fdiff.h/.c,
// np_texture.h, np_span.h and np_fixed.h; the sequencer is np_span_seq.v
// (np_span_sim), the engine (np_fdiff_engine: front end, core, set-up
// engine's timing, colour pipeline) is this module.
// Verilog-2005, synthesizable; Verilator -Wall clean (waiver below).
//
// Parameters: the unit's configuration keys (noisepipe units, fdiff)
//   IDX_INT      idx_int      I: index integer bits, 1..11 (10)
//   W_FRAC       w_frac       Fw: colour weight bits, 1..24 (12)
//   GUARD        guard        G: F = Fw + G index fraction bits (44)
//   RESETUP      resetup      K: re-set-up interval; only 0 (off, the default) is built
//   SETUP_MULTS  setup_mults  P: multipliers of the set-up engine, 1..64 (2)
//   MULT_LAT     mult_lat     Lm: their latency, clocks, 1..16 (2)
// and the texture's octave count (the `texture` key's registers):
//   N_OCT        np_tex_regs.n_oct, 1..8 (wood 1, marble 4): the lanes built.
// Default register formats only (k s48 Q23.24, m s24 Q7.16), as np_texel.v.
// Derived: F = Fw + G, W = 1 + I + F: N_i[0..3], Q[0..2] and x are s(W) QI.F.
//
// Ports: np_span_ports.vh, as np_texel.v (the same register inputs, descriptor
// and pixel ports). The colour banks C1..C3 are np_tex_colour.v, the begun
// descriptor and the quadric's exact set-up np_tex_quad.vh (both shared with np_texel.v).
//
// Registers of the core (np_fdiff_core), per octave o:
//   u[3] u40 Q8.32 (DDA, mod 256), du[3] s40 Q7.32, d[0..3] s(W) QI.F (n, dn, d2n, d3n);
// the quadric q[0..2] s(W) QI.F; the pixel k u17 of n u17.
// Per pixel (adv, np_fdiff_core_advance): q += dq, dq += d2q; per octave
// n += dn, dn += d2n, d2n += d3n (mod 2^W, on the old values), u += du; when
// any axis's cell (u[39:32]) changes, the octave's differences are set up at
// the new u (np_fdiff_cell_setup). x = q + sum n (mod 2^W) of the issued
// pixel goes into bank C1 with its split, as the C1 stage of the declaration.
// Banks: C1 (seg u8, cw u(Fw+1)), C2 (prod u(8+Fw) x 3), C3 (rgb u8 x 3):
// latency 3 clocks from issue to the output register (NP_FDIFF_TAIL_STAGES).
//
// The set-up values (bits): NOTE, as np_texel.v, the span's front end, the
// quadric and every cell's differences are computed here as combinational
// datapaths of the descriptor / of the octave's new u, loaded in the clock
// they are used (the bits are those of np_fdiff.c; only their timing is the
// engine's). The P pipelined multipliers, the shadow sets of differences and
// the descriptor buffer's set-up registers that the declaration prices are
// not built as storage; their *timing* is built exactly:
//
// The set-up engine's timing (np_fdiff.c's timeline, in real time): jobs
//   ring:  per octave B = 4 cell jobs (a FIFO, keys = the pixel they are for),
//          schedule cell {4, 14, 6, 4; 4 fixed}
//   cur:   the begun span's jobs: quadric {18, 15; 2 fixed} and per octave
//          front end {18 | 6 diagonal; 1 fixed} then cell {4, 14, 6, 4; 4}
//   next:  the same for the buffered span (prefetch), lowest priority
// each with state (none / in flight / done), phase, products left, and a
// countdown to the clock it may proceed (done: its values usable). Every
// clock the P multiplier slots go to the ready jobs in order of need (key,
// then octave; the span jobs last), a job takes min(left, slots left); a
// level finished at clock x lets the next start at x + Lm (+ the fixed
// clocks after it). Per octave a crossing finder (R = 4 pixels a clock, a DDA
// from the span's first pixel from the clock its set-up is done) finds the
// next pixel whose cell differs from the last one found and holds it until
// the ring has room, when the job is released into the ring (it may issue in
// that clock). A pixel waits (iss_ready to the sequencer low) until the span
// jobs (first pixel) or the ring heads of the octaves it crosses in are done;
// in the clock they are, the heads leave the ring. A descriptor buffered while
// a pixel waits for a job that still issues products has its jobs held until
// that job's last product (np_fdiff.c's core_prefetch: "not inside a stall
// already allotted"). bg_stall and adv_stall of np_span_seq are 0: the wait is
// the set-up engine's done flags on iss_ready, which is the same clock for
// clock as np_span_sim's stall counter (cosim checks it).
//
// Fault copies: NP_FAULT_FLIP flips bit 0 of cr when x's 4 low bits are 0101;
// NP_FAULT_STALL lets bank C2 overwrite its content under a stall;
// NP_FAULT_DROP drops the dn += d2n update of every octave at pixels with
// k = 7 (mod 16) (the bits go wrong until the next cell set-up);
// NP_FAULT_SETUP lets a pixel go one clock prior its cell job is done.
// Lint waivers (Verilator -Wall), whole file:
//   UNUSEDSIGNAL the 128-bit modular temporaries of which each register keeps its bits.
//   LATCH        the combinational blocks assign every element of their arrays in for
//                loops before any read, which Verilator's path check does not follow.
/* verilator lint_off UNUSEDSIGNAL */
/* verilator lint_off LATCH */
module np_fdiff #(
    parameter integer IDX_INT = 10,
    parameter integer W_FRAC = 12,
    parameter integer GUARD = 44,
    parameter integer RESETUP = 0,
    parameter integer SETUP_MULTS = 2,
    parameter integer MULT_LAT = 2,
    parameter integer N_OCT = 1
) (
`include "np_span_ports.vh"
);
    localparam integer FW = W_FRAC;
    localparam integer F = W_FRAC + GUARD;
    localparam integer W = 1 + IDX_INT + F;
    localparam integer QF = 88;                   // np_tex_q_frac at the default k_frac 24
    localparam integer YF = 116;                  // NP_FDIFF_EXACT_FRAC
    localparam integer STALL_W = 16;
    localparam integer PAY_W = 3 * 48 + 3 * 41;
    localparam integer P = SETUP_MULTS, LM = MULT_LAT;
    localparam integer NB = 3;                    // banks C1 C2 C3
    localparam integer B = 4;                     // NP_FDIFF_SHADOWS
    localparam integer R = 4;                     // NP_FDIFF_FINDER_RATE
    localparam integer NR = N_OCT * B;            // ring jobs
    localparam integer NS = N_OCT + 1;            // jobs of one span: quadric, then per octave
    localparam integer J = NR + 2 * NS;           // ring, cur span, next span
    localparam integer JC = NR, JN = NR + NS;     // first job of the cur / next span bank

`include "np_hash.vh"

    generate
        if (RESETUP != 0) begin : g_no_resetup
            // Not built: the interval's step counters, the quadric's job and the finder's K rule.
            initial $fatal(1, "np_fdiff: RESETUP (resetup) other than 0 is not built");
        end
    endgenerate

    // ---------------------------------------------------------------- sequencer
    wire iss_valid, bg, bg_pf, pf, adv, seq_busy;
    wire iss_ready;
    wire [15:0] iss_x, iss_y;
    wire [16:0] bg_n;
    wire [PAY_W-1:0] bg_pay;
    np_span_seq #(.PAY_W(PAY_W), .PREFETCH(1), .STALL_W(STALL_W)) u_seq (
        .clk(clk), .rst(rst),
        .in_valid(in_valid), .in_ready(in_ready), .in_y(in_y), .in_x0(in_x0), .in_n(in_n),
        .in_pay({in_dr, in_dt, in_ds, in_r, in_t, in_s}),
        .iss_valid(iss_valid), .iss_ready(iss_ready), .iss_x(iss_x), .iss_y(iss_y),
        .bg(bg), .bg_pf(bg_pf), .bg_n(bg_n), .bg_pay(bg_pay), .bg_stall({STALL_W{1'b0}}),
        .pf(pf), .adv(adv), .adv_stall({STALL_W{1'b0}}), .busy(seq_busy));

    wire bg_job = bg && bg_n != 17'd0;
    wire pf_job = pf && in_n != 17'd0;

    // ---------------------------------------------------------------- set-up schedules (np_tex_sched)
    // Lists: 0 cell, 1 quadric, 2 span (front end then cell). dg: every octave's M diagonal.
    function [7:0] ph_mults;
        input [1:0] list;
        input [3:0] p;
        input dg;
        begin
            ph_mults = 8'd0;
            case (list)
                2'd0: case (p) 4'd0: ph_mults = 8'd4; 4'd1: ph_mults = 8'd14; 4'd2: ph_mults = 8'd6;
                          4'd3: ph_mults = 8'd4; default: ph_mults = 8'd0; endcase
                2'd1: case (p) 4'd0: ph_mults = 8'd18; 4'd1: ph_mults = 8'd15; default: ph_mults = 8'd0; endcase
                default: case (p) 4'd0: ph_mults = dg ? 8'd6 : 8'd18; 4'd1: ph_mults = 8'd4; 4'd2: ph_mults = 8'd14;
                             4'd3: ph_mults = 8'd6; 4'd4: ph_mults = 8'd4; default: ph_mults = 8'd0; endcase
            endcase
        end
    endfunction
    // The fixed clocks after level p (the schedule's own after its last level).
    function [7:0] ph_after;
        input [1:0] list;
        input [3:0] p;
        begin
            ph_after = 8'd0;
            case (list)
                2'd0: if (p == 4'd3) ph_after = 8'd4;
                2'd1: if (p == 4'd1) ph_after = 8'd2;
                default: if (p == 4'd0) ph_after = 8'd1; else if (p == 4'd4) ph_after = 8'd4;
            endcase
        end
    endfunction
    function [3:0] ph_n;
        input [1:0] list;
        begin
            ph_n = list == 2'd0 ? 4'd4 : list == 2'd1 ? 4'd2 : 4'd5;
        end
    endfunction
    function [1:0] job_list;
        input integer i;
        begin
            job_list = i < NR ? 2'd0 : (i == JC || i == JN) ? 2'd1 : 2'd2;
        end
    endfunction

    wire [N_OCT-1:0] offdiag;
    wire diag = offdiag == {N_OCT{1'b0}};

    // ---------------------------------------------------------------- the jobs
    reg [1:0] st[0:J-1];     // 0 none, 1 in flight, 2 done
    reg [3:0] ph[0:J-1];     // current level
    reg [7:0] left[0:J-1];   // its products still to issue
    reg [7:0] rdy[0:J-1];    // clocks until it may proceed (done: until its values are usable)
    reg [16:0] key[0:J-1];   // ring: the pixel it is for
    reg gflag;               // the next span's jobs are held (prefetched inside an allotted stall)
    // ring per octave
    reg [1:0] head[0:N_OCT-1];
    reg [2:0] cnt[0:N_OCT-1];
    // the crossing finder per octave: 0 off, 1 searching, 2 holding a found pixel
    reg [1:0] fst[0:N_OCT-1];
    reg [39:0] fu[0:N_OCT-1][0:2];
    reg [16:0] fk[0:N_OCT-1];
    // waits
    reg span_wait;                 // the begun span's first pixel waits for the cur jobs
    reg [N_OCT-1:0] pend;          // the next pixel waits for these octaves' ring heads
    reg [16:0] k_e, n_e;           // the core's pixel and the span's length
    // core
    reg [39:0] u_q[0:N_OCT-1][0:2];
    reg [39:0] du_q[0:N_OCT-1][0:2];

    // --- waits: done flags
    reg span_ok, pend_ok;
    reg [N_OCT-1:0] head_done, head_busy;
    integer o2, i2;
    always @(*) begin
        span_ok = 1'b1;
        for (i2 = JC; i2 < JC + NS; i2 = i2 + 1) if (st[i2] != 2'd2 || rdy[i2] != 8'd0) span_ok = 1'b0;
        pend_ok = 1'b1;
        for (o2 = 0; o2 < N_OCT; o2 = o2 + 1) begin
`ifdef NP_FAULT_SETUP
            head_done[o2] = st[o2*B + {30'd0, head[o2]}] == 2'd2 && rdy[o2*B + {30'd0, head[o2]}] <= 8'd1;  // fault: one clock early
`else
            head_done[o2] = st[o2*B + {30'd0, head[o2]}] == 2'd2 && rdy[o2*B + {30'd0, head[o2]}] == 8'd0;
`endif
            if (pend[o2] && !head_done[o2]) pend_ok = 1'b0;
        end
    end
    wire span_go = span_wait && span_ok;        // the first pixel's set-up is done in this clock
    wire [N_OCT-1:0] pop = pend_ok ? pend : {N_OCT{1'b0}};
    wire setup_ok = (!span_wait || span_ok) && (pend == {N_OCT{1'b0}} || pend_ok);

    // --- the crossing finders and releases into the rings
    reg [N_OCT-1:0] rel;                 // octave o releases its held pixel into its ring in this clock
    reg [16:0] rel_key[0:N_OCT-1];
    reg [1:0] n_fst[0:N_OCT-1];
    reg [39:0] n_fu[0:N_OCT-1][0:2];
    reg [16:0] n_fk[0:N_OCT-1];
    reg [39:0] bu[0:2], uj[0:2];
    reg [16:0] bk;
    reg [7:0] bcell[0:2];
    reg found, ended, act_f;
    reg [2:0] room;
    integer of, a3, jj;
    always @(*) begin
        for (of = 0; of < N_OCT; of = of + 1) begin
            rel[of] = 1'b0;
            rel_key[of] = fk[of];
            n_fst[of] = fst[of];
            n_fk[of] = fk[of];
            for (a3 = 0; a3 < 3; a3 = a3 + 1) n_fu[of][a3] = fu[of][a3];
            room = cnt[of] - {2'd0, pop[of]};
            // the base of this clock's search: the span's first pixel when its set-up is done now
            act_f = span_go || fst[of] == 2'd1 || (fst[of] == 2'd2 && room < 3'd4);
            if (fst[of] == 2'd2 && room < 3'd4) rel[of] = 1'b1;
            for (a3 = 0; a3 < 3; a3 = a3 + 1) begin
                bu[a3] = span_go ? u_q[of][a3] : fu[of][a3];
                bcell[a3] = bu[a3][39:32];
            end
            bk = span_go ? 17'd0 : fk[of];
            if (span_go || fst[of] != 2'd0) n_fst[of] = act_f ? 2'd1 : 2'd2;
            found = 1'b0;
            ended = 1'b0;
            for (a3 = 0; a3 < 3; a3 = a3 + 1) uj[a3] = bu[a3];
            if (act_f) begin
                for (jj = 1; jj <= R; jj = jj + 1) begin
                    for (a3 = 0; a3 < 3; a3 = a3 + 1) uj[a3] = bu[a3] + {8'd0, jj[31:0]} * du_q[of][a3];
                    if (!found && !ended) begin
                        if ({15'd0, bk} + jj >= {15'd0, n_e}) ended = 1'b1;
                        else if (uj[0][39:32] != bcell[0] || uj[1][39:32] != bcell[1] || uj[2][39:32] != bcell[2]) begin
                            found = 1'b1;
                            n_fk[of] = bk + jj[16:0];
                            for (a3 = 0; a3 < 3; a3 = a3 + 1) n_fu[of][a3] = uj[a3];
                        end
                    end
                end
                if (found) n_fst[of] = 2'd2;
                else if (ended || {15'd0, bk} + R + 1 >= {15'd0, n_e}) n_fst[of] = 2'd0;
                else begin
                    n_fst[of] = 2'd1;
                    n_fk[of] = bk + R[16:0];
                    for (a3 = 0; a3 < 3; a3 = a3 + 1) n_fu[of][a3] = bu[a3] + {8'd0, R[31:0]} * du_q[of][a3];
                end
            end
        end
    end

    // --- the engine: effective job states (with this clock's releases), slot allotment, next states
    reg [1:0] e_st[0:J-1];
    reg [3:0] e_ph[0:J-1];
    reg [7:0] e_left[0:J-1];
    reg [7:0] e_rdy[0:J-1];
    reg [16:0] e_key[0:J-1];
    reg [J-1:0] elig;
    reg [7:0] take[0:J-1];
    reg [1:0] n_st[0:J-1];
    reg [3:0] n_ph[0:J-1];
    reg [7:0] n_left[0:J-1];
    reg [7:0] n_rdy[0:J-1];
    reg prior;
    reg busy_n;
    reg [1:0] tail;
    integer i, jx, pre, sl, oo;
    always @(*) begin
        for (i = 0; i < J; i = i + 1) begin
            e_st[i] = st[i];
            e_ph[i] = ph[i];
            e_left[i] = left[i];
            e_rdy[i] = rdy[i];
            e_key[i] = key[i];
        end
        for (oo = 0; oo < N_OCT; oo = oo + 1)
            if (rel[oo]) begin
                tail = head[oo] + cnt[oo][1:0];
                e_st[oo*B + {30'd0, tail}] = 2'd1;
                e_ph[oo*B + {30'd0, tail}] = 4'd0;
                e_left[oo*B + {30'd0, tail}] = ph_mults(2'd0, 4'd0, 1'b0);
                e_rdy[oo*B + {30'd0, tail}] = 8'd0;
                e_key[oo*B + {30'd0, tail}] = rel_key[oo];
            end
        for (i = 0; i < J; i = i + 1) elig[i] = e_st[i] == 2'd1 && e_rdy[i] == 8'd0 && !(i >= JN && gflag);
        for (i = 0; i < J; i = i + 1) begin
            pre = 0;
            for (jx = 0; jx < J; jx = jx + 1) begin
                if (i < NR && jx < NR) prior = e_key[jx] < e_key[i] || (e_key[jx] == e_key[i] && jx < i);
                else prior = jx < i;
                if (elig[jx] && prior) pre = pre + {24'd0, e_left[jx]};
            end
            sl = pre >= P ? 0 : P - pre;
            take[i] = !elig[i] ? 8'd0 : ({24'd0, e_left[i]} < sl) ? e_left[i] : sl[7:0];
        end
        for (i = 0; i < J; i = i + 1) begin
            n_st[i] = e_st[i];
            n_ph[i] = e_ph[i];
            n_left[i] = e_left[i];
            n_rdy[i] = e_rdy[i] != 8'd0 ? e_rdy[i] - 8'd1 : 8'd0;
            if (take[i] != 8'd0) begin
                n_left[i] = e_left[i] - take[i];
                if (n_left[i] == 8'd0) begin
                    n_rdy[i] = LM[7:0] + ph_after(job_list(i), e_ph[i]) - 8'd1;
                    if (e_ph[i] + 4'd1 >= ph_n(job_list(i))) n_st[i] = 2'd2;
                    else begin
                        n_ph[i] = e_ph[i] + 4'd1;
                        n_left[i] = ph_mults(job_list(i), e_ph[i] + 4'd1, diag);
                    end
                end
            end
        end
        // A job waited for still issues products after this clock (or is not yet released: its
        // finder has not reached it): a prefetch now is held.
        busy_n = 1'b0;
        for (oo = 0; oo < N_OCT; oo = oo + 1)
            if (pend[oo] && n_st[oo*B + {30'd0, head[oo]}] != 2'd2) busy_n = 1'b1;
        if (span_wait)
            for (i = JC; i < JC + NS; i = i + 1) if (n_st[i] != 2'd2) busy_n = 1'b1;
    end

    // ---------------------------------------------------------------- handshake (np_pipe)
    reg [NB-1:0] bv;
    wire [NB-1:0] en, bv_next;  // NP_FAULT_STALL: bank C2 overwrites its content when its successor stalls
    wire iss = iss_valid && setup_ok;   // the pixel offered to bank C1
    wire c1_ready;
    np_pipe_ctrl #(.NB(NB), .STALL_BANK(1)) u_ctrl (.v(bv), .in_valid(iss), .out_ready(out_ready),
        .en(en), .v_next(bv_next), .in_ready(c1_ready), .out_valid(out_valid));
    assign iss_ready = c1_ready && setup_ok;
    always @(posedge clk) if (rst) bv <= {NB{1'b0}}; else bv <= bv_next;
    wire ld_c1 = en[0] && iss, ld_c2 = en[1] && bv[0], ld_c3 = en[2] && bv[1];
    reg [15:0] xb[0:NB-1], yb[0:NB-1];
    always @(posedge clk) begin
        if (ld_c1) begin xb[0] <= iss_x; yb[0] <= iss_y; end
        if (ld_c2) begin xb[1] <= xb[0]; yb[1] <= yb[0]; end
        if (ld_c3) begin xb[2] <= xb[1]; yb[2] <= yb[1]; end
    end

    // ---------------------------------------------------------------- the begun descriptor, the quadric: set-up (np_fdiff_quad_setup) and steps
`include "np_tex_quad.vh"
    wire [127:0] qe[0:2];                                                  // np_tex_quadric_exact, Q.88 mod 2^128
    assign qe[0] = q0_w;
    assign qe[1] = q1_w;
    assign qe[2] = q2_w;
    wire [W-1:0] qi[0:2];                                                  // np_tex_to_index(qe, 88, F, W): s(W) QI.F
    genvar qj;
    generate
        for (qj = 0; qj < 3; qj = qj + 1) begin : g_qidx
            if (QF > F) begin : g_round
                wire [127:0] h = (qe[qj] + (128'd1 << (QF - F - 1))) >> (QF - F);
                assign qi[qj] = h[W-1:0];
            end else begin : g_shift
                wire [127:0] h = qe[qj] << (F - QF);
                assign qi[qj] = h[W-1:0];
            end
        end
    endgenerate
    reg [W-1:0] q_r[0:2];
    always @(posedge clk) begin
        if (bg_job) begin
            q_r[0] <= qi[0];
            q_r[1] <= qi[1];
            q_r[2] <= qi[2];
        end else if (adv && k_e + 17'd1 < n_e) begin
            q_r[0] <= q_r[0] + q_r[1];
            q_r[1] <= q_r[1] + q_r[2];
        end
    end

    // ---------------------------------------------------------------- octaves
    wire [N_OCT-1:0] xcell;          // the octave's cell changes at the next pixel
    wire [W*N_OCT-1:0] n_all;        // N_i[0] of every octave
    wire step = adv && k_e + 17'd1 < n_e;
    genvar o, ab, a, cn;
    generate
        for (o = 0; o < N_OCT; o = o + 1) begin : g_oct
`include "np_tex_front.vh"
            // --- front end (np_tex_octave_span) and the DDA; su: the u a cell is set up at
            wire [39:0] su[0:2];
            wire [39:0] sdu[0:2];
            wire [2:0] cx;
            for (a = 0; a < 3; a = a + 1) begin : g_axis
                wire [39:0] u_nx = u_q[o][a] + du_q[o][a];   // u40 Q8.32, mod 256
                assign su[a] = bg_job ? u0[a] : u_nx;
                assign sdu[a] = bg_job ? du0[a] : du_q[o][a];
                assign cx[a] = u_nx[39:32] != u_q[o][a][39:32];
                always @(posedge clk) begin
                    if (bg_job) begin
                        u_q[o][a] <= u0[a];
                        du_q[o][a] <= du0[a];
                    end else if (step) begin
                        u_q[o][a] <= u_nx;
                    end
                end
            end
            assign xcell[o] = cx != 3'd0;
            // --- cell set-up at su (np_fdiff_cell_setup): lattice, a..h, levels 1..4, one rounding
            wire [5:0] nc[0:7];
            for (cn = 0; cn < 8; cn = cn + 1) begin : g_corner
                wire [7:0] hi = su[0][39:32] + cn % 2, hj = su[1][39:32] + (cn / 2) % 2, hk = su[2][39:32] + cn / 4;
                assign nc[cn] = hash6(hi, hj, hk);
            end
            // the seed's N0..N7 (np_fdiff.c): N2 = corner 3, N3 = corner 2, N6 = corner 7, N7 = corner 6
            wire [127:0] N0 = {122'd0, nc[0]}, N1 = {122'd0, nc[1]}, N2 = {122'd0, nc[3]}, N3 = {122'd0, nc[2]};
            wire [127:0] N4 = {122'd0, nc[4]}, N5 = {122'd0, nc[5]}, N6 = {122'd0, nc[7]}, N7 = {122'd0, nc[6]};
            // a..h s10 Q3.6, exact (held modulo 2^128, as np_s128)
            wire [127:0] ka = N0, kb = N1 - N0, kc = N3 - N0, kd = N4 - N0, ke = N0 - N1 + N2 - N3;
            wire [127:0] kf = N7 - N4 - N3 + N0, kg = N5 - N4 - N1 + N0, kh = N4 - N5 + N6 - N7 - ke;
            // fractions u32 Q0.32, steps s40 Q7.32
            wire [127:0] fru = {96'd0, su[0][31:0]}, frv = {96'd0, su[1][31:0]}, frw = {96'd0, su[2][31:0]};
            wire [127:0] dU = {{88{sdu[0][39]}}, sdu[0]}, dV = {{88{sdu[1][39]}}, sdu[1]}, dW = {{88{sdu[2][39]}}, sdu[2]};
            wire [127:0] uv = fru * frv, dudv = dU * dV, crs = fru * dV + frv * dU;      // level 1, Q.64
            wire [127:0] p0 = (ka << 64) + ((kb * fru + kc * frv) << 32) + ke * uv;      // level 2, Q.70
            wire [127:0] p1 = ((kb * dU + kc * dV) << 32) + ke * crs;
            wire [127:0] p2 = ke * dudv;
            wire [127:0] r0 = (kd << 64) + ((kf * frv + kg * fru) << 32) + kh * uv;
            wire [127:0] r1 = ((kf * dV + kg * dU) << 32) + kh * crs;
            wire [127:0] r2 = kh * dudv;
            wire [127:0] dl = (p0 << 32) + frw * r0;                                     // level 3, Q.102
            wire [127:0] gm = (p1 << 32) + frw * r1 + dW * r0;
            wire [127:0] bt = (p2 << 32) + frw * r2 + dW * r1;
            wire [127:0] al = dW * r2;
            wire [127:0] xe[0:3];                                                        // equation 21, Q.102
            assign xe[0] = dl;
            assign xe[1] = al + bt + gm;
            assign xe[2] = 128'd6 * al + 128'd2 * bt;
            assign xe[3] = 128'd6 * al;
            wire [127:0] ampx = {{96{amp[31]}}, amp};
            wire [W-1:0] dn[0:3];                                                        // np_tex_to_index(a' x, 116, F, W)
            genvar dj;
            for (dj = 0; dj < 4; dj = dj + 1) begin : g_d
                wire [127:0] y = ampx * xe[dj];                                          // level 4, Q.116
                if (YF > F) begin : g_round
                    wire [127:0] h = (y + (128'd1 << (YF - F - 1))) >> (YF - F);
                    assign dn[dj] = h[W-1:0];
                end else begin : g_shift
                    wire [127:0] h = y << (F - YF);
                    assign dn[dj] = h[W-1:0];
                end
            end
            // --- the forward differences (equation 22), or a set-up
            reg [W-1:0] d_r[0:3];
            wire setup_now = bg_job || (step && xcell[o]);
            always @(posedge clk) begin
                if (setup_now) begin
                    d_r[0] <= dn[0];
                    d_r[1] <= dn[1];
                    d_r[2] <= dn[2];
                    d_r[3] <= dn[3];
                end else if (step) begin
                    d_r[0] <= d_r[0] + d_r[1];
`ifdef NP_FAULT_DROP
                    if (k_e[3:0] != 4'd7) d_r[1] <= d_r[1] + d_r[2];  // fault: dn += d2n dropped at k = 7 mod 16
`else
                    d_r[1] <= d_r[1] + d_r[2];
`endif
                    d_r[2] <= d_r[2] + d_r[3];
                end
            end
            assign n_all[W*o +: W] = d_r[0];
        end
    endgenerate

    // ---------------------------------------------------------------- registers of the engine's timing
    integer ri, ro, ra;
    always @(posedge clk) begin
        if (rst) begin
            for (ri = 0; ri < J; ri = ri + 1) begin
                st[ri] <= 2'd0;
                ph[ri] <= 4'd0;
                left[ri] <= 8'd0;
                rdy[ri] <= 8'd0;
                key[ri] <= 17'd0;
            end
            for (ro = 0; ro < N_OCT; ro = ro + 1) begin
                head[ro] <= 2'd0;
                cnt[ro] <= 3'd0;
                fst[ro] <= 2'd0;
                fk[ro] <= 17'd0;
                for (ra = 0; ra < 3; ra = ra + 1) fu[ro][ra] <= 40'd0;
            end
            gflag <= 1'b0;
            span_wait <= 1'b0;
            pend <= {N_OCT{1'b0}};
            k_e <= 17'd0;
            n_e <= 17'd0;
        end else begin
            for (ri = 0; ri < J; ri = ri + 1) begin
                st[ri] <= n_st[ri];
                ph[ri] <= n_ph[ri];
                left[ri] <= n_left[ri];
                rdy[ri] <= n_rdy[ri];
                key[ri] <= e_key[ri];
            end
            for (ro = 0; ro < N_OCT; ro = ro + 1) begin
                fst[ro] <= n_fst[ro];
                fk[ro] <= n_fk[ro];
                for (ra = 0; ra < 3; ra = ra + 1) fu[ro][ra] <= n_fu[ro][ra];
                if (pop[ro]) st[ro*B + {30'd0, head[ro]}] <= 2'd0;
                if (rel[ro] && !pop[ro]) cnt[ro] <= cnt[ro] + 3'd1;
                else if (pop[ro] && !rel[ro]) cnt[ro] <= cnt[ro] - 3'd1;
                if (pop[ro]) head[ro] <= head[ro] + 2'd1;
            end
            if (rel != {N_OCT{1'b0}}) begin
                // a released job in the popped slot (a full ring): the release wins over the pop
                for (ro = 0; ro < N_OCT; ro = ro + 1)
                    if (rel[ro] && pop[ro] && cnt[ro] == 3'd4) st[ro*B + {30'd0, head[ro]}] <= n_st[ro*B + {30'd0, head[ro]}];
            end
            gflag <= pf_job && !bg ? busy_n : gflag && busy_n;
            if (span_go) span_wait <= 1'b0;
            pend <= (pend & ~pop) | (step ? xcell : {N_OCT{1'b0}});
            if (adv) k_e <= k_e + 17'd1;
            // the next span's jobs: released at the next clock
            if (pf_job && !bg) begin
                for (ri = JN; ri < JN + NS; ri = ri + 1) begin
                    st[ri] <= 2'd1;
                    ph[ri] <= 4'd0;
                    left[ri] <= ph_mults(job_list(ri), 4'd0, diag);
                    rdy[ri] <= 8'd0;
                end
            end
            if (bg) begin
                // the ring and the finders are the previous span's: cleared
                for (ri = 0; ri < NR; ri = ri + 1) st[ri] <= 2'd0;
                for (ro = 0; ro < N_OCT; ro = ro + 1) begin
                    head[ro] <= 2'd0;
                    cnt[ro] <= 3'd0;
                    fst[ro] <= 2'd0;
                end
                pend <= {N_OCT{1'b0}};
                k_e <= 17'd0;
                n_e <= bg_n;
                span_wait <= bg_job;
                gflag <= 1'b0;
                for (ri = 0; ri < NS; ri = ri + 1) begin
                    st[JN + ri] <= 2'd0;
                    if (!bg_job) st[JC + ri] <= 2'd0;
                    else if (st[JN + ri] != 2'd0 && !pf_job) begin
                        // prefetched: its jobs go on from where the engine has them
                        st[JC + ri] <= n_st[JN + ri];
                        ph[JC + ri] <= n_ph[JN + ri];
                        left[JC + ri] <= n_left[JN + ri];
                        rdy[JC + ri] <= n_rdy[JN + ri];
                    end else begin
                        // from idle, or buffered in this very clock: released at the next clock
                        st[JC + ri] <= 2'd1;
                        ph[JC + ri] <= 4'd0;
                        left[JC + ri] <= ph_mults(job_list(JC + ri), 4'd0, diag);
                        rdy[JC + ri] <= 8'd0;
                    end
                end
            end
        end
    end

    // ---------------------------------------------------------------- C1: x = Q + sum N (mod 2^W), split
    reg [W-1:0] x_w;
    integer oi;
    always @(*) begin
        x_w = q_r[0];
        for (oi = 0; oi < N_OCT; oi = oi + 1) x_w = x_w + n_all[W*oi +: W];
    end
    // C1 (from x_w) C2 C3: the colour map
    np_tex_colour #(.W(W), .F(F), .FW(FW)) u_colour (.clk(clk), .x(x_w), .ld_c1(ld_c1), .ld_c2(ld_c2), .ld_c3(ld_c3),
        .cmap(cmap), .cmap_n(cmap_n), .cmap_rep(cmap_rep), .cr(cr), .cg(cg), .cb(cb));
    assign px = xb[NB-1];
    assign py = yb[NB-1];
endmodule
/* verilator lint_on LATCH */
/* verilator lint_on UNUSEDSIGNAL */
