/* SPDX-License-Identifier: MIT */
/* np_wave_json.h - reading a wave scene file (src/wave/wave_json.c; in np_render, which has cJSON). */
#ifndef NP_WAVE_JSON_H
#define NP_WAVE_JSON_H

#include "np_wave_host.h"
#include "np_wave_scene.h"

#ifdef __cplusplus
extern "C" {
#endif

/*
 * Read path into s (np_wave_scene_init first, then the file's fields); the
 * `frames` section into frames[3] = { count, first, step } when frames is not
 * NULL (left as they are when absent). 0, or -1 with "FILE: FIELD: message".
 */
int np_wave_scene_read(const char *path, np_wave_scene *s, unsigned *frames, char *err, size_t errlen);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* NP_WAVE_JSON_H */
