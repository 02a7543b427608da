/* SPDX-License-Identifier: MIT */
/*
 * The device-results reader (verify --results) on arbitrary bytes, against the
 * header of a small vector set of one of the units (first byte picks it).
 */
#include <string.h>

#include "np_fuzz.h"
#include "np_unit.h"
#include "np_vec.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1)
        return 0;
    size_t n_units = 0;
    while (np_units[n_units])
        n_units++;
    const np_unit *u = np_units[data[0] % n_units];
    np_vec_header h;
    char err[256];
    if (np_vec_header_init(&h, u, NULL, err, sizeof err) != 0)
        return 0;
    h.count = 1u + (uint64_t)(size > 1 ? data[1] % 64u : 0u);
    const char *path = np_fuzz_file(data + 1, size - 1);
    if (!path)
        return 0;
    np_vec_results rr;
    if (np_vec_results_open(&rr, path, &h) != 0) {
        np_fuzz_assert(rr.L.err[0] != '\0');
        np_vec_results_close(&rr);
        return 0;
    }
    np_vec_rec rec;
    int st;
    while ((st = np_vec_results_read(&rr, &rec)) == 1)
        ;
    if (st < 0)
        np_fuzz_assert(rr.L.err[0] != '\0');
    np_vec_results_close(&rr);
    return 0;
}
