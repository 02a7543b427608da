/* SPDX-License-Identifier: MIT */
/*
 * The unit-conformance test: every check of np_conformance.h on every unit
 * of the registry. `test_conformance` lists the cases as UNIT.CHECK (the
 * build registers each in CTest as conformance.UNIT.CHECK from that list,
 * testbench/conformance.cmake), `test_conformance UNIT.CHECK` runs one.
 * A unit added to the registry gets every case without an edit here.
 */
#include <stdio.h>
#include <string.h>

#include "np_conformance.h"
#include "np_test.h"

int np_test_failures = 0;

int main(int argc, char **argv)
{
    const np_unit *u;
    if (argc < 2) {
        for (size_t i = 0; (u = np_unit_at(i)) != NULL; i++)
            for (const np_conf_check *c = np_conf_checks; c->name; c++)
                printf("%s.%s\n", u->name, c->name);
        return 0;
    }
    const char *dot = strrchr(argv[1], '.');
    char unit[64];
    snprintf(unit, sizeof unit, "%.*s", dot ? (int)(dot - argv[1]) : 0, argv[1]);
    const np_conf_check *c = dot ? np_conf_find(dot + 1) : NULL;
    if (!c || !(u = np_unit_find(unit))) {
        fprintf(stderr, "unknown case '%s' (UNIT.CHECK; run without arguments for the list)\n", argv[1]);
        return 2;
    }
    const np_conf_env env = { NP_VEC_DIR, NP_KAT_DIR, NP_CONF_WORK };
    int rc = c->fn(u, &env);
    if (np_test_failures)
        fprintf(stderr, "%s: %d check(s) failed\n", argv[1], np_test_failures);
    if (rc == NP_TEST_SKIP && !np_test_failures)
        return NP_TEST_SKIP;
    return rc || np_test_failures ? 1 : 0;
}
