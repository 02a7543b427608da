/* SPDX-License-Identifier: MIT */
/*
 * Configuration strings through the models: the first byte picks a unit, the
 * rest is a "key=value,..." string. An accepted configuration must round-trip
 * (format, configure, format: the same text), and its bit-exact model, float
 * reference, datapath declaration and (for pipelined units) cycle model must
 * run on inputs taken from the same bytes without a finding.
 */
#include <string.h>

#include "np_fuzz.h"
#include "np_datapath.h"
#include "np_pipe.h"
#include "np_unit.h"

enum { MAX_OPS = 4096 };

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1 || size > 400)
        return 0;
    size_t n_units = 0;
    while (np_units[n_units])
        n_units++;
    const np_unit *u = np_units[data[0] % n_units];
    char spec[401];
    memcpy(spec, data + 1, size - 1);
    spec[size - 1] = '\0';

    np_unit_cfg cfg, again;
    char err[512], text[512], text2[512];
    if (np_unit_configure(u, cfg.bytes, spec, err, sizeof err) != 0) {
        np_fuzz_assert(err[0] != '\0');
        return 0;
    }
    np_unit_cfg_format(u, cfg.bytes, text, sizeof text);
    np_fuzz_assert(np_unit_configure(u, again.bytes, text, err, sizeof err) == 0);
    np_unit_cfg_format(u, again.bytes, text2, sizeof text2);
    np_fuzz_assert(strcmp(text, text2) == 0);

    np_unit_fields f;
    u->fields(cfg.bytes, &f);
    np_fuzz_assert(f.n_in >= 1 && f.n_in <= NP_UNIT_MAX_FIELDS && f.n_out >= 1 && f.n_out <= NP_UNIT_MAX_FIELDS);
    uint64_t in[NP_UNIT_MAX_FIELDS] = { 0 }, out[NP_UNIT_MAX_FIELDS];
    double ref[NP_UNIT_MAX_FIELDS];
    for (unsigned i = 0; i < f.n_in; i++) {
        uint64_t v = 0;
        for (unsigned b = 0; b < 8; b++)
            v = v << 8 | data[(1u + i * 8u + b) % size];
        in[i] = f.in[i].bits >= 64 ? v : v & (((uint64_t)1 << f.in[i].bits) - 1u);
    }
    /* Stream units take only valid descriptors; their fuzzing is the vector reader's. */
    if (!u->stream) {
        u->eval(cfg.bytes, in, out);
        for (unsigned i = 0; i < f.n_out; i++)
            np_fuzz_assert(f.out[i].bits >= 64 || out[i] >> f.out[i].bits == 0);
        u->ref(cfg.bytes, in, ref);
        np_pipe p;
        if (u->pipe_init && u->pipe_init(&p, cfg.bytes) == 0) {
            np_pipe_free(&p);
        }
    }
    if (u->datapath) {
        np_op *ops = malloc(MAX_OPS * sizeof *ops);
        if (ops) {
            size_t n = u->datapath(cfg.bytes, ops, MAX_OPS);
            np_fuzz_assert(n > 0);
            free(ops);
        }
    }
    return 0;
}
