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
//   +vectors=FILE   the $readmemh vector file (required)
//   +cfg=NAME       s2 s2_coarse s2_narrow s4 s4_coarse s4_narrow s5 s5_coarse
//                   s5_narrow s3 s3_t1 s3_coarse s4_opts
//   +bubble=B +stall=S   input bubbles and output stalls, in 1/8 (default 2, 2)
//   +seed=N         the bubble/stall generator's seed (xorshift32, default 1)
// Verdict: "In N tests, no errors found." or $fatal (non-zero exit status).
// Lint: a bench, not hardware: its clocked process is procedural code that
// reads files and keeps counts, so blocking assignments are intended there.
/* verilator lint_off BLKSEQ */
module rtl_simplexn_tb;
    localparam integer NCFG = 13;
    localparam integer MAX_ERRORS = 20;
    function [10*8-1:0] cfg_name;
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

    reg clk = 1'b0;
    reg rst = 1'b1;
    reg in_valid = 1'b0, out_ready = 1'b0;
    reg [79:0] xin = 80'd0;      // the word's inputs, right-aligned: {x, y, ...}
    integer sel = -1;
    wire [NCFG-1:0] in_ready_k, out_valid_k;
    wire [20*NCFG-1:0] f_k;      // each DUT's f, right-aligned
    reg [NCFG*40-1:0] cfg_k;     // dims out_bits t_frac p_frac k_frac, 8 bits each

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

    wire in_ready = in_ready_k[sel];
    wire out_valid = out_valid_k[sel];
    wire [19:0] f20 = f_k[20*sel+:20];

    always #5 clk = !clk;

    reg [8*64-1:0] want_name;
    // A line (or a chunk of one): Icarus's $fgets wants a reg, and Verilator's
    // $sscanf reads a reg's string only when it fills the reg (leading NUL
    // bytes end it), so Verilator gets a string.
`ifdef VERILATOR
    string line;
`define NP_LAST_CHAR (line.len() > 0 ? line.getc(line.len() - 1) : 8'h00)
`define NP_CLEAR_LINE line = ""
`else
    reg [8*200-1:0] line;  // $fgets stops at 200 characters; the rest comes next
`define NP_LAST_CHAR line[7:0]
`define NP_CLEAR_LINE line = 0
`endif
    reg [159:0] word;  // valid, inputs, result
    reg [31:0] rng;
    string vec_path;
    integer fd_in, fd_out, n_hdr, n_in, n_out, errors, cycles, idle, bubble, stall, seed, k;
    integer c_dims, c_n, c_nd, c_d, c_wt, c_wp, c_wk, dims, rw, fsh, nbits;
    reg in_done;
    reg [1:0] comment;  // per handle: the chunk read last belongs to a '//' line that goes on

    function [31:0] xorshift;
        input [31:0] s;
        reg [31:0] t;
        begin
            t = s ^ (s << 13);
            t = t ^ (t >> 17);
            xorshift = t ^ (t << 5);
        end
    endfunction

    // Next data word of a handle into `word`; 0 at the end of the file.
    // Header lines: "// count N" and "// config ..." are taken from handle fd_in.
    task next_word(input integer fd, input integer hdr, output integer got);
        integer rr, n1, n2, n3, n4, n5, n6;
        begin
            got = 0;
            while (got == 0 && !$feof(fd)) begin
                `NP_CLEAR_LINE;
                rr = $fgets(line, fd);
                if (rr > 0 && comment[hdr]) begin
                    comment[hdr] = `NP_LAST_CHAR != 8'h0a;  // the rest of a long comment line
                end else if (rr > 0) begin
                    // a line that is not a data word (a comment) and does not end
                    // here goes on in the next chunk, which is skipped
                    comment[hdr] = `NP_LAST_CHAR != 8'h0a;
                    if (hdr != 0 && $sscanf(line, "// count %d", n1) == 1) n_hdr = n1;
                    else if (hdr != 0 && $sscanf(line,
                        "// config out_bits=%d dout_bits=%d deriv=%d t_frac=%d p_frac=%d k_frac=%d",
                        n1, n2, n3, n4, n5, n6) == 6) begin
                        c_dims = 3; c_n = n1; c_nd = n2; c_d = n3; c_wt = n4; c_wp = n5; c_wk = n6;
                    end else if (hdr != 0 && $sscanf(line, "// config dims=%d out_bits=%d t_frac=%d p_frac=%d",
                        n1, n2, n3, n4) == 4) begin
                        c_dims = n1; c_n = n2; c_nd = 0; c_d = 0; c_wt = n3; c_wp = n4; c_wk = 0;
                    end else if ($sscanf(line, "%h", word) == 1) begin
                        got = 1;
                        comment[hdr] = 1'b0;
                    end
                end
            end
        end
    endtask

    initial begin
        if (!$value$plusargs("vectors=%s", vec_path)) $fatal(1, "rtl_simplexn_tb: +vectors=FILE missing");
        if (!$value$plusargs("cfg=%s", want_name)) want_name = "s4";
        if (!$value$plusargs("bubble=%d", bubble)) bubble = 2;
        if (!$value$plusargs("stall=%d", stall)) stall = 2;
        if (!$value$plusargs("seed=%d", seed)) seed = 1;
        rng = seed == 0 ? 32'h9e3779b9 : seed[31:0];
        for (k = 0; k < NCFG; k = k + 1) if (cfg_name(k) == want_name[10*8-1:0] && want_name[8*64-1:8*10] == 0) sel = k;
        if (sel < 0) $fatal(1, "rtl_simplexn_tb: unknown +cfg=%0s", want_name);
        fd_in = $fopen(vec_path, "r");
        fd_out = $fopen(vec_path, "r");
        if (fd_in == 0 || fd_out == 0) $fatal(1, "rtl_simplexn_tb: cannot open %0s", vec_path);
        n_hdr = -1; c_dims = -1; c_n = -1; c_nd = -1; c_d = -1; c_wt = -1; c_wp = -1; c_wk = -1;
        n_in = 0; n_out = 0; errors = 0; cycles = 0; idle = 0;
        in_done = 0; comment = 2'b00;
    end

    // The word's layout (from the header): [rw + 16 dims] valid, then the
    // inputs, then the result of rw bits, f its bits [fsh + N - 1 : fsh].
    task layout;
        begin
            dims = {24'd0, cfg_k[40*sel+32+:8]};
            nbits = {24'd0, cfg_k[40*sel+24+:8]};
            rw = c_d != 0 ? c_n + 3 * c_nd : c_n;
            fsh = c_d != 0 ? 3 * c_nd : 0;
        end
    endtask

    // Driver: a presented input stays until it is accepted; bubbles and
    // stalls from the generator. Both sides change after the clock edge.
    integer got_in, got_out;
    reg [159:0] want_word;
    /* verilator lint_off UNUSEDSIGNAL */
    reg [159:0] sh;  // the word shifted to a field (its top bits are not read)
    /* verilator lint_on UNUSEDSIGNAL */
    reg [19:0] got_m, want_m, mask20;
    always @(posedge clk) begin
        if (rst) begin
            if (cycles == 2) begin
                rst <= 1'b0;
            end
            cycles = cycles + 1;
        end else begin
            cycles = cycles + 1;
            // output side: sample the transfer of this edge
            if (out_valid && out_ready) begin
                next_word(fd_out, 0, got_out);
                want_word = word;
                layout;
                if (got_out == 0 || want_word[rw+16*dims] !== 1'b1) begin
                    $fatal(1, "rtl_simplexn_tb: the DUT delivered more results (%0d) than the file holds", n_out + 1);
                end
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
                n_out = n_out + 1;
                idle = 0;
            end else idle = idle + 1;
            if (in_valid && in_ready) begin
                n_in = n_in + 1;
                in_valid <= 1'b0;
            end
            // next input
            if (!in_done && (!in_valid || in_ready)) begin
                rng = xorshift(rng);
                if ({29'd0, rng[2:0]} >= bubble) begin
                    next_word(fd_in, 1, got_in);
                    layout;
                    if (n_in == 0 && {c_dims[7:0], c_n[7:0], c_wt[7:0], c_wp[7:0], c_wk[7:0]} != cfg_k[40*sel+:40])
                        $fatal(1, "rtl_simplexn_tb: %0s is for dims=%0d out_bits=%0d t_frac=%0d p_frac=%0d k_frac=%0d, not for cfg %0s",
                               vec_path, c_dims, c_n, c_wt, c_wp, c_wk, want_name);
                    if (got_in == 0 || word[rw+16*dims] !== 1'b1) begin
                        in_done = 1;
                        in_valid <= 1'b0;
                    end else begin
                        in_valid <= 1'b1;
                        sh = word >> rw;
                        xin <= sh[79:0] & ({80{1'b1}} >> (80 - 16 * dims));
                    end
                end else in_valid <= 1'b0;
            end
            rng = xorshift(rng);
            out_ready <= {29'd0, rng[5:3]} >= stall;
            if (in_done && n_out == n_in) begin
                if (n_hdr < 0) $fatal(1, "rtl_simplexn_tb: %0s has no '// count N' header line", vec_path);
                if (n_hdr != n_in)
                    $fatal(1, "rtl_simplexn_tb: the header's count is %0d but the file holds %0d vectors", n_hdr, n_in);
                if (n_in == 0) $fatal(1, "rtl_simplexn_tb: no vectors in %0s", vec_path);
                if (errors > MAX_ERRORS) $display("rtl_simplexn_tb: (only the first %0d errors are shown)", MAX_ERRORS);
                if (errors != 0)
                    $fatal(1, "rtl_simplexn_tb: cfg %0s: In %0d tests, %0d errors found.", want_name, n_in, errors);
                $display("rtl_simplexn_tb: cfg %0s (dims=%0d out_bits=%0d t_frac=%0d p_frac=%0d k_frac=%0d), %0d cycles: In %0d tests, no errors found.",
                         want_name, c_dims, c_n, c_wt, c_wp, c_wk, cycles, n_in);
                $finish;
            end
            if (idle > 1000)
                $fatal(1, "rtl_simplexn_tb: no output for 1000 cycles after %0d of %0d results (%0d errors)", n_out, n_in, errors);
        end
    end
endmodule
