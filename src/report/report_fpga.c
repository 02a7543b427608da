/* SPDX-License-Identifier: MIT */
/*
 * report_fpga.c - `noisepipe report fpga` (np_fpga.h, docs/fpga.md): the
 * reference RTL through the open iCE40 flow of Debian's packages.
 *
 * Per unit, in a temporary folder:
 *   1. yosys: the RTL at the configuration (np_synth_write_rtl: the same head as
 *      --synth), `hierarchy -top T; portlist T` -> the ports and their widths;
 *   2. the I/O harness np_fpga_top.v (below), generated from those ports;
 *   3. yosys: `synth_ice40 -top np_fpga_top -noflatten [-retime] -json`, then
 *      `stat -top T` (the unit's own cells: its module and the modules under it);
 *   4. nextpnr-ice40 --DEVICE --package P --freq F --seed S --report (JSON:
 *      utilisation, Fmax, critical path) --timing-allow-fail (a clock below the
 *      target is reported, not an error);
 *   5. icepack (the bitstream) and icetime -t (its own timing of the packed design,
 *      a second opinion on nextpnr's Fmax).
 * Results per second = Fmax x results per clock (the cost model's throughput of
 * the as-built circuit, or the --rtl-param variant's: np_synth_rtl_clocks_per_result).
 */
#include <cjson/cJSON.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "np_common.h"
#include "np_fpga.h"
#include "np_outfile.h"
#include "np_report.h"
#include "np_synth.h"

void np_fpga_opts_init(np_fpga_opts *o)
{
    memset(o, 0, sizeof *o);
    o->device = "hx8k";
    o->freq_mhz = 12.0;
    o->seed = 1;
}

typedef struct port {
    char name[64];
    unsigned width;
    int out;
} port;

enum { MAX_PORTS = 64 };

/* What one place-and-route gave. */
typedef struct pnr_result {
    int ok;                       /* placed, routed and packed */
    char error[512];              /* the tool's message when not */
    unsigned lut, ff, carry, bram, dsp, lc, lc_avail, bram_avail, io, io_avail;
    double fmax, target, icetime; /* MHz; icetime 0 when it did not run */
    char cp_from[64], cp_to[64];  /* the critical path's registers */
    char cp_from_lc[512], cp_to_lc[512]; /* nextpnr's names of their logic cells */
    unsigned cp_cells;            /* logic cells on it */
    double cp_logic, cp_route;    /* ns */
} pnr_result;

/* snprintf for messages that may be cut short (paths inside them are long). */
static void msg(char *dst, size_t len, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static void msg(char *dst, size_t len, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(dst, len, fmt, ap);
    va_end(ap);
}

static int run(const char *cmd, const char *log)
{
    char c[16384];
    msg(c, sizeof c, "%s >'%s' 2>&1", cmd, log);
    return system(c);
}

/* The first line of log that starts with "ERROR" (or its last line). */
static void log_error(const char *log, char *out, size_t len)
{
    FILE *f = fopen(log, "r");
    char line[512], last[512] = "";
    msg(out, len, "see %s", log);
    if (!f)
        return;
    while (fgets(line, sizeof line, f)) {
        line[strcspn(line, "\r\n")] = '\0';
        if (strncmp(line, "ERROR", 5) == 0) {
            msg(out, len, "%s (log: %s)", line, log);
            fclose(f);
            return;
        }
        if (line[0])
            msg(last, sizeof last, "%s", line);
    }
    fclose(f);
    if (last[0])
        msg(out, len, "%s (log: %s)", last, log);
}

/* portlist's lines: "input [15:0] x". */
static int read_ports(const char *path, port *p, unsigned *n, char *err, size_t errlen)
{
    FILE *f = fopen(path, "r");
    if (!f) {
        msg(err, errlen, "%s: no port list from yosys", path);
        return -1;
    }
    char line[512];
    *n = 0;
    while (fgets(line, sizeof line, f)) {
        char dir[16], name[128];
        int hi, lo;
        if (sscanf(line, " %15s [%d:%d] %127s", dir, &hi, &lo, name) != 4)
            continue;
        if (strcmp(dir, "input") != 0 && strcmp(dir, "output") != 0) {
            msg(err, errlen, "%s: port %s is %s (the harness takes inputs and outputs)", path, name, dir);
            fclose(f);
            return -1;
        }
        if (*n == MAX_PORTS || strlen(name) >= sizeof p->name) {
            msg(err, errlen, "%s: too many ports or a name too long", path);
            fclose(f);
            return -1;
        }
        msg(p[*n].name, sizeof p[*n].name, "%s", name);
        p[*n].width = (unsigned)(hi > lo ? hi - lo : lo - hi) + 1u;
        p[*n].out = dir[0] == 'o';
        (*n)++;
    }
    fclose(f);
    if (*n == 0) {
        msg(err, errlen, "%s: yosys listed no ports", path);
        return -1;
    }
    return 0;
}

/*
 * The harness: isr (the unit's input bits and one load bit) shifts in from
 * pin sin; when the load bit is set osr takes every output bit, else shifts
 * out to pin sout. Neither register is reset (an iCE40 flip-flop powers up 0).
 */
static int write_harness(const char *path, const char *top, const port *p, unsigned n, unsigned *in_bits,
                         unsigned *out_bits)
{
    unsigned in = 0, out = 0;
    for (unsigned i = 0; i < n; i++)
        if (strcmp(p[i].name, "clk") != 0)
            *(p[i].out ? &out : &in) += p[i].width;
    FILE *f = fopen(path, "w");
    if (!f)
        return -1;
    fprintf(f, "// Generated by noisepipe report fpga (src/report/report_fpga.c): the I/O harness of %s.\n"
               "// Every input bit of the unit from a shift register fed by pin sin; every output bit\n"
               "// loaded into a shift register read out on pin sout (the load bit: isr[%u]).\n",
            top, in);
    fprintf(f, "module np_fpga_top (input wire clk, input wire sin, output wire sout);\n");
    fprintf(f, "    reg [%u:0] isr;\n    always @(posedge clk) isr <= {isr[%u:0], sin};\n", in, in ? in - 1 : 0);
    if (out == 0)
        out = 1;
    fprintf(f, "    wire [%u:0] o;\n    reg [%u:0] osr;\n", out - 1, out - 1);
    if (out > 1)
        fprintf(f, "    always @(posedge clk) osr <= isr[%u] ? o : {osr[%u:0], 1'b0};\n", in, out - 2);
    else
        fprintf(f, "    always @(posedge clk) osr <= isr[%u] ? o : 1'b0;\n", in);
    fprintf(f, "    assign sout = osr[%u];\n    %s u (", out - 1, top);
    unsigned ib = 0, ob = 0;
    for (unsigned i = 0; i < n; i++) {
        fprintf(f, "%s.%s(", i ? ", " : "", p[i].name);
        if (strcmp(p[i].name, "clk") == 0) {
            fprintf(f, "clk)");
        } else if (p[i].out) {
            fprintf(f, "o[%u:%u])", ob + p[i].width - 1, ob);
            ob += p[i].width;
        } else {
            fprintf(f, "isr[%u:%u])", ib + p[i].width - 1, ib);
            ib += p[i].width;
        }
    }
    fprintf(f, ");\nendmodule\n");
    *in_bits = in;
    *out_bits = ob;
    return fclose(f) == 0 ? 0 : -1;
}

/* `stat -top T`: the cell counts of the block after "design hierarchy" (or of "=== T ==="). */
static int read_stat(const char *path, const char *top, pnr_result *r)
{
    FILE *f = fopen(path, "r");
    if (!f)
        return -1;
    char line[512], mod[128];
    snprintf(mod, sizeof mod, "=== %s ===", top);
    long at = -1, hier = -1;
    while (fgets(line, sizeof line, f)) {
        if (strstr(line, "=== design hierarchy ==="))
            hier = ftell(f);
        else if (strstr(line, mod))
            at = ftell(f);
    }
    if (hier >= 0)
        at = hier;
    if (at < 0) {
        fclose(f);
        return -1;
    }
    fseek(f, at, SEEK_SET);
    r->lut = r->ff = r->carry = r->bram = r->dsp = 0;
    while (fgets(line, sizeof line, f)) {
        char cell[64];
        unsigned v;
        if (strstr(line, "===") && hier < 0)
            break;
        if (sscanf(line, " %63s %u", cell, &v) != 2)
            continue;
        if (strcmp(cell, "SB_LUT4") == 0)
            r->lut += v;
        else if (strcmp(cell, "SB_CARRY") == 0)
            r->carry += v;
        else if (strncmp(cell, "SB_DFF", 6) == 0)
            r->ff += v;
        else if (strncmp(cell, "SB_RAM40", 8) == 0)
            r->bram += v;
        else if (strcmp(cell, "SB_MAC16") == 0)
            r->dsp += v;
    }
    fclose(f);
    return 0;
}

/* A cell name of nextpnr's ("u.g_engine.r1_k_SB_DFFESR_Q_D_SB_LUT4_O_1_LC") -> the register ("r1_k"). */
static void reg_of(const char *cell, char *out, size_t len)
{
    char buf[512];
    snprintf(buf, sizeof buf, "%s", cell);
    char *cut = strstr(buf, "_SB_");
    if (cut)
        *cut = '\0';
    cut = strchr(buf, '$');
    if (cut)
        *cut = '\0';
    cut = strchr(buf, '[');
    if (cut)
        *cut = '\0';
    const char *s = strrchr(buf, '.');
    msg(out, len, "%s", s ? s + 1 : buf);
}

/* The first bit of a connection or net ("bits": [398]); -1 for a constant. */
static long bit0(const cJSON *a)
{
    const cJSON *b = cJSON_GetArrayItem(a, 0);
    return cJSON_IsNumber(b) ? (long)b->valuedouble : -1;
}

/*
 * A logic cell of nextpnr's packed design ("u.g_engine.r1_k_SB_DFFESR_Q_D_SB_LUT4_O_1_LC",
 * "u.r3_l_SB_DFFE_Q_DFFLC") -> the register its flip-flop holds, from Yosys's netlist (the
 * cell named is the LC's LUT or flip-flop; a LUT's flip-flop is the one its output feeds),
 * as "r1_k" (instance path and bit index dropped). 0, or -1 when the netlist does not say
 * (a cell without a flip-flop, a name not found).
 */
static int lc_reg(const cJSON *modules, const np_unit *u, const char *lc, char *out, size_t len)
{
    char name[1024];
    msg(name, sizeof name, "%s", lc);
    size_t n = strlen(name);
    int dff_only = n > 6 && strcmp(name + n - 6, "_DFFLC") == 0;
    if (dff_only)
        name[n - 6] = '\0';
    else if (n > 3 && strcmp(name + n - 3, "_LC") == 0)
        name[n - 3] = '\0';
    else
        return -1;
    const cJSON *mod = cJSON_GetObjectItemCaseSensitive(modules, "np_fpga_top");
    const char *c = name;
    for (int depth = 0; depth < 8 && mod; depth++) {
        const cJSON *cells = cJSON_GetObjectItemCaseSensitive(mod, "cells");
        const cJSON *cell = cJSON_GetObjectItemCaseSensitive(cells, c);
        if (!cell) { /* an instance path: "u." -> the unit's module, "skid." -> its submodule */
            const char *dot = strchr(c, '.');
            char inst[256];
            if (!dot || (size_t)(dot - c) >= sizeof inst)
                return -1;
            memcpy(inst, c, (size_t)(dot - c));
            inst[dot - c] = '\0';
            const cJSON *ic = cJSON_GetObjectItemCaseSensitive(cells, inst);
            const cJSON *type = cJSON_GetObjectItemCaseSensitive(ic, "type");
            if (!cJSON_IsString(type))
                return -1;
            mod = cJSON_GetObjectItemCaseSensitive(modules, type->valuestring);
            c = dot + 1;
            continue;
        }
        long q = -1;
        const cJSON *type = cJSON_GetObjectItemCaseSensitive(cell, "type");
        const cJSON *conn = cJSON_GetObjectItemCaseSensitive(cell, "connections");
        if (!cJSON_IsString(type))
            return -1;
        if (strncmp(type->valuestring, "SB_DFF", 6) == 0) {
            q = bit0(cJSON_GetObjectItemCaseSensitive(conn, "Q"));
        } else { /* a LUT: the flip-flop its output feeds */
            long o = bit0(cJSON_GetObjectItemCaseSensitive(conn, "O"));
            const cJSON *e;
            cJSON_ArrayForEach(e, cells)
            {
                const cJSON *t = cJSON_GetObjectItemCaseSensitive(e, "type");
                const cJSON *cn = cJSON_GetObjectItemCaseSensitive(e, "connections");
                if (o >= 0 && cJSON_IsString(t) && strncmp(t->valuestring, "SB_DFF", 6) == 0 &&
                    bit0(cJSON_GetObjectItemCaseSensitive(cn, "D")) == o) {
                    q = bit0(cJSON_GetObjectItemCaseSensitive(cn, "Q"));
                    break;
                }
            }
        }
        if (q < 0)
            return -1;
        /* The bit's name: a bank's register ("r0_w") before a plain wire that is the same bit
           ("dw0"), before a name Yosys made ("scurve$func$...a", "r1_g[0]_SB_DFFE_Q_D_SB_LUT4_O_I1":
           a function's argument, a LUT input named after the flip-flop it leads to), before a hidden one. */
        const cJSON *net, *best = NULL;
        int best_score = -1;
        cJSON_ArrayForEach(net, cJSON_GetObjectItemCaseSensitive(mod, "netnames"))
        {
            const cJSON *b, *hide = cJSON_GetObjectItemCaseSensitive(net, "hide_name");
            char rn[256];
            reg_of(net->string, rn, sizeof rn);
            int plain = strchr(net->string, '$') == NULL && strstr(net->string, "_SB_") == NULL; /* not Yosys's */
            int score = plain && np_synth_stage_of(u, rn) ? 3 : plain ? 2 : cJSON_IsNumber(hide) && hide->valueint == 0 ? 1 : 0;
            if (score <= best_score)
                continue;
            cJSON_ArrayForEach(b, cJSON_GetObjectItemCaseSensitive(net, "bits"))
            {
                if (cJSON_IsNumber(b) && (long)b->valuedouble == q) {
                    best = net;
                    best_score = score;
                    break;
                }
            }
        }
        if (!best)
            return -1;
        reg_of(best->string, out, len);
        return 0;
    }
    return -1;
}

static unsigned util(const cJSON *u, const char *name, unsigned *avail)
{
    const cJSON *e = cJSON_GetObjectItemCaseSensitive(u, name);
    const cJSON *used = cJSON_GetObjectItemCaseSensitive(e, "used"), *av = cJSON_GetObjectItemCaseSensitive(e, "available");
    if (avail)
        *avail = cJSON_IsNumber(av) ? (unsigned)av->valuedouble : 0u;
    return cJSON_IsNumber(used) ? (unsigned)used->valuedouble : 0u;
}

/* A JSON file, parsed (NULL when it cannot be read or parsed). */
static cJSON *load_json(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *buf = n > 0 ? malloc((size_t)n + 1) : NULL;
    if (!buf || fread(buf, 1, (size_t)n, f) != (size_t)n) {
        free(buf);
        fclose(f);
        return NULL;
    }
    fclose(f);
    buf[n] = '\0';
    cJSON *j = cJSON_Parse(buf);
    free(buf);
    return j;
}

/* nextpnr's --report JSON. */
static int read_report(const char *path, pnr_result *r)
{
    cJSON *j = load_json(path);
    if (!j)
        return -1;
    const cJSON *u = cJSON_GetObjectItemCaseSensitive(j, "utilization");
    r->lc = util(u, "ICESTORM_LC", &r->lc_avail);
    r->io = util(u, "SB_IO", &r->io_avail);
    (void)util(u, "ICESTORM_RAM", &r->bram_avail);
    const cJSON *fm = cJSON_GetObjectItemCaseSensitive(j, "fmax"), *clk;
    cJSON_ArrayForEach(clk, fm)
    {
        const cJSON *a = cJSON_GetObjectItemCaseSensitive(clk, "achieved"),
                    *c = cJSON_GetObjectItemCaseSensitive(clk, "constraint");
        if (cJSON_IsNumber(a)) {
            r->fmax = a->valuedouble;
            r->target = cJSON_IsNumber(c) ? c->valuedouble : 0.0;
        }
    }
    const cJSON *cp;
    cJSON_ArrayForEach(cp, cJSON_GetObjectItemCaseSensitive(j, "critical_paths"))
    {
        const cJSON *from = cJSON_GetObjectItemCaseSensitive(cp, "from"), *to = cJSON_GetObjectItemCaseSensitive(cp, "to");
        if (!cJSON_IsString(from) || !cJSON_IsString(to) || strcmp(from->valuestring, to->valuestring) != 0 ||
            strncmp(from->valuestring, "posedge", 7) != 0)
            continue; /* the clock's own register-to-register path, not a pin's */
        const cJSON *path_ = cJSON_GetObjectItemCaseSensitive(cp, "path"), *st;
        int first = 1;
        cJSON_ArrayForEach(st, path_)
        {
            const cJSON *type = cJSON_GetObjectItemCaseSensitive(st, "type"), *d = cJSON_GetObjectItemCaseSensitive(st, "delay");
            const cJSON *tcell = cJSON_GetObjectItemCaseSensitive(cJSON_GetObjectItemCaseSensitive(st, "to"), "cell");
            double dl = cJSON_IsNumber(d) ? d->valuedouble : 0.0;
            if (first && cJSON_IsString(tcell)) {
                reg_of(tcell->valuestring, r->cp_from, sizeof r->cp_from);
                msg(r->cp_from_lc, sizeof r->cp_from_lc, "%s", tcell->valuestring);
            }
            first = 0;
            if (cJSON_IsString(type) && strcmp(type->valuestring, "logic") == 0) {
                r->cp_cells++;
                r->cp_logic += dl;
            } else if (cJSON_IsString(type) && strcmp(type->valuestring, "routing") == 0) {
                r->cp_route += dl;
            } else {
                r->cp_logic += dl; /* clock-to-q, setup */
            }
            if (cJSON_IsString(tcell)) {
                reg_of(tcell->valuestring, r->cp_to, sizeof r->cp_to);
                msg(r->cp_to_lc, sizeof r->cp_to_lc, "%s", tcell->valuestring);
            }
        }
        break;
    }
    cJSON_Delete(j);
    return r->lc > 0 ? 0 : -1;
}

/*
 * A placement that failed for want of cells: nextpnr's "ICESTORM_LC: 40987/ 7680" (or its RAM
 * line) before "no BELs remaining". 1 with r->lc and r->lc_avail set (or the RAMs'), else 0.
 */
static int read_no_fit(const char *log, pnr_result *r)
{
    FILE *f = fopen(log, "r");
    char line[1024];
    int nofit = 0;
    unsigned used, avail;
    while (f && fgets(line, sizeof line, f)) {
        const char *p = strstr(line, "ICESTORM_LC:");
        if (p && sscanf(p + 12, " %u/ %u", &used, &avail) == 2) {
            r->lc = used;
            r->lc_avail = avail;
        }
        if (strstr(line, "no BELs remaining"))
            nofit = 1;
    }
    if (f)
        fclose(f);
    return nofit && r->lc_avail > 0 && r->lc > r->lc_avail;
}

/* icetime -t's "Total path delay: 39.84 ns (25.10 MHz)". */
static double read_icetime(const char *log)
{
    FILE *f = fopen(log, "r");
    char line[512];
    double mhz = 0.0;
    while (f && fgets(line, sizeof line, f)) {
        const char *p = strstr(line, "Total path delay:");
        const char *q = p ? strchr(p, '(') : NULL;
        if (q)
            mhz = atof(q + 1);
    }
    if (f)
        fclose(f);
    return mhz;
}

/* Copy src to dst through np_outfile (atomic). */
static int copy_file(const char *src, const char *dst)
{
    FILE *in = fopen(src, "rb");
    if (!in)
        return -1;
    np_outfile o;
    if (np_outfile_open(&o, dst, "wb") != 0) {
        fclose(in);
        return -1;
    }
    char buf[65536];
    size_t n;
    while ((n = fread(buf, 1, sizeof buf, in)) > 0)
        fwrite(buf, 1, n, o.f);
    int bad = ferror(in);
    fclose(in);
    return np_outfile_close(&o, !bad) == 0 && !bad ? 0 : -1;
}

static void progress(const char *unit, const char *what)
{
    if (isatty(2))
        fprintf(stderr, "report fpga: %s: %s...\n", unit, what);
}

/* Synthesis (with or without -retime), place and route, pack, icetime: files w/NAME.*. */
static void flow(const np_unit *u, const void *cfg, const np_fpga_opts *o, const char *pkg, const char *w,
                 const char *name, int retime, pnr_result *r)
{
    const char *top = np_synth_rtl_top(u), *rtl = o->rtl_dir ? o->rtl_dir : np_synth_default_rtl_dir();
    char ys[4200], log[4200], json[4200], stat[4200], cmd[16384], err[512];
    memset(r, 0, sizeof *r);
    snprintf(ys, sizeof ys, "%s/%s.ys", w, name);
    snprintf(log, sizeof log, "%s/%s-yosys.log", w, name);
    snprintf(json, sizeof json, "%s/%s.json", w, name);
    snprintf(stat, sizeof stat, "%s/%s-stat.txt", w, name);
    FILE *f = fopen(ys, "w");
    if (!f || np_synth_write_rtl(f, u, cfg, rtl, err, sizeof err) != 0) {
        msg(r->error, sizeof r->error, "%s", f ? err : "cannot write the yosys script");
        if (f)
            fclose(f);
        return;
    }
    fprintf(f, "read_verilog %s/harness.v\nsynth_ice40 -top np_fpga_top -noflatten%s -json %s\n"
               "tee -q -o %s stat -top %s\n",
            w, retime ? " -retime" : "", json, stat, top);
    if (fclose(f) != 0) {
        msg(r->error, sizeof r->error, "cannot write %s", ys);
        return;
    }
    progress(u->name, retime ? "yosys synth_ice40 -retime" : "yosys synth_ice40");
    snprintf(cmd, sizeof cmd, "yosys -q -s '%s'", ys);
    if (run(cmd, log) != 0 || read_stat(stat, top, r) != 0) {
        log_error(log, r->error, sizeof r->error);
        return;
    }
    char asc[4200], rep[4200], plog[4200], bin[4200], tlog[4200];
    snprintf(asc, sizeof asc, "%s/%s.asc", w, name);
    snprintf(rep, sizeof rep, "%s/%s-report.json", w, name);
    snprintf(plog, sizeof plog, "%s/%s-nextpnr.log", w, name);
    snprintf(bin, sizeof bin, "%s/%s.bin", w, name);
    snprintf(tlog, sizeof tlog, "%s/%s-icetime.log", w, name);
    char what[128];
    snprintf(what, sizeof what, "nextpnr-ice40 --%s --package %s, seed %llu (a few minutes)", o->device, pkg,
             (unsigned long long)o->seed);
    progress(u->name, what);
    snprintf(cmd, sizeof cmd,
             "nextpnr-ice40 --%s --package %s --json '%s' --asc '%s' --report '%s' --freq %g --seed %llu "
             "--timing-allow-fail",
             o->device, pkg, json, asc, rep, o->freq_mhz, (unsigned long long)o->seed);
    if (run(cmd, plog) != 0) {
        if (read_no_fit(plog, r))
            msg(r->error, sizeof r->error, "does not fit the device: the unit and its harness need %u logic cells of "
                "%u (%.0f %%; nextpnr: no BEL left; log %s)", r->lc, r->lc_avail, 100.0 * r->lc / r->lc_avail, plog);
        else
            log_error(plog, r->error, sizeof r->error);
        return;
    }
    if (read_report(rep, r) != 0) {
        msg(r->error, sizeof r->error, "%s: no utilisation in nextpnr's report", rep);
        return;
    }
    cJSON *net = load_json(json); /* the critical path's ends: the registers of their logic cells */
    if (net) {
        const cJSON *mods = cJSON_GetObjectItemCaseSensitive(net, "modules");
        if (r->cp_from_lc[0])
            (void)lc_reg(mods, u, r->cp_from_lc, r->cp_from, sizeof r->cp_from);
        if (r->cp_to_lc[0])
            (void)lc_reg(mods, u, r->cp_to_lc, r->cp_to, sizeof r->cp_to);
        cJSON_Delete(net);
    }
    snprintf(cmd, sizeof cmd, "icepack '%s' '%s'", asc, bin);
    char ilog[4200];
    snprintf(ilog, sizeof ilog, "%s/%s-icepack.log", w, name);
    if (run(cmd, ilog) != 0) {
        log_error(ilog, r->error, sizeof r->error);
        return;
    }
    snprintf(cmd, sizeof cmd, "icetime -d %s -P %s -t '%s'", o->device, pkg, asc);
    if (run(cmd, tlog) == 0)
        r->icetime = read_icetime(tlog);
    r->ok = 1;
}

static void print_si(FILE *f, double v)
{
    if (v >= 1e6)
        fprintf(f, "%.2f M", v / 1e6);
    else if (v >= 1e3)
        fprintf(f, "%.2f k", v / 1e3);
    else
        fprintf(f, "%.2f", v);
}

static void print_stage(FILE *f, const np_unit *u, const char *reg)
{
    /* A --rtl-param variant may regroup the banks (LERP_SERIAL's engine is bank r1): no stage names then. */
    const char *st = np_synth_rtl_param_spec()[0] ? NULL : np_synth_stage_of(u, reg);
    fprintf(f, "`%s`", reg[0] ? reg : "?");
    if (st)
        fprintf(f, " (stage %s)", st);
    else if (strncmp(reg, "isr", 3) == 0 || strncmp(reg, "osr", 3) == 0)
        fprintf(f, " (the harness)");
}

/* One unit's section. */
static void print_unit(FILE *f, const np_unit *u, const np_unit_cost *c, const np_fpga_opts *o, const char *pkg,
                       unsigned in_bits, unsigned out_bits, double rate, const pnr_result *r, const pnr_result *rt)
{
    const char *var = np_synth_rtl_param_spec();
    fprintf(f, "## %s (`%s`%s%s%s) on iCE40-%s %s\n\n", u->name, c->cfg, var[0] ? ", RTL `" : "", var,
            var[0] ? "`" : "", o->device[0] == 'h' ? "HX8K" : "UP5K", pkg);
    if (!r->ok) {
        fprintf(f, "**No bitstream**: %s\n\n", r->error);
        if (r->lut + r->ff > 0) /* synthesised: what it needs */
            fprintf(f, "The unit (Yosys, its own modules): %u LUT4, %u flip-flops, %u carry cells, %u block RAMs.\n\n",
                    r->lut, r->ff, r->carry, r->bram);
        return;
    }
    fprintf(f, "| | the unit (Yosys, its own modules) | the placed design (nextpnr: unit + I/O harness) |\n"
               "| --- | ---: | ---: |\n");
    fprintf(f, "| LUT4 | %u | |\n| flip-flops | %u | |\n| carry cells (SB_CARRY) | %u | |\n", r->lut, r->ff, r->carry);
    fprintf(f, "| block RAMs (4 Kbit) | %u | %u of %u |\n", r->bram, r->bram, r->bram_avail);
    if (r->dsp)
        fprintf(f, "| DSP (SB_MAC16) | %u | |\n", r->dsp);
    fprintf(f, "| logic cells (LUT4 + flip-flop) | | %u of %u (%.1f %%) |\n", r->lc, r->lc_avail,
            r->lc_avail ? 100.0 * r->lc / r->lc_avail : 0.0);
    fprintf(f, "| I/O pins | | %u of %u |\n", r->io, r->io_avail);
    fprintf(f, "| Fmax after routing (nextpnr, seed %llu) | | %.2f MHz (target %.2f MHz: %s) |\n",
            (unsigned long long)o->seed, r->fmax, r->target, r->fmax >= r->target ? "met" : "**missed**");
    if (r->icetime > 0.0)
        fprintf(f, "| Fmax (icetime on the packed design) | | %.2f MHz |\n", r->icetime);
    else
        fprintf(f, "| Fmax (icetime on the packed design) | | not run (icetime needs fpga-icestorm-chipdb) |\n");
    const char *note = c->has_timing && !var[0] ? c->timing.throughput_note : "";
    fprintf(f, "| results per clock | %.4g%s%s%s | |\n", rate, note[0] ? " (" : "", note, note[0] ? ")" : "");
    fprintf(f, "| results per second at Fmax | ");
    print_si(f, rate * r->fmax * 1e6);
    fprintf(f, " | |\n\n");
    fprintf(f, "Critical path (nextpnr): from ");
    print_stage(f, u, r->cp_from);
    fprintf(f, " to ");
    print_stage(f, u, r->cp_to);
    fprintf(f, ", %u logic cells, %.1f ns in cells and %.1f ns in routing (%.1f ns).", r->cp_cells, r->cp_logic,
            r->cp_route, r->cp_logic + r->cp_route);
    const char *lim = np_synth_rtl_param_spec()[0] ? NULL : np_synth_stage_of(u, r->cp_to);
    if (lim)
        fprintf(f, " The stage that limits Fmax: **%s** (the logic that loads the path's end).", lim);
    if (rt && rt->ok)
        fprintf(f, " With `synth_ice40 -retime` (ABC moves flip-flops across logic): %.2f MHz (%+.1f %%), %u logic "
                   "cells, %u flip-flops in the unit.",
                rt->fmax, 100.0 * (rt->fmax / r->fmax - 1.0), rt->lc, rt->ff);
    else if (rt)
        fprintf(f, " With `synth_ice40 -retime`: no result (%s).", rt->error);
    else
        fprintf(f, " `--retime` measures what retiming gains.");
    fprintf(f, "\n\nThe I/O harness: %u input bits shift in from one pin, %u output bits shift out to another "
               "(%u flip-flops and %u LUT4s of the placed design's logic cells are the harness's).\n\n",
            in_bits, out_bits, in_bits + 1 + out_bits, out_bits);
}

int np_report_fpga(const np_unit *only, const char *spec, const np_fpga_opts *o)
{
    const char *pkg = o->package ? o->package : strcmp(o->device, "up5k") == 0 ? "sg48" : "ct256";
    if (strcmp(o->device, "hx8k") != 0 && strcmp(o->device, "up5k") != 0) {
        np_err("report", "--device %s: expected hx8k or up5k", o->device);
        return NP_EXIT_USAGE;
    }
    if (only && !np_synth_has_rtl(only)) {
        np_err("report", "unit %s has no reference RTL (fpga: the units --synth lists)", only->name);
        return NP_EXIT_USAGE;
    }
    if (system("yosys -V >/dev/null 2>&1") != 0 || system("nextpnr-ice40 --version >/dev/null 2>&1") != 0 ||
        system("icepack -h >/dev/null 2>&1; command -v icepack >/dev/null") != 0) {
        np_err("report", "fpga needs yosys, nextpnr-ice40 and icepack on PATH: "
                         "apt-get install yosys nextpnr-ice40 fpga-icestorm fpga-icestorm-chipdb");
        return NP_EXIT_USAGE;
    }
    char *md = NULL;
    size_t mdlen = 0;
    FILE *m = open_memstream(&md, &mdlen);
    if (!m)
        return NP_EXIT_USAGE;
    fprintf(m, "# The units on an iCE40 FPGA\n\n`noisepipe report fpga`: Yosys `synth_ice40`, nextpnr-ice40 "
               "(target %g MHz, seed %llu), icepack, icetime (docs/fpga.md).\n\n",
            o->freq_mhz, (unsigned long long)o->seed);
    int rc = NP_EXIT_OK, any = 0;
    char *sum = NULL; /* the summary table, one row a unit */
    size_t sumlen = 0;
    FILE *sm = open_memstream(&sum, &sumlen);
    if (!sm) {
        fclose(m);
        free(md);
        return NP_EXIT_USAGE;
    }
    const np_unit *u;
    size_t next = 0;
    while ((u = np_synth_unit_next(only, &next)) != NULL) {
        any = 1;
        char err[512];
        if (!np_synth_has_rtl(u)) {
            np_err("report", "unit %s has no reference RTL (fpga: the units --synth lists)", u->name);
            rc = NP_EXIT_USAGE;
            break;
        }
        np_unit_cfg cfg;
        np_unit_cost *c = calloc(1, sizeof *c);
        if (!c || np_unit_configure(u, &cfg, only ? spec : NULL, err, sizeof err) != 0 ||
            np_unit_cost_compute(u, &cfg, &np_cost_default, c, err, sizeof err) != 0) {
            np_err("report", "%s: %s", u->name, c ? err : "out of memory");
            free(c);
            rc = NP_EXIT_USAGE;
            break;
        }
        char w[4096], ys[4200], log[4200], ports_txt[4200], harness[4200], cmd[8800];
        if (np_tempdir(w, sizeof w, "noisepipe-fpga", err, sizeof err) != 0) {
            np_err("report", "%s", err);
            free(c);
            rc = NP_EXIT_USAGE;
            break;
        }
        snprintf(ys, sizeof ys, "%s/ports.ys", w);
        snprintf(log, sizeof log, "%s/ports.log", w);
        snprintf(ports_txt, sizeof ports_txt, "%s/ports.txt", w);
        snprintf(harness, sizeof harness, "%s/harness.v", w);
        FILE *f = fopen(ys, "w");
        const char *rtl = o->rtl_dir ? o->rtl_dir : np_synth_default_rtl_dir();
        if (!f || np_synth_write_rtl(f, u, &cfg, rtl, err, sizeof err) != 0) {
            np_err("report", "%s: %s", u->name, f ? err : "cannot write the yosys script");
            if (f)
                fclose(f);
            free(c);
            rc = NP_EXIT_USAGE;
            break;
        }
        fprintf(f, "hierarchy -top %s\ntee -q -o %s portlist %s\n", np_synth_rtl_top(u), ports_txt, np_synth_rtl_top(u));
        fclose(f);
        port p[MAX_PORTS];
        unsigned np = 0, in_bits = 0, out_bits = 0;
        snprintf(cmd, sizeof cmd, "yosys -q -s '%s'", ys);
        if (run(cmd, log) != 0 || read_ports(ports_txt, p, &np, err, sizeof err) != 0 ||
            write_harness(harness, np_synth_rtl_top(u), p, np, &in_bits, &out_bits) != 0) {
            char e2[600];
            log_error(log, e2, sizeof e2);
            np_err("report", "%s: yosys could not elaborate the RTL: %s", u->name, e2);
            free(c);
            rc = NP_EXIT_USAGE;
            break;
        }
        double t0 = np_now();
        pnr_result r, rt;
        flow(u, &cfg, o, pkg, w, u->name, 0, &r);
        if (r.ok && o->retime) {
            char name[80];
            snprintf(name, sizeof name, "%s-retime", u->name);
            flow(u, &cfg, o, pkg, w, name, 1, &rt);
        }
        unsigned cpr = np_synth_rtl_clocks_per_result(u);
        double rate = cpr ? 1.0 / cpr : c->throughput;
        print_unit(m, u, c, o, pkg, in_bits, out_bits, rate, &r, o->retime && r.ok ? &rt : NULL);
        if (r.ok) {
            fprintf(sm, "| %s%s%s | %u | %u | %u | %u of %u | %.2f | %.4g | ", u->name, np_synth_rtl_param_spec()[0] ? " " : "",
                    np_synth_rtl_param_spec(), r.lut, r.ff, r.bram, r.lc, r.lc_avail, r.fmax, rate);
            print_si(sm, rate * r.fmax * 1e6);
            fprintf(sm, " |\n");
        } else {
            char need[64] = "no bitstream";
            if (r.lc_avail)
                msg(need, sizeof need, "does not fit: %u of %u", r.lc, r.lc_avail);
            fprintf(sm, "| %s%s%s | %u | %u | %u | %s | | %.4g | |\n", u->name, np_synth_rtl_param_spec()[0] ? " " : "",
                    np_synth_rtl_param_spec(), r.lut, r.ff, r.bram, need, rate);
        }
        fprintf(m, "The flow took %.0f s.\n\n", np_now() - t0);
        if (!r.ok) {
            np_err("report", "%s: no bitstream: %s", u->name, r.error);
            rc = NP_EXIT_FAIL;
        } else if (o->out_dir) {
            const char *ext[] = { "bin", "asc", "json", "report.json", "nextpnr.log" };
            const char *src[] = { "%s/%s.bin", "%s/%s.asc", "%s/%s.json", "%s/%s-report.json", "%s/%s-nextpnr.log" };
            for (unsigned k = 0; k < 5; k++) {
                char s[4300], d[4300];
                snprintf(s, sizeof s, src[k], w, u->name);
                snprintf(d, sizeof d, "%s/fpga-%s.%s", o->out_dir, u->name, ext[k]);
                if (copy_file(s, d) != 0) {
                    np_err("report", "cannot write %s", d);
                    rc = NP_EXIT_USAGE;
                }
            }
            fprintf(m, "Kept: `fpga-%s.bin` (the bitstream, icepack), `.asc`, `.json` (Yosys's netlist), "
                       "`.report.json` and `.nextpnr.log`.\n\n", u->name);
        }
        if (r.ok) { /* keep the files of a failed run for its message */
            snprintf(cmd, sizeof cmd, "rm -rf '%s'", w);
            if (system(cmd) != 0)
                np_err("report", "could not remove %s", w);
        }
        free(c);
    }
    if (fclose(sm) == 0 && any && sumlen > 0) {
        fprintf(m, "## Summary (%s, seed %llu)\n\n| unit | LUT4 | flip-flops | block RAMs | logic cells (with the harness) | "
                   "Fmax (MHz) | results per clock | results per second |\n| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n%s\n",
                strcmp(o->device, "up5k") == 0 ? "iCE40-UP5K" : "iCE40-HX8K", (unsigned long long)o->seed, sum);
    }
    free(sum);
    if (!any && rc == NP_EXIT_OK) {
        np_err("report", "no unit has reference RTL");
        rc = NP_EXIT_USAGE;
    }
    if (fclose(m) != 0) {
        free(md);
        return NP_EXIT_USAGE;
    }
    fwrite(md, 1, mdlen, stdout);
    if (o->out_dir) {
        char path[4200];
        snprintf(path, sizeof path, "%s/fpga.md", o->out_dir);
        np_outfile of;
        if (np_outfile_open(&of, path, "w") != 0) {
            np_err("report", "%s", of.err);
            rc = NP_EXIT_USAGE;
        } else {
            fwrite(md, 1, mdlen, of.f);
            if (np_outfile_close(&of, 1) != 0) {
                np_err("report", "cannot write %s", path);
                rc = NP_EXIT_USAGE;
            }
        }
    }
    free(md);
    return rc;
}
