// SPDX-License-Identifier: MIT
// np_hatch - reference RTL of the hatching unit `hatch` (Szecsi and Sziranyi,
// "Recursive Procedural Tonal Art Maps", shared/seeds/003), brute force:
// every seed of every layer, one shading point a clock. Written from the
// bit-exact specification rtl_model/np_hatch.h (docs/hatch.md) and its cycle
// model np_hatch_pipe_init (np_pipe.h). Verilog-2005, synthesizable; Icarus
// and Verilator -Wall clean. One seed lane is np_hatch_seed.v.
//
// Parameters: the unit's configuration keys (noisepipe units --unit hatch)
//   SET      set: 0 fkm16, 1 best16 (default), 2 fkm64, 3 best64 (np_hatch_sets' order)
//   LAYERS   layers 1..4 (4)
//   FADE     fade: 0 smooth (default), 1 one by one
//   GUARD    guard 0..22 (9): colour register F = 8 + GUARD fraction bits
//   LANES    lanes P (1): seeds per stage, a power of two dividing N, <= 16
//   ROT      rot: 0 pin (default), 1 "0", 2 "45", 3 "90", 4 "1e-4" (NP_HATCH_ROT_*)
//   INV_LEN  inv_len u16 Q8.8; 0 (default) is the key's default: 1024 at N = 16, 2048 at N = 64
//   INV_WID  inv_wid u16 Q8.8; 0: 8533 at N = 16, 17067 at N = 64
// and the pipe options IN_REG, OUT_SKID (np_pipe.h, np_classic3.v). The
// coverage-prefiltered unit (cover_slots, not a registry key) is not built here.
//
// Ports (np_hatch.h's formats; the registry's fields):
//   xu, xv  u33 Q1.32  seed-space position mod 2
//   tone    u8 unorm8  a = tone / 255
//   pm      u17 Q1.16  2^-m
//   om      u17 Q1.16  1 - m (saturated to 1 in stage A)
//   c       u8 unorm8  the paper's colour after every stroke, round(255 c)
//
// Banks = stages of the cycle model: A, then G = LAYERS N / LANES seed
// stages S0..S(G-1) (latency 1 + G: 65 at the default, 257 for 4 x 64 seeds).
// Stage S_g holds the LANES seeds pos = g LANES + k (k = 0..LANES-1, layer
// pos / N, seed i = pos mod N: compositing order, i counting up), their
// blends in series; the last stage also rounds the output. What each bank
// holds:
//   A, S0..S(G-2): xu, xv u33; al[0..LAYERS-1] u31 Q1.30; oms u17 Q1.16;
//                  ku, kv u33 Q9.24; col u(F+1) Q1.F (the colour register)
//   S(G-1):        c u8
// Stage A: A = round(tone 2^30 / 255) u31 Q1.30 (a 256-word ROM of constants);
// al[l] = clamp(4 A - l 2^30, 0, 2^30); oms = min(om, 0x10000); ku = pm inv_len,
// kv = pm inv_wid, exact; col = 2^F (white). The seeds (W = rotl_N(b, i),
// st, W[0]) and each layer's R are wiring: constants of each lane.
// The handshake is np_pipe's (np_aacount.v): bank k loads when it is empty or
// its content moves on.
// Lint waiver (Verilator -Wall), for the whole file:
//   UNUSEDSIGNAL  the last bank's carry (x, the tones, k: nothing reads them
//                 after the last seed), each lane's alpha (a trace port), and
//                 the bits of the output rounding below the result.
/* verilator lint_off UNUSEDSIGNAL */
module np_hatch #(
    parameter integer SET = 1,
    parameter integer LAYERS = 4,
    parameter integer FADE = 0,
    parameter integer GUARD = 9,
    parameter integer LANES = 1,
    parameter integer ROT = 0,
    parameter integer INV_LEN = 0,
    parameter integer INV_WID = 0,
    parameter integer IN_REG = 0,
    parameter integer OUT_SKID = 0
) (
`include "np_pipe_ports.vh"
    input wire [32:0] xu,
    input wire [32:0] xv,
    input wire [7:0] tone,
    input wire [16:0] pm,
    input wire [16:0] om,
    output wire [7:0] c
);
    localparam integer N = SET >= 2 ? 64 : 16;
    localparam integer F = 8 + GUARD;
    localparam integer G = LAYERS * N / LANES;  // seed stages
    localparam integer NB = 1 + G;              // banks = latency
    localparam integer IU = INV_LEN != 0 ? INV_LEN : (N == 64 ? 2048 : 1024);
    localparam integer IV = INV_WID != 0 ? INV_WID : (N == 64 ? 17067 : 8533);
    localparam integer IW = 33 + 33 + 8 + 17 + 17;                // the input bundle
    localparam integer CW = 33 + 33 + 31 * LAYERS + 17 + 33 + 33 + F + 1;  // a bank's carry
    localparam [31:0] ONE30 = 32'h40000000;

    // ---------------------------------------------------------------- seeds (np_hatch.c)
    // np_hatch_sets[SET]'s patterns, axis 0 u, 1 v
    function [63:0] set_b;
        input integer s;
        input integer axis;
        begin
            case (s)
                0: set_b = axis == 0 ? 64'h0a5f : 64'h23b3;
                1: set_b = axis == 0 ? 64'h0da7 : 64'h3e94;
                2: set_b = axis == 0 ? 64'h024129b4d896dbff : 64'h105a64169f797717;
                default: set_b = axis == 0 ? 64'h1fb34b5ad1f8c844 : 64'h6ea31ebc148d2e3c;
            endcase
        end
    endfunction
    function [63:0] nmask;
        input integer n;
        nmask = n >= 64 ? ~64'd0 : ((64'd1 << n) - 64'd1);
    endfunction
    // np_hatch_layer_b: u complemented when l & 1, v when l & 2
    function [63:0] layer_b;
        input integer l;
        input integer axis;
        reg [63:0] b;
        begin
            b = set_b(SET, axis) & nmask(N);
            if ((axis == 0 && (l % 2) == 1) || (axis == 1 && (l / 2) % 2 == 1)) b = ~b & nmask(N);
            layer_b = b;
        end
    endfunction
    // rotl_N(b, i)
    function [63:0] rotl;
        input [63:0] b;
        input integer i;
        input integer n;
        begin
            if (i % n == 0) rotl = b & nmask(n);
            else rotl = ((b << (i % n)) | ((b & nmask(n)) >> (n - i % n))) & nmask(n);
        end
    endfunction
    // np_hatch_seed_st: the first 32 bits of 0.WWW...
    function [31:0] seed_st;
        input [63:0] w;
        input integer n;
        reg [63:0] acc;
        integer k;
        begin
            if (n >= 32) begin
                acc = w >> (n - 32);
                seed_st = acc[31:0];
            end else begin
                acc = 64'd0;
                for (k = 0; k < 32; k = k + n) acc = (acc << n) | w;
                seed_st = acc[31:0];
            end
        end
    endfunction
    // np_hatch_layer_r: (c, s) s16 Q1.14; PIN angles 45, -45, 0, 90 degrees for l = 0..3
    function [31:0] layer_r;  // {c, s}
        input integer l;
        integer k;
        begin
            if (ROT == 0) k = l == 0 ? 1 : (l == 1 ? 4 : (l == 2 ? 0 : 2));
            else k = ROT - 1;
            case (k)
                0: layer_r = {16'd16384, 16'd0};          // 0
                1: layer_r = {16'd11585, 16'd11585};      // 45
                2: layer_r = {16'd0, 16'd16384};          // 90
                3: layer_r = {16'd16384, 16'd2};          // 1e-4 rad
                default: layer_r = {16'd11585, 16'hd2bf}; // -45: s = -11585
            endcase
        end
    endfunction
    // A = round(tone 2^30 / 255) for every tone: 255 is odd, no ties
    function [31*256-1:0] a_rom;
        input integer words;  // 256
        integer t;
        reg [39:0] q;
        begin
            a_rom = {31*256{1'b0}};
            for (t = 0; t < words; t = t + 1) begin
                q = (({32'd0, t[7:0]} << 30) + 40'd127) / 40'd255;
                a_rom[31*t +: 31] = q[30:0];
            end
        end
    endfunction
    localparam [31*256-1:0] AROM = a_rom(256);

    // ---------------------------------------------------------------- handshake
    wire core_in_valid, core_in_ready, core_out_valid, core_out_ready;
    wire [IW-1:0] cin;
    reg [NB-1:0] v;
    wire [NB-1:0] en, v_next;  // NP_FAULT_STALL: bank S0 overwrites its content when its successor stalls
    np_pipe_ctrl #(.NB(NB), .STALL_BANK(1)) u_ctrl (.v(v), .in_valid(core_in_valid), .out_ready(core_out_ready),
        .en(en), .v_next(v_next), .in_ready(core_in_ready), .out_valid(core_out_valid));
    always @(posedge clk) if (rst) v <= {NB{1'b0}}; else v <= v_next;

    // ---------------------------------------------------------------- A
    wire [32:0] ixu = cin[IW-1 -: 33];
    wire [32:0] ixv = cin[IW-34 -: 33];
    wire [7:0] itone = cin[41:34];
    wire [16:0] ipm = cin[33:17];
    wire [16:0] iom = cin[16:0];
    wire [30:0] a_w = AROM[31*itone +: 31];
    wire [33:0] a4 = {1'b0, a_w, 2'b00};  // 4 A <= 2^32
    reg [31*LAYERS-1:0] al_w;
    integer l_a;
    reg signed [35:0] d_a;
    always @(*) begin
        for (l_a = 0; l_a < LAYERS; l_a = l_a + 1) begin
            d_a = $signed({2'b00, a4}) - $signed({4'd0, l_a[1:0], 30'd0});
            al_w[31*l_a +: 31] = d_a < 0 ? 31'd0 : (d_a > $signed({4'd0, ONE30}) ? ONE30[30:0] : d_a[30:0]);
        end
    end
    wire [16:0] oms_w = iom > 17'h10000 ? 17'h10000 : iom;
    wire [32:0] ku_w = {16'd0, ipm} * {17'd0, IU[15:0]};
    wire [32:0] kv_w = {16'd0, ipm} * {17'd0, IV[15:0]};
    wire [F:0] white = {1'b1, {F{1'b0}}};
    // bank k (A, S0..S(G-2)): {xu, xv, al, oms, ku, kv, col}. An array of nets, one a bank (not one
    // flat vector: a simulator that schedules per net would wake every stage on any bank's change).
    wire [CW-1:0] bank [0:G-1];
    reg [CW-1:0] ra;
    always @(posedge clk) if (en[0] && core_in_valid) ra <= {ixu, ixv, al_w, oms_w, ku_w, kv_w, white};
    assign bank[0] = ra;

    // ---------------------------------------------------------------- S0..S(G-1)
    reg [7:0] rc_out;
    genvar g, k;
    generate
        for (g = 0; g < G; g = g + 1) begin : g_st
            wire [CW-1:0] b = bank[g];
            wire [32:0] sxu = b[CW-1 -: 33];
            wire [32:0] sxv = b[CW-34 -: 33];
            wire [31*LAYERS-1:0] sal = b[CW-67 -: 31*LAYERS];
            wire [16:0] soms = b[F+66+17 -: 17];
            wire [32:0] sku = b[F+66 -: 33];
            wire [32:0] skv = b[F+33 -: 33];
            wire [(F+1)*(LANES+1)-1:0] cc;  // the colour before lane k at [(F+1) k +: F+1]
            assign cc[F:0] = b[F:0];
            for (k = 0; k < LANES; k = k + 1) begin : g_lane
                localparam integer POS = g * LANES + k;
                localparam integer L = POS / N;
                localparam integer I = POS % N;
                localparam [63:0] WU = rotl(layer_b(L, 0), I, N);
                localparam [63:0] WV = rotl(layer_b(L, 1), I, N);
                localparam [31:0] RR = layer_r(L);
                wire [30:0] alpha;
                np_hatch_seed #(.ST_U(seed_st(WU, N)), .ST_V(seed_st(WV, N)), .W0_U(WU[0]), .W0_V(WV[0]),
                                .RC(RR[31:16]), .RS(RR[15:0]), .FADE(FADE), .N(N), .I(I), .F(F)) u_seed (
                    .xu(sxu), .xv(sxv), .al(sal[31*L +: 31]), .oms(soms), .ku(sku), .kv(skv),
                    .c_in(cc[(F+1)*k +: F+1]), .c_out(cc[(F+1)*(k+1) +: F+1]), .alpha(alpha));
            end
            wire [F:0] col = cc[(F+1)*LANES +: F+1];
            if (g < G - 1) begin : g_carry
                reg [CW-1:0] r;
                always @(posedge clk) if (en[g+1] && v[g]) r <= {b[CW-1:F+1], col};
                assign bank[g+1] = r;
            end else begin : g_out
                // out = floor((255 col + 2^(F-1)) / 2^F): round(255 c) half up
                wire [F+8:0] c255 = {col, 8'd0} - {8'd0, col} + ({{(F+8){1'b0}}, 1'b1} << (F - 1));
                reg [7:0] o;
                always @(*) begin
                    o = c255[F+7:F];
`ifdef NP_FAULT_FLIP
                    if (col[3:0] == 4'h5) o[0] = !o[0];  // fault: bit 0 of c when the colour word is 5 mod 16
`endif
                end
                always @(posedge clk) if (en[g+1] && v[g]) rc_out <= o;
            end
        end
    endgenerate

    // ---------------------------------------------------------------- options
    np_pipe_opts #(.IW(IW), .OW(8), .IN_REG(IN_REG), .OUT_SKID(OUT_SKID)) u_opts (.clk(clk), .rst(rst),
        .in_valid(in_valid), .in_ready(in_ready), .in_data({xu, xv, tone, pm, om}),
        .core_in_valid(core_in_valid), .core_in_ready(core_in_ready), .core_in_data(cin),
        .core_out_valid(core_out_valid), .core_out_ready(core_out_ready), .core_out_data(rc_out),
        .out_valid(out_valid), .out_ready(out_ready), .out_data(c));
endmodule
/* verilator lint_on UNUSEDSIGNAL */
