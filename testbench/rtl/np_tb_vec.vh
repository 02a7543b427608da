// SPDX-License-Identifier: MIT
// np_tb_vec.vh - what every rtl_*_tb.v bench shares, `include'd inside its
// module: reading a golden vector file ($readmemh export of `noisepipe
// vectors`) as text through two handles, the plusargs, the driver with its
// random bubbles and stalls, and the verdict. Each bench keeps only what is
// its unit's: the DUT table, the config line(s) it parses, the word's layout,
// the comparison and the verdict's config text.
//
// The file is read twice, through two handles, as a text file (never as a
// memory): the driver takes each word's inputs, the checker each word's
// expected result, in order. So what a simulator leaves in unwritten memory
// does not matter; the bench requires the header's "// count N" and
// "// config" lines, checks that the config is the DUT's and that exactly N
// words are read, and stops at a word whose valid bit is not 1 (a terminator
// word). Verdict: "In N tests, no errors found." or $fatal (non-zero exit).
//
//   +vectors=FILE   the $readmemh vector file (required)
//   +cfg=NAME       one of the bench's cfg_name table (np_tb_open's default)
//   +bubble=B +stall=S   input bubbles and output stalls, in 1/8 (default 2, 2)
//   +seed=N         the bubble/stall generator's seed (xorshift32, default 1)
//
// The bench includes it before its DUT table, having defined NP_TB (its name,
// for messages) and declared NCFG, NAME_W (cfg_name's width in characters),
// cfg_name(k), and `word` and `want_word` (as wide as its words). It declares
// what the DUT table wires: clk, rst, in_valid, out_ready, sel (the DUT that
// runs) and in_ready_k, out_valid_k (each DUT's, bit K for DUT K). After it,
// the bench supplies these tasks:
//   header_line(took)  a header line of handle fd_in other than "// count N"
//                      (in `line`): parse it, took = 1 when it was one
//   layout             from sel and the header: vpos, the word's valid bit
//   check_result       compare the DUT's outputs with want_word (errors,
//                      MAX_ERRORS shown as "inputs => got expected: want")
//   check_config       at the first input: the header's config is the DUT's
//   drive_input        put `word`'s inputs on the DUT (nonblocking)
//   report_pass        the pass line, with its config
// The clocked process is the bench's: blocking assignments in it are
// intended (lint_off BLKSEQ in the bench).
    localparam integer MAX_ERRORS = 20;

    reg clk = 1'b0;
    reg rst = 1'b1;
    reg in_valid = 1'b0, out_ready = 1'b0;
    integer sel = -1;
    wire [NCFG-1:0] in_ready_k, out_valid_k;
    wire in_ready = in_ready_k[sel];
    wire out_valid = out_valid_k[sel];

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
    reg [31:0] rng;
    string vec_path;
    integer fd_in, fd_out, n_hdr, n_in, n_out, errors, cycles, idle, bubble, stall, seed, k;
    /* verilator lint_off UNUSEDSIGNAL */
    integer vpos;  // the word's valid bit (an index: its top bits are not read)
    /* verilator lint_on UNUSEDSIGNAL */
    integer got_in, got_out;
    reg in_done;
    reg [1:0] comment;  // per handle: the chunk read last belongs to a '//' line that goes on

    function [31:0] xorshift;
        input [31:0] s;
        reg [31:0] xs;  // not t: wave's bench has a signal t
        begin
            xs = s ^ (s << 13);
            xs = xs ^ (xs >> 17);
            xorshift = xs ^ (xs << 5);
        end
    endfunction

    // Next data word of a handle into `word`; 0 at the end of the file.
    // Header lines ("// count N" and the bench's header_line) are taken from handle fd_in.
    task next_word(input integer fd, input integer hdr, output integer got);
        integer rr, n1, took;
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
                    took = 0;
                    if (hdr != 0 && $sscanf(line, "// count %d", n1) == 1) begin
                        n_hdr = n1;
                        took = 1;
                    end else if (hdr != 0) header_line(took);
                    if (took == 0 && $sscanf(line, "%h", word) == 1) begin
                        got = 1;
                        comment[hdr] = 1'b0;
                    end
                end
            end
        end
    endtask

    // The plusargs, the configuration by name (dflt without +cfg), both handles, the counts.
    task np_tb_open(input [8*16-1:0] dflt);
        begin
            if (!$value$plusargs("vectors=%s", vec_path)) $fatal(1, "%0s: +vectors=FILE missing", `NP_TB);
            if (!$value$plusargs("cfg=%s", want_name)) want_name = {384'd0, dflt};
            if (!$value$plusargs("bubble=%d", bubble)) bubble = 2;
            if (!$value$plusargs("stall=%d", stall)) stall = 2;
            if (!$value$plusargs("seed=%d", seed)) seed = 1;
            rng = seed == 0 ? 32'h9e3779b9 : seed[31:0];
            for (k = 0; k < NCFG; k = k + 1)
                if (cfg_name(k) == want_name[8*NAME_W-1:0] && want_name[8*64-1:8*NAME_W] == 0) sel = k;
            if (sel < 0) $fatal(1, "%0s: unknown +cfg=%0s", `NP_TB, want_name);
            fd_in = $fopen(vec_path, "r");
            fd_out = $fopen(vec_path, "r");
            if (fd_in == 0 || fd_out == 0) $fatal(1, "%0s: cannot open %0s", `NP_TB, vec_path);
            n_hdr = -1;
            n_in = 0; n_out = 0; errors = 0; cycles = 0; idle = 0;
            in_done = 0; comment = 2'b00;
        end
    endtask

    // Driver: a presented input stays until it is accepted; bubbles and
    // stalls from the generator. Both sides change after the clock edge.
    always @(posedge clk) begin
        if (rst) begin
            if (cycles == 2) rst <= 1'b0;
            cycles = cycles + 1;
        end else begin
            cycles = cycles + 1;
            // output side: sample the transfer of this edge
            if (out_valid && out_ready) begin
                next_word(fd_out, 0, got_out);
                want_word = word;
                layout;
                if (got_out == 0 || want_word[vpos] !== 1'b1)
                    $fatal(1, "%0s: the DUT delivered more results (%0d) than the file holds", `NP_TB, n_out + 1);
                check_result;
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
                    if (n_in == 0) check_config;
                    if (got_in == 0 || word[vpos] !== 1'b1) begin
                        in_done = 1;
                        in_valid <= 1'b0;
                    end else begin
                        in_valid <= 1'b1;
                        drive_input;
                    end
                end else in_valid <= 1'b0;
            end
            rng = xorshift(rng);
            out_ready <= {29'd0, rng[5:3]} >= stall;
            if (in_done && n_out == n_in) begin
                if (n_hdr < 0) $fatal(1, "%0s: %0s has no '// count N' header line", `NP_TB, vec_path);
                if (n_hdr != n_in)
                    $fatal(1, "%0s: the header's count is %0d but the file holds %0d vectors", `NP_TB, n_hdr, n_in);
                if (n_in == 0) $fatal(1, "%0s: no vectors in %0s", `NP_TB, vec_path);
                if (errors > MAX_ERRORS) $display("%0s: (only the first %0d errors are shown)", `NP_TB, MAX_ERRORS);
                if (errors != 0)
                    $fatal(1, "%0s: cfg %0s: In %0d tests, %0d errors found.", `NP_TB, want_name, n_in, errors);
                report_pass;
                $finish;
            end
            if (idle > 1000)
                $fatal(1, "%0s: no output for 1000 cycles after %0d of %0d results (%0d errors)", `NP_TB, n_out, n_in,
                       errors);
        end
    end
