// SPDX-License-Identifier: MIT
// rtl_classicn_tb - runs the reference RTL rtl_model/verilog/np_classicn.v on
// a golden vector file ($readmemh export of `noisepipe vectors --unit
// classicN`, N = 2, 4, 5, or of classic3's sets: at DIMS = 3 the module must
// give classic3's f bit for bit), under Icarus Verilog and Verilator
// (--binary) alike. The same bench as rtl_classicn_tb.v (one DUT instance
// per configuration of the table below, +cfg=NAME picks the one that runs,
// the file read as text through two handles, "// count N" and "// config"
// required and checked, random bubbles and stalls); its header parsing takes
// both config lines:
//   n-D sets   "// config dims=D out_bits=N s_frac=WS lerp_frac=WL"
//   classic3   "// config out_bits=N s_frac=WS lerp_frac=WL"  (dims 3)
// The word is {valid, the DIMS inputs, f}.
//
//   +cfg=NAME       c2 c2_wide_l c4 c4_wide_l c5 c5_wide_l c3 c3_cheap c3_wide_l
//                   c4_opts
//   +vectors, +bubble, +stall, +seed as np_tb_vec.vh says (file reading, driver
//   and verdict are its too).
// Verdict: "In N tests, no errors found." or $fatal (non-zero exit status).
// Lint: a bench, not hardware: its clocked process is procedural code that
// reads files and keeps counts, so blocking assignments are intended there.
/* verilator lint_off BLKSEQ */
module rtl_classicn_tb;
    localparam integer NCFG = 10;
    localparam integer NAME_W = 10;
    function [8*NAME_W-1:0] cfg_name;
        input integer k;
        case (k)
            0: cfg_name = "c2";
            1: cfg_name = "c2_wide_l";
            2: cfg_name = "c4";
            3: cfg_name = "c4_wide_l";
            4: cfg_name = "c5";
            5: cfg_name = "c5_wide_l";
            6: cfg_name = "c3";
            7: cfg_name = "c3_cheap";
            8: cfg_name = "c3_wide_l";
            default: cfg_name = "c4_opts";
        endcase
    endfunction

    reg [79:0] xin = 80'd0;      // the word's inputs, right-aligned: {x, y, ...}
    wire [16*NCFG-1:0] f_k;      // each DUT's f, right-aligned
    reg [NCFG*32-1:0] cfg_k;     // dims out_bits s_frac lerp_frac, 8 bits each

    reg [159:0] word, want_word;  // valid, inputs, result
    integer c_dims, c_n, c_ws, c_wl, dims, rw, nbits;
    /* verilator lint_off UNUSEDSIGNAL */
    reg [159:0] sh;  // the word shifted to a field (its top bits are not read)
    /* verilator lint_on UNUSEDSIGNAL */
    reg [15:0] got_m, want_m, mask16;
`define NP_TB "rtl_classicn_tb"
`include "np_tb_vec.vh"

`define NP_DUT(K, D, N, WS, WL, IR, OS) \
    wire clk_``K = clk & (sel == K); \
    wire [N-1:0] f_``K; \
    np_classicn #(.DIMS(D), .OUT_BITS(N), .S_FRAC(WS), .LERP_FRAC(WL), \
                  .IN_REG(IR), .OUT_SKID(OS)) dut_``K ( \
        .clk(clk_``K), .rst(rst), .in_valid(in_valid && sel == K), .in_ready(in_ready_k[K]), \
        .x(xin[16*D-1:0]), .out_valid(out_valid_k[K]), .out_ready(out_ready), .f(f_``K)); \
    assign f_k[16*K+:16] = {{(16-N){1'b0}}, f_``K}; \
    initial cfg_k[32*K+:32] = {8'd D, 8'd N, 8'd WS, 8'd WL};

    `NP_DUT(0, 2, 8, 12, 11, 0, 0)
    `NP_DUT(1, 2, 12, 3, 12, 0, 0)
    `NP_DUT(2, 4, 8, 12, 10, 0, 0)
    `NP_DUT(3, 4, 12, 3, 12, 0, 0)
    `NP_DUT(4, 5, 8, 12, 10, 0, 0)
    `NP_DUT(5, 5, 12, 3, 12, 0, 0)
    `NP_DUT(6, 3, 8, 12, 11, 0, 0)
    `NP_DUT(7, 3, 8, 4, 6, 0, 0)
    `NP_DUT(8, 3, 15, 3, 20, 0, 0)
    `NP_DUT(9, 4, 8, 12, 10, 1, 1)

    wire [15:0] f16 = f_k[16*sel+:16];


    task header_line(output integer took);
        integer n1, n2, n3, n4;
        begin
            took = 1;
            if ($sscanf(line, "// config dims=%d out_bits=%d s_frac=%d lerp_frac=%d", n1, n2, n3, n4) == 4) begin
                c_dims = n1; c_n = n2; c_ws = n3; c_wl = n4;
            end else if ($sscanf(line, "// config out_bits=%d s_frac=%d lerp_frac=%d", n1, n2, n3) == 3) begin
                c_dims = 3; c_n = n1; c_ws = n2; c_wl = n3;
            end else took = 0;
        end
    endtask

    initial begin
        np_tb_open("c4");
        c_dims = -1; c_n = -1; c_ws = -1; c_wl = -1;
    end

    // The word's layout (from the header): [rw + 16 dims] valid, then the
    // inputs, then the result f of rw = N bits.
    task layout;
        begin
            dims = {24'd0, cfg_k[32*sel+24+:8]};
            nbits = {24'd0, cfg_k[32*sel+16+:8]};
            rw = c_n;
            vpos = rw + 16 * dims;
        end
    endtask

    task check_result;
        begin
            mask16 = {16{1'b1}} >> (16 - nbits);
            want_m = want_word[15:0] & mask16;
            got_m = f16 & mask16;
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
        if ({c_dims[7:0], c_n[7:0], c_ws[7:0], c_wl[7:0]} != cfg_k[32*sel+:32])
            $fatal(1, "rtl_classicn_tb: %0s is for dims=%0d out_bits=%0d s_frac=%0d lerp_frac=%0d, not for cfg %0s",
                   vec_path, c_dims, c_n, c_ws, c_wl, want_name);
    endtask

    task drive_input;
        begin
            sh = word >> rw;
            xin <= sh[79:0] & ({80{1'b1}} >> (80 - 16 * dims));
        end
    endtask

    task report_pass;
        $display("rtl_classicn_tb: cfg %0s (dims=%0d out_bits=%0d s_frac=%0d lerp_frac=%0d), %0d cycles: In %0d tests, no errors found.",
                 want_name, c_dims, c_n, c_ws, c_wl, cycles, n_in);
    endtask
endmodule
