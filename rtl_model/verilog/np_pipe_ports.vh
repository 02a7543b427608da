// SPDX-License-Identifier: MIT
// np_pipe_ports.vh - the ports of np_pipe's handshake that every noise unit's
// pipe has (np_pipe.h, docs/rtl.md): `include it first between the parentheses
// of the module's ANSI port list; the unit's data ports follow it. Included by
// np_pipe_opts.v, simplex3, aacount, hatch and wave (classic3, simplexn and
// classicn declare the same ports themselves; texel and fdiff take them from
// np_span_ports.vh).
//   clk, rst                 the clock; synchronous reset, active high (every valid bit to 0)
//   in_valid, in_ready       a transaction's inputs are taken at an edge where both are 1
//   out_valid, out_ready     a result is delivered at an edge where both are 1
    input wire clk,
    input wire rst,
    input wire in_valid,
    output wire in_ready,
    output wire out_valid,
    input wire out_ready,
