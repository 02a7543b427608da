// SPDX-License-Identifier: MIT
// rtl_classic3_tb - runs the reference RTL rtl_model/verilog/np_classic3.v on
// a golden vector file ($readmemh export of `noisepipe vectors --unit
// classic3`), under Icarus Verilog and Verilator (--binary) alike.
//
// One compiled bench holds every configuration of the table below, one DUT
// instance each; +cfg=NAME picks the one that runs (the others sit idle with
// their clock held), so one Verilated build serves every configuration.
//
//   +vectors=FILE   the $readmemh vector file (required)
//   +cfg=NAME       default | s_frac10 | cheap | exact_s | wide_l | opts, and
//                   the circuit variants (np_classic3.v's S_TABLE, HASH_SERIAL,
//                   LERP_SERIAL): s_table | h_serial | both | l_serial | ls_table
//                   (LERP_SERIAL with S_TABLE) at the default configuration,
//                   st_cheap | hs_cheap | bo_cheap | ls_cheap (out_bits=8 s_frac=4 lerp_frac=6),
//                   st_exact (out_bits=12 s_frac=24 lerp_frac=30, S_TABLE),
//                   ls_wide (out_bits=15 s_frac=3 lerp_frac=20, LERP_SERIAL)
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
module rtl_classic3_tb;
    localparam integer NCFG = 17;
    localparam integer MAX_ERRORS = 20;
    // name, out_bits, s_frac, lerp_frac, in_reg, out_skid, s_table, hash_serial, lerp_serial
    function [8*8-1:0] cfg_name;
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

    reg clk = 1'b0;
    reg rst = 1'b1;
    reg in_valid = 1'b0, out_ready = 1'b0;
    reg [15:0] x = 16'd0, y = 16'd0, z = 16'd0;
    integer sel = -1;
    wire [NCFG-1:0] in_ready_k, out_valid_k;
    wire [16*NCFG-1:0] f_k;      // each DUT's f, sign-extended to 16 bits
    reg [NCFG*8-1:0] outbits_k;  // each DUT's out_bits (for the checker)
    reg [NCFG*8-1:0] sfrac_k, lfrac_k;

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

    wire in_ready = in_ready_k[sel];
    wire out_valid = out_valid_k[sel];
    wire [15:0] f16 = f_k[16*sel+:16];

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
    reg [127:0] word;
    reg [31:0] rng;
    string vec_path;
    integer fd_in, fd_out, n_hdr, n_in, n_out, errors, cycles, idle, bubble, stall, seed, nb, k;
    integer c_n, c_ws, c_wl;
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
        integer rr, n1, n2, n3;
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
                    else if (hdr != 0 && $sscanf(line, "// config out_bits=%d s_frac=%d lerp_frac=%d",
                                                 n1, n2, n3) == 3) begin
                        c_n = n1; c_ws = n2; c_wl = n3;
                    end else if ($sscanf(line, "%h", word) == 1) begin
                        got = 1;
                        comment[hdr] = 1'b0;
                    end
                end
            end
        end
    endtask

    initial begin
        if (!$value$plusargs("vectors=%s", vec_path)) $fatal(1, "rtl_classic3_tb: +vectors=FILE missing");
        if (!$value$plusargs("cfg=%s", want_name)) want_name = "default";
        if (!$value$plusargs("bubble=%d", bubble)) bubble = 2;
        if (!$value$plusargs("stall=%d", stall)) stall = 2;
        if (!$value$plusargs("seed=%d", seed)) seed = 1;
        rng = seed == 0 ? 32'h9e3779b9 : seed[31:0];
        for (k = 0; k < NCFG; k = k + 1) if (cfg_name(k) == want_name[8*8-1:0] && want_name[8*64-1:8*8] == 0) sel = k;
        if (sel < 0) $fatal(1, "rtl_classic3_tb: unknown +cfg=%0s", want_name);
        fd_in = $fopen(vec_path, "r");
        fd_out = $fopen(vec_path, "r");
        if (fd_in == 0 || fd_out == 0) $fatal(1, "rtl_classic3_tb: cannot open %0s", vec_path);
        n_hdr = -1; c_n = -1; c_ws = -1; c_wl = -1;
        n_in = 0; n_out = 0; errors = 0; cycles = 0; idle = 0;
        in_done = 0; comment = 2'b00;
    end

    // Driver: a presented input stays until it is accepted; bubbles and
    // stalls from the generator. Both sides change after the clock edge.
    integer got_in, got_out;
    reg [127:0] want_word;
    reg [15:0] want16, got_m, want_m, mask16;
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
                nb = {24'd0, outbits_k[8*sel+:8]};
                if (got_out == 0 || want_word[nb+48] !== 1'b1) begin
                    $fatal(1, "rtl_classic3_tb: the DUT delivered more results (%0d) than the file holds", n_out + 1);
                end
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
                    nb = {24'd0, outbits_k[8*sel+:8]};
                    if (n_in == 0 && (c_n != nb || c_ws != {24'd0, sfrac_k[8*sel+:8]} || c_wl != {24'd0, lfrac_k[8*sel+:8]}))
                        $fatal(1, "rtl_classic3_tb: %0s is for out_bits=%0d s_frac=%0d lerp_frac=%0d, not for cfg %0s",
                               vec_path, c_n, c_ws, c_wl, want_name);
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
                if (n_hdr < 0) $fatal(1, "rtl_classic3_tb: %0s has no '// count N' header line", vec_path);
                if (n_hdr != n_in)
                    $fatal(1, "rtl_classic3_tb: the header's count is %0d but the file holds %0d vectors", n_hdr, n_in);
                if (n_in == 0) $fatal(1, "rtl_classic3_tb: no vectors in %0s", vec_path);
                if (errors > MAX_ERRORS) $display("rtl_classic3_tb: (only the first %0d errors are shown)", MAX_ERRORS);
                if (errors != 0)
                    $fatal(1, "rtl_classic3_tb: cfg %0s: In %0d tests, %0d errors found.", want_name, n_in, errors);
                $display("rtl_classic3_tb: cfg %0s (out_bits=%0d s_frac=%0d lerp_frac=%0d), %0d cycles: In %0d tests, no errors found.",
                         want_name, c_n, c_ws, c_wl, cycles, n_in);
                $finish;
            end
            if (idle > 1000)
                $fatal(1, "rtl_classic3_tb: no output for 1000 cycles after %0d of %0d results (%0d errors)", n_out, n_in, errors);
        end
    end
endmodule
