// SPDX-License-Identifier: MIT
// np_board_hx8k - np_board_top on the Lattice iCE40-HX8K breakout board (docs/board.md; pins in
// hx8k_breakout.pcf): the 12 MHz oscillator, FT2232H channel B's UART with CTS#, the 8 LEDs.
//
// The board has no reset button wired to a user pin: a power-on reset holds the gateware in
// reset for 2^RST_BITS clocks after configuration (about 5.5 ms at RST_BITS 16), long enough
// for the FT2232H's lines to settle.
// Ports (u: unsigned, width in bits):
//   clk12       u1: 12 MHz
//   uart_rxd    u1: from the FT2232H's TXD (OUT bytes from the host)
//   uart_txd    u1: to the FT2232H's RXD (IN bytes to the host)
//   uart_cts_n  u1: to the FT2232H's CTS#: low while the OUT buffer has room (np_board_top's rts_n)
//   led         u8: [0] heartbeat (about 0.7 Hz: the bitstream runs), [1] a frame in the engine
//               (stretched to about 22 ms, so one frame shows), [2] overflow (sticky: an OUT
//               byte was lost, the host ignored CTS#), [3] a UART framing error seen (sticky:
//               the baud rate is wrong, or the line broke), [4] OUT bytes flowing, [5] IN
//               bytes flowing (both stretched), [6] CTS# high (the board is holding the host
//               back), [7] in reset
module np_board_hx8k #(
    parameter integer RST_BITS = 16,
    parameter integer BEAT_BITS = 24,  // LED0 toggles every 2^(BEAT_BITS-1) clocks
    parameter integer HOLD_BITS = 18   // activity LEDs stay on 2^HOLD_BITS clocks
) (
    input wire clk12,
    input wire uart_rxd,
    output wire uart_txd,
    output wire uart_cts_n,
    output wire [7:0] led
);
    reg [RST_BITS:0] por = 0;
    wire rst = !por[RST_BITS];
    always @(posedge clk12)
        if (rst)
            por <= por + 1'b1;

    wire overflow, frame_err, busy;
    np_board_top u_top(
        .clk(clk12), .rst(rst), .rxd(uart_rxd), .txd(uart_txd), .rts_n(uart_cts_n),
        .overflow(overflow), .frame_err(frame_err), .busy(busy));

    reg [BEAT_BITS-1:0] beat = 0;
    always @(posedge clk12)
        beat <= beat + 1'b1;

    reg seen_frame_err;
    always @(posedge clk12)
        if (rst)
            seen_frame_err <= 1'b0;
        else if (frame_err)
            seen_frame_err <= 1'b1;

    // A start bit (the line low) is activity; a stretched copy of it lights the LED.
    wire busy_led, rx_led, tx_led;
    np_board_led_hold #(.BITS(HOLD_BITS)) u_busy(.clk(clk12), .rst(rst), .trig(busy), .on(busy_led));
    np_board_led_hold #(.BITS(HOLD_BITS)) u_rx(.clk(clk12), .rst(rst), .trig(!uart_rxd), .on(rx_led));
    np_board_led_hold #(.BITS(HOLD_BITS)) u_tx(.clk(clk12), .rst(rst), .trig(!uart_txd), .on(tx_led));

    assign led = {rst, uart_cts_n, tx_led, rx_led, seen_frame_err, overflow, busy_led, beat[BEAT_BITS-1]};
endmodule
