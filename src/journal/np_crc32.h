/* SPDX-License-Identifier: MIT */
/*
 * np_crc32.h - CRC-32/ISO-HDLC (Ethernet, zlib): reflected polynomial
 * 0xEDB88320, init and final XOR 0xFFFFFFFF. np_crc32(0, p, n) is the CRC of
 * p[0..n); pass a previous result as crc to continue it. "123456789" ->
 * 0xCBF43926. One implementation for the USB link's frames (np_link_crc32)
 * and the journals' line checksums (np_jfile.h).
 */
#ifndef NP_CRC32_H
#define NP_CRC32_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

extern const uint32_t np_crc32_table[256];
uint32_t np_crc32(uint32_t crc, const void *p, size_t n);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* NP_CRC32_H */
