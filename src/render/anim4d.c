/* SPDX-License-Identifier: MIT */
/*
 * A time-varying solid texture through 4-D noise (Perlin, "Noise Hardware":
 * "Noise over R^4 is also very useful for time-varying solid textures"):
 * a lit sphere whose surface point p reads simplex4's bit-exact model (through
 * the registry, at its defaults: f is s16) at (p, t), t advancing 1/16 lattice unit per frame, rendered as a short PNG
 * frame sequence (`noisepipe report anim4d`). Not a scene of the scene
 * pipeline: a stand-alone view of the unit, for looking at.
 */
#include "np_anim4d.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "np_image.h"
#include "np_unit.h"

enum { SIZE = 192, T_STEP = 16 }; /* pixels; Q8.8 steps of t per frame (1/16 unit) */

/* A real coordinate to the unit's u16 Q8.8 word (round half up; the scene stays inside [0, 256)). */
static uint16_t q88(double v) { return (uint16_t)floor(v * 256.0 + 0.5); }

static uint8_t byte_of(double v)
{
    double c = v < 0.0 ? 0.0 : v > 1.0 ? 1.0 : v;
    return (uint8_t)floor(c * 255.0 + 0.5);
}

int np_anim4d_frames(const char *dir, unsigned frames, char *err, size_t errlen)
{
    const np_unit *u = np_unit_find("simplex4");
    np_unit_cfg cfg;
    np_unit_fields fl;
    if (!u) {
        snprintf(err, errlen, "no unit simplex4 in the registry");
        return -1;
    }
    if (np_unit_configure(u, &cfg, NULL, err, errlen) != 0)
        return -1;
    u->fields(&cfg, &fl);
    uint8_t *rgb = malloc((size_t)SIZE * SIZE * 3u);
    if (!rgb) {
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    const double lx = -0.4, ly = 0.5, lz = 0.768; /* light direction (about unit length) */
    for (unsigned fr = 0; fr < frames; fr++) {
        for (unsigned py = 0; py < SIZE; py++)
            for (unsigned px = 0; px < SIZE; px++) {
                double sx = (2.0 * px + 1.0) / SIZE - 1.0, sy = 1.0 - (2.0 * py + 1.0) / SIZE;
                double r2 = sx * sx + sy * sy, col[3] = { 0.12, 0.12, 0.14 };
                if (r2 <= 1.0) {
                    double sz = sqrt(1.0 - r2), lam = sx * lx + sy * ly + sz * lz;
                    const uint64_t x[4] = { q88(8.0 + 3.0 * sx), q88(8.0 + 3.0 * sy), q88(8.0 + 3.0 * sz),
                                            (uint16_t)(0x0400u + fr * T_STEP) };
                    uint64_t w[NP_UNIT_MAX_FIELDS];
                    u->eval(&cfg, x, w);
                    double f = np_unit_field_value(&fl.out[0], w[0]);
                    double v = 0.5 + 5.0 * f, shade = 0.25 + 0.75 * (lam > 0.0 ? lam : 0.0);
                    col[0] = shade * (0.2 + 0.8 * v);
                    col[1] = shade * (0.1 + 0.7 * v * v);
                    col[2] = shade * (0.05 + 0.3 * v * v * v);
                }
                for (unsigned c = 0; c < 3; c++)
                    rgb[((size_t)py * SIZE + px) * 3u + c] = byte_of(col[c]);
            }
        char path[4096];
        snprintf(path, sizeof path, "%s/anim4d-%02u.png", dir, fr);
        if (np_image_write_png(path, SIZE, SIZE, rgb, err, errlen) != 0) {
            free(rgb);
            return -1;
        }
    }
    free(rgb);
    return 0;
}
