// SPDX-License-Identifier: MIT
// np_crc32 - the board's CRC-32 (docs/usb-protocol.md, "CRC"): CRC-32/ISO-HDLC as in
// Ethernet, zlib and PNG (polynomial 0x04C11DB7 bit-reflected, 0xEDB88320; initial value
// 0xFFFFFFFF; final XOR 0xFFFFFFFF), one byte a clock, the same values as the host's
// np_crc32 (src/journal/crc32.c). The CRC of "123456789" is 0xCBF43926; of no bytes, 0.
//
// Ports (u: unsigned, width in bits):
//   clk       the clock; everything changes at its rising edge
//   rst       u1, synchronous, active high: the state to 0xFFFFFFFF (as init)
//   init      u1: start a CRC (the state to 0xFFFFFFFF); wins over en on the same edge
//   en        u1: fold byte d into the state at this edge
//   d         u8: the byte, least significant bit first on the wire (the reflected CRC)
//   crc       u32: the CRC of the bytes folded since the last init (the state XOR
//             0xFFFFFFFF), combinational from the state: valid the clock after the last en
// The state register s (u32) holds the reflected remainder; one byte is eight shift-and-XOR
// steps unrolled into one clock (a 32-bit XOR network, no table).
module np_crc32 (
    input wire clk,
    input wire rst,
    input wire init,
    input wire en,
    input wire [7:0] d,
    output wire [31:0] crc
);
`ifdef NP_FAULT_CRC
    localparam [31:0] POLY = 32'hEDB88321; // fault copy: one polynomial bit wrong
`else
    localparam [31:0] POLY = 32'hEDB88320;
`endif
    reg [31:0] s;

    // One byte: x = state ^ byte, then eight steps of x = x[0] ? x >> 1 ^ POLY : x >> 1.
    function [31:0] step;
        input [31:0] c;
        input [7:0] b;
        integer i;
        reg [31:0] x;
        begin
            x = c ^ {24'd0, b};
            for (i = 0; i < 8; i = i + 1)
                x = x[0] ? ((x >> 1) ^ POLY) : (x >> 1);
            step = x;
        end
    endfunction

    always @(posedge clk)
        if (rst || init)
            s <= 32'hFFFFFFFF;
        else if (en)
            s <= step(s, d);

    assign crc = ~s;
endmodule
