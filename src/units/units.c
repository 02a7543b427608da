/* SPDX-License-Identifier: MIT */
#include "np_unit.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

extern const np_unit np_unit_classic3;
extern const np_unit np_unit_simplex3;

extern const np_unit np_unit_fdiff, np_unit_texel;

const np_unit *const np_units[] = { &np_unit_classic3, &np_unit_simplex3, &np_unit_fdiff, &np_unit_texel, NULL };

/* Units added by np_unit_register (see np_unit.h: filled before threads start, read-only after). */
static const np_unit *registered[NP_UNIT_MAX_REGISTERED];
static size_t n_registered;

static size_t n_builtin(void)
{
    size_t n = 0;
    while (np_units[n])
        n++;
    return n;
}

const np_unit *np_unit_at(size_t i)
{
    size_t nb = n_builtin();
    if (i < nb)
        return np_units[i];
    return i - nb < n_registered ? registered[i - nb] : NULL;
}

const np_unit *np_unit_find(const char *name)
{
    const np_unit *u;
    for (size_t i = 0; (u = np_unit_at(i)) != NULL; i++)
        if (strcmp(u->name, name) == 0)
            return u;
    return NULL;
}

int np_unit_register(const np_unit *u)
{
    /* The entries every tool calls without checking; the rest are optional (np_unit.h). */
    int complete = u && u->name && u->name[0] && u->cfg_default && u->cfg_set && u->cfg_format &&
                   u->cfg_check && u->fields && u->eval && u->ref && u->error_bound_lsb &&
                   (u->stream || (u->pipe_init && u->sig_set_in && u->sig_get_out)) && u->boundary;
    if (!complete || np_unit_find(u->name) || n_registered >= NP_UNIT_MAX_REGISTERED)
        return -1;
    registered[n_registered++] = u;
    return 0;
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
