// SPDX-License-Identifier: MIT
// np_span_seq - reference RTL of the span sequencer that every span unit
// shares (rtl_model/np_span.h, np_span_sim: the cycle-accurate model). It
// reads span descriptors (valid/ready), keeps the span in the engine and a
// one-deep descriptor buffer, counts the set-up stall the engine asks for,
// and issues one pixel per clock into the engine's pipeline (valid/ready)
// unless the stall is running or the pipeline does not take it.
// Verilog-2005, synthesizable; Verilator -Wall clean.
//
// The engine (np_texel.v; later np_fdiff) is outside: this module tells it
// when a span begins (bg, with the descriptor bg_pay / bg_n), when a
// descriptor enters the buffer (pf, with in_pay / in_n: np_span_engine's
// prefetch) and when a pixel issues (adv: step to the next pixel), and takes
// back the set-up clocks begin and advance return (bg_stall, adv_stall:
// combinational in the same clock, as the C engine's return values).
//
// Parameters
//   PAY_W      bits of the descriptor's payload the engine reads (np_texel:
//              s, t, r s48 and ds, dt, dr s41: 267); opaque here
//   PREFETCH   1: the engine has a descriptor buffer (np_span_engine.prefetch
//              set; np_texel and np_fdiff); 0: a descriptor is read only
//              while the unit is idle
//   STALL_W    width of the stall counter and of bg_stall, adv_stall (16)
//
// Ports (np_span_port; formats as np_texture.h's span descriptor)
//   in_valid, in_ready        descriptor handshake; in_ready = PREFETCH ? !has_next : !busy
//   in_y, in_x0   u16         scanline, first pixel (they only tag the pixels)
//   in_n          u17         pixels, 0..65536 (0: an empty span, no work)
//   in_pay        PAY_W       the engine's fields
//   iss_valid, iss_ready      the current pixel into the engine's pipeline
//                             (iss_valid = busy && stall == 0; iss_ready =
//                             the pipeline's first bank loads, np_pipe)
//   iss_x, iss_y  u16         the pixel's position: x0 + k (mod 2^16), y
//   bg            1           a span begins in this clock (the engine loads bg_pay)
//   bg_pf         1           ... and it is the buffered one (prefetch was called for it)
//   bg_n          u17         its length; bg_pay PAY_W its fields
//   bg_stall      u(STALL_W)  engine: the set-up clocks before its first pixel
//   pf            1           a descriptor enters the buffer in this clock (in_n, in_pay)
//   adv           1           the current pixel issues (the engine steps its state)
//   adv_stall     u(STALL_W)  engine: the set-up clocks before the next pixel
//   busy          1           a span is in the engine
//
// Registers (np_span_sim's fields)
//   busy 1, k u17, n u17, y u16, x0 u16        the span in the engine (sp, k, busy)
//   has_next 1, nx_y, nx_x0 u16, nx_n u17, nx_pay   the descriptor buffer (next, has_next)
//   stall u(STALL_W)                           set-up clocks left before pixel k may issue
//
// One clock (np_span_sim_clock, in its order):
//   busy:  a descriptor accepted goes to the buffer (pf); then, if stall > 0
//          it counts down, else if the pixel issued: stall = adv_stall,
//          k + 1, and after the last pixel busy falls and the buffered span
//          (the one just accepted, too) begins in this clock (bg, bg_pf);
//   idle:  a descriptor accepted begins (bg, not prefetched); else a
//          buffered one begins (never reached: the buffer is only filled
//          while busy, and emptied in the clock busy falls).
// A begun span with n = 0 leaves the unit idle (busy = 0).
module np_span_seq #(
    parameter integer PAY_W = 267,
    parameter integer PREFETCH = 1,
    parameter integer STALL_W = 16
) (
    input wire clk,
    input wire rst,
    input wire in_valid,
    output wire in_ready,
    input wire [15:0] in_y,
    input wire [15:0] in_x0,
    input wire [16:0] in_n,
    input wire [PAY_W-1:0] in_pay,
    output wire iss_valid,
    input wire iss_ready,
    output wire [15:0] iss_x,
    output wire [15:0] iss_y,
    output wire bg,
    output wire bg_pf,
    output wire [16:0] bg_n,
    output wire [PAY_W-1:0] bg_pay,
    input wire [STALL_W-1:0] bg_stall,
    output wire pf,
    output wire adv,
    input wire [STALL_W-1:0] adv_stall,
    output wire busy
);
    reg r_busy, has_next;
    reg [16:0] k, n, nx_n;
    reg [15:0] y, x0, nx_y, nx_x0;
    reg [PAY_W-1:0] nx_pay;
    reg [STALL_W-1:0] stall;

    assign busy = r_busy;
    assign in_ready = PREFETCH != 0 ? !has_next : !r_busy;
    wire accept = in_valid && in_ready;
    assign iss_valid = r_busy && stall == {STALL_W{1'b0}};
    wire issued = iss_valid && iss_ready;
    assign iss_x = x0 + k[15:0];
    assign iss_y = y;

    // The last pixel of the span issues in this clock.
    wire last = issued && k + 17'd1 >= n;
    // Into the buffer: only while busy (with PREFETCH, in_ready = !has_next).
    assign pf = r_busy && accept;
    // A span begins: the buffered one (or the one accepted now) after the
    // last pixel; an accepted one while idle; a buffered one while idle.
    wire bg_next = r_busy ? last && (has_next || accept) : !accept && has_next;
    wire bg_in = !r_busy && accept;
    assign bg = bg_next || bg_in;
    assign bg_pf = bg_next;
    // The buffered descriptor, or the one entering the buffer in this very clock.
    wire from_buf = has_next;
    assign bg_n = bg_in ? in_n : from_buf ? nx_n : in_n;
    assign bg_pay = bg_in ? in_pay : from_buf ? nx_pay : in_pay;
    wire [15:0] bg_y = bg_in ? in_y : from_buf ? nx_y : in_y;
    wire [15:0] bg_x0 = bg_in ? in_x0 : from_buf ? nx_x0 : in_x0;
    assign adv = issued;

    always @(posedge clk) begin
        if (rst) begin
            r_busy <= 1'b0;
            has_next <= 1'b0;
            k <= 17'd0;
            n <= 17'd0;
            y <= 16'd0;
            x0 <= 16'd0;
            stall <= {STALL_W{1'b0}};
            nx_n <= 17'd0;
            nx_y <= 16'd0;
            nx_x0 <= 16'd0;
            nx_pay <= {PAY_W{1'b0}};
        end else begin
            if (pf) begin
                has_next <= 1'b1;
                nx_n <= in_n;
                nx_y <= in_y;
                nx_x0 <= in_x0;
                nx_pay <= in_pay;
            end
            if (r_busy) begin
                if (stall != {STALL_W{1'b0}}) begin
`ifdef NP_FAULT_SETUP
                    stall <= {STALL_W{1'b0}};  // fault: a set-up stall ends after one clock
`else
                    stall <= stall - {{(STALL_W - 1){1'b0}}, 1'b1};
`endif
                end else if (issued) begin
                    stall <= adv_stall;
                    k <= k + 17'd1;
                    if (last) r_busy <= 1'b0;
                end
            end
            if (bg) begin
                k <= 17'd0;
                n <= bg_n;
                y <= bg_y;
                x0 <= bg_x0;
                stall <= bg_stall;
                r_busy <= bg_n != 17'd0;
                if (bg_next) has_next <= 1'b0;
            end
        end
    end
endmodule
