/* SPDX-License-Identifier: MIT */
/*
 * gen_crc_vectors - messages and their CRC-32 from the host's np_crc32 (src/journal/crc32.c),
 * for the board's np_crc32.v (testbench/rtl/board_crc32_tb.v), as $readmemh words: per message
 * its length, its bytes, its CRC. The empty message, "123456789", runs of 0x00 and 0xFF, then
 * seeded random messages of 1..300 bytes.   gen_crc_vectors N SEED > FILE
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "np_crc32.h"
#include "np_rng.h"

static void put(const unsigned char *b, unsigned n)
{
    printf("%08x\n", n);
    for (unsigned i = 0; i < n; i++)
        printf("%02x\n", b[i]);
    printf("%08x\n", np_crc32(0, b, n));
}

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: gen_crc_vectors N SEED\n");
        return 2;
    }
    unsigned n = (unsigned)strtoul(argv[1], NULL, 10);
    np_rng r;
    np_rng_seed(&r, strtoull(argv[2], NULL, 10));
    unsigned char b[300];
    put(b, 0);
    put((const unsigned char *)"123456789", 9);
    memset(b, 0, sizeof b);
    put(b, 64);
    memset(b, 0xff, sizeof b);
    put(b, 300);
    for (unsigned m = 0; m < n; m++) {
        unsigned len = 1 + (unsigned)(np_rng_next(&r) % 300);
        for (unsigned i = 0; i < len; i++)
            b[i] = (unsigned char)np_rng_next(&r);
        put(b, len);
    }
    return 0;
}
