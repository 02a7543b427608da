// SPDX-License-Identifier: MIT
// Option of every unit's pipe (np_pipe.h, docs/rtl.md); with ON = 0 it is wires.
// np_pipe_skid - a two-entry output buffer (main + skid register) whose
// s_ready is a register: it cuts the combinational path from m_ready back
// into the pipe (and so from out_ready to in_ready).
//   latency + 1 clock; s_ready = !skid_valid, a flip-flop; full throughput
//   (one transfer per clock when m_ready stays high); when m_ready drops
//   the transfer already accepted lands in the skid register.
module np_pipe_skid #(
    parameter integer W = 8,
    parameter integer ON = 1
) (
    input wire clk,
    input wire rst,
    input wire s_valid,
    output wire s_ready,
    input wire [W-1:0] s_data,
    output wire m_valid,
    input wire m_ready,
    output wire [W-1:0] m_data
);
    generate
        if (ON != 0) begin : g_on
            reg mv, kv;
            reg [W-1:0] md, kd;
            assign s_ready = !kv;
            assign m_valid = mv;
            assign m_data = md;
            always @(posedge clk) begin
                if (rst) begin
                    mv <= 1'b0;
                    kv <= 1'b0;
                end else if (!mv || m_ready) begin
                    // the main register empties or moves on: refill it, from
                    // the skid register first (s_ready is 0 then)
                    if (kv) begin
                        md <= kd;
                        kv <= 1'b0;
                    end else begin
                        mv <= s_valid;
                        if (s_valid) md <= s_data;
                    end
                end else if (s_valid && !kv) begin
                    kd <= s_data;  // stalled with the main register full
                    kv <= 1'b1;
                end
            end
        end else begin : g_off
            assign s_ready = m_ready;
            assign m_valid = s_valid;
            assign m_data = s_data;
            wire unused = &{1'b0, clk, rst};
        end
    endgenerate
endmodule
