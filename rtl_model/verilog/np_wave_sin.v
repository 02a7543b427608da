// SPDX-License-Identifier: MIT
// np_wave_sin - sin(2 pi th / 2^32) of the wave unit, bit for bit
// np_wave_sin (rtl_model/np_wave.c; docs/wave.md "sin/cos: a quarter-wave
// ROM with linear interpolation"). Combinational; cos th = sin(th + 2^30)
// (the caller adds). L = ROM_LOG2 (6..10), IFRAC = 16 (NP_WAVE_IFRAC).
//   q  = th[31:30] (quadrant), x = th[29:0]
//   x' = x in quadrants 0 and 2, 2^30 - x in 1 and 3 (exact: u31, 0 .. 2^30)
//   a  = x' >> (30 - L)           u(L+1), 0 .. 2^L (2^L only for x' = 2^30)
//   f  = x'[29-L -: 16]           u16, the bits below dropped (truncated)
//   D  = R[a + 1] - R[a]          u12 (0 .. 3217 at L = 6: the ROM rises
//                                 over a quarter wave and each step is at
//                                 most 2^17 2 pi / 2^(L+2) < 2^12; at
//                                 a = 2^L, f = 0 and D is not used)
//   v  = R[a] + round(D f / 2^16) u18 Q1.17 (round half up: + 2^15, >> 16)
//   s  = -v in quadrants 2 and 3  s19 Q1.17
module np_wave_sin #(
    parameter integer ROM_LOG2 = 8
) (
    input wire [31:0] th,       // u32 Q0.32 turns
    output wire [18:0] s        // s19 Q1.17
);
    localparam integer L = ROM_LOG2;
    wire [30:0] x0 = {1'b0, th[29:0]};
`ifdef NP_FAULT_MIRROR
    // fault: the one's complement mirror 2^30 - 1 - x (docs/wave.md's misreading)
    wire [30:0] xm = th[30] ? (31'h3fff_ffff - x0) : x0;
`else
    wire [30:0] xm = th[30] ? (31'h4000_0000 - x0) : x0;  // the mirror, exact
`endif
    wire [L:0] a = xm[30:30-L];
    wire [15:0] f = xm[29-L-:16];
    wire [17:0] r0, r1;
    np_wave_rom #(.ROM_LOG2(L)) u_r0 (.a(a), .r(r0));
    np_wave_rom #(.ROM_LOG2(L)) u_r1 (.a(a + {{L{1'b0}}, 1'b1}), .r(r1));
    wire [17:0] dd = r1 - r0;
    wire [11:0] d = dd[11:0];
    wire [27:0] df = d * f;
    wire [12:0] di = df[27:16] + {11'd0, df[15]};  // round(D f / 2^16), <= D
    wire [17:0] v = r0 + {5'd0, di};
    assign s = th[31] ? -{1'b0, v} : {1'b0, v};
    // The bits of x' below f are dropped (truncated, not rounded into f), and
    // bits 17..12 of R[a + 1] - R[a] are 0 wherever f is not (above); df[14:0]
    // are below the rounding's half.
    wire unused = &{1'b0, xm[13-L:0], dd[17:12], df[14:0]};
endmodule
