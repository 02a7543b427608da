// SPDX-License-Identifier: MIT
// np_tex_quad.vh - what every span texturing unit computes from the begun
// descriptor (np_texel.v, np_fdiff.v): `include it inside the module body,
// after np_span_seq's bg_pay (s, t, r s48 Q15.32 at [48 a +: 48], ds, dt, dr
// s41 Q8.32 at [144 + 41 a +: 41]) and with the port k_reg (np_span_ports.vh).
//   sv[a], dsv[a]     s, ds of axis a sign-extended to 128 bits (the C model's
//                     np_s128, modulo 2^128)
//   kx(i)             k[i] s48 Q23.24 sign-extended to 128 bits
//   q0_w, q1_w, q2_w  np_tex_quadric_exact: q, dq, d2q Q.88 modulo 2^128, with
//                     M_q = [[A B C] [B E F] [C F H]], b = (D, G, I)
    wire [127:0] sv[0:2], dsv[0:2];
    genvar ax;
    generate
        for (ax = 0; ax < 3; ax = ax + 1) begin : g_desc
            wire [47:0] s48 = bg_pay[48*ax +: 48];
            wire [40:0] d41 = bg_pay[144 + 41*ax +: 41];
            assign sv[ax] = {{80{s48[47]}}, s48};
            assign dsv[ax] = {{87{d41[40]}}, d41};
        end
    endgenerate
    function [127:0] kx;
        input integer ki;
        begin
            kx = {{80{k_reg[48*ki+47]}}, k_reg[48*ki +: 48]};
        end
    endfunction
    wire [127:0] mq00 = kx(0), mq01 = kx(1), mq02 = kx(2), mq11 = kx(4), mq12 = kx(5), mq22 = kx(7);
    wire [127:0] bq0 = kx(3), bq1 = kx(6), bq2 = kx(8), kj = kx(9);
    wire [127:0] ms0 = mq00 * sv[0] + mq01 * sv[1] + mq02 * sv[2];
    wire [127:0] ms1 = mq01 * sv[0] + mq11 * sv[1] + mq12 * sv[2];
    wire [127:0] ms2 = mq02 * sv[0] + mq12 * sv[1] + mq22 * sv[2];
    wire [127:0] mds0 = mq00 * dsv[0] + mq01 * dsv[1] + mq02 * dsv[2];
    wire [127:0] mds1 = mq01 * dsv[0] + mq11 * dsv[1] + mq12 * dsv[2];
    wire [127:0] mds2 = mq02 * dsv[0] + mq12 * dsv[1] + mq22 * dsv[2];
    wire [127:0] sms = sv[0] * ms0 + sv[1] * ms1 + sv[2] * ms2;            // Q.88
    wire [127:0] smds = sv[0] * mds0 + sv[1] * mds1 + sv[2] * mds2;        // Q.88
    wire [127:0] dsmds = dsv[0] * mds0 + dsv[1] * mds1 + dsv[2] * mds2;    // Q.88
    wire [127:0] bs = bq0 * sv[0] + bq1 * sv[1] + bq2 * sv[2];             // Q.56
    wire [127:0] bds = bq0 * dsv[0] + bq1 * dsv[1] + bq2 * dsv[2];         // Q.56
    wire [127:0] q0_w = sms + (bs << 33) + (kj << 64);
    wire [127:0] q1_w = (smds << 1) + dsmds + (bds << 33);
    wire [127:0] q2_w = dsmds << 1;
