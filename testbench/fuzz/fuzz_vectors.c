/* SPDX-License-Identifier: MIT */
/* The vector-file reader (np_vec_open / np_vec_read) on arbitrary bytes. */
#include <string.h>

#include "np_fuzz.h"
#include "np_vec.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const char *path = np_fuzz_file(data, size);
    if (!path)
        return 0;
    np_vec_reader r;
    if (np_vec_open(&r, path) != 0) {
        np_fuzz_assert(r.L.err[0] != '\0'); /* a refusal always says why */
        np_vec_close(&r);
        return 0;
    }
    np_vec_rec rec;
    int st;
    uint64_t n = 0;
    while ((st = np_vec_read(&r, &rec)) == 1 && n < 1000000)
        n++;
    if (st < 0)
        np_fuzz_assert(r.L.err[0] != '\0');
    np_vec_close(&r);
    return 0;
}
