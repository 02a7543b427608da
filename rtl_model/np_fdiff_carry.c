/* SPDX-License-Identifier: MIT */
#include "np_fdiff_carry.h"

/* Ring operations modulo 2^128 (np_fixed.h): exact on the low 128 bits of the true values. */
static np_s128 mul(np_s128 a, np_s128 b) { return np_mul128(a, b); }
static np_s128 add(np_s128 a, np_s128 b) { return np_add128(a, b); }
static np_s128 sub(np_s128 a, np_s128 b) { return np_add128(a, np_mul128((np_s128)-1, b)); }
static np_s128 shl(np_s128 a, unsigned s) { return np_shl128(a, s); }

/* Axis pairs of the quadratic monomials: UV, VW, WU. */
static const unsigned PA[3] = { 0, 1, 2 }, PB[3] = { 1, 2, 0 };

void np_fdiff_cell_coef(const uint64_t u[3], int64_t co[8])
{
    uint8_t n[8];
    np_tex_lattice(np_tex_cell(u[0]), np_tex_cell(u[1]), np_tex_cell(u[2]), n);
    /*
     * The seed's corners N0..N7 (Section 3): N0 (0,0,0), N1 (1,0,0),
     * N2 (1,1,0), N3 (0,1,0), N4 (0,0,1), N5 (1,0,1), N6 (1,1,1), N7 (0,1,1);
     * ours are c = 4cz + 2cy + cx.
     */
    const int64_t N0 = n[0], N1 = n[1], N2 = n[3], N3 = n[2], N4 = n[4], N5 = n[5], N6 = n[7], N7 = n[6];
    /* The Appendix's coefficients, s10 Q3.6, exact. */
    const int64_t ce = N0 - N1 + N2 - N3;
    co[0] = N0;
    co[1] = N1 - N0;
    co[2] = N3 - N0;
    co[3] = N4 - N0;
    co[4] = ce;
    co[5] = N7 - N4 - N3 + N0;
    co[6] = N5 - N4 - N1 + N0;
    co[7] = N4 - N5 + N6 - N7 - ce;
}

/* Forward differences Delta^0..Delta^(n-1) at k = 0 of the values v[0..n) at k = 0..n-1 (n <= 4), in place. */
static void to_differences(np_s128 *v, unsigned n)
{
    for (unsigned t = 1; t < n; t++)
        for (unsigned k = n - 1u; k >= t; k--)
            v[k] = sub(v[k], v[k - 1u]);
}

void np_fdiff_carry_init(np_fdiff_carry *c, const np_tex_regs *r, unsigned oct, const uint64_t u[3],
                         const int64_t du[3])
{
    const unsigned C = NP_TEX_FC;
    const np_s128 amp = (np_s128)r->oct[oct].amp; /* Q.14 */
    np_s128 f[3], d[3];
    for (unsigned a = 0; a < 3; a++) {
        f[a] = (np_s128)np_tex_frac(u[a]);
        d[a] = (np_s128)du[a];
    }
    /* U_a at k (Q.32). */
#define AT(a, k) add(f[a], mul((np_s128)(k), d[a]))
    c->amp = shl(amp, 3u * C);
    for (unsigned a = 0; a < 3; a++) {
        c->lin[a][0] = shl(mul(amp, f[a]), 2u * C);
        c->lin[a][1] = shl(mul(amp, d[a]), 2u * C);
    }
    for (unsigned p = 0; p < 3; p++) {
        for (unsigned k = 0; k < 3; k++)
            c->quad[p][k] = shl(mul(amp, mul(AT(PA[p], k), AT(PB[p], k))), C);
        to_differences(c->quad[p], 3);
    }
    for (unsigned k = 0; k < 4; k++)
        c->cub[k] = mul(amp, mul(mul(AT(0, k), AT(1, k)), AT(2, k)));
    to_differences(c->cub, 4);
#undef AT
}

void np_fdiff_carry_step(np_fdiff_carry *c)
{
    /* Lower orders first: each reads the next order's old value. */
    for (unsigned a = 0; a < 3; a++)
        c->lin[a][0] = add(c->lin[a][0], c->lin[a][1]);
    for (unsigned p = 0; p < 3; p++) {
        c->quad[p][0] = add(c->quad[p][0], c->quad[p][1]);
        c->quad[p][1] = add(c->quad[p][1], c->quad[p][2]);
    }
    for (unsigned t = 0; t < 3; t++)
        c->cub[t] = add(c->cub[t], c->cub[t + 1u]);
}

void np_fdiff_carry_rebase(np_fdiff_carry *c, const int32_t j[3])
{
    if (!j[0] && !j[1] && !j[2])
        return;
    const np_s128 J[3] = { j[0], j[1], j[2] };
    const np_fdiff_carry o = *c; /* every new value from the old ones */
    for (unsigned t = 0; t < 4; t++) {
        const np_s128 A = t == 0 ? o.amp : 0;
        np_s128 L[3], Q[3];
        for (unsigned a = 0; a < 3; a++)
            L[a] = t < 2 ? o.lin[a][t] : 0;
        for (unsigned p = 0; p < 3; p++)
            Q[p] = t < 3 ? o.quad[p][t] : 0;
        /* (U - ju)(V - jv)(W - jw) = UVW - jw UV - ju VW - jv WU + jv jw U + ju jw V + ju jv W - ju jv jw */
        np_s128 x = sub(o.cub[t], add(add(mul(J[2], Q[0]), mul(J[0], Q[1])), mul(J[1], Q[2])));
        x = add(x, add(add(mul(mul(J[1], J[2]), L[0]), mul(mul(J[0], J[2]), L[1])), mul(mul(J[0], J[1]), L[2])));
        c->cub[t] = sub(x, mul(mul(mul(J[0], J[1]), J[2]), A));
        if (t < 3)
            for (unsigned p = 0; p < 3; p++) {
                const unsigned a = PA[p], b = PB[p];
                /* (Ua - ja)(Ub - jb) = Ua Ub - jb Ua - ja Ub + ja jb */
                np_s128 y = sub(Q[p], add(mul(J[b], L[a]), mul(J[a], L[b])));
                c->quad[p][t] = add(y, mul(mul(J[a], J[b]), A));
            }
    }
    for (unsigned a = 0; a < 3; a++)
        c->lin[a][0] = sub(o.lin[a][0], mul(J[a], o.amp));
}

void np_fdiff_carry_shift(const uint64_t u[3], const int64_t du[3], int32_t j[3])
{
    for (unsigned a = 0; a < 3; a++)
        j[a] = (int32_t)np_asr((int64_t)np_tex_frac(u[a]) + du[a], NP_TEX_FC); /* floor: [-128, 128] */
}

void np_fdiff_carry_setup(const np_fdiff_carry *c, const uint64_t u[3], unsigned F, unsigned W, np_s128 d[4],
                          np_s128 exact[4])
{
    int64_t co[8];
    np_fdiff_cell_coef(u, co);
    np_s128 cf[8];
    for (unsigned i = 0; i < 8; i++)
        cf[i] = (np_s128)co[i];
    /* Y_t = sum_m c_m a' Delta^t[m]: Q.6 times Q.110 = Q.116, modulo 2^128. */
    for (unsigned t = 0; t < 4; t++) {
        np_s128 y = t == 0 ? mul(cf[0], c->amp) : 0;
        for (unsigned a = 0; t < 2 && a < 3; a++)
            y = add(y, mul(cf[1u + a], c->lin[a][t]));
        for (unsigned p = 0; t < 3 && p < 3; p++)
            y = add(y, mul(cf[4u + p], c->quad[p][t]));
        y = add(y, mul(cf[7], c->cub[t]));
        if (exact)
            exact[t] = y;
        d[t] = np_tex_to_index(y, NP_FDIFF_CARRY_FRAC + NP_TEX_LAT_FRAC, F, W);
    }
}

void np_fdiff_carry_wrap(np_fdiff_carry *c, unsigned bits)
{
    if (bits >= 128)
        return;
    c->amp = np_wrap_s128(c->amp, bits);
    for (unsigned a = 0; a < 3; a++)
        for (unsigned t = 0; t < 2; t++)
            c->lin[a][t] = np_wrap_s128(c->lin[a][t], bits);
    for (unsigned p = 0; p < 3; p++)
        for (unsigned t = 0; t < 3; t++)
            c->quad[p][t] = np_wrap_s128(c->quad[p][t], bits);
    for (unsigned t = 0; t < 4; t++)
        c->cub[t] = np_wrap_s128(c->cub[t], bits);
}
