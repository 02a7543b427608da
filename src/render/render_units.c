/* SPDX-License-Identifier: MIT */
/* The units that render a scene: the registry's span units whose cfg_scene accepts it (np_render.h). */
#include "np_render.h"

#include <stdio.h>
#include <string.h>

/* u's configuration as "key=value,..." without the texture (the texture is the scene's). */
static void cfg_text(const np_unit *u, const void *cfg, char *buf, size_t len)
{
    char all[512];
    u->cfg_format(cfg, all, sizeof all);
    size_t n = 0;
    buf[0] = '\0';
    for (char *save = NULL, *tok = strtok_r(all, " ", &save); tok && n < len; tok = strtok_r(NULL, " ", &save)) {
        if (strncmp(tok, "texture=", 8) == 0)
            continue;
        int w = snprintf(buf + n, len - n, "%s%s", n ? "," : "", tok);
        if (w < 0)
            break;
        n += (size_t)w;
    }
}

int np_render_units(const np_scene *sc, const char *(*spec)(const void *ctx, const np_unit *u), const void *ctx,
                    np_render_unit_cfg *us, char *err, size_t errlen)
{
    int n = 0;
    for (size_t i = 0; np_units[i]; i++) {
        const np_unit *u = np_units[i];
        if (!u->span || !u->cfg_scene)
            continue;
        if (n == NP_RENDER_MAX_UNITS) {
            snprintf(err, errlen, "more than %d units render scene %s", NP_RENDER_MAX_UNITS, sc->name);
            return -1;
        }
        np_render_unit_cfg *c = &us[n];
        memset(c, 0, sizeof *c);
        c->u = u;
        char why[512];
        int rc = u->cfg_scene(&c->cfg, sc, why, sizeof why);
        if (rc < 0) {
            snprintf(err, errlen, "%s: %s", u->name, why);
            return -1;
        }
        if (rc == 0)
            continue;
        if (np_unit_configure_over(u, &c->cfg, spec ? spec(ctx, u) : NULL, why, sizeof why) != 0) {
            snprintf(err, errlen, "%s configuration: %s", u->name, why);
            return -1;
        }
        cfg_text(u, &c->cfg, c->text, sizeof c->text);
        n++;
    }
    return n;
}
