// SPDX-License-Identifier: MIT
// rtl_aacount_tb - runs the reference RTL rtl_model/verilog/np_aacount.v on a
// golden vector file ($readmemh export of `noisepipe vectors --unit aacount`),
// under Icarus Verilog and Verilator (--binary) alike. The same bench as
// rtl_simplex3_tb.v with aacount's word: {valid, w0, w1, ..., s, mask, sd, sn,
// ss}, w0 = bus[63:0] first, the last word holding what is left of the
// np_aacount_bus_pack bus (np_aacount.h); outputs s (u5), mask (u16), then
// sd, sn, ss (u5 each) for the metrics that are built (a metric that is off
// has no field: the DUT drives it 0 and the bench checks that too).
//
// One compiled bench holds every configuration of the table below, one DUT
// instance each; +cfg=NAME picks the one that runs.
//
//   +cfg=NAME       default | m2 | m4 | m1 | taps5 | opts | strict
//   +vectors, +bubble, +stall, +seed as np_tb_vec.vh says (file reading, driver
//   and verdict are its too).
//
// The file is read twice, through two handles, as a text file; the bench
// requires the header's "// count N" and "// config" lines, checks that the
// config is the DUT's and that exactly N words are read.
// Verdict: "In N tests, no errors found." or $fatal (non-zero exit status).
// Lint: a bench, not hardware: blocking assignments in its clocked process are
// intended; the bus register is as wide as the widest DUT's and the tile key
// (after the unit) is read but not checked.
/* verilator lint_off BLKSEQ */
/* verilator lint_off UNUSEDSIGNAL */
module rtl_aacount_tb;
    localparam integer NCFG = 7;
    localparam integer NAME_W = 8;
    function [8*NAME_W-1:0] cfg_name;
        input integer k;
        case (k)
            0: cfg_name = "default";
            1: cfg_name = "m2";
            2: cfg_name = "m4";
            3: cfg_name = "m1";
            4: cfg_name = "taps5";
            5: cfg_name = "opts";
            default: cfg_name = "strict";
        endcase
    endfunction

    reg [511:0] bus = 512'd0;
    wire [36*NCFG-1:0] o_k;       // each DUT's {s, mask, sd, sn, ss}
    reg [NCFG*16-1:0] bb_k;       // its bus width
    reg [NCFG*3-1:0] on_k;        // its metrics built: {depth, normal, luma}
    reg [NCFG*144-1:0] cfg_k;     // m depth normal luma luma_taps (8 bits each), c_d (32), c_n, c_s (16), t_min, t_edge

    reg [639:0] word, want_word;
    integer bb, ow;
    reg [31:0] c_m, c_dd, c_nn, c_ll, c_tt, c_tile, c_ser, c_cd, c_cn, c_cs, c_tm, c_te;
    reg [35:0] want36;
    reg [2:0] on;
`define NP_TB "rtl_aacount_tb"
`include "np_tb_vec.vh"

`define NP_DUT(K, MM, DD, NN, LL, TT, CD, CN, CS, TM, TE, IR, OS) \
    wire clk_``K = clk & (sel == K); \
    localparam integer BB_``K = MM * MM * ((DD != 0 ? 24 : 0) + (NN != 0 ? 24 : 0)) + (LL != 0 ? 40 : 0); \
    np_aacount #(.M(MM), .DEPTH(DD), .NORMAL(NN), .LUMA(LL), .LUMA_TAPS(TT), .C_D(CD), .C_N(CN), .C_S(CS), \
                 .T_MIN(TM), .T_EDGE(TE), .IN_REG(IR), .OUT_SKID(OS)) dut_``K ( \
        .clk(clk_``K), .rst(rst), .in_valid(in_valid && sel == K), .in_ready(in_ready_k[K]), \
        .bus(bus[BB_``K-1:0]), .out_valid(out_valid_k[K]), .out_ready(out_ready), \
        .s(o_k[36*K+31+:5]), .mask(o_k[36*K+15+:16]), .sd(o_k[36*K+10+:5]), .sn(o_k[36*K+5+:5]), .ss(o_k[36*K+:5])); \
    initial begin bb_k[16*K+:16] = BB_``K[15:0]; on_k[3*K+:3] = {DD != 0, NN != 0, LL != 0}; \
        cfg_k[144*K+:144] = {8'd MM, 8'd DD, 8'd NN, 8'd LL, 8'd TT, 32'd CD, 16'd CN, 16'd CS, 16'd TM, 16'd TE, 8'd0}; end

    `NP_DUT(0, 3, 1, 1, 1, 4, 1000000, 32, 128, 16, 32, 0, 0)
    `NP_DUT(1, 2, 1, 1, 1, 4, 1000000, 32, 128, 16, 32, 0, 0)
    `NP_DUT(2, 4, 1, 0, 1, 5, 1000000, 32, 128, 16, 32, 0, 0)
    `NP_DUT(3, 1, 1, 1, 1, 4, 1000000, 32, 128, 16, 32, 0, 0)
    `NP_DUT(4, 3, 0, 1, 1, 5, 1000000, 60, 40, 8, 64, 0, 0)
    `NP_DUT(5, 3, 1, 1, 1, 4, 1000000, 32, 128, 16, 32, 1, 1)
    `NP_DUT(6, 3, 1, 1, 0, 4, 4000000000, 255, 128, 16, 32, 0, 0)

    wire [35:0] o36 = o_k[36*sel+:36];


    // The bus of a word: bus bit 64 k + o at word bit LSB(k) + o, LSB(k) =
    // OW + BB - 64 (k + 1) but OW for the last word (OW: the output fields' bits).
    function [511:0] bus_of;
        input [639:0] wd;
        input integer nbits;
        input integer obits;
        integer b, kk, nw, lsb;
        begin
            bus_of = 512'd0;
            nw = (nbits + 63) / 64;
            for (b = 0; b < nbits; b = b + 1) begin
                kk = b / 64;
                lsb = kk == nw - 1 ? obits : obits + nbits - 64 * (kk + 1);
                bus_of[b] = wd[lsb + b % 64];
            end
        end
    endfunction

    // The word's output fields {s, mask[, sd][, sn][, ss]} (ow bits) as 36
    // bits {s, mask, sd, sn, ss}, an absent field 0.
    function [35:0] outs_of;
        input [639:0] wd;
        input [2:0] present;
        integer pos;
        begin
            outs_of = 36'd0;
            pos = 0;
            if (present[0]) begin outs_of[4:0] = wd[pos+:5]; pos = pos + 5; end
            if (present[1]) begin outs_of[9:5] = wd[pos+:5]; pos = pos + 5; end
            if (present[2]) begin outs_of[14:10] = wd[pos+:5]; pos = pos + 5; end
            outs_of[35:15] = wd[pos+:21];
        end
    endfunction
    task header_line(output integer took);
        reg [31:0] a1, a2, a3, a4, a5, a6, a7, a8, a9, a10, a11, a12;
        begin
            took = $sscanf(line,
                "// config m=%d depth=%d normal=%d luma=%d luma_taps=%d tile=%d serial=%d c_d=%d c_n=%d c_s=%d t_min=%d t_edge=%d",
                a1, a2, a3, a4, a5, a6, a7, a8, a9, a10, a11, a12) == 12 ? 1 : 0;
            if (took != 0) begin
                c_m = a1; c_dd = a2; c_nn = a3; c_ll = a4; c_tt = a5; c_tile = a6; c_ser = a7;
                c_cd = a8; c_cn = a9; c_cs = a10; c_tm = a11; c_te = a12;
            end
        end
    endtask

    initial begin
        np_tb_open("default");
        c_m = 0; c_ser = 0; c_tile = 0;
    end

    // The word: {valid, the bus words (bb bits), the output fields (ow bits)}.
    task layout;
        begin
            bb = {16'd0, bb_k[16*sel+:16]};
            on = on_k[3*sel+:3];
            ow = 21 + 5 * ({31'd0, on[0]} + {31'd0, on[1]} + {31'd0, on[2]});
            vpos = bb + ow;
        end
    endtask

    task check_result;
        begin
            want36 = outs_of(want_word, on);
            if (o36 !== want36) begin
                errors = errors + 1;
                if (errors <= MAX_ERRORS)
                    $display("s %0d mask %h sd %0d sn %0d ss %0d expected: s %0d mask %h sd %0d sn %0d ss %0d  (vector %0d)",
                             o36[35:31], o36[30:15], o36[14:10], o36[9:5], o36[4:0],
                             want36[35:31], want36[30:15], want36[14:10], want36[9:5], want36[4:0], n_out);
            end
        end
    endtask

    task check_config;
        if ({c_m[7:0], c_dd[7:0], c_nn[7:0], c_ll[7:0], c_tt[7:0], c_cd, c_cn[15:0], c_cs[15:0],
             c_tm[15:0], c_te[15:0], 8'd0} != cfg_k[144*sel+:144] || c_ser != 0)
            $fatal(1, "rtl_aacount_tb: %0s is for m=%0d depth=%0d normal=%0d luma=%0d luma_taps=%0d serial=%0d c_d=%0d c_n=%0d c_s=%0d t_min=%0d t_edge=%0d, not for cfg %0s",
                   vec_path, c_m, c_dd, c_nn, c_ll, c_tt, c_ser, c_cd, c_cn, c_cs, c_tm, c_te, want_name);
    endtask

    task drive_input;
        bus <= bus_of(word, bb, ow);
    endtask

    task report_pass;
        $display("rtl_aacount_tb: cfg %0s (m=%0d depth=%0d normal=%0d luma=%0d luma_taps=%0d c_d=%0d c_n=%0d c_s=%0d t_min=%0d t_edge=%0d), %0d cycles: In %0d tests, no errors found.",
                 want_name, c_m, c_dd, c_nn, c_ll, c_tt, c_cd, c_cn, c_cs, c_tm, c_te, cycles, n_in);
    endtask
endmodule
/* verilator lint_on UNUSEDSIGNAL */
