/* SPDX-License-Identifier: MIT */
#include "np_cli.h"

#include <errno.h>
#include <stdarg.h>
#include <stdlib.h>
#include <time.h>
#include <unistd.h>

void np_err(const char *cmd, const char *fmt, ...)
{
    va_list ap;
    fprintf(stderr, "noisepipe %s: ", cmd);
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fputc('\n', stderr);
}

int np_errf(char *err, size_t errlen, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err, errlen, fmt, ap);
    va_end(ap);
    return -1;
}

int np_parse_u64(const char *s, uint64_t lo, uint64_t hi, uint64_t *out)
{
    char *end;
    if (!s || !*s || *s == '-' || *s == '+' || *s == ' ')
        return -1;
    errno = 0;
    unsigned long long v = strtoull(s, &end, 0);
    if (errno || *end || v < lo || v > hi)
        return -1;
    *out = (uint64_t)v;
    return 0;
}

double np_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

void np_progress_start(np_progress *p, const char *label, uint64_t total)
{
    p->label = label;
    p->total = total;
    p->start = p->last = np_now();
    p->tty = isatty(2);
}

void np_progress_update(np_progress *p, uint64_t done)
{
    if (!p->tty)
        return;
    double t = np_now();
    if (t - p->last < 0.25 && done < p->total)
        return;
    p->last = t;
    double el = t - p->start;
    double frac = p->total ? (double)done / (double)p->total : 0.0;
    double eta = frac > 0 ? el / frac - el : 0.0;
    fprintf(stderr, "\r%s: %5.1f%%  %llu/%llu  %.0f s elapsed, %.0f s left   ", p->label,
            100.0 * frac, (unsigned long long)done, (unsigned long long)p->total, el, eta);
    fflush(stderr);
}

void np_progress_end(np_progress *p)
{
    if (p->tty)
        fputs("\r\033[K", stderr);
}
