/* SPDX-License-Identifier: MIT */
/*
 * report_synth.c - `noisepipe report gates --synth`: Yosys + ABC on the
 * reference RTL, NAND2 equivalents per pipeline stage, beside the cost model.
 *
 * Flow (the one the cost model's constants were measured with, so that both
 * columns count the same cells; docs/cost-model.md):
 *   read_verilog; chparam (every configuration key, upper case, is a parameter);
 *   synth -top T -flatten; dfflegalize -cell $_DFF_P_ 01 (enables and resets
 *   become logic in front of a plain flip-flop); abc -g NAND -script F;
 *   opt_clean; stat -tech cmos, where F is ABC's default script for a gate
 *   library (Yosys 0.23's abc pass) with the SAT sweep bounded:
 *   `&fraig -x -C 1000` instead of `&fraig -x` (1,000,000 conflicts a node),
 *   which ran for over 10 CPU minutes on simplex3's KT (three squarers of
 *   conditionally negated words) without finishing. NP_SYNTH_ABC_FULL keeps
 *   the unbounded default script (docs/cost-model.md, "Flow").
 * Weights: Yosys 0.23's CMOS transistor counts (`stat -tech cmos`, kernel/cost.h:
 * $_NAND_ 4, $_NOT_ 2, $_DFF_P_ 16), divided by 4 (one NAND2 = 4 transistors):
 * NAND2 1, NOT 0.5, D flip-flop 4.
 *
 * Per stage: the stage whose results bank k holds (registers named rK_* in the
 * RTL) is the input cone of bank k's flip-flops, stopping at other flip-flops'
 * outputs (`select w:*rK_* %ci1 %ci*:-$_DFF_P_[Q]`). Cells in exactly one
 * bank's cone are that stage's; the rest (the valid bits and their handshake,
 * whose enables fan out to every bank, the pipe options, and any cell two cones
 * share) are reported as "shared".
 */
#include <ctype.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "np_aacount.h"
#include "np_hatch.h"
#include "np_common.h"
#include "np_outfile.h"
#include "np_synth.h"
#include "np_wave.h"

#ifndef NP_RTL_DIR
#define NP_RTL_DIR "rtl_model/verilog"
#endif

const char *np_synth_default_rtl_dir(void)
{
    return NP_RTL_DIR;
}

/*
 * The RTL parameters of a unit that do not come from its keys one for one:
 * `chparam` arguments (" -set NAME V") for buf; -1 with a message in err
 * when the configuration has no RTL.
 */
typedef int (*rtl_params_fn)(const void *cfg, char *buf, size_t len, char *err, size_t errlen);

/*
 * A unit's RTL: top module, files, the register prefix of each stage's bank
 * (its registers are named <prefix>_*), or, for an RTL whose banks are not
 * named so, bank_sel: the Yosys selection of bank k's registers (of the
 * model's n_stages); the keys that are no RTL parameter (NULL-terminated), the
 * parameters derived from the configuration block, the banks' valid bits.
 * by_name: synthesised only when --unit names the unit (the n-D units, wave
 * and aacount: a run over every unit, and report fpga, keep classic3 and
 * simplex3, whose syntheses the docs and tests time; aacount alone takes 30 min).
 */
enum { RTL_FILES = 8 }; /* a unit's RTL files at the most, NULL-terminated when fewer */

typedef struct rtl_desc {
    const char *unit, *top;
    const char *files[RTL_FILES];
    struct { const char *stage, *prefix; } bank[12];
    const char *not_params[4];
    rtl_params_fn params;
    const char *valid; /* the banks' valid bits (NULL: "v") */
    void (*bank_sel)(unsigned k, unsigned n_stages, char *buf, size_t len);
    int by_name;
} rtl_desc;

/*
 * wave: the block starts with its np_wave_unit (unit_wave.c: "first: the
 * pipe's cfg is the block"). MLOG2 from the register set, and the widths of
 * the register-dependent signals at the declaration's (np_wave_datapath_widths:
 * the RTL's defaults hold every accepted register set, the declaration those
 * of the test set the report prices). sincos=recurrence has no RTL.
 */
static int wave_params(const void *cfg, char *buf, size_t len, char *err, size_t errlen)
{
    const np_wave_unit *u = cfg;
    if (u->c.sincos != NP_WAVE_SINCOS_ROM) {
        snprintf(err, errlen, "sincos=recurrence has no reference RTL (docs/wave.md, \"Reference RTL\")");
        return -1;
    }
    np_wave_dp_widths w;
    np_wave_datapath_widths(u, &w);
    int k = snprintf(buf, len, " -set MLOG2 %u -set W_AP %u -set W_YC %u -set W_SA %u -set W_XP %u -set W_YS %u"
                     " -set W_XS %u -set W_GM %u", (unsigned)u->r.mlog2, w.ap, w.yc, w.sa, w.xp, w.ys, w.xs, w.gm);
    if (k > 0 && (size_t)k < len && u->c.cap)
        k += snprintf(buf + k, len - (size_t)k, " -set W_BC %u", w.bc);
    if (k > 0 && (size_t)k < len && np_wave_has_jac(&u->c))
        k += snprintf(buf + k, len - (size_t)k, " -set W_LJ %u -set W_JS %u -set W_J %u", w.lj, w.js, w.j);
    if (k > 0 && (size_t)k < len && u->c.normals)
        k += snprintf(buf + k, len - (size_t)k, " -set W_LY %u", w.ly);
    if (k < 0 || (size_t)k >= len) {
        snprintf(err, errlen, "wave: parameter list too long");
        return -1;
    }
    return 0;
}

/* aacount: the parallel variant only (np_aacount.v); tile runs after the unit. */
static int aacount_params(const void *cfg, char *buf, size_t len, char *err, size_t errlen)
{
    const np_aacount_cfg *c = cfg;
    if (c->serial) {
        snprintf(err, errlen, "serial=1 has no reference RTL (np_aacount.v is the parallel variant)");
        return -1;
    }
    if (len)
        buf[0] = '\0';
    return 0;
}

/*
 * np_classicn.v's banks (2n + 3 of them: L, H, I1m, I1a, ..., Inm, Ina, O):
 * L r0_*, H r1_*, level l's multiply g_lvl[l].ra and .rp, its add
 * g_lvl[l].rl, O ro_f; and the s-curve of axis a carried in banks 1 .. 1 + 2a
 * as g_s[a].q[k], which the datapath declaration counts in bank k ('?' stands
 * for the brackets in Yosys's patterns).
 */
static void classicn_bank_sel(unsigned k, unsigned n_stages, char *buf, size_t len)
{
    if (k == 0)
        snprintf(buf, len, "w:*r0_*");
    else if (k + 1 == n_stages)
        snprintf(buf, len, "w:ro_f");
    else if (k == 1)
        snprintf(buf, len, "w:*r1_* w:g_s?*?.q?1? %%u");
    else if (k % 2 == 0) /* level (k - 2) / 2's multiply */
        snprintf(buf, len, "w:g_lvl?%u?.ra w:g_lvl?%u?.rp %%u w:g_s?*?.q?%u? %%u", (k - 2) / 2, (k - 2) / 2, k);
    else
        snprintf(buf, len, "w:g_lvl?%u?.rl w:g_s?*?.q?%u? %%u", (k - 3) / 2, k);
}

/*
 * hatch: brute force only (np_hatch.v; the coverage unit, cover_slots, has no
 * RTL). Its banks are the declaration's two rows: A is `ra`; S, the G seed
 * stages declared as one row, is every seed stage's bank g_st[g].g_carry.r
 * and the output register rc_out ('?' for the brackets).
 */
static int hatch_params(const void *cfg, char *buf, size_t len, char *err, size_t errlen)
{
    const np_hatch_cfg *c = cfg;
    if (c->cover_slots) {
        snprintf(err, errlen, "the coverage unit (mode=coverage) has no reference RTL (docs/hatch.md, \"Reference RTL\")");
        return -1;
    }
    if (len)
        buf[0] = '\0';
    return 0;
}

static void hatch_bank_sel(unsigned k, unsigned n_stages, char *buf, size_t len)
{
    (void)n_stages;
    if (k == 0)
        snprintf(buf, len, "w:ra");
    else
        snprintf(buf, len, "w:g_st?*?.g_carry.r w:rc_out %%u");
}

/*
 * The pipe around every unit but classic3, simplexn and classicn: handshake and
 * options (np_pipe_ctrl.v, np_pipe_opts.v). classic3 and the n-D units place the
 * two options themselves.
 */
#define NP_PIPE_RTL "np_pipe_ctrl.v", "np_pipe_opts.v", "np_pipe_in_reg.v", "np_pipe_skid.v"

#define NP_SIMPLEXN_RTL(name)                                                                                 \
    { name, "np_simplexn", { "np_simplexn.v", "np_pipe_in_reg.v", "np_pipe_skid.v", NULL },                  \
      { { "SK", "r0" }, { "RK", "r1" }, { "CH", "r2" }, { "KT", "r3" }, { "P2", "r4" }, { "P4", "r5" },        \
        { "M", "r6" }, { "A", "r7" }, { "O", "r8" }, { NULL, NULL } }, { NULL }, NULL, NULL, NULL, 1 }
#define NP_CLASSICN_RTL(name)                                                                                 \
    { name, "np_classicn", { "np_classicn.v", "np_pipe_in_reg.v", "np_pipe_skid.v", NULL }, { { NULL, NULL } }, \
      { NULL }, NULL, NULL, classicn_bank_sel, 1 }

static const rtl_desc rtl_units[] = {
    { "classic3", "np_classic3", { "np_classic3.v", "np_pipe_in_reg.v", "np_pipe_skid.v", NULL },
      { { "L", "r0" }, { "H", "r1" }, { "I1m", "r2" }, { "I1a", "r3" }, { "I2m", "r4" }, { "I2a", "r5" },
        { "I3m", "r6" }, { "I3a", "r7" }, { "O", "r8" }, { NULL, NULL } }, { NULL }, NULL, NULL, NULL, 0 },
    /* simplex3 names its banks by the derivative datapath's numbering; without it there is no r7 (M2). */
    { "simplex3", "np_simplex3", { "np_simplex3.v", NP_PIPE_RTL, NULL },
      { { "SK", "r0" }, { "RK", "r1" }, { "CH", "r2" }, { "KT", "r3" }, { "P2", "r4" }, { "P4", "r5" },
        { "M", "r6" }, { "M2", "r7" }, { "A", "r8" }, { "O", "r9" }, { NULL, NULL } }, { NULL }, NULL, NULL, NULL, 0 },
    { "wave", "np_wave", { "np_wave.v", "np_wave_sin.v", "np_wave_rom.v", NP_PIPE_RTL, NULL },
      { { "P", "r0" }, { "S", "r1" }, { "A", "r2" }, { "M", "r3" }, { "T", "r4" }, { "G", "r5" }, { "N", "r6" },
        { NULL, NULL } },
      { "sincos", "reset", "regs", NULL }, wave_params, "bv", NULL, 1 },
    { "aacount", "np_aacount", { "np_aacount.v", NP_PIPE_RTL, NULL },
      { { "A", "ra" }, { "V", "rv" }, { "P", "rp" }, { "C", "rc" }, { NULL, NULL } },
      { "tile", NULL }, aacount_params, NULL, NULL, 1 },
    /* hatch: millions of gates at every registry configuration (docs/hatch.md, "Synthesis"). */
    { "hatch", "np_hatch", { "np_hatch.v", "np_hatch_seed.v", NP_PIPE_RTL, NULL },
      { { NULL, NULL } }, { NULL }, hatch_params, NULL, hatch_bank_sel, 1 },
    /* The n-D units (np_simplexn.v, np_classicn.v; every key, DIMS included, is a parameter). */
    NP_CLASSICN_RTL("classic2"), NP_CLASSICN_RTL("classic4"), NP_CLASSICN_RTL("classic5"),
    NP_SIMPLEXN_RTL("simplex2"), NP_SIMPLEXN_RTL("simplex4"), NP_SIMPLEXN_RTL("simplex5"),
    /* np_simplexn.v at DIMS = 3 (the unregistered unit simplexn3, report dims' 3-D simplex row). */
    NP_SIMPLEXN_RTL("simplexn3"),
};

static const rtl_desc *rtl_of(const np_unit *u)
{
    for (size_t i = 0; i < sizeof rtl_units / sizeof rtl_units[0]; i++)
        if (strcmp(rtl_units[i].unit, u->name) == 0)
            return &rtl_units[i];
    return NULL;
}

int np_synth_has_rtl(const np_unit *u)
{
    return rtl_of(u) != NULL;
}

int np_synth_in_default_set(const np_unit *u)
{
    const rtl_desc *d = rtl_of(u);
    return d != NULL && !d->by_name;
}

const np_unit *np_synth_unit_next(const np_unit *only, size_t *i)
{
    const np_unit *u;
    while ((u = np_unit_at((*i)++)) != NULL)
        if (only ? u == only : np_synth_in_default_set(u))
            return u;
    return NULL;
}

/*
 * ABC's script: Yosys 0.23's default for -g/-liberty without -constr (`yosys
 * -h abc`), its SAT sweep limited to 1,000 conflicts a node unless full.
 */
static const char abc_script_bounded[] = "strash; &get -n; &fraig -x -C 1000; &put; scorr; dc2; dretime; strash; "
                                         "&get -n; &dch -f; &nf; &put\n";

/* The abc command: with the bounded script (written to path) or Yosys's default. */
static void write_abc(FILE *f, int flags, const char *abc_path)
{
    if (flags & NP_SYNTH_ABC_FULL)
        fprintf(f, "abc -g NAND\n");
    else
        fprintf(f, "abc -g NAND -script %s\n", abc_path);
}

static const char *prefix_of(const rtl_desc *d, const char *stage)
{
    for (unsigned i = 0; i < 12 && d->bank[i].stage; i++)
        if (strcmp(d->bank[i].stage, stage) == 0)
            return d->bank[i].prefix;
    return NULL;
}

/*
 * --rtl-param: RTL parameters that are not configuration keys (the pipe options
 * and classic3's circuit variants, docs/rtl.md), as " -set NAME V" for chparam.
 * The cost model declares only the as-built circuit, so with any of them the
 * report prints Yosys's figures beside the as-built model, labelled as such.
 */
static const struct {
    const char *unit;
    const char *names[6];
} rtl_extra_params[] = {
    { "classic3", { "IN_REG", "OUT_SKID", "S_TABLE", "HASH_SERIAL", "LERP_SERIAL", NULL } },
    { "simplex3", { "IN_REG", "OUT_SKID", NULL } },
    { "wave", { "IN_REG", "OUT_SKID", NULL } },
    { "aacount", { "IN_REG", "OUT_SKID", NULL } },
    { "hatch", { "IN_REG", "OUT_SKID", NULL } },
};
static char g_rtl_params[256];      /* " -set S_TABLE 1 -set HASH_SERIAL 1" */
static char g_rtl_params_spec[256]; /* "S_TABLE=1 HASH_SERIAL=1", for the heading */

int np_synth_set_rtl_params(const np_unit *u, const char *spec, char *err, size_t errlen)
{
    g_rtl_params[0] = g_rtl_params_spec[0] = '\0';
    if (!spec)
        return 0;
    const char *const *names = NULL;
    for (size_t i = 0; i < sizeof rtl_extra_params / sizeof rtl_extra_params[0]; i++)
        if (u && strcmp(rtl_extra_params[i].unit, u->name) == 0)
            names = rtl_extra_params[i].names;
    if (!names) {
        snprintf(err, errlen, "--rtl-param needs --unit classic3, simplex3, wave, aacount or hatch");
        return -1;
    }
    size_t n = 0, m = 0;
    for (const char *p = spec; *p;) {
        char name[32];
        size_t k = 0;
        while (*p && *p != '=' && *p != ',' && k + 1 < sizeof name)
            name[k++] = (char)toupper((unsigned char)*p++);
        name[k] = '\0';
        int known = 0;
        for (unsigned j = 0; names[j]; j++)
            known |= strcmp(names[j], name) == 0;
        if (!known) {
            snprintf(err, errlen, "--rtl-param %s: '%s' is not an RTL parameter of %s outside its configuration keys (",
                     spec, name, u->name);
            for (unsigned j = 0; names[j]; j++)
                snprintf(err + strlen(err), errlen - strlen(err), "%s%s", j ? ", " : "", names[j]);
            snprintf(err + strlen(err), errlen - strlen(err), "; keys go in --config)");
            return -1;
        }
        char *end;
        unsigned long v = *p == '=' ? strtoul(p + 1, &end, 10) : 2;
        if (*p != '=' || end == p + 1 || v > 1 || (*end && *end != ',')) {
            snprintf(err, errlen, "--rtl-param %s: %s needs =0 or =1 (NAME=V,NAME=V)", spec, name);
            return -1;
        }
        int w1 = snprintf(g_rtl_params + n, sizeof g_rtl_params - n, " -set %s %lu", name, v);
        int w2 = snprintf(g_rtl_params_spec + m, sizeof g_rtl_params_spec - m, "%s%s=%lu", m ? " " : "", name, v);
        if (w1 < 0 || w2 < 0 || (n += (size_t)w1) >= sizeof g_rtl_params ||
            (m += (size_t)w2) >= sizeof g_rtl_params_spec) {
            snprintf(err, errlen, "--rtl-param %s: too long", spec);
            g_rtl_params[0] = g_rtl_params_spec[0] = '\0';
            return -1;
        }
        p = *end ? end + 1 : end;
    }
    return 0;
}

static int not_param(const rtl_desc *d, const char *key)
{
    for (unsigned i = 0; i < 4 && d->not_params[i]; i++)
        if (strcmp(d->not_params[i], key) == 0)
            return 1;
    return 0;
}

/* Every file of the unit's RTL is readable in dir (else a message naming it). */
static int rtl_readable(const rtl_desc *d, const char *dir, char *err, size_t errlen)
{
    for (unsigned i = 0; i < RTL_FILES && d->files[i]; i++) {
        char path[4096];
        snprintf(path, sizeof path, "%s/%s", dir, d->files[i]);
        if (access(path, R_OK) != 0) {
            snprintf(err, errlen, "%s: cannot read the RTL (--rtl DIR names rtl_model/verilog)", path);
            return -1;
        }
    }
    return 0;
}

/*
 * The script's head: the RTL at the configuration (every key, upper case, is
 * a parameter, but the unit's not_params; then its derived ones).
 */
static int write_read(FILE *f, const rtl_desc *d, const np_unit *u, const void *cfg, const char *dir, char *err,
                      size_t errlen)
{
    char derived[512] = "";
    if (d->params && d->params(cfg, derived, sizeof derived, err, errlen) != 0)
        return -1;
    fprintf(f, "read_verilog -I%s", dir);
    for (unsigned i = 0; i < RTL_FILES && d->files[i]; i++)
        fprintf(f, " %s/%s", dir, d->files[i]);
    fprintf(f, "\nchparam");
    size_t nk = np_unit_key_count(u);
    for (size_t k = 0; k < nk; k++) {
        const np_unit_key *key = &u->keys[k];
        if (not_param(d, key->name))
            continue;
        fprintf(f, " -set ");
        for (const char *p = key->name; *p; p++)
            fputc(toupper((unsigned char)*p), f);
        fprintf(f, " %u", np_unit_key_get(key, cfg));
    }
    fputs(derived, f);
    fputs(g_rtl_params, f); /* --rtl-param (np_synth_set_rtl_params) */
    fprintf(f, " %s\n", d->top);
    return 0;
}

/* The cone of every bank (c0, c1, ...) and of the valid bits (cv); stop at the flip-flops' outputs. */
static int write_cones(FILE *f, const rtl_desc *d, const np_unit *u, const np_unit_cost *c, const char *ff,
                       const char *extra, char *err, size_t errlen)
{
    fprintf(f, "select -set cv w:%s %s %%ci1 %%ci*:-%s[Q]\n", d->valid ? d->valid : "v", extra, ff);
    for (unsigned k = 0; k < c->n_stages; k++) {
        char sel[256];
        const char *p = d->bank_sel ? "" : prefix_of(d, c->st[k].name);
        if (!p) {
            snprintf(err, errlen, "%s: stage %s has no register bank in %s", u->name, c->st[k].name, d->files[0]);
            return -1;
        }
        if (d->bank_sel)
            d->bank_sel(k, c->n_stages, sel, sizeof sel);
        else
            snprintf(sel, sizeof sel, "w:*%s_*", p);
        fprintf(f, "select -set c%u %s %%ci1 %%ci*:-%s[Q]%s\n", k, sel, ff, *extra ? " @cv %d" : "");
    }
    return 0;
}

/*
 * The whole-design script: synthesis, then one selection per bank and a stat
 * of what only it holds.
 */
static int write_script(FILE *f, const rtl_desc *d, const np_unit *u, const void *cfg, const np_unit_cost *c,
                        const char *dir, const char *out, int flags, const char *abc_path, char *err, size_t errlen)
{
    if (write_read(f, d, u, cfg, dir, err, errlen) != 0)
        return -1;
    fprintf(f, "synth -top %s -flatten\ndfflegalize -cell $_DFF_P_ 01\n", d->top);
    write_abc(f, flags, abc_path);
    fprintf(f, "opt_clean\n");
    fprintf(f, "tee -q -o %s log NP_TOTAL\ntee -q -a %s stat -tech cmos\n", out, out);
    if (write_cones(f, d, u, c, "$_DFF_P_", "", err, errlen) != 0)
        return -1;
    for (unsigned k = 0; k < c->n_stages; k++) {
        fprintf(f, "tee -q -a %s log NP_STAGE %u\ntee -q -a %s stat -tech cmos @c%u", out, k, out, k);
        for (unsigned j = 0; j < c->n_stages; j++)
            if (j != k)
                fprintf(f, " @c%u %%d", j);
        fprintf(f, " @cv %%d\n");
    }
    return 0;
}

/*
 * The per-stage script (--per-stage): the whole design to gates without ABC
 * (`synth -noabc`, the flip-flops legalised), saved; then for each bank its
 * input cone alone (stopping at other flip-flops' outputs and at the valid
 * bits and their enables, whose drivers become inputs; the bank's flip-flops
 * become outputs) through ABC, and last what no bank's cone holds (the
 * shared row). ABC, the slow part, then sees one stage at a time; a cell two
 * cones share is counted in both (the whole-design flow puts it in shared).
 */
static int write_script_stages(FILE *f, const rtl_desc *d, const np_unit *u, const void *cfg, const np_unit_cost *c,
                               const char *dir, const char *out, int flags, const char *abc_path, char *err,
                               size_t errlen)
{
    if (write_read(f, d, u, cfg, dir, err, errlen) != 0)
        return -1;
    fprintf(f, "synth -top %s -flatten -noabc\ndfflegalize -cell $_DFF_P_ 01\nopt_clean\n", d->top);
    fprintf(f, "tee -q -o %s log NP_FLOPS\ntee -q -a %s stat\ndesign -save np_gates\n", out, out);
    for (unsigned k = 0; k <= c->n_stages; k++) {
        fprintf(f, "design -load np_gates\n");
        if (write_cones(f, d, u, c, "$_DFF_P_", "w:en", err, errlen) != 0)
            return -1;
        if (k < c->n_stages) {
            fprintf(f, "delete t:* @c%u %%d\n", k);
        } else { /* shared: the rest */
            fprintf(f, "select -set call");
            for (unsigned j = 0; j < c->n_stages; j++)
                fprintf(f, " @c%u", j);
            fprintf(f, "\ndelete @call t:* %%i\n");
        }
        fprintf(f, "setundef -undriven -expose\nexpose t:$_DFF_P_ %%co1:+$_DFF_P_[Q]\n");
        write_abc(f, flags, abc_path);
        fprintf(f, "opt_clean\n");
        if (k < c->n_stages)
            fprintf(f, "tee -q -a %s log NP_STAGE %u\n", out, k);
        else
            fprintf(f, "tee -q -a %s log NP_SHARED\n", out);
        fprintf(f, "tee -q -a %s stat -tech cmos\n", out);
    }
    return 0;
}

/*
 * Parse the tee'd statistics: "NP_TOTAL" / "NP_STAGE k" markers, then $_DFF_P_
 * and transistor counts; the per-stage flow's "NP_FLOPS" (the whole design's
 * flip-flops) and "NP_SHARED" (what no bank's cone holds), whose total is the
 * sum of the parts.
 */
static int parse_stats(FILE *f, np_synth_result *r, unsigned n_stages)
{
    char line[512];
    int cur = -2, seen_total = 0, parts = 0; /* -1: the whole design; -3: shared; k: stage k */
    while (fgets(line, sizeof line, f)) {
        const char *p;
        if (strncmp(line, "NP_TOTAL", 8) == 0 || strncmp(line, "NP_FLOPS", 8) == 0) {
            cur = -1;
            seen_total = 1;
            parts = line[3] == 'F';
        } else if (strncmp(line, "NP_SHARED", 9) == 0) {
            cur = -3;
        } else if (strncmp(line, "NP_STAGE ", 9) == 0) {
            long k = strtol(line + 9, NULL, 10);
            cur = k >= 0 && (unsigned long)k < n_stages ? (int)k : -2;
        } else if ((p = strstr(line, "$_DFF_P_")) != NULL) {
            unsigned v = (unsigned)strtoul(p + 8, NULL, 10);
            if (cur == -1)
                r->dff = v;
            else if (cur >= 0)
                r->st[cur].dff = v;
        } else if ((p = strstr(line, "Estimated number of transistors:")) != NULL) {
            double g = atof(p + strlen("Estimated number of transistors:")) / 4.0;
            if (cur == -1)
                r->total = g;
            else if (cur == -3)
                r->shared = g;
            else if (cur >= 0)
                r->st[cur].gates = g;
        }
    }
    if (parts) {
        r->total = r->shared;
        for (unsigned k = 0; k < n_stages; k++)
            r->total += r->st[k].gates;
    }
    return seen_total && r->total > 0 ? 0 : -1;
}

int np_synth_run(const np_unit *u, const void *cfg, const np_unit_cost *c, const char *rtl_dir, int flags,
                 np_synth_result *r, char *err, size_t errlen)
{
    int per_stage = flags & NP_SYNTH_PER_STAGE;
    memset(r, 0, sizeof *r);
    const rtl_desc *d = rtl_of(u);
    if (!d) {
        snprintf(err, errlen, "unit %s has no reference RTL (--synth: classic3, simplex3; with --unit also "
                 "wave, aacount, hatch, classic2/4/5, simplex2/4/5)", u->name);
        return -1;
    }
    if (system("yosys -V >/dev/null 2>&1") != 0) {
        snprintf(err, errlen, "--synth needs yosys (and berkeley-abc) on PATH: apt-get install yosys berkeley-abc");
        return -2;
    }
    if (rtl_readable(d, rtl_dir, err, errlen) != 0)
        return -1;
    char dir[4096], script[4200], out[4200], log[4200], abc[4200];
    if (np_tempdir(dir, sizeof dir, "noisepipe-synth", err, errlen) != 0)
        return -1;
    snprintf(script, sizeof script, "%s/synth.ys", dir);
    snprintf(out, sizeof out, "%s/stat.txt", dir);
    snprintf(log, sizeof log, "%s/yosys.log", dir);
    snprintf(abc, sizeof abc, "%s/abc.script", dir);
    int rc = -1;
    FILE *f = fopen(script, "w"), *fa = fopen(abc, "w");
    if (fa && (fputs(abc_script_bounded, fa) == EOF) + (fclose(fa) != 0) != 0)
        fa = NULL;
    if (!f || !fa) {
        if (f)
            fclose(f);
        snprintf(err, errlen, "cannot write %s", script);
    } else {
        int w = per_stage ? write_script_stages(f, d, u, cfg, c, rtl_dir, out, flags, abc, err, errlen)
                          : write_script(f, d, u, cfg, c, rtl_dir, out, flags, abc, err, errlen);
        if (fclose(f) != 0 && w == 0) {
            snprintf(err, errlen, "cannot write %s", script);
            w = -1;
        }
        if (w == 0) {
            char cmd[8800];
            snprintf(cmd, sizeof cmd, "yosys -q -s '%s' >'%s' 2>&1", script, log);
            int st = system(cmd);
            FILE *s = st == 0 ? fopen(out, "r") : NULL;
            if (!s) {
                snprintf(err, errlen, "yosys failed (status %d); its log: %s", st, log);
            } else {
                r->n_stages = c->n_stages;
                for (unsigned k = 0; k < c->n_stages; k++)
                    snprintf(r->st[k].name, sizeof r->st[k].name, "%s", c->st[k].name);
                if (parse_stats(s, r, c->n_stages) != 0) {
                    snprintf(err, errlen, "no statistics in yosys's output %s (log %s)", out, log);
                } else {
                    if (!per_stage) {
                        double sum = 0.0;
                        for (unsigned k = 0; k < r->n_stages; k++)
                            sum += r->st[k].gates;
                        r->shared = r->total - sum;
                    }
                    rc = 0;
                }
                fclose(s);
            }
        }
    }
    if (rc == 0) { /* keep the files of a failed run for its message */
        remove(script);
        remove(out);
        remove(log);
        remove(abc);
        rmdir(dir);
    }
    return rc;
}

/*
 * The model's stage without its valid bit (every declared bank counts one):
 * synthesis puts the valid bits, whose handshake reaches every bank, in the
 * shared row, so the model's valid bits are compared there too.
 */
static double model_stage(const np_stage_cost *m, double ff)
{
    return m->logic + m->regs - (m->reg_bits > 0 ? ff : 0.0);
}

double np_synth_model_stage(const np_stage_cost *m)
{
    return model_stage(m, np_cost_default.ff_bit);
}

/* FNV-1a, 64 bits, continued from h over n bytes. */
static uint64_t fnv1a(uint64_t h, const void *p, size_t n)
{
    const unsigned char *b = p;
    for (size_t i = 0; i < n; i++)
        h = (h ^ b[i]) * UINT64_C(0x100000001b3);
    return h;
}

/* 1 when one of d's files (in dir) has the line `include "name"`. */
static int rtl_includes(const rtl_desc *d, const char *dir, const char *name)
{
    char want[128];
    snprintf(want, sizeof want, "`include \"%s\"", name);
    int found = 0;
    for (unsigned i = 0; i < RTL_FILES && d->files[i] && !found; i++) {
        char path[4096], line[4096];
        snprintf(path, sizeof path, "%s/%s", dir, d->files[i]);
        FILE *f = fopen(path, "r");
        if (!f)
            continue;
        while (!found && fgets(line, sizeof line, f))
            found = strncmp(line, want, strlen(want)) == 0;
        fclose(f);
    }
    return found;
}

int np_synth_key(const np_unit *u, const void *cfg, const char *rtl_dir, int flags, char key[17], char *err,
                 size_t errlen)
{
    const rtl_desc *d = rtl_of(u);
    if (!d) {
        snprintf(err, errlen, "unit %s has no reference RTL", u->name);
        return -1;
    }
    uint64_t h = UINT64_C(0xcbf29ce484222325);
    char buf[4096];
    /* The files by name and content (not by folder: a worktree's copy is the same RTL). */
    for (unsigned i = 0; i < RTL_FILES && d->files[i]; i++) {
        char path[4096];
        snprintf(path, sizeof path, "%s/%s", rtl_dir, d->files[i]);
        FILE *f = fopen(path, "rb");
        if (!f) {
            snprintf(err, errlen, "%s: cannot read the RTL (--rtl DIR names rtl_model/verilog)", path);
            return -1;
        }
        h = fnv1a(h, d->files[i], strlen(d->files[i]) + 1u);
        size_t n;
        while ((n = fread(buf, 1, sizeof buf, f)) > 0)
            h = fnv1a(h, buf, n);
        fclose(f);
    }
    /*
     * The headers the RTL includes are part of it too. np_hashn.vh and
     * np_hash.vh count whenever they are present, as they always have, so
     * that an unchanged unit keeps its key (docs/synth-cache); the shared
     * pipe and texturing headers count for a unit whose files include them.
     */
    static const char *const includes[] = { "np_hashn.vh", "np_hash.vh", "np_fixed.vh", "np_pipe_ports.vh",
                                            "np_span_ports.vh", "np_tex_quad.vh", "np_tex_front.vh" };
    for (unsigned i = 0; i < sizeof includes / sizeof includes[0]; i++) {
        if (i >= 2 && !rtl_includes(d, rtl_dir, includes[i]))
            continue;
        char path[4096];
        snprintf(path, sizeof path, "%s/%s", rtl_dir, includes[i]);
        FILE *f = fopen(path, "rb");
        if (!f)
            continue;
        h = fnv1a(h, includes[i], strlen(includes[i]) + 1u);
        size_t n;
        while ((n = fread(buf, 1, sizeof buf, f)) > 0)
            h = fnv1a(h, buf, n);
        fclose(f);
    }
    /* The chparam line (every parameter the configuration sets) and the flow. */
    FILE *t = tmpfile();
    if (!t) {
        snprintf(err, errlen, "cannot create a temporary file");
        return -1;
    }
    if (write_read(t, d, u, cfg, rtl_dir, err, errlen) != 0) {
        fclose(t);
        return -1;
    }
    rewind(t);
    while (fgets(buf, sizeof buf, t))
        if (strncmp(buf, "chparam", 7) == 0)
            h = fnv1a(h, buf, strlen(buf));
    fclose(t);
    h = fnv1a(h, &flags, sizeof flags);
    h = fnv1a(h, abc_script_bounded, sizeof abc_script_bounded);
    snprintf(key, 17, "%016llx", (unsigned long long)h);
    return 0;
}

double np_synth_print(FILE *f, const np_unit_cost *c, const np_synth_result *r)
{
    double worst = 0.0, ff = np_cost_default.ff_bit, valid = 0.0;
    unsigned sd = 0;
    fprintf(f, "| stage | model logic | model registers (bits) | model | Yosys flip-flops | Yosys | model / Yosys |\n");
    fprintf(f, "| --- | ---: | ---: | ---: | ---: | ---: | ---: |\n");
    for (unsigned k = 0; k < c->n_stages && k < r->n_stages; k++) {
        const np_stage_cost *m = &c->st[k];
        double mt = model_stage(m, ff), y = r->st[k].gates;
        double q = y > 0 ? mt / y : 0.0;
        valid += m->reg_bits > 0 ? ff : 0.0;
        sd += r->st[k].dff;
        if (y > 0 && fabs(q - 1.0) > worst)
            worst = fabs(q - 1.0);
        fprintf(f, "| %s | %.0f | %.0f (%u) | %.0f | %u | %.0f | %.3f |\n", m->name, m->logic, m->regs - (m->reg_bits ? ff : 0.0),
                m->reg_bits ? m->reg_bits - 1u : 0u, mt, r->st[k].dff, y, q);
    }
    fprintf(f, "| shared: valid bits, handshake, options | | %.0f (%u) | %.0f | %u | %.0f | |\n", valid,
            c->n_stages, valid, r->dff - sd, r->shared);
    fprintf(f, "| **total** | **%.0f** | **%.0f (%u)** | **%.0f** | **%u** | **%.0f** | **%.3f** |\n", c->logic,
            c->regs, c->reg_bits, c->total, r->dff, r->total, r->total > 0 ? c->total / r->total : 0.0);
    return worst;
}

/*
 * Yosys per stage with the as-built model beside it (--rtl-param: no model
 * of the variant): no ratio column, since the two describe different circuits.
 */
static void print_variant(FILE *f, const np_unit_cost *c, const np_synth_result *r)
{
    double ff = np_cost_default.ff_bit;
    unsigned sd = 0;
    fprintf(f, "| stage | Yosys flip-flops | Yosys | cost model of the as-built circuit (not this variant) |\n");
    fprintf(f, "| --- | ---: | ---: | ---: |\n");
    for (unsigned k = 0; k < c->n_stages && k < r->n_stages; k++) {
        sd += r->st[k].dff;
        fprintf(f, "| %s | %u | %.0f | %.0f |\n", c->st[k].name, r->st[k].dff, r->st[k].gates,
                model_stage(&c->st[k], ff));
    }
    fprintf(f, "| shared: valid bits, handshake, options | %u | %.0f | %.0f |\n", r->dff - sd, r->shared,
            ff * c->n_stages);
    fprintf(f, "| **total** | **%u** | **%.0f** | **%.0f** |\n", r->dff, r->total, c->total);
}

int np_report_gates_synth(const np_unit *only, const char *spec, const char *rtl_dir, int flags,
                          double tolerance_pct)
{
    int per_stage = flags & NP_SYNTH_PER_STAGE;
    if (!rtl_dir)
        rtl_dir = np_synth_default_rtl_dir();
    int rc = NP_EXIT_OK, any = 0;
    const np_unit *u;
    size_t next = 0;
    while ((u = np_synth_unit_next(only, &next)) != NULL) {
        any = 1;
        char err[512];
        np_unit_cfg cfg;
        np_unit_cost *c = calloc(1, sizeof *c);
        if (!c)
            return NP_EXIT_USAGE;
        if (np_unit_configure(u, &cfg, only ? spec : NULL, err, sizeof err) != 0 ||
            np_unit_cost_compute(u, &cfg, &np_cost_default, c, err, sizeof err) != 0) {
            np_err("report", "%s: %s", u->name, err);
            free(c);
            return NP_EXIT_USAGE;
        }
        if (isatty(2))
            fprintf(stderr, "report: synthesising %s (%s) with yosys (about 1 minute for classic3, several for simplex3)...\n",
                    u->name, c->cfg);
        double t0 = np_now();
        np_synth_result r;
        int s = np_synth_run(u, &cfg, c, rtl_dir, flags, &r, err, sizeof err);
        if (s != 0) {
            np_err("report", "%s: %s", u->name, err);
            free(c);
            return NP_EXIT_USAGE;
        }
        double worst = 0.0;
        if (g_rtl_params_spec[0]) {
            printf("## %s (`%s`, RTL `%s`): Yosys per stage\n\n", u->name, c->cfg, g_rtl_params_spec);
            print_variant(stdout, c, &r);
        } else {
            printf("## %s (`%s`): cost model against Yosys\n\n", u->name, c->cfg);
            worst = np_synth_print(stdout, c, &r);
        }
        printf("\nNAND2 equivalents: Yosys 0.23 + ABC (`abc -g NAND`, %s; `stat -tech cmos` transistors / 4; "
               "enables and the valid bits' logic included; %s); ",
               flags & NP_SYNTH_ABC_FULL ? "ABC's default script, --abc-full" : "SAT sweep bounded, &fraig -x -C 1000",
               per_stage ? "ABC per stage, --per-stage" : "the whole design");
        if (g_rtl_params_spec[0]) /* --rtl-param */
            printf("a variant the cost model does not declare (its column: the as-built circuit); ");
        else
            printf("largest stage deviation %.1f %%; ", 100.0 * worst);
        printf("yosys took %.0f s.\n\n", np_now() - t0);
        if (tolerance_pct >= 0.0 && 100.0 * worst > tolerance_pct) {
            np_err("report", "%s: a stage is %.1f %% from synthesis (tolerance %.1f %%)", u->name, 100.0 * worst,
                   tolerance_pct);
            rc = NP_EXIT_FAIL;
        }
        free(c);
    }
    if (!any) {
        np_err("report", "unit %s has no reference RTL (--synth: classic3, simplex3; with --unit also wave, "
                         "aacount, hatch, classic2/4/5, simplex2/4/5)", only ? only->name : "(any)");
        return NP_EXIT_USAGE;
    }
    return rc;
}

/* ---- what report fpga (report_fpga.c) shares with --synth: the same RTL table and head ---- */

const char *np_synth_rtl_top(const np_unit *u)
{
    const rtl_desc *d = rtl_of(u);
    return d ? d->top : NULL;
}

int np_synth_write_rtl(FILE *f, const np_unit *u, const void *cfg, const char *rtl_dir, char *err, size_t errlen)
{
    const rtl_desc *d = rtl_of(u);
    if (!d) {
        snprintf(err, errlen, "unit %s has no reference RTL", u->name);
        return -1;
    }
    if (rtl_readable(d, rtl_dir, err, errlen) != 0)
        return -1;
    return write_read(f, d, u, cfg, rtl_dir, err, errlen);
}

const char *np_synth_stage_of(const np_unit *u, const char *reg)
{
    const rtl_desc *d = rtl_of(u);
    if (!d || !reg)
        return NULL;
    for (unsigned i = 0; i < 12 && d->bank[i].stage; i++) {
        size_t n = strlen(d->bank[i].prefix);
        if (strncmp(reg, d->bank[i].prefix, n) == 0 && reg[n] == '_')
            return d->bank[i].stage;
    }
    return NULL;
}

const char *np_synth_rtl_param_spec(void)
{
    return g_rtl_params_spec;
}

unsigned np_synth_rtl_clocks_per_result(const np_unit *u)
{
    /* docs/rtl.md, "classic3 circuit variants": the serial hash (and the serial lerp engine, which
       implies it) take one point every 8 clocks. */
    if (u && strcmp(u->name, "classic3") == 0 &&
        (strstr(g_rtl_params_spec, "HASH_SERIAL=1") || strstr(g_rtl_params_spec, "LERP_SERIAL=1")))
        return 8;
    return 0;
}
