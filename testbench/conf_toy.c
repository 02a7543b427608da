/* SPDX-License-Identifier: MIT */
/* A run-time-registered unit's golden files, verify and conformance run (np_conformance.h). */
#include "np_conformance.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "np_kat.h"
#include "np_test.h"
#include "np_vec.h"

static const char *with(const char *base, const char *ext, char *buf, size_t len)
{
    snprintf(buf, len, "%s%s", base, ext);
    return buf;
}

int np_conf_toy_generate(np_conf_toy *t, const np_unit *u, const char *work, const char *tag, const char *kat_cfg)
{
    memset(t, 0, sizeof *t);
    t->u = u;
    snprintf(t->dir, sizeof t->dir, "%s/%s-%s", work, u->name, tag);
    snprintf(t->set, sizeof t->set, "%s/%s/%s-l1-seed1", t->dir, u->name, u->name);
    t->env = (np_conf_env){ t->dir, t->dir, t->dir };
    np_vec_header h;
    char err[NP_VEC_ERRLEN], cmd[4400], vec[4500], memh[4500], kat[4500];
    if (np_vec_header_init(&h, u, NULL, err, sizeof err) != 0) {
        NP_CHECK(0, "%s", err);
        return 1;
    }
    snprintf(cmd, sizeof cmd, "mkdir -p '%s/%s'", t->dir, u->name);
    NP_CHECK(system(cmd) == 0, "%s", cmd);
    np_vec_output o[2] = { { with(t->set, ".vec", vec, sizeof vec), NP_VEC_TEXT },
                           { with(t->set, ".memh", memh, sizeof memh), NP_VEC_READMEMH } };
    int rc = np_vec_generate(&h, 1, 1, UINT64_MAX, o, 2, err, sizeof err);
    NP_CHECK(rc == 0, "vectors: %s", err);
    snprintf(t->sources, sizeof t->sources, "%s", h.sources);
    char *argv[] = { (char *)u->name, "--config", (char *)kat_cfg };
    np_kat_spec s;
    snprintf(kat, sizeof kat, "%s/%s_kat.inc", t->dir, u->name);
    FILE *f = fopen(kat, "w");
    NP_CHECK(f && np_kat_parse(3, argv, NULL, &s, err, sizeof err) == 0 && np_kat_write(&s, f, err, sizeof err) == 0,
             "kat: %s", err);
    if (f)
        fclose(f);
    return rc != 0 || np_test_failures ? 1 : 0;
}

int np_conf_toy_open(const np_conf_toy *t, np_vec_reader *r)
{
    char vec[4500];
    int rc = np_vec_open(r, with(t->set, ".vec", vec, sizeof vec));
    NP_CHECK(rc == 0, "%s", r->L.err);
    return rc != 0;
}

/* Flip the low bit of the first output field's last hex digit (after the n_in input fields). */
static void flip_output_bit(char *line, unsigned n_in)
{
    char *p = line;
    for (unsigned f = 0; f < n_in && p; f++)
        if ((p = strchr(p, ' ')) != NULL)
            p++;
    if (!p)
        return;
    p += strcspn(p, " \n") - 1u;
    static const char hex[] = "0123456789abcdef";
    const char *d = strchr(hex, *p);
    if (d && *p)
        *p = hex[(unsigned)(d - hex) ^ 1u];
}

int np_conf_toy_verify(const np_conf_toy *t)
{
    char vec[4500], bad[4500];
    np_verify_opts o = { "verify", 10, -1.0, 1, 1, NULL };
    int rc = np_verify(with(t->set, ".vec", vec, sizeof vec), &o, stdout);
    NP_CHECK(rc == 0, "verify of %s: %d", vec, rc);
    /* A wrong expected output in one vector must fail the run. */
    snprintf(bad, sizeof bad, "%s/bad.vec", t->dir);
    FILE *in = fopen(vec, "r"), *out = fopen(bad, "w");
    np_unit_fields fields;
    np_unit_cfg cfg;
    np_unit_cfg_default(t->u, &cfg);
    t->u->fields(&cfg, &fields);
    char line[1024];
    int changed = 0;
    while (in && out && fgets(line, sizeof line, in)) {
        if (line[0] != '#' && !changed++)
            flip_output_bit(line, fields.n_in);
        fputs(line, out);
    }
    if (in)
        fclose(in);
    if (out)
        fclose(out);
    FILE *sink = tmpfile();
    NP_CHECK(changed && np_verify(bad, &o, sink ? sink : stdout) == 1, "a wrong output bit was not caught");
    if (sink)
        fclose(sink);
    printf("%s: its vectors verify through its cycle model with random stalls; a flipped output bit fails\n",
           t->u->name);
    return np_test_failures ? 1 : 0;
}

int np_conf_toy_conformance(const np_conf_toy *t)
{
    for (const np_conf_check *c = np_conf_checks; c->name; c++) {
        int before = np_test_failures;
        int rc = c->fn(t->u, &t->env);
        NP_CHECK(rc == 0, "conformance check %s: %d (a skip fails here)", c->name, rc);
        printf("== conformance.%s.%s: %s\n", t->u->name, c->name,
               np_test_failures == before && rc == 0 ? "pass" : "FAIL");
    }
    return np_test_failures ? 1 : 0;
}
