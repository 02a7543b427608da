// SPDX-License-Identifier: MIT
// np_span_ports.vh - the port list every span texturing unit shares (np_texel.v,
// np_fdiff.v): `include it between the parentheses of the module's ANSI port
// list; the unit declares the parameter N_OCT before it. Formats (np_tex_regs,
// np_span, np_tex_pixel; written by the host between frames and held constant
// while spans run, for the registers):
//   k_reg   [480]  k[i] s48 Q23.24 at [48 i +: 48], order A' B' C' D' E' F' G' H' I' J'
//   m_reg   [216 N_OCT]  octave o's m[a][b] s24 Q7.16 at [24 (9 o + 3 a + b) +: 24]
//   o_reg   [144 N_OCT]  o[a] s48 Q15.32 at [48 (3 o + a) +: 48]
//   amp_reg [32 N_OCT]   a'_o s32 Q17.14 at [32 o +: 32]
//   cmap    [6144] entry e, channel ch (0 r, 1 g, 2 b) u8 at [24 e + 8 ch +: 8]
//   cmap_n  u9 N, 2..256; cmap_rep 1: repeat (N a power of two), 0: clamp
// Span descriptor in (valid/ready, np_span_seq.v):
//   in_y, in_x0 u16; in_n u17 (0..65536); in_s, in_t, in_r s48 Q15.32;
//   in_ds, in_dt, in_dr s41 Q8.32
// Pixel out (valid/ready): px, py u16; cr, cg, cb u8.
    input wire clk,
    input wire rst,
    input wire [479:0] k_reg,
    input wire [216*N_OCT-1:0] m_reg,
    input wire [144*N_OCT-1:0] o_reg,
    input wire [32*N_OCT-1:0] amp_reg,
    input wire [6143:0] cmap,
    input wire [8:0] cmap_n,
    input wire cmap_rep,
    input wire in_valid,
    output wire in_ready,
    input wire [15:0] in_y,
    input wire [15:0] in_x0,
    input wire [16:0] in_n,
    input wire [47:0] in_s,
    input wire [47:0] in_t,
    input wire [47:0] in_r,
    input wire [40:0] in_ds,
    input wire [40:0] in_dt,
    input wire [40:0] in_dr,
    output wire out_valid,
    input wire out_ready,
    output wire [15:0] px,
    output wire [15:0] py,
    output wire [7:0] cr,
    output wire [7:0] cg,
    output wire [7:0] cb
