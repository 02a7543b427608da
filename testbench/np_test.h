/* SPDX-License-Identifier: MIT */
/*
 * np_test.h - the tiny harness every test program uses. A program holds a
 * table of named cases; `prog CASE` runs one (CTest registers each by name,
 * so `ctest -R area.case` runs one), `prog` alone lists them.
 * NP_CHECK records a failure with file:line and goes on; a case fails when
 * any check failed. Cases print what they measured.
 */
#ifndef NP_TEST_H
#define NP_TEST_H

#include <stdio.h>
#include <string.h>

typedef int (*np_test_fn)(void);
typedef struct np_test_case {
    const char *name;
    np_test_fn fn;
} np_test_case;

extern int np_test_failures;

/* A case returns NP_TEST_SKIP when a tool it needs is missing (CTest SKIP_RETURN_CODE). */
enum { NP_TEST_SKIP = 77 };

#define NP_CHECK(cond, ...)                                                                    \
    do {                                                                                       \
        if (!(cond)) {                                                                         \
            np_test_failures++;                                                                \
            if (np_test_failures <= 20) {                                                      \
                fprintf(stderr, "%s:%d: check failed: %s: ", __FILE__, __LINE__, #cond);        \
                fprintf(stderr, __VA_ARGS__);                                                  \
                fputc('\n', stderr);                                                           \
            }                                                                                  \
        }                                                                                      \
    } while (0)

/* Defines main() running the named case of a NULL-terminated table. */
#define NP_TEST_MAIN(table)                                                                    \
    int np_test_failures = 0;                                                                  \
    int main(int argc, char **argv)                                                            \
    {                                                                                          \
        if (argc < 2) {                                                                        \
            for (const np_test_case *c = (table); c->name; c++)                                \
                puts(c->name);                                                                 \
            return 0;                                                                          \
        }                                                                                      \
        for (const np_test_case *c = (table); c->name; c++)                                    \
            if (strcmp(c->name, argv[1]) == 0) {                                               \
                int rc = c->fn();                                                              \
                if (np_test_failures)                                                          \
                    fprintf(stderr, "%s: %d check(s) failed\n", c->name, np_test_failures);    \
                if (rc == NP_TEST_SKIP && !np_test_failures)                                   \
                    return NP_TEST_SKIP;                                                       \
                return rc || np_test_failures ? 1 : 0;                                         \
            }                                                                                  \
        fprintf(stderr, "unknown case '%s'\n", argv[1]);                                       \
        return 2;                                                                              \
    }

#endif /* NP_TEST_H */
