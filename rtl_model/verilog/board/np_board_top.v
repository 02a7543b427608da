// SPDX-License-Identifier: MIT
// np_board_top - the whole board's gateware (docs/board.md): the FT2232H's UART channel in
// (np_uart_rx), the protocol engine with classic3 behind it (np_board_core), the UART out
// (np_uart_tx). The byte streams of docs/usb-protocol.md travel on the UART; the FT2232H
// bridges them to its USB bulk endpoints.
//
// Parameters:
//   CLKS_PER_BIT  the UART's bit time in clocks (4: 3 Mbaud at 12 MHz)
//   MAX_PAYLOAD, WINDOW, RXB_AW, CLOCK_HZ   np_board_core's
//   ROOM_LOW      rts_n rises when fewer than ROOM_LOW bytes of room are left in the OUT buffer
// Ports (u: unsigned, width in bits):
//   clk, rst      rst synchronous, active high
//   rxd           u1: the UART line from the FT2232H (OUT bytes)
//   txd           u1: the UART line to the FT2232H (IN bytes)
//   rts_n         u1: low while the board can take more OUT bytes (to the FT2232H's CTS#: it
//                 stops sending within a few bytes, which ROOM_LOW covers)
//   overflow      u1, sticky until rst: a byte arrived with no room for it (lost). Never
//                 happens while the sender honours rts_n; the board's LED
//   frame_err     u1: for one clock, a UART byte with a low stop bit (dropped by np_uart_rx)
//   busy          u1: the engine is in a frame
// A UART has no valid/ready: np_uart_rx offers each byte for one clock. The engine takes it
// whenever its buffer has room, which rts_n keeps so.
module np_board_top #(
    parameter integer CLKS_PER_BIT = 4,
    parameter integer MAX_PAYLOAD = 1024,
    parameter integer WINDOW = 2,
    parameter integer RXB_AW = 11,
    parameter integer ROOM_LOW = 16,
    parameter [31:0] CLOCK_HZ = 12000000
) (
    input wire clk,
    input wire rst,
    input wire rxd,
    output wire txd,
    output wire rts_n,
    output reg overflow,
    output wire frame_err,
    output wire busy
);
    wire rx_valid;
    wire [7:0] rx_data;
    wire in_ready, in_room_low;
    wire out_valid, out_ready;
    wire [7:0] out_data;

    np_uart_rx #(.CLKS_PER_BIT(CLKS_PER_BIT)) u_rx(
        .clk(clk), .rst(rst), .rxd(rxd), .valid(rx_valid), .data(rx_data), .frame_err(frame_err));

    /* verilator lint_off PINCONNECTEMPTY */
    np_board_core #(.MAX_PAYLOAD(MAX_PAYLOAD), .WINDOW(WINDOW), .RXB_AW(RXB_AW), .ROOM_LOW(ROOM_LOW),
                    .CLOCK_HZ(CLOCK_HZ)) u_core(
        .clk(clk), .rst(rst),
        .in_valid(rx_valid), .in_ready(in_ready), .in_data(rx_data),
        .out_valid(out_valid), .out_ready(out_ready), .out_data(out_data),
        .out_last(),  // a UART has no packets: the FT2232H's latency timer ends them
        .in_room_low(in_room_low), .busy(busy));
    /* verilator lint_on PINCONNECTEMPTY */

    np_uart_tx #(.CLKS_PER_BIT(CLKS_PER_BIT)) u_tx(
        .clk(clk), .rst(rst), .valid(out_valid), .data(out_data), .ready(out_ready), .txd(txd));

    assign rts_n = in_room_low;
    always @(posedge clk)
        if (rst)
            overflow <= 1'b0;
        else if (rx_valid && !in_ready)
            overflow <= 1'b1;
endmodule
