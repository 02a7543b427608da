/* SPDX-License-Identifier: MIT */
/*
 * np_render_tools.h - what the render and report commands run on the
 * renderer: golden-image hash lists (render_hash.c), the render benchmark
 * (render_bench.c) and the hatched scenes (render_hatch_scene.c). The
 * commands (src/cli/cmd_render.c, cmd_report.c) parse the options and call these.
 */
#ifndef NP_RENDER_TOOLS_H
#define NP_RENDER_TOOLS_H

#include <stddef.h>

#include "np_render.h"
#include "np_unit.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The configuration the command line gives unit u over the scene's ("key=value,..."; NULL: none). */
typedef const char *(*np_render_spec_fn)(const void *ctx, const np_unit *u);

/* --- Golden hashes --- */

typedef struct hash_rec {
    char scene[64], image[16], hash[65], cfg[256];
} hash_rec;

typedef struct hash_list {
    hash_rec *r;
    size_t n, cap;
} hash_list;

int np_render_hash_add(hash_list *l, const char *scene, const char *image, const char *hash, const char *cfg);
/* Lines "scene image sha256 configuration"; '#' comments. 0, or -1 with a message. */
int np_render_hash_read(const char *path, hash_list *l);
int np_render_hash_write(const char *path, const hash_list *l);
/* Compare got with the golden list; prints each difference. Returns the number of failures. */
unsigned np_render_hash_check(const hash_list *golden, const hash_list *got, const char *path);

/* --- Benchmark --- */

/* Time the float reference and every unit on scene path, best of repeat runs. NP_EXIT_*. */
int np_render_bench(const char *path, unsigned repeat, np_render_spec_fn spec, const void *ctx);

/*
 * A scene with a "hatch" section: the hatched image through the unit hatch
 * (render_hatch.c, docs/hatch.md "Scenes") into out, its hash appended;
 * table: B16/C16/B64/C64 beside the paper's Table 1; frames > 0: a zoom
 * sequence over levels levels. NP_EXIT_*.
 */
struct np_scene;
int np_render_hatch_scene(const struct np_scene *sc, const char *out, int ppm, int cycles, unsigned table,
                          unsigned frames, double levels, hash_list *hashes);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* NP_RENDER_TOOLS_H */
