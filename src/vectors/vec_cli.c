/* SPDX-License-Identifier: MIT */
/* vec_cli.c - option parsing shared by the vectors, verify, device and run commands. */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "np_common.h"
#include "np_vec.h"

int np_vec_is_help(const char *arg) { return strcmp(arg, "--help") == 0 || strcmp(arg, "-h") == 0; }

int np_vec_opt(const char *cmd, int argc, char **argv, int *i, const char *name,
               const char **val)
{
    const char *a = argv[*i];
    size_t n = strlen(name);
    if (strncmp(a, name, n) != 0)
        return 0;
    if (a[n] == '=') {
        *val = a + n + 1;
        return 1;
    }
    if (a[n] != '\0')
        return 0;
    if (*i + 1 >= argc) {
        np_err(cmd, "option %s needs a value (see noisepipe %s --help)", name, cmd);
        return -1;
    }
    *val = argv[++*i];
    return 1;
}

int np_vec_opt_u64(const char *cmd, const char *name, const char *val, uint64_t lo,
                   uint64_t hi, uint64_t *out)
{
    if (np_parse_u64(val, lo, hi, out) == 0)
        return 0;
    np_err(cmd, "%s '%s': expected a decimal number in %llu..%llu", name, val,
           (unsigned long long)lo, (unsigned long long)hi);
    return -1;
}

int np_vec_opt_double(const char *cmd, const char *name, const char *val, double *out)
{
    char *end;
    errno = 0;
    double v = strtod(val, &end);
    if (*val == '\0' || *end != '\0' || errno || !isfinite(v) || v < 0) {
        np_err(cmd, "%s '%s': expected a number >= 0", name, val);
        return -1;
    }
    *out = v;
    return 0;
}

int np_vec_opt_header(const char *cmd, const char *name, const char *spec, np_vec_header *h)
{
    char err[NP_VEC_ERRLEN];
    const np_unit *u = name ? np_unit_find(name) : NULL;
    if (!u) {
        char known[256];
        np_vec_unit_names(known, sizeof known);
        if (name)
            np_err(cmd, "unknown unit '%s' (units: %s)", name, known);
        else
            np_err(cmd, "--unit is required (units: %s)", known);
        return -1;
    }
    if (np_vec_header_init(h, u, spec, err, sizeof err) != 0) {
        np_err(cmd, "bad --config for unit %s: %s", u->name, err);
        return -1;
    }
    return 0;
}
