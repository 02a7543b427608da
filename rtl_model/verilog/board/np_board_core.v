// SPDX-License-Identifier: MIT
// np_board_core - the board without its link: the protocol engine (np_link_engine.v) with its
// one slot, classic3 in the configuration the board builds (out_bits=8 s_frac=12
// lerp_frac=11, LERP_SERIAL=1: the variant that leaves most of an iCE40-HX8K to the rest,
// docs/fpga.md), on byte streams. np_board_top.v puts the UART around it; the differential
// test (testbench/rtl/board_diff.cpp) drives it directly.
//
// Ports (u: unsigned, width in bits; valid/ready: a byte moves on a clock where both are high):
//   clk, rst             rst synchronous, active high
//   in_valid, in_ready, in_data u1 u1 u8      OUT bytes (host to board)
//   out_valid, out_ready, out_data u1 u1 u8   IN bytes (board to host)
//   out_last             u1: out_data ends a frame
//   in_room_low          u1: fewer than ROOM_LOW bytes of room in the OUT buffer (for a
//                        link without valid/ready, e.g. the UART's RTS)
//
// Records (docs/usb-protocol.md section 5): input 8 bytes, x y z u16 little-endian then two
// zero bytes (ignored); output 4 bytes, f s8 in byte 0, then three zero bytes.
module np_board_core #(
    parameter integer MAX_PAYLOAD = 1024,
    parameter integer WINDOW = 2,
    parameter integer RXB_AW = 11,
    parameter integer ROOM_LOW = 16,
    parameter [31:0] CLOCK_HZ = 12000000
) (
    input wire clk,
    input wire rst,
    input wire in_valid,
    output wire in_ready,
    input wire [7:0] in_data,
    output wire out_valid,
    input wire out_ready,
    output wire [7:0] out_data,
    output wire out_last,
    output wire in_room_low,
    output wire busy
);
    localparam integer OUT_BITS = 8;
    wire u_in_valid, u_in_ready, u_out_valid, u_out_ready;
    wire [63:0] u_in_rec;
    wire [31:0] u_out_rec;
    wire [OUT_BITS-1:0] f;

    np_link_engine #(
        .MAX_PAYLOAD(MAX_PAYLOAD), .WINDOW(WINDOW), .RXB_AW(RXB_AW), .IN_STRIDE(8), .OUT_STRIDE(4),
        .BOARD_ID("classic3 on iCE40-HX8K breakout"), .SLOT_UNIT("classic3"),
        .SLOT_CFG("out_bits=8 s_frac=12 lerp_frac=11"),
        .SLOT_LAYOUT(160'h00000000000000080000000000101010_04080103),
        .LATENCY(17), .CLOCK_HZ(CLOCK_HZ), .ROOM_LOW(ROOM_LOW)
    ) u_eng (
        .clk(clk), .rst(rst),
        .in_valid(in_valid), .in_ready(in_ready), .in_data(in_data),
        .out_valid(out_valid), .out_ready(out_ready), .out_data(out_data), .out_last(out_last),
        .in_room_low(in_room_low),
        .u_in_valid(u_in_valid), .u_in_ready(u_in_ready), .u_in_rec(u_in_rec),
        .u_out_valid(u_out_valid), .u_out_ready(u_out_ready), .u_out_rec(u_out_rec),
        .busy(busy)
    );

    /* verilator lint_off UNUSEDSIGNAL */
    wire [15:0] pad = u_in_rec[63:48];  // the record's padding: zero on the wire, not looked at
    /* verilator lint_on UNUSEDSIGNAL */
    np_classic3 #(.OUT_BITS(OUT_BITS), .S_FRAC(12), .LERP_FRAC(11), .LERP_SERIAL(1)) u_unit (
        .clk(clk), .rst(rst),
        .in_valid(u_in_valid), .in_ready(u_in_ready),
        .x(u_in_rec[15:0]), .y(u_in_rec[31:16]), .z(u_in_rec[47:32]),
        .out_valid(u_out_valid), .out_ready(u_out_ready), .f(f)
    );
    assign u_out_rec = {{(32 - OUT_BITS){1'b0}}, f};
endmodule
