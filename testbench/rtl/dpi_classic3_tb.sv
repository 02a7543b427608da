// SPDX-License-Identifier: MIT
// dpi_classic3_tb - example SystemVerilog testbench using noisepipe's models
// through DPI-C (rtl_model/verilog/dpi/np_dpi_pkg.sv) on the classic3 RTL:
//   - scoreboard: each accepted input's expected f from the bit-exact model
//     (np_dpi_classic3_eval), queued, compared with the DUT's f in order;
//   - lock step: the C cycle model (np_dpi_classic3_pipe_new) evaluated on
//     the same port inputs every cycle: in_ready, out_valid and f must agree.
// Random stimulus ($urandom), 1 in 4 cycles a bubble and 1 in 4 a stall.
// Build (testbench/rtl.cmake, test rtl.dpi.build): Verilator --binary with
// np_dpi_pkg.sv, this file, np_classic3.v and the pipe options, np_dpi.a, libnoisepipe_rtl.a.
//   ./dpi_classic3_tb [+n=TRANSACTIONS]
/* verilator lint_off BLKSEQ */
module dpi_classic3_tb;
    import np_dpi_pkg::*;
    localparam int N = 8, WS = 12, WL = 11;

    logic clk = 1'b0, rst = 1'b1;
    logic in_valid = 1'b0, out_ready = 1'b0;
    logic [15:0] x = '0, y = '0, z = '0;
    logic in_ready, out_valid;
    logic [N-1:0] f;
    np_classic3 #(.OUT_BITS(N), .S_FRAC(WS), .LERP_FRAC(WL)) dut (
        .clk(clk), .rst(rst), .in_valid(in_valid), .in_ready(in_ready), .x(x), .y(y), .z(z),
        .out_valid(out_valid), .out_ready(out_ready), .f(f));

    always #5 clk = !clk;

    chandle pm;
    int expect_q[$];
    int ntx = 200000, n_out = 0, n_in = 0, errors = 0, lock_errors = 0, cycles = 0;
    int m_in_ready, m_out_valid, m_f, want;
    int m_dx, m_dy, m_dz;  // the simplex unit's outputs: 0 for classic3
    wire unused_d = |{m_dx, m_dy, m_dz};

    initial begin
        void'($value$plusargs("n=%d", ntx));
        pm = np_dpi_classic3_pipe_new(N, WS, WL, 0, 0);
        if (pm == null) $fatal(1, "dpi_classic3_tb: the cycle model rejects the configuration");
        if (np_dpi_classic3_eval(N, WS, WL, 0, 0, 32'h80) != 32'he0)  // np_classic.h: f(0,0,0.5) = -0.5
            $fatal(1, "dpi_classic3_tb: the bit-exact model's known answer is wrong");
        repeat (3) @(posedge clk);
        rst = 1'b0;
    end

    always @(posedge clk) if (!rst) begin
        cycles++;
        // The cycle model sees this cycle's port inputs, as the RTL does.
        np_dpi_pipe_eval(pm, int'(in_valid), int'(x), int'(y), int'(z), int'(out_ready), m_in_ready,
                         m_out_valid, m_f, m_dx, m_dy, m_dz);
        if (m_in_ready != int'(in_ready) || m_out_valid != int'(out_valid) ||
            (out_valid && m_f != int'(f))) begin
            lock_errors++;
            if (lock_errors <= 10)
                $display("cycle %0d: rtl in_ready %0d out_valid %0d f %h | cycle model %0d %0d %h", cycles,
                         in_ready, out_valid, f, m_in_ready, m_out_valid, m_f[N-1:0]);
        end
        np_dpi_pipe_clock(pm);
        if (in_valid && in_ready) begin
            expect_q.push_back(np_dpi_classic3_eval(N, WS, WL, int'(x), int'(y), int'(z)));
            n_in++;
        end
        if (out_valid && out_ready) begin
            want = expect_q.pop_front();
            if (want != int'(f)) begin
                errors++;
                if (errors <= 10) $display("transaction %0d: got %h expected %h", n_out, f, want[N-1:0]);
            end
            n_out++;
        end
        if (!in_valid || in_ready) begin
            in_valid <= n_in < ntx && $urandom_range(3) != 0;
            x <= 16'($urandom);
            y <= 16'($urandom);
            z <= 16'($urandom);
        end
        out_ready <= $urandom_range(3) != 0;
        if (n_out == ntx) begin
            np_dpi_pipe_free(pm);
            if (errors != 0 || lock_errors != 0)
                $fatal(1, "dpi_classic3_tb: %0d transactions: %0d scoreboard errors, %0d lock-step mismatches",
                       n_out, errors, lock_errors);
            $display("dpi_classic3_tb: %0d transactions in %0d cycles: 0 scoreboard errors (bit-exact model), 0 lock-step mismatches (cycle model)",
                     n_out, cycles);
            $finish;
        end
        if (cycles > 100 * ntx + 1000) $fatal(1, "dpi_classic3_tb: stuck after %0d transactions", n_out);
    end
endmodule
