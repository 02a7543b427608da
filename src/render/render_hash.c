/* SPDX-License-Identifier: MIT */
/* noisepipe render: the golden-image hash lists (vectors/images/hashes.txt; render_cli.h). */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "np_common.h"
#include "np_outfile.h"
#include "np_render_tools.h"

int np_render_hash_add(hash_list *l, const char *scene, const char *image, const char *hash, const char *cfg)
{
    if (l->n == l->cap) {
        size_t nc = l->cap ? 2 * l->cap : 16;
        hash_rec *nr = realloc(l->r, nc * sizeof *nr);
        if (!nr)
            return -1;
        l->r = nr;
        l->cap = nc;
    }
    hash_rec *h = &l->r[l->n++];
    snprintf(h->scene, sizeof h->scene, "%s", scene);
    snprintf(h->image, sizeof h->image, "%s", image);
    snprintf(h->hash, sizeof h->hash, "%s", hash);
    snprintf(h->cfg, sizeof h->cfg, "%s", cfg);
    return 0;
}

/* Lines "scene image sha256 configuration"; '#' comments. 0, or -1 with a message. */
int np_render_hash_read(const char *path, hash_list *l)
{
    FILE *f = fopen(path, "r");
    if (!f) {
        np_err("render", "%s: cannot open: %s", path, strerror(errno));
        return -1;
    }
    char line[1024];
    unsigned no = 0;
    while (fgets(line, sizeof line, f)) {
        no++;
        char *p = line;
        while (*p == ' ' || *p == '\t')
            p++;
        if (*p == '#' || *p == '\n' || *p == '\0')
            continue;
        char sc[64], im[16], h[65], cfg[256];
        if (sscanf(p, "%63s %15s %64s %255s", sc, im, h, cfg) != 4 || strlen(h) != 64) {
            np_err("render", "%s:%u: expected 'scene image sha256 configuration'", path, no);
            fclose(f);
            return -1;
        }
        if (np_render_hash_add(l, sc, im, h, cfg)) {
            fclose(f);
            return -1;
        }
    }
    fclose(f);
    return 0;
}

int np_render_hash_write(const char *path, const hash_list *l)
{
    np_outfile o;
    if (np_outfile_open(&o, path, "w") != 0) {
        np_err("render", "%s", o.err);
        return -1;
    }
    FILE *f = o.f;
    fputs("# noisepipe golden images: SHA-256 of each image as a binary PPM (np_image_hash;\n"
          "# `noisepipe render --ppm` writes the PPM files, `sha256sum` of them gives these).\n"
          "# Written by `noisepipe render --write-hashes`; checked by `noisepipe render --hashes`\n"
          "# and by the test render.golden_hashes. A change to any bit of an image shows here.\n"
          "# scene image sha256 configuration\n",
          f);
    for (size_t i = 0; i < l->n; i++)
        fprintf(f, "%s %s %s %s\n", l->r[i].scene, l->r[i].image, l->r[i].hash, l->r[i].cfg);
    if (np_outfile_close(&o, 1) != 0) {
        np_err("render", "%s", o.err);
        return -1;
    }
    return 0;
}

/* Compare got with the golden list; prints each difference. Returns the number of failures. */
unsigned np_render_hash_check(const hash_list *golden, const hash_list *got, const char *path)
{
    unsigned bad = 0;
    for (size_t i = 0; i < got->n; i++) {
        const hash_rec *g = &got->r[i], *w = NULL;
        for (size_t k = 0; k < golden->n; k++)
            if (strcmp(golden->r[k].scene, g->scene) == 0 && strcmp(golden->r[k].image, g->image) == 0)
                w = &golden->r[k];
        if (!w) {
            printf("hash: %s %s: no golden hash in %s\n", g->scene, g->image, path);
            bad++;
        } else if (strcmp(w->cfg, g->cfg) != 0) {
            printf("hash: %s %s: configuration %s differs from the golden one %s\n", g->scene, g->image, g->cfg,
                   w->cfg);
            bad++;
        } else if (strcmp(w->hash, g->hash) != 0) {
            printf("hash: %s %s: CHANGED: %s, golden %s\n", g->scene, g->image, g->hash, w->hash);
            bad++;
        } else {
            printf("hash: %s %s: matches %s\n", g->scene, g->image, path);
        }
    }
    return bad;
}

