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
//   +vectors=FILE   the $readmemh vector file (required)
//   +cfg=NAME       c2 c2_wide_l c4 c4_wide_l c5 c5_wide_l c3 c3_cheap c3_wide_l
//                   c4_opts
//   +bubble=B +stall=S   input bubbles and output stalls, in 1/8 (default 2, 2)
//   +seed=N         the bubble/stall generator's seed (xorshift32, default 1)
// Verdict: "In N tests, no errors found." or $fatal (non-zero exit status).
// Lint: a bench, not hardware: its clocked process is procedural code that
// reads files and keeps counts, so blocking assignments are intended there.
/* verilator lint_off BLKSEQ */
module rtl_classicn_tb;
    localparam integer NCFG = 10;
    localparam integer MAX_ERRORS = 20;
    function [10*8-1:0] cfg_name;
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

    reg clk = 1'b0;
    reg rst = 1'b1;
    reg in_valid = 1'b0, out_ready = 1'b0;
    reg [79:0] xin = 80'd0;      // the word's inputs, right-aligned: {x, y, ...}
    integer sel = -1;
    wire [NCFG-1:0] in_ready_k, out_valid_k;
    wire [16*NCFG-1:0] f_k;      // each DUT's f, right-aligned
    reg [NCFG*32-1:0] cfg_k;     // dims out_bits s_frac lerp_frac, 8 bits each

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
    reg [159:0] word;  // valid, inputs, result
    reg [31:0] rng;
    string vec_path;
    integer fd_in, fd_out, n_hdr, n_in, n_out, errors, cycles, idle, bubble, stall, seed, k;
    integer c_dims, c_n, c_ws, c_wl, dims, rw, nbits;
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
        integer rr, n1, n2, n3, n4;
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
                    else if (hdr != 0 && $sscanf(line, "// config dims=%d out_bits=%d s_frac=%d lerp_frac=%d",
                        n1, n2, n3, n4) == 4) begin
                        c_dims = n1; c_n = n2; c_ws = n3; c_wl = n4;
                    end else if (hdr != 0 && $sscanf(line, "// config out_bits=%d s_frac=%d lerp_frac=%d",
                        n1, n2, n3) == 3) begin
                        c_dims = 3; c_n = n1; c_ws = n2; c_wl = n3;
                    end else if ($sscanf(line, "%h", word) == 1) begin
                        got = 1;
                        comment[hdr] = 1'b0;
                    end
                end
            end
        end
    endtask

    initial begin
        if (!$value$plusargs("vectors=%s", vec_path)) $fatal(1, "rtl_classicn_tb: +vectors=FILE missing");
        if (!$value$plusargs("cfg=%s", want_name)) want_name = "c4";
        if (!$value$plusargs("bubble=%d", bubble)) bubble = 2;
        if (!$value$plusargs("stall=%d", stall)) stall = 2;
        if (!$value$plusargs("seed=%d", seed)) seed = 1;
        rng = seed == 0 ? 32'h9e3779b9 : seed[31:0];
        for (k = 0; k < NCFG; k = k + 1) if (cfg_name(k) == want_name[10*8-1:0] && want_name[8*64-1:8*10] == 0) sel = k;
        if (sel < 0) $fatal(1, "rtl_classicn_tb: unknown +cfg=%0s", want_name);
        fd_in = $fopen(vec_path, "r");
        fd_out = $fopen(vec_path, "r");
        if (fd_in == 0 || fd_out == 0) $fatal(1, "rtl_classicn_tb: cannot open %0s", vec_path);
        n_hdr = -1; c_dims = -1; c_n = -1; c_ws = -1; c_wl = -1;
        n_in = 0; n_out = 0; errors = 0; cycles = 0; idle = 0;
        in_done = 0; comment = 2'b00;
    end

    // The word's layout (from the header): [rw + 16 dims] valid, then the
    // inputs, then the result f of rw = N bits.
    task layout;
        begin
            dims = {24'd0, cfg_k[32*sel+24+:8]};
            nbits = {24'd0, cfg_k[32*sel+16+:8]};
            rw = c_n;
        end
    endtask

    // Driver: a presented input stays until it is accepted; bubbles and
    // stalls from the generator. Both sides change after the clock edge.
    integer got_in, got_out;
    reg [159:0] want_word;
    /* verilator lint_off UNUSEDSIGNAL */
    reg [159:0] sh;  // the word shifted to a field (its top bits are not read)
    /* verilator lint_on UNUSEDSIGNAL */
    reg [15:0] got_m, want_m, mask16;
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
                    $fatal(1, "rtl_classicn_tb: the DUT delivered more results (%0d) than the file holds", n_out + 1);
                end
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
                    if (n_in == 0 && {c_dims[7:0], c_n[7:0], c_ws[7:0], c_wl[7:0]} != cfg_k[32*sel+:32])
                        $fatal(1, "rtl_classicn_tb: %0s is for dims=%0d out_bits=%0d s_frac=%0d lerp_frac=%0d, not for cfg %0s",
                               vec_path, c_dims, c_n, c_ws, c_wl, want_name);
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
                if (n_hdr < 0) $fatal(1, "rtl_classicn_tb: %0s has no '// count N' header line", vec_path);
                if (n_hdr != n_in)
                    $fatal(1, "rtl_classicn_tb: the header's count is %0d but the file holds %0d vectors", n_hdr, n_in);
                if (n_in == 0) $fatal(1, "rtl_classicn_tb: no vectors in %0s", vec_path);
                if (errors > MAX_ERRORS) $display("rtl_classicn_tb: (only the first %0d errors are shown)", MAX_ERRORS);
                if (errors != 0)
                    $fatal(1, "rtl_classicn_tb: cfg %0s: In %0d tests, %0d errors found.", want_name, n_in, errors);
                $display("rtl_classicn_tb: cfg %0s (dims=%0d out_bits=%0d s_frac=%0d lerp_frac=%0d), %0d cycles: In %0d tests, no errors found.",
                         want_name, c_dims, c_n, c_ws, c_wl, cycles, n_in);
                $finish;
            end
            if (idle > 1000)
                $fatal(1, "rtl_classicn_tb: no output for 1000 cycles after %0d of %0d results (%0d errors)", n_out, n_in, errors);
        end
    end
endmodule
