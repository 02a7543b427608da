/* SPDX-License-Identifier: MIT */
#include "np_common.h"

#include <errno.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
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

/* Digits of base 10 or 16 only: no sign, blank, prefix or suffix; overflow refused. */
static int parse_digits(const char *s, unsigned base, uint64_t lo, uint64_t hi, uint64_t *out)
{
    if (!s || !*s)
        return -1;
    uint64_t v = 0;
    for (const char *p = s; *p; p++) {
        unsigned d;
        if (*p >= '0' && *p <= '9')
            d = (unsigned)(*p - '0');
        else if (base == 16 && *p >= 'a' && *p <= 'f')
            d = (unsigned)(*p - 'a') + 10u;
        else if (base == 16 && *p >= 'A' && *p <= 'F')
            d = (unsigned)(*p - 'A') + 10u;
        else
            return -1;
        if (v > (UINT64_MAX - d) / base)
            return -1;
        v = v * base + d;
    }
    if (v < lo || v > hi)
        return -1;
    *out = v;
    return 0;
}

int np_parse_u64(const char *s, uint64_t lo, uint64_t hi, uint64_t *out)
{
    return parse_digits(s, 10, lo, hi, out);
}

int np_parse_u64_hex(const char *s, unsigned max_digits, uint64_t lo, uint64_t hi, uint64_t *out)
{
    if (!s || strlen(s) > max_digits)
        return -1;
    return parse_digits(s, 16, lo, hi, out);
}

int np_parse_u64_or_0x(const char *s, uint64_t lo, uint64_t hi, uint64_t *out)
{
    if (s && s[0] == '0' && (s[1] == 'x' || s[1] == 'X'))
        return parse_digits(s + 2, 16, lo, hi, out);
    return parse_digits(s, 10, lo, hi, out);
}

double np_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

static int progress_mode = NP_PROGRESS_AUTO;

void np_progress_set_mode(int mode) { progress_mode = mode; }

void np_progress_start(np_progress *p, const char *label, uint64_t total)
{
    p->label = label;
    p->total = total;
    p->start = p->last = np_now();
    int tty = isatty(2);
    /* 1: a rewritten line on a terminal; 2: a line every few seconds (forced into a log). */
    p->tty = progress_mode == NP_PROGRESS_NEVER    ? 0
             : progress_mode == NP_PROGRESS_ALWAYS ? (tty ? 1 : 2)
                                                   : tty;
}

void np_progress_update(np_progress *p, uint64_t done)
{
    if (!p->tty)
        return;
    double t = np_now();
    if (t - p->last < (p->tty == 2 ? 5.0 : 0.25) && done < p->total)
        return;
    p->last = t;
    double el = t - p->start;
    double frac = p->total ? (double)done / (double)p->total : 0.0;
    double eta = frac > 0 ? el / frac - el : 0.0;
    fprintf(stderr, "%s%s: %5.1f%%  %llu/%llu  %.0f s elapsed, %.0f s left%s", p->tty == 1 ? "\r" : "",
            p->label, 100.0 * frac, (unsigned long long)done, (unsigned long long)p->total, el, eta,
            p->tty == 1 ? "   " : "\n");
    fflush(stderr);
}

void np_progress_end(np_progress *p)
{
    if (p->tty == 1)
        fputs("\r\033[K", stderr);
}
