// SPDX-License-Identifier: MIT
// rtl_simplex3_tb - runs the reference RTL rtl_model/verilog/np_simplex3.v on
// a golden vector file ($readmemh export of `noisepipe vectors --unit
// simplex3`), under Icarus Verilog and Verilator (--binary) alike. The same
// bench as rtl_classic3_tb.v with the simplex unit's outputs: f, and with
// deriv=1 dfdx, dfdy, dfdz (the word's fields after x, y, z).
//
// One compiled bench holds every configuration of the table below, one DUT
// instance each; +cfg=NAME picks the one that runs (the others sit idle with
// their clock held), so one Verilated build serves every configuration. The
// file reading, plusargs, driver and verdict are np_tb_vec.vh's.
//
//   +cfg=NAME       default | f_only | t1 | narrow | wide_p | opts | coarse
//   +vectors, +bubble, +stall, +seed as np_tb_vec.vh says.
// Lint: a bench, not hardware: its clocked process is procedural code that
// reads files and keeps counts, so blocking assignments are intended there.
/* verilator lint_off BLKSEQ */
module rtl_simplex3_tb;
    localparam integer NCFG = 7;
    localparam integer NAME_W = 8;
    function [8*NAME_W-1:0] cfg_name;
        input integer k;
        case (k)
            0: cfg_name = "default";
            1: cfg_name = "f_only";
            2: cfg_name = "t1";
            3: cfg_name = "narrow";
            4: cfg_name = "wide_p";
            5: cfg_name = "opts";
            default: cfg_name = "coarse";
        endcase
    endfunction

    reg [15:0] x = 16'd0, y = 16'd0, z = 16'd0;
    wire [80*NCFG-1:0] o_k;      // each DUT's result fields, right-aligned: {f[, dfdx, dfdy, dfdz]}
    reg [NCFG*8-1:0] rw_k;       // their width
    reg [NCFG*48-1:0] cfg_k;     // out_bits dout_bits deriv t_frac p_frac k_frac, 8 bits each

    reg [159:0] word, want_word;
    integer nb, c_n, c_nd, c_d, c_wt, c_wp, c_wk;
    reg [79:0] got_m, want_m, mask80;
`define NP_TB "rtl_simplex3_tb"
`include "np_tb_vec.vh"

`define NP_DUT(K, N, ND, D, WT, WP, WK, IR, OS) \
    wire clk_``K = clk & (sel == K); \
    wire [N-1:0] f_``K; \
    wire [ND-1:0] dx_``K, dy_``K, dz_``K; \
    np_simplex3 #(.OUT_BITS(N), .DOUT_BITS(ND), .DERIV(D), .T_FRAC(WT), .P_FRAC(WP), .K_FRAC(WK), \
                  .IN_REG(IR), .OUT_SKID(OS)) dut_``K ( \
        .clk(clk_``K), .rst(rst), .in_valid(in_valid && sel == K), .in_ready(in_ready_k[K]), \
        .x(x), .y(y), .z(z), .out_valid(out_valid_k[K]), .out_ready(out_ready), .f(f_``K), \
        .dfdx(dx_``K), .dfdy(dy_``K), .dfdz(dz_``K)); \
    assign o_k[80*K+:80] = D ? {{(80-N-3*ND){1'b0}}, f_``K, dx_``K, dy_``K, dz_``K} \
                             : {{(80-N){1'b0}}, f_``K}; \
    initial begin rw_k[8*K+:8] = D ? N + 3 * ND : N; cfg_k[48*K+:48] = {8'd N, 8'd ND, 8'd D, 8'd WT, 8'd WP, 8'd WK}; end

    `NP_DUT(0, 16, 16, 1, 24, 22, 22, 0, 0)
    `NP_DUT(1, 16, 16, 0, 23, 20, 22, 0, 0)
    `NP_DUT(2, 16, 16, 1, 1, 22, 22, 0, 0)
    `NP_DUT(3, 8, 8, 1, 16, 14, 14, 0, 0)
    `NP_DUT(4, 12, 10, 1, 10, 30, 4, 0, 0)
    `NP_DUT(5, 16, 16, 1, 24, 22, 22, 1, 1)
    `NP_DUT(6, 16, 16, 1, 20, 14, 16, 0, 0)

    wire [79:0] o80 = o_k[80*sel+:80];


    task header_line(output integer took);
        integer n1, n2, n3, n4, n5, n6;
        begin
            took = $sscanf(line, "// config out_bits=%d dout_bits=%d deriv=%d t_frac=%d p_frac=%d k_frac=%d",
                           n1, n2, n3, n4, n5, n6) == 6 ? 1 : 0;
            if (took != 0) begin
                c_n = n1; c_nd = n2; c_d = n3; c_wt = n4; c_wp = n5; c_wk = n6;
            end
        end
    endtask

    initial begin
        np_tb_open("default");
        c_n = -1; c_nd = -1; c_d = -1; c_wt = -1; c_wp = -1; c_wk = -1;
    end

    // The word: {valid, x, y, z, the result fields} (nb bits of them).
    task layout;
        begin
            nb = {24'd0, rw_k[8*sel+:8]};
            vpos = nb + 48;
        end
    endtask

    task check_result;
        begin
            mask80 = {80{1'b1}} >> (80 - nb);
            want_m = want_word[79:0] & mask80;
            got_m = o80 & mask80;
            if (got_m !== want_m) begin
                errors = errors + 1;
                if (errors <= MAX_ERRORS)
                    $display("%h %h %h => %h expected: %h  (vector %0d)", want_word[nb+47-:16],
                             want_word[nb+31-:16], want_word[nb+15-:16], got_m, want_m, n_out);
            end
        end
    endtask

    task check_config;
        if ({c_n[7:0], c_nd[7:0], c_d[7:0], c_wt[7:0], c_wp[7:0], c_wk[7:0]} != cfg_k[48*sel+:48])
            $fatal(1, "rtl_simplex3_tb: %0s is for out_bits=%0d dout_bits=%0d deriv=%0d t_frac=%0d p_frac=%0d k_frac=%0d, not for cfg %0s",
                   vec_path, c_n, c_nd, c_d, c_wt, c_wp, c_wk, want_name);
    endtask

    task drive_input;
        {x, y, z} <= word[nb+47-:48];
    endtask

    task report_pass;
        $display("rtl_simplex3_tb: cfg %0s (out_bits=%0d dout_bits=%0d deriv=%0d t_frac=%0d p_frac=%0d k_frac=%0d), %0d cycles: In %0d tests, no errors found.",
                 want_name, c_n, c_nd, c_d, c_wt, c_wp, c_wk, cycles, n_in);
    endtask
endmodule
