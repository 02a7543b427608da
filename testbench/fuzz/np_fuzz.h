/* SPDX-License-Identifier: MIT */
/*
 * np_fuzz.h - what the libFuzzer harnesses share (docs/fuzzing.md).
 *
 * Each harness defines LLVMFuzzerTestOneInput. Built with clang
 * -fsanitize=fuzzer it is a libFuzzer target; built with any compiler and
 * replay_main.c it replays a corpus (files or folders given as arguments),
 * which is how the checked-in corpora run in every build, sanitizers included.
 * A harness treats a rejected input (the library's -1 with a message) as
 * success: only a crash, a sanitizer finding, a hang or a violated invariant
 * (np_fuzz_assert) is a finding.
 */
#ifndef NP_FUZZ_H
#define NP_FUZZ_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* An invariant the code promises; a violation aborts, which the fuzzer reports with the input. */
#define np_fuzz_assert(c)                                                                      \
    do {                                                                                       \
        if (!(c)) {                                                                            \
            fprintf(stderr, "%s:%d: invariant violated: %s\n", __FILE__, __LINE__, #c);        \
            abort();                                                                           \
        }                                                                                      \
    } while (0)

/*
 * Write data to this process's scratch file (the readers take paths) and
 * return its path; NULL if it cannot be written.
 */
const char *np_fuzz_file(const uint8_t *data, size_t size);

#endif /* NP_FUZZ_H */
