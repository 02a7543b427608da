// SPDX-License-Identifier: MIT
// np_board_led_hold - on for 2^BITS clocks after the last clock trig was high.
module np_board_led_hold #(parameter integer BITS = 18) (
    input wire clk,
    input wire rst,
    input wire trig,
    output wire on
);
    reg [BITS:0] left;
    always @(posedge clk)
        if (rst)
            left <= 0;
        else if (trig)
            left <= {1'b1, {BITS{1'b0}}};
        else if (left != 0)
            left <= left - 1'b1;
    assign on = left != 0;
endmodule
