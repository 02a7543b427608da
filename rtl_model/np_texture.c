/* SPDX-License-Identifier: MIT */
#include "np_texture.h"

#include <stddef.h>
#include <string.h>

/* Quadric register order (np_tex_regs.k). */
enum { KA, KB, KC, KD, KE, KF, KG, KH, KI, KJ, K_COUNT };

const char *np_tex_regs_check(const np_tex_regs *r)
{
    if (r->k_bits && (r->k_bits > NP_TEX_K_BITS_MAX || r->k_frac > NP_TEX_K_FRAC_MAX || r->k_frac + 1u > r->k_bits))
        return "quadric register format outside s64 / 48 fraction bits";
    if (r->m_bits && (r->m_bits > NP_TEX_M_BITS_MAX || r->m_frac > NP_TEX_M_FRAC_MAX || r->m_frac + 1u > r->m_bits ||
                      r->m_bits > 1u + NP_TEX_M_INT_MAX + r->m_frac))
        return "transform register format outside s48 / 40 fraction bits / 7 integer bits";
    if (r->n_oct > NP_TEX_MAX_OCTAVES)
        return "at most 8 octaves";
    if (r->cmap_n < 2 || r->cmap_n > NP_TEX_CMAP_MAX)
        return "colour map needs 2..256 entries";
    if (r->cmap_repeat && (r->cmap_n & (r->cmap_n - 1u)) != 0)
        return "a repeating colour map needs a power-of-two number of entries";
    for (unsigned i = 0; i < K_COUNT; i++)
        if (!np_fits_s(r->k[i], np_tex_k_bits(r)))
            return "quadric coefficient outside its register (s48 Q23.24 or the scene-sized format)";
    for (unsigned i = 0; i < r->n_oct; i++) {
        const np_tex_octave *o = &r->oct[i];
        for (unsigned a = 0; a < 3; a++) {
            for (unsigned b = 0; b < 3; b++)
                if (!np_fits_s(o->m[a][b], np_tex_m_bits(r)))
                    return "octave transform entry outside its register (s24 Q7.16 or the scene-sized format)";
            if (!np_fits_s(o->o[a], NP_TEX_O_BITS))
                return "octave offset outside s48 Q15.32";
        }
        if (!np_fits_s(o->amp, NP_TEX_AMP_BITS))
            return "octave amplitude outside s32 Q17.14";
    }
    return NULL;
}

int np_tex_regs_diagonal(const np_tex_regs *r)
{
    for (unsigned i = 0; i < r->n_oct; i++)
        for (unsigned a = 0; a < 3; a++)
            for (unsigned b = 0; b < 3; b++)
                if (a != b && r->oct[i].m[a][b] != 0)
                    return 0;
    return 1;
}

const char *np_span_check(const np_span *sp)
{
    if (sp->n > NP_TEX_SPAN_MAX)
        return "span longer than 65536 pixels";
    if ((uint32_t)sp->x0 + sp->n > NP_TEX_SPAN_MAX)
        return "span runs past pixel 65535";
    for (unsigned a = 0; a < 3; a++) {
        if (!np_fits_s(sp->s[a], NP_TEX_S_BITS))
            return "texture coordinate outside s48 Q15.32";
        if (!np_fits_s(sp->ds[a], NP_TEX_DS_BITS))
            return "texture derivative outside s41 Q8.32";
    }
    /* The last pixel's coordinate must stay within s48 too (the DDA does not wrap there). */
    for (unsigned a = 0; a < 3; a++) {
        int64_t last = sp->s[a] + (int64_t)(sp->n ? sp->n - 1u : 0u) * sp->ds[a];
        if (!np_fits_s(last, NP_TEX_S_BITS))
            return "texture coordinate leaves s48 Q15.32 along the span";
    }
    return NULL;
}

void np_tex_octave_span(const np_tex_regs *r, unsigned i, const int64_t s[3], const int64_t ds[3],
                        np_tex_oct_span *o)
{
    const np_tex_octave *t = &r->oct[i];
    /*
     * Products s24 Q7.16 x s48 Q15.32: Q22.48, exact in 128 bits (scene-sized:
     * at most s48 Q7.40 x s48, Q22.72 in 96 bits).
     */
    const unsigned sh = np_tex_m_frac(r);
    for (unsigned a = 0; a < 3; a++) {
        np_s128 u = np_shl128((np_s128)t->o[a], sh); /* Q15.48 */
        np_s128 d = 0;
        for (unsigned b = 0; b < 3; b++) {
            u = np_add128(u, np_mul128((np_s128)t->m[a][b], (np_s128)s[b]));
            d = np_add128(d, np_mul128((np_s128)t->m[a][b], (np_s128)ds[b]));
        }
        o->u[a] = np_trunc_u((uint64_t)np_round_wrap128((np_u128)u, sh, NP_TEX_U_BITS), NP_TEX_U_BITS);
        o->du[a] = (int64_t)np_round_wrap128((np_u128)d, sh, NP_TEX_DU_BITS);
    }
}

void np_tex_lattice(uint8_t i, uint8_t j, uint8_t k, uint8_t n[8])
{
    for (unsigned c = 0; c < 8; c++)
        n[c] = np_hash6((uint8_t)(i + (c & 1u)), (uint8_t)(j + ((c >> 1) & 1u)),
                        (uint8_t)(k + ((c >> 2) & 1u)));
}

void np_tex_quadric_exact(const np_tex_regs *r, const int64_t s[3], const int64_t ds[3],
                          np_s128 q[3])
{
    const int64_t *k = r->k;
    /* M_q = [[A B C] [B E F] [C F H]], b = (D, G, I). */
    const int64_t mq[3][3] = { { k[KA], k[KB], k[KC] }, { k[KB], k[KE], k[KF] }, { k[KC], k[KF], k[KH] } };
    const int64_t bq[3] = { k[KD], k[KG], k[KI] };
    np_s128 ms[3], mds[3];                 /* level 1: Q?.56 */
    for (unsigned a = 0; a < 3; a++) {
        ms[a] = mds[a] = 0;
        for (unsigned b = 0; b < 3; b++) {
            ms[a] = np_add128(ms[a], np_mul128((np_s128)mq[a][b], (np_s128)s[b]));
            mds[a] = np_add128(mds[a], np_mul128((np_s128)mq[a][b], (np_s128)ds[b]));
        }
    }
    np_s128 sms = 0, smds = 0, dsmds = 0, bs = 0, bds = 0; /* level 2 */
    for (unsigned a = 0; a < 3; a++) {
        sms = np_add128(sms, np_mul128((np_s128)s[a], ms[a]));       /* Q.88 */
        smds = np_add128(smds, np_mul128((np_s128)s[a], mds[a]));    /* Q.88 */
        dsmds = np_add128(dsmds, np_mul128((np_s128)ds[a], mds[a])); /* Q.88 */
        bs = np_add128(bs, np_mul128((np_s128)bq[a], (np_s128)s[a]));   /* Q.56 */
        bds = np_add128(bds, np_mul128((np_s128)bq[a], (np_s128)ds[a])); /* Q.56 */
    }
    const unsigned up = NP_TEX_FC;         /* Q.56 -> Q.88 (Q.(32 + k_frac) -> Q.(64 + k_frac)) */
    const unsigned upj = 2u * NP_TEX_FC;   /* J: Q.24 -> Q.88 */
    q[0] = np_add128(np_add128(sms, np_shl128(bs, up + 1u)), np_shl128((np_s128)k[KJ], upj));
    q[1] = np_add128(np_add128(np_shl128(smds, 1), dsmds), np_shl128(bds, up + 1u));
    q[2] = np_shl128(dsmds, 1);
}

void np_tex_colour_split(const np_tex_regs *r, np_s128 x, unsigned F, unsigned fw, unsigned *seg,
                         uint32_t *w)
{
    unsigned n = r->cmap_n;
    np_u128 frac;
    if (r->cmap_repeat) {
        *seg = (unsigned)(((np_u128)x >> F) & (np_u128)(n - 1u));
        frac = (np_u128)x & NP_MASK128(F);
    } else {
        np_s128 top = np_shl128((np_s128)(n - 1u), F);
        if (x < 0) {
            *seg = 0;
            *w = 0;
            return;
        }
        if (x >= top) {
            *seg = n - 2u;
            *w = (uint32_t)1 << fw;
            return;
        }
        *seg = (unsigned)((np_u128)x >> F);
        frac = (np_u128)x & NP_MASK128(F);
    }
    /* Round the fraction to fw bits (ties up); the result may be 2^fw. */
    if (F >= fw)
        *w = (uint32_t)(F == fw ? frac : (frac + ((np_u128)1 << (F - fw - 1u))) >> (F - fw));
    else
        *w = (uint32_t)(frac << (fw - F));
}

void np_tex_colour_mix(const np_tex_regs *r, unsigned seg, uint32_t w, unsigned fw, int64_t prod[3])
{
    unsigned next = r->cmap_repeat ? (seg + 1u) & (r->cmap_n - 1u) : seg + 1u;
    for (unsigned ch = 0; ch < 3; ch++) {
        int64_t c0 = r->cmap[seg][ch], c1 = r->cmap[next][ch];
        prod[ch] = np_shl(c0, fw) + (int64_t)w * (c1 - c0); /* s(10+Fw) Q9.Fw, exact */
    }
}

void np_tex_colour_round(const int64_t prod[3], unsigned fw, uint8_t rgb[3])
{
    for (unsigned ch = 0; ch < 3; ch++)
        rgb[ch] = (uint8_t)np_shr_round_half_up(prod[ch], fw); /* in [0, 255]: see the header */
}

void np_tex_colour(const np_tex_regs *r, np_s128 x, unsigned F, unsigned fw, uint8_t rgb[3])
{
    unsigned seg;
    uint32_t w;
    int64_t prod[3];
    np_tex_colour_split(r, x, F, fw, &seg, &w);
    np_tex_colour_mix(r, seg, w, fw, prod);
    np_tex_colour_round(prod, fw, rgb);
}

unsigned np_tex_colour_slope(const np_tex_regs *r)
{
    unsigned n = r->cmap_n, segs = r->cmap_repeat ? n : n - 1u, best = 0;
    for (unsigned k = 0; k < segs; k++) {
        unsigned next = (k + 1u) % n;
        for (unsigned ch = 0; ch < 3; ch++) {
            int d = (int)r->cmap[next][ch] - (int)r->cmap[k][ch];
            unsigned a = (unsigned)(d < 0 ? -d : d);
            if (a > best)
                best = a;
        }
    }
    return best;
}

unsigned np_tex_sched_cycles(const np_tex_sched *s, unsigned P, unsigned Lm)
{
    unsigned c = s->fixed;
    for (unsigned l = 0; l < s->levels; l++)
        if (s->mults[l])
            c += (s->mults[l] + P - 1u) / P + Lm - 1u;
    return c;
}

unsigned np_tex_sched_products(const np_tex_sched *s)
{
    unsigned n = 0;
    for (unsigned l = 0; l < s->levels; l++)
        n += s->mults[l];
    return n;
}

/* u0 = M s + o and du = M ds: 9 + 9 products in one level; round and load. */
const np_tex_sched np_tex_sched_octave = { "octave", 1, 1, { 18 } };
/* Diagonal M: 3 + 3 products. */
const np_tex_sched np_tex_sched_octave_diag = { "octave(diag)", 1, 1, { 6 } };

/* --- Datapath declaration pieces --- */

unsigned np_tex_seg_bits(const np_tex_regs *r) { return np_bits_for_range(0, (int64_t)r->cmap_n - 1, 0); }

unsigned np_tex_reg_bits(const np_tex_regs *r)
{
    const unsigned oct = 9u * np_tex_m_bits(r) + 3u * NP_TEX_O_BITS + NP_TEX_AMP_BITS;
    return K_COUNT * np_tex_k_bits(r) + r->n_oct * oct + r->cmap_n * 3u * 8u;
}

unsigned np_tex_dp_lattice(np_dp *d, const char *stage, unsigned lanes, unsigned level0)
{
    /* Per cell: (i+1, j+1, k+1); per corner 8 bitPatterns lookups (3 index bits -> 6) and 7 adders. */
    np_dp_op(d, stage, NULL, NP_OP_ADD, 3u * lanes, NP_TEX_CELL_BITS, 0, 0, 0, level0);
    np_dp_op(d, stage, NULL, NP_OP_LUT, 64u * lanes, 3, NP_TEX_LAT_FRAC, 0, 0, level0 + 1u);
    np_dp_op(d, stage, NULL, NP_OP_ADD, 32u * lanes, NP_TEX_LAT_FRAC, 0, 0, 0, level0 + 2u);
    np_dp_op(d, stage, NULL, NP_OP_ADD, 16u * lanes, NP_TEX_LAT_FRAC, 0, 0, 0, level0 + 3u);
    np_dp_op(d, stage, "n", NP_OP_ADD, 8u * lanes, NP_TEX_LAT_FRAC, 0, NP_TEX_LAT_FRAC, 0, level0 + 4u);
    return level0 + 5u;
}

void np_tex_dp_colour(np_dp *d, const np_tex_regs *r, unsigned F, unsigned W, unsigned fw, unsigned c1_level0,
                      unsigned side)
{
    /* A clamped index is below 2^I (I = W - F - 1 integer bits), so its segment needs at most I bits. */
    const unsigned sb_all = np_tex_seg_bits(r), sb = !r->cmap_repeat && W - F - 1u < sb_all ? W - F - 1u : sb_all;
    const unsigned cw = fw + 1u, pw = 8u + fw;
    /* C1: seg = floor(x) (wiring; repeat: mod N, a mask), w = frac(x) rounded to Fw bits. */
    unsigned lv = c1_level0;
    if (F > fw)
        np_dp_op(d, "C1", "cw", NP_OP_ADD, 1, cw, 0, cw, 0, lv++);
    else
        np_dp_op(d, "C1", "cw", NP_OP_REG, 0, 0, 0, cw, 0, lv);
    if (!r->cmap_repeat) {
        /* Clamp: x >= (N - 1) 2^F compares the integer bits (x < 0 is the sign bit); pick 0 / 1.0 / w. */
        np_dp_op(d, "C1", NULL, NP_OP_CMP, 1, W - F, 0, 0, 0, c1_level0);
        np_dp_op(d, "C1", "seg", NP_OP_MUX, 1, sb, 3, sb, 0, lv);
        np_dp_op(d, "C1", NULL, NP_OP_MUX, 1, cw, 3, 0, 0, lv);
    } else {
        np_dp_op(d, "C1", "seg", NP_OP_REG, 0, 0, 0, sb, 0, lv);
    }
    np_dp_op(d, "C1", NULL, NP_OP_REG, 1, sb + cw + side + 1u, 0, 0, 0, 0);
    /* C2: next = seg + 1 (mod N), read c[seg] and c[next] (N:1 of 24 bits), c = c0 2^Fw + w (c1 - c0). */
    np_dp_op(d, "C2", NULL, NP_OP_ADD, 1, sb, 0, 0, 0, 0);
    np_dp_op(d, "C2", NULL, NP_OP_MUX, 2, 24, r->cmap_n, 0, 0, 1);
    np_dp_op(d, "C2", "cd", NP_OP_ADD, 3, 9, 0, 9, 1, 2);
    np_dp_op(d, "C2", "mix", NP_OP_MUL, 3, cw, 9, 9u + fw, 1, 3);
    np_dp_op(d, "C2", "prod", NP_OP_ADD, 3, pw, 0, pw, 0, 4);
    np_dp_op(d, "C2", NULL, NP_OP_REG, 1, 3u * pw + side + 1u, 0, 0, 0, 0);
    /* C3: round to 8 bits (half up). */
    np_dp_op(d, "C3", "rgb", NP_OP_ADD, 3, pw, 0, 8, 0, 0);
    np_dp_op(d, "C3", NULL, NP_OP_REG, 1, 24u + side + 1u, 0, 0, 0, 0);
}

void np_tex_trace(np_trace *t, size_t n, const char *name, int64_t v)
{
    for (size_t i = 0; i < n; i++)
        if (t[i].signal && strcmp(t[i].signal, name) == 0)
            np_trace_add(&t[i], v);
}

void np_tex_trace128(np_trace *t, size_t n, const char *name, np_s128 v)
{
    /* Two's complement bits of v: the position of the highest bit that differs from the sign, plus 2. */
    np_u128 m = (np_u128)(v < 0 ? ~v : v);
    unsigned bits = 1;
    while (m) {
        bits++;
        m >>= 1;
    }
    for (size_t i = 0; i < n; i++)
        if (t[i].signal && strcmp(t[i].signal, name) == 0)
            np_trace_add_wide(&t[i], bits, v < 0);
}

void np_tex_trace_colour(const np_tex_regs *r, unsigned seg, uint32_t w, const int64_t prod[3],
                         const uint8_t rgb[3], unsigned fw, np_trace *t, size_t n)
{
    unsigned next = r->cmap_repeat ? (seg + 1u) & (r->cmap_n - 1u) : seg + 1u;
    np_tex_trace(t, n, "seg", seg);
    np_tex_trace(t, n, "cw", w);
    for (unsigned ch = 0; ch < 3; ch++) {
        int64_t c0 = r->cmap[seg][ch], c1 = next < r->cmap_n ? r->cmap[next][ch] : c0;
        np_tex_trace(t, n, "cd", c1 - c0);
        np_tex_trace(t, n, "mix", prod[ch] - np_shl(c0, fw));
        np_tex_trace(t, n, "prod", prod[ch]);
        np_tex_trace(t, n, "rgb", rgb[ch]);
    }
}
