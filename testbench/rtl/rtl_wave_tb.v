// SPDX-License-Identifier: MIT
// rtl_wave_tb - runs the reference RTL rtl_model/verilog/np_wave.v on a
// golden vector file ($readmemh export of `noisepipe vectors --unit wave`),
// under Icarus Verilog and Verilator (--binary) alike. The same bench as
// rtl_classic3_tb.v / rtl_simplex3_tb.v, with the wave unit's register set:
// the file's "// reg NAME HEX FORMAT" header lines (their specification,
// docs/wave.md) drive the DUT's register inputs before the first word.
//
// One compiled bench holds every configuration of the table below, one DUT
// instance each; +cfg=NAME picks the one that runs (the others sit idle with
// their clock held), so one Verilated build serves every configuration.
//
//   +cfg=NAME       default | rom6 | rom10 | irr0_cap0 | trains4 | jac | fold | normals | opts
//   +vectors, +bubble, +stall, +seed as np_tb_vec.vh says (file reading, driver
//   and verdict are its too).
//
// The file is read twice, through two handles, as a text file (never as a
// memory): the driver takes the header (config, registers, count) and each
// word's inputs, the checker each word's expected outputs, in order. The
// bench requires "// count N" (exactly N words must be read), a "// config"
// line equal to the DUT's configuration (keys trains irr cap rom_log2 and
// normals, fold when set; sincos=recurrence is refused: it has no RTL), one
// "// reg" line for each register the configuration reads and mlog2 equal to
// the DUT's MLOG2, and stops at a word whose valid bit is not 1.
// Verdict: "In N tests, no errors found." or $fatal (non-zero exit status).
// Lint: a bench, not hardware: its clocked process is procedural code that
// reads files and keeps counts, so blocking assignments are intended there.
/* verilator lint_off BLKSEQ */
module rtl_wave_tb;
    localparam integer NCFG = 9;
    localparam integer IB = 151;  // i j t ph u v r g
    localparam integer NAME_W = 9;
    function [8*NAME_W-1:0] cfg_name;
        input integer k;
        case (k)
            0: cfg_name = "default";
            1: cfg_name = "rom6";
            2: cfg_name = "rom10";
            3: cfg_name = "irr0_cap0";
            4: cfg_name = "trains4";
            5: cfg_name = "jac";
            6: cfg_name = "fold";
            7: cfg_name = "normals";
            default: cfg_name = "opts";
        endcase
    endfunction

    reg [15:0] i = 16'd0, j = 16'd0, u = 16'd0, v = 16'd0;
    reg [31:0] t = 32'd0, ph = 32'd0;
    reg [7:0] r = 8'd0;
    reg [14:0] g = 15'd0;
    // the register set (4 lanes; a DUT takes its TRAINS)
    reg [2:0] rg_n;
    reg [127:0] rg_kx, rg_kz, rg_phi, rg_om;
    reg [59:0] rg_amp, rg_airr;
    reg [63:0] rg_cx, rg_cz, rg_kmx, rg_kmz;
    reg [15:0] rg_width;
    reg [2:0] rg_mlog2;
    reg [31:0] rg_pu, rg_pv, rg_pt, rg_omc;
    reg [14:0] rg_b, rg_gcap;
    wire [109*NCFG-1:0] o_k;     // each DUT's result fields, right-aligned: {y, dx, dz[, nx, ny, nz][, fold]}
    reg [NCFG*8-1:0] rw_k;       // their width
    reg [NCFG*48-1:0] cfg_k;     // trains irr cap rom_log2 normals fold, 8 bits each

    reg [271:0] word, want_word;
    integer nb, n_regs, want_regs;
    integer c_tr, c_ir, c_cp, c_l, c_no, c_fo;
    reg [108:0] got_m, want_m, mask;
`define NP_TB "rtl_wave_tb"
`include "np_tb_vec.vh"

`define NP_DUT(K, TR, IR, CP, L, NO, FO, INR, OS) \
    wire clk_``K = clk & (sel == K); \
    wire [15:0] y_``K, dx_``K, dz_``K; \
    wire [19:0] nx_``K, ny_``K, nz_``K; \
    wire fold_``K; \
    np_wave #(.TRAINS(TR), .IRR(IR), .CAP(CP), .ROM_LOG2(L), .NORMALS(NO), .FOLD(FO), \
              .IN_REG(INR), .OUT_SKID(OS)) dut_``K ( \
        .clk(clk_``K), .rst(rst), \
        .n(rg_n), .kx(rg_kx[32*TR-1:0]), .kz(rg_kz[32*TR-1:0]), .phi(rg_phi[32*TR-1:0]), .om(rg_om[32*TR-1:0]), \
        .amp(rg_amp[15*TR-1:0]), .airr(rg_airr[15*TR-1:0]), .cx(rg_cx[16*TR-1:0]), .cz(rg_cz[16*TR-1:0]), \
        .kmx(rg_kmx[16*TR-1:0]), .kmz(rg_kmz[16*TR-1:0]), .width(rg_width), .pu(rg_pu), .pv(rg_pv), \
        .pt(rg_pt), .omc(rg_omc), .b(rg_b), .gcap(rg_gcap), \
        .in_valid(in_valid && sel == K), .in_ready(in_ready_k[K]), \
        .i(i), .j(j), .t(t), .ph(ph), .u(u), .v(v), .r(r), .g(g), \
        .out_valid(out_valid_k[K]), .out_ready(out_ready), .y(y_``K), .dx(dx_``K), .dz(dz_``K), \
        .nx(nx_``K), .ny(ny_``K), .nz(nz_``K), .fold(fold_``K)); \
    assign o_k[109*K+:109] = NO ? (FO ? {y_``K, dx_``K, dz_``K, nx_``K, ny_``K, nz_``K, fold_``K} \
                                      : {1'b0, y_``K, dx_``K, dz_``K, nx_``K, ny_``K, nz_``K}) \
                                : (FO ? {60'd0, y_``K, dx_``K, dz_``K, fold_``K} \
                                      : {61'd0, y_``K, dx_``K, dz_``K}); \
    initial begin rw_k[8*K+:8] = 48 + 60 * NO + FO; cfg_k[48*K+:48] = {8'd TR, 8'd IR, 8'd CP, 8'd L, 8'd NO, 8'd FO}; end

    `NP_DUT(0, 2, 1, 1, 8, 0, 0, 0, 0)
    `NP_DUT(1, 2, 1, 1, 6, 0, 0, 0, 0)
    `NP_DUT(2, 2, 1, 1, 10, 0, 0, 0, 0)
    `NP_DUT(3, 2, 0, 0, 8, 0, 0, 0, 0)
    `NP_DUT(4, 4, 1, 1, 8, 0, 0, 0, 0)
    `NP_DUT(5, 2, 1, 1, 8, 1, 1, 0, 0)
    `NP_DUT(6, 1, 0, 0, 8, 0, 1, 0, 0)
    `NP_DUT(7, 3, 1, 1, 8, 1, 0, 0, 0)
    `NP_DUT(8, 2, 1, 1, 8, 0, 0, 1, 1)

    wire [108:0] o109 = o_k[109*sel+:109];

`ifdef VERILATOR
    string rname;
    string tname;
`else
    reg [8*32-1:0] rname;
    reg [8*32-1:0] tname;
`endif

    // One "// reg NAME HEX" line: the register it names, or $fatal.
    task set_reg(input [31:0] val);
        integer q, hit;
        begin
            hit = 0;
            if (rname == "n") begin rg_n = val[2:0]; hit = 1; end
            if (rname == "width") begin rg_width = val[15:0]; hit = 1; end
            if (rname == "mlog2") begin rg_mlog2 = val[2:0]; hit = 1; end
            if (rname == "pu") begin rg_pu = val; hit = 1; end
            if (rname == "pv") begin rg_pv = val; hit = 1; end
            if (rname == "pt") begin rg_pt = val; hit = 1; end
            if (rname == "omc") begin rg_omc = val; hit = 1; end
            if (rname == "b") begin rg_b = val[14:0]; hit = 1; end
            if (rname == "gcap") begin rg_gcap = val[14:0]; hit = 1; end
            for (q = 0; q < 4; q = q + 1) begin
                $sformat(tname, "tr%0d.kx", q);   if (rname == tname) begin rg_kx[32*q+:32] = val; hit = 1; end
                $sformat(tname, "tr%0d.kz", q);   if (rname == tname) begin rg_kz[32*q+:32] = val; hit = 1; end
                $sformat(tname, "tr%0d.phi", q);  if (rname == tname) begin rg_phi[32*q+:32] = val; hit = 1; end
                $sformat(tname, "tr%0d.om", q);   if (rname == tname) begin rg_om[32*q+:32] = val; hit = 1; end
                $sformat(tname, "tr%0d.amp", q);  if (rname == tname) begin rg_amp[15*q+:15] = val[14:0]; hit = 1; end
                $sformat(tname, "tr%0d.airr", q); if (rname == tname) begin rg_airr[15*q+:15] = val[14:0]; hit = 1; end
                $sformat(tname, "tr%0d.cx", q);   if (rname == tname) begin rg_cx[16*q+:16] = val[15:0]; hit = 1; end
                $sformat(tname, "tr%0d.cz", q);   if (rname == tname) begin rg_cz[16*q+:16] = val[15:0]; hit = 1; end
                $sformat(tname, "tr%0d.kmx", q);  if (rname == tname) begin rg_kmx[16*q+:16] = val[15:0]; hit = 1; end
                $sformat(tname, "tr%0d.kmz", q);  if (rname == tname) begin rg_kmz[16*q+:16] = val[15:0]; hit = 1; end
            end
            if (hit == 0) $fatal(1, "rtl_wave_tb: %0s: unknown register '%0s' in a '// reg' line", vec_path, rname);
            n_regs = n_regs + 1;
        end
    endtask

    // Header lines of handle fd_in: "// reg ..." and "// config ...".
    task header_line(output integer took);
        integer n1, n2, n3, n4, n5, n6, nf;
        reg [31:0] hv;
        /* verilator lint_off UNUSEDSIGNAL */
        reg [7:0] ch;  // the first letter after sincos= (only that it is there counts)
        /* verilator lint_on UNUSEDSIGNAL */
        begin
            took = 1;
            if ($sscanf(line, "// reg %s %h", rname, hv) == 2) set_reg(hv);
            else if ($sscanf(line, "// config trains=%d irr=%d cap=%d rom_log2=%d", n1, n2, n3, n4) == 4) begin
                c_tr = n1; c_ir = n2; c_cp = n3; c_l = n4; c_no = 0; c_fo = 0;
                nf = $sscanf(line, "// config trains=%d irr=%d cap=%d rom_log2=%d normals=%d fold=%d",
                             n1, n2, n3, n4, n5, n6);
                if (nf >= 5) c_no = n5;
                if (nf == 6) c_fo = n6;
                if ($sscanf(line, "// config trains=%d irr=%d cap=%d rom_log2=%d fold=%d",
                            n1, n2, n3, n4, n6) == 5) c_fo = n6;
                if ($sscanf(line, "// config trains=%d irr=%d cap=%d rom_log2=%d sincos=%c",
                            n1, n2, n3, n4, ch) == 5)
                    $fatal(1, "rtl_wave_tb: %0s is for sincos=recurrence, which has no RTL (docs/wave.md, Reference RTL)", vec_path);
            end else took = 0;
        end
    endtask

    initial begin
        np_tb_open("default");
        c_tr = -1; c_ir = -1; c_cp = -1; c_l = -1; c_no = -1; c_fo = -1;
        n_regs = 0;
        rg_n = 0; rg_kx = 0; rg_kz = 0; rg_phi = 0; rg_om = 0; rg_amp = 0; rg_airr = 0; rg_cx = 0; rg_cz = 0;
        rg_kmx = 0; rg_kmz = 0; rg_width = 0; rg_mlog2 = 3'd7; rg_pu = 0; rg_pv = 0; rg_pt = 0; rg_omc = 0;
        rg_b = 0; rg_gcap = 0;
    end

    // The word: {valid, i, j, t, ph, u, v, r, g (IB bits), the result fields} (nb bits of them).
    task layout;
        begin
            nb = {24'd0, rw_k[8*sel+:8]};
            vpos = nb + IB;
        end
    endtask

    task check_result;
        begin
            mask = {109{1'b1}} >> (109 - nb);
            want_m = want_word[108:0] & mask;
            got_m = o109 & mask;
            if (got_m !== want_m) begin
                errors = errors + 1;
                if (errors <= MAX_ERRORS)
                    $display("i %h j %h t %h ph %h u %h v %h r %h g %h => %h expected: %h  (vector %0d)",
                             want_word[nb+150-:16], want_word[nb+134-:16], want_word[nb+118-:32],
                             want_word[nb+86-:32], want_word[nb+54-:16], want_word[nb+38-:16],
                             want_word[nb+22-:8], want_word[nb+14-:15], got_m, want_m, n_out);
            end
        end
    endtask

    task check_config;
        begin
            if ({c_tr[7:0], c_ir[7:0], c_cp[7:0], c_l[7:0], c_no[7:0], c_fo[7:0]} != cfg_k[48*sel+:48])
                $fatal(1, "rtl_wave_tb: %0s is for trains=%0d irr=%0d cap=%0d rom_log2=%0d normals=%0d fold=%0d, not for cfg %0s",
                       vec_path, c_tr, c_ir, c_cp, c_l, c_no, c_fo, want_name);
            // n, 8 a train (10 with normals or fold), 8 for the box
            want_regs = 1 + rg_n * ((c_no != 0 || c_fo != 0) ? 10 : 8) + 8;
            if (n_regs != want_regs)
                $fatal(1, "rtl_wave_tb: %0s has %0d '// reg' lines before its first vector, not the %0d of its register set",
                       vec_path, n_regs, want_regs);
            if (rg_mlog2 != 3'd3)
                $fatal(1, "rtl_wave_tb: %0s has mlog2=%0d; the DUT is built for MLOG2=3", vec_path, rg_mlog2);
        end
    endtask

    task drive_input;
        {i, j, t, ph, u, v, r, g} <= word[nb+IB-1-:IB];
    endtask

    task report_pass;
        $display("rtl_wave_tb: cfg %0s (trains=%0d irr=%0d cap=%0d rom_log2=%0d normals=%0d fold=%0d), %0d cycles: In %0d tests, no errors found.",
                 want_name, c_tr, c_ir, c_cp, c_l, c_no, c_fo, cycles, n_in);
    endtask
endmodule
