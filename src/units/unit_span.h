/* SPDX-License-Identifier: MIT */
/*
 * unit_span.h - internal: the one registry adapter of the span units
 * (rtl_model/np_span.h). A span unit's own file (unit_fdiff.c,
 * unit_texel.c) holds only what is its own: the configuration block and its
 * keys, the error bound, the datapath declaration, the timing, and an np_su
 * naming its engine; NP_SU_DEFINE and NP_SU_MEMBERS make the rest of its
 * np_unit from this adapter.
 *
 * A vector transaction is one pixel (np_stream.h): the span descriptor's
 * texture fields and length, then the pixel index k; out the pixel's colour.
 * (The descriptor's y and x0 only tag the pixels; they are not in vectors.)
 *
 *   in   s, t, r     s48 Q15.32   texture coordinate at pixel 0
 *        ds, dt, dr  s41 Q8.32    step per pixel
 *        n           u17          pixels of the span (0..65536)
 *        k           u16          the pixel (0..65535); defined for any k,
 *                                 also k >= n (the span continued)
 *   out  cr, cg, cb  u8           colour, 8-bit
 *
 * The texture is configuration: texture=wood|marble|ramp (np_texreg.h), or
 * a scene's texture (np_ut_texture_add).
 *
 * The unit's models:
 *   eval       pixel k of the descriptor: the engine placed at pixel k
 *              (its seek, or begin and k advances, continued from the
 *              previous call in the same thread when it is the same span
 *              and not behind it), then its pipeline stages;
 *   pipe       the same as a per-transaction pipeline: a front stage that
 *              places the engine ("R" or "F"), then the engine's stages. It
 *              gives the unit's bits, not its timing;
 *   stream     the cycle-accurate model: np_span_sim behind the generic
 *              stream port (a span in, its pixels out).
 */
#ifndef UNIT_SPAN_H
#define UNIT_SPAN_H

#include <pthread.h>
#include <stddef.h>
#include <stdint.h>

#include "np_ref.h"
#include "np_rng.h"
#include "np_span.h"
#include "np_stream.h"
#include "np_texture.h"
#include "np_unit.h"

extern const np_unit np_unit_fdiff, np_unit_texel;

enum { UT_S, UT_T, UT_R, UT_DS, UT_DT, UT_DR, UT_N, UT_K, UT_NIN, UT_NDESC = UT_K };

/* --- Textures and descriptors (shared by every span unit) --- */

/* Words of a descriptor (UT_NDESC fields) into a span at y = 0, x0 = 0. */
void np_ut_span(const uint64_t *in, np_span *sp);
/* The registers of built-in texture number tex (compiled once, thread-safe). */
const np_tex_regs *np_ut_regs(unsigned tex);
/* The name of texture number tex; NULL past the last one defined. */
const char *np_ut_texture_name(unsigned tex);
/*
 * A scene's texture as a named texture of the registry (after the built-in
 * ones): compiled into registers, then "texture=NAME" selects it in every
 * tool. The same name again redefines that texture (same number). 0 with *tex,
 * or -1 with err (it does not fit the registers, or the slots are full).
 * Call before any thread uses the texture.
 */
int np_ut_texture_add(const char *name, const np_ref_texture *t, unsigned *tex, char *err, size_t errlen);
/*
 * The units' texture key (an enumeration: np_ut_texture_name's words, the
 * built-in textures then the scenes' "scene:NAME"), over member of type.
 */
#define UT_TEXTURE_KEY(type, member)                                                                     \
    NP_UNIT_KEY_WORDS("texture", type, member, 0, 2, 0,                                                  \
                      "texture in the registers: a built-in one, or a scene's (scene:NAME, added by a render)", \
                      np_ut_texture_name, NP_UNIT_KEY_SCENE)

/* --- The adapter --- */

/*
 * The adapter's limits: engine stages, bytes of an engine's state and of the
 * per-transaction bundle (the transaction's words, the context, the engine's
 * bundle). A unit's file checks its engine against them (_Static_assert).
 */
enum { NP_SU_STAGES_MAX = 15, NP_SU_CORE_MAX = 8192, NP_SU_SIG_MAX = 4096, NP_SU_SIG_HEAD = 256 };

/* A span unit: its engine, where the engine's configuration and the texture are in its block. */
typedef struct np_su {
    np_unit_span span;       /* np_unit.span points here */
    size_t engine_cfg_size;  /* bytes of the engine's configuration (compared by the eval cache) */
    const char *front_name;  /* the pipe's front stage: "R" (runs the engine) or "F" (places it) */
    /*
     * Optional (NULL: the scene texture's colour at the pixel, np_ref.h, as
     * for every unit that renders the texture): the float reference of a
     * span unit whose engine computes something else (the toy span unit of
     * testbench/test_toy_span.c).
     */
    void (*ref)(const void *cfg, const uint64_t *in, double *out);
    /*
     * The most index integer bits the unit has (0: no colour index register,
     * no scene check). When set, the engine's configuration begins with its
     * idx_int (unsigned), and np_su_cfg_scene checks a scene's register
     * rounding and index range against the unit's bound (np_texreg.h).
     */
    unsigned idx_int_max;
    /*
     * Optional: the unit's own colour bound (LSB) for spans of at most
     * max_span pixels (NULL: error_bound_lsb, the bound for any span). The
     * scene check and the scene sizing use it over the scene's widest span.
     */
    double (*bound_span)(const void *cfg, unsigned max_span);
    /* The pipe's stage table, built by the first pipe_init. */
    np_stage_desc stages[1 + NP_SU_STAGES_MAX];
    int built;
} np_su;

/* The registry's callbacks, for su (the ones NP_SU_DEFINE binds to a unit). */
void np_su_front(const np_su *su, const void *cfg, void *sig);
void np_su_eval(const np_su *su, const void *cfg, const uint64_t *in, uint64_t *out);
/*
 * eval_n: the points in order, the engine kept from one to the next: a point
 * that continues the previous one's span (same s, ds; k one more) is one
 * advance, as the stream model steps; any other is placed as eval places it
 * (seek, or begin and k advances; a sequential engine continues a span
 * forwards). A span's pixels in order are the natural batch.
 */
void np_su_eval_n(const np_su *su, const void *cfg, const uint64_t *in, uint64_t *out, size_t n);
void np_su_ref(const np_su *su, const void *cfg, const uint64_t *in, double *out);
int np_su_pipe_init(np_su *su, np_stage_fn front, np_pipe *p, const void *cfg);
int np_su_stream_init(const np_su *su, void *state, const void *cfg);
size_t np_su_datapath(const np_su *su, const void *cfg, np_op *ops, size_t max);
/*
 * cfg_scene: register the scene's texture and select it (1: the scene uses
 * the unit). cfg holds the defaults. With su->idx_int_max: sizes idx_int to
 * a clamped map's index range (up to the maximum), and refuses (-1, the
 * message naming scene, field, value and the width it needs) a scene whose
 * register rounding takes the unit's bound (u->error_bound_lsb) over 1 LSB.
 */
int np_su_cfg_scene(const np_su *su, const np_unit *u, void *cfg, const np_unit_scene *sc, char *err, size_t errlen);
/*
 * The predicted colour bound (LSB) of unit u in configuration cfg on the
 * scene whose texture cfg selects: the unit's own bound over spans of
 * max_span pixels plus the registers' rounding over the scene (the bound
 * np_su_cfg_scene computed); NAN when cfg's texture is not a scene's.
 */
double np_su_predicted_lsb(const np_unit *u, const void *cfg, unsigned max_span);
/*
 * For a unit's cfg_check: NULL, or a message when cfg's texture is a scene's
 * whose clamped index does not fit cfg's idx_int (it would wrap).
 */
const char *np_su_scene_index_check(const np_unit_span *s, const void *cfg, unsigned idx_int_max);
/* The register bound np_su_cfg_scene computed for texture tex (a scene's), or NULL. */
const struct np_texreg_scene_bound *np_ut_texture_bound(unsigned tex);

/* The callbacks that need no np_su. */
void np_su_fields(const void *cfg, np_unit_fields *f);
void np_su_sig_set_in(void *sig, const uint64_t *in);
void np_su_sig_get_out(const void *cfg, const void *sig, uint64_t *out);
size_t np_su_boundary(const void *cfg, uint64_t (*in)[NP_UNIT_MAX_FIELDS], size_t max);
uint64_t np_su_beats(const void *cfg, const uint64_t *desc);
size_t np_su_descriptors(const void *cfg, uint64_t (*desc)[NP_UNIT_MAX_FIELDS], size_t max);
void np_su_random_desc(const void *cfg, np_rng *rng, uint64_t *desc);
/* The stream model's state: the sequencer behind the generic stream port. */
typedef struct np_su_stream {
    np_span_sim sim;
    np_span in;
    np_span_port port;
} np_su_stream;
void np_su_stream_free(void *state);
void np_su_stream_eval(void *state, np_unit_stream_port *p);
void np_su_stream_clock(void *state, const np_unit_stream_port *p);
int np_su_stream_idle(const void *state);
void np_su_stream_counters(const void *state, uint64_t *cycles, uint64_t *setup);

/* The engine's configuration and registers of a unit configuration block. */
static inline const void *np_su_engine_cfg(const np_unit_span *s, const void *cfg) { return np_unit_span_cfg(s, cfg); }
static inline unsigned np_su_texture(const np_unit_span *s, const void *cfg)
{
    return *(const unsigned *)(const void *)((const char *)cfg + s->texture_offset);
}

/* For a timing(): append one set-up to t. */
void np_su_add_setup(np_unit_timing *t, const char *what, unsigned products, unsigned cycles);

/*
 * The unit's bindings of the adapter for su (an np_su) and its np_unit
 * (for its defaults): the callbacks that need su, and the stream model.
 */
#define NP_SU_DEFINE(SU, UNIT)                                                                                  \
    static void su_front(const void *cfg, void *sig) { np_su_front(&SU, cfg, sig); }                                  \
    static void su_eval(const void *cfg, const uint64_t *in, uint64_t *out) { np_su_eval(&SU, cfg, in, out); }        \
    static void su_ref(const void *cfg, const uint64_t *in, double *out) { np_su_ref(&SU, cfg, in, out); }            \
    static void su_eval_n(const void *cfg, const uint64_t *in, uint64_t *out, size_t n)                               \
    {                                                                                                                  \
        np_su_eval_n(&SU, cfg, in, out, n);                                                                            \
    }                                                                                                                  \
    static int su_pipe_init(np_pipe *p, const void *cfg) { return np_su_pipe_init(&SU, su_front, p, cfg); }           \
    static int su_stream_init(void *state, const void *cfg) { return np_su_stream_init(&SU, state, cfg); }            \
    static size_t su_datapath(const void *cfg, np_op *ops, size_t max) { return np_su_datapath(&SU, cfg, ops, max); } \
    static int su_cfg_scene(void *cfg, const np_unit_scene *sc, char *err, size_t errlen)                              \
    {                                                                                                                  \
        np_unit_cfg_default(&UNIT, cfg);                                                                               \
        return np_su_cfg_scene(&SU, &UNIT, cfg, sc, err, errlen);                                                             \
    }                                                                                                                  \
    static const np_unit_stream su_stream = {                                                                         \
        .n_desc = UT_NDESC,                                                                                            \
        .length_field = UT_N,                                                                                          \
        .beats = np_su_beats,                                                                                          \
        .descriptors = np_su_descriptors,                                                                              \
        .random_desc = np_su_random_desc,                                                                              \
        .state_size = sizeof(np_su_stream),                                                                            \
        .init = su_stream_init,                                                                                        \
        .free = np_su_stream_free,                                                                                     \
        .eval = np_su_stream_eval,                                                                                     \
        .clock = np_su_stream_clock,                                                                                   \
        .idle = np_su_stream_idle,                                                                                     \
        .counters = np_su_stream_counters,                                                                             \
    }

/* The np_unit members the adapter fills (after NP_SU_DEFINE(SU, ...)). */
#define NP_SU_MEMBERS(SU)                                                                                              \
    .fields = np_su_fields, .eval = su_eval, .ref = su_ref, .tolerance_lsb = 1.0, .pipe_init = su_pipe_init,        \
    .sig_set_in = np_su_sig_set_in, .sig_get_out = np_su_sig_get_out, .boundary = np_su_boundary,                    \
    .stream = &su_stream, .cfg_scene = su_cfg_scene, .datapath = su_datapath, .span = &SU.span, .eval_n = su_eval_n

#endif /* UNIT_SPAN_H */
