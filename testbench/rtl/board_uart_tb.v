// SPDX-License-Identifier: MIT
// board_uart_tb - np_uart_tx and np_uart_rx (rtl_model/verilog/board/) at CLKS_PER_BIT = `CPB
// (define it; default 8), clock 10 ns. Three parts, each on NB seeded random bytes:
//   tx: bytes into np_uart_tx with random gaps; the bench's own receiver samples txd in the
//       middle of each bit (start 0, 8 data bits LSB first, stop 1) and compares; it also
//       checks the back-to-back pace, 10 * CPB + 1 clocks a byte;
//   rx: the bench drives rxd at a bit time of CPB * 10 ns * (1 + ppm / 10^6) for ppm in
//       +EPPM, 0, -EPPM (`EPPM, default 30000: 3 %), with random idle gaps, a frame with a low
//       stop bit every 16th byte (must raise frame_err and give no byte) and a glitch shorter
//       than half a bit before every 8th byte (must give nothing);
//   loop: np_uart_tx's txd into a second np_uart_rx.
// Prints "In N bytes, E errors found." (N counts every byte checked in the three parts).
`timescale 1ns / 1ps
`ifndef CPB
`define CPB 8
`endif
`ifndef EPPM
`define EPPM 30000
`endif
module board_uart_tb;
    localparam integer NB = 400;
    reg clk = 0, rst = 1;
    always #5 clk = ~clk;

    // tx under test
    reg tv = 0;
    reg [7:0] td = 0;
    wire tready, txd;
    np_uart_tx #(.CLKS_PER_BIT(`CPB)) tx (.clk(clk), .rst(rst), .valid(tv), .data(td), .ready(tready), .txd(txd));
    // rx under test, driven by the bench
    reg rxd = 1;
    wire rv, rerr;
    wire [7:0] rdata;
    np_uart_rx #(.CLKS_PER_BIT(`CPB)) rx (.clk(clk), .rst(rst), .rxd(rxd), .valid(rv), .data(rdata), .frame_err(rerr));
    // loopback rx
    wire lv, lerr;
    wire [7:0] ldata;
    np_uart_rx #(.CLKS_PER_BIT(`CPB)) lrx (.clk(clk), .rst(rst), .rxd(txd), .valid(lv), .data(ldata), .frame_err(lerr));

    integer errors = 0, checked = 0, seed = 7;
    reg [7:0] sent [0:NB-1];
    reg [7:0] rsent [0:3*NB-1];
    integer nsent = 0, nmon = 0, nloop = 0, nrsent = 0, nrgot = 0, nferr = 0, wantferr = 0;

    task fail(input [8*40-1:0] what, input integer i, input [7:0] got, input [7:0] want);
        begin
            if (errors < 10)
                $display("%0s %0d: got %02x, want %02x", what, i, got, want);
            errors = errors + 1;
        end
    endtask

    // The bench's receiver on txd: mid-bit samples from the falling edge.
    reg [7:0] mb;
    integer k, t_start, t_prev = -1, pace_bad = 0, backtoback = 0;
    initial begin : monitor
        @(negedge rst);
        forever begin
            @(negedge txd);
            t_start = $time;
            if (t_prev >= 0 && t_start - t_prev == (10 * `CPB + 1) * 10)
                backtoback = backtoback + 1;
            else if (t_prev >= 0 && t_start - t_prev < (10 * `CPB + 1) * 10)
                pace_bad = pace_bad + 1;
            t_prev = t_start;
            #(`CPB * 5);
            if (txd !== 1'b0)
                fail("tx start bit", nmon, {7'd0, txd}, 8'd0);
            for (k = 0; k < 8; k = k + 1) begin
                #(`CPB * 10);
                mb[k] = txd;
            end
            #(`CPB * 10);
            if (txd !== 1'b1)
                fail("tx stop bit", nmon, {7'd0, txd}, 8'd1);
            if (mb !== sent[nmon])
                fail("tx byte", nmon, mb, sent[nmon]);
            nmon = nmon + 1;
            checked = checked + 1;
        end
    end
    // The loopback receiver.
    always @(posedge clk)
        if (!rst && lv) begin
            if (ldata !== sent[nloop])
                fail("loopback byte", nloop, ldata, sent[nloop]);
            nloop = nloop + 1;
            checked = checked + 1;
        end else if (!rst && lerr) begin
            fail("loopback frame_err", nloop, 8'd1, 8'd0);
        end
    // The rx under test.
    always @(posedge clk)
        if (!rst && rv) begin
            if (rdata !== rsent[nrgot])
                fail("rx byte", nrgot, rdata, rsent[nrgot]);
            nrgot = nrgot + 1;
            checked = checked + 1;
        end else if (!rst && rerr) begin
            nferr = nferr + 1;
        end

    // Drive one frame on rxd at bit time bt (ns, real): start, 8 bits, stop (stop_v).
    task frame(input [7:0] b, input real bt, input stop_v);
        integer j;
        begin
            rxd = 0;
            #(bt);
            for (j = 0; j < 8; j = j + 1) begin
                rxd = b[j];
                #(bt);
            end
            rxd = stop_v;
            #(bt);
            rxd = 1;
        end
    endtask

    integer i, p;
    real bt;
    reg [7:0] b;
    initial begin
        repeat (4) @(posedge clk);
        rst <= 0;
        // tx (and the loopback): half the bytes back to back, half with random gaps
        for (i = 0; i < NB; i = i + 1) begin
            b = $random(seed);
            sent[i] = b;
            @(negedge clk);
            while (!tready)
                @(negedge clk);
            while (i >= NB / 2 && ($random(seed) & 1)) // idle clocks between bytes
                @(negedge clk);
            tv = 1;
            td = b;
            @(posedge clk);
            #1 tv = 0;
        end
        wait (tready);
        #(`CPB * 10 * 12);
        // rx at three bit times
        for (p = 0; p < 3; p = p + 1) begin
            bt = `CPB * 10.0 * (1.0 + (p == 0 ? `EPPM : p == 1 ? 0 : -`EPPM) / 1000000.0);
            for (i = 0; i < NB; i = i + 1) begin
                b = $random(seed);
                #(($random(seed) & 3) * bt / 3.0);
                if (i % 8 == 7) begin // a glitch shorter than half a bit
                    rxd = 0;
                    #(bt / 3.0);
                    rxd = 1;
                    #(bt);
                end
                if (i % 16 == 15) begin
                    frame(b, bt, 0); // low stop bit: frame_err, no byte
                    wantferr = wantferr + 1;
                    #(bt * 2);
                end else begin
                    rsent[nrsent] = b;
                    nrsent = nrsent + 1;
                    frame(b, bt, 1);
                end
            end
        end
        #(`CPB * 10 * 12);
        if (nmon != NB || nloop != NB) begin
            $display("tx: %0d bytes seen by the bench's receiver and %0d by the loopback, of %0d", nmon, nloop, NB);
            errors = errors + 1;
        end
        if (nrgot != nrsent) begin
            $display("rx: %0d bytes received of %0d", nrgot, nrsent);
            errors = errors + 1;
        end
        if (nferr != wantferr) begin
            $display("rx: %0d framing errors flagged, %0d sent", nferr, wantferr);
            errors = errors + 1;
        end
        if (pace_bad != 0 || backtoback < NB / 2 - 1 || backtoback > NB - NB / 8) begin
            $display("tx pace: %0d bytes closer than %0d clocks, %0d back to back", pace_bad, 10 * `CPB + 1, backtoback);
            errors = errors + 1;
        end
        $display("CPB %0d, bit time +-%0d ppm: %0d framing errors flagged, %0d back-to-back bytes at %0d clocks",
                 `CPB, `EPPM, nferr, backtoback, 10 * `CPB + 1);
        $display("In %0d bytes, %0d errors found.", checked, errors);
        $finish;
    end
endmodule
