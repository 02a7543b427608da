// SPDX-License-Identifier: MIT
// rtl_simplex3_tb - runs the reference RTL rtl_model/verilog/np_simplex3.v on
// a golden vector file ($readmemh export of `noisepipe vectors --unit
// simplex3`), under Icarus Verilog and Verilator (--binary) alike. The same
// bench as rtl_classic3_tb.v with the simplex unit's outputs: f, and with
// deriv=1 dfdx, dfdy, dfdz (the word's fields after x, y, z).
//
// One compiled bench holds every configuration of the table below, one DUT
// instance each; +cfg=NAME picks the one that runs (the others sit idle with
// their clock held), so one Verilated build serves every configuration.
//
//   +vectors=FILE   the $readmemh vector file (required)
//   +cfg=NAME       default | f_only | t1 | narrow | wide_p | opts | coarse
//   +bubble=B +stall=S   input bubbles and output stalls, in 1/8 (default 2, 2)
//   +seed=N         the bubble/stall generator's seed (xorshift32, default 1)
//
// The file is read twice, through two handles, as a text file (never as a
// memory): the driver takes each word's inputs, the checker each word's
// expected f, in order. So what a simulator leaves in unwritten memory does
// not matter; the bench requires the header's "// count N" and "// config"
// lines, checks that the config is the DUT's and that exactly N words are
// read, and stops at a word whose valid bit is not 1 (a terminator word).
// Verdict: "In N tests, no errors found." or $fatal (non-zero exit status).
// Lint: a bench, not hardware: its clocked process is procedural code that
// reads files and keeps counts, so blocking assignments are intended there.
/* verilator lint_off BLKSEQ */
module rtl_simplex3_tb;
    localparam integer NCFG = 7;
    localparam integer MAX_ERRORS = 20;
    function [8*8-1:0] cfg_name;
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

    reg clk = 1'b0;
    reg rst = 1'b1;
    reg in_valid = 1'b0, out_ready = 1'b0;
    reg [15:0] x = 16'd0, y = 16'd0, z = 16'd0;
    integer sel = -1;
    wire [NCFG-1:0] in_ready_k, out_valid_k;
    wire [80*NCFG-1:0] o_k;      // each DUT's result fields, right-aligned: {f[, dfdx, dfdy, dfdz]}
    reg [NCFG*8-1:0] rw_k;       // their width
    reg [NCFG*48-1:0] cfg_k;     // out_bits dout_bits deriv t_frac p_frac k_frac, 8 bits each

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

    wire in_ready = in_ready_k[sel];
    wire out_valid = out_valid_k[sel];
    wire [79:0] o80 = o_k[80*sel+:80];

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
    reg [159:0] word;
    reg [31:0] rng;
    string vec_path;
    integer fd_in, fd_out, n_hdr, n_in, n_out, errors, cycles, idle, bubble, stall, seed, nb, k;
    integer c_n, c_nd, c_d, c_wt, c_wp, c_wk;
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
                        c_n = n1; c_nd = n2; c_d = n3; c_wt = n4; c_wp = n5; c_wk = n6;
                    end else if ($sscanf(line, "%h", word) == 1) begin
                        got = 1;
                        comment[hdr] = 1'b0;
                    end
                end
            end
        end
    endtask

    initial begin
        if (!$value$plusargs("vectors=%s", vec_path)) $fatal(1, "rtl_simplex3_tb: +vectors=FILE missing");
        if (!$value$plusargs("cfg=%s", want_name)) want_name = "default";
        if (!$value$plusargs("bubble=%d", bubble)) bubble = 2;
        if (!$value$plusargs("stall=%d", stall)) stall = 2;
        if (!$value$plusargs("seed=%d", seed)) seed = 1;
        rng = seed == 0 ? 32'h9e3779b9 : seed[31:0];
        for (k = 0; k < NCFG; k = k + 1) if (cfg_name(k) == want_name[8*8-1:0] && want_name[8*64-1:8*8] == 0) sel = k;
        if (sel < 0) $fatal(1, "rtl_simplex3_tb: unknown +cfg=%0s", want_name);
        fd_in = $fopen(vec_path, "r");
        fd_out = $fopen(vec_path, "r");
        if (fd_in == 0 || fd_out == 0) $fatal(1, "rtl_simplex3_tb: cannot open %0s", vec_path);
        n_hdr = -1; c_n = -1; c_nd = -1; c_d = -1; c_wt = -1; c_wp = -1; c_wk = -1;
        n_in = 0; n_out = 0; errors = 0; cycles = 0; idle = 0;
        in_done = 0; comment = 2'b00;
    end

    // Driver: a presented input stays until it is accepted; bubbles and
    // stalls from the generator. Both sides change after the clock edge.
    integer got_in, got_out;
    reg [159:0] want_word;
    reg [79:0] got_m, want_m, mask80;
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
                nb = {24'd0, rw_k[8*sel+:8]};
                if (got_out == 0 || want_word[nb+48] !== 1'b1) begin
                    $fatal(1, "rtl_simplex3_tb: the DUT delivered more results (%0d) than the file holds", n_out + 1);
                end
                mask80 = {80{1'b1}} >> (80 - nb);
                want_m = want_word[79:0] & mask80;
                got_m = o80 & mask80;
                if (got_m !== want_m) begin
                    errors = errors + 1;
                    if (errors <= MAX_ERRORS)
                        $display("%h %h %h => %h expected: %h  (vector %0d)", want_word[nb+47-:16],
                                 want_word[nb+31-:16], want_word[nb+15-:16], got_m, want_m, n_out);
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
                    nb = {24'd0, rw_k[8*sel+:8]};
                    if (n_in == 0 && {c_n[7:0], c_nd[7:0], c_d[7:0], c_wt[7:0], c_wp[7:0], c_wk[7:0]} != cfg_k[48*sel+:48])
                        $fatal(1, "rtl_simplex3_tb: %0s is for out_bits=%0d dout_bits=%0d deriv=%0d t_frac=%0d p_frac=%0d k_frac=%0d, not for cfg %0s",
                               vec_path, c_n, c_nd, c_d, c_wt, c_wp, c_wk, want_name);
                    if (got_in == 0 || word[nb+48] !== 1'b1) begin
                        in_done = 1;
                        in_valid <= 1'b0;
                    end else begin
                        in_valid <= 1'b1;
                        {x, y, z} <= word[nb+47-:48];
                    end
                end else in_valid <= 1'b0;
            end
            rng = xorshift(rng);
            out_ready <= {29'd0, rng[5:3]} >= stall;
            if (in_done && n_out == n_in) begin
                if (n_hdr < 0) $fatal(1, "rtl_simplex3_tb: %0s has no '// count N' header line", vec_path);
                if (n_hdr != n_in)
                    $fatal(1, "rtl_simplex3_tb: the header's count is %0d but the file holds %0d vectors", n_hdr, n_in);
                if (n_in == 0) $fatal(1, "rtl_simplex3_tb: no vectors in %0s", vec_path);
                if (errors > MAX_ERRORS) $display("rtl_simplex3_tb: (only the first %0d errors are shown)", MAX_ERRORS);
                if (errors != 0)
                    $fatal(1, "rtl_simplex3_tb: cfg %0s: In %0d tests, %0d errors found.", want_name, n_in, errors);
                $display("rtl_simplex3_tb: cfg %0s (out_bits=%0d dout_bits=%0d deriv=%0d t_frac=%0d p_frac=%0d k_frac=%0d), %0d cycles: In %0d tests, no errors found.",
                         want_name, c_n, c_nd, c_d, c_wt, c_wp, c_wk, cycles, n_in);
                $finish;
            end
            if (idle > 1000)
                $fatal(1, "rtl_simplex3_tb: no output for 1000 cycles after %0d of %0d results (%0d errors)", n_out, n_in, errors);
        end
    end
endmodule
