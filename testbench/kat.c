/* SPDX-License-Identifier: MIT */
/* Known-answer tables of any registered unit (np_kat.h). */
#include "np_kat.h"

#include <inttypes.h>
#include <stdlib.h>
#include <string.h>

#include "np_rng.h"
#include "np_stream.h"
#include "np_unit.h"
#include "np_vec.h"

typedef struct kat_row {
    uint64_t in[NP_UNIT_MAX_FIELDS];
    char note[128];
} kat_row;

int np_kat_parse(int argc, char **argv, const char *dir, np_kat_spec *s, char *err, size_t errlen)
{
    static char inputs_path[4096];
    memset(s, 0, sizeof *s);
    s->configs[s->n_configs++] = "";
    s->rows = NP_KAT_ROWS;
    size_t at = 0;
    for (int i = 0; i < argc; i++) {
        at += (size_t)snprintf(s->argv_text + at, at < sizeof s->argv_text ? sizeof s->argv_text - at : 0,
                               "%s%s", i ? " " : "", argv[i]);
        int has_val = i + 1 < argc;
        if (strcmp(argv[i], "--config") == 0 && has_val) {
            if (s->n_configs == NP_KAT_MAX_CONFIGS) {
                snprintf(err, errlen, "at most %d configurations", NP_KAT_MAX_CONFIGS - 1);
                return -1;
            }
            s->configs[s->n_configs++] = argv[i + 1];
        } else if (strcmp(argv[i], "--inputs") == 0 && has_val) {
            const char *p = argv[i + 1];
            if (dir && p[0] != '/')
                snprintf(inputs_path, sizeof inputs_path, "%s/%s", dir, p);
            else
                snprintf(inputs_path, sizeof inputs_path, "%s", p);
            s->inputs = inputs_path;
        } else if (strcmp(argv[i], "-n") == 0 && has_val) {
            unsigned n;
            if (np_unit_parse_uint(argv[i + 1], 1, NP_KAT_MAX_ROWS, &n) != 0) {
                snprintf(err, errlen, "-n %s: expected 1..%d", argv[i + 1], NP_KAT_MAX_ROWS);
                return -1;
            }
            s->rows = n;
        } else if (argv[i][0] != '-' && !s->unit) {
            s->unit = argv[i];
            continue;
        } else {
            snprintf(err, errlen, "unexpected argument '%s'", argv[i]);
            return -1;
        }
        i++;
        at += (size_t)snprintf(s->argv_text + at, at < sizeof s->argv_text ? sizeof s->argv_text - at : 0, " %s",
                               argv[i]);
    }
    if (!s->unit) {
        snprintf(err, errlen, "no unit named");
        return -1;
    }
    if (at >= sizeof s->argv_text) {
        snprintf(err, errlen, "arguments too long");
        return -1;
    }
    return 0;
}

/* Inputs and notes of an existing table: every line that opens with '{'. */
static int read_inputs(const char *path, unsigned n_in, kat_row *rows, unsigned *n, char *err, size_t errlen)
{
    FILE *f = fopen(path, "r");
    if (!f) {
        snprintf(err, errlen, "%s: cannot open", path);
        return -1;
    }
    char line[1024];
    *n = 0;
    while (fgets(line, sizeof line, f)) {
        if (line[0] != '{')
            continue;
        if (*n == NP_KAT_MAX_ROWS) {
            fclose(f);
            snprintf(err, errlen, "%s: more than %d rows", path, NP_KAT_MAX_ROWS);
            return -1;
        }
        kat_row *r = &rows[(*n)++];
        memset(r, 0, sizeof *r);
        char *p = line + 1;
        for (unsigned a = 0; a < n_in; a++) {
            char *end;
            r->in[a] = strtoull(p, &end, 0);
            if (end == p || (*end != ',' && *end != ' ')) {
                fclose(f);
                snprintf(err, errlen, "%s: row %u: input %u is not a number", path, *n, a);
                return -1;
            }
            p = end + 1;
        }
        char *c0 = strstr(p, "/*"), *c1 = c0 ? strstr(c0, "*/") : NULL;
        if (c0 && c1) {
            *c1 = '\0';
            char *semi = NULL;
            for (char *q = strstr(c0 + 2, "; "); q; q = strstr(q + 1, "; "))
                semi = q;
            if (semi) {
                *semi = '\0';
                const char *note = c0 + 2;
                while (*note == ' ')
                    note++;
                snprintf(r->note, sizeof r->note, "%s", note);
            }
        }
    }
    fclose(f);
    if (*n == 0) {
        snprintf(err, errlen, "%s: no rows", path);
        return -1;
    }
    return 0;
}

/* The unit's boundary table (its first two thirds of the rows), then random inputs. */
static void gen_inputs(const np_unit *u, const void *cfg, const np_unit_fields *fl, unsigned want, kat_row *rows,
                       unsigned *n)
{
    uint64_t (*b)[NP_UNIT_MAX_FIELDS] = calloc(want, sizeof *b);
    size_t nb = b ? u->boundary(cfg, b, want) : 0;
    unsigned take = want - want / 3u;
    *n = 0;
    memset(rows, 0, want * sizeof *rows);
    for (size_t i = 0; i < nb && *n < take; i++, (*n)++)
        memcpy(rows[*n].in, b[i], sizeof b[i]);
    free(b);
    np_rng r;
    np_rng_seed(&r, NP_KAT_SEED);
    for (; *n < want; (*n)++) {
        uint64_t *in = rows[*n].in;
        if (u->stream) { /* a valid descriptor and one of its beats */
            u->stream->random_desc(cfg, &r, in);
            uint64_t beats = u->stream->beats(cfg, in);
            in[u->stream->n_desc] = beats ? np_rng_below(&r, beats) : 0;
        } else {
            for (unsigned a = 0; a < fl->n_in; a++)
                in[a] = np_rng_next(&r) >> (64u - fl->in[a].bits);
        }
    }
}

/* Characters of the widest value of a field as printed: hex digits, or a decimal with its sign. */
static int dec_width(const np_field *f)
{
    char buf[32];
    if (f->is_signed)
        return snprintf(buf, sizeof buf, "-%" PRIu64, (uint64_t)1 << (f->bits - 1u));
    return snprintf(buf, sizeof buf, "%" PRIu64, np_vec_mask(f->bits));
}

static void put_value(FILE *out, const np_field *f, uint64_t w)
{
    if (f->is_signed && f->bits < 64 && (w >> (f->bits - 1u) & 1u))
        fprintf(out, "%*" PRId64, dec_width(f), -(int64_t)(((uint64_t)1 << f->bits) - w));
    else
        fprintf(out, "%*" PRIu64, dec_width(f), w);
}

int np_kat_write(const np_kat_spec *s, FILE *out, char *err, size_t errlen)
{
    const np_unit *u = np_unit_find(s->unit);
    if (!u) {
        snprintf(err, errlen, "unknown unit '%s'", s->unit);
        return -1;
    }
    np_vec_header *h = calloc(s->n_configs, sizeof *h);
    kat_row *rows = calloc(NP_KAT_MAX_ROWS, sizeof *rows);
    int rc = -1;
    unsigned n = 0;
    if (!h || !rows) {
        snprintf(err, errlen, "out of memory");
        goto done;
    }
    for (unsigned c = 0; c < s->n_configs; c++)
        if (np_vec_header_init(&h[c], u, s->configs[c], err, errlen) != 0)
            goto done;
    const np_unit_fields *f0 = &h[0].fields;
    if (s->inputs ? read_inputs(s->inputs, f0->n_in, rows, &n, err, errlen) != 0
                  : (gen_inputs(u, &h[0].cfg, f0, s->rows, rows, &n), 0))
        goto done;

    fprintf(out, "/* Generated by `gen_kat %s` (testbench/gen_kat.c); conformance.%s.kat regenerates it.\n",
            s->argv_text, u->name);
    fprintf(out, " * Known answers of unit %s. Columns: inputs", u->name);
    for (unsigned a = 0; a < f0->n_in; a++)
        fprintf(out, " %s", f0->in[a].name);
    for (unsigned c = 0; c < s->n_configs; c++) {
        fprintf(out, ", then [%u]", c);
        for (unsigned k = 0; k < h[c].fields.n_out; k++)
            fprintf(out, " %s (%s)", h[c].fields.out[k].name, h[c].fields.out[k].format);
    }
    fprintf(out, ";\n");
    for (unsigned c = 0; c < s->n_configs; c++)
        fprintf(out, " * [%u] %s%s\n", c, h[c].cfg_text, c ? "" : " (the default)");
    if (s->inputs)
        fprintf(out, " * Inputs chosen and annotated by hand (kept from the table itself).\n");
    else
        fprintf(out, " * Inputs: the unit's boundary table, then random ones (np_rng seed %d).\n", NP_KAT_SEED);
    fprintf(out, " * Comments: the note, then the float reference of [0]. */\n");

    for (unsigned i = 0; i < n; i++) {
        fputs("{ ", out);
        for (unsigned a = 0; a < f0->n_in; a++)
            fprintf(out, "%s0x%0*" PRIx64, a ? ", " : "", (int)((f0->in[a].bits + 3u) / 4u),
                    rows[i].in[a] & np_vec_mask(f0->in[a].bits));
        uint64_t refbits[NP_UNIT_MAX_FIELDS] = { 0 };
        for (unsigned c = 0; c < s->n_configs; c++) {
            uint64_t o[NP_UNIT_MAX_FIELDS], rb[NP_UNIT_MAX_FIELDS];
            np_vec_compute(&h[c], rows[i].in, o, rb);
            if (c == 0)
                memcpy(refbits, rb, sizeof rb);
            for (unsigned k = 0; k < h[c].fields.n_out; k++) {
                fputs(", ", out);
                put_value(out, &h[c].fields.out[k], o[k]);
            }
        }
        fputs(" }, /* ", out);
        if (rows[i].note[0])
            fprintf(out, "%s; ref ", rows[i].note);
        for (unsigned k = 0; k < f0->n_out; k++)
            fprintf(out, "%s%+.6f", k ? " " : "", np_vec_ref_value(refbits[k]));
        fputs(" */\n", out);
    }
    rc = ferror(out) ? -1 : 0;
    if (rc)
        snprintf(err, errlen, "write error");
done:
    free(h);
    free(rows);
    return rc;
}

void np_kat_dir_of(const char *path, char *dir, size_t len)
{
    const char *slash = strrchr(path, '/');
    if (slash)
        snprintf(dir, len, "%.*s", (int)(slash - path), path);
    else
        snprintf(dir, len, ".");
}

/* The whole file in memory (NUL-terminated), or NULL. */
static char *slurp(FILE *f, size_t *len)
{
    size_t cap = 1 << 16, n = 0, got;
    char *buf = malloc(cap + 1);
    while (buf && (got = fread(buf + n, 1, cap - n, f)) > 0) {
        n += got;
        if (n == cap) {
            char *nb = realloc(buf, 2 * cap + 1);
            if (!nb) {
                free(buf);
                return NULL;
            }
            buf = nb;
            cap *= 2;
        }
    }
    if (buf)
        buf[n] = '\0';
    *len = n;
    return buf;
}

int np_kat_check(const char *path, char *err, size_t errlen)
{
    FILE *f = fopen(path, "r");
    if (!f) {
        snprintf(err, errlen, "%s: cannot open", path);
        return -1;
    }
    size_t n_old = 0;
    char *old = slurp(f, &n_old);
    fclose(f);
    const char *tag = "/* Generated by `gen_kat ";
    char *args = old && strncmp(old, tag, strlen(tag)) == 0 ? old + strlen(tag) : NULL;
    char *tick = args ? strchr(args, '`') : NULL;
    if (!tick) {
        snprintf(err, errlen, "%s: the first line does not say `gen_kat ...`", path);
        free(old);
        return -1;
    }
    char cmd[512];
    snprintf(cmd, sizeof cmd, "%.*s", (int)(tick - args), args);
    char *argv[32];
    int argc = 0;
    for (char *save = NULL, *t = strtok_r(cmd, " ", &save); t && argc < 32; t = strtok_r(NULL, " ", &save))
        argv[argc++] = t;
    char dir[4096];
    np_kat_dir_of(path, dir, sizeof dir);
    const char *base = strrchr(path, '/') ? strrchr(path, '/') + 1 : path;
    np_kat_spec s;
    int rc = -1;
    FILE *tmp = NULL;
    char *now = NULL;
    size_t n_now = 0;
    if (np_kat_parse(argc, argv, dir, &s, err, errlen) != 0)
        goto done;
    if (!(tmp = tmpfile())) {
        snprintf(err, errlen, "no temporary file");
        goto done;
    }
    if (np_kat_write(&s, tmp, err, errlen) != 0)
        goto done;
    rewind(tmp);
    if (!(now = slurp(tmp, &n_now))) {
        snprintf(err, errlen, "out of memory");
        goto done;
    }
    rc = 0;
    if (n_now != n_old || memcmp(now, old, n_old) != 0) {
        unsigned line = 1;
        for (size_t i = 0; i < n_old && i < n_now && old[i] == now[i]; i++)
            line += old[i] == '\n';
        snprintf(err, errlen, "%s differs from its regeneration from line %u on (refresh: cd %s && gen_kat %.*s -o %s)",
                 path, line, dir, (int)(tick - args), args, base);
        rc = 1;
    }
done:
    if (tmp)
        fclose(tmp);
    free(now);
    free(old);
    return rc;
}
