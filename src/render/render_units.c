/* SPDX-License-Identifier: MIT */
/* The units that render a scene: the registry's span units whose cfg_scene accepts it (np_render.h). */
#include "np_render.h"

#include <stdio.h>
#include <string.h>

/* Does the "key=value,..." list kv set key (len characters)? */
static int sets(const char *kv, const char *key, size_t len)
{
    for (const char *p = kv; p && *p; p += strcspn(p, ","), p += *p == ',')
        if (strcspn(p, "=") == len && strncmp(p, key, len) == 0)
            return 1;
    return 0;
}

int np_render_unit_reconfigure(np_render_unit_cfg *c, const char *more, char *err, size_t errlen)
{
    const np_unit *u = c->u;
    char spec[sizeof c->spec + 256];
    size_t n = 0;
    spec[0] = '\0';
    /* c's keys, but those more sets (more wins), then more. */
    for (const char *p = c->spec; *p && n < sizeof spec; p += strcspn(p, ","), p += *p == ',') {
        size_t len = strcspn(p, ",");
        if (!sets(more, p, strcspn(p, "=")))
            n += (size_t)snprintf(spec + n, sizeof spec - n, "%s%.*s", n ? "," : "", (int)len, p);
    }
    if (more && *more && n < sizeof spec)
        snprintf(spec + n, sizeof spec - n, "%s%s", n ? "," : "", more);
    if (np_unit_configure(u, &c->cfg, spec, err, errlen) != 0)
        return -1;
    /* The keys the scene sets are the scene's. */
    for (const np_unit_key *k = u->keys; k && k->name; k++)
        if (k->flags & NP_UNIT_KEY_SCENE)
            memcpy(c->cfg.bytes + k->offset, c->scene.bytes + k->offset, k->size);
    np_unit_cfg_format_opt(u, &c->cfg, NP_UNIT_FMT_COMMAS | NP_UNIT_FMT_NO_SCENE, c->text, sizeof c->text);
    return 0;
}

int np_render_units(const np_scene *sc, const char *(*spec)(const void *ctx, const np_unit *u), const void *ctx,
                    np_render_unit_cfg *us, char *err, size_t errlen)
{
    int n = 0;
    const np_unit *u;
    for (size_t i = 0; (u = np_unit_at(i)) != NULL; i++) {
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
        int rc = np_scene_cfg_unit(u, &c->scene, sc, why, sizeof why);
        if (rc < 0) {
            snprintf(err, errlen, "%s: %s", u->name, why);
            return -1;
        }
        if (rc == 0)
            continue;
        const char *s = spec ? spec(ctx, u) : NULL;
        if (s && strlen(s) >= sizeof c->spec) {
            snprintf(err, errlen, "%s configuration too long", u->name);
            return -1;
        }
        snprintf(c->spec, sizeof c->spec, "%s", s ? s : "");
        /*
         * Registers sized by the scene (np_scene.size_registers): the index
         * and guard bits cfg_scene chose, unless the spec gives them.
         */
        static const char *const sized_keys[] = { "idx_int", "guard" };
        for (unsigned j = 0; sc->size_registers && j < sizeof sized_keys / sizeof sized_keys[0]; j++)
            for (const np_unit_key *k = u->keys; k && k->name; k++)
                if (strcmp(k->name, sized_keys[j]) == 0 && k->size == sizeof(unsigned) &&
                    !sets(c->spec, k->name, strlen(k->name))) {
                    unsigned v;
                    memcpy(&v, c->scene.bytes + k->offset, sizeof v);
                    size_t n0 = strlen(c->spec);
                    snprintf(c->spec + n0, sizeof c->spec - n0, "%s%s=%u", n0 ? "," : "", k->name, v);
                }
        if (np_render_unit_reconfigure(c, NULL, why, sizeof why) != 0) {
            snprintf(err, errlen, "%s configuration: %s", u->name, why);
            return -1;
        }
        n++;
    }
    return n;
}
