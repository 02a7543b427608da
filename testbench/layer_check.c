/* SPDX-License-Identifier: MIT */
/*
 * layer_check.c - the layer check (ctest -R layers): every #include "..." under
 * rtl_model/ and src/ against the layer order that docs/architecture.md states.
 *
 *   layer_check ROOT [DOC]      (DOC default ROOT/docs/architecture.md)
 *
 * The document holds three tables between HTML comments the check looks for:
 *   <!-- layer-order --> ... <!-- /layer-order -->        | level | folders |
 *   <!-- layer-rules --> ... <!-- /layer-rules -->        | folder | may not include from | except |
 *   <!-- layer-exceptions --> ... <!-- /layer-exceptions --> | file | includes | why |
 * A file may include a header of its own folder or of a folder at a lower level;
 * anything else (up, or sideways at the same level) fails, as does an include the
 * rules forbid, unless the exceptions list it. An exception that no longer matches
 * an include fails too (the list only shrinks), and so does an include circle
 * between files. Each failure names the file and line. Exit 0 clean, 1 on a failure,
 * 2 when the tree or the document cannot be read.
 */
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

enum { MAX_FILES = 2048, MAX_INC = 64, MAX_FOLDERS = 32, MAX_RULES = 16, MAX_EXC = 128 };

typedef struct file {
    char path[512];   /* relative to ROOT */
    char name[128];   /* basename */
    char folder[64];  /* "units", "rtl_model" */
    unsigned n_inc;
    struct { char name[128]; unsigned line; int to; } inc[MAX_INC]; /* to: file index or -1 */
    int color;        /* cycle search */
} file;

static file *g_files;
static unsigned g_n;
static struct { char name[64]; int level; } g_folders[MAX_FOLDERS];
static unsigned g_nf;
static struct { char folder[64], from[64], except[256]; } g_rules[MAX_RULES];
static unsigned g_nr;
static struct { char file[512], inc[128]; int used; unsigned line; } g_exc[MAX_EXC];
static unsigned g_ne;
static unsigned g_fail;

static int level_of(const char *folder)
{
    for (unsigned i = 0; i < g_nf; i++)
        if (strcmp(g_folders[i].name, folder) == 0)
            return g_folders[i].level;
    return -1;
}

static int is_source(const char *n)
{
    const char *d = strrchr(n, '.');
    return d && (!strcmp(d, ".c") || !strcmp(d, ".h") || !strcmp(d, ".cpp") || !strcmp(d, ".inc"));
}

static int walk(const char *root, const char *rel)
{
    char dir[1024];
    snprintf(dir, sizeof dir, "%s/%s", root, rel);
    DIR *d = opendir(dir);
    if (!d)
        return -1;
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        if (e->d_name[0] == '.')
            continue;
        char r[1024], full[2048];
        snprintf(r, sizeof r, "%s/%s", rel, e->d_name);
        snprintf(full, sizeof full, "%s/%s", root, r);
        struct stat st;
        if (stat(full, &st) != 0)
            continue;
        if (S_ISDIR(st.st_mode)) {
            if (walk(root, r) != 0) {
                closedir(d);
                return -1;
            }
        } else if (is_source(e->d_name)) {
            if (g_n == MAX_FILES) {
                fprintf(stderr, "layer_check: more than %d files\n", MAX_FILES);
                closedir(d);
                return -1;
            }
            file *f = &g_files[g_n++];
            snprintf(f->path, sizeof f->path, "%s", r);
            snprintf(f->name, sizeof f->name, "%s", e->d_name);
            if (strncmp(r, "src/", 4) == 0) {
                const char *s = r + 4, *slash = strchr(s, '/');
                size_t n = slash ? (size_t)(slash - s) : 0;
                snprintf(f->folder, sizeof f->folder, "%.*s", (int)n, s);
            } else {
                snprintf(f->folder, sizeof f->folder, "rtl_model");
            }
        }
    }
    closedir(d);
    return 0;
}

/* The cells of a Markdown table row "| a | b | c |" into cell[] (trimmed, backticks dropped). */
static unsigned cells(char *line, char cell[][256], unsigned max)
{
    unsigned n = 0;
    char *p = strchr(line, '|');
    while (p && n < max) {
        char *q = strchr(p + 1, '|');
        if (!q)
            break;
        char buf[256];
        size_t k = 0;
        for (char *c = p + 1; c < q && k + 1 < sizeof buf; c++)
            if (*c != '`')
                buf[k++] = *c;
        buf[k] = '\0';
        char *b = buf;
        while (*b == ' ')
            b++;
        size_t l = strlen(b);
        while (l && (b[l - 1] == ' ' || b[l - 1] == '\n'))
            b[--l] = '\0';
        snprintf(cell[n++], 256, "%s", b);
        p = q;
    }
    return n;
}

static int read_doc(const char *path)
{
    FILE *f = fopen(path, "r");
    if (!f) {
        fprintf(stderr, "layer_check: cannot read %s\n", path);
        return -1;
    }
    char line[1024], cell[4][256];
    int section = 0; /* 1 order, 2 rules, 3 exceptions */
    unsigned ln = 0;
    while (fgets(line, sizeof line, f)) {
        ln++;
        if (strstr(line, "<!-- layer-order -->"))
            section = 1;
        else if (strstr(line, "<!-- layer-rules -->"))
            section = 2;
        else if (strstr(line, "<!-- layer-exceptions -->"))
            section = 3;
        else if (strstr(line, "<!-- /layer-"))
            section = 0;
        else if (section && line[0] == '|' && !strstr(line, "---")) {
            unsigned n = cells(line, cell, 4);
            if (section == 1 && n >= 2 && cell[0][0] >= '0' && cell[0][0] <= '9') {
                int lv = atoi(cell[0]);
                for (char *tok = strtok(cell[1], ", "); tok; tok = strtok(NULL, ", "))
                    if (g_nf < MAX_FOLDERS) {
                        snprintf(g_folders[g_nf].name, sizeof g_folders[g_nf].name, "%s", tok);
                        g_folders[g_nf++].level = lv;
                    }
            } else if (section == 2 && n >= 3 && strcmp(cell[0], "folder") != 0 && g_nr < MAX_RULES) {
                snprintf(g_rules[g_nr].folder, sizeof g_rules[g_nr].folder, "%s", cell[0]);
                snprintf(g_rules[g_nr].from, sizeof g_rules[g_nr].from, "%s", cell[1]);
                snprintf(g_rules[g_nr].except, sizeof g_rules[g_nr].except, "%s", cell[2]);
                g_nr++;
            } else if (section == 3 && n >= 2 && strcmp(cell[0], "file") != 0 && g_ne < MAX_EXC) {
                snprintf(g_exc[g_ne].file, sizeof g_exc[g_ne].file, "%s", cell[0]);
                snprintf(g_exc[g_ne].inc, sizeof g_exc[g_ne].inc, "%s", cell[1]);
                g_exc[g_ne++].line = ln;
            }
        }
    }
    fclose(f);
    if (g_nf == 0) {
        fprintf(stderr, "layer_check: %s: no <!-- layer-order --> table\n", path);
        return -1;
    }
    return 0;
}

static int read_includes(const char *root, file *f)
{
    char full[2048], line[1024];
    snprintf(full, sizeof full, "%s/%s", root, f->path);
    FILE *in = fopen(full, "r");
    if (!in)
        return -1;
    unsigned ln = 0;
    while (fgets(line, sizeof line, in)) {
        ln++;
        const char *p = line;
        while (*p == ' ' || *p == '\t')
            p++;
        if (*p != '#')
            continue;
        p++;
        while (*p == ' ' || *p == '\t')
            p++;
        if (strncmp(p, "include", 7) != 0)
            continue;
        p += 7;
        while (*p == ' ' || *p == '\t')
            p++;
        if (*p != '"')
            continue;
        const char *q = strchr(p + 1, '"');
        if (!q || f->n_inc == MAX_INC)
            continue;
        const char *base = p + 1;
        for (const char *c = p + 1; c < q; c++)
            if (*c == '/')
                base = c + 1;
        snprintf(f->inc[f->n_inc].name, sizeof f->inc[f->n_inc].name, "%.*s", (int)(q - base), base);
        f->inc[f->n_inc].line = ln;
        f->inc[f->n_inc].to = -1;
        f->n_inc++;
    }
    fclose(in);
    return 0;
}

/* The file an include names: of the includer's folder first, else the only one of that name. */
static int resolve(const file *from, const char *name)
{
    int any = -1;
    for (unsigned i = 0; i < g_n; i++)
        if (strcmp(g_files[i].name, name) == 0) {
            if (strcmp(g_files[i].folder, from->folder) == 0)
                return (int)i;
            any = (int)i;
        }
    return any;
}

static int listed(const file *f, const char *inc)
{
    for (unsigned i = 0; i < g_ne; i++)
        if (strcmp(g_exc[i].file, f->path) == 0 && strcmp(g_exc[i].inc, inc) == 0) {
            g_exc[i].used = 1;
            return 1;
        }
    return 0;
}

static int in_list(const char *list, const char *name)
{
    char buf[256];
    snprintf(buf, sizeof buf, "%s", list);
    for (char *tok = strtok(buf, ", "); tok; tok = strtok(NULL, ", "))
        if (strcmp(tok, name) == 0)
            return 1;
    return 0;
}

/* Depth-first search for an include circle; stack holds the path. */
static int stack[MAX_FILES];
static unsigned g_circles;
static void dfs(int v, unsigned depth)
{
    g_files[v].color = 1;
    stack[depth] = v;
    for (unsigned k = 0; k < g_files[v].n_inc; k++) {
        int w = g_files[v].inc[k].to;
        if (w < 0)
            continue;
        if (g_files[w].color == 1) {
            fprintf(stderr, "%s:%u: include circle:", g_files[v].path, g_files[v].inc[k].line);
            unsigned s = 0;
            while (stack[s] != w)
                s++;
            for (; s <= depth; s++)
                fprintf(stderr, " %s ->", g_files[stack[s]].name);
            fprintf(stderr, " %s\n", g_files[w].name);
            g_circles++;
        } else if (g_files[w].color == 0) {
            dfs(w, depth + 1);
        }
    }
    g_files[v].color = 2;
}

int main(int argc, char **argv)
{
    if (argc < 2 || argc > 3) {
        fprintf(stderr, "usage: layer_check ROOT [DOC]\n");
        return 2;
    }
    const char *root = argv[1];
    char doc[1024];
    snprintf(doc, sizeof doc, "%s/docs/architecture.md", root);
    g_files = calloc(MAX_FILES, sizeof *g_files);
    if (!g_files || read_doc(argc == 3 ? argv[2] : doc) != 0)
        return 2;
    if (walk(root, "src") != 0 || walk(root, "rtl_model") != 0) {
        fprintf(stderr, "layer_check: cannot read %s/src and %s/rtl_model\n", root, root);
        return 2;
    }
    for (unsigned i = 0; i < g_n; i++) {
        if (level_of(g_files[i].folder) < 0) {
            fprintf(stderr, "%s: folder %s has no level in the layer order (%s)\n", g_files[i].path, g_files[i].folder,
                    argc == 3 ? argv[2] : doc);
            g_fail++;
        }
        if (read_includes(root, &g_files[i]) != 0) {
            fprintf(stderr, "layer_check: cannot read %s\n", g_files[i].path);
            return 2;
        }
    }
    unsigned across = 0, excused = 0;
    for (unsigned i = 0; i < g_n; i++) {
        file *f = &g_files[i];
        int lf = level_of(f->folder);
        for (unsigned k = 0; k < f->n_inc; k++) {
            int t = resolve(f, f->inc[k].name);
            f->inc[k].to = t;
            if (t < 0 || lf < 0)
                continue; /* a system or generated header */
            const file *h = &g_files[t];
            int lt = level_of(h->folder);
            const char *why = NULL;
            if (strcmp(h->folder, f->folder) != 0) {
                across++;
                if (lt > lf)
                    why = "goes up";
                else if (lt == lf)
                    why = "goes sideways";
                for (unsigned r = 0; r < g_nr && !why; r++)
                    if (strcmp(g_rules[r].folder, f->folder) == 0 && strcmp(g_rules[r].from, h->folder) == 0 &&
                        !in_list(g_rules[r].except, h->name))
                        why = "is forbidden by the layer rules";
            }
            if (!why)
                continue;
            if (listed(f, h->name)) {
                excused++;
                continue;
            }
            fprintf(stderr, "%s:%u: #include \"%s\" (%s, level %d) from %s (level %d) %s\n", f->path, f->inc[k].line,
                    f->inc[k].name, h->folder, lt, f->folder, lf, why);
            g_fail++;
        }
    }
    for (unsigned i = 0; i < g_ne; i++)
        if (!g_exc[i].used) {
            fprintf(stderr, "%s:%u: the exception %s -> %s matches no forbidden include any more: remove it\n",
                    argc == 3 ? argv[2] : doc, g_exc[i].line, g_exc[i].file, g_exc[i].inc);
            g_fail++;
        }
    for (unsigned i = 0; i < g_n; i++)
        if (g_files[i].color == 0)
            dfs((int)i, 0);
    g_fail += g_circles;
    printf("layer check: %u files, %u includes between folders, %u known exceptions (listed in docs/architecture.md), "
           "%u include circles, %u failures\n", g_n, across, excused, g_circles, g_fail);
    free(g_files);
    return g_fail ? 1 : 0;
}
