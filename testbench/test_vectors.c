/* SPDX-License-Identifier: MIT */
/*
 * test_vectors.c - golden vectors end to end, through the noisepipe command:
 * the checked-in set regenerates byte for byte and verifies; every kind of
 * bad input gives exit status 2 and a message naming FILE:LINE and the field;
 * `vectors | device | verify -` passes; one flipped bit fails and names
 * exactly that vector; --results files; the $readmemh and .coe layouts;
 * determinism; a level-2 set of more than 10^6 vectors with bubbles and
 * stalls. Every case runs in its own folder under NP_VEC_WORK.
 *
 * Compile-time paths: NP_NOISEPIPE (the command), NP_VEC_DIR (vectors/),
 * NP_VEC_WORK (scratch).
 */
#include <errno.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>

#include "np_test.h"

#define CHECKED_IN NP_VEC_DIR "/classic3/classic3-l1-seed1"

static char dir[4096]; /* this case's folder */

/* ------------------------------------------------------------------------- */
/* Helpers */

/* The folder of case `name`, created afresh (files of an earlier run are removed by name). */
static void case_dir(const char *name)
{
    snprintf(dir, sizeof dir, "%s/%s", NP_VEC_WORK, name);
    mkdir(NP_VEC_WORK, 0777);
    mkdir(dir, 0777);
}

/* dir/name, in one of a few rotating buffers. */
static const char *at(const char *name)
{
    static char buf[8][4200];
    static unsigned k;
    char *b = buf[k++ % 8u];
    snprintf(b, sizeof buf[0], "%s/%s", dir, name);
    return b;
}

/* Run a shell command (paths are single-quoted by the callers); its exit status, or -1. */
static int sh(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
static int sh(const char *fmt, ...)
{
    char cmd[16384];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(cmd, sizeof cmd, fmt, ap);
    va_end(ap);
    int st = system(cmd);
    if (st == -1 || !WIFEXITED(st))
        return -1;
    return WEXITSTATUS(st);
}

/* Run `noisepipe ARGS` with stdout and stderr in dir/out.txt and dir/err.txt. */
static int np(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
static int np(const char *fmt, ...)
{
    char args[8192];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(args, sizeof args, fmt, ap);
    va_end(ap);
    return sh("'%s' %s >'%s' 2>'%s'", NP_NOISEPIPE, args, at("out.txt"), at("err.txt"));
}

/* Whole file, NUL-terminated (caller frees); NULL when it cannot be read. */
static char *slurp(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    size_t cap = 1 << 16, n = 0;
    char *b = malloc(cap + 1);
    size_t r;
    while (b && (r = fread(b + n, 1, cap - n, f)) > 0) {
        n += r;
        if (n == cap) {
            char *nb = realloc(b, 2 * cap + 1);
            if (!nb) {
                free(b);
                b = NULL;
                break;
            }
            b = nb;
            cap *= 2;
        }
    }
    fclose(f);
    if (b)
        b[n] = '\0';
    if (len)
        *len = n;
    return b;
}

static void spew(const char *path, const char *text)
{
    FILE *f = fopen(path, "wb");
    NP_CHECK(f != NULL, "cannot write %s", path);
    if (f) {
        fputs(text, f);
        fclose(f);
    }
}

/* Does file path contain s? Prints the file when not. */
static int file_has(const char *path, const char *s)
{
    char *t = slurp(path, NULL);
    int ok = t && strstr(t, s);
    if (!ok)
        fprintf(stderr, "--- %s does not contain '%s'; it holds:\n%s\n", path, s, t ? t : "(nothing)");
    free(t);
    return ok;
}

/* Does file path lack s? Prints the file when it has it. */
static int file_lacks(const char *path, const char *s)
{
    char *t = slurp(path, NULL);
    int ok = !t || !strstr(t, s);
    if (!ok)
        fprintf(stderr, "--- %s should not contain '%s'; it holds:\n%s\n", path, s, t);
    free(t);
    return ok;
}

static unsigned count_of(const char *text, const char *s)
{
    unsigned n = 0;
    for (const char *p = text; (p = strstr(p, s)) != NULL; p += strlen(s))
        n++;
    return n;
}

/* Byte-for-byte equality; on a difference, says where. */
static int same_file(const char *a, const char *b)
{
    size_t la, lb;
    char *ta = slurp(a, &la), *tb = slurp(b, &lb);
    int ok = ta && tb && la == lb && memcmp(ta, tb, la) == 0;
    if (!ok && ta && tb) {
        size_t k = 0, line = 1;
        for (; k < la && k < lb && ta[k] == tb[k]; k++)
            line += ta[k] == '\n';
        fprintf(stderr, "%s and %s differ at byte %zu (line %zu); sizes %zu, %zu\n", a, b, k, line, la, lb);
    }
    free(ta);
    free(tb);
    return ok;
}

/* The "# count N" of a vector file (0 if absent). */
static unsigned long long header_count(const char *path)
{
    char *t = slurp(path, NULL);
    const char *p = t ? strstr(t, "# count ") : NULL;
    unsigned long long n = p ? strtoull(p + 8, NULL, 10) : 0;
    free(t);
    return n;
}

/* The number after `key` in text (0 when absent). */
static unsigned long long number_before(const char *text, const char *key)
{
    const char *p = strstr(text, key);
    if (!p)
        return 0;
    while (p > text && (p[-1] == ' '))
        p--;
    while (p > text && p[-1] >= '0' && p[-1] <= '9')
        p--;
    return strtoull(p, NULL, 10);
}

/* A text file as lines (modifiable); *n lines. Frees with lines_free. */
typedef struct lines {
    char *v[64];
    unsigned n;
} lines;

static void lines_free(lines *L)
{
    for (unsigned k = 0; k < L->n; k++)
        free(L->v[k]);
    L->n = 0;
}

static char *join(const lines *L)
{
    size_t len = 1;
    for (unsigned k = 0; k < L->n; k++)
        len += strlen(L->v[k]) + 1;
    char *t = malloc(len), *p = t;
    for (unsigned k = 0; k < L->n; k++)
        p += sprintf(p, "%s\n", L->v[k]);
    *p = '\0';
    return t;
}

static void set_line(lines *L, unsigned lineno, const char *text)
{
    free(L->v[lineno - 1]);
    L->v[lineno - 1] = strdup(text);
}

/*
 * A small good vector file as lines: the header of a generated file for
 * config (NULL = default) with its first 3 vectors and "# count 3".
 * Returns the line number of the first vector.
 */
static unsigned small_file(lines *L, const char *config)
{
    char args[512];
    snprintf(args, sizeof args, "vectors --unit classic3 %s%s -n 0 -o '%s'", config ? "--config " : "",
             config ? config : "", at("base.vec"));
    NP_CHECK(np("%s", args) == 0, "noisepipe %s failed", args);
    char *t = slurp(at("base.vec"), NULL), *save = NULL;
    unsigned first = 0, data = 0;
    L->n = 0;
    for (char *s = t ? strtok_r(t, "\n", &save) : NULL; s && L->n < 64 && data < 3;
         s = strtok_r(NULL, "\n", &save)) {
        if (strncmp(s, "# count ", 8) == 0)
            s = "# count 3";
        L->v[L->n++] = strdup(s);
        if (s[0] != '#') {
            data++;
            first = first ? first : L->n;
        }
    }
    free(t);
    NP_CHECK(data == 3 && first > 1, "base file: %u vector lines, first at %u", data, first);
    return first;
}

/* Replace token k (0-based) of line lineno by tok (NULL: drop it); a k past the last token appends tok. */
static void set_token(lines *L, unsigned lineno, unsigned k, const char *tok)
{
    char out[1024] = "", *src = strdup(L->v[lineno - 1]), *save = NULL;
    unsigned i = 0;
    for (char *s = strtok_r(src, " ", &save); s; s = strtok_r(NULL, " ", &save), i++) {
        const char *w = i == k ? tok : s;
        if (w)
            snprintf(out + strlen(out), sizeof out - strlen(out), "%s%s", out[0] ? " " : "", w);
    }
    if (k >= i && tok)
        snprintf(out + strlen(out), sizeof out - strlen(out), " %s", tok);
    free(src);
    set_line(L, lineno, out);
}

/* ------------------------------------------------------------------------- */
/* The checked-in set and the default job */

static int regen_level1_identical(void)
{
    case_dir("regen_level1_identical");
    NP_CHECK(np("vectors --unit classic3 --seed 1 --level 1 -o '%s'", at("v.vec")) == 0, "vectors failed");
    NP_CHECK(np("vectors --unit classic3 --seed 1 --level 1 --format readmemh -o '%s'", at("v.memh")) == 0,
             "vectors --format readmemh failed");
    NP_CHECK(same_file(at("v.vec"), CHECKED_IN ".vec"), "regenerated text vectors differ from the checked-in set");
    NP_CHECK(same_file(at("v.memh"), CHECKED_IN ".memh"), "regenerated readmemh export differs from the checked-in set");
    printf("regenerated %llu vectors: identical to %s.vec and .memh\n", header_count(at("v.vec")), CHECKED_IN);
    return 0;
}

static int verify_checked_in(void)
{
    char verdict[128];
    case_dir("verify_checked_in");
    unsigned long long n = header_count(CHECKED_IN ".vec");
    NP_CHECK(n >= 1000, "checked-in set has only %llu vectors", n);
    NP_CHECK(np("verify '%s'", CHECKED_IN ".vec") == 0, "verify of the checked-in set failed");
    snprintf(verdict, sizeof verdict, "In %llu tests, no errors found in classic3 (", n);
    NP_CHECK(file_has(at("out.txt"), verdict), "verdict");
    NP_CHECK(file_has(at("out.txt"), "correctly rounded"), "summary");
    NP_CHECK(np("verify --no-stalls '%s'", CHECKED_IN ".vec") == 0, "verify --no-stalls failed");
    char *t = slurp(at("out.txt"), NULL);
    /* Without stalls every transaction must have had its latency checked exactly. */
    NP_CHECK(t && number_before(strstr(t, "exact on the ") ? strstr(t, "exact on the ") + 13 : t,
                                "transactions") == n,
             "latency was not checked exactly on every transaction:\n%s", t ? t : "");
    free(t);
    return 0;
}

static int run_default(void)
{
    case_dir("run_default");
    NP_CHECK(np("run -o '%s'", at("out")) == 0, "noisepipe run failed");
    NP_CHECK(file_has(at("out.txt"), "latency "), "run prints the latency");
    NP_CHECK(file_has(at("out.txt"), "max |error|"), "run prints the error summary");
    NP_CHECK(file_has(at("out.txt"), "no errors found in classic3"), "run prints the verdict");
    NP_CHECK(same_file(at("out/classic3-l1-seed1.vec"), CHECKED_IN ".vec"), "run's vectors = checked-in set");
    NP_CHECK(same_file(at("out/classic3-l1-seed1.memh"), CHECKED_IN ".memh"), "run's readmemh = checked-in set");
    NP_CHECK(np("run --bogus") == 2, "unknown option: exit 2");
    return 0;
}

/* ------------------------------------------------------------------------- */
/* Device and results */

static int device_pipe_passes(void)
{
    case_dir("device_pipe_passes");
    NP_CHECK(sh("'%s' vectors --unit classic3 | '%s' device --unit-from-header | '%s' verify - >'%s' 2>'%s'",
                NP_NOISEPIPE, NP_NOISEPIPE, NP_NOISEPIPE, at("out.txt"), at("err.txt")) == 0,
             "vectors | device | verify - failed");
    NP_CHECK(file_has(at("out.txt"), "no errors found in classic3"), "verdict");
    NP_CHECK(file_has(at("out.txt"), "in the device results carried by the vector lines"),
             "the device's results were checked, not the cycle model");
    return 0;
}

/* Flip bit `bit` of transaction k: verify must fail naming exactly that vector. */
static void flip_one(unsigned long long k, unsigned bit, unsigned long long n)
{
    char want[64], verdict[96];
    int rc = sh("'%s' device --flip-bit %u --at %llu '%s' | '%s' verify - >'%s' 2>'%s'", NP_NOISEPIPE, bit,
                k, CHECKED_IN ".vec", NP_NOISEPIPE, at("out.txt"), at("err.txt"));
    NP_CHECK(rc == 1, "flip bit %u of vector %llu: exit %d, expected 1", bit, k, rc);
    char *t = slurp(at("out.txt"), NULL);
    snprintf(want, sizeof want, ": vector %llu: ", k);
    snprintf(verdict, sizeof verdict, "In %llu tests, 1 error found", n);
    NP_CHECK(t && count_of(t, ": vector ") == 1, "exactly one failing vector expected:\n%s", t ? t : "");
    NP_CHECK(t && strstr(t, want), "the failure must name vector %llu:\n%s", k, t ? t : "");
    NP_CHECK(t && strstr(t, "bit mismatch"), "reason: bit mismatch");
    NP_CHECK(t && strstr(t, verdict), "verdict '%s'", verdict);
    free(t);
}

static int flip_bit_names_vector(void)
{
    case_dir("flip_bit_names_vector");
    unsigned long long n = header_count(CHECKED_IN ".vec");
    flip_one(0, 0, n);
    flip_one(1234, 3, n);
    flip_one(n - 1, 7, n); /* the sign bit of the last vector */
    return 0;
}

static int results_file(void)
{
    case_dir("results_file");
    unsigned long long n = header_count(CHECKED_IN ".vec");
    NP_CHECK(np("device --format results -o '%s' '%s'", at("r.hex"), CHECKED_IN ".vec") == 0, "device failed");
    char *t = slurp(at("r.hex"), NULL);
    unsigned long long words = 0;
    for (char *s = t; s && *s;) {
        char *e = strchr(s, '\n');
        if (!(s[0] == '/' && s[1] == '/'))
            words++;
        s = e ? e + 1 : s + strlen(s);
    }
    free(t);
    NP_CHECK(words == n, "results file has %llu result lines, expected %llu", words, n);
    NP_CHECK(np("verify --results '%s' '%s'", at("r.hex"), CHECKED_IN ".vec") == 0, "verify --results failed");
    NP_CHECK(file_has(at("out.txt"), "no errors found"), "verdict");
    NP_CHECK(np("device --format results --flip-bit 5 --at 77 -o '%s' '%s'", at("f.hex"), CHECKED_IN ".vec") == 0,
             "device --flip-bit failed");
    NP_CHECK(np("verify --results '%s' '%s'", at("f.hex"), CHECKED_IN ".vec") == 1, "flipped result: exit 1");
    NP_CHECK(file_has(at("out.txt"), ": vector 77: "), "names vector 77");
    NP_CHECK(file_has(at("out.txt"), "1 error found"), "one error");
    /* A results file one line short is bad input, named by file and line. */
    NP_CHECK(sh("head -n -1 '%s' >'%s'", at("r.hex"), at("short.hex")) == 0, "head");
    NP_CHECK(np("verify --results '%s' '%s'", at("short.hex"), CHECKED_IN ".vec") == 2, "short results: exit 2");
    NP_CHECK(file_has(at("err.txt"), "short.hex:"), "message names the results file");
    NP_CHECK(file_has(at("err.txt"), "results end after"), "message says the results are short");
    return 0;
}

/* ------------------------------------------------------------------------- */
/* Export layouts */

/* Bits [pos, pos + n) (n <= 64) of a hex word of nd digits. */
static uint64_t word_bits(const char *hex, unsigned nd, unsigned pos, unsigned n)
{
    uint64_t v = 0;
    for (unsigned b = pos + n; b-- > pos;) {
        unsigned d = b / 4u;
        if (d >= nd) {
            v <<= 1;
            continue;
        }
        char c = hex[nd - 1u - d];
        unsigned x = (unsigned)(c <= '9' ? c - '0' : c - 'a' + 10);
        v = v << 1 | ((x >> (b % 4u)) & 1u);
    }
    return v;
}

/*
 * Check a packed export (readmemh, or coe when coe != 0) against the text
 * vectors of the same seed: one word per vector, ceil((1 + 48 + out_bits)/4)
 * digits, {1'b1, x, y, z, f} MSB first.
 */
static void check_packed(const char *packed, const char *vec, unsigned out_bits, int coe)
{
    unsigned total = 1u + 3u * 16u + out_bits, nd = (total + 3u) / 4u;
    char *p = slurp(packed, NULL), *v = slurp(vec, NULL);
    NP_CHECK(p && v, "cannot read %s / %s", packed, vec);
    if (!p || !v) {
        free(p);
        free(v);
        return;
    }
    if (coe)
        NP_CHECK(strstr(p, "memory_initialization_radix=16;\nmemory_initialization_vector=\n"), "coe preamble");
    char *ps = NULL, *vs = NULL, *pl = strtok_r(p, "\n", &ps), *vl = strtok_r(v, "\n", &vs);
    unsigned long long words = 0, bad = 0, n = 0;
    const char *comment = coe ? ";" : "//";
    for (; vl; vl = strtok_r(NULL, "\n", &vs)) {
        if (vl[0] == '#')
            continue;
        n++;
        while (pl && (strncmp(pl, comment, strlen(comment)) == 0 || strncmp(pl, "memory_", 7) == 0))
            pl = strtok_r(NULL, "\n", &ps);
        if (!pl)
            break;
        words++;
        size_t len = strlen(pl);
        char end = coe ? pl[len - 1] : '\0';
        if (coe)
            len--;
        unsigned long long x, y, z, f;
        int ok = sscanf(vl, "%llx %llx %llx %llx", &x, &y, &z, &f) == 4 && len == nd &&
                 word_bits(pl, nd, total - 1u, 1) == 1 && word_bits(pl, nd, total - 17u, 16) == x &&
                 word_bits(pl, nd, total - 33u, 16) == y && word_bits(pl, nd, total - 49u, 16) == z &&
                 word_bits(pl, nd, 0, out_bits) == f && (!coe || end == ',' || end == ';');
        if (!ok && bad++ < 5)
            fprintf(stderr, "word %llu '%s' does not pack '%s'\n", words - 1, pl, vl);
        pl = strtok_r(NULL, "\n", &ps);
        if (coe)
            NP_CHECK((end == ';') == (pl == NULL), "word %llu: ';' must end the last word only", words - 1);
    }
    NP_CHECK(words == n && n > 0 && pl == NULL, "%s: %llu words for %llu vectors", packed, words, n);
    NP_CHECK(bad == 0, "%llu words with a wrong layout", bad);
    NP_CHECK(n == header_count(vec), "vector count");
    printf("%s: %llu words of %u bits (%u hex digits), layout checked\n", packed, words, total, nd);
    free(p);
    free(v);
}

static int readmemh_layout(void)
{
    case_dir("readmemh_layout");
    check_packed(CHECKED_IN ".memh", CHECKED_IN ".vec", 8, 0);
    NP_CHECK(file_has(CHECKED_IN ".memh", "// word 57 bits = 15 hex digits per transaction, MSB first: "
                                          "[56] valid [55:40] x [39:24] y [23:8] z [7:0] f"),
             "the ruler comment");
    return 0;
}

static int coe_layout(void)
{
    case_dir("coe_layout");
    NP_CHECK(np("vectors --unit classic3 --format coe -o '%s'", at("v.coe")) == 0, "vectors --format coe");
    check_packed(at("v.coe"), CHECKED_IN ".vec", 8, 1);
    return 0;
}

/* Other output widths: 10 bits (59-bit words, a part-filled top digit) and 16 (65 bits, > 64). */
static int layout_other_widths(void)
{
    case_dir("layout_other_widths");
    static const unsigned widths[] = { 10, 16 };
    for (unsigned k = 0; k < 2; k++) {
        char cfg[32];
        snprintf(cfg, sizeof cfg, "out_bits=%u", widths[k]);
        NP_CHECK(np("vectors --unit classic3 --config %s -n 200 -o '%s'", cfg, at("w.vec")) == 0, "vectors");
        NP_CHECK(np("vectors --unit classic3 --config %s -n 200 --format readmemh -o '%s'", cfg, at("w.memh")) == 0,
                 "vectors readmemh");
        check_packed(at("w.memh"), at("w.vec"), widths[k], 0);
        NP_CHECK(np("verify '%s'", at("w.vec")) == 0, "verify %s", cfg);
    }
    return 0;
}

/* ------------------------------------------------------------------------- */
/* Determinism and the verifier's own failures */

static int determinism(void)
{
    case_dir("determinism");
    NP_CHECK(np("vectors --unit classic3 --seed 7 -o '%s'", at("a.vec")) == 0, "a");
    NP_CHECK(np("vectors --unit classic3 --seed 7 -o '%s'", at("b.vec")) == 0, "b");
    NP_CHECK(np("vectors --unit classic3 --seed 8 -o '%s'", at("c.vec")) == 0, "c");
    NP_CHECK(same_file(at("a.vec"), at("b.vec")), "same seed twice must give identical files");
    size_t la, lc;
    char *a = slurp(at("a.vec"), &la), *c = slurp(at("c.vec"), &lc);
    NP_CHECK(a && c && (la != lc || memcmp(a, c, la) != 0), "a different seed must give a different file");
    /* The seed moves only the random cases (the last 1024): every line before them matches. */
    unsigned long long fixed = header_count(at("a.vec")) - 1024u, n = 0;
    const char *pa = a ? strstr(a, "\n0") : NULL, *pc = c ? strstr(c, "\n0") : NULL;
    while (pa && pc && n < fixed) {
        const char *ea = strchr(pa + 1, '\n'), *ec = strchr(pc + 1, '\n');
        if (!ea || !ec || ea - pa != ec - pc || memcmp(pa, pc, (size_t)(ea - pa)) != 0)
            break;
        pa = ea;
        pc = ec;
        n++;
    }
    NP_CHECK(n == fixed, "vector %llu of the boundary and pattern cases depends on the seed", n);
    NP_CHECK(pa && pc && strcmp(pa, pc) != 0, "the random cases must depend on the seed");
    free(a);
    free(c);
    NP_CHECK(np("vectors --unit classic3 -n 5 -o '%s'", at("n.vec")) == 0, "-n 5");
    unsigned long long base = header_count(CHECKED_IN ".vec") - 1024u;
    NP_CHECK(header_count(at("n.vec")) == base + 5u, "-n 5 gives %llu + 5 vectors, not %llu", base,
             header_count(at("n.vec")));
    NP_CHECK(np("vectors --unit classic3 --level 3") == 2, "--level 3: exit 2");
    NP_CHECK(np("vectors --unit nosuch") == 2 && file_has(at("err.txt"), "unknown unit 'nosuch'"), "unknown unit");
    return 0;
}

static int accuracy_tolerance_fails(void)
{
    case_dir("accuracy_tolerance_fails");
    NP_CHECK(np("verify --tolerance 0.25 --errors 0 '%s'", CHECKED_IN ".vec") == 1,
             "a quarter-LSB tolerance must fail (the model is faithful, not correctly rounded)");
    NP_CHECK(file_has(at("out.txt"), "accuracy: |error|"), "reason: accuracy");
    NP_CHECK(file_lacks(at("out.txt"), "bit mismatch"), "no bit mismatch on the cycle model");
    return 0;
}

static int errors_limit(void)
{
    case_dir("errors_limit");
    NP_CHECK(np("verify --tolerance 0 --errors 5 '%s'", CHECKED_IN ".vec") == 1, "exit 1");
    char *t = slurp(at("out.txt"), NULL);
    NP_CHECK(t && count_of(t, " => ") == 5, "exactly 5 failures printed:\n%s", t ? t : "");
    NP_CHECK(t && strstr(t, "5 errors found") && strstr(t, "stopped after 5 errors"), "verdict says it stopped");
    NP_CHECK(t && count_of(t, "In ") == 1, "one verdict line");
    free(t);
    return 0;
}

/* A vector whose expected output was edited: the verifier blames the file. */
static int model_mismatch_caught(void)
{
    lines L;
    case_dir("model_mismatch_caught");
    unsigned first = small_file(&L, NULL);
    char *line = strdup(L.v[first]), tok[3], *s = line;
    for (unsigned k = 0; k < 3; k++)
        s = strchr(s, ' ') + 1;
    snprintf(tok, sizeof tok, "%02x", (unsigned)((strtoul(s, NULL, 16) + 1u) & 0xffu));
    set_token(&L, first + 1, 3, tok);
    char *t = join(&L);
    spew(at("m.vec"), t);
    NP_CHECK(np("verify '%s'", at("m.vec")) == 1, "edited expected value: exit 1");
    NP_CHECK(file_has(at("out.txt"), "m.vec:"), "names the file");
    NP_CHECK(file_has(at("out.txt"), ": vector 1: "), "names vector 1");
    NP_CHECK(file_has(at("out.txt"), "disagrees with the bit-exact model"), "reason");
    free(t);
    free(line);
    lines_free(&L);
    return 0;
}

/* ------------------------------------------------------------------------- */
/* Bad input: exit 2, a message naming FILE:LINE and the field. */

typedef struct bad_kind {
    const char *name;
    const char *config; /* of the base file (NULL: default) */
    int line;           /* edit: > 0 the n-th vector line, < 0 header line -line, 0 none */
    int token;          /* token to replace (0-based); -1 the whole line; -2 append */
    const char *text;   /* the new token or line; NULL drops the token */
    int msg_line;       /* line the message names: 0 the edited one, -1 the last line, > 0 that line */
    const char *want;   /* expected message; %u is msg_line */
} bad_kind;

static const bad_kind bad_kinds[] = {
    { "bad_truncated_line", NULL, 2, 4, NULL, 0, "bad.vec:%u: field f.ref: missing: truncated line has 4 fields" },
    { "bad_field_width", NULL, 2, 0, "000", 0, "bad.vec:%u: field x: wrong width: 3 hex digits in '000', expected 4" },
    { "bad_non_hex", NULL, 3, 1, "0g00", 0, "bad.vec:%u: field y: non-hex digit 'g' in '0g00'" },
    { "bad_too_many_fields", NULL, 1, -2, "00 00", 0, "bad.vec:%u: too many fields: 7, expected 5 (x y z f f.ref)" },
    { "bad_value_range", "out_bits=6", 2, 3, "7f", 0, "bad.vec:%u: field f: value 7f out of range for 6 bits" },
    { "bad_unknown_unit", NULL, -2, -1, "# unit nosuch", 0, "bad.vec:%u: unknown unit 'nosuch'" },
    { "bad_config", NULL, -3, -1, "# config out_bits=99", 0, "bad.vec:%u: bad config 'out_bits=99'" },
    { "bad_config_missing_key", NULL, -3, -1, "# config out_bits=8 s_frac=12", 0,
      "bad.vec:%u: bad config 'out_bits=8 s_frac=12' for unit classic3: key lerp_frac missing" },
    { "bad_config_key_twice", NULL, -3, -1, "# config out_bits=8 s_frac=12 lerp_frac=11 s_frac=12", 0,
      "bad.vec:%u: bad config 'out_bits=8 s_frac=12 lerp_frac=11 s_frac=12' for unit classic3: key s_frac given twice" },
    { "bad_config_hex", NULL, -3, -1, "# config out_bits=0x8 s_frac=12 lerp_frac=11", 0,
      "bad.vec:%u: bad config 'out_bits=0x8 s_frac=12 lerp_frac=11' for unit classic3: out_bits=0x8: not a number: expected a "
      "decimal integer in 2..16" },
    { "bad_field_decl", NULL, -10, -1, "# field f out 8 s8 Q3.5", 0,
      "bad.vec:%u: field f: header declares 'f out 8 s8 Q3.5', but unit classic3" },
    { "bad_missing_header", NULL, 0, 0, NULL, 1, "bad.vec:%u: missing header" },
    { "bad_missing_file", NULL, 0, 0, NULL, 0, "nosuch.vec: cannot open" },
    { "bad_empty_file", NULL, 0, 0, NULL, 0, "bad.vec: empty file" },
    { "bad_truncated_file", NULL, -6, -1, "# count 4", -1, "bad.vec:%u: truncated file: it ends after 3 vectors" },
};

/* Write the bad file of kind b into the case folder; returns its path and the line the message names. */
static const char *make_bad(const bad_kind *b, unsigned *msg_line)
{
    lines L;
    unsigned first = small_file(&L, b->config);
    unsigned edited = b->line > 0 ? first + (unsigned)b->line - 1u : (unsigned)-b->line;
    if (b->line != 0 && b->token == -1)
        set_line(&L, edited, b->text);
    else if (b->line != 0)
        set_token(&L, edited, b->token == -2 ? 99u : (unsigned)b->token, b->text);
    if (strcmp(b->name, "bad_missing_header") == 0) { /* the vector lines alone */
        lines V = { .n = 0 };
        for (unsigned k = first - 1u; k < L.n; k++)
            V.v[V.n++] = strdup(L.v[k]);
        lines_free(&L);
        L = V;
    }
    *msg_line = b->msg_line > 0 ? (unsigned)b->msg_line : b->msg_line < 0 ? L.n : edited;
    char *t = strcmp(b->name, "bad_empty_file") == 0 ? strdup("") : join(&L);
    const char *path = at(strcmp(b->name, "bad_missing_file") == 0 ? "nosuch.vec" : "bad.vec");
    if (strcmp(b->name, "bad_missing_file") != 0)
        spew(path, t);
    free(t);
    lines_free(&L);
    return path;
}

static int bad_input(const char *name)
{
    const bad_kind *b = NULL;
    for (unsigned k = 0; k < sizeof bad_kinds / sizeof bad_kinds[0]; k++)
        if (strcmp(bad_kinds[k].name, name) == 0)
            b = &bad_kinds[k];
    case_dir(name);
    unsigned line;
    const char *path = make_bad(b, &line);
    char want[512];
    snprintf(want, sizeof want, b->want, line);
    int rc = np("verify '%s'", path);
    NP_CHECK(rc == 2, "verify: exit %d, expected 2", rc);
    NP_CHECK(file_has(at("err.txt"), want), "verify's message");
    NP_CHECK(file_lacks(at("out.txt"), "In "), "no verdict on bad input");
    rc = np("device '%s'", path);
    NP_CHECK(rc == 2, "device: exit %d, expected 2", rc);
    NP_CHECK(file_has(at("err.txt"), want), "device's message");
    printf("%s: exit 2 with '%s'\n", name, want);
    return 0;
}

#define BAD_CASE(n) \
    static int n(void) { return bad_input(#n); }
BAD_CASE(bad_truncated_line)
BAD_CASE(bad_field_width)
BAD_CASE(bad_non_hex)
BAD_CASE(bad_too_many_fields)
BAD_CASE(bad_value_range)
BAD_CASE(bad_unknown_unit)
BAD_CASE(bad_config)
BAD_CASE(bad_config_missing_key)
BAD_CASE(bad_config_key_twice)
BAD_CASE(bad_config_hex)
BAD_CASE(bad_field_decl)
BAD_CASE(bad_missing_header)
BAD_CASE(bad_missing_file)
BAD_CASE(bad_empty_file)
BAD_CASE(bad_truncated_file)

/*
 * The '# reg' header lines (a unit with a register block: wave): the
 * checked-in set carries them, and a value edited, a line dropped, or a line
 * in a unit without registers is bad input (exit 2) naming the line and the
 * register, in verify and device alike.
 */
#define WAVE_SET NP_VEC_DIR "/wave/wave-l1-seed1"
static int reg_case(const char *sed, const char *src, const char *want)
{
    NP_CHECK(sh("sed %s '%s' >'%s'", sed, src, at("bad.vec")) == 0, "sed failed");
    int rc = np("verify '%s'", at("bad.vec"));
    NP_CHECK(rc == 2, "verify (sed %s): exit %d, expected 2", sed, rc);
    NP_CHECK(file_has(at("err.txt"), want), "verify's message");
    NP_CHECK(file_lacks(at("out.txt"), "In "), "no verdict on bad input");
    rc = np("device '%s'", at("bad.vec"));
    NP_CHECK(rc == 2, "device (sed %s): exit %d, expected 2", sed, rc);
    NP_CHECK(file_has(at("err.txt"), want), "device's message");
    printf("sed %s: exit 2 with '%s'\n", sed, want);
    return 0;
}

static int reg_lines(void)
{
    case_dir("reg_lines");
    NP_CHECK(file_has(WAVE_SET ".vec", "\n# reg tr0.kx 86ac1284 s32 Q0.32\n"), "the text set carries the registers");
    NP_CHECK(file_has(WAVE_SET ".memh", "\n// reg tr0.kx 86ac1284 s32 Q0.32\n"), "the $readmemh set carries them");
    NP_CHECK(file_has(WAVE_SET ".memh", "\n// reg gcap 5333 u15 Q1.14\n"), "down to the last");
    /* The device's output keeps them, and verify reads it back. */
    NP_CHECK(np("device -o '%s' '%s'", at("dev.vec"), WAVE_SET ".vec") == 0, "device on the wave set");
    NP_CHECK(file_has(at("dev.vec"), "\n# reg gcap 5333 u15 Q1.14\n"), "device's file carries them");
    NP_CHECK(np("verify --no-stalls '%s'", at("dev.vec")) == 0, "verify of the device's answers");
    /* A results file's '// reg' lines must be the vectors' registers too. */
    NP_CHECK(np("device --format results -o '%s' '%s'", at("r.hex"), WAVE_SET ".vec") == 0, "device --format results");
    NP_CHECK(file_has(at("r.hex"), "\n// reg tr1.om 094af269 u32 Q0.32\n"), "results header carries the registers");
    NP_CHECK(np("verify --results '%s' '%s'", at("r.hex"), WAVE_SET ".vec") == 0, "verify --results of the wave set");
    NP_CHECK(sh("sed 's|^// reg tr1.om 094af269|// reg tr1.om 094af26a|' '%s' >'%s'", at("r.hex"), at("r2.hex")) == 0,
             "sed");
    NP_CHECK(np("verify --results '%s' '%s'", at("r2.hex"), WAVE_SET ".vec") == 2, "results of other registers: exit 2");
    NP_CHECK(file_has(at("err.txt"), "register tr1.om: the results are for 'tr1.om 094af26a u32 Q0.32', the vectors "
                                     "for 'tr1.om 094af269 u32 Q0.32'"),
             "names the register");
    reg_case("-e 's/^# reg tr0.kx 86ac1284/# reg tr0.kx 86ac1384/'", WAVE_SET ".vec",
             "bad.vec:5: register tr0.kx: header says 'tr0.kx 86ac1384 s32 Q0.32', but unit wave (trains=2 irr=1 "
             "cap=1 rom_log2=8 regs=1) holds 'tr0.kx 86ac1284 s32 Q0.32'");
    reg_case("-e 's/^# reg tr1.cz 37c3 s16 Q1.14/# reg tr1.cz 37c3 s16 Q2.13/'", WAVE_SET ".vec",
             "bad.vec:20: register tr1.cz: header says 'tr1.cz 37c3 s16 Q2.13'");
    reg_case("-e '/^# reg gcap/d'", WAVE_SET ".vec",
             "bad.vec:27: missing header line '# reg gcap 5333 u15 Q1.14' (unit wave (trains=2 irr=1 cap=1 rom_log2=8 "
             "regs=1) has 25 registers; the file gives 24)");
    reg_case("-e '/^# reg/d'", WAVE_SET ".vec", "bad.vec:3: missing header line '# reg n 2 u3'");
    reg_case("-e 's/^# reg n 2 u3/# reg n 2 u3\\n# reg n 2 u3/'", WAVE_SET ".vec",
             "bad.vec:5: register tr0.kx: header says 'n 2 u3'");
    reg_case("-e 's/^# seed 1/# reg k 1 u1/'", CHECKED_IN ".vec",
             "bad.vec:4: reg: 'k 1 u1' is not a register of unit classic3 (out_bits=8 s_frac=12 lerp_frac=11), which "
             "has no register block");
    return 0;
}

/* A failed or refused write leaves no file behind. */
static int atomic_output(void)
{
    case_dir("atomic_output");
    remove(at("none/v.vec"));
    NP_CHECK(np("vectors --unit classic3 -o '%s'", at("none/v.vec")) == 2, "unwritable path: exit 2");
    struct stat st;
    NP_CHECK(stat(at("none/v.vec"), &st) != 0, "no file may be left");
    /* The device stops on bad input: the output file it was writing must not appear. */
    lines L;
    unsigned first = small_file(&L, NULL);
    set_token(&L, first + 2, 0, "zzzz");
    char *t = join(&L);
    spew(at("bad.vec"), t);
    remove(at("dev.vec"));
    NP_CHECK(np("device -o '%s' '%s'", at("dev.vec"), at("bad.vec")) == 2, "device on bad input: exit 2");
    NP_CHECK(stat(at("dev.vec"), &st) != 0, "the device left a partial file");
    NP_CHECK(sh("ls '%s' | grep -q tmp", dir) != 0, "a temporary file was left");
    free(t);
    lines_free(&L);
    return 0;
}

/* ------------------------------------------------------------------------- */

static int level2_million_stalls(void)
{
    case_dir("level2_million_stalls");
    NP_CHECK(np("vectors --unit classic3 --level 2 --seed 3 -o '%s'", at("l2.vec")) == 0, "level 2 vectors");
    unsigned long long n = header_count(at("l2.vec"));
    NP_CHECK(n >= 1000000u, "level 2 has %llu vectors, expected >= 10^6", n);
    NP_CHECK(np("verify '%s'", at("l2.vec")) == 0, "verify of level 2 on the cycle model failed");
    char *t = slurp(at("out.txt"), NULL), verdict[96];
    snprintf(verdict, sizeof verdict, "In %llu tests, no errors found", n);
    NP_CHECK(t && strstr(t, verdict), "verdict:\n%s", t ? t : "");
    unsigned long long bubbles = t ? number_before(t, "input bubbles") : 0,
                       stalls = t ? number_before(t, "output stalls") : 0;
    NP_CHECK(bubbles > n / 10 && stalls > n / 10, "too few bubbles (%llu) or stalls (%llu) for %llu vectors",
             bubbles, stalls, n);
    printf("level 2: %llu vectors verified with %llu input bubbles and %llu output stalls\n", n, bubbles, stalls);
    free(t);
    remove(at("l2.vec"));
    return 0;
}

static const np_test_case cases[] = {
    { "regen_level1_identical", regen_level1_identical },
    { "verify_checked_in", verify_checked_in },
    { "run_default", run_default },
    { "device_pipe_passes", device_pipe_passes },
    { "flip_bit_names_vector", flip_bit_names_vector },
    { "results_file", results_file },
    { "readmemh_layout", readmemh_layout },
    { "coe_layout", coe_layout },
    { "layout_other_widths", layout_other_widths },
    { "determinism", determinism },
    { "accuracy_tolerance_fails", accuracy_tolerance_fails },
    { "errors_limit", errors_limit },
    { "model_mismatch_caught", model_mismatch_caught },
    { "bad_truncated_line", bad_truncated_line },
    { "bad_field_width", bad_field_width },
    { "bad_non_hex", bad_non_hex },
    { "bad_too_many_fields", bad_too_many_fields },
    { "bad_value_range", bad_value_range },
    { "bad_unknown_unit", bad_unknown_unit },
    { "bad_config", bad_config },
    { "bad_config_missing_key", bad_config_missing_key },
    { "bad_config_key_twice", bad_config_key_twice },
    { "bad_config_hex", bad_config_hex },
    { "bad_field_decl", bad_field_decl },
    { "bad_missing_header", bad_missing_header },
    { "bad_missing_file", bad_missing_file },
    { "bad_empty_file", bad_empty_file },
    { "bad_truncated_file", bad_truncated_file },
    { "reg_lines", reg_lines },
    { "atomic_output", atomic_output },
    { "level2_million_stalls", level2_million_stalls },
    { NULL, NULL },
};

NP_TEST_MAIN(cases)
