// SPDX-License-Identifier: MIT
// The host's end of np_board_top's UART line, as board_e2e.cpp and board_sim.cpp both model it:
// 8N1 at kCpb clocks a bit each way. Tx sends a byte it is given (the caller decides when: while
// the board's rts_n is low, and what faults apply); Rx samples the board's line in the middle of
// each bit. np_line_reset holds the board's rst for four clocks.
#ifndef NP_UART_LINE_H
#define NP_UART_LINE_H

#include <cstdint>

namespace np_line {

const unsigned kCpb = 4;  // np_board_top's CLKS_PER_BIT (its default)

// A transmitter: bit 0 idle; 1 start, 2..9 data (LSB first), 10 stop.
struct Tx {
    unsigned bit = 0, clk = 0;
    uint8_t cur = 0;
    bool idle() const { return bit == 0; }
    void start(uint8_t b)
    {
        cur = b;
        bit = 1;
        clk = 0;
    }
    // One clock of the byte in progress (not idle): the line level.
    int clock()
    {
        int v = bit == 1 ? 0 : bit == 10 ? 1 : (cur >> (bit - 2)) & 1;
        if (++clk == kCpb) {
            clk = 0;
            bit = bit == 10 ? 0 : bit + 1;
        }
        return v;
    }
};

// A receiver: a start edge, then each bit sampled in its middle. A stop bit read low is a
// framing error (counted, the byte dropped).
struct Rx {
    unsigned bit = 0, clk = 0;
    uint8_t sh = 0;
    int prev = 1;
    uint64_t framing = 0;
    bool idle() const { return bit == 0; }
    // One clock of line level v; 1 with a byte in *b.
    int step(int v, uint8_t *b)
    {
        int out = 0;
        if (bit == 0) {
            if (prev && !v) {
                bit = 1;
                clk = kCpb / 2;  // to the middle of the start bit
            }
        } else if (--clk == 0) {
            clk = kCpb;
            if (bit == 1) {
                bit = v ? 0 : 2;  // high in the middle of the start bit: a glitch
            } else if (bit < 10) {
                sh = (uint8_t)(sh >> 1 | (v ? 0x80 : 0));
                bit++;
            } else {
                bit = 0;
                if (!v) {
                    framing++;
                } else {
                    *b = sh;
                    out = 1;
                }
            }
        }
        prev = v;
        return out;
    }
};

// The board out of reset: rxd idle high, rst held for four clocks.
template <class Top>
void reset(Top *t)
{
    t->rxd = 1;
    t->rst = 1;
    for (int k = 0; k < 4; k++) {
        t->clk = 0;
        t->eval();
        t->clk = 1;
        t->eval();
    }
    t->rst = 0;
}

}  // namespace np_line

#endif
