// SPDX-License-Identifier: MIT
// np_hash.vh - the lattice hash and the gradient decode of np_hash.h, shared by
// np_classic3.v and np_simplex3.v. Verilog-2005 functions: `include this file
// inside a module body (tools need -I rtl_model/verilog; Yosys also finds it
// beside the including file).
//
//   pat(idx)          the seed's eight 6-bit bit patterns (np_hash_bit_patterns)
//   hash6(i, j, k)    np_hash6: u6 gradient index of lattice point (i, j, k), each u8;
//                     eight pattern lookups summed mod 64
//   grad_fields(h)    np_grad_decode's fields, packed {use_r, use_q, neg_r,
//                     neg_q, neg_p, ar[1:0], aq[1:0], ap[1:0]} (11 bits): p, q
//                     and r take axes ap, aq, ar (0 = x, 1 = y, 2 = z, distinct),
//                     each negated when its neg bit is 1; the gradient is
//                     p + (use_q ? q : 0) + (use_r ? r : 0), so two or three
//                     axes are non-zero.

function [5:0] pat;
    input [2:0] idx;
    begin
        case (idx)
            3'd0: pat = 6'h15; 3'd1: pat = 6'h38; 3'd2: pat = 6'h32; 3'd3: pat = 6'h2c;
            3'd4: pat = 6'h0d; 3'd5: pat = 6'h13; 3'd6: pat = 6'h07; default: pat = 6'h2a;
        endcase
    end
endfunction

function [5:0] hash6;
    input [7:0] i, j, k;
    begin
        hash6 = pat({i[0], j[0], k[0]}) + pat({j[1], k[1], i[1]}) + pat({k[2], i[2], j[2]})
              + pat({i[3], j[3], k[3]}) + pat({j[4], k[4], i[4]}) + pat({k[5], i[5], j[5]})
              + pat({i[6], j[6], k[6]}) + pat({j[7], k[7], i[7]});
    end
endfunction

function [10:0] grad_fields;
    input [5:0] h;
    reg [1:0] b;
    begin
        b = h[1:0];
        grad_fields[1:0] = b == 2'd1 ? 2'd0 : b == 2'd2 ? 2'd1 : 2'd2;  // ap
        grad_fields[3:2] = b == 2'd1 ? 2'd1 : b == 2'd2 ? 2'd2 : 2'd0;  // aq
        grad_fields[5:4] = b == 2'd1 ? 2'd2 : b == 2'd2 ? 2'd0 : 2'd1;  // ar
        grad_fields[6] = h[5] == h[3];                                   // neg_p
        grad_fields[7] = h[5] == h[4];                                   // neg_q
        grad_fields[8] = h[5] != (h[4] ^ h[3]);                          // neg_r
        grad_fields[9] = b == 2'd0 || !h[2];                             // use_q
        grad_fields[10] = b == 2'd0 || h[2];                             // use_r
    end
endfunction
