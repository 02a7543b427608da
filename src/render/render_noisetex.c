/* SPDX-License-Identifier: MIT */
/* A time-varying solid texture through a 4-D noise unit on the G-buffer (np_noisetex.h). */
#include "np_noisetex.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "np_fixed.h"
#include "np_unit_span.h"

enum { IN_X, IN_Y, IN_Z, IN_W, N_IN = 4, Q88_SHIFT = NP_TEX_FC - 8 };

int np_noisetex_init(np_noisetex *t, const np_scene *sc, const np_unit_cfg *cfg, char *err, size_t errlen)
{
    memset(t, 0, sizeof *t);
    t->sc = sc;
    if (!sc->noise.present) {
        snprintf(err, errlen, "%s: the scene's texture has no \"noise\" section", sc->name);
        return -1;
    }
    t->u = np_unit_find(sc->noise.unit);
    np_unit_fields f;
    if (!t->u) {
        snprintf(err, errlen, "%s: field 'texture.noise.unit': no unit %s", sc->name, sc->noise.unit);
        return -1;
    }
    if (cfg)
        t->cfg = *cfg;
    else
        np_unit_cfg_default(t->u, &t->cfg);
    t->u->fields(&t->cfg, &f);
    if (f.n_in != N_IN || f.n_out != 1 || f.in[IN_W].bits != 16 || f.in[IN_W].frac != 8) {
        snprintf(err, errlen, "%s: field 'texture.noise.unit': %s is not a 4-D noise unit with u16 Q8.8 inputs",
                 sc->name, sc->noise.unit);
        return -1;
    }
    t->out_frac = f.out[0].frac;
    t->bound_lsb = t->u->error_bound_lsb ? t->u->error_bound_lsb(&t->cfg) : -1.0;
    return 0;
}

double np_noisetex_step_bound_lsb(const np_noisetex *t)
{
    if (strcmp(t->u->name, "simplex4") != 0 || t->bound_lsb < 0.0)
        return -1.0;
    /*
     * Along any input axis one corner's term A t^4 (G . d), t = r^2 - |d|^2,
     * has slope at most A |G| (t^4 + 8 t^3 |d|^2) = A |G| (4 t^3 - 7 t^4) with
     * r^2 = 1/2, largest at t = 3/7: A |G| 27/343; n + 1 corners at most.
     */
    const double lip = 6.0 * 5.0 * sqrt(3.0) * 27.0 / 343.0;
    return lip * (t->sc->noise.dw / 256.0) * ldexp(1.0, (int)t->out_frac) + 2.0 * t->bound_lsb;
}

/* The unit's cycle model over in[0..n) back to back (no bubble, no stall): its outputs against want[]. */
static int run_pipe(const np_noisetex *t, const uint64_t (*in)[N_IN], const int64_t *want, uint64_t n,
                    np_noisetex_stats *st)
{
    np_pipe p;
    if (t->u->pipe_init(&p, &t->cfg) != 0)
        return -1;
    void *sig = calloc(1, p.sig_size);
    if (!sig) {
        np_pipe_free(&p);
        return -1;
    }
    np_unit_fields f;
    t->u->fields(&t->cfg, &f);
    uint64_t next = 0, done = 0;
    while (done < n) {
        np_pipe_port port;
        memset(&port, 0, sizeof port);
        port.in_valid = next < n;
        if (port.in_valid) {
            memset(sig, 0, p.sig_size);
            t->u->sig_set_in(sig, in[next]);
            port.in_sig = sig;
        }
        port.out_ready = 1;
        np_pipe_eval(&p, &port);
        if (port.out_valid) {
            uint64_t out;
            t->u->sig_get_out(&t->cfg, port.out_sig, &out);
            if (np_sext(out, f.out[0].bits) != want[done])
                st->cycle_mismatch++;
            done++;
        }
        if (port.in_valid && port.in_ready)
            next++;
        np_pipe_clock(&p, &port);
    }
    st->cycles = p.stats.cycles;
    free(sig);
    np_pipe_free(&p);
    return 0;
}

int np_noisetex_frame(const np_noisetex *t, const np_gbuf *g, unsigned fr, int cycles, uint8_t *rgb, double *ref,
                      int32_t *code0, np_noisetex_stats *st, char *err, size_t errlen)
{
    const np_scene *sc = t->sc;
    const np_tex_regs *r = &g->regs;
    const unsigned n_oct = r->n_oct, F = NP_NOISETEX_IDX_FRAC, fw = NP_NOISETEX_W_FRAC;
    const unsigned W = 1u + NP_NOISETEX_IDX_INT + F;
    const size_t npix = (size_t)g->w * g->h;
    memset(st, 0, sizeof *st);
    st->w = (uint16_t)(sc->noise.w0 + fr * (unsigned)sc->noise.dw);
    np_gbuf_lightq lq;
    np_gbuf_light_setup(sc, &lq);
    np_unit_fields f;
    t->u->fields(&t->cfg, &f);
    uint64_t (*in)[N_IN] = NULL;
    int64_t *codes = NULL;
    if (cycles) {
        in = malloc((npix * (n_oct ? n_oct : 1u) + 1u) * sizeof *in);
        codes = malloc((npix * (n_oct ? n_oct : 1u) + 1u) * sizeof *codes);
        if (!in || !codes) {
            free(in);
            free(codes);
            snprintf(err, errlen, "out of memory");
            return -1;
        }
    }
    for (size_t p = 0; p < npix; p++) {
        size_t i = p * g->n; /* sample 0 of the pixel: m = 1 */
        uint8_t *c = &rgb[3 * p];
        if (code0)
            code0[p] = 0;
        if (g->poly[i] == NP_GBUF_NONE) {
            for (unsigned k = 0; k < 3; k++) {
                c[k] = (uint8_t)sc->background[k];
                if (ref)
                    ref[3 * p + k] = sc->background[k];
            }
            continue;
        }
        int64_t s[3];
        double sf[3];
        np_gbuf_texcoord(g, i, s);
        np_gbuf_texcoord_f(g, i, sf);
        const int64_t zero[3] = { 0, 0, 0 };
        np_s128 q[3];
        np_tex_quadric_exact(r, s, zero, q);
        np_s128 acc = q[0]; /* Q88 */
        double fref = np_ref_quadric(sc->tex.quad, sf);
        for (unsigned o = 0; o < n_oct; o++) {
            np_tex_oct_span os;
            np_tex_octave_span(r, o, s, zero, &os);
            uint64_t x[N_IN], out;
            for (unsigned a = 0; a < 3; a++)
                x[a] = np_shr_round_half_up_u(os.u[a], Q88_SHIFT) & NP_MASK(16);
            x[IN_W] = st->w;
            t->u->eval(&t->cfg, x, &out);
            int64_t n = np_sext(out, f.out[0].bits);
            /* a' (s32 Q17.14) x n (Q.out_frac): exact, brought to Q88 by a left shift. */
            acc = np_add128(acc, np_shl128(np_mul128((np_s128)r->oct[o].amp, (np_s128)n),
                                           NP_TEX_Q_EXACT_FRAC - NP_TEX_AMP_FRAC - t->out_frac));
            double nr;
            t->u->ref(&t->cfg, x, &nr);
            fref += sc->tex.oct[o].amp * nr;
            if (o == 0 && code0)
                code0[p] = (int32_t)n;
            if (cycles) {
                memcpy(in[st->transactions], x, sizeof x);
                codes[st->transactions] = n;
            }
            st->transactions++;
        }
        double xr = np_ref_colour_index(&sc->tex.cmap, fref);
        if (!r->cmap_repeat && !(fabs(xr) < ldexp(1.0, NP_NOISETEX_IDX_INT - 1))) {
            snprintf(err, errlen, "%s: the colour index %g at pixel (%zu, %zu) is beyond the index register's range",
                     sc->name, xr, p % g->w, p / g->w);
            free(in);
            free(codes);
            return -1;
        }
        np_tex_colour(r, np_tex_to_index(acc, NP_TEX_Q_EXACT_FRAC, F, W), F, fw, c);
        double cr[3], L = 1.0;
        np_ref_colour(&sc->tex.cmap, fref, cr);
        for (unsigned k = 0; k < 3; k++) {
            double e = fabs((double)c[k] - cr[k]);
            st->max_lsb = e > st->max_lsb ? e : st->max_lsb;
            st->over_one += e > 1.0;
        }
        if (lq.on) {
            double nd[3];
            np_gbuf_light(&lq, g->normal[i], c);
            np_gbuf_normal_decode(g->normal[i], nd);
            L = np_gbuf_light_ref(sc, nd);
        }
        for (unsigned k = 0; k < 3; k++) {
            double e = fabs((double)c[k] - cr[k] * L);
            st->max_lit_lsb = e > st->max_lit_lsb ? e : st->max_lit_lsb;
            if (ref)
                ref[3 * p + k] = cr[k] * L;
        }
        st->samples++;
    }
    int rc = 0;
    if (cycles && run_pipe(t, (const uint64_t(*)[N_IN])in, codes, st->transactions, st) != 0) {
        snprintf(err, errlen, "out of memory");
        rc = -1;
    }
    free(in);
    free(codes);
    return rc;
}
