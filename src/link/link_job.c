/* SPDX-License-Identifier: MIT */
/*
 * link_job.c - the vectors the host streams (docs/usb-protocol.md, section
 * 5): records packed as they travel, and the hash that names them (the
 * journal's binding).
 */
#include "np_link.h"

#include <stdlib.h>
#include <string.h>

#include "np_rng.h"

int np_link_job_init(np_link_job *j, const np_unit *u, const void *cfg, uint64_t n)
{
    memset(j, 0, sizeof *j);
    j->unit = u;
    memcpy(&j->cfg, cfg, sizeof j->cfg);
    u->fields(&j->cfg, &j->fields);
    np_unit_cfg_format(u, &j->cfg, j->cfg_text, sizeof j->cfg_text);
    np_link_layout_init(&j->lay, &j->fields);
    j->n = n;
    size_t m = n ? (size_t)n : 1u;
    j->in = malloc(m * j->lay.in_stride);
    j->want = malloc(m * j->lay.out_stride);
    if (!j->in || !j->want) {
        np_link_job_free(j);
        return -1;
    }
    return 0;
}

void np_link_job_set(np_link_job *j, uint64_t i, const uint64_t *in, const uint64_t *want)
{
    const np_link_layout *l = &j->lay;
    np_link_pack(j->in + i * l->in_stride, in, l->in_lane, l->n_in, l->in_stride);
    np_link_pack(j->want + i * l->out_stride, want, l->out_lane, l->n_out, l->out_stride);
}

/* FNV-1a, 64 bits: identity, not security (a journal is refused for other vectors). */
static uint64_t fnv1a(uint64_t h, const void *p, size_t n)
{
    const uint8_t *b = p;
    for (size_t k = 0; k < n; k++)
        h = (h ^ b[k]) * 0x100000001b3u;
    return h;
}

void np_link_job_seal(np_link_job *j)
{
    uint64_t h = 0xcbf29ce484222325u;
    uint8_t n8[8];
    h = fnv1a(h, j->unit->name, strlen(j->unit->name) + 1u);
    h = fnv1a(h, j->cfg_text, strlen(j->cfg_text) + 1u);
    np_link_put64(n8, j->n);
    h = fnv1a(h, n8, sizeof n8);
    h = fnv1a(h, j->in, (size_t)j->n * j->lay.in_stride);
    h = fnv1a(h, j->want, (size_t)j->n * j->lay.out_stride);
    j->hash = h;
}

int np_link_job_random(np_link_job *j, const np_unit *u, const void *cfg, uint64_t n,
                       uint64_t seed)
{
    if (np_link_job_init(j, u, cfg, n) != 0)
        return -1;
    np_rng r;
    np_rng_seed(&r, seed);
    uint64_t in[NP_UNIT_MAX_FIELDS] = { 0 }, out[NP_UNIT_MAX_FIELDS] = { 0 };
    for (uint64_t i = 0; i < n; i++) {
        for (unsigned k = 0; k < j->fields.n_in; k++) {
            unsigned b = j->fields.in[k].bits;
            in[k] = np_rng_next(&r) & np_link_mask(b);
        }
        u->eval(&j->cfg, in, out);
        np_link_job_set(j, i, in, out);
    }
    np_link_job_seal(j);
    return 0;
}

void np_link_job_free(np_link_job *j)
{
    free(j->in);
    free(j->want);
    free(j->line);
    j->in = j->want = NULL;
    j->line = NULL;
}
