/* SPDX-License-Identifier: MIT */
/* Shared primitives: fixed-point helpers, the table-free hash, the gradient, the generator. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "np_classic.h"
#include "np_fdiff.h"
#include "np_fixed.h"
#include "np_hash.h"
#include "np_ref.h"
#include "np_rng.h"
#include "np_simplex.h"
#include "np_test.h"
#include "np_texel.h"
#include "np_unit.h"

/* FNV-1a over np_hash6(i,j,k) for i, j, k = 0..255 in that nesting order. */
#define NP_HASH_TABLE_FNV 0x3c19d3ded8996425ull

/* Values around every power of two, and the extremes, for the shift helpers. */
static int64_t edge_value(unsigned n)
{
    static const int64_t base[] = { 0, 1, -1, 2, -2, 3, -3, 5, -5, 7, -7 };
    unsigned nb = sizeof base / sizeof base[0];
    if (n < nb)
        return base[n];
    n -= nb;
    unsigned p = (n / 6) % 61;
    int64_t v = (int64_t)1 << p;
    switch (n % 6) {
    case 0: return v;
    case 1: return v - 1;
    case 2: return v + 1;
    case 3: return -v;
    case 4: return -v - 1;
    default: return -v + 1;
    }
}

static int fixed_asr(void)
{
    unsigned checked = 0;
    for (unsigned n = 0; n < 11 + 6 * 61; n++) {
        int64_t v = edge_value(n);
        for (unsigned sh = 0; sh < 62; sh++, checked++) {
            /* floor division by 2^sh, written with C's truncating division. */
            int64_t d = (int64_t)1 << sh;
            int64_t q = v / d;
            if ((v % d != 0) && (v < 0))
                q -= 1;
            NP_CHECK(np_asr(v, sh) == q, "asr(%lld, %u) = %lld, want %lld", (long long)v, sh,
                     (long long)np_asr(v, sh), (long long)q);
        }
    }
    NP_CHECK(np_asr(INT64_MIN, 62) == -2, "asr(INT64_MIN, 62)");
    printf("np_asr: %u (value, shift) pairs equal floor division\n", checked);
    return 0;
}

static int fixed_round(void)
{
    /* Round half up: floor(v / 2^sh + 1/2); ties go toward +infinity. */
    NP_CHECK(np_shr_round_half_up(3, 1) == 2, "1.5 -> 2");
    NP_CHECK(np_shr_round_half_up(-3, 1) == -1, "-1.5 -> -1");
    NP_CHECK(np_shr_round_half_up(5, 2) == 1, "1.25 -> 1");
    NP_CHECK(np_shr_round_half_up(-5, 2) == -1, "-1.25 -> -1");
    NP_CHECK(np_shr_round_half_up(6, 2) == 2, "1.5 -> 2");
    NP_CHECK(np_shr_round_half_up(-6, 2) == -1, "-1.5 -> -1");
    NP_CHECK(np_shr_round_half_up(-7, 2) == -2, "-1.75 -> -2");
    NP_CHECK(np_shr_round_half_up(7, 0) == 7, "sh 0 exact");
    NP_CHECK(np_shr_round_half_up_u(0xff, 8) == 1, "255/256 -> 1");
    NP_CHECK(np_shr_round_half_up_u(0x7f, 8) == 0, "127/256 -> 0");
    NP_CHECK(np_shr_round_half_up_u(0x80, 8) == 1, "tie -> up");
    /* Every value of a 16-bit range against the exact real rounding in double. */
    unsigned checked = 0;
    for (int64_t v = -40000; v <= 40000; v++)
        for (unsigned sh = 0; sh < 12; sh++, checked++) {
            double want = floor((double)v / (double)((int64_t)1 << sh) + 0.5);
            NP_CHECK((double)np_shr_round_half_up(v, sh) == want, "round(%lld, %u)", (long long)v, sh);
        }
    printf("np_shr_round_half_up: %u cases equal floor(v/2^sh + 1/2)\n", checked);
    return 0;
}

static int fixed_sat_sext(void)
{
    NP_CHECK(np_sat_s(200, 8) == 127, "sat 200");
    NP_CHECK(np_sat_s(-200, 8) == -128, "sat -200");
    NP_CHECK(np_sat_s(-128, 8) == -128, "sat -128 exact");
    NP_CHECK(np_sat_s(127, 8) == 127, "sat 127 exact");
    NP_CHECK(np_sat_u(-1, 8) == 0 && np_sat_u(256, 8) == 255 && np_sat_u(255, 8) == 255, "sat_u");
    NP_CHECK(np_sext(0x80, 8) == -128 && np_sext(0x7f, 8) == 127 && np_sext(0x1ff, 8) == -1, "sext 8");
    NP_CHECK(np_sext(0x400, 11) == -1024 && np_sext(0x3ff, 11) == 1023, "sext 11");
    NP_CHECK(np_wrap_s(128, 8) == -128 && np_wrap_s(-129, 8) == 127, "wrap");
    NP_CHECK(np_fits_s(-1024, 11) && !np_fits_s(1024, 11) && np_fits_u(255, 8) && !np_fits_u(-1, 8),
             "fits");
    NP_CHECK(NP_MASK(0) == 0 && NP_MASK(6) == 63 && NP_MASK(63) == INT64_MAX, "mask");
    /* sext(trunc(v)) == v for every v an n-bit signal can hold (n >= 3 holds -3..3). */
    for (unsigned n = 3; n < 63; n++)
        for (int64_t v = -3; v <= 3; v++) {
            int64_t w = np_sext(np_trunc_u((uint64_t)v, n), n);
            NP_CHECK(w == v, "sext(trunc(%lld, %u)) = %lld", (long long)v, n, (long long)w);
        }
    NP_CHECK(np_sext(np_trunc_u((uint64_t)-1, 1), 1) == -1 && np_sext(0, 1) == 0, "1-bit signal");
    puts("saturation, sign extension and masking: all cases pass");
    return 0;
}

/*
 * A slow, literal transcription of the seed's Appendix B shuffle(), kept
 * independent of np_hash.c (which is organised differently).
 */
static int jb(int n, int bit) { return n >> bit & 1; }
static int jbb(int i, int j, int k, int bit)
{
    static const int T[] = { 0x15, 0x38, 0x32, 0x2c, 0x0d, 0x13, 0x07, 0x2a };
    return T[jb(i, bit) << 2 | jb(j, bit) << 1 | jb(k, bit)];
}
static int java_shuffle(int i, int j, int k)
{
    return jbb(i, j, k, 0) + jbb(j, k, i, 1) + jbb(k, i, j, 2) + jbb(i, j, k, 3) + jbb(j, k, i, 4) +
           jbb(k, i, j, 5) + jbb(i, j, k, 6) + jbb(j, k, i, 7);
}

static int hash_kat(void)
{
    /* Computed by hand-transcribing the Java into Python (not from this code). */
    static const struct { uint8_t i, j, k, h; } kat[] = {
        { 0, 0, 0, 40 },    { 1, 0, 0, 32 },     { 0, 1, 0, 5 },     { 0, 0, 1, 11 },
        { 255, 255, 255, 16 }, { 1, 2, 3, 24 },  { 17, 99, 200, 47 }, { 128, 64, 32, 32 },
        { 255, 0, 128, 39 }, { 85, 170, 85, 29 }, { 200, 13, 77, 51 }, { 3, 250, 9, 43 },
    };
    for (unsigned n = 0; n < sizeof kat / sizeof kat[0]; n++) {
        uint8_t h = np_hash6(kat[n].i, kat[n].j, kat[n].k);
        NP_CHECK(h == kat[n].h, "hash(%u,%u,%u) = %u, want %u", kat[n].i, kat[n].j, kat[n].k, h, kat[n].h);
    }
    /* 8 * 0x15 = 168 = 40 mod 64: the origin reads pattern 0 eight times. */
    NP_CHECK(np_hash6(0, 0, 0) == (8 * 0x15) % 64, "origin");
    puts("hash known answers: 13 pass");
    return 0;
}

static int hash_exhaustive(void)
{
    /* All 2^24 lattice points against the literal transcription; histogram of the 64 values. */
    uint64_t count[64] = { 0 };
    uint64_t fnv = 0xcbf29ce484222325u;
    unsigned bad = 0;
    for (int i = 0; i < 256; i++)
        for (int j = 0; j < 256; j++)
            for (int k = 0; k < 256; k++) {
                uint8_t h = np_hash6((uint8_t)i, (uint8_t)j, (uint8_t)k);
                if (h != (java_shuffle(i, j, k) & 63))
                    bad++;
                count[h]++;
                fnv = (fnv ^ h) * 0x100000001b3u;
            }
    NP_CHECK(bad == 0, "%u lattice points differ from the Appendix B transcription", bad);
    /* Distribution: expected 2^24 / 64 = 262144 each if uniform. */
    double chi2 = 0.0;
    uint64_t lo = UINT64_MAX, hi = 0;
    unsigned present = 0;
    for (unsigned v = 0; v < 64; v++) {
        double d = (double)count[v] - 262144.0;
        chi2 += d * d / 262144.0;
        lo = count[v] < lo ? count[v] : lo;
        hi = count[v] > hi ? count[v] : hi;
        present += count[v] != 0;
    }
    printf("hash over 2^24 points: %u/64 values occur, count min %llu max %llu (uniform 262144), chi2 %.0f (63 dof)\n",
           present, (unsigned long long)lo, (unsigned long long)hi, chi2);
    printf("histogram:");
    for (unsigned v = 0; v < 64; v++)
        printf("%s%llu", v % 8 ? " " : "\n  ", (unsigned long long)count[v]);
    printf("\nFNV-1a of the table: %016llx\n", (unsigned long long)fnv);
    NP_CHECK(present == 64, "every 6-bit index must occur");
    /* The checked-in table hash: any change to any of the 2^24 entries shows here. */
    NP_CHECK(fnv == NP_HASH_TABLE_FNV, "table hash %016llx changed", (unsigned long long)fnv);
    return 0;
}

static int grad_all64(void)
{
    /* Decoded coefficients agree with Appendix B (np_ref_grad, in double) for every index. */
    static const double pts[][3] = { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 }, { 0.25, -0.5, 0.75 },
                                     { -1, -1, -1 }, { 0.1, 0.2, 0.3 }, { 3, 5, 7 } };
    unsigned three = 0;
    for (unsigned h = 0; h < 64; h++) {
        np_grad g = np_grad_decode((uint8_t)h);
        unsigned nz = (unsigned)(g.cx != 0) + (unsigned)(g.cy != 0) + (unsigned)(g.cz != 0);
        NP_CHECK(nz == 2 || nz == 3, "h=%u has %u non-zero terms", h, nz);
        NP_CHECK(g.cx >= -1 && g.cx <= 1 && g.cy >= -1 && g.cy <= 1 && g.cz >= -1 && g.cz <= 1, "h=%u", h);
        three += nz == 3;
        for (unsigned p = 0; p < sizeof pts / sizeof pts[0]; p++) {
            double want = np_ref_grad(h, pts[p][0], pts[p][1], pts[p][2]);
            double got = g.cx * pts[p][0] + g.cy * pts[p][1] + g.cz * pts[p][2];
            NP_CHECK(got == want, "h=%u point %u: %g vs %g", h, p, got, want);
        }
        /* Fixed-point form: exact on s9 Q1.8 offsets. */
        int16_t dx = -256, dy = 255, dz = -17;
        int16_t q = np_grad_apply_q8(g, dx, dy, dz);
        NP_CHECK((double)q == np_ref_grad(h, (double)dx, (double)dy, (double)dz), "h=%u fixed", h);
    }
    /* Appendix B: b == 0 gives the three-term gradients: 16 of 64 indices. */
    NP_CHECK(three == 16, "three-term gradients %u, want 16", three);
    printf("gradient decode: 64 indices agree with Appendix B; %u three-term, %u two-term\n", three, 64 - three);
    return 0;
}

static int grad_fixed_range(void)
{
    /* |g| <= 768 for every index and every s9 Q1.8 offset corner: fits s11. */
    int lo = 0, hi = 0;
    for (unsigned h = 0; h < 64; h++) {
        np_grad g = np_grad_decode((uint8_t)h);
        for (int a = 0; a < 8; a++) {
            int16_t d[2] = { -256, 255 };
            int v = np_grad_apply_q8(g, d[a & 1], d[a >> 1 & 1], d[a >> 2 & 1]);
            lo = v < lo ? v : lo;
            hi = v > hi ? v : hi;
        }
    }
    printf("gradient contribution range over all indices and offsets: [%d, %d] (s11 Q2.8 holds [-1024, 1023])\n", lo, hi);
    /* -768: (1,1,1).(-256,-256,-256); +768: (-1,-1,-1).(-256,-256,-256). */
    NP_CHECK(lo == -768 && hi == 768, "range [%d, %d], want [-768, 768]", lo, hi);
    NP_CHECK(np_fits_s(lo, 11) && np_fits_s(hi, 11), "fits s11");
    return 0;
}

static int rng_kat(void)
{
    /* splitmix64 and xoshiro256** against their authors' published outputs. */
    static const uint64_t sm[] = { 6457827717110365317u, 3203168211198807973u, 9817491932198370423u,
                                   4593380528125082431u, 16408922859458223821u };
    uint64_t st = 1234567;
    for (unsigned n = 0; n < 5; n++)
        NP_CHECK(np_splitmix64(&st) == sm[n], "splitmix64 output %u", n);
    static const uint64_t xo[] = { 11520u, 0u, 1509978240u, 1215971899390074240u, 1216172134540287360u };
    np_rng r = { { 1, 2, 3, 4 } };
    for (unsigned n = 0; n < 5; n++)
        NP_CHECK(np_rng_next(&r) == xo[n], "xoshiro256** output %u", n);
    /* Bounded draws stay in range and hit both ends. */
    np_rng_seed(&r, 42);
    unsigned seen = 0;
    for (unsigned n = 0; n < 10000; n++) {
        uint64_t v = np_rng_below(&r, 7);
        NP_CHECK(v < 7, "below 7: %llu", (unsigned long long)v);
        seen |= 1u << v;
    }
    NP_CHECK(seen == 0x7f, "every value of [0,7) drawn");
    puts("splitmix64 and xoshiro256** match the published known answers");
    return 0;
}

/* ------------------------------------------------------------------------- */
/* Configuration keys of every registered unit (np_unit_key, units.c). */

/* For every unit: the default configuration's text configures, every key once, to the same block and text. */
static int unit_keys_roundtrip(void)
{
    const np_unit *u;
    for (size_t i = 0; (u = np_unit_at(i)) != NULL; i++) {
        np_unit_cfg def, back, none;
        char text[512], again[512], err[512] = "";
        NP_CHECK(u->keys && np_unit_key_count(u) > 0, "%s declares no keys", u->name);
        np_unit_cfg_default(u, &def);
        np_unit_cfg_format(u, &def, text, sizeof text);
        NP_CHECK(np_unit_configure_all(u, &back, text, err, sizeof err) == 0, "%s: '%s': %s", u->name, text, err);
        np_unit_cfg_format(u, &back, again, sizeof again);
        NP_CHECK(strcmp(text, again) == 0, "%s: '%s' came back as '%s'", u->name, text, again);
        NP_CHECK(memcmp(&def, &back, sizeof def) == 0, "%s: the block differs after the round trip", u->name);
        NP_CHECK(np_unit_configure(u, &none, NULL, err, sizeof err) == 0, "%s: defaults: %s", u->name, err);
        NP_CHECK(memcmp(&def, &none, sizeof def) == 0, "%s: configure(NULL) is not the default", u->name);
        NP_CHECK(u->cfg_check == NULL || u->cfg_check(&def) == NULL, "%s: the default is inconsistent", u->name);
        /* The text is every key once, in the table's order, one space between (a key added later: not at its default). */
        const char *p = text;
        for (const np_unit_key *k = u->keys; k->name; k++) {
            size_t n = strlen(k->name);
            if (k->flags & NP_UNIT_KEY_ADDED) {
                NP_CHECK(strncmp(p, k->name, n) != 0 || p[n] != '=', "%s: key %s (added later) at its default in '%s'",
                         u->name, k->name, text);
                continue;
            }
            NP_CHECK(strncmp(p, k->name, n) == 0 && p[n] == '=', "%s: key %s not next in '%s'", u->name, k->name, text);
            p = strchr(p, ' ');
            p = p ? p + 1 : text + strlen(text);
        }
        NP_CHECK(*p == '\0', "%s: more than the keys in '%s'", u->name, text);
        printf("%s: %s\n", u->name, text);
    }
    return 0;
}

/* Every key's lo and hi are accepted, lo - 1 and hi + 1 refused with a message naming the key and range. */
static int unit_keys_ranges(void)
{
    unsigned checked = 0;
    const np_unit *u;
    for (size_t i = 0; (u = np_unit_at(i)) != NULL; i++) {
        for (const np_unit_key *k = u->keys; k->name; k++) {
            np_unit_cfg cfg;
            char v[32], err[512], range[128];
            np_unit_cfg_default(u, &cfg);
            np_unit_key_range(k, range, sizeof range);
            if (k->word) {
                for (unsigned w = k->lo; w <= k->hi; w++) {
                    NP_CHECK(k->word(w) != NULL, "%s %s: no word for %u", u->name, k->name, w);
                    if (!k->word(w))
                        continue;
                    NP_CHECK(np_unit_cfg_set(u, &cfg, k->name, k->word(w), err, sizeof err) == 0, "%s", err);
                    NP_CHECK(np_unit_key_get(k, &cfg) == w, "%s %s=%s", u->name, k->name, k->word(w));
                }
                err[0] = '\0';
                NP_CHECK(np_unit_cfg_set(u, &cfg, k->name, "nosuch", err, sizeof err) != 0, "%s: word accepted",
                         k->name);
                NP_CHECK(strstr(err, k->name) && strstr(err, k->word(k->lo)), "%s %s: message '%s'", u->name,
                         k->name, err);
                checked++;
                continue;
            }
            const unsigned ends[2] = { k->lo, k->hi };
            for (unsigned e = 0; e < 2; e++) {
                snprintf(v, sizeof v, "%u", ends[e]);
                err[0] = '\0';
                NP_CHECK(np_unit_cfg_set(u, &cfg, k->name, v, err, sizeof err) == 0, "%s %s=%s refused: %s", u->name,
                         k->name, v, err);
                NP_CHECK(np_unit_key_get(k, &cfg) == ends[e], "%s %s=%s stored %u", u->name, k->name, v,
                         np_unit_key_get(k, &cfg));
            }
            const unsigned long long outside[2] = { (unsigned long long)k->lo - 1u, (unsigned long long)k->hi + 1u };
            for (unsigned e = k->lo == 0 ? 1 : 0; e < 2; e++) {
                snprintf(v, sizeof v, "%llu", outside[e]);
                err[0] = '\0';
                NP_CHECK(np_unit_cfg_set(u, &cfg, k->name, v, err, sizeof err) != 0, "%s %s=%s accepted", u->name,
                         k->name, v);
                NP_CHECK(strstr(err, k->name) && strstr(err, v) && strstr(err, range),
                         "%s %s=%s: message '%s' does not name the key, value and range %s", u->name, k->name, v, err,
                         range);
            }
            checked++;
        }
    }
    printf("%u keys: both ends accepted, one beyond refused naming the key\n", checked);
    return 0;
}

/* Decimal digits only: "010" is ten; a sign, a base prefix, blanks, junk or nothing are refused. */
static int unit_keys_decimal(void)
{
    unsigned v = 0;
    NP_CHECK(np_unit_parse_uint("010", 0, 100, &v) == 0 && v == 10, "\"010\" is %u, expected ten", v);
    NP_CHECK(np_unit_parse_uint("0", 0, 100, &v) == 0 && v == 0, "\"0\"");
    NP_CHECK(np_unit_parse_uint("4294967295", 0, 4294967295u, &v) == 0 && v == 4294967295u, "UINT_MAX");
    static const char *const bad[] = { "0x5", "+3", "", "3abc", " 3", "3 ", "-1", "1e2", "99999999999999999999999" };
    for (unsigned i = 0; i < sizeof bad / sizeof bad[0]; i++)
        NP_CHECK(np_unit_parse_uint(bad[i], 0, 4294967295u, &v) != 0, "\"%s\" accepted as %u", bad[i], v);
    const np_unit *u = np_unit_find("classic3");
    np_unit_cfg cfg;
    char err[512], text[256];
    NP_CHECK(np_unit_configure(u, &cfg, "out_bits=010", err, sizeof err) == 0, "%s", err);
    np_unit_cfg_format(u, &cfg, text, sizeof text);
    NP_CHECK(strcmp(text, "out_bits=10 s_frac=14 lerp_frac=13") == 0, "out_bits=010 gave '%s'", text);
    for (unsigned i = 0; i < 5; i++) {
        char spec[64];
        snprintf(spec, sizeof spec, "out_bits=%s", bad[i]);
        err[0] = '\0';
        NP_CHECK(np_unit_configure(u, &cfg, spec, err, sizeof err) != 0, "'%s' accepted", spec);
        NP_CHECK(strstr(err, "out_bits=") && strstr(err, "2..16"), "'%s': message '%s'", spec, err);
        printf("%-14s -> %s\n", spec, err);
    }
    return 0;
}

/* A key given twice is an error naming it; an unknown key lists the keys; a '# config' text misses none. */
static int unit_keys_twice_missing(void)
{
    const np_unit *u;
    for (size_t i = 0; (u = np_unit_at(i)) != NULL; i++) {
        np_unit_cfg cfg;
        char text[512], spec[1024], err[512];
        np_unit_cfg_default(u, &cfg);
        np_unit_cfg_format(u, &cfg, text, sizeof text);
        for (const np_unit_key *k = u->keys; k->name; k++) {
            char one[128];
            np_unit_key_text(k, &cfg, one, sizeof one);
            /* Twice, in configure (a subset) and in a full text. */
            snprintf(spec, sizeof spec, "%s=%s,%s=%s", k->name, one, k->name, one);
            err[0] = '\0';
            NP_CHECK(np_unit_configure(u, &cfg, spec, err, sizeof err) != 0, "%s: '%s' accepted", u->name, spec);
            NP_CHECK(strstr(err, k->name) && strstr(err, "twice"), "%s '%s': message '%s'", u->name, spec, err);
            if (k->flags & NP_UNIT_KEY_ADDED) /* left out of the default's text: give it twice there */
                snprintf(spec, sizeof spec, "%s %s=%s %s=%s", text, k->name, one, k->name, one);
            else
                snprintf(spec, sizeof spec, "%s %s=%s", text, k->name, one);
            err[0] = '\0';
            NP_CHECK(np_unit_configure_all(u, &cfg, spec, err, sizeof err) != 0, "%s: '%s' accepted", u->name, spec);
            NP_CHECK(strstr(err, k->name) && strstr(err, "twice"), "%s '%s': message '%s'", u->name, spec, err);
            /* Missing: the full text without this key. */
            spec[0] = '\0';
            for (const np_unit_key *q = u->keys; q->name; q++)
                if (q != k) {
                    np_unit_key_text(q, &cfg, one, sizeof one);
                    snprintf(spec + strlen(spec), sizeof spec - strlen(spec), "%s%s=%s", *spec ? " " : "", q->name, one);
                }
            err[0] = '\0';
            if (k->flags & NP_UNIT_KEY_ADDED) {
                /* A key added later may be missing from a '# config' text (the files before it): its default. */
                NP_CHECK(np_unit_configure_all(u, &cfg, spec, err, sizeof err) == 0, "%s: '%s' refused: %s", u->name,
                         spec, err);
                NP_CHECK(np_unit_key_get(k, &cfg) == k->def, "%s: %s missing is not its default", u->name, k->name);
                continue;
            }
            NP_CHECK(np_unit_configure_all(u, &cfg, spec, err, sizeof err) != 0, "%s: '%s' accepted", u->name, spec);
            NP_CHECK(strstr(err, k->name) && strstr(err, "missing"), "%s '%s': message '%s'", u->name, spec, err);
            NP_CHECK(np_unit_configure(u, &cfg, spec, err, sizeof err) == 0, "%s: a subset: %s", u->name, err);
        }
        err[0] = '\0';
        NP_CHECK(np_unit_configure(u, &cfg, "nosuch=1", err, sizeof err) != 0, "%s: unknown key accepted", u->name);
        for (const np_unit_key *k = u->keys; k->name; k++)
            NP_CHECK(strstr(err, k->name) != NULL, "%s: '%s' does not list %s", u->name, err, k->name);
        printf("%s: %s\n", u->name, err);
    }
    return 0;
}

/* A derived default follows the other keys unless given, whatever the order. */
static int unit_keys_derived(void)
{
    const np_unit *u = np_unit_find("classic3");
    np_unit_cfg a, b;
    char ta[256], tb[256], err[512];
    NP_CHECK(np_unit_configure(u, &a, "s_frac=10,out_bits=12", err, sizeof err) == 0, "%s", err);
    NP_CHECK(np_unit_configure(u, &b, "out_bits=12 s_frac=10", err, sizeof err) == 0, "%s", err);
    np_unit_cfg_format(u, &a, ta, sizeof ta);
    np_unit_cfg_format(u, &b, tb, sizeof tb);
    NP_CHECK(strcmp(ta, tb) == 0 && strcmp(ta, "out_bits=12 s_frac=10 lerp_frac=15") == 0, "'%s' / '%s'", ta, tb);
    NP_CHECK(np_unit_configure(u, &a, "out_bits=16", err, sizeof err) == 0, "%s", err);
    np_unit_cfg_format(u, &a, ta, sizeof ta);
    NP_CHECK(strcmp(ta, "out_bits=16 s_frac=20 lerp_frac=19") == 0, "out_bits=16 gave '%s'", ta);
    /* The consistency of several keys is the unit's cfg_check: lerp_frac >= out_bits - 2. */
    err[0] = '\0';
    NP_CHECK(np_unit_configure(u, &a, "out_bits=16,lerp_frac=13", err, sizeof err) != 0, "lerp_frac 13 < 14 accepted");
    NP_CHECK(strstr(err, "lerp_frac") != NULL, "message '%s'", err);
    printf("%s; out_bits=16,lerp_frac=13: %s\n", tb, err);
    return 0;
}

/* The value of key name in the default configuration of unit unit. */
static unsigned default_key(const char *unit, const char *name)
{
    const np_unit *u = np_unit_find(unit);
    const np_unit_key *k = u ? np_unit_key_find(u, name) : NULL;
    np_unit_cfg cfg;
    NP_CHECK(k != NULL, "%s has no key %s", unit, name);
    if (!k)
        return 0;
    np_unit_cfg_default(u, &cfg);
    return np_unit_key_get(k, &cfg);
}

/* The key tables' defaults are the models' own (np_*_cfg_default), which the models' tests use. */
static int unit_keys_model_defaults(void)
{
    np_classic_cfg c = np_classic_cfg_default(8);
    NP_CHECK(default_key("classic3", "out_bits") == c.out_bits && default_key("classic3", "s_frac") == c.s_frac &&
                 default_key("classic3", "lerp_frac") == c.lerp_frac, "classic3");
    np_simplex_cfg x = np_simplex_cfg_default(16, 16, 1);
    NP_CHECK(default_key("simplex3", "out_bits") == x.out_bits && default_key("simplex3", "dout_bits") == x.dout_bits &&
                 default_key("simplex3", "deriv") == x.deriv && default_key("simplex3", "t_frac") == x.t_frac &&
                 default_key("simplex3", "p_frac") == x.p_frac && default_key("simplex3", "k_frac") == x.k_frac,
             "simplex3");
    np_fdiff_cfg f = np_fdiff_cfg_default();
    NP_CHECK(default_key("fdiff", "idx_int") == f.idx_int && default_key("fdiff", "w_frac") == f.w_frac &&
                 default_key("fdiff", "guard") == f.guard && default_key("fdiff", "resetup") == f.resetup &&
                 default_key("fdiff", "setup_mults") == f.setup_mults && default_key("fdiff", "mult_lat") == f.mult_lat,
             "fdiff");
    np_texel_cfg t = np_texel_cfg_default();
    NP_CHECK(default_key("texel", "idx_int") == t.idx_int && default_key("texel", "w_frac") == t.w_frac &&
                 default_key("texel", "guard") == t.guard && default_key("texel", "weight_frac") == t.weight_frac &&
                 default_key("texel", "setup_mults") == t.setup_mults && default_key("texel", "mult_lat") == t.mult_lat,
             "texel");
    puts("classic3, simplex3, fdiff, texel: the key tables' defaults are the models' defaults");
    return 0;
}

static const np_test_case cases[] = {
    { "unit_keys_model_defaults", unit_keys_model_defaults },
    { "unit_keys_roundtrip", unit_keys_roundtrip },
    { "unit_keys_ranges", unit_keys_ranges },
    { "unit_keys_decimal", unit_keys_decimal },
    { "unit_keys_twice_missing", unit_keys_twice_missing },
    { "unit_keys_derived", unit_keys_derived },
    { "fixed_asr", fixed_asr },
    { "fixed_round", fixed_round },
    { "fixed_sat_sext", fixed_sat_sext },
    { "hash_kat", hash_kat },
    { "hash_exhaustive", hash_exhaustive },
    { "grad_all64", grad_all64 },
    { "grad_fixed_range", grad_fixed_range },
    { "rng_kat", rng_kat },
    { NULL, NULL },
};
NP_TEST_MAIN(cases)
