// SPDX-License-Identifier: MIT
// np_hashn.vh - the n-D lattice hash and the n-D gradient decode of
// rtl_model/np_hashn.h (docs/noise-nd.md, "The n-D hash", "The n-D
// gradient"), shared by np_simplexn.v and np_classicn.v. Verilog-2005
// functions: `include this file inside a module body (tools need
// -I rtl_model/verilog). It includes np_hash.vh (pat, grad_fields): the
// seed's table T is one definition for every n, and n = 3's gradient IS
// np_grad_decode's.
//
//   hashn(n, c)   np_hashn_stream: u6 index of the lattice point c, packed
//                 c[8a +: 8] = coordinate a (u8), a = 0 .. n-1 (bits above
//                 8n ignored). Stream position m = n B + r holds bit B of
//                 coordinate (B + r) mod n; lookup l reads stream bits 3l,
//                 3l+1, 3l+2 as the index 4 s[3l] + 2 s[3l+1] + s[3l+2] of
//                 T (positions past 8n read 0); h = the sum mod 64 of the
//                 ceil(8n/3) lookups. n = 3: hash6 exactly (ndim.hash3_is_seed).
//                 n is a constant at every call: the loops and the modulo
//                 are elaboration-time wiring, the circuit is ceil(8n/3)
//                 lookups 3 -> 6 and a six-bit adder tree.
//   gradn(n, h)   np_gradn_decode: the coefficients in {-1, 0, 1}, 2 bits
//                 per axis at [2a +: 2] (01 = +1, 11 = -1, 00 = 0), axis a
//                 = input field a (x, y, z, w, v); a sign bit of 1 gives -1.
//                 n = 2: h[2] = 0 an axis (h[0] which, h[1] its sign),
//                 h[2] = 1 the diagonal with signs h[0], h[1]; n = 3:
//                 grad_fields (Appendix B); n = 4: axis 2 h[1] + h[0] is 0,
//                 the other three take signs h[2], h[3], h[4] in increasing
//                 axis order; n = 5: sign of axis a = h[a].
`include "np_hash.vh"

function [5:0] hashn;
    input integer n;
    input [39:0] c;
    integer l, j, m, plane, r;
    reg [2:0] idx;
    begin
        hashn = 6'd0;
        for (l = 0; l < 14; l = l + 1) begin
            if (l < (8 * n + 2) / 3) begin
                for (j = 0; j < 3; j = j + 1) begin
                    m = 3 * l + j;
                    plane = m / n;
                    r = m % n;
                    idx[2-j] = m < 8 * n ? c[8 * ((plane + r) % n) + (plane % 8)] : 1'b0;
                end
                hashn = hashn + pat(idx);
            end
        end
    end
endfunction

function [9:0] gradn;
    input integer n;
    input [5:0] h;
    reg [10:0] gf;
    integer a;
    begin
        gradn = 10'd0;
        case (n)
            2: begin
                if (!h[2]) gradn[2*h[0]+:2] = h[1] ? 2'b11 : 2'b01;
                else begin
                    gradn[1:0] = h[0] ? 2'b11 : 2'b01;
                    gradn[3:2] = h[1] ? 2'b11 : 2'b01;
                end
            end
            3: begin
                gf = grad_fields(h);  // p, q and r are distinct axes
                gradn[2*gf[1:0]+:2] = gf[6] ? 2'b11 : 2'b01;
                if (gf[9]) gradn[2*gf[3:2]+:2] = gf[7] ? 2'b11 : 2'b01;
                if (gf[10]) gradn[2*gf[5:4]+:2] = gf[8] ? 2'b11 : 2'b01;
            end
            4: begin
                // axis a < 2 h[1] + h[0] takes sign bit 2 + a, an axis above it 1 + a
                for (a = 0; a < 4; a = a + 1)
                    if (a != {30'd0, h[1:0]})
                        gradn[2*a+:2] = h[a < {30'd0, h[1:0]} ? 2 + a : 1 + a] ? 2'b11 : 2'b01;
            end
            default: begin
                for (a = 0; a < 5; a = a + 1) gradn[2*a+:2] = h[a] ? 2'b11 : 2'b01;
            end
        endcase
    end
endfunction
