// SPDX-License-Identifier: MIT
// Option of every unit's pipe (np_pipe.h, docs/rtl.md); with ON = 0 it is
// wires: the unit is exactly np_pipe (no extra latency).

// np_pipe_in_reg - one more bank in front of the unit's first stage, with the
// pipe's own rule: it loads when it is empty or its content moves on.
//   latency + 1 clock; s_ready = !v | m_ready: the ready chain is one bank
//   longer and still combinational (the input side gets a clean register
//   boundary for its data, not for its ready).
module np_pipe_in_reg #(
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
            reg v;
            reg [W-1:0] d;
            assign s_ready = !v || m_ready;
            assign m_valid = v;
            assign m_data = d;
            always @(posedge clk) begin
                if (rst) v <= 1'b0;
                else if (s_ready) v <= s_valid;
                if (s_ready && s_valid) d <= s_data;
            end
        end else begin : g_off
            assign s_ready = m_ready;
            assign m_valid = s_valid;
            assign m_data = s_data;
            wire unused = &{1'b0, clk, rst};
        end
    endgenerate
endmodule
