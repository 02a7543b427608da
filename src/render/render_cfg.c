/* SPDX-License-Identifier: MIT */
/* The renderer's unit configurations as text (np_render.h). */
#include "np_render.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "np_cli.h"

/* --- Unit configurations as text --- */

typedef struct cfg_key {
    const char *name;
    size_t off; /* offset of the unsigned field */
    unsigned lo, hi;
} cfg_key;

static const cfg_key fdiff_keys[] = {
    { "idx_int", offsetof(np_fdiff_cfg, idx_int), 1, 11 },
    { "w_frac", offsetof(np_fdiff_cfg, w_frac), 1, 24 },
    { "guard", offsetof(np_fdiff_cfg, guard), 0, NP_FDIFF_GUARD_MAX },
    { "resetup", offsetof(np_fdiff_cfg, resetup), 0, NP_TEX_SPAN_MAX },
    { "setup_mults", offsetof(np_fdiff_cfg, setup_mults), 1, NP_FDIFF_MULTS_MAX },
    { "mult_lat", offsetof(np_fdiff_cfg, mult_lat), 1, NP_FDIFF_LAT_MAX },
    { NULL, 0, 0, 0 },
};

static const cfg_key texel_keys[] = {
    { "idx_int", offsetof(np_texel_cfg, idx_int), 1, 11 },
    { "w_frac", offsetof(np_texel_cfg, w_frac), 1, 24 },
    { "guard", offsetof(np_texel_cfg, guard), 0, 100 },
    { "weight_frac", offsetof(np_texel_cfg, weight_frac), NP_TEXEL_WT_MIN, NP_TEXEL_WT_MAX },
    { "setup_mults", offsetof(np_texel_cfg, setup_mults), 1, 64 },
    { "mult_lat", offsetof(np_texel_cfg, mult_lat), 1, 16 },
    { NULL, 0, 0, 0 },
};

static int cfg_parse(const char *unit, const cfg_key *keys, void *cfg, const char *spec, char *err, size_t errlen)
{
    char buf[512];
    if (!spec || !*spec)
        return 0;
    if (strlen(spec) >= sizeof buf) {
        snprintf(err, errlen, "%s configuration too long", unit);
        return -1;
    }
    strcpy(buf, spec);
    for (char *save = NULL, *tok = strtok_r(buf, ", ", &save); tok; tok = strtok_r(NULL, ", ", &save)) {
        char *eq = strchr(tok, '=');
        if (!eq) {
            snprintf(err, errlen, "%s configuration '%s': expected key=value", unit, tok);
            return -1;
        }
        *eq = '\0';
        const cfg_key *k = keys;
        while (k->name && strcmp(k->name, tok) != 0)
            k++;
        if (!k->name) {
            char list[256] = "";
            for (const cfg_key *q = keys; q->name; q++)
                snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", q == keys ? "" : ", ", q->name);
            snprintf(err, errlen, "unknown %s configuration key '%s' (keys: %s)", unit, tok, list);
            return -1;
        }
        uint64_t v;
        if (np_parse_u64(eq + 1, k->lo, k->hi, &v)) {
            snprintf(err, errlen, "%s configuration %s=%s: expected an integer in %u..%u", unit, tok, eq + 1, k->lo,
                     k->hi);
            return -1;
        }
        *(unsigned *)(void *)((char *)cfg + k->off) = (unsigned)v;
    }
    return 0;
}

static void cfg_format(const cfg_key *keys, const void *cfg, char *buf, size_t len)
{
    size_t n = 0;
    buf[0] = '\0';
    for (const cfg_key *k = keys; k->name && n < len; k++) {
        int w = snprintf(buf + n, len - n, "%s%s=%u", k == keys ? "" : ",", k->name,
                         *(const unsigned *)(const void *)((const char *)cfg + k->off));
        if (w < 0)
            break;
        n += (size_t)w;
    }
}

int np_render_fdiff_cfg_parse(np_fdiff_cfg *c, const char *spec, char *err, size_t errlen)
{
    *c = np_fdiff_cfg_default();
    if (cfg_parse("fdiff", fdiff_keys, c, spec, err, errlen))
        return -1;
    const char *why = np_fdiff_cfg_check(c);
    if (why) {
        snprintf(err, errlen, "fdiff configuration: %s", why);
        return -1;
    }
    return 0;
}

void np_render_fdiff_cfg_format(const np_fdiff_cfg *c, char *buf, size_t len) { cfg_format(fdiff_keys, c, buf, len); }

int np_render_texel_cfg_parse(np_texel_cfg *c, const char *spec, char *err, size_t errlen)
{
    *c = np_texel_cfg_default();
    if (cfg_parse("texel", texel_keys, c, spec, err, errlen))
        return -1;
    const char *why = np_texel_cfg_check(c);
    if (why) {
        snprintf(err, errlen, "texel configuration: %s", why);
        return -1;
    }
    return 0;
}

void np_render_texel_cfg_format(const np_texel_cfg *c, char *buf, size_t len) { cfg_format(texel_keys, c, buf, len); }

