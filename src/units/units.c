/* SPDX-License-Identifier: MIT */
#include "np_unit.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

extern const np_unit np_unit_classic3;
extern const np_unit np_unit_aacount;
extern const np_unit np_unit_simplex3;
extern const np_unit np_unit_wave;

extern const np_unit np_unit_fdiff, np_unit_texel;
extern const np_unit np_unit_hatch;

/* Noise in n = 2..5 dimensions (docs/noise-nd.md); n = 3 is classic3 and simplex3. */
extern const np_unit np_unit_classic2, np_unit_classic4, np_unit_classic5;
extern const np_unit np_unit_simplex2, np_unit_simplex4, np_unit_simplex5;

const np_unit *const np_units[] = { &np_unit_classic3, &np_unit_simplex3, &np_unit_fdiff, &np_unit_texel,
                                    &np_unit_aacount,  &np_unit_wave,
                                    &np_unit_classic2, &np_unit_classic4, &np_unit_classic5,
                                    &np_unit_simplex2, &np_unit_simplex4, &np_unit_simplex5, &np_unit_hatch, NULL };

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
    int complete = u && u->name && u->name[0] && u->keys && u->fields && u->eval && u->ref && u->error_bound_lsb &&
                   (u->stream || (u->pipe_init && u->sig_set_in && u->sig_get_out)) && u->boundary;
    if (!complete || np_unit_find(u->name) || n_registered >= NP_UNIT_MAX_REGISTERED)
        return -1;
    registered[n_registered++] = u;
    return 0;
}

void np_unit_eval_n_generic(const np_unit *u, const void *cfg, const uint64_t *in, uint64_t *out, size_t n)
{
    np_unit_fields f;
    u->fields(cfg, &f);
    for (size_t i = 0; i < n; i++) {
        uint64_t a[NP_UNIT_MAX_FIELDS], b[NP_UNIT_MAX_FIELDS];
        for (unsigned k = 0; k < f.n_in; k++)
            a[k] = in[k * n + i];
        u->eval(cfg, a, b);
        for (unsigned k = 0; k < f.n_out; k++)
            out[k * n + i] = b[k];
    }
}

void np_unit_eval_n(const np_unit *u, const void *cfg, const uint64_t *in, uint64_t *out, size_t n)
{
    if (u->eval_n)
        u->eval_n(cfg, in, out, n);
    else
        np_unit_eval_n_generic(u, cfg, in, out, n);
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

int np_unit_parse_uint(const char *v, unsigned lo, unsigned hi, unsigned *out)
{
    /* Digits only, so "010" is ten and "0x5", "+3", " 3", "", "3abc" are refused (strtoul takes several). */
    unsigned long long n = 0;
    if (*v == '\0')
        return -1;
    for (const char *p = v; *p; p++) {
        if (*p < '0' || *p > '9')
            return -1;
        n = n * 10u + (unsigned)(*p - '0');
        if (n > hi)
            return -1;
    }
    if (n < lo)
        return -1;
    *out = (unsigned)n;
    return 0;
}

const np_unit_key *np_unit_key_find(const np_unit *u, const char *name)
{
    for (const np_unit_key *k = u->keys; k && k->name; k++)
        if (strcmp(k->name, name) == 0)
            return k;
    return NULL;
}

size_t np_unit_key_count(const np_unit *u)
{
    size_t n = 0;
    while (u->keys && u->keys[n].name)
        n++;
    return n;
}

unsigned np_unit_key_get(const np_unit_key *k, const void *cfg)
{
    const unsigned char *p = (const unsigned char *)cfg + k->offset;
    uint8_t v8;
    uint16_t v16;
    uint32_t v32;
    uint64_t v64;
    switch (k->size) {
    case 1: memcpy(&v8, p, sizeof v8); return v8;
    case 2: memcpy(&v16, p, sizeof v16); return v16;
    case 4: memcpy(&v32, p, sizeof v32); return v32;
    default: memcpy(&v64, p, sizeof v64); return (unsigned)v64;
    }
}

void np_unit_key_put(const np_unit_key *k, void *cfg, unsigned v)
{
    unsigned char *p = (unsigned char *)cfg + k->offset;
    uint8_t v8 = (uint8_t)v;
    uint16_t v16 = (uint16_t)v;
    uint32_t v32 = (uint32_t)v;
    uint64_t v64 = v;
    switch (k->size) {
    case 1: memcpy(p, &v8, sizeof v8); break;
    case 2: memcpy(p, &v16, sizeof v16); break;
    case 4: memcpy(p, &v32, sizeof v32); break;
    default: memcpy(p, &v64, sizeof v64); break;
    }
}

/* Append "%s%s" of a, b to buf (always terminated, truncated when full). */
static void put(char *buf, size_t len, const char *a, const char *b)
{
    size_t n = strlen(buf);
    if (n + 1 < len)
        snprintf(buf + n, len - n, "%s%s", a, b);
}

/* An enumeration's words from lo, joined by sep: up to hi, or (all) every one word() names. */
static void words(const np_unit_key *k, int all, const char *sep, char *buf, size_t len)
{
    buf[0] = '\0';
    for (unsigned v = k->lo; (all || v <= k->hi) && k->word(v); v++)
        put(buf, len, v == k->lo ? "" : sep, k->word(v));
}

void np_unit_key_range(const np_unit_key *k, char *buf, size_t len)
{
    if (k->word)
        words(k, 0, "|", buf, len);
    else
        snprintf(buf, len, "%u..%u", k->lo, k->hi);
}

void np_unit_key_text(const np_unit_key *k, const void *cfg, char *buf, size_t len)
{
    unsigned v = np_unit_key_get(k, cfg);
    const char *w = k->word ? k->word(v) : NULL;
    if (w)
        snprintf(buf, len, "%s", w);
    else
        snprintf(buf, len, "%u", v);
}

void np_unit_cfg_default(const np_unit *u, void *cfg)
{
    memset(cfg, 0, NP_UNIT_CFG_MAX);
    for (const np_unit_key *k = u->keys; k && k->name; k++)
        if (!k->derive)
            np_unit_key_put(k, cfg, k->def);
    for (const np_unit_key *k = u->keys; k && k->name; k++)
        if (k->derive)
            np_unit_key_put(k, cfg, k->derive(cfg));
}

/* "unknown configuration key 'K' for unit U (keys: a, b, c)". */
static int unknown_key(const np_unit *u, const char *key, char *err, size_t errlen)
{
    char list[512] = "";
    for (const np_unit_key *k = u->keys; k && k->name; k++)
        put(list, sizeof list, k == u->keys ? "" : ", ", k->name);
    snprintf(err, errlen, "unknown configuration key '%s' for unit %s (keys: %s)", key, u->name, list);
    return -1;
}

int np_unit_cfg_set(const np_unit *u, void *cfg, const char *key, const char *value, char *err, size_t errlen)
{
    const np_unit_key *k = np_unit_key_find(u, key);
    if (!k)
        return unknown_key(u, key, err, errlen);
    unsigned v;
    if (k->word) {
        for (v = k->lo; k->word(v); v++)
            if (strcmp(k->word(v), value) == 0) {
                np_unit_key_put(k, cfg, v);
                return 0;
            }
        char list[512];
        words(k, 1, ", ", list, sizeof list);
        snprintf(err, errlen, "%s=%s: expected one of %s", key, value, list);
        return -1;
    }
    if (np_unit_parse_uint(value, k->lo, k->hi, &v) != 0) {
        /* Say which: not a number at all, or a number out of the key's range. */
        int digits = *value != '\0';
        for (const char *p = value; *p; p++)
            digits &= *p >= '0' && *p <= '9';
        snprintf(err, errlen, "%s=%s: %s: expected a decimal integer in %u..%u", key, value,
                 digits ? "out of range" : "not a number", k->lo, k->hi);
        return -1;
    }
    np_unit_key_put(k, cfg, v);
    return 0;
}

void np_unit_cfg_format_opt(const np_unit *u, const void *cfg, unsigned how, char *buf, size_t len)
{
    const char *sep = how & NP_UNIT_FMT_COMMAS ? "," : " ";
    int first = 1;
    buf[0] = '\0';
    for (const np_unit_key *k = u->keys; k && k->name; k++) {
        if ((how & NP_UNIT_FMT_NO_SCENE) && (k->flags & NP_UNIT_KEY_SCENE))
            continue;
        if ((k->flags & NP_UNIT_KEY_ADDED) && !k->derive && np_unit_key_get(k, cfg) == k->def)
            continue;
        char v[96];
        np_unit_key_text(k, cfg, v, sizeof v);
        put(buf, len, first ? "" : sep, k->name);
        put(buf, len, "=", v);
        first = 0;
    }
}

void np_unit_cfg_format(const np_unit *u, const void *cfg, char *buf, size_t len)
{
    np_unit_cfg_format_opt(u, cfg, 0, buf, len);
}

enum { MAX_KEYS = 64 };

static int configure(const np_unit *u, void *cfg, const char *spec, int all, char *err, size_t errlen)
{
    unsigned char given[MAX_KEYS] = { 0 };
    size_t n_keys = np_unit_key_count(u);
    if (n_keys > MAX_KEYS) {
        snprintf(err, errlen, "unit %s: more than %d configuration keys", u->name, MAX_KEYS);
        return -1;
    }
    np_unit_cfg_default(u, cfg);
    if (spec && *spec) {
        char buf[512];
        if (strlen(spec) >= sizeof buf) {
            snprintf(err, errlen, "configuration too long");
            return -1;
        }
        strcpy(buf, spec);
        for (char *save = NULL, *tok = strtok_r(buf, ", ", &save); tok; tok = strtok_r(NULL, ", ", &save)) {
            char *eq = strchr(tok, '=');
            if (!eq) {
                snprintf(err, errlen, "'%s': expected key=value", tok);
                return -1;
            }
            *eq = '\0';
            if (np_unit_cfg_set(u, cfg, tok, eq + 1, err, errlen) != 0)
                return -1;
            size_t i = (size_t)(np_unit_key_find(u, tok) - u->keys);
            if (given[i]) {
                snprintf(err, errlen, "key %s given twice", tok);
                return -1;
            }
            given[i] = 1;
        }
    }
    for (size_t i = 0; i < n_keys; i++) {
        const np_unit_key *k = &u->keys[i];
        if (all && !given[i] && !(k->flags & NP_UNIT_KEY_ADDED)) {
            snprintf(err, errlen, "key %s missing (a '# config' line gives every key of unit %s once)", k->name,
                     u->name);
            return -1;
        }
        if (k->derive && !given[i])
            np_unit_key_put(k, cfg, k->derive(cfg));
    }
    const char *why = u->cfg_check ? u->cfg_check(cfg) : NULL;
    if (why) {
        snprintf(err, errlen, "%s", why);
        return -1;
    }
    return 0;
}

int np_unit_configure(const np_unit *u, void *cfg, const char *spec, char *err, size_t errlen)
{
    return configure(u, cfg, spec, 0, err, errlen);
}

int np_unit_configure_all(const np_unit *u, void *cfg, const char *spec, char *err, size_t errlen)
{
    return configure(u, cfg, spec, 1, err, errlen);
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

void np_unit_set_reg(np_unit_reg *r, const char *name, unsigned bits, uint64_t value, const char *fmt)
{
    snprintf(r->name, sizeof r->name, "%s", name);
    r->bits = bits;
    r->value = bits >= 64u ? value : value & ((UINT64_C(1) << bits) - 1u);
    snprintf(r->format, sizeof r->format, "%s", fmt);
}
