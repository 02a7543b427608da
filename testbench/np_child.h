/* SPDX-License-Identifier: MIT */
/*
 * np_child.h - start a program in a child process with its standard output
 * and error in files: how test_link and test_link_usb run `noisepipe stream`;
 * the seed of a run that kills it at a random moment.
 */
#ifndef NP_CHILD_H
#define NP_CHILD_H

#include <fcntl.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
#include <unistd.h>

/* fork + execv(argv[0], argv), stdout to out, stderr to err; the child's pid (-1 when fork failed). */
static inline pid_t np_child_start(char *const *argv, const char *out, const char *err)
{
    fflush(NULL);
    pid_t pid = fork();
    if (pid == 0) {
        int fo = open(out, O_WRONLY | O_CREAT | O_TRUNC, 0644), fe = open(err, O_WRONLY | O_CREAT | O_TRUNC, 0644);
        dup2(fo, 1);
        dup2(fe, 2);
        execv(argv[0], argv);
        _exit(127);
    }
    return pid;
}

/* The seed of a kill-and-resume run: NP_TEST_SEED, else the clock; printed, so the run can be repeated. */
static inline uint64_t np_child_seed(void)
{
    const char *s = getenv("NP_TEST_SEED");
    uint64_t seed;
    if (s) {
        seed = strtoull(s, NULL, 0);
    } else {
        struct timespec ts;
        clock_gettime(CLOCK_REALTIME, &ts);
        seed = (uint64_t)ts.tv_nsec ^ (uint64_t)ts.tv_sec;
    }
    printf("seed %llu (NP_TEST_SEED=%llu repeats this run)\n", (unsigned long long)seed, (unsigned long long)seed);
    return seed;
}

#endif /* NP_CHILD_H */
