/* SPDX-License-Identifier: MIT */
/*
 * The scene parser on arbitrary text, and every accepted scene of at most
 * 64 x 64 pixels through rendering: scan conversion, the float reference and
 * the texture units' bit-exact renders.
 */
#include <string.h>

#include "np_fuzz.h"
#include "np_render.h"
#include "np_scene.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size > 65536)
        return 0;
    char *json = malloc(size + 1);
    if (!json)
        return 0;
    memcpy(json, data, size);
    json[size] = '\0';
    np_scene sc;
    char err[512] = "";
    int rc = np_scene_parse(json, "fuzz.json", &sc, err, sizeof err);
    free(json);
    if (rc != 0) {
        np_fuzz_assert(err[0] != '\0');
        return 0;
    }
    if ((uint64_t)sc.width * sc.height <= 64u * 64u) {
        np_render_frame fr;
        if (np_render_prepare(&sc, &fr, err, sizeof err) == 0) {
            if (np_render_reference(&fr) == 0) {
                np_fdiff_cfg fc = np_fdiff_cfg_default();
                np_texel_cfg tc = np_texel_cfg_default();
                np_render_run run;
                if (np_render_fdiff(&fr, &fc, 1, &run) == 0) {
                    np_fuzz_assert(run.cycle_mismatch == 0);
                    np_render_run_free(&run);
                }
                if (np_render_texel(&fr, &tc, 1, &run) == 0) {
                    np_fuzz_assert(run.cycle_mismatch == 0);
                    np_render_run_free(&run);
                }
            }
            np_render_frame_free(&fr);
        }
    }
    np_scene_free(&sc);
    return 0;
}
