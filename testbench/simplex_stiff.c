/* SPDX-License-Identifier: MIT */
/* The simplex unit's stability cases: simplex faces, the kernel at t = 0, the extreme inputs,
 * the largest magnitudes and widths, the wrap at 256. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "simplex_test.h"

/* ------------------------------------------------------------------------ */
/*
 * Simplex faces on the 8.8 grid: u = v exactly when X = Y (then i = j), and
 * so on. Each face case measures the error at the tie itself and one input
 * step either side, and counts the ties where the two simplices meeting
 * there differ by more than 2 LSB in the reference (so that choosing the
 * other simplex than Appendix B's rule would show as an error).
 */
typedef enum { FACE_UV, FACE_VW, FACE_UW, FACE_UVW } face_kind;

static void face_point(face_kind k, np_rng *r, uint16_t in[3], unsigned *step_axis)
{
    uint16_t a = rnd16(r), b = rnd16(r);
    switch (k) {
    case FACE_UV: in[0] = in[1] = a; in[2] = b; *step_axis = 0; break;
    case FACE_VW: in[1] = in[2] = a; in[0] = b; *step_axis = 1; break;
    case FACE_UW: in[0] = in[2] = a; in[1] = b; *step_axis = 2; break;
    default: in[0] = in[1] = in[2] = a; *step_axis = (unsigned)(np_rng_next(r) % 3u); break;
    }
}

static int face_case(face_kind k, const char *name)
{
    np_simplex_cfg cfg = default_cfg();
    np_rng r;
    np_rng_seed(&r, 77 + (uint64_t)k);
    emax on, side;
    memset(&on, 0, sizeof on);
    memset(&side, 0, sizeof side);
    unsigned n = k == FACE_UVW ? 65536u : 200000u, decisive = 0, ties_same = 0;
    double maxjump = 0.0;
    uint16_t jat[3] = { 0, 0, 0 };
    for (unsigned it = 0; it < n; it++) {
        uint16_t in[3];
        unsigned ax;
        face_point(k, &r, in, &ax);
        if (k == FACE_UVW)
            in[0] = in[1] = in[2] = (uint16_t)it; /* the whole diagonal */
        uint32_t cell[3];
        int32_t off[3];
        front_end(in[0], in[1], in[2], cell, off);
        NP_CHECK((k == FACE_UV && off[0] == off[1]) || (k == FACE_VW && off[1] == off[2]) ||
                     (k == FACE_UW && off[0] == off[2]) || (k == FACE_UVW && off[0] == off[1] && off[1] == off[2]),
                 "not on the face");
        /* Appendix B's ranking in double at the same point gives the same simplex as the exact one. */
        {
            double px = in[0] / 256.0, py = in[1] / 256.0, pz = in[2] / 256.0, s3 = (px + py + pz) / 3;
            double fi = floor(px + s3), fj = floor(py + s3), fk = floor(pz + s3), s6 = (fi + fj + fk) / 6.;
            double u = px - fi + s6, v = py - fj + s6, w = pz - fk + s6;
            int jhi = u >= w ? u >= v ? 0 : 1 : v >= w ? 1 : 2;
            int jlo = u < w ? u < v ? 0 : 1 : v < w ? 1 : 2;
            uint8_t hi, lo;
            np_simplex_rank(off[0], off[1], off[2], &hi, &lo);
            NP_CHECK(hi == jhi && lo == jlo, "(%04x,%04x,%04x): rank %u,%u, Appendix B %d,%d", in[0], in[1], in[2], hi,
                     lo, jhi, jlo);
            ties_same += hi == jhi && lo == jlo;
        }
        if (k == FACE_UVW) {
            /* The six simplices around the diagonal differ only in corners e_a and e_a + e_b: all out of reach. */
            static const unsigned masks[6] = { 1, 2, 4, 3, 5, 6 };
            for (unsigned m = 0; m < 6; m++) {
                int32_t d[3];
                unsigned c = (masks[m] == 3 || masks[m] == 5 || masks[m] == 6) ? 2u : 1u;
                for (unsigned a = 0; a < 3; a++)
                    d[a] = np_simplex_corner_d(off[a], masks[m] >> a & 1u, c);
                NP_CHECK(np_simplex_kernel_t(np_simplex_r2(d)) == 0, "diagonal corner %u in reach", masks[m]);
            }
        }
        errs e;
        measure(&cfg, in[0], in[1], in[2], &e);
        emax_add(&on, &e, in[0], in[1], in[2]);
        /* The reference's two one-sided limits at the tie (1e-9 along the step axis). */
        double p[3] = { in[0] / 256.0, in[1] / 256.0, in[2] / 256.0 }, pp[3], pm[3];
        memcpy(pp, p, sizeof p);
        memcpy(pm, p, sizeof p);
        pp[ax] += 1e-9;
        pm[ax] -= 1e-9;
        double jump = fabs(np_ref_simplex3(pp[0], pp[1], pp[2], NULL) - np_ref_simplex3(pm[0], pm[1], pm[2], NULL)) *
                      p2(np_simplex_f_frac(&cfg));
        if (jump > maxjump) {
            maxjump = jump;
            memcpy(jat, in, sizeof jat);
        }
        decisive += jump > 2.0;
        for (int s = -1; s <= 1; s += 2) {
            uint16_t q[3] = { in[0], in[1], in[2] };
            q[ax] = (uint16_t)(q[ax] + s);
            measure(&cfg, q[0], q[1], q[2], &e);
            emax_add(&side, &e, q[0], q[1], q[2]);
        }
    }
    printf("%s: %u tie inputs, the exact ranking equals Appendix B's at %u; the reference's one-sided limits "
           "(+-1e-9 across the face) differ by up to %.3g LSB of f (at (%04x,%04x,%04x)), by more than 2 LSB at "
           "%u of them\n",
           name, n, ties_same, maxjump, jat[0], jat[1], jat[2], decisive);
    emax_print("  on the face", &on, 1);
    emax_print("  one step either side", &side, 1);
    emax_check(name, &on, &cfg);
    emax_check(name, &side, &cfg);
    if (k == FACE_UVW) {
        /* On the diagonal the corners in which the six simplices differ are at |d|^2 >= 2/3 > 0.6. */
        NP_CHECK(maxjump < 1e-3, "jump %.3g LSB on the diagonal", maxjump);
        printf("  on u = v = w the choice of simplex does not matter: every corner in which the six simplices "
               "differ has t < 0 (|d|^2 >= 2/3), so f and df are continuous there\n");
    } else {
        NP_CHECK(decisive > 0, "no decisive tie: the case cannot tell the simplex choice");
    }
    return 0;
}

int simplex_faces_uv(void) { return face_case(FACE_UV, "faces_uv (X = Y)"); }
int simplex_faces_vw(void) { return face_case(FACE_VW, "faces_vw (Y = Z)"); }
int simplex_faces_uw(void) { return face_case(FACE_UW, "faces_uw (X = Z)"); }
int simplex_faces_uvw(void) { return face_case(FACE_UVW, "faces_uvw (X = Y = Z)"); }

/* ------------------------------------------------------------------------ */

/* The offsets D of the four corners of the simplex that local configuration (U, V, W) lies in. */
static void corner_offsets(int32_t u, int32_t v, int32_t w, int32_t d[4][3])
{
    uint8_t hi, lo;
    np_simplex_rank(u, v, w, &hi, &lo);
    const int32_t off[3] = { u, v, w };
    for (unsigned k = 0; k < 4; k++) {
        unsigned mask = np_simplex_corner_mask(hi, lo, k);
        for (unsigned a = 0; a < 3; a++)
            d[k][a] = np_simplex_corner_d(off[a], mask >> a & 1u, k);
    }
}

typedef struct tz_ctx {
    int32_t tmin_pos, tmax_neg;   /* smallest T > 0 and largest T <= 0 (T before the clamp) */
    int32_t at_pos[4], at_neg[4]; /* U, V, W, corner */
    uint64_t hist_zero;           /* configurations with some corner at T == 0 (none expected) */
} tz_ctx;

static void tz_visit(void *ctxv, int32_t u, int32_t v, int32_t w)
{
    tz_ctx *c = ctxv;
    int32_t cd[4][3];
    corner_offsets(u, v, w, cd);
    for (unsigned k = 0; k < 4; k++) {
        int32_t td = NP_SIMPLEX_T_VERTEX - NP_SIMPLEX_R2_SCALE * (int32_t)np_simplex_r2(cd[k]);
        if (td == 0)
            c->hist_zero++;
        if (td > 0 && td < c->tmin_pos) {
            c->tmin_pos = td;
            c->at_pos[0] = u, c->at_pos[1] = v, c->at_pos[2] = w, c->at_pos[3] = (int32_t)k;
        }
        if (td <= 0 && td > c->tmax_neg) {
            c->tmax_neg = td;
            c->at_neg[0] = u, c->at_neg[1] = v, c->at_neg[2] = w, c->at_neg[3] = (int32_t)k;
        }
    }
}

/* The model's T of corner k at an input (stages SK..KT). */
static uint32_t corner_tau2(const np_simplex_cfg *cfg, const uint16_t in[3], unsigned k, int32_t *t_unclamped)
{
    np_simplex_sig s;
    memset(&s, 0, sizeof s);
    s.x = in[0];
    s.y = in[1];
    s.z = in[2];
    for (unsigned st = 0; st < 5; st++) /* SK RK CH KT P2 */
        np_simplex_stages_d[st].fn(cfg, &s);
    *t_unclamped = NP_SIMPLEX_T_VERTEX - NP_SIMPLEX_R2_SCALE * (int32_t)s.r2[k];
    return s.tau2[k];
}

int simplex_kernel_t_zero(void)
{
    /*
     * Over every local configuration: the T values nearest 0. T = 0 (t
     * exactly 0) is unreachable from 8.8 inputs (np_simplex.h says why), so
     * the case takes the nearest T on either side, at a corner, maps it to an
     * input in several cells, and measures the error there and one input
     * step either side on every axis.
     */
    tz_ctx c = { INT32_MAX, INT32_MIN, { 0 }, { 0 }, 0 };
    uint64_t nconf = for_each_config(tz_visit, &c);
    NP_CHECK(nconf == 25165824u, "local configurations %llu", (unsigned long long)nconf);
    NP_CHECK(c.hist_zero == 0, "t exactly 0 reached at %llu configurations", (unsigned long long)c.hist_zero);
    printf("%llu local configurations; t = 0 reached 0 times; nearest: T = %d (t = %+.3g) at U,V,W = %d,%d,%d "
           "corner %d; T = %d (t = %+.3g) at %d,%d,%d corner %d\n",
           (unsigned long long)nconf, c.tmin_pos, c.tmin_pos / (45.0 * 262144.0), c.at_pos[0], c.at_pos[1],
           c.at_pos[2], c.at_pos[3], c.tmax_neg, c.tmax_neg / (45.0 * 262144.0), c.at_neg[0], c.at_neg[1],
           c.at_neg[2], c.at_neg[3]);
    np_simplex_cfg cfg = default_cfg();
    emax at, side;
    memset(&at, 0, sizeof at);
    memset(&side, 0, sizeof side);
    for (int which = 0; which < 2; which++) {
        const int32_t *cf = which ? c.at_neg : c.at_pos;
        int32_t want = which ? c.tmax_neg : c.tmin_pos;
        for (int32_t i0 = 30; i0 < 200; i0 += 7) {
            uint16_t in[3];
            if (!input_of(cf[0], cf[1], cf[2], i0, in)) {
                NP_CHECK(0, "no input for the configuration in cell %d", i0);
                continue;
            }
            int32_t t;
            uint32_t tau2 = corner_tau2(&cfg, in, (unsigned)cf[3], &t);
            NP_CHECK(t == want, "input (%04x,%04x,%04x) has T %d, want %d", in[0], in[1], in[2], t, want);
            NP_CHECK(tau2 == 0, "tau2 %u at T = %d", tau2, t);
            if (i0 == 30)
                printf("  T = %d at input (%04x,%04x,%04x): tau2 = %u\n", t, in[0], in[1], in[2], tau2);
            errs e;
            measure(&cfg, in[0], in[1], in[2], &e);
            emax_add(&at, &e, in[0], in[1], in[2]);
            for (unsigned a = 0; a < 3; a++)
                for (int s = -1; s <= 1; s += 2) {
                    uint16_t q[3] = { in[0], in[1], in[2] };
                    q[a] = (uint16_t)(q[a] + s);
                    measure(&cfg, q[0], q[1], q[2], &e);
                    emax_add(&side, &e, q[0], q[1], q[2]);
                }
        }
    }
    emax_print("  at the T nearest 0", &at, 1);
    emax_print("  one input step either side", &side, 1);
    emax_check("kernel_t_zero", &at, &cfg);
    emax_check("kernel_t_zero", &side, &cfg);
    /* The support test on exact T: a tiny positive T still gives a zero term, continuously. */
    NP_CHECK(np_simplex_kernel_t((uint32_t)(NP_SIMPLEX_T_VERTEX / 5)) == 3u, "T of R2 = 1415577");
    NP_CHECK(np_simplex_kernel_t((uint32_t)(NP_SIMPLEX_T_VERTEX / 5 + 1)) == 0u, "clamp");
    return 0;
}

/* ------------------------------------------------------------------------ */

int simplex_extremes_0_and_max(void)
{
    /* Each axis at 0, 1, 0xfffe, 0xffff with the others random, and the 8 corners of the domain. */
    np_simplex_cfg cfg = default_cfg();
    np_rng r;
    np_rng_seed(&r, 5);
    static const uint16_t ext[4] = { 0x0000, 0x0001, 0xfffe, 0xffff };
    for (unsigned a = 0; a < 3; a++) {
        emax m;
        memset(&m, 0, sizeof m);
        for (unsigned it = 0; it < 100000; it++) {
            uint16_t in[3];
            rnd3(&r, in);
            in[a] = ext[it % 4u];
            errs e;
            measure(&cfg, in[0], in[1], in[2], &e);
            emax_add(&m, &e, in[0], in[1], in[2]);
        }
        char what[64];
        snprintf(what, sizeof what, "%c at 0, 1, 0xfffe, 0xffff", "xyz"[a]);
        emax_print(what, &m, 1);
        emax_check(what, &m, &cfg);
    }
    emax m;
    memset(&m, 0, sizeof m);
    for (unsigned c = 0; c < 8; c++) {
        uint16_t in[3] = { (c & 1u) ? 0xffff : 0, (c & 2u) ? 0xffff : 0, (c & 4u) ? 0xffff : 0 };
        errs e;
        measure(&cfg, in[0], in[1], in[2], &e);
        emax_add(&m, &e, in[0], in[1], in[2]);
        printf("  (%04x,%04x,%04x): f %d dfdx %d dfdy %d dfdz %d; reference %+.6f %+.6f %+.6f %+.6f\n", in[0], in[1],
               in[2], e.o.f, e.o.df[0], e.o.df[1], e.o.df[2], e.ref[0], e.ref[1], e.ref[2], e.ref[3]);
    }
    emax_print("the 8 corners of the domain", &m, 1);
    emax_check("corners", &m, &cfg);
    /* The origin: corner 0 sits on the point (G.d = 0), the others are out of reach: f = 0 exactly. */
    np_simplex_out o;
    np_simplex_eval(&cfg, 0, 0, 0, &o);
    NP_CHECK(o.f == 0 && np_ref_simplex3_q88(0, 0, 0, NULL) == 0.0, "f at the origin");
    return 0;
}

/* ------------------------------------------------------------------------ */

typedef struct mag_ctx {
    double bf, bd; /* adversarial-gradient bounds */
    int32_t at_f[3];
} mag_ctx;

static void mag_visit(void *ctxv, int32_t u, int32_t v, int32_t w)
{
    mag_ctx *c = ctxv;
    int32_t cd[4][3];
    corner_offsets(u, v, w, cd);
    double sf = 0.0, sd[3] = { 0.0, 0.0, 0.0 };
    for (unsigned k = 0; k < 4; k++) {
        double d[3];
        for (unsigned a = 0; a < 3; a++)
            d[a] = cd[k][a] / 1536.0;
        double t = .6 - d[0] * d[0] - d[1] * d[1] - d[2] * d[2];
        if (t <= 0)
            continue;
        double t3 = t * t * t, t4 = t3 * t, ad[3] = { fabs(d[0]), fabs(d[1]), fabs(d[2]) };
        /* max over the 20 gradients of |G.d| is |d|_1 (all three coefficients, signs aligned) */
        sf += 8 * t4 * (ad[0] + ad[1] + ad[2]);
        /* of |8t^4 G_a - 64t^3 (G.d) d_a|: |8t^4 - 64t^3 d_a^2| + 64t^3 |d_a| (|d_b| + |d_c|) */
        for (unsigned a = 0; a < 3; a++)
            sd[a] += fabs(8 * t4 - 64 * t3 * d[a] * d[a]) + 64 * t3 * ad[a] * (ad[(a + 1) % 3] + ad[(a + 2) % 3]);
    }
    if (sf > c->bf) {
        c->bf = sf;
        c->at_f[0] = u, c->at_f[1] = v, c->at_f[2] = w;
    }
    for (unsigned a = 0; a < 3; a++)
        c->bd = fmax(c->bd, sd[a]);
}

/* Widen an observed |max| and check a signal against its width. */
#define WIDTH_S(v, bits, mx)                                                                     \
    do {                                                                                         \
        NP_CHECK(np_fits_s((int64_t)(v), (bits)), "%s = %lld does not fit s%u", #v, (long long)(v), (unsigned)(bits)); \
        if (llabs((long long)(v)) > (mx))                                                        \
            (mx) = llabs((long long)(v));                                                        \
    } while (0)
#define WIDTH_U(v, bits, mx)                                                                     \
    do {                                                                                         \
        NP_CHECK(np_fits_u((int64_t)(v), (bits)), "%s = %lld does not fit u%u", #v, (long long)(v), (unsigned)(bits)); \
        if ((long long)(v) > (mx))                                                               \
            (mx) = (long long)(v);                                                               \
    } while (0)

enum { W_SK, W_CELL, W_OFF, W_D, W_GD, W_R2, W_T, W_TAU2, W_TAU3, W_TAU4, W_FC, W_Q, W_E, W_M, W_EM, W_S, W_QS, W_F, W_DF, W_N };
static const char *const W_NAME[W_N] = { "SX u19", "cell u9", "U s12", "D s12", "gd s14", "R2 u22", "T u23",
                                         "tau2 u(WT)", "tau3 u(WT)", "tau4 u(WT)", "fc s(WP+1)", "q s(WP+1)",
                                         "e s(WP+1)", "m s(WP+1)", "e-m s(WP+1)", "S s(WP+2)", "Q s(WP+3)",
                                         "f sN", "df sND" };

/* Run every stage on one input and check every signal against its declared width. */
static void check_widths(const np_simplex_cfg *cfg, uint16_t x, uint16_t y, uint16_t z, long long mx[W_N])
{
    np_simplex_sig s;
    memset(&s, 0, sizeof s);
    s.x = x;
    s.y = y;
    s.z = z;
    for (unsigned k = 0; k < NP_SIMPLEX_STAGES_D; k++)
        np_simplex_stages_d[k].fn(cfg, &s);
    unsigned wt = cfg->t_frac, wp = cfg->p_frac;
    for (unsigned a = 0; a < 3; a++) {
        WIDTH_U(s.sk[a], NP_SIMPLEX_SKEW_BITS, mx[W_SK]);
        WIDTH_U(s.cell[a], NP_SIMPLEX_CELL_BITS, mx[W_CELL]);
        WIDTH_S(s.off[a], NP_SIMPLEX_OFF_BITS, mx[W_OFF]);
        WIDTH_S(s.qs[a], wp + 3u, mx[W_QS]);
        WIDTH_S(s.df[a], cfg->dout_bits, mx[W_DF]);
    }
    for (unsigned c = 0; c < 4; c++) {
        WIDTH_S(s.gd[c], NP_SIMPLEX_GD_BITS, mx[W_GD]);
        WIDTH_U(s.r2[c], NP_SIMPLEX_R2_BITS, mx[W_R2]);
        WIDTH_U(s.t[c], NP_SIMPLEX_T_BITS, mx[W_T]);
        WIDTH_U(s.tau2[c], wt, mx[W_TAU2]);
        WIDTH_U(s.tau3[c], wt, mx[W_TAU3]);
        WIDTH_U(s.tau4[c], wt, mx[W_TAU4]);
        WIDTH_S(s.fc[c], wp + 1u, mx[W_FC]);
        WIDTH_S(s.q[c], wp + 1u, mx[W_Q]);
        for (unsigned a = 0; a < 3; a++) {
            WIDTH_S(s.d[c][a], NP_SIMPLEX_OFF_BITS, mx[W_D]);
            NP_CHECK(s.d[c][a] >= -NP_SIMPLEX_UNIT && s.d[c][a] <= NP_SIMPLEX_UNIT, "|D| > 1536");
            WIDTH_S(s.e[c][a], wp + 1u, mx[W_E]);
            WIDTH_S(s.m[c][a], wp + 1u, mx[W_M]);
            WIDTH_S(s.e[c][a] - s.m[c][a], wp + 1u, mx[W_EM]);
        }
        NP_CHECK(s.r2[c] <= (uint32_t)NP_SIMPLEX_UNIT * NP_SIMPLEX_UNIT, "R2 > 1536^2");
    }
    WIDTH_S(s.s, wp + 2u, mx[W_S]);
    WIDTH_S(s.f, cfg->out_bits, mx[W_F]);
    /* The saturation never acts: the rounded value before it already fits. */
    int64_t rf = np_simplex_requant(np_simplex_kf(cfg) * s.s, cfg->k_frac + cfg->p_frac, np_simplex_f_frac(cfg));
    NP_CHECK(np_fits_s(rf, cfg->out_bits), "f saturated: %lld", (long long)rf);
    for (unsigned a = 0; a < 3; a++) {
        int64_t rd = np_simplex_requant(np_simplex_kd(cfg) * s.qs[a], cfg->k_frac + cfg->p_frac, np_simplex_d_frac(cfg));
        NP_CHECK(np_fits_s(rd, cfg->dout_bits), "df saturated: %lld", (long long)rd);
    }
}

int simplex_max_magnitude(void)
{
    /* 1. The output formats: adversarial-gradient bounds over every local configuration. */
    mag_ctx c;
    memset(&c, 0, sizeof c);
    uint64_t nconf = for_each_config(mag_visit, &c);
    printf("over all %llu local configurations, any gradients: |f| <= %.6f (at U,V,W = %d,%d,%d), "
           "|df_a| <= %.6f\n",
           (unsigned long long)nconf, c.bf, c.at_f[0], c.at_f[1], c.at_f[2], c.bd);
    NP_CHECK(c.bf < 0.5, "f does not fit Q-1: bound %.6f", c.bf);
    NP_CHECK(c.bd < 2.0, "df does not fit Q1: bound %.6f", c.bd);
    NP_CHECK(fabs(c.bf - 0.347438) < 1e-6 && fabs(c.bd - 1.740774) < 1e-6, "bounds differ from np_simplex.h");

    /* 2. What the unit produces: random inputs and every exact cell centre (U = V = W = 384). */
    np_simplex_cfg cfg = default_cfg();
    long long mx[W_N];
    memset(mx, 0, sizeof mx);
    np_rng r;
    np_rng_seed(&r, 31);
    int32_t best_f = 0, best_d = 0;
    uint16_t at_f[3] = { 0, 0, 0 }, at_d[3] = { 0, 0, 0 };
    for (unsigned it = 0; it < 300000; it++) {
        uint16_t x = rnd16(&r), y = rnd16(&r), z = rnd16(&r);
        check_widths(&cfg, x, y, z, mx);
    }
    /* cells (i, j, k) with i + j + k = 0 mod 3 have an input exactly at the centre U = V = W = 384 */
    unsigned ncentre = 0;
    for (int32_t i = 0; i < 256; i++)
        for (int32_t j = 0; j < 256; j++)
            for (int32_t k = (3 - (i + j) % 3) % 3; k < 256; k += 3) {
                int32_t n = i + j + k, num[3] = { 384 + 1536 * i - 256 * n, 384 + 1536 * j - 256 * n,
                                                  384 + 1536 * k - 256 * n };
                if (num[0] < 0 || num[1] < 0 || num[2] < 0 || num[0] > 6 * 0xffff || num[1] > 6 * 0xffff ||
                    num[2] > 6 * 0xffff)
                    continue;
                uint16_t in[3] = { (uint16_t)(num[0] / 6), (uint16_t)(num[1] / 6), (uint16_t)(num[2] / 6) };
                np_simplex_out o;
                np_simplex_eval(&cfg, in[0], in[1], in[2], &o);
                ncentre++;
                if (abs(o.f) > best_f) {
                    best_f = abs(o.f);
                    memcpy(at_f, in, sizeof in);
                }
            }
    check_widths(&cfg, at_f[0], at_f[1], at_f[2], mx);
    /* the largest |df| over the random inputs */
    np_rng_seed(&r, 31);
    for (unsigned it = 0; it < 1000000; it++) {
        uint16_t in[3];
            rnd3(&r, in);
        np_simplex_out o;
        np_simplex_eval(&cfg, in[0], in[1], in[2], &o);
        for (unsigned a = 0; a < 3; a++)
            if (abs(o.df[a]) > best_d) {
                best_d = abs(o.df[a]);
                memcpy(at_d, in, sizeof in);
            }
        if (abs(o.f) > best_f) {
            best_f = abs(o.f);
            memcpy(at_f, in, sizeof in);
        }
    }
    printf("largest |f| the unit produced: %d = %.6f at (%04x,%04x,%04x) (of 1e6 random inputs and %u exact "
           "cell centres); largest |df| %d = %.6f at (%04x,%04x,%04x)\n",
           best_f, best_f / p2(np_simplex_f_frac(&cfg)), at_f[0], at_f[1], at_f[2], ncentre, best_d,
           best_d / p2(np_simplex_d_frac(&cfg)), at_d[0], at_d[1], at_d[2]);
    NP_CHECK(best_f / p2(np_simplex_f_frac(&cfg)) <= c.bf + 1e-4, "f above the bound");
    NP_CHECK(best_d / p2(np_simplex_d_frac(&cfg)) <= c.bd + 1e-3, "df above the bound");

    /* 3. Every intermediate against its declared width, also at other widths. */
    static const unsigned cfgs[][3] = { { 16, 16, 1 }, { 8, 8, 1 }, { 20, 20, 1 }, { 4, 5, 1 }, { 12, 6, 0 } };
    for (unsigned ci = 1; ci < 5; ci++) {
        np_simplex_cfg k = np_simplex_cfg_default(cfgs[ci][0], cfgs[ci][1], cfgs[ci][2]);
        k.deriv = 1; /* trace every signal */
        long long m2[W_N];
        memset(m2, 0, sizeof m2);
        for (unsigned it = 0; it < 50000; it++) {
            uint16_t x = rnd16(&r), y = rnd16(&r), z = rnd16(&r);
            check_widths(&k, x, y, z, m2);
        }
        check_widths(&k, at_f[0], at_f[1], at_f[2], m2);
        check_widths(&k, at_d[0], at_d[1], at_d[2], m2);
    }
    printf("every signal within its width over 3e5 random inputs and the extremes (default unit; 5e4 each at 4 other widths):\n");
    for (unsigned w = 0; w < W_N; w++) {
        double scale = 1.0;
        if (w >= W_TAU2 && w <= W_TAU4)
            scale = p2(cfg.t_frac);
        else if (w >= W_FC && w <= W_QS)
            scale = p2(cfg.p_frac);
        else if (w == W_F)
            scale = p2(np_simplex_f_frac(&cfg));
        else if (w == W_DF)
            scale = p2(np_simplex_d_frac(&cfg));
        printf("  %-12s max |word| %12lld", W_NAME[w], mx[w]);
        if (scale != 1.0)
            printf("  = %.6f", (double)mx[w] / scale);
        printf("\n");
    }
    NP_CHECK(np_simplex_kf(&cfg) < (1ll << cfg.k_frac) && np_simplex_kd(&cfg) < (1ll << (cfg.k_frac + 2u)),
             "constants");
    return 0;
}


/* ------------------------------------------------------------------------ */

int simplex_wrap(void)
{
    np_simplex_cfg cfg = default_cfg();
    np_rng r;
    np_rng_seed(&r, 256);
    /* 1. The skewed lattice mod 256: (128,128,128) = 0x8000 per word is a period, bit for bit. */
    unsigned same = 0, n = 500000;
    for (unsigned it = 0; it < n; it++) {
        uint16_t x = (uint16_t)(rnd16(&r) & 0x7fffu), y = (uint16_t)(rnd16(&r) & 0x7fffu),
                 z = (uint16_t)(rnd16(&r) & 0x7fffu);
        np_simplex_out a, b;
        np_simplex_eval(&cfg, x, y, z, &a);
        np_simplex_eval(&cfg, (uint16_t)(x + 0x8000u), (uint16_t)(y + 0x8000u), (uint16_t)(z + 0x8000u), &b);
        int eq = a.f == b.f && a.df[0] == b.df[0] && a.df[1] == b.df[1] && a.df[2] == b.df[2];
        NP_CHECK(eq, "(%04x,%04x,%04x) vs +0x8000", x, y, z);
        same += (unsigned)eq;
    }
    printf("unit: outputs at (x,y,z) and (x,y,z) + 0x8000 identical at %u of %u inputs (cells i and i + 256 "
           "hash alike)\n",
           same, n);
    /* 2. The unit against the Appendix B transcription (unbounded ints) in cells 256..511. */
    double maxe = 0.0;
    for (unsigned it = 0; it < 300000; it++) {
        uint16_t x = (uint16_t)(rnd16(&r) | 0x8000u), y = (uint16_t)(rnd16(&r) | 0x8000u),
                 z = (uint16_t)(rnd16(&r) | 0x8000u);
        np_simplex_out o;
        np_simplex_eval(&cfg, x, y, z, &o);
        double j = J_noise(x / 256.0, y / 256.0, z / 256.0) * p2(16);
        maxe = fmax(maxe, fabs(o.f - j));
        NP_CHECK(fabs(o.f - j) <= 1.0, "(%04x,%04x,%04x): unit %d, Appendix B %.3f", x, y, z, o.f, j);
    }
    printf("unit vs Appendix B (hash on unbounded ints) with every cell index >= 256: max f error %.4f LSB\n", maxe);
    /* 3. The reference: periodic under skewed translations by 256, also into negative coordinates. */
    double m1 = 0.0, m2 = 0.0;
    for (unsigned it = 0; it < 200000; it++) {
        double x = rnd01(&r) * 256.0, y = rnd01(&r) * 256.0, z = rnd01(&r) * 256.0;
        double f = np_ref_simplex3(x, y, z, NULL);
        if (face_distance(x, y, z) < 1e-9)
            continue; /* a translation's rounding could cross a face */
        m1 = fmax(m1, fabs(f - np_ref_simplex3(x - 128.0, y - 128.0, z - 128.0, NULL)));
        m1 = fmax(m1, fabs(f - np_ref_simplex3(x + 384.0, y + 384.0, z + 384.0, NULL)));
        /* skewed (256, 0, 0) unskewed: (256 - 256/6, -256/6, -256/6) */
        m2 = fmax(m2, fabs(f - np_ref_simplex3(x + 640.0 / 3.0, y - 128.0 / 3.0, z - 128.0 / 3.0, NULL)));
    }
    printf("reference: |f(p) - f(p + k (128,128,128))| <= %.3g (k = -1, 3); "
           "|f(p) - f(p + (640/3, -128/3, -128/3))| <= %.3g\n",
           m1, m2);
    NP_CHECK(m1 < 1e-12 && m2 < 1e-9, "reference not periodic under skewed translations by 256");
    /* 4. No tiling at 256 along an axis: the seam where an input word wraps. */
    double seam_unit = 0.0, seam_ref = 0.0, cont = 0.0;
    for (unsigned it = 0; it < 100000; it++) {
        uint16_t y = rnd16(&r), z = rnd16(&r);
        np_simplex_out a, b;
        np_simplex_eval(&cfg, 0xffff, y, z, &a);
        np_simplex_eval(&cfg, 0x0000, y, z, &b);
        seam_unit = fmax(seam_unit, fabs((double)(a.f - b.f)));
        double yy = y / 256.0, zz = z / 256.0;
        double r256 = np_ref_simplex3(256.0, yy, zz, NULL), r0 = np_ref_simplex3(0.0, yy, zz, NULL);
        seam_ref = fmax(seam_ref, fabs(r256 - r0) * p2(16));
        if (face_distance(256.0, yy, zz) > 1.0 / 512)
            cont = fmax(cont, fabs(np_ref_simplex3(255.99609375, yy, zz, NULL) - r256) * p2(16));
    }
    printf("input wrap 0xffff -> 0x0000 on x: the unit's f jumps by up to %.0f LSB; the reference's "
           "|f(256,y,z) - f(0,y,z)| is up to %.0f LSB, while f(256 - 1/256) to f(256) moves at most %.1f LSB "
           "(away from faces): the unit computes f on [0,256)^3 and does not tile at 256\n",
           seam_unit, seam_ref, cont);
    NP_CHECK(seam_ref > 100.0, "the function unexpectedly tiles at 256");
    return 0;
}

