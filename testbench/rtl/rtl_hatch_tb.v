// SPDX-License-Identifier: MIT
// rtl_hatch_tb - runs the reference RTL rtl_model/verilog/np_hatch.v on a
// golden vector file ($readmemh export of `noisepipe vectors --unit hatch`),
// under Icarus Verilog and Verilator (--binary) alike. The same bench as
// rtl_aacount_tb.v with hatch's word (117 bits, MSB first): [116] valid
// [115:83] xu [82:50] xv [49:42] tone [41:25] pm [24:8] om [7:0] c.
//
// One compiled bench holds every configuration of the table below, one DUT
// instance each (the others sit idle with their clock held); +cfg=NAME picks
// the one that runs.
//
//   +vectors=FILE   the $readmemh vector file (required)
//   +cfg=NAME       default | onebyone | best64 | g0 | rot45 | fkm16_l1 | opts | lanes4
//   +bubble=B +stall=S   input bubbles and output stalls, in 1/8 (default 2, 2)
//   +seed=N         the bubble/stall generator's seed (xorshift32, default 1)
//
// The file is read twice, through two handles, as a text file: the driver
// takes the header and each word's inputs, the checker each word's expected
// c, in order. The bench requires "// count N" (exactly N words must be
// read) and a "// config" line whose eight keys are the DUT's, and stops at
// a word whose valid bit is not 1.
// Verdict: "In N tests, no errors found." or $fatal (non-zero exit status).
// Lint: a bench, not hardware: its clocked process is procedural code that
// reads files and keeps counts, so blocking assignments are intended there;
// the config words are wider than most keys.
/* verilator lint_off BLKSEQ */
/* verilator lint_off UNUSEDSIGNAL */
module rtl_hatch_tb;
    localparam integer NCFG = 8;
    localparam integer MAX_ERRORS = 20;
    localparam integer KW = 8 * 16;  // one key=value word of the config line
    function [8*9-1:0] cfg_name;
        input integer k;
        case (k)
            0: cfg_name = "default";
            1: cfg_name = "onebyone";
            2: cfg_name = "best64";
            3: cfg_name = "g0";
            4: cfg_name = "rot45";
            5: cfg_name = "fkm16_l1";
            6: cfg_name = "opts";
            default: cfg_name = "lanes4";
        endcase
    endfunction

    // a key=value string literal zero-extended to one config word (as $sscanf's %s leaves it)
    function [KW-1:0] kw;
        input [KW-1:0] w;
        kw = w;
    endfunction

    reg clk = 1'b0;
    reg rst = 1'b1;
    reg in_valid = 1'b0, out_ready = 1'b0;
    reg [32:0] xu = 33'd0, xv = 33'd0;
    reg [7:0] tone = 8'd0;
    reg [16:0] pm = 17'd0, om = 17'd0;
    integer sel = -1;
    wire [NCFG-1:0] in_ready_k, out_valid_k;
    wire [8*NCFG-1:0] c_k;
    reg [8*KW*NCFG-1:0] cfg_k;  // each DUT's eight config words

`define NP_DUT(K, ST, LY, FD, GD, LN, RT, IL, IWD, IR, OS, W1, W2, W3, W4, W5, W6, W7, W8) \
    wire clk_``K = clk & (sel == K); \
    np_hatch #(.SET(ST), .LAYERS(LY), .FADE(FD), .GUARD(GD), .LANES(LN), .ROT(RT), .INV_LEN(IL), .INV_WID(IWD), \
               .IN_REG(IR), .OUT_SKID(OS)) dut_``K ( \
        .clk(clk_``K), .rst(rst), .in_valid(in_valid && sel == K), .in_ready(in_ready_k[K]), \
        .xu(xu), .xv(xv), .tone(tone), .pm(pm), .om(om), \
        .out_valid(out_valid_k[K]), .out_ready(out_ready), .c(c_k[8*K+:8])); \
    initial cfg_k[8*KW*K+:8*KW] = {kw(W1), kw(W2), kw(W3), kw(W4), kw(W5), kw(W6), kw(W7), kw(W8)};

    `NP_DUT(0, 1, 4, 0, 9, 1, 0, 0, 0, 0, 0, "set=best16", "layers=4", "fade=smooth", "guard=9", "lanes=1", "rot=pin", "inv_len=1024", "inv_wid=8533")
    `NP_DUT(1, 1, 4, 1, 9, 1, 0, 0, 0, 0, 0, "set=best16", "layers=4", "fade=onebyone", "guard=9", "lanes=1", "rot=pin", "inv_len=1024", "inv_wid=8533")
    `NP_DUT(2, 3, 4, 0, 9, 1, 0, 0, 0, 0, 0, "set=best64", "layers=4", "fade=smooth", "guard=9", "lanes=1", "rot=pin", "inv_len=2048", "inv_wid=17067")
    `NP_DUT(3, 1, 4, 0, 0, 1, 0, 0, 0, 0, 0, "set=best16", "layers=4", "fade=smooth", "guard=0", "lanes=1", "rot=pin", "inv_len=1024", "inv_wid=8533")
    `NP_DUT(4, 1, 4, 0, 9, 1, 2, 0, 0, 0, 0, "set=best16", "layers=4", "fade=smooth", "guard=9", "lanes=1", "rot=45", "inv_len=1024", "inv_wid=8533")
    `NP_DUT(5, 0, 1, 0, 9, 1, 0, 0, 0, 0, 0, "set=fkm16", "layers=1", "fade=smooth", "guard=9", "lanes=1", "rot=pin", "inv_len=1024", "inv_wid=8533")
    `NP_DUT(6, 1, 4, 0, 9, 1, 0, 0, 0, 1, 1, "set=best16", "layers=4", "fade=smooth", "guard=9", "lanes=1", "rot=pin", "inv_len=1024", "inv_wid=8533")
    `NP_DUT(7, 1, 4, 0, 9, 4, 0, 0, 0, 0, 0, "set=best16", "layers=4", "fade=smooth", "guard=9", "lanes=4", "rot=pin", "inv_len=1024", "inv_wid=8533")

    wire in_ready = in_ready_k[sel];
    wire out_valid = out_valid_k[sel];
    wire [7:0] c_out = c_k[8*sel+:8];

    always #5 clk = !clk;

    reg [8*64-1:0] want_name;
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
    integer fd_in, fd_out, n_hdr, n_in, n_out, errors, cycles, idle, bubble, stall, seed, k, n_ink;
    reg [8*KW-1:0] cfg_file;
    reg have_cfg;
    reg in_done;
    reg [1:0] comment;

    function [31:0] xorshift;
        input [31:0] s;
        reg [31:0] t;
        begin
            t = s ^ (s << 13);
            t = t ^ (t >> 17);
            xorshift = t ^ (t << 5);
        end
    endfunction

    task next_word(input integer fd, input integer hdr, output integer got);
        integer rr;
        reg [KW-1:0] a1, a2, a3, a4, a5, a6, a7, a8;
        integer n1;
        begin
            got = 0;
            while (got == 0 && !$feof(fd)) begin
                `NP_CLEAR_LINE;
                rr = $fgets(line, fd);
                if (rr > 0 && comment[hdr]) begin
                    comment[hdr] = `NP_LAST_CHAR != 8'h0a;
                end else if (rr > 0) begin
                    comment[hdr] = `NP_LAST_CHAR != 8'h0a;
                    if (hdr != 0 && $sscanf(line, "// count %d", n1) == 1) n_hdr = n1;
                    else if (hdr != 0 && $sscanf(line, "// config %s %s %s %s %s %s %s %s",
                                                 a1, a2, a3, a4, a5, a6, a7, a8) == 8) begin
                        cfg_file = {a1, a2, a3, a4, a5, a6, a7, a8};
                        have_cfg = 1'b1;
                    end else if ($sscanf(line, "%h", word) == 1) begin
                        got = 1;
                        comment[hdr] = 1'b0;
                    end
                end
            end
        end
    endtask

    initial begin
        if (!$value$plusargs("vectors=%s", vec_path)) $fatal(1, "rtl_hatch_tb: +vectors=FILE missing");
        if (!$value$plusargs("cfg=%s", want_name)) want_name = "default";
        if (!$value$plusargs("bubble=%d", bubble)) bubble = 2;
        if (!$value$plusargs("stall=%d", stall)) stall = 2;
        if (!$value$plusargs("seed=%d", seed)) seed = 1;
        rng = seed == 0 ? 32'h9e3779b9 : seed[31:0];
        for (k = 0; k < NCFG; k = k + 1) if (cfg_name(k) == want_name[8*9-1:0] && want_name[8*64-1:8*9] == 0) sel = k;
        if (sel < 0) $fatal(1, "rtl_hatch_tb: unknown +cfg=%0s", want_name);
        fd_in = $fopen(vec_path, "r");
        fd_out = $fopen(vec_path, "r");
        if (fd_in == 0 || fd_out == 0) $fatal(1, "rtl_hatch_tb: cannot open %0s", vec_path);
        n_hdr = -1; have_cfg = 1'b0; cfg_file = 0;
        n_in = 0; n_out = 0; errors = 0; cycles = 0; idle = 0; n_ink = 0;
        in_done = 0; comment = 2'b00;
    end

    integer got_in, got_out;
    reg [127:0] want_word;
    always @(posedge clk) begin
        if (rst) begin
            if (cycles == 2) rst <= 1'b0;
            cycles = cycles + 1;
        end else begin
            cycles = cycles + 1;
            if (out_valid && out_ready) begin
                next_word(fd_out, 0, got_out);
                want_word = word;
                if (got_out == 0 || want_word[116] !== 1'b1)
                    $fatal(1, "rtl_hatch_tb: the DUT delivered more results (%0d) than the file holds", n_out + 1);
                if (c_out !== want_word[7:0]) begin
                    errors = errors + 1;
                    if (errors <= MAX_ERRORS)
                        $display("xu %h xv %h tone %h pm %h om %h => c %h expected: %h  (vector %0d)",
                                 want_word[115:83], want_word[82:50], want_word[49:42], want_word[41:25],
                                 want_word[24:8], c_out, want_word[7:0], n_out);
                end
                if (want_word[7:0] != 8'hff) n_ink = n_ink + 1;
                n_out = n_out + 1;
                idle = 0;
            end else idle = idle + 1;
            if (in_valid && in_ready) begin
                n_in = n_in + 1;
                in_valid <= 1'b0;
            end
            if (!in_done && (!in_valid || in_ready)) begin
                rng = xorshift(rng);
                if ({29'd0, rng[2:0]} >= bubble) begin
                    next_word(fd_in, 1, got_in);
                    if (n_in == 0 && (!have_cfg || cfg_file != cfg_k[8*KW*sel+:8*KW]))
                        $fatal(1, "rtl_hatch_tb: %0s has no '// config' line or is for another configuration than cfg %0s (%0s; the file: %0s)",
                               vec_path, want_name, cfg_k[8*KW*sel+:8*KW], cfg_file);
                    if (got_in == 0 || word[116] !== 1'b1) begin
                        in_done = 1;
                        in_valid <= 1'b0;
                    end else begin
                        in_valid <= 1'b1;
                        xu <= word[115:83];
                        xv <= word[82:50];
                        tone <= word[49:42];
                        pm <= word[41:25];
                        om <= word[24:8];
                    end
                end else in_valid <= 1'b0;
            end
            rng = xorshift(rng);
            out_ready <= {29'd0, rng[5:3]} >= stall;
            if (in_done && n_out == n_in) begin
                if (n_hdr < 0) $fatal(1, "rtl_hatch_tb: %0s has no '// count N' header line", vec_path);
                if (n_hdr != n_in)
                    $fatal(1, "rtl_hatch_tb: the header's count is %0d but the file holds %0d vectors", n_hdr, n_in);
                if (n_in == 0) $fatal(1, "rtl_hatch_tb: no vectors in %0s", vec_path);
                if (errors > MAX_ERRORS) $display("rtl_hatch_tb: (only the first %0d errors are shown)", MAX_ERRORS);
                if (errors != 0)
                    $fatal(1, "rtl_hatch_tb: cfg %0s: In %0d tests, %0d errors found.", want_name, n_in, errors);
                $display("rtl_hatch_tb: cfg %0s, %0d with ink (c < 255), %0d cycles: In %0d tests, no errors found.",
                         want_name, n_ink, cycles, n_in);
                $finish;
            end
            if (idle > 1000)
                $fatal(1, "rtl_hatch_tb: no output for 1000 cycles after %0d of %0d results (%0d errors)", n_out, n_in, errors);
        end
    end
endmodule
/* verilator lint_on UNUSEDSIGNAL */
/* verilator lint_on BLKSEQ */
