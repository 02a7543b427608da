// SPDX-License-Identifier: MIT
// rtl_texel_tb - runs the reference RTL rtl_model/verilog/np_texel.v (with
// np_span_seq.v) on a golden vector set of the stream unit texel
// (vectors/texel/*.vec, written by np_stream_generate; docs/vectors.md and
// src/units/np_stream.h), under Icarus Verilog and Verilator (--binary) alike.
//
// A transaction of the set is one pixel: inputs s t r ds dt dr n k, outputs
// cr cg cb (then three float references, ignored here). Consecutive lines of
// one descriptor with k = k0, k0 + 1, ..., k0 + m - 1 are a run; the bench
// sends the run's descriptor once, with its length cut to k0 + m (np_stream.h:
// the pixels do not depend on n), and compares pixels k0 .. k0 + m - 1 of
// what comes out, ignoring the first k0. The RTL has no seek: a run that
// starts at k0 > 0 costs k0 + m pixels of simulation. Run j is sent as
// scanline y = j at x0 = 0, so every pixel's tags must read (x, y) = (k, j).
//
//   +vectors=FILE   the .vec file (required): "# count N", "# unit texel" and
//                   "# config texture=T idx_int= w_frac= guard= weight_frac=
//                   setup_mults= mult_lat=" required and equal to the DUT's
//   +regs=FILE      the texture's registers (texel_regs T FILE; required): its
//                   "texture T" must be the set's T and n_oct the DUT's N_OCT
//   +bubble=B +stall=S   input bubbles and output stalls, in 1/8 (default 2, 2)
//   +seed=N         the bubble/stall generator's seed (xorshift32, default 1)
//   +cycles=C       optional: the run must take exactly C cycles (the timing
//                   of np_span_sim under this traffic; a wrong count fails)
// Verdict: "... C cycles: In N tests, no errors found." or $fatal (non-zero
// exit status). The cycle count pins the unit's timing (set-up stalls,
// descriptor buffer, latency) under the bench's traffic.
// Lint: a bench, not hardware: its clocked process is procedural code that
// reads files and keeps counts, so blocking assignments are intended there.
//
// The same bench runs the forward-difference unit fdiff (np_fdiff.v) when built
// with -DNP_TB_FDIFF: module rtl_fdiff_tb, sets of unit fdiff (vectors/fdiff/),
// whose config line has resetup= where texel's has weight_frac= (the fifth key).
/* verilator lint_off BLKSEQ */
`ifdef NP_TB_FDIFF
`define NP_TB "rtl_fdiff_tb"
`define NP_TB_UNIT "fdiff"
`define NP_TB_KEY5 "resetup"
/* verilator lint_off DECLFILENAME */  // the fdiff build of this file: its module is rtl_fdiff_tb
module rtl_fdiff_tb;
/* verilator lint_on DECLFILENAME */
`else
`define NP_TB "rtl_texel_tb"
`define NP_TB_UNIT "texel"
`define NP_TB_KEY5 "weight_frac"
module rtl_texel_tb;
`endif
    localparam integer MAX_ERRORS = 20;
    localparam integer MAXV = 65536;       // transactions a set may hold
    // The DUT's configuration (np_texel.v's parameters).
`ifdef NP_TB_FDIFF
    localparam integer IDX_INT = 10, W_FRAC = 12, GUARD = 44, KEY5 = 0, SETUP_MULTS = 2, MULT_LAT = 2;  // KEY5: RESETUP
`else
    localparam integer IDX_INT = 10, W_FRAC = 12, GUARD = 20, KEY5 = 16, SETUP_MULTS = 2, MULT_LAT = 2;  // KEY5: WEIGHT_FRAC
`endif
    localparam integer N_OCT = 1;

    reg clk = 1'b0;
    reg rst = 1'b1;
    always #5 clk = !clk;

    // registers
    reg [479:0] k_reg = 480'd0;
    reg [216*N_OCT-1:0] m_reg = 0;
    reg [144*N_OCT-1:0] o_reg = 0;
    reg [32*N_OCT-1:0] amp_reg = 0;
    reg [6143:0] cmap = 6144'd0;
    reg [8:0] cmap_n = 9'd0;
    reg cmap_rep = 1'b0;
    // descriptor port
    reg in_valid = 1'b0, out_ready = 1'b0;
    reg [15:0] in_y = 16'd0, in_x0 = 16'd0;
    reg [16:0] in_n = 17'd0;
    reg [47:0] in_s = 48'd0, in_t = 48'd0, in_r = 48'd0;
    reg [40:0] in_ds = 41'd0, in_dt = 41'd0, in_dr = 41'd0;
    wire in_ready, out_valid;
    wire [15:0] px, py;
    wire [7:0] cr, cg, cb;

`ifdef NP_TB_FDIFF
    np_fdiff #(.IDX_INT(IDX_INT), .W_FRAC(W_FRAC), .GUARD(GUARD), .RESETUP(KEY5),
`else
    np_texel #(.IDX_INT(IDX_INT), .W_FRAC(W_FRAC), .GUARD(GUARD), .WEIGHT_FRAC(KEY5),
`endif
               .SETUP_MULTS(SETUP_MULTS), .MULT_LAT(MULT_LAT), .N_OCT(N_OCT)) dut (
        .clk(clk), .rst(rst), .k_reg(k_reg), .m_reg(m_reg), .o_reg(o_reg), .amp_reg(amp_reg), .cmap(cmap),
        .cmap_n(cmap_n), .cmap_rep(cmap_rep),
        .in_valid(in_valid), .in_ready(in_ready), .in_y(in_y), .in_x0(in_x0), .in_n(in_n),
        .in_s(in_s), .in_t(in_t), .in_r(in_r), .in_ds(in_ds), .in_dt(in_dt), .in_dr(in_dr),
        .out_valid(out_valid), .out_ready(out_ready), .px(px), .py(py), .cr(cr), .cg(cg), .cb(cb));

    // The set, read at time 0: per transaction its descriptor, k and colour.
    reg [47:0] v_s[0:MAXV-1], v_t[0:MAXV-1], v_r[0:MAXV-1];
    reg [40:0] v_ds[0:MAXV-1], v_dt[0:MAXV-1], v_dr[0:MAXV-1];
    reg [16:0] v_n[0:MAXV-1];
    reg [15:0] v_k[0:MAXV-1];
    reg [23:0] v_rgb[0:MAXV-1];
    // Runs: first transaction, k0, m.
    integer r_first[0:MAXV-1], r_k0[0:MAXV-1], r_m[0:MAXV-1];

`ifdef VERILATOR
    string line;
    string vec_path;
    string regs_path;
    string tex_set;
    string tex_regs;
`define NP_LAST_CHAR (line.len() > 0 ? line.getc(line.len() - 1) : 8'h00)
`define NP_CLEAR_LINE line = ""
`else
    reg [8*400-1:0] line;  // $fgets stops at 400 characters; the rest comes next
    reg [8*256-1:0] vec_path;
    reg [8*256-1:0] regs_path;
    reg [8*32-1:0] tex_set;
    reg [8*32-1:0] tex_regs;
`define NP_LAST_CHAR line[7:0]
`define NP_CLEAR_LINE line = 0
`endif
    reg [31:0] rng;
    integer fd, rr, nv, nruns, n_hdr, c_i, c_fw, c_g, c_wt, c_p, c_lm, has_unit, n_oct_regs, errors, cycles, idle;
    integer bubble, stall, seed, i1, i2, i3, cont, nregs;
    integer want_cycles;
    /* verilator lint_off UNUSEDSIGNAL */
    reg [63:0] h1, h2, h3, h4, h5, h6, h7, h8, h9, h10, h11;  // a line's fields, read at 64 bits, kept at their widths
    /* verilator lint_on UNUSEDSIGNAL */

    function [31:0] xorshift;
        input [31:0] s;
        reg [31:0] x;
        begin
            x = s ^ (s << 13);
            x = x ^ (x >> 17);
            xorshift = x ^ (x << 5);
        end
    endfunction

    initial begin
        if (!$value$plusargs("vectors=%s", vec_path)) $fatal(1, "%0s: +vectors=FILE missing", `NP_TB);
        if (!$value$plusargs("regs=%s", regs_path)) $fatal(1, "%0s: +regs=FILE missing", `NP_TB);
        if (!$value$plusargs("bubble=%d", bubble)) bubble = 2;
        if (!$value$plusargs("stall=%d", stall)) stall = 2;
        if (!$value$plusargs("seed=%d", seed)) seed = 1;
        if (!$value$plusargs("cycles=%d", want_cycles)) want_cycles = -1;
        rng = seed == 0 ? 32'h9e3779b9 : seed[31:0];
        // --- registers
        fd = $fopen(regs_path, "r");
        if (fd == 0) $fatal(1, "%0s: cannot open %0s", `NP_TB, regs_path);
        n_oct_regs = -1;
        nregs = 0;
        cont = 0;
        while (!$feof(fd)) begin
            `NP_CLEAR_LINE;
            rr = $fgets(line, fd);
            if (rr > 0 && cont == 0) begin
                if ($sscanf(line, "texture %s", tex_regs) == 1) nregs = nregs + 1;
                else if ($sscanf(line, "n_oct %d", i1) == 1) n_oct_regs = i1;
                else if ($sscanf(line, "cmap_n %d", i1) == 1) cmap_n = i1[8:0];
                else if ($sscanf(line, "cmap_rep %d", i1) == 1) cmap_rep = i1[0];
                else if ($sscanf(line, "k %d %h", i1, h1) == 2) k_reg[48*i1 +: 48] = h1[47:0];
                else if ($sscanf(line, "m %d %d %d %h", i1, i2, i3, h1) == 4) begin
                    if (i1 < N_OCT) m_reg[24*(9*i1 + 3*i2 + i3) +: 24] = h1[23:0];
                end else if ($sscanf(line, "o %d %d %h", i1, i2, h1) == 3) begin
                    if (i1 < N_OCT) o_reg[48*(3*i1 + i2) +: 48] = h1[47:0];
                end else if ($sscanf(line, "amp %d %h", i1, h1) == 2) begin
                    if (i1 < N_OCT) amp_reg[32*i1 +: 32] = h1[31:0];
                end else if ($sscanf(line, "cmap %d %h", i1, h1) == 2) begin
                    cmap[24*i1 +: 8] = h1[23:16];
                    cmap[24*i1 + 8 +: 8] = h1[15:8];
                    cmap[24*i1 + 16 +: 8] = h1[7:0];
                end
            end
            if (rr > 0) cont = `NP_LAST_CHAR != 8'h0a ? 1 : 0;
        end
        $fclose(fd);
        if (nregs != 1) $fatal(1, "%0s: %0s has no 'texture NAME' line", `NP_TB, regs_path);
        if (n_oct_regs != N_OCT)
            $fatal(1, "%0s: %0s has n_oct %0d; the DUT is built for N_OCT=%0d", `NP_TB, regs_path, n_oct_regs, N_OCT);
        // --- the vector set
        fd = $fopen(vec_path, "r");
        if (fd == 0) $fatal(1, "%0s: cannot open %0s", `NP_TB, vec_path);
        nv = 0;
        n_hdr = -1;
        c_i = -1; c_fw = -1; c_g = -1; c_wt = -1; c_p = -1; c_lm = -1;
        has_unit = 0;
        cont = 0;
        while (!$feof(fd)) begin
            `NP_CLEAR_LINE;
            rr = $fgets(line, fd);
            if (rr > 0 && cont == 0) begin
                if ($sscanf(line, "# count %d", i1) == 1) n_hdr = i1;
                else if ($sscanf(line, "# unit %s", tex_set) == 1) begin
                    if (tex_set != `NP_TB_UNIT) $fatal(1, "%0s: %0s is a set of unit %0s, not %0s", `NP_TB, vec_path, tex_set, `NP_TB_UNIT);
                    has_unit = 1;
`ifdef NP_TB_FDIFF
                end else if ($sscanf(line, "# config texture=%s idx_int=%d w_frac=%d guard=%d resetup=%d setup_mults=%d mult_lat=%d",
                                     tex_set, c_i, c_fw, c_g, c_wt, c_p, c_lm) == 7) begin
`else
                end else if ($sscanf(line, "# config texture=%s idx_int=%d w_frac=%d guard=%d weight_frac=%d setup_mults=%d mult_lat=%d",
                                     tex_set, c_i, c_fw, c_g, c_wt, c_p, c_lm) == 7) begin
`endif
                end else if ($sscanf(line, "%h %h %h %h %h %h %h %h %h %h %h", h1, h2, h3, h4, h5, h6, h7, h8, h9, h10, h11) == 11) begin
                    if (nv >= MAXV) $fatal(1, "%0s: %0s holds more than %0d transactions", `NP_TB, vec_path, MAXV);
                    v_s[nv] = h1[47:0]; v_t[nv] = h2[47:0]; v_r[nv] = h3[47:0];
                    v_ds[nv] = h4[40:0]; v_dt[nv] = h5[40:0]; v_dr[nv] = h6[40:0];
                    v_n[nv] = h7[16:0]; v_k[nv] = h8[15:0];
                    v_rgb[nv] = {h9[7:0], h10[7:0], h11[7:0]};
                    nv = nv + 1;
                end
            end
            if (rr > 0) cont = `NP_LAST_CHAR != 8'h0a ? 1 : 0;
        end
        $fclose(fd);
        if (n_hdr < 0) $fatal(1, "%0s: %0s has no '# count N' header line", `NP_TB, vec_path);
        if (n_hdr != nv) $fatal(1, "%0s: the header's count is %0d but the file holds %0d vectors", `NP_TB, n_hdr, nv);
        if (nv == 0) $fatal(1, "%0s: no vectors in %0s", `NP_TB, vec_path);
        if (has_unit == 0) $fatal(1, "%0s: %0s has no '# unit' header line", `NP_TB, vec_path);
        if (c_i != IDX_INT || c_fw != W_FRAC || c_g != GUARD || c_wt != KEY5 || c_p != SETUP_MULTS || c_lm != MULT_LAT)
            $fatal(1, "%0s: %0s is for idx_int=%0d w_frac=%0d guard=%0d %0s=%0d setup_mults=%0d mult_lat=%0d, not for the DUT's %0d %0d %0d %0d %0d %0d", `NP_TB,
                   vec_path, c_i, c_fw, c_g, `NP_TB_KEY5, c_wt, c_p, c_lm, IDX_INT, W_FRAC, GUARD, KEY5, SETUP_MULTS, MULT_LAT);
        if (tex_set != tex_regs) $fatal(1, "%0s: %0s is for texture=%0s but %0s holds texture %0s", `NP_TB, vec_path, tex_set, regs_path, tex_regs);
        // --- runs
        nruns = 0;
        for (i1 = 0; i1 < nv; i1 = i1 + 1) begin
            if (nruns > 0 && v_s[i1] == v_s[i1-1] && v_t[i1] == v_t[i1-1] && v_r[i1] == v_r[i1-1] &&
                v_ds[i1] == v_ds[i1-1] && v_dt[i1] == v_dt[i1-1] && v_dr[i1] == v_dr[i1-1] && v_n[i1] == v_n[i1-1] &&
                v_k[i1] == v_k[i1-1] + 16'd1) begin
                r_m[nruns-1] = r_m[nruns-1] + 1;
            end else begin
                r_first[nruns] = i1;
                r_k0[nruns] = {16'd0, v_k[i1]};
                r_m[nruns] = 1;
                nruns = nruns + 1;
            end
        end
        for (i1 = 0; i1 < nruns; i1 = i1 + 1)
            if (r_k0[i1] + r_m[i1] > {15'd0, v_n[r_first[i1]]})
                $fatal(1, "%0s: run %0d (transaction %0d) reaches pixel %0d of a %0d-pixel span", `NP_TB, i1, r_first[i1],
                       r_k0[i1] + r_m[i1] - 1, v_n[r_first[i1]]);
        errors = 0;
        cycles = 0;
        idle = 0;
    end

    // Driver and checker. Both sides change after the clock edge.
    integer sent = 0, orun = 0, opix = 0, checked = 0, pixels = 0, dv;
    reg [23:0] got, want;
    always @(posedge clk) begin
        cycles = cycles + 1;
        if (rst) begin
            if (cycles == 3) rst <= 1'b0;
        end else begin
            // output side: the transfer of this edge
            if (out_valid && out_ready) begin
                if (orun >= nruns) $fatal(1, "%0s: the DUT delivered more pixels than the runs hold", `NP_TB);
                if (px != opix[15:0] || py != orun[15:0]) begin
                    errors = errors + 1;
                    if (errors <= MAX_ERRORS)
                        $display("run %0d pixel %0d: tagged (x, y) = (%0d, %0d), expected (%0d, %0d)", orun, opix, px, py,
                                 opix, orun);
                end
                if (opix >= r_k0[orun]) begin
                    dv = r_first[orun] + opix - r_k0[orun];
                    got = {cr, cg, cb};
                    want = v_rgb[dv];
                    if (got !== want) begin
                        errors = errors + 1;
                        if (errors <= MAX_ERRORS)
                            $display("%h %h %h %h %h %h %h %h => %h %h %h expected: %h %h %h  (vector %0d)",
                                     v_s[dv], v_t[dv], v_r[dv], v_ds[dv], v_dt[dv], v_dr[dv], v_n[dv], v_k[dv],
                                     got[23:16], got[15:8], got[7:0], want[23:16], want[15:8], want[7:0], dv);
                    end
                    checked = checked + 1;
                end
                pixels = pixels + 1;
                opix = opix + 1;
                if (opix >= r_k0[orun] + r_m[orun]) begin
                    orun = orun + 1;
                    opix = 0;
                end
                idle = 0;
            end else idle = idle + 1;
            // input side: a presented descriptor stays until it is accepted
            if (in_valid && in_ready) begin
                sent = sent + 1;
                in_valid <= 1'b0;
            end
            if (sent < nruns && (!in_valid || in_ready)) begin
                rng = xorshift(rng);
                if ({29'd0, rng[2:0]} >= bubble) begin
                    dv = r_first[sent];
                    in_valid <= 1'b1;
                    in_y <= sent[15:0];
                    in_x0 <= 16'd0;
                    in_n <= r_k0[sent][16:0] + r_m[sent][16:0];
                    in_s <= v_s[dv]; in_t <= v_t[dv]; in_r <= v_r[dv];
                    in_ds <= v_ds[dv]; in_dt <= v_dt[dv]; in_dr <= v_dr[dv];
                end else in_valid <= 1'b0;
            end
            rng = xorshift(rng);
            out_ready <= {29'd0, rng[5:3]} >= stall;
            if (orun == nruns && sent == nruns) begin
                if (errors > MAX_ERRORS) $display("%0s: (only the first %0d errors are shown)", `NP_TB, MAX_ERRORS);
                if (errors != 0)
                    $fatal(1, "%0s: texture=%0s: In %0d tests, %0d errors found.", `NP_TB, tex_set, checked, errors);
                if (want_cycles >= 0 && cycles != want_cycles)
                    $fatal(1, "%0s: all %0d tests right, but in %0d cycles, not the %0d of the C cycle model's timing", `NP_TB,
                           checked, cycles, want_cycles);
                $display("%0s: texture=%0s idx_int=%0d w_frac=%0d guard=%0d %0s=%0d setup_mults=%0d mult_lat=%0d, %0d runs, %0d pixels, %0d cycles: In %0d tests, no errors found.", `NP_TB,
                         tex_set, IDX_INT, W_FRAC, GUARD, `NP_TB_KEY5, KEY5, SETUP_MULTS, MULT_LAT, nruns, pixels, cycles, checked);
                $finish;
            end
            if (idle > 1000)
                $fatal(1, "%0s: no output for 1000 cycles after %0d of %0d runs (%0d errors)", `NP_TB, orun, nruns, errors);
        end
    end
endmodule
`undef NP_TB
`undef NP_TB_UNIT
`undef NP_TB_KEY5
