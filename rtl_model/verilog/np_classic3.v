// SPDX-License-Identifier: MIT
// np_classic3 - reference RTL of the classic 3-D gradient noise unit, written
// from the bit-exact specification rtl_model/np_classic.h (with np_hash.h and
// np_fixed.h) and the cycle model np_classic_pipe (np_pipe.h). Verilog-2005,
// synthesizable; Icarus (-g2005) and Verilator (-Wall) clean.
//
// Parameters are the unit's configuration keys (noisepipe units):
//   OUT_BITS  = out_bits  N   output sN Q2.(N-2)           2..16, default 8
//   S_FRAC    = s_frac    WS  s-curve fraction bits        1..24, default N+4
//   LERP_FRAC = lerp_frac WL  interpolator fraction bits   N-2..30, default N+3
// and two options of the pipe (docs/rtl.md; both 0 = np_classic_pipe exactly):
//   IN_REG  1: an input register (bank R_in) before L: latency + 1; in_ready
//           depends only on R_in and bank L, not on the stages behind it
//           beyond L's ready (see docs/rtl.md for the exact expression).
//   OUT_SKID 1: a two-entry skid buffer after O: latency + 1; out_ready is
//           registered: no combinational path from out_ready to in_ready.
// and three circuit variants for the gate count (docs/rtl.md, docs/classic3.md
// "Perlin's under 10K gates"; all 0 = today's circuit, gate for gate):
//   S_TABLE 1: the s-curve of each axis from a 256-entry constant table
//           (u(WS+1) per entry, the same bits: each entry is the formula's
//           value) in H; bank R0 no longer holds u^2, v^2, w^2 and L has no
//           squarers. Timing unchanged (latency 9, 1 result / clock).
//   HASH_SERIAL 1: one hash circuit serves the eight corners in turn. A point
//           entering L has corner 0 hashed from the input at once and
//           corners 1..7 from held i, j, k on the next seven clocks (r0_c
//           counts them); in_ready is low during those seven clocks and
//           bank R0 becomes valid with the 8th hash. Latency 16 clocks
//           (9 + 7), throughput 1 result / 8 clocks. No C cycle model
//           matches this timing (the co-simulation does not apply).
//   LERP_SERIAL 1 (implies HASH_SERIAL): stages H to I3a become one engine
//           that takes bank L's content (a copy: r1_h, r1_u, r1_v, r1_w) and
//           does the seven lerps in turn with one lerp unit (one subtractor,
//           multiplier, adder and rounding: elerp) and one s-curve, fed by
//           two gradient decoders (the corners of one level-1 lerp); partial
//           results in r1_l, l3 into bank R7. 7 clocks a point, overlapped
//           with L hashing the next: latency 17 clocks (9 + 7 + 1),
//           throughput 1 result / 8 clocks; banks R1..R6 stay empty, and
//           en[1] is the engine's "free". Same bits (elerp's contract).
//
// Pipeline: nine banks R0..R8 after stages L, H, I1m, I1a, I2m, I2a, I3m,
// I3a, O; latency 9 clocks. Handshake (as np_pipe_eval/np_pipe_clock):
//   out_valid = v[8]; en[8] = !v[8] | out_ready;
//   en[k] = !v[k] | (en[k+1] & ... ) i.e. a bank loads when it is empty or its
//   content moves on this cycle; in_ready = en[0] (HASH_SERIAL: and not busy).
// A bank that loads takes its predecessor's valid bit (a bubble when it is 0).
//
// Register contents per bank (widths for the parameters; docs/rtl.md has the
// table): R0 u,v,w u8, h[8] u6, u^2,v^2,w^2 u16 (not with S_TABLE; with
// HASH_SERIAL also i,j,k u8, the corner counter u3 and a busy bit); R1 g[8] s11, sx,sy,sz
// u(WS+1); R2 a[4] s11, prod[4] s(13+WS), sy, sz; R3 l1[4] s(WL+3), sy, sz;
// R4 a[2] s(WL+3), prod[2] s(WL+5+WS), sz; R5 l2[2] s(WL+3), sz; R6 a s(WL+3),
// prod s(WL+5+WS); R7 l3 s(WL+2); R8 f sN. LERP_SERIAL: R0 as HASH_SERIAL's
// (its u^2, v^2, w^2 have no load: synthesis drops them); the engine r1_h 8 x u6,
// r1_u, r1_v, r1_w u8, r1_k u3, r1_busy, r1_l[6] s(WL+3); R7, R8 as above.
//
// Fault injection for the tests that must fail: `define NP_FAULT_FLIP flips
// bit 0 of f when l3[3:0] == 4'h5 (a datapath fault, about 1 input in 16);
// `define NP_FAULT_STALL makes bank I2a load while its successor stalls (a
// handshake fault: a transaction is overwritten and lost). For the variants:
// `define NP_FAULT_STABLE puts a wrong bit (weight 1/4) in every 16th entry of
// the S_TABLE table; `define NP_FAULT_SERIAL raises HASH_SERIAL's in_ready one
// clock early, during the 8th hash (an off-by-one: the next point overwrites
// u, v, w and the hash slots of one still in bank L); `define NP_FAULT_LSERIAL
// makes LERP_SERIAL's engine read the hashes from bank L instead of its copy
// (saving 48 flip-flops: L overwrites them with the next point's meanwhile).
// Each acts only in its variant.
module np_classic3 #(
    parameter integer OUT_BITS = 8,
    parameter integer S_FRAC = 12,
    parameter integer LERP_FRAC = 11,
    parameter integer IN_REG = 0,
    parameter integer OUT_SKID = 0,
    parameter integer S_TABLE = 0,
    parameter integer HASH_SERIAL = 0,
    parameter integer LERP_SERIAL = 0
) (
    input wire clk,
    input wire rst,  // synchronous, active high: empties every bank
    input wire in_valid,
    output wire in_ready,
    input wire [15:0] x,
    input wire [15:0] y,
    input wire [15:0] z,
    output wire out_valid,
    input wire out_ready,
    output wire [OUT_BITS-1:0] f
);
    localparam integer N = OUT_BITS, WS = S_FRAC, WL = LERP_FRAC, F = OUT_BITS - 2;
    localparam integer SW = WS + 1;       // s: u(WS+1) Q1.WS
    localparam integer GW = 11;           // g: s11 Q2.8
    localparam integer FI = 8;            // fraction bits of g (the input's)
    // Level 1 (operands g, Q2.8), levels 2 and 3 (operands l, Q2.WL).
    localparam integer D1W = GW + 1;      // g1 - g0: s12 Q3.8
    localparam integer P1W = D1W + SW;    // s * diff, s unsigned: s(12+WS+1)
    localparam integer LW = WL + 3;       // l1, l2: s(WL+3) Q2.WL
    localparam integer L3W = WL + 2;      // l3: s(WL+2) Q1.WL (|l3| <= 1.5)
    localparam integer D2W = LW + 1;      // l b - a: s(WL+4) Q3.WL
    localparam integer P2W = D2W + SW;
    // Sums a*2^WS + prod: exact, then one rounding. One guard bit over the
    // product width covers the carry of the rounding constant.
    localparam integer S1W = P1W + 2 > LW + 1 ? P1W + 2 : LW + 1;  // LW + 1: the left shift
    localparam integer S2W = P2W + 2;
    localparam integer SH1 = FI + WS - WL;  // > 0: round off; <= 0: shift left
    localparam integer HS = HASH_SERIAL != 0 || LERP_SERIAL != 0 ? 1 : 0;  // LERP_SERIAL implies it

    // ---------------------------------------------------------------- handshake
    wire core_in_valid, core_in_ready, core_out_valid, core_out_ready;
    wire [15:0] cx, cy, cz;
    wire [N-1:0] core_f;
    reg [8:0] v;   // bank valid bits R0..R8
    reg [8:0] en;  // bank k loads this cycle
    wire l_busy;   // HASH_SERIAL: bank L is collecting a point's corner hashes (else 0)
    wire l_done;   // HASH_SERIAL: the 8th corner hash is written at this edge (else 0)
    wire e_free;   // LERP_SERIAL: the engine takes bank L's content at this edge if valid
    wire e_fin;    // LERP_SERIAL: the engine's output is l3 this cycle (its 7th lerp)
    // np_pipe: moves[k] = v[k] & (!v[k+1] | moves[k+1]) and a bank loads when
    // !v[k] | moves[k]; since !v[k+1] implies en[k+1], that is !v[k] | en[k+1].
    integer e;
    always @(*) begin
        en[8] = !v[8] || core_out_ready;
        for (e = 7; e >= 0; e = e - 1) en[e] = !v[e] || en[e+1];
        if (LERP_SERIAL != 0) begin
            // banks R1..R6 are the engine (always empty); it takes L's content when free
            en[1] = e_free;
            en[0] = !v[0] || en[1];
        end
`ifdef NP_FAULT_STALL
        en[5] = 1'b1;  // fault: bank I2a overwrites its content when its successor stalls
`endif
    end
`ifdef NP_FAULT_SERIAL
    // fault: in_ready rises one clock early, while L writes the 8th hash of the last point
    assign core_in_ready = en[0] && (!l_busy || l_done);
`else
    assign core_in_ready = en[0] && !l_busy;
`endif
    assign core_out_valid = v[8];
    // Bank L's valid bit: the accepted point's, or (HASH_SERIAL) set by the 8th hash.
    wire v0_in = HS != 0 ? l_done : core_in_valid;
    // What each bank loads: its predecessor's valid bit; with LERP_SERIAL bank
    // R7 loads the engine's, and R1..R6 stay empty.
    wire [8:0] v_in = LERP_SERIAL != 0 ? {v[7], e_fin, 6'd0, v0_in} : {v[7:0], v0_in};

    always @(posedge clk) begin
        if (rst) v <= 9'd0;
        else v <= (v & ~en) | (v_in & en);
    end

    // ---------------------------------------------------------------- L
    // Hash of one lattice point (np_hash6) and the gradient decode: np_hash.vh.
`include "np_hash.vh"

    wire [7:0] ci = cx[15:8], cj = cy[15:8], ck = cz[15:8];
    wire l_acc = core_in_valid && core_in_ready;  // a point enters L at this edge
    reg [7:0] r0_u, r0_v, r0_w;
    reg [6*8-1:0] r0_h;
    always @(posedge clk) if (l_acc) begin
        r0_u <= cx[7:0];
        r0_v <= cy[7:0];
        r0_w <= cz[7:0];
    end
    generate
        if (HS == 0) begin : g_hash8
            // eight hash circuits, one per corner, in one clock
            wire [7:0] ci1 = ci + 8'd1, cj1 = cj + 8'd1, ck1 = ck + 8'd1;  // the tile wraps at 256
            assign l_busy = 1'b0;
            assign l_done = 1'b0;
            always @(posedge clk) if (l_acc)
                r0_h <= {hash6(ci1, cj1, ck1), hash6(ci, cj1, ck1), hash6(ci1, cj, ck1), hash6(ci, cj, ck1),
                         hash6(ci1, cj1, ck), hash6(ci, cj1, ck), hash6(ci1, cj, ck), hash6(ci, cj, ck)};
        end else begin : g_hash1
            // one hash circuit: corner 0 = (i, j, k) from the input at the accepting
            // edge, corner c (bit 0: i + 1, bit 1: j + 1, bit 2: k + 1) from the held
            // i, j, k on the c-th clock after it; hash c goes to slot c of r0_h.
            reg [7:0] r0_i, r0_j, r0_k;  // the point's integer parts, u8
            reg [2:0] r0_c;              // the corner hashed this clock while busy, 1..7
            reg r0_busy;
            wire [7:0] hi = r0_busy ? (r0_c[0] ? r0_i + 8'd1 : r0_i) : ci;
            wire [7:0] hj = r0_busy ? (r0_c[1] ? r0_j + 8'd1 : r0_j) : cj;
            wire [7:0] hk = r0_busy ? (r0_c[2] ? r0_k + 8'd1 : r0_k) : ck;
            wire [5:0] h1 = hash6(hi, hj, hk);
            wire [2:0] slot = r0_busy ? r0_c : 3'd0;
            integer s8;
            assign l_busy = r0_busy;
            assign l_done = r0_busy && r0_c == 3'd7;
            always @(posedge clk) begin
                if (rst) r0_busy <= 1'b0;
                else if (l_acc) r0_busy <= 1'b1;
                else if (l_done) r0_busy <= 1'b0;
                if (l_acc) begin
                    r0_c <= 3'd1;
                    r0_i <= ci;
                    r0_j <= cj;
                    r0_k <= ck;
                end else if (r0_busy) r0_c <= r0_c + 3'd1;
                if (l_acc || r0_busy)
                    for (s8 = 0; s8 < 8; s8 = s8 + 1)
                        if (slot == s8[2:0]) r0_h[6*s8+:6] <= h1;
            end
        end
    endgenerate

    // ---------------------------------------------------------------- H
    // Gradient (np_grad_decode / np_grad_apply_q8): p, q, r are the corner
    // offsets of the axes grad_fields(h) names (np_hash.vh), each
    // conditionally negated, and g = p + q + r, p + q or p + r as its use bits
    // say. An offset is s9 Q1.8 in [-256, 255]; its negation needs s10
    // (-(-256) = 256), so the negates work on s10 and the sum on s11.
    function signed [9:0] axis10;
        input [1:0] a;
        input signed [8:0] dx, dy, dz;
        begin
            axis10 = a == 2'd0 ? {dx[8], dx} : a == 2'd1 ? {dy[8], dy} : {dz[8], dz};
        end
    endfunction
    function signed [GW-1:0] grad;
        input [5:0] h;
        input signed [8:0] dx, dy, dz;
        reg [10:0] gf;
        reg signed [9:0] p, q, r;
        begin
            gf = grad_fields(h);
            p = axis10(gf[1:0], dx, dy, dz);
            q = axis10(gf[3:2], dx, dy, dz);
            r = axis10(gf[5:4], dx, dy, dz);
            if (gf[6]) p = -p;
            if (gf[7]) q = -q;
            if (gf[8]) r = -r;
            if (gf[9] && gf[10]) grad = {p[9], p} + {q[9], q} + {r[9], r};
            else if (gf[9]) grad = {p[9], p} + {q[9], q};
            else grad = {p[9], p} + {r[9], r};
        end
    endfunction
    // s-curve: round(u^2 (768 - 2u) / 2^(24 - WS)), u(WS+1). The numerator is
    // exact in u24; one extra bit holds the rounding carry.
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

    wire [SW-1:0] h_sx, h_sy, h_sz;  // s(u), s(v), s(w): u(WS+1) Q1.WS
    // LERP_SERIAL: the engine's fraction this step (u, v or w) and its s-curve. Whichever of
    // these and h_s* the variant does not read has no load: synthesis removes its logic.
    wire [7:0] e_t;
    wire [SW-1:0] e_s;
    generate
        if (S_TABLE == 0) begin : g_sarith
            // u^2 etc. in L (u16 Q0.16, held in bank R0), the rest of the formula in H
            reg [15:0] r0_su, r0_sv, r0_sw;
            always @(posedge clk) if (l_acc) begin
                r0_su <= cx[7:0] * cx[7:0];
                r0_sv <= cy[7:0] * cy[7:0];
                r0_sw <= cz[7:0] * cz[7:0];
            end
            assign h_sx = scurve(r0_su, r0_u);
            assign h_sy = scurve(r0_sv, r0_v);
            assign h_sz = scurve(r0_sw, r0_w);
            assign e_s = scurve({8'd0, e_t} * {8'd0, e_t}, e_t);  // LERP_SERIAL's one s-curve
        end else begin : g_stable
            // the table: entry t is scurve(t*t, t), the formula's value, computed at
            // elaboration (a constant); one copy per axis, indexed by the fraction.
            // Entries sit at a power-of-two pitch TP >= SW (the bits above SW are 0),
            // so the index is {t, TB zeros}: a plain 256-way ROM select. With pitch SW
            // (index SW * t) Yosys builds a barrel shifter over the whole table that ABC
            // does not fold back: 2,829.5 NAND2 against 474 for one s_frac=9 table.
            localparam integer TB = SW <= 8 ? 3 : SW <= 16 ? 4 : 5;  // SW <= 25
            localparam integer TP = 1 << TB;
            wire [256*TP-1:0] s_rom;
            genvar t;
            for (t = 0; t < 256; t = t + 1) begin : g_entry
                localparam [31:0] T32 = t;        // u8: the fraction
                localparam [31:0] SQ32 = t * t;   // u16: its square
`ifdef NP_FAULT_STABLE
                // fault: a wrong bit (weight 2^-2 of 1.0) in every 16th entry
                assign s_rom[TP*t+:SW] = scurve(SQ32[15:0], T32[7:0]) ^ (T32[3:0] == 4'h5 ? 1 << (SW - 3) : 0);
`else
                assign s_rom[TP*t+:SW] = scurve(SQ32[15:0], T32[7:0]);
`endif
                if (TP > SW) begin : g_pad
                    assign s_rom[TP*t+SW+:TP-SW] = 0;
                end
            end
            assign h_sx = s_rom[{r0_u, {TB{1'b0}}}+:SW];
            assign h_sy = s_rom[{r0_v, {TB{1'b0}}}+:SW];
            assign h_sz = s_rom[{r0_w, {TB{1'b0}}}+:SW];
            assign e_s = s_rom[{e_t, {TB{1'b0}}}+:SW];  // LERP_SERIAL's one lookup
        end
    endgenerate
    // ---------------------------------------------------------------- I1m, I1a
    // s * (b - a): s is unsigned, so it enters the signed product zero-extended.
    function signed [P1W-1:0] mul1;
        input [SW-1:0] s;
        input signed [GW-1:0] a, b;
        reg signed [D1W-1:0] d;
        reg signed [P1W-1:0] sp, dp;
        begin
            d = {b[GW-1], b} - {a[GW-1], a};
            sp = {{(P1W-SW){1'b0}}, s};
            dp = {{(P1W-D1W){d[D1W-1]}}, d};
            mul1 = sp * dp;
        end
    endfunction
    function signed [P2W-1:0] mul2;
        input [SW-1:0] s;
        input signed [LW-1:0] a, b;
        reg signed [D2W-1:0] d;
        reg signed [P2W-1:0] sp, dp;
        begin
            d = {b[LW-1], b} - {a[LW-1], a};
            sp = {{(P2W-SW){1'b0}}, s};
            dp = {{(P2W-D2W){d[D2W-1]}}, d};
            mul2 = sp * dp;
        end
    endfunction
    function signed [LW-1:0] lerp1;
        input signed [GW-1:0] a;
        input signed [P1W-1:0] pr;
        reg signed [S1W-1:0] s, t;
        begin
            s = {{(S1W-GW){a[GW-1]}}, a};
            t = {{(S1W-P1W){pr[P1W-1]}}, pr};
            s = (s <<< WS) + t;
            t = 1;
            if (SH1 > 0) s = (s + (t <<< (SH1 > 0 ? SH1 - 1 : 0))) >>> (SH1 > 0 ? SH1 : 0);
            else s = s <<< (SH1 > 0 ? 0 : -SH1);
            lerp1 = s[LW-1:0];
        end
    endfunction
    function signed [LW-1:0] lerp2;  // a*2^WS + prod, rounded from WL + WS to WL bits
        input signed [LW-1:0] a;
        input signed [P2W-1:0] pr;
        reg signed [S2W-1:0] s, t;
        begin
            s = {{(S2W-LW){a[LW-1]}}, a};
            t = {{(S2W-P2W){pr[P2W-1]}}, pr};
            s = (s <<< WS) + t;
            t = 1;
            s = (s + (t <<< (WS - 1))) >>> WS;
            lerp2 = s[LW-1:0];
        end
    endfunction
    // LERP_SERIAL's lerp unit: a + s * (b - a) for all three levels, on operands
    // at FC = max(WL, 8) fraction bits (g << FC - 8, l << FC - WL: exact). The sum
    // a*2^WS + s*(b - a), exact at FC + WS fraction bits, is rounded half up to WL:
    // the same exact value and the same rounding as lerp1 (FI + WS -> WL bits) and
    // lerp2 (WL + WS -> WL), so the same bits. SHE = FC + WS - WL >= 1.
    localparam integer FC = WL > FI ? WL : FI;
    localparam integer EOW = FC + 3;      // operand: g or l, s(FC+3) Q2.FC
    localparam integer EDW = EOW + 1;     // b - a
    localparam integer EPW = EDW + SW;    // s * (b - a)
    localparam integer EEW = EPW + 2;     // the sum and the rounding carry
    localparam integer SHE = FC + WS - WL;
    function signed [LW-1:0] elerp;
        input [SW-1:0] s;
        input signed [EOW-1:0] a, b;
        reg signed [EDW-1:0] d;
        reg signed [EPW-1:0] sp, dp;
        reg signed [EEW-1:0] t, pe, one;
        begin
            d = {b[EOW-1], b} - {a[EOW-1], a};
            sp = {{(EPW-SW){1'b0}}, s};
            dp = {{(EPW-EDW){d[EDW-1]}}, d};
            sp = sp * dp;
            t = {{(EEW-EOW){a[EOW-1]}}, a};
            pe = {{(EEW-EPW){sp[EPW-1]}}, sp};
            t = (t <<< WS) + pe;
            one = 1;
            t = (t + (one <<< (SHE - 1))) >>> SHE;
            elerp = t[LW-1:0];
        end
    endfunction

    reg signed [L3W-1:0] r7_l3;  // l3 (both datapaths)
    generate
        if (LERP_SERIAL == 0) begin : g_pipe
            // stages H to I3a, one bank each, one point per clock
            integer c, p;
            wire signed [8:0] du0 = {1'b0, r0_u}, dv0 = {1'b0, r0_v}, dw0 = {1'b0, r0_w};
            wire signed [8:0] du1 = {1'b1, r0_u}, dv1 = {1'b1, r0_v}, dw1 = {1'b1, r0_w};  // t - 256
            assign e_t = 8'd0;
            assign e_free = 1'b0;
            assign e_fin = 1'b0;
            wire unused_e_s = ^e_s;
            reg signed [GW-1:0] r1_g[0:7];
            reg [SW-1:0] r1_sx, r1_sy, r1_sz;
            always @(posedge clk) if (en[1] && v[0]) begin
                for (c = 0; c < 8; c = c + 1)
                    r1_g[c] <= grad(r0_h[6*c+:6], c[0] ? du1 : du0, c[1] ? dv1 : dv0, c[2] ? dw1 : dw0);
                r1_sx <= h_sx;
                r1_sy <= h_sy;
                r1_sz <= h_sz;
            end

            reg signed [GW-1:0] r2_a[0:3];
            reg signed [P1W-1:0] r2_p[0:3];
            reg [SW-1:0] r2_sy, r2_sz;
            always @(posedge clk) if (en[2] && v[1]) begin
                for (p = 0; p < 4; p = p + 1) begin
                    r2_a[p] <= r1_g[2*p];
                    r2_p[p] <= mul1(r1_sx, r1_g[2*p], r1_g[2*p+1]);
                end
                r2_sy <= r1_sy;
                r2_sz <= r1_sz;
            end

            // Level-1 sum with FI + WS fraction bits, rounded (or widened) to WL.
            reg signed [LW-1:0] r3_l[0:3];
            reg [SW-1:0] r3_sy, r3_sz;
            always @(posedge clk) if (en[3] && v[2]) begin
                for (p = 0; p < 4; p = p + 1) r3_l[p] <= lerp1(r2_a[p], r2_p[p]);
                r3_sy <= r2_sy;
                r3_sz <= r2_sz;
            end

            // ---------------------------------------------------------------- I2m, I2a, I3m, I3a
            reg signed [LW-1:0] r4_a[0:1];
            reg signed [P2W-1:0] r4_p[0:1];
            reg [SW-1:0] r4_sz;
            always @(posedge clk) if (en[4] && v[3]) begin
                for (p = 0; p < 2; p = p + 1) begin
                    r4_a[p] <= r3_l[2*p];
                    r4_p[p] <= mul2(r3_sy, r3_l[2*p], r3_l[2*p+1]);
                end
                r4_sz <= r3_sz;
            end
            reg signed [LW-1:0] r5_l[0:1];
            reg [SW-1:0] r5_sz;
            always @(posedge clk) if (en[5] && v[4]) begin
                for (p = 0; p < 2; p = p + 1) r5_l[p] <= lerp2(r4_a[p], r4_p[p]);
                r5_sz <= r4_sz;
            end
            reg signed [LW-1:0] r6_a;
            reg signed [P2W-1:0] r6_p;
            always @(posedge clk) if (en[6] && v[5]) begin
                r6_a <= r5_l[0];
                r6_p <= mul2(r5_sz, r5_l[0], r5_l[1]);
            end
            // |l3| <= 1.5 (np_classic.h): l3 fits s(WL+2); lerp2's top bit is a copy of its sign.
            wire signed [LW-1:0] l3_full = lerp2(r6_a, r6_p);
            always @(posedge clk) if (en[7] && v[6]) r7_l3 <= l3_full[L3W-1:0];
            wire unused_l3_sign = l3_full[LW-1];
        end else begin : g_engine
            // LERP_SERIAL: one engine does stages H to I3a for one point at a time, with
            // two gradient decoders and one lerp unit (elerp), step k = r1_k on the
            // clocks after it takes bank L's content:
            //   k 0..3  l1[k]   = lerp(g[2k], g[2k+1], s(u))   corners 2k, 2k+1
            //   k 4, 5  l2[k-4] = lerp(l1[2k-8], l1[2k-7], s(v))
            //   k 6     l3      = lerp(l2[0], l2[1], s(w))     into bank R7 when it loads
            // It holds its own copy of the point (r1_h, r1_u, r1_v, r1_w), so L hashes
            // the next point meanwhile; free again after step 6, it takes the next at
            // that edge: 7 clocks a point, under L's 8 (1 result / 8 clocks).
            reg [6*8-1:0] r1_h;
            reg [7:0] r1_u, r1_v, r1_w;
            reg [2:0] r1_k;
            reg r1_busy;
            reg signed [LW-1:0] r1_l[0:5];  // l1[0..3], then l2[0..1]
            integer q;
            wire e_last = r1_busy && r1_k == 3'd6;
            assign e_fin = e_last;
            // en[7] spelled out (the vector en also holds en[1] = e_free: not a loop,
            // but Verilator would schedule it as one)
            wire en7 = !v[7] || !v[8] || core_out_ready;
            assign e_free = !r1_busy || (e_last && en7);
            wire e_take = v[0] && e_free;
`ifdef NP_FAULT_LSERIAL
            // fault: the engine reads L's bank (saving the 48-bit copy), which L
            // overwrites with the next point's hashes while the engine still needs them
            wire [6*8-1:0] e_h = r0_h;
            wire unused_fault_h = ^r1_h;
`else
            wire [6*8-1:0] e_h = r1_h;
`endif
            // corners 2k (x offset u) and 2k+1 (u - 256); y and z offsets from k's bits
            wire [11:0] hp = r1_k[1] ? (r1_k[0] ? e_h[47:36] : e_h[35:24]) : (r1_k[0] ? e_h[23:12] : e_h[11:0]);
            wire signed [8:0] eu0 = {1'b0, r1_u}, eu1 = {1'b1, r1_u};
            wire signed [8:0] ev = {r1_k[0], r1_v}, ew = {r1_k[1], r1_w};
            wire signed [GW-1:0] ga = grad(hp[5:0], eu0, ev, ew), gb = grad(hp[11:6], eu1, ev, ew);
            // level 2 or 3 operands: k = 4: l1[0], l1[1]; 5: l1[2], l1[3]; 6: l2[0], l2[1]
            wire signed [LW-1:0] la = r1_k[1] ? r1_l[4] : (r1_k[0] ? r1_l[2] : r1_l[0]);
            wire signed [LW-1:0] lb = r1_k[1] ? r1_l[5] : (r1_k[0] ? r1_l[3] : r1_l[1]);
            // operands at FC fraction bits (sign-extended, shifted left: exact)
            wire [EOW-1:0] ag = {{(EOW-GW+1){ga[GW-1]}}, ga[GW-2:0]} << (FC - FI);
            wire [EOW-1:0] bg = {{(EOW-GW+1){gb[GW-1]}}, gb[GW-2:0]} << (FC - FI);
            wire [EOW-1:0] al = {{(EOW-LW+1){la[LW-1]}}, la[LW-2:0]} << (FC - WL);
            wire [EOW-1:0] bl = {{(EOW-LW+1){lb[LW-1]}}, lb[LW-2:0]} << (FC - WL);
            assign e_t = r1_k[2] ? (r1_k[1] ? r1_w : r1_v) : r1_u;
            wire signed [LW-1:0] e_l = elerp(e_s, r1_k[2] ? al : ag, r1_k[2] ? bl : bg);
            always @(posedge clk) begin
                if (rst) r1_busy <= 1'b0;
                else if (e_take) r1_busy <= 1'b1;
                else if (e_last && en7) r1_busy <= 1'b0;
                if (e_take) begin
                    r1_h <= r0_h;
                    r1_u <= r0_u;
                    r1_v <= r0_v;
                    r1_w <= r0_w;
                    r1_k <= 3'd0;
                end else if (r1_busy && !e_last) begin
                    r1_k <= r1_k + 3'd1;
                    for (q = 0; q < 6; q = q + 1)
                        if (r1_k == q[2:0]) r1_l[q] <= e_l;
                end
            end
            // |l3| <= 1.5: it fits s(WL+2), as in the pipeline
            always @(posedge clk) if (en[7] && e_fin) r7_l3 <= e_l[L3W-1:0];
            wire unused_l3_sign = e_l[LW-1];
            wire unused_h_s = ^{h_sx, h_sy, h_sz};  // the pipeline's s-curves: no load here
        end
    endgenerate

    // ---------------------------------------------------------------- O
    // round(l3) to F fraction bits (half up), saturate to N bits.
    localparam integer SHO = WL - F;      // >= 0 (lerp_frac >= out_bits - 2)
    localparam integer OW = L3W + 1;      // l3 plus the rounding carry
    localparam signed [OW-1:0] HI = (1 << (N - 1)) - 1;
    localparam signed [OW-1:0] LO = -(1 << (N - 1));
    reg signed [OW-1:0] o_r, o_one;
    reg [N-1:0] o_f;
    always @(*) begin
        o_r = {r7_l3[L3W-1], r7_l3};
        o_one = 1;
        if (SHO > 0) o_r = (o_r + (o_one <<< (SHO > 0 ? SHO - 1 : 0))) >>> SHO;
        o_f = o_r > HI ? HI[N-1:0] : (o_r < LO ? LO[N-1:0] : o_r[N-1:0]);
`ifdef NP_FAULT_FLIP
        if (r7_l3[3:0] == 4'h5) o_f[0] = !o_f[0];  // fault: a datapath bit, 1 input in 16
`endif
    end
    reg [N-1:0] r8_f;
    always @(posedge clk) if (en[8] && v[7]) r8_f <= o_f;
    assign core_f = r8_f;

    // ---------------------------------------------------------------- options
    np_pipe_in_reg #(.W(48), .ON(IN_REG)) u_in (
        .clk(clk), .rst(rst),
        .s_valid(in_valid), .s_ready(in_ready), .s_data({x, y, z}),
        .m_valid(core_in_valid), .m_ready(core_in_ready), .m_data({cx, cy, cz}));
    np_pipe_skid #(.W(N), .ON(OUT_SKID)) u_out (
        .clk(clk), .rst(rst),
        .s_valid(core_out_valid), .s_ready(core_out_ready), .s_data(core_f),
        .m_valid(out_valid), .m_ready(out_ready), .m_data(f));
endmodule
