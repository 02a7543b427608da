// SPDX-License-Identifier: MIT
// np_pipe_opts - the two options of a noise unit's pipe around its core
// (np_pipe.h, docs/rtl.md; simplex3, aacount, hatch, wave: classic3, simplexn
// and classicn place the two directly): the input register np_pipe_in_reg.v (IN_REG) in
// front of the core's first bank and the output skid buffer np_pipe_skid.v
// (OUT_SKID) behind its last; with both 0 it is wires (the unit is exactly
// np_pipe). The core's side is np_pipe_ctrl.v's handshake.
// Parameters: IW, OW the input and output bundles' widths; IN_REG, OUT_SKID
// the units' configuration keys in_reg, out_skid (0 or 1).
// Ports (valid/ready pairs: a transfer at an edge where both are 1): np_pipe_ports.vh's, then
//   in_data [IW], out_data [OW]               the unit's inputs and outputs (with in_valid ... out_ready)
//   core_in_valid, core_in_ready, core_in_data [IW]    into the core's bank 0
//   core_out_valid, core_out_ready, core_out_data [OW] out of the core's last bank
module np_pipe_opts #(
    parameter integer IW = 8,
    parameter integer OW = 8,
    parameter integer IN_REG = 0,
    parameter integer OUT_SKID = 0
) (
`include "np_pipe_ports.vh"
    input wire [IW-1:0] in_data,
    output wire [OW-1:0] out_data,
    output wire core_in_valid,
    input wire core_in_ready,
    output wire [IW-1:0] core_in_data,
    input wire core_out_valid,
    output wire core_out_ready,
    input wire [OW-1:0] core_out_data
);
    np_pipe_in_reg #(.W(IW), .ON(IN_REG)) u_in (
        .clk(clk), .rst(rst),
        .s_valid(in_valid), .s_ready(in_ready), .s_data(in_data),
        .m_valid(core_in_valid), .m_ready(core_in_ready), .m_data(core_in_data));
    np_pipe_skid #(.W(OW), .ON(OUT_SKID)) u_out (
        .clk(clk), .rst(rst),
        .s_valid(core_out_valid), .s_ready(core_out_ready), .s_data(core_out_data),
        .m_valid(out_valid), .m_ready(out_ready), .m_data(out_data));
endmodule
