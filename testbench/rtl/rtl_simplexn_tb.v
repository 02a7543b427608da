// SPDX-License-Identifier: MIT
// rtl_simplexn_tb - runs the reference RTL rtl_model/verilog/np_simplexn.v on
// a golden vector file ($readmemh export of `noisepipe vectors --unit
// simplexN`, N = 2, 4, 5, or of simplex3's sets: at DIMS = 3 the module must
// give simplex3's f bit for bit, and the bench checks the word's f field,
// ignoring simplex3's derivative fields), under Icarus Verilog and Verilator
// (--binary) alike. The same bench as rtl_simplex3_tb.v (one DUT instance
// per configuration of the table below, +cfg=NAME picks the one that runs,
// the file read as text through two handles, "// count N" and "// config"
// required and checked, random bubbles and stalls); its header parsing takes
// both config lines:
//   n-D sets   "// config dims=D out_bits=N t_frac=WT p_frac=WP"  (k_frac 0)
//   simplex3   "// config out_bits=N dout_bits=ND deriv=1 t_frac=WT p_frac=WP k_frac=WK"
//              (dims 3; the word's result is {f, dfdx, dfdy, dfdz}, f checked)
//
//   +cfg=NAME       s2 s2_coarse s2_narrow s4 s4_coarse s4_narrow s5 s5_coarse
//                   s5_narrow s3 s3_t1 s3_coarse s4_opts
//   +vectors, +bubble, +stall, +seed as np_tb_vec.vh says (file reading, driver
//   and verdict are its too).
// Verdict: "In N tests, no errors found." or $fatal (non-zero exit status).
// Lint: a bench, not hardware: its clocked process is procedural code that
// reads files and keeps counts, so blocking assignments are intended there.
/* verilator lint_off BLKSEQ */
module rtl_simplexn_tb;
    localparam integer NCFG = 13;
    localparam integer NAME_W = 10;
    function [8*NAME_W-1:0] cfg_name;
        input integer k;
        case (k)
            0: cfg_name = "s2";
            1: cfg_name = "s2_coarse";
            2: cfg_name = "s2_narrow";
            3: cfg_name = "s4";
            4: cfg_name = "s4_coarse";
            5: cfg_name = "s4_narrow";
            6: cfg_name = "s5";
            7: cfg_name = "s5_coarse";
            8: cfg_name = "s5_narrow";
            9: cfg_name = "s3";
            10: cfg_name = "s3_t1";
            11: cfg_name = "s3_coarse";
            default: cfg_name = "s4_opts";
        endcase
    endfunction

    reg [79:0] xin = 80'd0;      // the word's inputs, right-aligned: {x, y, ...}
    wire [20*NCFG-1:0] f_k;      // each DUT's f, right-aligned
    reg [NCFG*40-1:0] cfg_k;     // dims out_bits t_frac p_frac k_frac, 8 bits each

    reg [159:0] word, want_word;  // valid, inputs, result
    integer c_dims, c_n, c_nd, c_d, c_wt, c_wp, c_wk, dims, rw, fsh, nbits;
    /* verilator lint_off UNUSEDSIGNAL */
    reg [159:0] sh;  // the word shifted to a field (its top bits are not read)
    /* verilator lint_on UNUSEDSIGNAL */
    reg [19:0] got_m, want_m, mask20;
`define NP_TB "rtl_simplexn_tb"
`include "np_tb_vec.vh"

`define NP_DUT(K, D, N, WT, WP, WK, IR, OS) \
    wire clk_``K = clk & (sel == K); \
    wire [N-1:0] f_``K; \
    np_simplexn #(.DIMS(D), .OUT_BITS(N), .T_FRAC(WT), .P_FRAC(WP), .K_FRAC(WK), \
                  .IN_REG(IR), .OUT_SKID(OS)) dut_``K ( \
        .clk(clk_``K), .rst(rst), .in_valid(in_valid && sel == K), .in_ready(in_ready_k[K]), \
        .x(xin[16*D-1:0]), .out_valid(out_valid_k[K]), .out_ready(out_ready), .f(f_``K)); \
    assign f_k[20*K+:20] = {{(20-N){1'b0}}, f_``K}; \
    initial cfg_k[40*K+:40] = {8'd D, 8'd N, 8'd WT, 8'd WP, 8'd WK};

    `NP_DUT(0, 2, 16, 25, 25, 0, 0, 0)
    `NP_DUT(1, 2, 16, 14, 20, 0, 0, 0)
    `NP_DUT(2, 2, 20, 3, 14, 0, 0, 0)
    `NP_DUT(3, 4, 16, 25, 25, 0, 0, 0)
    `NP_DUT(4, 4, 16, 14, 20, 0, 0, 0)
    `NP_DUT(5, 4, 20, 3, 14, 0, 0, 0)
    `NP_DUT(6, 5, 16, 25, 25, 0, 0, 0)
    `NP_DUT(7, 5, 16, 14, 20, 0, 0, 0)
    `NP_DUT(8, 5, 20, 3, 14, 0, 0, 0)
    `NP_DUT(9, 3, 16, 24, 22, 22, 0, 0)
    `NP_DUT(10, 3, 16, 1, 22, 22, 0, 0)
    `NP_DUT(11, 3, 16, 20, 14, 16, 0, 0)
    `NP_DUT(12, 4, 16, 25, 25, 0, 1, 1)

    wire [19:0] f20 = f_k[20*sel+:20];


    task header_line(output integer took);
        integer n1, n2, n3, n4, n5, n6;
        begin
            took = 1;
            if ($sscanf(line, "// config out_bits=%d dout_bits=%d deriv=%d t_frac=%d p_frac=%d k_frac=%d",
                        n1, n2, n3, n4, n5, n6) == 6) begin
                c_dims = 3; c_n = n1; c_nd = n2; c_d = n3; c_wt = n4; c_wp = n5; c_wk = n6;
            end else if ($sscanf(line, "// config dims=%d out_bits=%d t_frac=%d p_frac=%d", n1, n2, n3, n4) == 4) begin
                c_dims = n1; c_n = n2; c_nd = 0; c_d = 0; c_wt = n3; c_wp = n4; c_wk = 0;
            end else took = 0;
        end
    endtask

    initial begin
        np_tb_open("s4");
        c_dims = -1; c_n = -1; c_nd = -1; c_d = -1; c_wt = -1; c_wp = -1; c_wk = -1;
    end

    // The word's layout (from the header): [rw + 16 dims] valid, then the
    // inputs, then the result of rw bits whose f is at fsh (above simplex3's
    // derivatives).
    task layout;
        begin
            dims = {24'd0, cfg_k[40*sel+32+:8]};
            nbits = {24'd0, cfg_k[40*sel+24+:8]};
            rw = c_d != 0 ? c_n + 3 * c_nd : c_n;
            fsh = c_d != 0 ? 3 * c_nd : 0;
            vpos = rw + 16 * dims;
        end
    endtask

    task check_result;
        begin
            mask20 = {20{1'b1}} >> (20 - nbits);
            sh = want_word >> fsh;
            want_m = sh[19:0] & mask20;
            got_m = f20 & mask20;
            sh = want_word >> rw;
            if (got_m !== want_m) begin
                errors = errors + 1;
                if (errors <= MAX_ERRORS)
                    $display("%h => %h expected: %h  (vector %0d)", sh[79:0] & ({80{1'b1}} >> (80 - 16 * dims)),
                             got_m, want_m, n_out);
            end
        end
    endtask

    task check_config;
        if ({c_dims[7:0], c_n[7:0], c_wt[7:0], c_wp[7:0], c_wk[7:0]} != cfg_k[40*sel+:40])
            $fatal(1, "rtl_simplexn_tb: %0s is for dims=%0d out_bits=%0d t_frac=%0d p_frac=%0d k_frac=%0d, not for cfg %0s",
                   vec_path, c_dims, c_n, c_wt, c_wp, c_wk, want_name);
    endtask

    task drive_input;
        begin
            sh = word >> rw;
            xin <= sh[79:0] & ({80{1'b1}} >> (80 - 16 * dims));
        end
    endtask

    task report_pass;
        $display("rtl_simplexn_tb: cfg %0s (dims=%0d out_bits=%0d t_frac=%0d p_frac=%0d k_frac=%0d), %0d cycles: In %0d tests, no errors found.",
                 want_name, c_dims, c_n, c_wt, c_wp, c_wk, cycles, n_in);
    endtask
endmodule
