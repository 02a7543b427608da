// SPDX-License-Identifier: MIT
// Calibration circuits of the gate cost model (src/report/report_gates.c,
// docs/cost-model.md). test_report's case `cost_model_calibration` synthesises
// each with Yosys + ABC into NAND2/NOT and compares with the model.
module add16(input [15:0] a, b, output [15:0] y); assign y = a + b; endmodule
module add24(input [23:0] a, b, output [23:0] y); assign y = a + b; endmodule
module cmp16(input [15:0] a, b, output y); assign y = a < b; endmodule
module mux16(input [15:0] a, b, input s, output [15:0] y); assign y = s ? b : a; endmodule
module neg12(input signed [11:0] a, input s, output signed [11:0] y); assign y = s ? -a : a; endmodule
module mul8(input [7:0] a, b, output [15:0] y); assign y = a * b; endmodule
module mul13(input signed [12:0] a, input [12:0] b, output signed [25:0] y); assign y = a * $signed({1'b0, b}); endmodule
// Signed x signed (both two's complement: the sign rows of Baugh-Wooley cost more than an unsigned array).
module smul12x8(input signed [11:0] a, input signed [7:0] b, output signed [19:0] y); assign y = a * b; endmodule
module lut3x6(input [2:0] i, output reg [5:0] y);
  always @* case (i) 0: y = 6'h15; 1: y = 6'h38; 2: y = 6'h32; 3: y = 6'h2c;
                     4: y = 6'h0d; 5: y = 6'h13; 6: y = 6'h07; default: y = 6'h2a; endcase
endmodule
module dff16(input clk, input [15:0] d, output reg [15:0] q); always @(posedge clk) q <= d; endmodule
// A pipeline bank: flip-flops that hold under a stall (a load enable).
module dffe16(input clk, en, input [15:0] d, output reg [15:0] q); always @(posedge clk) if (en) q <= d; endmodule
// Adding a constant (an incrementer), comparing with a constant, squaring.
module inc16(input [15:0] a, output [15:0] y); assign y = a + 16'd1; endmodule
module cmpk16(input signed [15:0] a, output y); assign y = a > 16'sd1234; endmodule
module sqr8(input [7:0] a, output [15:0] y); assign y = a * a; endmodule
// The carry out of a sum whose sum bits are not read (simplex3's SK reads SX[18:8] and (683 nn)[19:11]).
module carry10(input [9:0] a, b, output y); wire [10:0] s = a + b; assign y = s[10]; endmodule
// The seed's whole table-free hash: 8 lookups and 7 six-bit additions.
module hash6(input [7:0] i, j, k, output [5:0] h);
  function [5:0] T(input [2:0] x);
    case (x) 0: T = 6'h15; 1: T = 6'h38; 2: T = 6'h32; 3: T = 6'h2c;
             4: T = 6'h0d; 5: T = 6'h13; 6: T = 6'h07; default: T = 6'h2a; endcase
  endfunction
  assign h = T({i[0],j[0],k[0]}) + T({j[1],k[1],i[1]}) + T({k[2],i[2],j[2]}) + T({i[3],j[3],k[3]})
           + T({j[4],k[4],i[4]}) + T({k[5],i[5],j[5]}) + T({i[6],j[6],k[6]}) + T({j[7],k[7],i[7]});
endmodule
