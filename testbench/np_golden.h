/* SPDX-License-Identifier: MIT */
/*
 * np_golden.h - the checked-in scenes (vectors/scenes/NAME.json) and golden
 * image hashes (vectors/images/FILE: lines "scene image sha256
 * [configuration]", '#' comments), read by the render, G-buffer, hatching
 * and adaptive-sampling tests.
 */
#ifndef NP_GOLDEN_H
#define NP_GOLDEN_H

#include <stddef.h>

#include "np_scene.h"

/* DIR/vectors/scenes/NAME.json into buf. */
void np_golden_scene_path(const char *dir, const char *name, char *buf, size_t n);

/* Load the checked-in scene NAME into s: 0; -1 (a failed check naming the error) when it cannot be loaded. */
int np_golden_scene_load(const char *dir, const char *name, np_scene *s);

/*
 * The hash of `image` of `scene` in DIR/vectors/images/FILE (DIR the source
 * tree, NP_SOURCE_DIR) into hex (64 hex digits and a NUL; the last matching
 * line wins). 0; -1 when the file cannot be opened; -2 when no line matches.
 */
int np_golden_hash(const char *dir, const char *file, const char *scene, const char *image, char hex[65]);

#endif /* NP_GOLDEN_H */
