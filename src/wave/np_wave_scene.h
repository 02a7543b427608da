/* SPDX-License-Identifier: MIT */
/*
 * np_wave_scene.h - a water grid with wave train boxes (WTBs), evaluated
 * frame by frame through the wave unit (rtl_model/np_wave.h): boxes and their
 * rays (PIN half-open cells), action points over the terrain (PIN Green's
 * law capped at 1.3, 0 over land, linear recovery over 16 grid units),
 * refraction as a phase shift, round waves (eq. (10)), irregular height
 * (eq. (8)), capillary noise (eq. (9), rates from the classic3 noise unit),
 * view-frustum culling of oriented boxes grown by sum A sideways, the cycle
 * model of the whole frame and the time-budget scheduler (PIN descending A).
 * docs/wave.md, "Scenes", has every choice.
 */
#ifndef NP_WAVE_SCENE_H
#define NP_WAVE_SCENE_H

#include <stddef.h>
#include <stdint.h>

#include "np_wave.h"

#ifdef __cplusplus
extern "C" {
#endif

enum { NP_WAVE_MAX_BOXES = 16 };

/* Effects (np_wave_scene.effects). */
enum { NP_WAVE_FX_REFRACTION = 1u, NP_WAVE_FX_IRREGULAR = 2u, NP_WAVE_FX_NOISE = 4u, NP_WAVE_FX_ROUND = 8u };

typedef struct np_wave_train_spec {
    double lambda; /* m */
    double angle;  /* rad, from the box's u axis */
    double amp;    /* A, m */
    double phase;  /* rad */
} np_wave_train_spec;

/* One point of a box, in ray order: the unit's transaction but for the frame. */
typedef struct np_wave_pt {
    uint16_t i, j, a, b;
    uint32_t ph; /* refraction + round waves, turns Q0.32 */
    uint16_t g;  /* ray gain u15 Q1.14 */
} np_wave_pt;

typedef struct np_wave_box {
    /* Given. */
    double ox, oz;      /* origin (the lower left corner looking along u), m */
    double angle;       /* u = (cos, sin) in the x-z plane, rad */
    double length;      /* along u (fetch), m */
    double width;       /* across (V rays), m */
    double wind;        /* m/s (eq. (1); informative when every train gives its amplitude) */
    double irr_a;       /* eq. (8)'s a, m (<= the smallest A) */
    unsigned n;
    np_wave_train_spec tr[NP_WAVE_MAX_TRAINS];
    /* Derived by np_wave_scene_prepare (ux, uz by np_wave_box_axes). */
    double ux, uz;         /* u = (cos angle, sin angle), from np_math */
    unsigned steps, rays;  /* L and V in grid units */
    np_wave_unit unit;     /* its registers, every train */
    double sum_ka;         /* 1.3 sum k (A + a): where the surface may fold */
    double hmax;           /* the OBB's half height: own and overlapping boxes' 1.3 sum (A + a), plus noise */
    double grow;           /* the OBB's sideways growth, m */
    np_wave_pt *pts;       /* its grid points in ray order */
    np_wave_pt *gpts;      /* the same points in grid order (j, then i): np_wave_frame's order, for locality */
    size_t npts;
} np_wave_box;

typedef struct np_wave_camera {
    double eye[3], target[3], up[3];
    double fov_y;      /* rad */
    double aspect, znear, zfar;
} np_wave_camera;

typedef struct np_wave_scene {
    unsigned grid;     /* grid x grid water points */
    double extent;     /* m: the grid spans [0, extent) in x and z */
    double dt;         /* s a frame */
    unsigned effects;  /* NP_WAVE_FX_* */
    int allow_fold;
    int reads_normals; /* "normals": true: the scene reads the unit's nx, ny, nz (key normals=1) */
    int reads_fold;    /* "fold": true: the scene reads the unit's fold flag (key fold=1) */
    unsigned lanes;    /* train lanes of the unit (1: one train a pass) */
    double noise_amp;  /* b, m */
    double noise_rate; /* rad/s at r = 1 (PIN 4) */
    /* Terrain: an island of noise (the classic3 unit) over a flat sea floor. */
    double sea_depth, isl_x, isl_z, isl_radius, isl_height, isl_noise, isl_scale;
    int has_camera;
    np_wave_camera cam;
    unsigned nbox;
    np_wave_box box[NP_WAVE_MAX_BOXES];
    /* Derived. */
    double spacing;
    float *depth;  /* grid^2, m (<= 0: land) */
    uint8_t *rate; /* grid^2, eq. (9)'s r as u8 */
} np_wave_scene;

/* Defaults for every field (then a reader fills what a file gives). */
void np_wave_scene_init(np_wave_scene *s);
void np_wave_scene_free(np_wave_scene *s);
/*
 * Derive everything: terrain, boxes' registers and point lists, OBBs. 0; or
 * -1 with a message naming the box (a refusal: exit 2), e.g. a box whose
 * 1.3 sum k (A + a) (with overlapping boxes) exceeds 1 without allow_fold,
 * a register set the unit refuses, a train over Nyquist left out (a note,
 * not an error: *notes counts them).
 */
int np_wave_scene_prepare(np_wave_scene *s, unsigned *dropped, char *err, size_t errlen);

/* Set the box's axes (ux, uz) from its angle, with np_math's sin and cos in turns. */
void np_wave_box_axes(np_wave_box *b);
/* The box's grid points: cell of internal point (a, b) is s in (a, a + 1], w in [b, b + 1) grid units. */
int np_wave_cell_of(const np_wave_box *b, double spacing, unsigned i, unsigned j, unsigned *a, unsigned *r);
/* Enumerate the box's points ray by ray (each grid point at most once); calls f(ctx, i, j, a, b); returns the count. */
size_t np_wave_box_walk(const np_wave_box *b, double spacing, unsigned grid,
                        void (*f)(void *ctx, unsigned i, unsigned j, unsigned a, unsigned r), void *ctx);

/* Frustum culling: 1 when the box's OBB is at least partly inside the camera's frustum. */
int np_wave_box_visible(const np_wave_scene *s, const np_wave_box *b);

/* What a frame runs: per box, trains selected (bit k: train k), and the noise pass. */
typedef struct np_wave_plan {
    unsigned sel[NP_WAVE_MAX_BOXES];
    int visible[NP_WAVE_MAX_BOXES];
    int noise;
} np_wave_plan;

/* Everything visible, every train, the noise pass when the scene has it. */
void np_wave_plan_full(const np_wave_scene *s, np_wave_plan *p);
/* Cycles of a frame under plan p (the cycle model below). */
uint64_t np_wave_plan_cycles(const np_wave_scene *s, const np_wave_plan *p);
/* The time-budget scheduler: trains by descending A (PIN) while they fit budget cycles; noise last. */
void np_wave_plan_budget(const np_wave_scene *s, uint64_t budget, np_wave_plan *p);

/* Cycle costs (docs/wave.md "Cycle model"). */
enum {
    NP_WAVE_CYC_CULL = 6,      /* per box, culled or not: six plane tests */
    NP_WAVE_CYC_BOX = 4,       /* per visible box: its box registers */
    NP_WAVE_CYC_TRAIN = 6,     /* per selected train: its registers */
    NP_WAVE_CYC_RAY = 1        /* per ray and pass: the ray's ph and g */
};

/*
 * Evaluate frame t under plan p through the bit-exact model: y, dx, dz
 * (Q5.10 LSB, summed over boxes and passes, plus the noise) into the
 * grid^2 arrays. Returns the cycles (np_wave_plan_cycles).
 */
uint64_t np_wave_frame(const np_wave_scene *s, const np_wave_plan *p, uint32_t t, int32_t *y, int32_t *dx, int32_t *dz);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* NP_WAVE_SCENE_H */
