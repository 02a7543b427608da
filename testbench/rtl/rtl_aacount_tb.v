// SPDX-License-Identifier: MIT
// rtl_aacount_tb - runs the reference RTL rtl_model/verilog/np_aacount.v on a
// golden vector file ($readmemh export of `noisepipe vectors --unit aacount`),
// under Icarus Verilog and Verilator (--binary) alike. The same bench as
// rtl_simplex3_tb.v with aacount's word: {valid, w0, w1, ..., s, mask, sd, sn,
// ss}, w0 = bus[63:0] first, the last word holding what is left of the
// np_aacount_bus_pack bus (np_aacount.h); outputs s (u5), mask (u16), then
// sd, sn, ss (u5 each) for the metrics that are built (a metric that is off
// has no field: the DUT drives it 0 and the bench checks that too).
//
// One compiled bench holds every configuration of the table below, one DUT
// instance each; +cfg=NAME picks the one that runs.
//
//   +vectors=FILE   the $readmemh vector file (required)
//   +cfg=NAME       default | m2 | m4 | m1 | taps5 | opts | strict
//   +bubble=B +stall=S   input bubbles and output stalls, in 1/8 (default 2, 2)
//   +seed=N         the bubble/stall generator's seed (xorshift32, default 1)
//
// The file is read twice, through two handles, as a text file; the bench
// requires the header's "// count N" and "// config" lines, checks that the
// config is the DUT's and that exactly N words are read.
// Verdict: "In N tests, no errors found." or $fatal (non-zero exit status).
// Lint: a bench, not hardware: blocking assignments in its clocked process are
// intended; the bus register is as wide as the widest DUT's and the tile key
// (after the unit) is read but not checked.
/* verilator lint_off BLKSEQ */
/* verilator lint_off UNUSEDSIGNAL */
module rtl_aacount_tb;
    localparam integer NCFG = 7;
    localparam integer MAX_ERRORS = 20;
    function [8*8-1:0] cfg_name;
        input integer k;
        case (k)
            0: cfg_name = "default";
            1: cfg_name = "m2";
            2: cfg_name = "m4";
            3: cfg_name = "m1";
            4: cfg_name = "taps5";
            5: cfg_name = "opts";
            default: cfg_name = "strict";
        endcase
    endfunction

    reg clk = 1'b0;
    reg rst = 1'b1;
    reg in_valid = 1'b0, out_ready = 1'b0;
    reg [511:0] bus = 512'd0;
    integer sel = -1;
    wire [NCFG-1:0] in_ready_k, out_valid_k;
    wire [36*NCFG-1:0] o_k;       // each DUT's {s, mask, sd, sn, ss}
    reg [NCFG*16-1:0] bb_k;       // its bus width
    reg [NCFG*3-1:0] on_k;        // its metrics built: {depth, normal, luma}
    reg [NCFG*144-1:0] cfg_k;     // m depth normal luma luma_taps (8 bits each), c_d (32), c_n, c_s (16), t_min, t_edge

`define NP_DUT(K, MM, DD, NN, LL, TT, CD, CN, CS, TM, TE, IR, OS) \
    wire clk_``K = clk & (sel == K); \
    localparam integer BB_``K = MM * MM * ((DD != 0 ? 24 : 0) + (NN != 0 ? 24 : 0)) + (LL != 0 ? 40 : 0); \
    np_aacount #(.M(MM), .DEPTH(DD), .NORMAL(NN), .LUMA(LL), .LUMA_TAPS(TT), .C_D(CD), .C_N(CN), .C_S(CS), \
                 .T_MIN(TM), .T_EDGE(TE), .IN_REG(IR), .OUT_SKID(OS)) dut_``K ( \
        .clk(clk_``K), .rst(rst), .in_valid(in_valid && sel == K), .in_ready(in_ready_k[K]), \
        .bus(bus[BB_``K-1:0]), .out_valid(out_valid_k[K]), .out_ready(out_ready), \
        .s(o_k[36*K+31+:5]), .mask(o_k[36*K+15+:16]), .sd(o_k[36*K+10+:5]), .sn(o_k[36*K+5+:5]), .ss(o_k[36*K+:5])); \
    initial begin bb_k[16*K+:16] = BB_``K[15:0]; on_k[3*K+:3] = {DD != 0, NN != 0, LL != 0}; \
        cfg_k[144*K+:144] = {8'd MM, 8'd DD, 8'd NN, 8'd LL, 8'd TT, 32'd CD, 16'd CN, 16'd CS, 16'd TM, 16'd TE, 8'd0}; end

    `NP_DUT(0, 3, 1, 1, 1, 4, 1000000, 32, 128, 16, 32, 0, 0)
    `NP_DUT(1, 2, 1, 1, 1, 4, 1000000, 32, 128, 16, 32, 0, 0)
    `NP_DUT(2, 4, 1, 0, 1, 5, 1000000, 32, 128, 16, 32, 0, 0)
    `NP_DUT(3, 1, 1, 1, 1, 4, 1000000, 32, 128, 16, 32, 0, 0)
    `NP_DUT(4, 3, 0, 1, 1, 5, 1000000, 60, 40, 8, 64, 0, 0)
    `NP_DUT(5, 3, 1, 1, 1, 4, 1000000, 32, 128, 16, 32, 1, 1)
    `NP_DUT(6, 3, 1, 1, 0, 4, 4000000000, 255, 128, 16, 32, 0, 0)

    wire in_ready = in_ready_k[sel];
    wire out_valid = out_valid_k[sel];
    wire [35:0] o36 = o_k[36*sel+:36];

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
    reg [639:0] word;
    reg [31:0] rng;
    string vec_path;
    integer fd_in, fd_out, n_hdr, n_in, n_out, errors, cycles, idle, bubble, stall, seed, bb, ow, k;
    reg [31:0] c_m, c_dd, c_nn, c_ll, c_tt, c_tile, c_ser, c_cd, c_cn, c_cs, c_tm, c_te;
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

    // The bus of a word: bus bit 64 k + o at word bit LSB(k) + o, LSB(k) =
    // OW + BB - 64 (k + 1) but OW for the last word (OW: the output fields' bits).
    function [511:0] bus_of;
        input [639:0] wd;
        input integer nbits;
        input integer obits;
        integer b, kk, nw, lsb;
        begin
            bus_of = 512'd0;
            nw = (nbits + 63) / 64;
            for (b = 0; b < nbits; b = b + 1) begin
                kk = b / 64;
                lsb = kk == nw - 1 ? obits : obits + nbits - 64 * (kk + 1);
                bus_of[b] = wd[lsb + b % 64];
            end
        end
    endfunction

    task next_word(input integer fd, input integer hdr, output integer got);
        integer rr, n1;
        reg [31:0] a1, a2, a3, a4, a5, a6, a7, a8, a9, a10, a11, a12;
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
                    else if (hdr != 0 && $sscanf(line,
                        "// config m=%d depth=%d normal=%d luma=%d luma_taps=%d tile=%d serial=%d c_d=%d c_n=%d c_s=%d t_min=%d t_edge=%d",
                        a1, a2, a3, a4, a5, a6, a7, a8, a9, a10, a11, a12) == 12) begin
                        c_m = a1; c_dd = a2; c_nn = a3; c_ll = a4; c_tt = a5; c_tile = a6; c_ser = a7;
                        c_cd = a8; c_cn = a9; c_cs = a10; c_tm = a11; c_te = a12;
                    end else if ($sscanf(line, "%h", word) == 1) begin
                        got = 1;
                        comment[hdr] = 1'b0;
                    end
                end
            end
        end
    endtask

    initial begin
        if (!$value$plusargs("vectors=%s", vec_path)) $fatal(1, "rtl_aacount_tb: +vectors=FILE missing");
        if (!$value$plusargs("cfg=%s", want_name)) want_name = "default";
        if (!$value$plusargs("bubble=%d", bubble)) bubble = 2;
        if (!$value$plusargs("stall=%d", stall)) stall = 2;
        if (!$value$plusargs("seed=%d", seed)) seed = 1;
        rng = seed == 0 ? 32'h9e3779b9 : seed[31:0];
        for (k = 0; k < NCFG; k = k + 1) if (cfg_name(k) == want_name[8*8-1:0] && want_name[8*64-1:8*8] == 0) sel = k;
        if (sel < 0) $fatal(1, "rtl_aacount_tb: unknown +cfg=%0s", want_name);
        fd_in = $fopen(vec_path, "r");
        fd_out = $fopen(vec_path, "r");
        if (fd_in == 0 || fd_out == 0) $fatal(1, "rtl_aacount_tb: cannot open %0s", vec_path);
        n_hdr = -1; c_m = 0; c_ser = 0; c_tile = 0;
        n_in = 0; n_out = 0; errors = 0; cycles = 0; idle = 0;
        in_done = 0; comment = 2'b00;
    end

    integer got_in, got_out;
    reg [639:0] want_word;
    reg [35:0] want36;
    reg [2:0] on;
    // The word's output fields {s, mask[, sd][, sn][, ss]} (ow bits) as 36
    // bits {s, mask, sd, sn, ss}, an absent field 0.
    function [35:0] outs_of;
        input [639:0] wd;
        input [2:0] present;
        integer pos;
        begin
            outs_of = 36'd0;
            pos = 0;
            if (present[0]) begin outs_of[4:0] = wd[pos+:5]; pos = pos + 5; end
            if (present[1]) begin outs_of[9:5] = wd[pos+:5]; pos = pos + 5; end
            if (present[2]) begin outs_of[14:10] = wd[pos+:5]; pos = pos + 5; end
            outs_of[35:15] = wd[pos+:21];
        end
    endfunction
    always @(posedge clk) begin
        if (rst) begin
            if (cycles == 2) rst <= 1'b0;
            cycles = cycles + 1;
        end else begin
            cycles = cycles + 1;
            bb = {16'd0, bb_k[16*sel+:16]};
            on = on_k[3*sel+:3];
            ow = 21 + 5 * ({31'd0, on[0]} + {31'd0, on[1]} + {31'd0, on[2]});
            if (out_valid && out_ready) begin
                next_word(fd_out, 0, got_out);
                want_word = word;
                if (got_out == 0 || want_word[bb+ow] !== 1'b1)
                    $fatal(1, "rtl_aacount_tb: the DUT delivered more results (%0d) than the file holds", n_out + 1);
                want36 = outs_of(want_word, on);
                if (o36 !== want36) begin
                    errors = errors + 1;
                    if (errors <= MAX_ERRORS)
                        $display("s %0d mask %h sd %0d sn %0d ss %0d expected: s %0d mask %h sd %0d sn %0d ss %0d  (vector %0d)",
                                 o36[35:31], o36[30:15], o36[14:10], o36[9:5], o36[4:0],
                                 want36[35:31], want36[30:15], want36[14:10], want36[9:5], want36[4:0], n_out);
                end
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
                    if (n_in == 0 && ({c_m[7:0], c_dd[7:0], c_nn[7:0], c_ll[7:0], c_tt[7:0], c_cd, c_cn[15:0], c_cs[15:0],
                                       c_tm[15:0], c_te[15:0], 8'd0} != cfg_k[144*sel+:144] || c_ser != 0))
                        $fatal(1, "rtl_aacount_tb: %0s is for m=%0d depth=%0d normal=%0d luma=%0d luma_taps=%0d serial=%0d c_d=%0d c_n=%0d c_s=%0d t_min=%0d t_edge=%0d, not for cfg %0s",
                               vec_path, c_m, c_dd, c_nn, c_ll, c_tt, c_ser, c_cd, c_cn, c_cs, c_tm, c_te, want_name);
                    if (got_in == 0 || word[bb+ow] !== 1'b1) begin
                        in_done = 1;
                        in_valid <= 1'b0;
                    end else begin
                        in_valid <= 1'b1;
                        bus <= bus_of(word, bb, ow);
                    end
                end else in_valid <= 1'b0;
            end
            rng = xorshift(rng);
            out_ready <= {29'd0, rng[5:3]} >= stall;
            if (in_done && n_out == n_in) begin
                if (n_hdr < 0) $fatal(1, "rtl_aacount_tb: %0s has no '// count N' header line", vec_path);
                if (n_hdr != n_in)
                    $fatal(1, "rtl_aacount_tb: the header's count is %0d but the file holds %0d vectors", n_hdr, n_in);
                if (n_in == 0) $fatal(1, "rtl_aacount_tb: no vectors in %0s", vec_path);
                if (errors > MAX_ERRORS) $display("rtl_aacount_tb: (only the first %0d errors are shown)", MAX_ERRORS);
                if (errors != 0)
                    $fatal(1, "rtl_aacount_tb: cfg %0s: In %0d tests, %0d errors found.", want_name, n_in, errors);
                $display("rtl_aacount_tb: cfg %0s (m=%0d depth=%0d normal=%0d luma=%0d luma_taps=%0d c_d=%0d c_n=%0d c_s=%0d t_min=%0d t_edge=%0d), %0d cycles: In %0d tests, no errors found.",
                         want_name, c_m, c_dd, c_nn, c_ll, c_tt, c_cd, c_cn, c_cs, c_tm, c_te, cycles, n_in);
                $finish;
            end
            if (idle > 1000)
                $fatal(1, "rtl_aacount_tb: no output for 1000 cycles after %0d of %0d results (%0d errors)", n_out, n_in, errors);
        end
    end
endmodule
/* verilator lint_on UNUSEDSIGNAL */
