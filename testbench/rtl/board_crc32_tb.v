// SPDX-License-Identifier: MIT
// board_crc32_tb - np_crc32 against the host's CRC-32 (src/journal/crc32.c): messages from
// gen_crc_vectors (testbench/gen_crc_vectors.c) as $readmemh words: a message is its length L,
// its L bytes, then the CRC the host computes. Bytes go in with random gaps (en low); the CRC is
// checked the clock after the last byte. +vectors=FILE. Prints "In N messages, E errors found."
`timescale 1ns / 1ps
module board_crc32_tb;
    reg clk = 0, rst = 1, init = 0, en = 0;
    reg [7:0] d = 0;
    wire [31:0] crc;
    np_crc32 dut (.clk(clk), .rst(rst), .init(init), .en(en), .d(d), .crc(crc));
    always #5 clk = ~clk;

    reg [31:0] mem [0:1048575];
    reg [1023:0] path;
    integer p, n, i, len, errors, msgs, seed;
    initial begin
        if (!$value$plusargs("vectors=%s", path)) begin
            $display("board_crc32_tb: +vectors=FILE needed");
            $finish;
        end
        for (i = 0; i < 1048576; i = i + 1)
            mem[i] = 32'hxxxxxxxx;
        $readmemh(path, mem);
        seed = 1;
        errors = 0;
        msgs = 0;
        p = 0;
        @(posedge clk);
        rst <= 0;
        while (mem[p] !== 32'hxxxxxxxx) begin
            len = mem[p];
            p = p + 1;
            @(negedge clk);
            init = 1;
            @(negedge clk);
            init = 0;
            for (n = 0; n < len; n = n + 1) begin
                while (($random(seed) & 3) == 0) begin // a gap: en low for a clock
                    en = 0;
                    d = $random(seed);
                    @(negedge clk);
                end
                en = 1;
                d = mem[p + n][7:0];
                @(negedge clk);
            end
            en = 0;
            p = p + len;
            if (crc !== mem[p]) begin
                if (errors < 10)
                    $display("message %0d (%0d bytes): crc %08x, want %08x", msgs, len, crc, mem[p]);
                errors = errors + 1;
            end
            p = p + 1;
            msgs = msgs + 1;
        end
        $display("In %0d messages, %0d errors found.", msgs, errors);
        $finish;
    end
endmodule
