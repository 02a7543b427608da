// SPDX-License-Identifier: MIT
// np_tex_front.vh - an octave's registers and its span front end, as every span
// texturing unit computes them (np_texel.v, np_fdiff.v): `include it first in
// the body of the unit's generate loop over the octaves (genvars o, ab, a;
// after np_tex_quad.vh's sv, dsv; the unit declares offdiag[N_OCT]).
//   mv[3 a + b]   m[a][b] of octave o sign-extended to 128 bits (s24 Q7.16)
//   offdiag[o]    1 when the octave's M has a non-zero element off its diagonal
//   amp           a'_o s32 Q17.14
//   u0[a], du0[a] the front end (np_tex_octave_span): u0 = round(M s + o) u40
//                 Q8.32 (mod 256), du = round(M ds) s40 Q7.32, each exact at 48
//                 fraction bits and rounded once, half up (np_round_wrap128)
    wire [127:0] mv[0:8];
    for (ab = 0; ab < 9; ab = ab + 1) begin : g_m
        wire [23:0] m24 = m_reg[24*(9*o + ab) +: 24];
        assign mv[ab] = {{104{m24[23]}}, m24};
    end
    assign offdiag[o] = m_reg[24*(9*o + 1) +: 24] != 24'd0 || m_reg[24*(9*o + 2) +: 24] != 24'd0 ||
                        m_reg[24*(9*o + 3) +: 24] != 24'd0 || m_reg[24*(9*o + 5) +: 24] != 24'd0 ||
                        m_reg[24*(9*o + 6) +: 24] != 24'd0 || m_reg[24*(9*o + 7) +: 24] != 24'd0;
    wire [31:0] amp = amp_reg[32*o +: 32];
    wire [39:0] u0[0:2], du0[0:2];
    for (a = 0; a < 3; a = a + 1) begin : g_front
        wire [47:0] o48 = o_reg[48*(3*o + a) +: 48];
        wire [127:0] uu = ({{80{o48[47]}}, o48} << 16) + mv[3*a] * sv[0] + mv[3*a+1] * sv[1] + mv[3*a+2] * sv[2];
        wire [127:0] dd = mv[3*a] * dsv[0] + mv[3*a+1] * dsv[1] + mv[3*a+2] * dsv[2];
        wire [127:0] u_rnd = (uu + (128'd1 << 15)) >> 16;
        wire [127:0] d_rnd = (dd + (128'd1 << 15)) >> 16;
        assign u0[a] = u_rnd[39:0];
        assign du0[a] = d_rnd[39:0];
    end
