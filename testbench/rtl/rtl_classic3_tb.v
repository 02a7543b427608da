// SPDX-License-Identifier: MIT
// rtl_classic3_tb - runs the reference RTL rtl_model/verilog/np_classic3.v on
// a golden vector file ($readmemh export of `noisepipe vectors --unit
// classic3`), under Icarus Verilog and Verilator (--binary) alike.
//
// One compiled bench holds every configuration of the table below, one DUT
// instance each; +cfg=NAME picks the one that runs (the others sit idle with
// their clock held), so one Verilated build serves every configuration. The
// file reading, plusargs, driver and verdict are np_tb_vec.vh's.
//
//   +cfg=NAME       default | s_frac10 | cheap | exact_s | wide_l | opts, and
//                   the circuit variants (np_classic3.v's S_TABLE, HASH_SERIAL,
//                   LERP_SERIAL): s_table | h_serial | both | l_serial | ls_table
//                   (LERP_SERIAL with S_TABLE) at the default configuration,
//                   st_cheap | hs_cheap | bo_cheap | ls_cheap (out_bits=8 s_frac=4 lerp_frac=6),
//                   st_exact (out_bits=12 s_frac=24 lerp_frac=30, S_TABLE),
//                   ls_wide (out_bits=15 s_frac=3 lerp_frac=20, LERP_SERIAL)
//   +vectors, +bubble, +stall, +seed as np_tb_vec.vh says.
// Lint: a bench, not hardware: its clocked process is procedural code that
// reads files and keeps counts, so blocking assignments are intended there.
/* verilator lint_off BLKSEQ */
module rtl_classic3_tb;
    localparam integer NCFG = 17;
    localparam integer NAME_W = 8;
    // name, out_bits, s_frac, lerp_frac, in_reg, out_skid, s_table, hash_serial, lerp_serial
    function [8*NAME_W-1:0] cfg_name;
        input integer k;
        case (k)
            0: cfg_name = "default";
            1: cfg_name = "s_frac10";
            2: cfg_name = "cheap";
            3: cfg_name = "exact_s";
            4: cfg_name = "wide_l";
            5: cfg_name = "opts";
            6: cfg_name = "s_table";
            7: cfg_name = "h_serial";
            8: cfg_name = "both";
            9: cfg_name = "st_cheap";
            10: cfg_name = "hs_cheap";
            11: cfg_name = "bo_cheap";
            12: cfg_name = "st_exact";
            13: cfg_name = "l_serial";
            14: cfg_name = "ls_cheap";
            15: cfg_name = "ls_table";
            default: cfg_name = "ls_wide";
        endcase
    endfunction

    reg [15:0] x = 16'd0, y = 16'd0, z = 16'd0;
    wire [16*NCFG-1:0] f_k;      // each DUT's f, sign-extended to 16 bits
    reg [NCFG*8-1:0] outbits_k;  // each DUT's out_bits (for the checker)
    reg [NCFG*8-1:0] sfrac_k, lfrac_k;

    reg [127:0] word, want_word;
    integer nb, c_n, c_ws, c_wl;
    reg [15:0] want16, got_m, want_m, mask16;
`define NP_TB "rtl_classic3_tb"
`include "np_tb_vec.vh"

`define NP_DUT(K, N, WS, WL, IR, OS, ST, HS, LS) \
    wire clk_``K = clk & (sel == K); \
    wire [N-1:0] f_``K; \
    np_classic3 #(.OUT_BITS(N), .S_FRAC(WS), .LERP_FRAC(WL), .IN_REG(IR), .OUT_SKID(OS), \
                  .S_TABLE(ST), .HASH_SERIAL(HS), .LERP_SERIAL(LS)) dut_``K ( \
        .clk(clk_``K), .rst(rst), .in_valid(in_valid && sel == K), .in_ready(in_ready_k[K]), \
        .x(x), .y(y), .z(z), .out_valid(out_valid_k[K]), .out_ready(out_ready), .f(f_``K)); \
    assign f_k[16*K+:16] = {{(16-N){f_``K[N-1]}}, f_``K}; \
    initial begin outbits_k[8*K+:8] = N; sfrac_k[8*K+:8] = WS; lfrac_k[8*K+:8] = WL; end

    `NP_DUT(0, 8, 12, 11, 0, 0, 0, 0, 0)
    `NP_DUT(1, 8, 10, 11, 0, 0, 0, 0, 0)
    `NP_DUT(2, 8, 4, 6, 0, 0, 0, 0, 0)
    `NP_DUT(3, 12, 24, 30, 0, 0, 0, 0, 0)
    `NP_DUT(4, 15, 3, 20, 0, 0, 0, 0, 0)
    `NP_DUT(5, 8, 12, 11, 1, 1, 0, 0, 0)
    `NP_DUT(6, 8, 12, 11, 0, 0, 1, 0, 0)
    `NP_DUT(7, 8, 12, 11, 0, 0, 0, 1, 0)
    `NP_DUT(8, 8, 12, 11, 0, 0, 1, 1, 0)
    `NP_DUT(9, 8, 4, 6, 0, 0, 1, 0, 0)
    `NP_DUT(10, 8, 4, 6, 0, 0, 0, 1, 0)
    `NP_DUT(11, 8, 4, 6, 0, 0, 1, 1, 0)
    `NP_DUT(12, 12, 24, 30, 0, 0, 1, 0, 0)
    `NP_DUT(13, 8, 12, 11, 0, 0, 0, 0, 1)
    `NP_DUT(14, 8, 4, 6, 0, 0, 0, 0, 1)
    `NP_DUT(15, 8, 12, 11, 0, 0, 1, 0, 1)
    `NP_DUT(16, 15, 3, 20, 0, 0, 0, 0, 1)

    wire [15:0] f16 = f_k[16*sel+:16];


    task header_line(output integer took);
        integer n1, n2, n3;
        begin
            took = $sscanf(line, "// config out_bits=%d s_frac=%d lerp_frac=%d", n1, n2, n3) == 3 ? 1 : 0;
            if (took != 0) begin
                c_n = n1; c_ws = n2; c_wl = n3;
            end
        end
    endtask

    initial begin
        np_tb_open("default");
        c_n = -1; c_ws = -1; c_wl = -1;
    end

    // The word: {valid, x, y, z, f} with f of out_bits.
    task layout;
        begin
            nb = {24'd0, outbits_k[8*sel+:8]};
            vpos = nb + 48;
        end
    endtask

    task check_result;
        begin
            want16 = want_word[15:0];
            mask16 = 16'hffff >> (16 - nb);
            for (k = nb; k < 16; k = k + 1) want16[k] = want16[nb-1];
            if (f16 !== want16) begin
                errors = errors + 1;
                got_m = f16 & mask16;
                want_m = want16 & mask16;
                if (errors <= MAX_ERRORS)
                    $display("%h %h %h => %h expected: %h  (vector %0d)", want_word[nb+47-:16],
                             want_word[nb+31-:16], want_word[nb+15-:16], got_m, want_m, n_out);
            end
        end
    endtask

    task check_config;
        if (c_n != nb || c_ws != {24'd0, sfrac_k[8*sel+:8]} || c_wl != {24'd0, lfrac_k[8*sel+:8]})
            $fatal(1, "rtl_classic3_tb: %0s is for out_bits=%0d s_frac=%0d lerp_frac=%0d, not for cfg %0s",
                   vec_path, c_n, c_ws, c_wl, want_name);
    endtask

    task drive_input;
        {x, y, z} <= word[nb+47-:48];
    endtask

    task report_pass;
        $display("rtl_classic3_tb: cfg %0s (out_bits=%0d s_frac=%0d lerp_frac=%0d), %0d cycles: In %0d tests, no errors found.",
                 want_name, c_n, c_ws, c_wl, cycles, n_in);
    endtask
endmodule
