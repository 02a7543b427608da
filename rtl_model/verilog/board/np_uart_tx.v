// SPDX-License-Identifier: MIT
// np_uart_tx - the board's UART transmitter toward the FT2232H's channel (docs/board.md):
// 8 data bits, least significant first, no parity, one stop bit (8N1); line idle high.
//
// Parameters:
//   CLKS_PER_BIT  clocks per bit (the clock over the baud rate: 12 MHz / 3 Mbaud = 4); >= 2
// Ports (u: unsigned, width in bits):
//   clk, rst      rst synchronous, active high: idle line, nothing in flight
//   valid, data   u1, u8: a byte to send; taken at an edge where valid & ready
//   ready         u1: the transmitter is idle (a byte can be taken)
//   txd           u1: the line (registered: no glitch)
// The start bit begins at the edge that takes the byte; the stop bit ends 10 * CLKS_PER_BIT
// clocks later, at the edge where ready rises again; the line then stays idle for at least one
// clock, so back-to-back bytes go out one every 10 * CLKS_PER_BIT + 1 clocks.
module np_uart_tx #(
    parameter integer CLKS_PER_BIT = 4
) (
    input wire clk,
    input wire rst,
    input wire valid,
    input wire [7:0] data,
    output wire ready,
    output reg txd
);
    localparam integer CW = CLKS_PER_BIT <= 2 ? 1 : $clog2(CLKS_PER_BIT);
    reg [8:0] sh;        // u9: stop bit, data[7:0]; bit 0 is the next bit out
    reg [3:0] bits;      // u4: bits still to send (0: idle)
    localparam integer LASTI = CLKS_PER_BIT - 1;
    localparam [CW-1:0] LAST = LASTI[CW-1:0];
    reg [CW-1:0] cnt;    // clocks left in the current bit, minus 1
    assign ready = bits == 4'd0;

    always @(posedge clk)
        if (rst) begin
            txd <= 1'b1;
            bits <= 4'd0;
            cnt <= {CW{1'b0}};
            sh <= 9'h1ff;
        end else if (bits == 4'd0) begin
            txd <= 1'b1;
            if (valid) begin
                sh <= {1'b1, data};
                bits <= 4'd10;
                cnt <= LAST;
                txd <= 1'b0; // the start bit
`ifdef NP_FAULT_UART_TX
                sh <= {1'b1, data[6:0], data[7]}; // fault copy: the byte rotated
`endif
            end
        end else if (cnt != {CW{1'b0}}) begin
            cnt <= cnt - 1'b1;
        end else begin
            cnt <= LAST;
            sh <= {1'b1, sh[8:1]};
            bits <= bits - 4'd1;
            txd <= bits == 4'd1 ? 1'b1 : sh[0];
        end
endmodule
