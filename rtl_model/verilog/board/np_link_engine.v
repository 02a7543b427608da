// SPDX-License-Identifier: MIT
// np_link_engine - the board's side of the USB link protocol (docs/usb-protocol.md, the
// contract; docs/board.md): OUT bytes in, IN bytes out, one unit slot behind it. Written from
// the document, section by section, and kept byte for byte equal to the C board emulator
// (src/link/link_board.c) configured with the same INFO (testbench/rtl/board_diff.cpp checks).
//
// Parameters:
//   MAX_PAYLOAD  the board's max_payload (INFO): a multiple of 4, 292..65532
//   WINDOW       the window announced in INFO (>= 1)
//   RXB_AW       the OUT buffer holds 2^RXB_AW bytes; >= one whole frame and ROOM_LOW
//                (28 + MAX_PAYLOAD + ROOM_LOW)
//   IN_STRIDE, OUT_STRIDE   bytes of the slot's input and output record (section 5)
//   BOARD_ID     INFO's board_id, <= 32 characters
//   SLOT_UNIT    the slot's unit name, <= 16 characters
//   SLOT_CFG     the slot's configuration text, canonical form, <= 111 characters
//   SLOT_LAYOUT  CONFIG payload bytes 16..35 (n_in, n_out, strides, in_bits[8], out_bits[8]),
//                byte 16 in bits 7:0
//   LATENCY, CLOCK_HZ   CONFIG_ACK's information fields
//   ROOM_LOW     in_room_low's threshold, bytes
// Ports (u: unsigned, width in bits); every handshake moves a beat on a clock where both
// valid and ready are high; everything changes at clk's rising edge:
//   clk, rst             rst synchronous, active high: power-on state (halted, hunting)
//   in_valid, in_ready, in_data u1 u1 u8   the OUT byte stream (from the host)
//   in_room_low          u1: fewer than ROOM_LOW bytes of room left in the OUT buffer (for a
//                        link that cannot stop at once: the UART's RTS, docs/board.md)
//   out_valid, out_ready, out_data u1 u1 u8   the IN byte stream (to the host)
//   out_last             u1: out_data is the last byte of a frame (for the IN rule: a USB
//                        bridge ends its packet there when no other frame follows)
//   u_in_valid, u_in_ready, u_in_rec  u1 u1 u(8*IN_STRIDE)   an input record to the unit,
//                        byte k of the record (wire order) in bits 8k+7..8k
//   u_out_valid, u_out_ready, u_out_rec u1 u1 u(8*OUT_STRIDE)  an output record, the same
//   busy                 u1: a frame is being checked, run or answered (for the board's LEDs)
//
// How it works. OUT bytes go into a buffer (a block RAM, synchronous read) and stay there until
// their frame is done: a frame whose payload CRC fails is re-scanned from its second byte, as
// the protocol's receiver does (section 2: "discards its first byte and hunts on from the next
// one"), so a HELLO inside the bytes of a damaged frame is still found. One frame at a time:
// header (24 bytes, its CRC at once), payload and pcrc (the CONFIG compared with the slot on
// the way), then the action; a DATA frame's records are read from the buffer a second time, only
// once its pcrc is known good (a board never runs data it is not sure of), into the unit,
// while the RESULT frame goes out (its header first: tag, count and len are known). The answer
// is sent completely before the next frame is looked at, so IN frames leave in order and
// back-pressure is simply this: out_ready low stalls the answer, the unit, the reading of the
// buffer, and at last in_ready. No byte is ever dropped.
//
// Choices where the document leaves one (docs/usb-protocol.md, and docs/board.md):
//   - n_slots 1; CONFIG compared with the slot byte for byte (section 4.2). A payload of
//     40..292 bytes that matches in unit and text but not in bytes 16..35 is BAD_LAYOUT;
//     anything else that is not the slot is NO_SUCH_CONFIG (the emulator decodes first and
//     says BAD_LENGTH for a payload it cannot parse: both refuse and halt).
//   - ERROR messages are empty (the field "may be empty").
//   - BYE_ACK cycles: clocks from a DATA frame's first record to its RESULT's last byte;
//     stalls: clocks the unit offered an output that was not taken.
//
// Fault copies for the tests that must fail: `define NP_FAULT_LINK_SEQ accepts any seq
// (no BAD_SEQ), `define NP_FAULT_LINK_PCRC takes every payload CRC as good.
module np_link_engine #(
    parameter integer MAX_PAYLOAD = 1024,
    parameter integer WINDOW = 2,
    parameter integer RXB_AW = 11,
    parameter integer IN_STRIDE = 8,
    parameter integer OUT_STRIDE = 4,
    parameter [8*32-1:0] BOARD_ID = "classic3 on iCE40-HX8K breakout",
    parameter [8*16-1:0] SLOT_UNIT = "classic3",
    parameter [8*112-1:0] SLOT_CFG = "out_bits=8 s_frac=12 lerp_frac=11",
    parameter [8*20-1:0] SLOT_LAYOUT = 160'h00000000000000080000000000101010_04080103,
    parameter [31:0] LATENCY = 17,
    parameter [31:0] CLOCK_HZ = 12000000,
    parameter integer ROOM_LOW = 16
) (
    input wire clk,
    input wire rst,
    input wire in_valid,
    output wire in_ready,
    input wire [7:0] in_data,
    output wire in_room_low,
    output wire out_valid,
    input wire out_ready,
    output reg [7:0] out_data,
    output wire out_last,
    output wire u_in_valid,
    input wire u_in_ready,
    output wire [8*IN_STRIDE-1:0] u_in_rec,
    input wire u_out_valid,
    output wire u_out_ready,
    input wire [8*OUT_STRIDE-1:0] u_out_rec,
    output wire busy
);
    // ---------------------------------------------------------------- constants
    // Frame types and error codes (sections 4 and 6).
    localparam [7:0] T_HELLO = 8'h01, T_CONFIG = 8'h02, T_DATA = 8'h03, T_BYE = 8'h04;
    localparam [7:0] T_INFO = 8'h81, T_ACK = 8'h82, T_RESULT = 8'h83, T_BYE_ACK = 8'h84;
    localparam [7:0] T_ERROR = 8'hEE;
    localparam [7:0] E_BAD_HEADER = 8'd1, E_BAD_CRC = 8'd2, E_BAD_VERSION = 8'd3;
    localparam [7:0] E_BAD_TYPE = 8'd4, E_BAD_LENGTH = 8'd5, E_BAD_SEQ = 8'd6;
    localparam [7:0] E_NOT_CONFIGURED = 8'd7, E_NO_SUCH_CONFIG = 8'd8, E_BAD_LAYOUT = 8'd9;
    localparam [31:0] HDR = 32'd24, CRCB = 32'd4;
    localparam [15:0] INFO_LEN = 16'd176;  // 48 + 128: one slot
    localparam [15:0] ACK_LEN = 16'd16, BYE_LEN = 16'd32, ERR_LEN = 16'd64;
    localparam [15:0] CFG_MIN = 16'd40, CFG_MAX = 16'd292;  // CONFIG payload bounds (4.2)
    localparam [31:0] MAX_RESULT = 32'd65532;
    localparam [15:0] MAXP16 = MAX_PAYLOAD[15:0];
    localparam [7:0] IN_STRIDE8 = IN_STRIDE[7:0], OUT_STRIDE8 = OUT_STRIDE[7:0];

    // The length of a string parameter: Verilog right-aligns a literal, leading NULs pad it.
    function integer slen;
        input [8*112-1:0] s;
        input integer field;
        integer i;
        begin
            slen = 0;
            for (i = 0; i < field; i = i + 1)
                if (s[8*i +: 8] != 8'd0)
                    slen = i + 1;
        end
    endfunction
    localparam integer ID_LEN = slen({{(8*80){1'b0}}, BOARD_ID}, 32);
    localparam integer UNIT_LEN = slen({{(8*96){1'b0}}, SLOT_UNIT}, 16);
    localparam integer CFG_LEN = slen(SLOT_CFG, 112);
    // Byte i (0 = first character) of a string of n characters; NUL past its end.
    function [7:0] sbyte;
        input [8*112-1:0] s;
        input integer n;
        input [15:0] i;
        integer k;
        begin
            k = n - 1 - {16'd0, i};
            sbyte = ({16'd0, i} < n) ? s[8*k +: 8] : 8'd0;
        end
    endfunction

    // ---------------------------------------------------------------- OUT buffer
    // Pointers count bytes modulo 2^(RXB_AW+1): wr (next byte written), fstart (first byte
    // of the frame being looked at), rd (next byte the parser reads). Bytes fstart..wr-1 are
    // held; in_ready while there is room.
    localparam integer PW = RXB_AW + 1;
    localparam [PW-1:0] SIZE = {1'b1, {RXB_AW{1'b0}}};
    reg [7:0] mem[0:(1 << RXB_AW)-1];
    reg [PW-1:0] wr, wr_d, fstart, rd;
    reg [PW-1:0] fstart_n, rd_n;
    reg [7:0] rdata;  // mem[rd], valid when rd != wr_d
    wire [PW-1:0] held = wr - fstart;
    assign in_ready = held != SIZE;
    localparam [PW-1:0] LOW = ROOM_LOW[PW-1:0];
    assign in_room_low = SIZE - held < LOW;
    wire b_valid = rd != wr_d;
    wire [7:0] b = rdata;
    always @(posedge clk) begin
        if (in_valid && in_ready)
            mem[wr[RXB_AW-1:0]] <= in_data;
        rdata <= mem[rd_n[RXB_AW-1:0]];
    end

    // ---------------------------------------------------------------- state
    localparam [2:0] M_HDR = 3'd0, M_HCHK = 3'd1, M_PAY = 3'd2, M_PCHK = 3'd3, M_FEED = 3'd4,
                     M_SEND = 3'd5;
    reg [2:0] m;
    reg in_step;      // section 2: the receiver knows where the next frame starts
    reg halted;       // section 6: no session, or after an ERROR: only HELLO is heard
    reg configured;   // a successful CONFIG since the HELLO
    reg [31:0] rx_expect, tx_seq;
    // The frame being looked at.
    reg [4:0] hcnt;   // header bytes read
    reg [16:0] pcnt;  // payload and pcrc bytes read
    reg [7:0] h_sync0, h_sync1, h_ver, h_type;
    reg [31:0] h_seq, h_hcrc, h_pcrc;
    reg [63:0] h_tag;
    reg [15:0] h_count, h_len;
    reg name_bad, lay_bad, text_bad;  // CONFIG against the slot
    reg go, g_err, g_reject, g_commit, g_hello, g_feed;  // the parser's decisions (below)
    // Session counters (BYE_ACK, 4.4).
    reg [63:0] c_records, c_cycles, c_stalls;
    reg [31:0] c_frames, c_errors;

    // One CRC each way: OUT, the header's bytes 0..19 up to the check (M_HCHK), then the
    // payload; IN, the header's bytes 0..19 (held while hcrc goes out), then the payload.
    reg rc_init;
    wire rc_en;
    wire [31:0] rh_crc, rp_crc;
    np_crc32 u_rc(.clk(clk), .rst(rst), .init(rc_init), .en(rc_en), .d(b), .crc(rh_crc));
    assign rp_crc = rh_crc;

    // ---------------------------------------------------------------- the sender
    // Started by the parser with s_go and the frame's type, tag, count, len (seq is tx_seq);
    // it sends header, payload and pcrc, and is idle again (s_idle) after the last byte.
    localparam [1:0] S_IDLE = 2'd0, S_HDR = 2'd1, S_PAY = 2'd2, S_PCRC = 2'd3;
    reg [1:0] s;
    reg s_go;
    reg [7:0] s_type, g_type;
    reg [63:0] s_tag, g_tag;
    reg [15:0] s_count, g_count, s_len, g_len;
    reg [31:0] s_seq;
    reg [7:0] s_code, g_code;
    reg [31:0] s_detail, g_detail;
    reg [4:0] s_hc;
    reg [15:0] s_pc;
    reg [1:0] s_cc;
    wire s_idle = s == S_IDLE;
    // RESULT: the unit's output record being sent.
    reg [8*OUT_STRIDE-1:0] orec;
    reg have_orec;
    reg [7:0] ob;
    assign u_out_ready = !have_orec && s == S_PAY && s_type == T_RESULT;
    wire [159:0] s_hdr = {s_len, s_count, s_tag, s_seq, s_type, 8'd1, 8'h50, 8'h4E};
    wire tc_en, tc_init;
    wire [31:0] th_crc, tp_crc;
    np_crc32 u_tc(.clk(clk), .rst(rst), .init(tc_init), .en(tc_en), .d(out_data), .crc(th_crc));
    assign tp_crc = th_crc;

    // Payload byte k of the frame being sent (RESULT: from orec).
    function [7:0] b32;  // byte i of a little-endian 32-bit field
        input [31:0] v;
        input [1:0] i;
        b32 = v[8*i +: 8];
    endfunction
    function [7:0] b64;
        input [63:0] v;
        input [2:0] i;
        b64 = v[8*i +: 8];
    endfunction
    // The constant bytes in one ROM (LUTs, read asynchronously), shared by the sender (INFO,
    // CONFIG_ACK) and the parser (the CONFIG it expects), which never use it at once:
    //   0..175    INFO's payload; its bytes 48..63 (unit) and 64..175 (text) are also what a
    //             CONFIG must carry in its bytes 0..15 and 36..147
    //   176..195  the slot's CONFIG bytes 16..35 (the field layout)
    //   196..211  CONFIG_ACK's payload
    //   212..255  zero (a CONFIG's bytes 148.. must be NULs)
    reg [7:0] rom[0:255];
    integer ri;
    initial begin
        for (ri = 0; ri < 256; ri = ri + 1)
            rom[ri] = 8'd0;
        for (ri = 0; ri < 4; ri = ri + 1) begin
            rom[ri] = b32(32'd1, ri[1:0]);  // version
            rom[4 + ri] = b32(MAX_PAYLOAD, ri[1:0]);
            rom[8 + ri] = b32(WINDOW, ri[1:0]);
            rom[12 + ri] = b32(32'd1, ri[1:0]);  // n_slots
            rom[196 + ri] = b32(LATENCY, ri[1:0]);
            rom[200 + ri] = b32(CLOCK_HZ, ri[1:0]);
        end
        rom[204] = IN_STRIDE8;
        rom[205] = OUT_STRIDE8;
        for (ri = 0; ri < 32; ri = ri + 1)
            rom[16 + ri] = sbyte({{(8*80){1'b0}}, BOARD_ID}, ID_LEN, ri[15:0]);
        for (ri = 0; ri < 16; ri = ri + 1)
            rom[48 + ri] = sbyte({{(8*96){1'b0}}, SLOT_UNIT}, UNIT_LEN, ri[15:0]);
        for (ri = 0; ri < 112; ri = ri + 1)
            rom[64 + ri] = sbyte(SLOT_CFG, CFG_LEN, ri[15:0]);
        for (ri = 0; ri < 20; ri = ri + 1)
            rom[176 + ri] = SLOT_LAYOUT[8*ri +: 8];
    end
    reg [7:0] rom_a;
    wire [7:0] rom_d = rom[rom_a];
    wire [15:0] pk = pcnt[15:0];  // the CONFIG payload byte being read
    always @(*)
        if (s != S_IDLE)
            rom_a = s_type == T_ACK ? 8'd196 + s_pc[7:0] : s_pc[7:0];
        else if (pk < 16'd16)
            rom_a = 8'd48 + pk[7:0];
        else if (pk < 16'd36)
            rom_a = 8'd160 + pk[7:0];  // 176 + (pk - 16)
        else if (pk < 16'd148)
            rom_a = 8'd28 + pk[7:0];  // 64 + (pk - 36)
        else
            rom_a = 8'd255;

    reg [7:0] pay;
    always @(*) begin
        pay = 8'd0;
        case (s_type)
        T_INFO, T_ACK:
            pay = rom_d;
        T_BYE_ACK:
            if (s_pc < 16'd8) pay = b64(c_records, s_pc[2:0]);
            else if (s_pc < 16'd16) pay = b64(c_cycles, s_pc[2:0]);
            else if (s_pc < 16'd24) pay = b64(c_stalls, s_pc[2:0]);
            else if (s_pc < 16'd28) pay = b32(c_frames, s_pc[1:0]);
            else pay = b32(c_errors, s_pc[1:0]);
        T_ERROR:
            if (s_pc < 16'd4) pay = b32({24'd0, s_code}, s_pc[1:0]);
            else if (s_pc < 16'd8) pay = b32(s_detail, s_pc[1:0]);
        T_RESULT:
            pay = orec[8*ob +: 8];
        default: pay = 8'd0;
        endcase
    end
    always @(*) begin
        case (s)
        S_HDR: out_data = s_hc < 5'd20 ? s_hdr[8*s_hc +: 8] : b32(th_crc, s_hc[1:0]);
        S_PAY: out_data = pay;
        S_PCRC: out_data = b32(tp_crc, s_cc);
        default: out_data = 8'd0;
        endcase
    end
    assign out_valid = s == S_HDR || s == S_PCRC || (s == S_PAY && (s_type != T_RESULT || have_orec));
    assign out_last = s == S_PCRC && s_cc == 2'd3;
    wire o_take = out_valid && out_ready;
    assign tc_en = o_take && ((s == S_HDR && s_hc < 5'd20) || s == S_PAY);
    assign tc_init = s_go || (o_take && s == S_HDR && s_hc == 5'd23);

    always @(posedge clk)
        if (rst) begin
            s <= S_IDLE;
            have_orec <= 1'b0;
            ob <= 8'd0;
            tx_seq <= 32'd0;
            s_hc <= 5'd0;
            s_pc <= 16'd0;
            s_cc <= 2'd0;
        end else begin
            if (u_out_valid && u_out_ready) begin
                orec <= u_out_rec;
                have_orec <= 1'b1;
            end
            case (s)
            S_IDLE:
                if (s_go) begin
                    s <= S_HDR;
                    s_type <= g_type;
                    s_tag <= g_tag;
                    s_count <= g_count;
                    s_len <= g_len;
                    s_code <= g_code;
                    s_detail <= g_detail;
                    // An answer to a HELLO (INFO, or ERROR BAD_VERSION) is seq 0 (section 3).
                    s_seq <= g_hello ? 32'd0 : tx_seq;
                    tx_seq <= (g_hello ? 32'd0 : tx_seq) + 32'd1;
                    s_hc <= 5'd0;
                    s_pc <= 16'd0;
                    s_cc <= 2'd0;
                    ob <= 8'd0;
                end
            S_HDR:
                if (o_take) begin
                    s_hc <= s_hc + 5'd1;
                    if (s_hc == 5'd23)
                        s <= s_len == 16'd0 ? S_PCRC : S_PAY;
                end
            S_PAY:
                if (o_take) begin
                    s_pc <= s_pc + 16'd1;
                    if (s_type == T_RESULT) begin
                        if (ob == OUT_STRIDE8 - 8'd1) begin
                            ob <= 8'd0;
                            have_orec <= 1'b0;
                        end else
                            ob <= ob + 8'd1;
                    end
                    if (s_pc == s_len - 16'd1)
                        s <= S_PCRC;
                end
            default:  // S_PCRC
                if (o_take) begin
                    s_cc <= s_cc + 2'd1;
                    if (s_cc == 2'd3)
                        s <= S_IDLE;
                end
            endcase
        end

    // ---------------------------------------------------------------- the parser
    // The unit's input record, filled from the buffer.
    reg [8*IN_STRIDE-1:0] irec;
    reg irec_full;
    reg [7:0] fb;      // bytes of irec filled
    reg [15:0] fed;    // records given to the unit
    reg [16:0] fbytes; // payload bytes read for the unit
    assign u_in_valid = irec_full;
    assign u_in_rec = irec;
    assign busy = m != M_HDR || hcnt != 5'd0;

    wire consume = b_valid && (m == M_HDR || m == M_PAY || (m == M_FEED && !irec_full && fbytes != {1'b0, h_len}));
    assign rc_en = consume && ((m == M_HDR && hcnt < 5'd20) || (m == M_PAY && pcnt < {1'b0, h_len}));

    wire hdr_ok = h_sync0 == 8'h4E && h_sync1 == 8'h50 && rh_crc == h_hcrc;
    /* verilator lint_off UNUSEDSIGNAL */
    wire [31:0] flen = {16'd0, h_len} + HDR + CRCB;  // (bits above the pointers' are dropped)
    /* verilator lint_on UNUSEDSIGNAL */
    wire [PW-1:0] fend = fstart + flen[PW-1:0];
`ifdef NP_FAULT_LINK_PCRC
    wire pcrc_ok = (rp_crc == h_pcrc) | 1'b1;  // fault copy: every pcrc taken as good
`else
    wire pcrc_ok = rp_crc == h_pcrc;
`endif
`ifdef NP_FAULT_LINK_SEQ
    wire seq_ok = (h_seq == rx_expect) | 1'b1;  // fault copy: no BAD_SEQ
`else
    wire seq_ok = h_seq == rx_expect;
`endif
    wire [31:0] data_in_bytes = {16'd0, h_count} * IN_STRIDE;
    wire [31:0] data_out_bytes = {16'd0, h_count} * OUT_STRIDE;

    // Decisions of the clock: what to send, and where the parser goes.
    always @(*) begin
        go = 1'b0;  // start the sender with g_*
        g_err = 1'b0;  // the frame sent is an ERROR of the session (halts, counts)
        g_reject = 1'b0;  // drop the first byte of this frame, hunt from the next
        g_commit = 1'b0;  // the frame is done: the next one starts after it
        g_hello = 1'b0;  // a new session
        g_feed = 1'b0;  // DATA: read the payload again, into the unit
        g_type = T_ERROR;
        g_tag = {32'd0, rx_expect};
        g_count = 16'd0;
        g_len = ERR_LEN;
        g_code = 8'd0;
        g_detail = 32'd0;
        case (m)
        M_HCHK:
            if (!hdr_ok) begin
                g_reject = 1'b1;
                if (in_step && !halted) begin
                    go = 1'b1; g_err = 1'b1; g_code = E_BAD_HEADER;
                end
            end else if (h_ver != 8'd1 && h_type != T_ERROR) begin
                g_reject = 1'b1;
                if (h_type == T_HELLO) begin  // section 3: refused in any state
                    go = 1'b1; g_err = 1'b1; g_hello = 1'b1; g_code = E_BAD_VERSION; g_detail = 32'd1;
                    g_tag = h_tag;
                end else if (!halted) begin
                    go = 1'b1; g_err = 1'b1; g_code = E_BAD_VERSION; g_detail = 32'd1;
                end
            end else if (h_len[1:0] != 2'd0 || h_len > MAXP16) begin
                g_reject = 1'b1;
                if (!halted) begin
                    go = 1'b1; g_err = 1'b1; g_code = E_BAD_LENGTH; g_detail = MAX_PAYLOAD;
                end
            end
        M_PCHK:
            if (!pcrc_ok) begin
                g_reject = 1'b1;
                if (!halted) begin
                    go = 1'b1; g_err = 1'b1; g_code = E_BAD_CRC;
                end
            end else if (h_type == T_HELLO) begin
                g_commit = 1'b1; g_hello = 1'b1; go = 1'b1;
                g_type = T_INFO; g_tag = h_tag; g_len = INFO_LEN;
            end else if (halted) begin
                g_commit = 1'b1;  // dropped silently until HELLO
            end else if (!seq_ok) begin
                g_commit = 1'b1; go = 1'b1; g_err = 1'b1; g_code = E_BAD_SEQ; g_detail = rx_expect;
            end else begin
                g_commit = 1'b1; go = 1'b1;
                g_tag = {32'd0, rx_expect + 32'd1};  // an ERROR's tag: the seq expected next
                case (h_type)
                T_CONFIG:
                    if (h_len < CFG_MIN || h_len > CFG_MAX) begin
                        g_err = 1'b1; g_code = E_BAD_LENGTH;
                    end else if (name_bad || text_bad || {16'd0, h_len} < 36 + CFG_LEN + 1) begin
                        g_err = 1'b1; g_code = E_NO_SUCH_CONFIG;
                    end else if (lay_bad) begin
                        g_err = 1'b1; g_code = E_BAD_LAYOUT;
                    end else begin
                        g_type = T_ACK; g_tag = 64'd0; g_len = ACK_LEN;
                    end
                T_DATA:
                    if (!configured) begin
                        g_err = 1'b1; g_code = E_NOT_CONFIGURED;
                    end else if (h_count == 16'd0 || data_in_bytes != {16'd0, h_len}) begin
                        g_err = 1'b1; g_code = E_BAD_LENGTH;
                    end else if (data_out_bytes > MAX_RESULT) begin
                        g_err = 1'b1; g_code = E_BAD_LENGTH; g_detail = MAX_PAYLOAD;
                    end else begin
                        g_commit = 1'b0; g_feed = 1'b1;
                        g_type = T_RESULT; g_tag = h_tag; g_count = h_count;
                        g_len = data_out_bytes[15:0];
                    end
                T_BYE: begin
                    g_type = T_BYE_ACK; g_tag = 64'd0; g_len = BYE_LEN;
                end
                default: begin
                    g_err = 1'b1; g_code = E_BAD_TYPE;
                end
                endcase
            end
        default: ;
        endcase
    end
    always @(*) s_go = go;

    // Next pointers (the buffer's read address is rd_n).
    wire feed_done = m == M_FEED && fed == h_count && !irec_full;
    always @(*) begin
        fstart_n = fstart;
        rd_n = rd + {{(PW-1){1'b0}}, consume};
        if (m == M_HDR && consume && !in_step &&
            ((hcnt == 5'd0 && b != 8'h4E) || (hcnt == 5'd1 && b != 8'h50))) begin
            fstart_n = fstart + 1'b1;  // hunting: not a header start
            rd_n = fstart + 1'b1;
        end
        if (g_reject) begin
            fstart_n = fstart + 1'b1;
            rd_n = fstart + 1'b1;
        end else if (g_commit || feed_done) begin
            fstart_n = fend;
            rd_n = fend;
        end else if (g_feed) begin
            rd_n = fstart + HDR[PW-1:0];
        end
    end
    wire hunt_skip = m == M_HDR && consume && !in_step &&
                     ((hcnt == 5'd0 && b != 8'h4E) || (hcnt == 5'd1 && b != 8'h50));

    always @(*) begin
        rc_init = rst || hunt_skip || g_reject || g_commit || feed_done || m == M_HCHK;
    end

    always @(posedge clk)
        if (rst) begin
            wr <= {PW{1'b0}};
            wr_d <= {PW{1'b0}};
            fstart <= {PW{1'b0}};
            rd <= {PW{1'b0}};
            m <= M_HDR;
            in_step <= 1'b0;
            halted <= 1'b1;
            configured <= 1'b0;
            rx_expect <= 32'd0;
            hcnt <= 5'd0;
            pcnt <= 17'd0;
            irec_full <= 1'b0;
            fb <= 8'd0;
            fed <= 16'd0;
            fbytes <= 17'd0;
            c_records <= 64'd0;
            c_cycles <= 64'd0;
            c_stalls <= 64'd0;
            c_frames <= 32'd0;
            c_errors <= 32'd0;
        end else begin
            if (in_valid && in_ready)
                wr <= wr + 1'b1;
            wr_d <= wr;
            fstart <= fstart_n;
            rd <= rd_n;
            case (m)
            M_HDR:
                if (hunt_skip)
                    hcnt <= 5'd0;
                else if (consume) begin
                    case (hcnt)
                    5'd0: h_sync0 <= b;
                    5'd1: h_sync1 <= b;
                    5'd2: h_ver <= b;
                    5'd3: h_type <= b;
                    default: ;
                    endcase
                    if (hcnt >= 5'd4 && hcnt < 5'd8) h_seq <= {b, h_seq[31:8]};
                    if (hcnt >= 5'd8 && hcnt < 5'd16) h_tag <= {b, h_tag[63:8]};
                    if (hcnt >= 5'd16 && hcnt < 5'd18) h_count <= {b, h_count[15:8]};
                    if (hcnt >= 5'd18 && hcnt < 5'd20) h_len <= {b, h_len[15:8]};
                    if (hcnt >= 5'd20) h_hcrc <= {b, h_hcrc[31:8]};
                    hcnt <= hcnt + 5'd1;
                    if (hcnt == 5'd23)
                        m <= M_HCHK;
                end
            M_HCHK: begin
                pcnt <= 17'd0;
                name_bad <= 1'b0;
                lay_bad <= 1'b0;
                text_bad <= 1'b0;
                m <= g_reject ? (go ? M_SEND : M_HDR) : M_PAY;
            end
            M_PAY:
                if (consume) begin
                    if (pcnt < {1'b0, h_len}) begin
                        if (pk < 16'd16 && b != rom_d) name_bad <= 1'b1;
                        if (pk >= 16'd16 && pk < 16'd36 && b != rom_d) lay_bad <= 1'b1;
                        if (pk >= 16'd36 && b != rom_d) text_bad <= 1'b1;
                    end else
                        h_pcrc <= {b, h_pcrc[31:8]};
                    pcnt <= pcnt + 17'd1;
                    if (pcnt == {1'b0, h_len} + 17'd3)
                        m <= M_PCHK;
                end
            M_PCHK: begin
                m <= g_feed ? M_FEED : (go ? M_SEND : M_HDR);
                irec_full <= 1'b0;
                fb <= 8'd0;
                fed <= 16'd0;
                fbytes <= 17'd0;
            end
            M_FEED:
                if (feed_done)
                    m <= M_SEND;
                else begin
                    if (consume) begin
                        irec[8*fb +: 8] <= b;
                        fbytes <= fbytes + 17'd1;
                        if (fb == IN_STRIDE8 - 8'd1) begin
                            fb <= 8'd0;
                            irec_full <= 1'b1;
                        end else
                            fb <= fb + 8'd1;
                    end
                    if (irec_full && u_in_ready) begin
                        irec_full <= 1'b0;
                        fed <= fed + 16'd1;
                    end
                end
            default:  // M_SEND: the answer goes out completely before the next frame
                if (s_idle && !go)
                    m <= M_HDR;
            endcase
            if (g_reject || g_commit || feed_done)
                hcnt <= 5'd0;
            if (g_reject)
                in_step <= 1'b0;
            if (m == M_PCHK && pcrc_ok)
                in_step <= 1'b1;
            // Section 3: HELLO resets the session; 4.2, 4.4: CONFIG and BYE.
            if (g_hello) begin
                rx_expect <= 32'd1;
                halted <= 1'b0;
                configured <= 1'b0;
                c_records <= 64'd0;
                c_cycles <= 64'd0;
                c_stalls <= 64'd0;
                c_frames <= 32'd0;
                c_errors <= 32'd0;
            end else if (m == M_PCHK && pcrc_ok && !halted && seq_ok) begin
                rx_expect <= rx_expect + 32'd1;
                if (h_type == T_CONFIG && !g_err)
                    configured <= 1'b1;
                if (h_type == T_BYE)
                    configured <= 1'b0;
                if (g_feed) begin
                    c_frames <= c_frames + 32'd1;
                    c_records <= c_records + {48'd0, h_count};
                end
            end
            if (g_err) begin
                halted <= 1'b1;
                configured <= 1'b0;
                c_errors <= (g_hello ? 32'd0 : c_errors) + 32'd1;
            end
            if (m == M_FEED || (m == M_SEND && s_type == T_RESULT && !s_idle))
                c_cycles <= c_cycles + 64'd1;
            if (u_out_valid && !u_out_ready)
                c_stalls <= c_stalls + 64'd1;
        end

    // The buffer must hold a whole frame with ROOM_LOW to spare: a sender that honours
    // in_room_low stops when fewer than ROOM_LOW bytes are free, and a frame that needed those
    // bytes would never be complete (the buffer is freed a frame at a time: a deadlock).
    initial begin
        if ((1 << RXB_AW) < HDR + CRCB + MAX_PAYLOAD + ROOM_LOW || MAX_PAYLOAD % 4 != 0 ||
            MAX_PAYLOAD < 292 || MAX_PAYLOAD > 65532) begin
            $display("np_link_engine: MAX_PAYLOAD %0d, RXB_AW %0d, ROOM_LOW %0d: need a multiple of 4 in 292..65532 and 2^RXB_AW >= 28 + MAX_PAYLOAD + ROOM_LOW",
                     MAX_PAYLOAD, RXB_AW, ROOM_LOW);
            $finish;
        end
    end
endmodule
