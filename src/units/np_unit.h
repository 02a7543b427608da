/* SPDX-License-Identifier: MIT */
/*
 * np_unit.h - the registry of hardware units.
 *
 * Every tool (vectors, verify, device, sweep, bench, reports) works on a unit
 * through this one interface, so a new unit plugs into all of them by filling
 * in one np_unit and adding it to np_units[] (units.c), or, for a unit that
 * lives outside the library (a test's), by np_unit_register() at run time.
 * docs/adding-a-unit.md lists the files a new unit brings.
 *
 * Words: every input and output field travels as a uint64_t holding the
 * field's hardware bits, masked to its width (a signed field is its two's
 * complement bit pattern). np_unit_field_value() turns an output word into
 * the real value it stands for.
 */
#ifndef NP_UNIT_H
#define NP_UNIT_H

#include <stddef.h>
#include <stdint.h>

#include "np_datapath.h"
#include "np_fixed.h"
#include "np_pipe.h"

#ifdef __cplusplus
extern "C" {
#endif

struct np_ref_texture;
struct np_aacount_scene;
struct np_hatch_scene;
struct np_rng;
struct np_unit_timing;
struct np_span_engine;
struct np_tex_regs;
struct np_rng;
struct np_unit_reg;

/*
 * A span unit's engine (rtl_model/np_span.h) as the registry shows it: the
 * renderer and the reports run any unit that has one on a frame's span
 * descriptors, with the unit's configuration.
 */
/*
 * One series of the error-against-run-time report (`noisepipe report
 * runtime`): the unit rendered with key = each of values, over fixed, over
 * the scene's configuration.
 */
typedef struct np_unit_sweep {
    const char *label;       /* the plots' legend, before the values' range, e.g. "fdiff K=0, guard" */
    const char *fixed;       /* "key=value,..." (NULL: none) */
    const char *key;         /* the swept key */
    const unsigned *values;
    unsigned n_values;
    int cycles_fixed;        /* the key does not change the cycles: they are counted once, at fixed */
    unsigned plot;           /* the series' place in the plots' legends (and its colour) */
} np_unit_sweep;

typedef struct np_unit_span {
    const struct np_span_engine *engine;
    size_t engine_cfg_offset; /* where the engine's configuration is inside the unit's block */
    size_t texture_offset;    /* where the texture number is (unsigned; src/units/unit_span.h) */
    /* The runtime report: the unit's sweeps, in the order of the report's rows. */
    const np_unit_sweep *sweeps;
    unsigned n_sweeps;
    /* Optional: one more error image for the report, NAME_UNIT_<extra_name>_err.png at extra_cfg. */
    const char *extra_name, *extra_cfg;
    /*
     * Optional (NULL: the conformance test cannot check the declared widths):
     * drive the engine's signals for its configuration ecfg and registers r
     * over the engine's stiff cases and random ones drawn from g, widening
     * each trace in t[0..n) whose signal they produce (np_datapath.h). The
     * conformance test (datapath_widths) calls it on registers over their
     * full formats, since the engine's declaration (np_span_engine.datapath)
     * holds for any registers. NULL, or a message naming a window of the
     * model that does not hold what the declaration keeps.
     */
    const char *(*trace)(const void *ecfg, const struct np_tex_regs *r, struct np_rng *g, np_trace *t, size_t n);
    /*
     * Optional (NULL: 0, the cost model does not know the engine's seek):
     * the clocks the engine's seek (np_span_engine.seek) takes to place a
     * pixel directly, for its configuration ecfg and registers r: the
     * G-buffer's cost model adds them to a run that starts inside its
     * sub-span (np_gbuf.h, "Deferred shading").
     */
    unsigned (*seek_cycles)(const void *ecfg, const struct np_tex_regs *r);
} np_unit_span;

/*
 * A supersampling unit's sample order and resolve (np_unit.samples): what a
 * G-buffer renderer needs of a unit that chooses how many of a pixel's m x m
 * samples to shade, so that the image it resolves is the unit's, bit for bit
 * (src/render/np_gbuf.h takes the first unit of the registry that has one).
 */
struct np_unit_scene;

/*
 * A pixel's window as a sample-count unit reads it (np_unit_samples.count):
 * the pixel's n = m^2 G-buffer samples and the lumas of the image S (each
 * pixel's sample of index 0), in the G-buffer's formats.
 */
enum { NP_UNIT_WIN_SAMPLES = 16, NP_UNIT_WIN_LUMAS = 5 };
typedef struct np_unit_window {
    uint32_t d[NP_UNIT_WIN_SAMPLES];       /* u24 depth code; uncovered: 2^24 - 1 */
    int8_t nrm[NP_UNIT_WIN_SAMPLES][3];    /* s8 x 3 normal; uncovered: (0, 0, 0) */
    uint8_t luma[NP_UNIT_WIN_LUMAS];       /* u8 Y of S: the pixel, left, right, up, down (clamped to the image) */
} np_unit_window;

/* A sample-count unit's answer for one window: s, and each metric's own count (a metric not built: as the unit leaves it). */
typedef struct np_unit_count {
    uint8_t s, sd, sn, ss;
} np_unit_count;

typedef struct np_unit_samples {
    /* The first s samples of an m x m pixel (1 <= m <= 4) as a mask: bit b m + a is sample (a, b); s >= m^2 gives all. */
    uint16_t (*mask)(unsigned m, unsigned s);
    /* One 8-bit channel of s shaded samples (1 <= s <= 16) that sum to sum (<= 255 s), as the unit resolves it. */
    uint8_t (*resolve)(uint32_t sum, unsigned s);
    /*
     * Optional (count NULL: the unit does not choose a count per pixel): the
     * adaptive count, for the adaptive supersampling renderer
     * (src/render/np_render_aa.h takes the first unit of the registry that
     * has one). cfg is a configuration block (np_unit_cfg), regs a register
     * block the unit computes from it, in np_unit_cfg storage too; both
     * opaque to the renderer.
     */
    /* cfg for scene sc's section of the unit (sc->aa, not NULL) at m (1..4), R = depth_range (z_far - z_near). */
    void (*cfg_scene)(void *cfg, const struct np_unit_scene *sc, unsigned m, double depth_range);
    /* Set cfg's m (1..4), no other key changing. */
    void (*set_m)(void *cfg, unsigned m);
    /* The host-computed registers of cfg, into regs (np_unit_cfg storage). */
    void (*regs)(const void *cfg, void *regs);
    /* The bit-exact count of window w with registers regs. */
    void (*count)(const void *cfg, const void *regs, const np_unit_window *w, np_unit_count *o);
    /*
     * The cycle-accurate model (the parallel variant) fed windows 0 .. n-1
     * (window(ctx, i, w) writes window i) back to back, output ready every
     * clock: its cycles, and *mismatch |= 1 when a count differs from
     * want[i]. 0, or -1 (no memory; nothing written).
     */
    int (*count_pipe)(const void *cfg, void (*window)(const void *ctx, size_t i, np_unit_window *w), const void *ctx,
                      size_t n, const uint8_t *want, uint64_t *cycles, int *mismatch);
    /* The serial variant's latency, clocks (its schedule: n beats a window + this). */
    unsigned (*serial_latency)(const void *cfg);
    /* After the count, over a w x h image of counts s: what cfg does there (a tile maximum), or nothing. */
    void (*post)(const void *cfg, uint8_t *s, unsigned w, unsigned h);
} np_unit_samples;

/*
 * A hatching unit's interface for the hatching renderer (np_unit.strokes;
 * src/render/np_hatch_render.h): a unit whose input fields are xu, xv (seed
 * space), tone, pm, om and whose one output is the colour, with the renderer's
 * coverage lists and per-stroke probe. cfg is a configuration block
 * (np_unit_cfg); a coverage list set is an opaque object of the unit's.
 */
enum { NP_UNIT_STROKE_LAYERS_MAX = 8 };
typedef struct np_unit_stroke_info {
    unsigned layers;       /* layers drawn, <= NP_UNIT_STROKE_LAYERS_MAX */
    unsigned seeds;        /* N: stroke seeds a tile per layer */
    unsigned brute_cycles; /* an iterative unit's cycles a point by brute force: layers N / lanes */
} np_unit_stroke_info;

/* One stroke at a point: its alpha, its level ramp and its offset from the seed (the unit's formats). */
typedef struct np_unit_stroke {
    uint32_t alpha, am;
    int64_t ru, rv;
} np_unit_stroke;

typedef struct np_unit_strokes {
    /* The xu / xv input word of a UV coordinate x_uv (u128 Q32.96, mod 2^32 in UV) at level (-64..31). */
    uint64_t (*xs)(np_u128 x_uv, int level);
    void (*info)(const void *cfg, np_unit_stroke_info *i);
    /* The host's coverage lists for cfg; NULL with a message in err (a list overflows, no memory). */
    void *(*cover_new)(const void *cfg, char *err, size_t errlen);
    void (*cover_free)(void *cover);
    /* Make cfg the coverage unit that reads lists cover (its cycle model and timing); cover outlives cfg's use. */
    void (*cover_cfg)(void *cfg, const void *cover);
    /*
     * The coverage unit's output word at input words in (xu, xv, tone, pm, om),
     * the listed seeds only; *cycles: an iterative unit's cycles there; len[l]:
     * the list length of each layer l < layers at the point.
     */
    uint64_t (*eval_cover)(const void *cfg, const void *cover, const uint64_t *in, unsigned *cycles, unsigned *len);
    /* Stroke i of layer l at input words in (brute force's set-up, then that seed's stage). */
    void (*stroke)(const void *cfg, const uint64_t *in, unsigned l, unsigned i, np_unit_stroke *z);
    /* The exact centre of stroke i of layer l in its seed tile, rounded down: u128 Q32.96 per axis (< 2^96). */
    void (*centre)(const void *cfg, unsigned l, unsigned i, np_u128 *su, np_u128 *sv);
} np_unit_strokes;

/* The engine's configuration inside a unit's configuration block cfg. */
static inline const void *np_unit_span_cfg(const np_unit_span *s, const void *cfg)
{
    return (const char *)cfg + s->engine_cfg_offset;
}

/*
 * A scene as the units see it (np_unit.cfg_scene): what a unit may read of a
 * scene, in the registry's and the units' own types. A client that has a
 * scene adapts it to this (the renderer: np_scene_for_units, src/render/), so
 * the registry and the units know nothing of the scene file or the renderer.
 * A unit whose scene section is its own declares the section's type with the
 * unit (np_aacount_scene in unit_aacount.h, np_hatch_scene in unit_hatch.h).
 */
typedef struct np_unit_scene {
    const char *name;                   /* for messages and the names of register sets */
    unsigned width;                     /* image width in pixels: the longest span */
    const struct np_ref_texture *tex;   /* the scene's texture (np_ref.h) */
    /* The box of the texture coordinates over the scene's explicit polygons (all 0 when it has none). */
    double tex_lo[3], tex_hi[3];
    int size_registers;                 /* a tool asks for registers sized to the scene (np_su_cfg_scene) */
    const char *noise_unit;             /* the unit the texture's octaves read ("simplex4"); NULL: value noise */
    const struct np_aacount_scene *aa;  /* the "aa" section; NULL: none */
    const struct np_hatch_scene *hatch; /* the "hatch" section; NULL: none */
} np_unit_scene;

enum { NP_UNIT_MAX_FIELDS = 8, NP_UNIT_CFG_MAX = 256 };

/* np_unit.adversarial's classes. */
enum { NP_ADV_ROUNDING = 1, NP_ADV_FACES = 2 };

/* Storage for any unit's configuration block (aligned for any struct). */
typedef union np_unit_cfg {
    unsigned char bytes[NP_UNIT_CFG_MAX];
    long double align_ld;
    uint64_t align_u64;
    void *align_p;
} np_unit_cfg;

typedef struct np_field {
    char name[16];   /* "x", "f" */
    unsigned bits;   /* hardware width, 1..64 */
    int is_signed;   /* two's complement */
    unsigned frac;   /* fraction bits: value = word / 2^frac */
    char format[32]; /* human text, e.g. "u16 Q8.8", "s8 Q2.6" */
} np_field;

typedef struct np_unit_fields {
    unsigned n_in, n_out;
    np_field in[NP_UNIT_MAX_FIELDS];
    np_field out[NP_UNIT_MAX_FIELDS];
} np_unit_fields;

/*
 * One configuration key of a unit, declared as data (np_unit.keys): the one
 * place a key's name, storage, range, default and meaning are written.
 * configure, format, the validation messages, `noisepipe units`, the
 * renderer's --unit-config and the DSE sweeps all read it (units.c).
 *
 * The value is an unsigned integer field of the unit's configuration block
 * (offset, size: 1, 2, 4 or 8 bytes). Numbers are written in decimal only
 * (docs/vectors.md, "Configuration keys"). An enumeration (word != NULL) is
 * written as a word and stored as its number: word(v) is the word of value v,
 * NULL when there is none; lo..hi are the words every build has (for
 * `noisepipe units`), and values above hi are accepted while word() names
 * them (words added at run time, e.g. a scene's texture).
 */
typedef struct np_unit_key {
    const char *name;    /* as written in "name=value" */
    size_t offset, size; /* the field in the unit's configuration block */
    unsigned lo, hi;     /* accepted range, inclusive */
    unsigned def;        /* default (unused when derive is set) */
    const char *meaning; /* one line */
    /* Optional: the default follows other keys: the value for cfg when this key is not given. */
    unsigned (*derive)(const void *cfg);
    /* Optional: an enumeration (above). */
    const char *(*word)(unsigned v);
    /* NP_UNIT_KEY_* */
    unsigned flags;
} np_unit_key;

enum {
    /*
     * The unit's cfg_scene sets this key from the scene (a texture): it is not
     * a design choice, so a render's configuration text leaves it out
     * (NP_UNIT_FMT_NO_SCENE) and --unit-config refuses it.
     */
    NP_UNIT_KEY_SCENE = 1u,
    /*
     * A key added to a unit after its vector files, KAT and image hashes were
     * checked in: the configuration text leaves it out while it holds its
     * default, and a '# config' line without it means the default, so the
     * existing files stay byte-identical (a fixed default only, not derived).
     */
    NP_UNIT_KEY_ADDED = 2u
};

/* Table entries: a number with a fixed default; one whose default derive() gives; an enumeration; the end. */
#define NP_UNIT_KEY(name, type, member, lo, hi, def, meaning) \
    { name, offsetof(type, member), sizeof(((type *)0)->member), lo, hi, def, meaning, NULL, NULL, 0u }
#define NP_UNIT_KEY_DERIVED(name, type, member, lo, hi, derive, meaning) \
    { name, offsetof(type, member), sizeof(((type *)0)->member), lo, hi, 0u, meaning, derive, NULL, 0u }
#define NP_UNIT_KEY_WORDS(name, type, member, lo, hi, def, meaning, word, flags) \
    { name, offsetof(type, member), sizeof(((type *)0)->member), lo, hi, def, meaning, NULL, word, flags }
#define NP_UNIT_KEY_ADDED_LATER(name, type, member, lo, hi, def, meaning) \
    { name, offsetof(type, member), sizeof(((type *)0)->member), lo, hi, def, meaning, NULL, NULL, NP_UNIT_KEY_ADDED }
#define NP_UNIT_KEY_END { NULL, 0u, 0u, 0u, 0u, 0u, NULL, NULL, NULL, 0u }

typedef struct np_unit {
    const char *name;    /* as typed on the command line, e.g. "classic3" */
    const char *summary; /* one line */
    /*
     * Configuration: an opaque block of at most NP_UNIT_CFG_MAX bytes whose
     * keys are this table, terminated by a NULL name. Configure, format and
     * default through np_unit_configure / np_unit_cfg_format /
     * np_unit_cfg_default (the table's order is the text's order).
     */
    const np_unit_key *keys;
    /* NULL when the keys are consistent with each other (each key's range is the table's), else a message. */
    const char *(*cfg_check)(const void *cfg);
    void (*fields)(const void *cfg, np_unit_fields *f);
    /* Bit-exact model. */
    void (*eval)(const void *cfg, const uint64_t *in, uint64_t *out);
    /* Float reference: the real value of each output field. */
    void (*ref)(const void *cfg, const uint64_t *in, double *out);
    /* Accuracy contract: max |output - reference| in output LSB (per field). */
    double tolerance_lsb;
    /* Guaranteed bound of the unit's error argument, in LSB (for reports). */
    double (*error_bound_lsb)(const void *cfg);
    /* Cycle-accurate model (np_pipe); the bundle is the pipe's signal struct. */
    int (*pipe_init)(np_pipe *p, const void *cfg);
    void (*sig_set_in)(void *sig, const uint64_t *in);
    void (*sig_get_out)(const void *cfg, const void *sig, uint64_t *out); /* masked words */
    /*
     * Hand-annotated boundary cases (the annotations are in the unit's
     * source) for the vector generator: writes up to max inputs, n_in words
     * each; returns the full count even when it is larger than max.
     */
    size_t (*boundary)(const void *cfg, uint64_t (*in)[NP_UNIT_MAX_FIELDS], size_t max);
    /*
     * Optional (NULL: the sweep calls eval and ref per input): the exhaustive
     * sweep's fast path (its constants: np_unit_sweep.h; np_sweep.h runs it)
     * for a unit with inputs x, y, z (u16 each).
     * For the 256 * rows inputs (x0 + t, y0 + r, z), 0 <= t < 256,
     * 0 <= r < rows, where x0 is a multiple of 256, rows a power of two <= 256
     * and y0 a multiple of rows, writes at index i = (f * rows + r) * 256 + t
     * (f: output field):
     *   if what & NP_SWEEP_MODEL: code[i] = the model's output as a signed
     *     integer in output LSB (the field's word, sign-extended if signed);
     *   if what & NP_SWEEP_REF: ref[i] = the float reference's value.
     * It must give exactly eval's bits and ref's doubles (testbench/test_sweep.c
     * proves it for classic3: a unit that adds a kernel adds such a test).
     */
    void (*sweep_rows)(const void *cfg, uint16_t x0, uint16_t y0, uint16_t z, unsigned rows,
                       unsigned what, int32_t *code, double *ref);
    /*
     * Optional (NULL: the adversarial search (np_search.h) has no classes of
     * the unit's own): n inputs of class cls for a unit with inputs x, y, z,
     * drawn with rng (the same rng state gives the same inputs), into in:
     *   NP_ADV_ROUNDING  where the datapath's internal roundings are worst,
     *                    derived from cfg's formats (not guessed);
     *   NP_ADV_FACES     the unit's own faces and boundaries, beyond the
     *                    equal-offset and lattice faces the search makes.
     * Returns n, or 0 when the unit has no inputs of that class.
     */
    size_t (*adversarial)(const void *cfg, unsigned cls, struct np_rng *rng,
                          uint64_t (*in)[NP_UNIT_MAX_FIELDS], size_t n);
    /*
     * Optional (NULL: the search climbs on the output's error): write to fine
     * a configuration of the same datapath whose outputs keep more fraction
     * bits (every internal width unchanged, only the last rounding finer), so
     * that its error against the reference is the datapath's error before
     * the output rounding: the smooth objective of the search's hill-climb.
     */
    void (*fine_cfg)(const void *cfg, void *fine);
    /*
     * Optional (NULL: not in the gate report): the datapath declaration of
     * np_datapath.h for cfg; writes up to max ops, returns the full count.
     */
    size_t (*datapath)(const void *cfg, np_op *ops, size_t max);
    /*
     * Optional (NULL: a one-input-one-output unit): a stream unit, which reads
     * a descriptor and writes a run of beats (the scanline texturing units: a
     * span in, its pixels out). Transactions are then beats, and the unit's
     * cycle-accurate model is this stream model; see np_stream.h.
     */
    const struct np_unit_stream *stream;
    /*
     * Optional (NULL: the timing is np_pipe's: latency = pipe depth, one
     * result per clock, the declaration's stages are the pipe's): the timing
     * of a unit whose cycle-accurate model is not one np_pipe (a stream unit),
     * from the unit's own schedule; the gate report's stages are then the
     * declaration's, in order. 0, or -1 with a message in err.
     */
    int (*timing)(const void *cfg, struct np_unit_timing *t, char *err, size_t errlen);
    /*
     * Optional (NULL: no scene uses the unit): configure cfg (from the
     * defaults) for what scene sc needs. 1: the scene uses the unit and cfg
     * is set; 0: it does not; -1 with a message in err.
     */
    int (*cfg_scene)(void *cfg, const np_unit_scene *sc, char *err, size_t errlen);
    /*
     * Optional (NULL: not a span unit): the span engine. A unit with one and
     * a cfg_scene that accepts a scene is rendered by `noisepipe render`.
     */
    const np_unit_span *span;
    /*
     * Optional (NULL: no width check, unless the unit is a span unit with
     * span->trace): widen each trace in t[0..n) whose signal stage k of the pipe
     * (pipe_init's stage k) produces, from the signal bundle sig just after
     * that stage ran. The conformance test (testbench/conformance.c) runs
     * the stages over the generator's cases and checks every declared
     * width (datapath) against what it traced.
     */
    void (*trace)(const void *cfg, unsigned k, const void *sig, np_trace *t, size_t n);
    /*
     * Optional (NULL: the default only): further configurations, as
     * "key=value,..." specs, NULL-terminated, on which the conformance test
     * runs its checks besides the default (narrow, wide, parts left out).
     */
    const char *const *conformance_configs;
    /*
     * Optional (NULL: the unit has no register block beyond its keys): the
     * registers configuration cfg holds (a unit whose keys select a register
     * set, e.g. wave's `regs`), in the unit's order: writes up to max, returns
     * the full count. A vector file carries them as '# reg NAME HEX FORMAT'
     * header lines (docs/vectors.md), which the reader checks against cfg, so
     * an RTL testbench can load the registers from the file.
     */
    size_t (*regs)(const void *cfg, struct np_unit_reg *r, size_t max);
    /*
     * Optional (NULL: np_unit_eval_n calls eval once per point): the
     * bit-exact model over n points at once, its configuration decoded once
     * per call. Field f of point i is in[f * n + i] and out[f * n + i] (one
     * array per field, as np_classic_eval_n takes them), words as eval's.
     * It must give exactly eval's words for every point, in any order and
     * for any n (the conformance check `batch` compares them on the level-1
     * cases, in runs and shuffled). Call it through np_unit_eval_n.
     */
    void (*eval_n)(const void *cfg, const uint64_t *in, uint64_t *out, size_t n);
    /*
     * Optional (NULL: the unit does not choose samples): its sample order and
     * resolve, for the G-buffer renderer (np_unit_samples).
     */
    const np_unit_samples *samples;
    /*
     * Optional (NULL: not a hatching unit): what the hatching renderer needs
     * besides eval, ref and the pipe (np_unit_strokes).
     */
    const np_unit_strokes *strokes;
} np_unit;

/*
 * The bit-exact model of u over n points (np_unit.eval_n's layout: field f
 * of point i at in[f * n + i], out[f * n + i]): the unit's batch path when it
 * has one, else np_unit_eval_n_generic. in and out do not overlap.
 */
void np_unit_eval_n(const np_unit *u, const void *cfg, const uint64_t *in, uint64_t *out, size_t n);
/* The fallback: u->eval per point (gathering each point's words), whatever u->eval_n is. */
void np_unit_eval_n_generic(const np_unit *u, const void *cfg, const uint64_t *in, uint64_t *out, size_t n);

/* For an eval_n that works in chunks: field f of points i0 .. i0+m-1 of an n-point batch, as u16 words. */
static inline void np_unit_chunk_u16(const uint64_t *in, size_t n, unsigned f, size_t i0, size_t m, uint16_t *dst)
{
    for (size_t i = 0; i < m; i++)
        dst[i] = (uint16_t)in[f * n + i0 + i];
}

/* One register of a unit's register block (np_unit.regs). */
typedef struct np_unit_reg {
    char name[16];   /* "tr0.kx" */
    unsigned bits;   /* 1..64 */
    uint64_t value;  /* the register's bits, masked to its width (two's complement if signed) */
    char format[24]; /* "s32 Q0.32" */
} np_unit_reg;

enum { NP_UNIT_MAX_REGS = 64 };

/* Fill one register description (value masked to bits). */
void np_unit_set_reg(np_unit_reg *r, const char *name, unsigned bits, uint64_t value, const char *fmt);

/* A set-up the unit stalls for (np_unit_timing). */
typedef struct np_unit_setup {
    char what[48];      /* e.g. "cell (per octave, on a cell change)" */
    unsigned products;  /* multiplications it issues */
    unsigned cycles;    /* the stall, clocks */
} np_unit_setup;

enum { NP_UNIT_MAX_SETUPS = 6, NP_UNIT_MAX_MULTI = 4 };

typedef struct np_unit_timing {
    unsigned latency;     /* clocks from accepting an input (a stream unit: a descriptor) to its first result */
    double throughput;    /* results per clock at the peak rate */
    char throughput_note[96]; /* what the peak rate holds for, e.g. "inside a cell" */
    /* Stages that take several clocks (a pipelined engine): the path per clock is the stage's / clocks. */
    unsigned n_multi;
    struct {
        const char *stage;
        unsigned clocks;
    } multi[NP_UNIT_MAX_MULTI];
    unsigned n_setup;
    np_unit_setup setup[NP_UNIT_MAX_SETUPS];
} np_unit_timing;

/* The built-in units, NULL-terminated. Tools that list units use np_unit_at(), which also sees registered ones. */
extern const np_unit *const np_units[];

/*
 * Runtime registration: add unit u (which must outlive every use; its name
 * must be new) behind the built-in units, so that np_unit_find, np_unit_at
 * and every tool built on them (vectors, verify, device, conformance, gate
 * report) see it. For a test or an embedding program that brings its own
 * unit; at most NP_UNIT_MAX_REGISTERED. 0, or -1 when the name is taken,
 * the unit lacks a required entry or the table is full.
 *
 * Not synchronised: register every unit before any thread that reads the
 * registry starts (the sweep's workers only read it).
 */
enum { NP_UNIT_MAX_REGISTERED = 16 };
int np_unit_register(const np_unit *u);
/* Every unit, built-in first then registered, by index from 0; NULL past the last. */
const np_unit *np_unit_at(size_t i);
/* The unit called name (built-in or registered), or NULL. */
const np_unit *np_unit_find(const char *name);

/* Real value of an output word of field f. */
double np_unit_field_value(const np_field *f, uint64_t word);

/* A whole decimal number in [lo, hi] (digits only: no sign, blank or base prefix); 0, or -1. */
int np_unit_parse_uint(const char *v, unsigned lo, unsigned hi, unsigned *out);

/* For units' fields(): fill one field description. */
void np_unit_set_field(np_field *f, const char *name, unsigned bits, int sgn, unsigned frac, const char *fmt);

/* The key of u called name, or NULL. */
const np_unit_key *np_unit_key_find(const np_unit *u, const char *name);
/* Number of keys of u. */
size_t np_unit_key_count(const np_unit *u);
/* The value of key k in cfg; store one (no check: np_unit_cfg_set checks). */
unsigned np_unit_key_get(const np_unit_key *k, const void *cfg);
void np_unit_key_put(const np_unit_key *k, void *cfg, unsigned v);
/* "lo..hi", or "w1|w2|w3" for an enumeration. */
void np_unit_key_range(const np_unit_key *k, char *buf, size_t len);
/* The value text of key k in cfg (a number, or an enumeration's word). */
void np_unit_key_text(const np_unit_key *k, const void *cfg, char *buf, size_t len);

/* Every key at its default (derived keys from the others); cfg is an np_unit_cfg (all of it is cleared first). */
void np_unit_cfg_default(const np_unit *u, void *cfg);
/*
 * Set one key from its text, no other key changes (a derived key is not
 * re-derived: np_unit_configure does that). 0, or -1 with a message naming
 * the key, the value and the range (or the known keys when key is unknown).
 */
int np_unit_cfg_set(const np_unit *u, void *cfg, const char *key, const char *value, char *err, size_t errlen);

enum {
    NP_UNIT_FMT_COMMAS = 1u,  /* "k=v,k=v" (one token) instead of "k=v k=v" */
    NP_UNIT_FMT_NO_SCENE = 2u /* leave out the keys the scene sets (NP_UNIT_KEY_SCENE) */
};
/* "key=value key=value": every key, in the table's order (the '# config' header line). */
void np_unit_cfg_format(const np_unit *u, const void *cfg, char *buf, size_t len);
/* The same with NP_UNIT_FMT_* options (the golden image hashes: COMMAS | NO_SCENE). */
void np_unit_cfg_format_opt(const np_unit *u, const void *cfg, unsigned how, char *buf, size_t len);

/*
 * Configure u from "key=value[,key=value...]" (commas or blanks between;
 * NULL or "" = defaults): the keys given over the defaults, the derived keys
 * not given derived, then the unit's cfg_check. A key given twice is an
 * error naming it. 0, or -1 with a message in err.
 */
int np_unit_configure(const np_unit *u, void *cfg, const char *spec, char *err, size_t errlen);
/*
 * The same, but spec must give every key exactly once (a vector file's
 * '# config' line): a missing key is an error naming it.
 */
int np_unit_configure_all(const np_unit *u, void *cfg, const char *spec, char *err, size_t errlen);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* NP_UNIT_H */
