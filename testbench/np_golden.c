/* SPDX-License-Identifier: MIT */
/* The checked-in scenes and golden image hashes (np_golden.h). */
#include "np_golden.h"

#include <stdio.h>
#include <string.h>

#include "np_test.h"

void np_golden_scene_path(const char *dir, const char *name, char *buf, size_t n)
{
    snprintf(buf, n, "%s/vectors/scenes/%s.json", dir, name);
}

int np_golden_scene_load(const char *dir, const char *name, np_scene *s)
{
    char path[1024], err[1024];
    np_golden_scene_path(dir, name, path, sizeof path);
    if (np_scene_load(path, s, err, sizeof err)) {
        NP_CHECK(0, "%s", err);
        return -1;
    }
    return 0;
}

int np_golden_hash(const char *dir, const char *file, const char *scene, const char *image, char hex[65])
{
    char path[1024], line[1024];
    snprintf(path, sizeof path, "%s/vectors/images/%s", dir, file);
    FILE *f = fopen(path, "r");
    if (!f)
        return -1;
    int found = 0;
    while (fgets(line, sizeof line, f)) {
        char sc[64], im[16], h[65];
        if (line[0] != '#' && sscanf(line, "%63s %15s %64s", sc, im, h) == 3 && strcmp(sc, scene) == 0 &&
            strcmp(im, image) == 0) {
            memcpy(hex, h, 65);
            found = 1;
        }
    }
    fclose(f);
    return found ? 0 : -2;
}
