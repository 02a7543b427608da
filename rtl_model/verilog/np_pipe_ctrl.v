// SPDX-License-Identifier: MIT
// The handshake of a unit's pipe of banks (np_pipe.h, docs/rtl.md): bank k
// loads when it is empty or its content moves on, en[k] = !v[k] | en[k+1],
// en[NB-1] = !v[NB-1] | out_ready; a bank's valid bit follows its predecessor's
// when it loads and holds otherwise. The valid bits stay the unit's own
// register (the synthesis report selects them by name, report_synth.c); this
// block is the logic around them, combinational only. Instantiated by
// simplex3, aacount, hatch, wave, texel and fdiff; classic3 (whose L stage
// has its own), simplexn and classicn write the same logic out themselves.
//
// np_pipe_ctrl - ports (NB banks, bank 0 first):
//   v          in,  NB bits: the unit's valid bits, v[k] = bank k holds a transaction
//   in_valid   in,  1 bit:   a transaction waits in front of bank 0
//   out_ready  in,  1 bit:   the consumer takes bank NB-1's content at this edge
//   en         out, NB bits: bank k loads at this edge
//   v_next     out, NB bits: the valid bits after this edge (reset not included)
//   in_ready   out, 1 bit:   en[0]
//   out_valid  out, 1 bit:   v[NB-1]
// `define NP_FAULT_STALL forces en[STALL_BANK] (a handshake fault: that bank
// overwrites its content when its successor stalls; the unit names the bank).
module np_pipe_ctrl #(
    parameter integer NB = 2,
    parameter integer STALL_BANK = 1
) (
    input wire [NB-1:0] v,
    input wire in_valid,
    input wire out_ready,
    output reg [NB-1:0] en,
    output wire [NB-1:0] v_next,
    output wire in_ready,
    output wire out_valid
);
`ifdef NP_FAULT_STALL
    localparam integer FAULT = 1;
`else
    localparam integer FAULT = 0;
`endif
    integer e;
    always @(*) begin
        en[NB-1] = !v[NB-1] || out_ready;
        for (e = NB - 2; e >= 0; e = e - 1) en[e] = !v[e] || en[e+1];
        if (FAULT != 0) en[STALL_BANK] = 1'b1;
    end
    assign in_ready = en[0];
    assign out_valid = v[NB-1];
    assign v_next = (v & ~en) | ({v[NB-2:0], in_valid} & en);
endmodule
