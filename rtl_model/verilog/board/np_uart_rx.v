// SPDX-License-Identifier: MIT
// np_uart_rx - the board's UART receiver from the FT2232H's channel (docs/board.md): 8N1,
// least significant bit first, line idle high.
//
// Parameters:
//   CLKS_PER_BIT  clocks per bit (the clock over the baud rate); >= 4
// Ports (u: unsigned, width in bits):
//   clk, rst      rst synchronous, active high: back to waiting for a start bit
//   rxd           u1: the line, asynchronous: two flip-flops bring it into clk's domain
//   valid, data   u1, u8: a byte received, for one clock (no back-pressure: a UART has none;
//                 the protocol engine behind takes a byte every clock it is offered one)
//   frame_err     u1: for one clock, a byte whose stop bit was low (dropped, not in valid)
// A start is a falling edge after the line was high; each bit is sampled once, in the middle
// of its bit time (CLKS_PER_BIT / 2 clocks after the start's edge, then every CLKS_PER_BIT),
// so the sender's bit time may differ from CLKS_PER_BIT by up to about 1 / (2 * 10) over a byte
// less one clock of the sampling uncertainty. A start bit that is high again at its middle is
// a glitch: the receiver goes back to waiting. After a low stop bit (a framing error, or a
// break) it waits for the line to be high before it looks for a start again.
module np_uart_rx #(
    parameter integer CLKS_PER_BIT = 4
) (
    input wire clk,
    input wire rst,
    input wire rxd,
    output reg valid,
    output reg [7:0] data,
    output reg frame_err
);
    localparam integer CW = $clog2(CLKS_PER_BIT + 1);
    localparam integer LASTI = CLKS_PER_BIT - 1, HALFI = CLKS_PER_BIT / 2 - 1;
    localparam [CW-1:0] LAST = LASTI[CW-1:0];
    localparam [CW-1:0] HALF = HALFI[CW-1:0];
    reg [1:0] sync;      // the line through two flip-flops (sync[1] is used)
    reg [3:0] bit_i;     // u4: 0 waiting; 1 start bit; 2..9 data bits 0..7; 10 stop bit; 11 after a
                         // low stop bit, waiting for the line to be high again
    reg [CW-1:0] cnt;    // clocks to the next sample, minus 1
    reg [7:0] sh;        // the data bits so far, shifted in from bit 7

    always @(posedge clk) begin
        valid <= 1'b0;
        frame_err <= 1'b0;
        if (rst) begin
            sync <= 2'b11;
            bit_i <= 4'd0;
            cnt <= {CW{1'b0}};
            sh <= 8'd0;
            data <= 8'd0;
        end else begin
            sync <= {sync[0], rxd};
            if (bit_i == 4'd11) begin
                if (sync[1])
                    bit_i <= 4'd0;
            end else if (bit_i == 4'd0) begin
                if (!sync[1]) begin // a start bit's edge (the line was high before it)
                    bit_i <= 4'd1;
                    cnt <= HALF;
                end
            end else if (cnt != {CW{1'b0}}) begin
                cnt <= cnt - 1'b1;
            end else begin
                cnt <= LAST;
                if (bit_i == 4'd1) begin
                    bit_i <= sync[1] ? 4'd0 : 4'd2; // high at its middle: a glitch
                end else if (bit_i != 4'd10) begin
                    sh <= {sync[1], sh[7:1]};
                    bit_i <= bit_i + 4'd1;
                end else begin
                    if (sync[1]) begin
                        valid <= 1'b1;
`ifdef NP_FAULT_UART_RX
                        data <= {sh[6:0], sh[7]}; // fault copy: the byte rotated
`else
                        data <= sh;
`endif
                        bit_i <= 4'd0;
                    end else begin
                        frame_err <= 1'b1;
                        bit_i <= 4'd11;
                    end
                end
            end
        end
    end
endmodule
