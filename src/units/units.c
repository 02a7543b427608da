/* SPDX-License-Identifier: MIT */
#include "np_unit.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

extern const np_unit np_unit_classic3;
extern const np_unit np_unit_simplex3;

extern const np_unit np_unit_fdiff, np_unit_texel;

const np_unit *const np_units[] = { &np_unit_classic3, &np_unit_simplex3, &np_unit_fdiff, &np_unit_texel, NULL };

const np_unit *np_unit_find(const char *name)
{
    for (size_t i = 0; np_units[i]; i++)
        if (strcmp(np_units[i]->name, name) == 0)
            return np_units[i];
    return NULL;
}

double np_unit_field_value(const np_field *f, uint64_t word)
{
    double scale = 1.0;
    for (unsigned i = 0; i < f->frac; i++)
        scale *= 0.5;
    if (f->is_signed && f->bits < 64 && (word >> (f->bits - 1u) & 1u)) {
        uint64_t mag = ((uint64_t)1 << f->bits) - word; /* two's complement magnitude */
        return -(double)mag * scale;
    }
    return (double)word * scale;
}

int np_unit_configure(const np_unit *u, void *cfg, const char *spec, char *err, size_t errlen)
{
    u->cfg_default(cfg);
    return np_unit_configure_over(u, cfg, spec, err, errlen);
}

int np_unit_configure_over(const np_unit *u, void *cfg, const char *spec, char *err, size_t errlen)
{
    if (spec && *spec) {
        char buf[512];
        if (strlen(spec) >= sizeof buf) {
            snprintf(err, errlen, "configuration too long");
            return -1;
        }
        strcpy(buf, spec);
        for (char *save = NULL, *tok = strtok_r(buf, ", ", &save); tok;
             tok = strtok_r(NULL, ", ", &save)) {
            char *eq = strchr(tok, '=');
            if (!eq) {
                snprintf(err, errlen, "'%s': expected key=value", tok);
                return -1;
            }
            *eq = '\0';
            if (u->cfg_set(cfg, tok, eq + 1, err, errlen) != 0)
                return -1;
        }
    }
    const char *why = u->cfg_check(cfg);
    if (why) {
        snprintf(err, errlen, "%s", why);
        return -1;
    }
    return 0;
}

int np_unit_parse_uint(const char *v, unsigned lo, unsigned hi, unsigned *out)
{
    char *end;
    unsigned long n = strtoul(v, &end, 10);
    if (*v == '\0' || *end != '\0' || *v == '-' || n < lo || n > hi)
        return -1;
    *out = (unsigned)n;
    return 0;
}

void np_unit_set_field(np_field *f, const char *name, unsigned bits, int sgn, unsigned frac,
                       const char *fmt)
{
    snprintf(f->name, sizeof f->name, "%s", name);
    f->bits = bits;
    f->is_signed = sgn;
    f->frac = frac;
    snprintf(f->format, sizeof f->format, "%s", fmt);
}
