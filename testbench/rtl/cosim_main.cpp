// SPDX-License-Identifier: MIT
// cosim_main - drives a Verilated unit (top renamed Vcosim: np_classic3,
// np_simplex3 with NP_COSIM_SIMPLEX, np_wave with NP_COSIM_WAVE, whose
// register inputs get np_cosim's test register set, np_aacount with
// NP_COSIM_AACOUNT and NP_COSIM_AAC_CFG, the ten values of its -G parameters
// that --cfg must repeat, or an n-D unit, np_simplexn or np_classicn, with
// NP_COSIM_NDIM=<registry unit> and NP_COSIM_KEYS=<key=value,...>, the
// configuration its -G parameters were made from, that --unit and --cfg must
// repeat) clock by clock beside the C cycle model (np_pipe, through
// np_cosim.h) with the same stimulus, and compares in_ready, out_valid and,
// when valid, every output word, every cycle. np_texel (a stream unit: span
// descriptors in, pixels out) builds with NP_COSIM_TEXEL=<its N_OCT> on top
// of NP_COSIM_NDIM=texel and NP_COSIM_KEYS (every key, texture= first): its
// register inputs get the texture's registers (np_cosim_tex_regs), its
// descriptor the stream model's (y = x0 = 0), and cr cg cb are compared.
// np_hatch builds with NP_COSIM_HATCH on top of NP_COSIM_NDIM=hatch and
// NP_COSIM_KEYS (every key of the unit): its ports xu xv tone pm om get the
// registry's input fields, its c is compared.
//
//   cosim --unit classic3 --cfg 8,12,11 [--in-reg] [--out-skid] [--cycles N]
//         [--seed S] [--no-traffic] [--bench] [--trace FILE]
//   cosim --unit simplex4 --cfg dims=4,out_bits=16,t_frac=25,p_frac=25 [...]
// --cfg lists the configuration the RTL was Verilated with (-G parameters),
// in the order of np_cosim_open; for a registry unit (an n-D build) it is
// the unit's every key, as `noisepipe vectors --config` writes them
// (np_cosim_open_spec). --bench also times the two models alone on
// the same stimulus and prints their cycles/s. Exit status 0: no mismatch;
// 1: a mismatch (the first 10 are printed); 2: bad usage.
//
// --trace FILE writes the cycle-level trace of the run (the ports, which
// both models drive identically when there is no mismatch), one line per
// cycle, after '#' header lines:
//   cycle in_valid in_ready x y z out_valid out_ready out...
// decimal cycle, 0/1 handshake bits, hex x y z (4 digits) and, when
// out_valid, each output word in hex (ceil(bits/4) digits), else '-'.
// (wave: i j t ph u v r g in place of x y z; aacount: the bus as one hex
// number, ceil(bits/4) digits, most significant first; a registry unit: its
// input fields, ceil(bits/4) digits each.)
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <algorithm>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "Vcosim.h"
#include "np_cosim.h"
#include "verilated.h"
#ifdef NP_COSIM_WAVE
#include "np_wave.h"
#endif
#ifdef NP_COSIM_TEXEL
#include "np_texture.h"
#endif

namespace {

#ifdef NP_COSIM_NDIM
// The registry unit and the configuration the n-D RTL was Verilated with (its -G parameters are
// these keys in capitals, DIMS the unit's n): the model must be the same unit at the same keys.
#define NP_COSIM_STR_(...) #__VA_ARGS__
#define NP_COSIM_STR(...) NP_COSIM_STR_(__VA_ARGS__)
const char *const nd_unit = NP_COSIM_STR(NP_COSIM_NDIM);
const char *const nd_keys = NP_COSIM_STR(NP_COSIM_KEYS);
#endif

#ifdef NP_COSIM_AACOUNT
// The ten -G values the RTL was Verilated with (m, depth, normal, luma, luma_taps, c_d, c_n, c_s, t_min, t_edge).
const unsigned aac_cfg[10] = {NP_COSIM_AAC_CFG};
// The window bus words (np_aacount_bus_pack's, 64 bits each) onto the port bus[bits-1:0].
template <typename T> void put_bus(T &p, const uint64_t *w, unsigned bits)
{
    p = (T)(bits >= 64 ? w[0] : (w[0] & ((1ull << bits) - 1)));
}
template <std::size_t N> void put_bus(VlWide<N> &p, const uint64_t *w, unsigned bits)
{
    for (unsigned k = 0; k < N; k++) {
        EData v = (EData)(w[k / 2] >> (32 * (k % 2)));
        if (32 * (k + 1) > bits) v &= (EData)((1ull << (bits - 32 * k)) - 1);
        p[k] = v;
    }
}
#endif

#if defined(NP_COSIM_WAVE) || defined(NP_COSIM_NDIM)
// Bits [bit, bit + w) of a Verilated port (CData .. QData, or VlWide for > 64 bits).
template <typename T> void put_bits(T &p, unsigned bit, unsigned w, uint64_t v)
{
    const uint64_t m = (w >= 64 ? ~0ull : ((1ull << w) - 1)) << bit;
    p = (T)(((uint64_t)p & ~m) | ((v << bit) & m));
}
template <std::size_t N> void put_bits(VlWide<N> &p, unsigned bit, unsigned w, uint64_t v)
{
    for (unsigned b = 0; b < w; b++) {
        EData &word = p[(bit + b) / 32];
        const EData m = (EData)1 << ((bit + b) % 32);
        word = ((v >> b) & 1u) ? (word | m) : (word & ~m);
    }
}
#endif

struct Rtl {
    std::unique_ptr<VerilatedContext> ctx{new VerilatedContext};
    std::unique_ptr<Vcosim> top{new Vcosim{ctx.get()}};
#ifdef NP_COSIM_WAVE
    // The box's registers on the register inputs (lane k at [W*k +: W]), held for the run.
    void regs(const np_wave_regs &r)
    {
        top->n = r.n;
        for (unsigned k = 0; k < NP_COSIM_TRAINS; k++) {  // the RTL's TRAINS lanes
            const np_wave_train &t = r.tr[k];
            put_bits(top->kx, 32 * k, 32, (uint32_t)t.kx);
            put_bits(top->kz, 32 * k, 32, (uint32_t)t.kz);
            put_bits(top->phi, 32 * k, 32, t.phi);
            put_bits(top->om, 32 * k, 32, t.om);
            put_bits(top->amp, 15 * k, 15, t.amp);
            put_bits(top->airr, 15 * k, 15, t.airr);
            put_bits(top->cx, 16 * k, 16, (uint16_t)t.cx);
            put_bits(top->cz, 16 * k, 16, (uint16_t)t.cz);
            put_bits(top->kmx, 16 * k, 16, (uint16_t)t.kmx);
            put_bits(top->kmz, 16 * k, 16, (uint16_t)t.kmz);
        }
        top->width = r.width;
        top->pu = r.pu;
        top->pv = r.pv;
        top->pt = r.pt;
        top->omc = r.omc;
        top->b = r.b;
        top->gcap = r.gcap;
    }
#endif
#ifdef NP_COSIM_TEXEL
    // The texture's registers on the register inputs (np_texel.v's layout), held for the run.
    void regs(const np_tex_regs &r)
    {
        for (unsigned i = 0; i < 10; i++) put_bits(top->k_reg, 48 * i, 48, (uint64_t)r.k[i]);
        for (unsigned o = 0; o < NP_COSIM_TEXEL; o++) {
            for (unsigned a = 0; a < 3; a++) {
                for (unsigned b = 0; b < 3; b++) put_bits(top->m_reg, 24 * (9 * o + 3 * a + b), 24, (uint64_t)r.oct[o].m[a][b]);
                put_bits(top->o_reg, 48 * (3 * o + a), 48, (uint64_t)r.oct[o].o[a]);
            }
            put_bits(top->amp_reg, 32 * o, 32, (uint64_t)(uint32_t)r.oct[o].amp);
        }
        for (unsigned e = 0; e < 256; e++)
            for (unsigned ch = 0; ch < 3; ch++) put_bits(top->cmap, 24 * e + 8 * ch, 8, e < r.cmap_n ? r.cmap[e][ch] : 0u);
        top->cmap_n = r.cmap_n;
        top->cmap_rep = r.cmap_repeat ? 1 : 0;
    }
#endif
    void reset()
    {
        top->clk = 0;
        top->rst = 1;
        top->in_valid = 0;
        top->out_ready = 0;
        top->eval();
        for (int i = 0; i < 2; i++) edge();
        top->rst = 0;
        top->eval();
    }
    void edge()
    {
        top->clk = 1;
        top->eval();
        top->clk = 0;
        top->eval();
    }
    unsigned bus_bits = 0;  // aacount: the width of the port bus
    unsigned nin = 0;       // n-D: the number of axes, the port x [16 nin - 1 : 0]
    void drive(const np_cosim_cycle &c)
    {
        top->in_valid = c.in_valid;
#ifdef NP_COSIM_WAVE
        top->i = (uint16_t)c.win[0];
        top->j = (uint16_t)c.win[1];
        top->t = c.win[2];
        top->ph = c.win[3];
        top->u = (uint16_t)c.win[4];
        top->v = (uint16_t)c.win[5];
        top->r = (uint8_t)c.win[6];
        top->g = (uint16_t)c.win[7];
#elif defined(NP_COSIM_AACOUNT)
        put_bus(top->bus, c.bus, bus_bits);
#elif defined(NP_COSIM_TEXEL)
        top->in_s = c.in[0];
        top->in_t = c.in[1];
        top->in_r = c.in[2];
        top->in_ds = c.in[3];
        top->in_dt = c.in[4];
        top->in_dr = c.in[5];
        top->in_n = (uint32_t)c.in[6];
        top->in_y = 0;
        top->in_x0 = 0;
#elif defined(NP_COSIM_HATCH)
        top->xu = c.in[0];  // the registry's fields in order: xu, xv u33; tone u8; pm, om u17
        top->xv = c.in[1];
        top->tone = (uint8_t)c.in[2];
        top->pm = (uint32_t)c.in[3];
        top->om = (uint32_t)c.in[4];
#elif defined(NP_COSIM_NDIM)
        for (unsigned a = 0; a < nin; a++)  // field a at [16 (n - 1 - a) +: 16]: x at the top
            put_bits(top->x, 16 * (nin - 1 - a), 16, c.in[a]);
#else
        top->x = c.x;
        top->y = c.y;
        top->z = c.z;
#endif
        top->out_ready = c.out_ready;
        top->eval();
    }
    // The outputs in np_cosim's order; the first nout of them are compared.
    void outs(uint32_t o[NP_COSIM_OUTS], unsigned normals) const
    {
        for (unsigned k = 0; k < NP_COSIM_OUTS; k++) o[k] = 0;
#if defined(NP_COSIM_WAVE)
        unsigned k = 0;
        o[k++] = top->y;
        o[k++] = top->dx;
        o[k++] = top->dz;
        if (normals) {
            o[k++] = top->nx;
            o[k++] = top->ny;
            o[k++] = top->nz;
        }
        o[k] = top->fold;  // compared only with fold (nout says)
#elif defined(NP_COSIM_AACOUNT)
        (void)normals;
        o[0] = top->s;
        o[1] = top->mask;
        o[2] = top->sd;
        o[3] = top->sn;
        o[4] = top->ss;
#elif defined(NP_COSIM_TEXEL)
        (void)normals;
        o[0] = top->cr;
        o[1] = top->cg;
        o[2] = top->cb;
#elif defined(NP_COSIM_HATCH)
        (void)normals;
        o[0] = top->c;
#elif defined(NP_COSIM_SIMPLEX)
        (void)normals;
        o[0] = top->f;
        o[1] = top->dfdx;
        o[2] = top->dfdy;
        o[3] = top->dfdz;
#else  // classic3, and the n-D units (their one output f)
        (void)normals;
        o[0] = top->f;
#endif
    }
};

double seconds_since(std::chrono::steady_clock::time_point t0)
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

int usage()
{
    std::fprintf(stderr, "usage: cosim --unit U --cfg V,V,...|KEY=V,... [--in-reg] [--out-skid] [--cycles N] "
                         "[--seed S] [--no-traffic] [--bench]\n");
    return 2;
}

} // namespace

int main(int argc, char **argv)
{
    const char *unit = nullptr, *cfg = nullptr, *trace_path = nullptr;
    int in_reg = 0, out_skid = 0, traffic = 1, bench = 0;
    unsigned long long cycles = 1000000, seed = 1;
    for (int i = 1; i < argc; i++) {
        std::string a = argv[i];
        if (a == "--unit" && i + 1 < argc) unit = argv[++i];
        else if (a == "--cfg" && i + 1 < argc) cfg = argv[++i];
        else if (a == "--in-reg") in_reg = 1;
        else if (a == "--out-skid") out_skid = 1;
        else if (a == "--no-traffic") traffic = 0;
        else if (a == "--bench") bench = 1;
        else if (a == "--trace" && i + 1 < argc) trace_path = argv[++i];
        else if (a == "--cycles" && i + 1 < argc) cycles = std::strtoull(argv[++i], nullptr, 10);
        else if (a == "--seed" && i + 1 < argc) seed = std::strtoull(argv[++i], nullptr, 10);
        else if (a.rfind("+verilator", 0) == 0) continue;
        else return usage();
    }
    if (!unit || !cfg) return usage();
    // key=value,...: a registry unit's configuration (np_cosim_open_spec); else the values of np_cosim_open.
    const bool spec = std::strchr(cfg, '=') != nullptr;
    std::vector<unsigned> p;
    for (const char *s = cfg; *s && !spec;) {
        char *end;
        p.push_back((unsigned)std::strtoul(s, &end, 10));
        if (end == s) return usage();
        s = *end == ',' ? end + 1 : end;
    }
    char err[600];
    auto open_model = [&]() {
        return spec ? np_cosim_open_spec(unit, cfg, in_reg, out_skid, seed, err, sizeof err)
                    : np_cosim_open(unit, p.data(), (unsigned)p.size(), in_reg, out_skid, seed, err, sizeof err);
    };
    np_cosim *m = open_model();
    if (!m) {
        std::fprintf(stderr, "cosim: %s\n", err);
        return 2;
    }
#ifdef NP_COSIM_NDIM
    // --unit and --cfg are what the RTL was Verilated with.
    if (!spec || std::strcmp(unit, nd_unit) != 0 || np_cosim_spec_is(m, nd_keys, err, sizeof err) != 0) {
        std::fprintf(stderr, "cosim: this binary is the RTL of --unit %s --cfg %s%s%s\n", nd_unit, nd_keys,
                     spec && std::strcmp(unit, nd_unit) == 0 ? ": " : "",
                     spec && std::strcmp(unit, nd_unit) == 0 ? err : "");
        return 2;
    }
#else
    if (spec) {
        std::fprintf(stderr, "cosim: this binary is not an n-D unit's RTL: --cfg takes values, not keys\n");
        return 2;
    }
#endif
    const unsigned nout = np_cosim_outputs(m);
#ifdef NP_COSIM_WAVE
    // --cfg is what the RTL was Verilated with: trains must be its TRAINS.
    if (!np_cosim_is_wave(m) || p[0] != NP_COSIM_TRAINS) {
        std::fprintf(stderr, "cosim: this binary is np_wave with TRAINS=%d: --unit wave --cfg %d,...\n",
                     NP_COSIM_TRAINS, NP_COSIM_TRAINS);
        return 2;
    }
    const unsigned wave_normals = p[4];
#else
    if (np_cosim_is_wave(m)) {
        std::fprintf(stderr, "cosim: this binary is not np_wave\n");
        return 2;
    }
    const unsigned wave_normals = 0;
#endif
#ifdef NP_COSIM_AACOUNT
    // --cfg is what the RTL was Verilated with: all ten values must be its parameters.
    if (!np_cosim_is_aacount(m) || p.size() != 10 || !std::equal(p.begin(), p.end(), aac_cfg)) {
        std::fprintf(stderr, "cosim: this binary is np_aacount with --cfg");
        for (unsigned k = 0; k < 10; k++) std::fprintf(stderr, "%c%u", k ? ',' : ' ', aac_cfg[k]);
        std::fprintf(stderr, " (m,depth,normal,luma,luma_taps,c_d,c_n,c_s,t_min,t_edge)\n");
        return 2;
    }
#else
    if (np_cosim_is_aacount(m)) {
        std::fprintf(stderr, "cosim: this binary is not np_aacount\n");
        return 2;
    }
#endif
    const unsigned aac_bits = np_cosim_aac_bus_bits(m), nin = np_cosim_inputs(m);
    Rtl rtl;
    rtl.bus_bits = aac_bits;
    rtl.nin = nin;
#ifdef NP_COSIM_WAVE
    rtl.regs(*np_cosim_wave_regs(m));
#endif
#ifdef NP_COSIM_TEXEL
    // The texture's octaves must be the RTL's lanes.
    if (!np_cosim_tex_regs(m) || np_cosim_tex_regs(m)->n_oct != NP_COSIM_TEXEL) {
        std::fprintf(stderr, "cosim: this binary is np_texel with N_OCT=%d: the texture has %u octaves\n", NP_COSIM_TEXEL,
                     np_cosim_tex_regs(m) ? np_cosim_tex_regs(m)->n_oct : 0u);
        return 2;
    }
    rtl.regs(*np_cosim_tex_regs(m));
#endif
    rtl.reset();

    FILE *trace = nullptr;
    if (trace_path) {
        trace = std::fopen(trace_path, "w");
        if (!trace) {
            std::fprintf(stderr, "cosim: cannot write %s\n", trace_path);
            return 2;
        }
        std::fprintf(trace, "# noisepipe cycle trace 1\n# unit %s\n# config %s%s%s\n# seed %llu\n", unit, cfg,
                     in_reg ? " in_reg" : "", out_skid ? " out_skid" : "", seed);
        std::fprintf(trace, "# columns cycle in_valid in_ready %s",
                     np_cosim_is_wave(m) ? "i j t ph u v r g" : np_cosim_is_aacount(m) ? "bus" : nin ? "" : "x y z");
        for (unsigned k = 0; k < nin; k++) std::fprintf(trace, "%sin%u(%u bits)", k ? " " : "", k, np_cosim_in_bits(m, k));
        std::fprintf(trace, " out_valid out_ready");
        for (unsigned k = 0; k < nout; k++) std::fprintf(trace, " out%u(%u bits)", k, np_cosim_out_bits(m, k));
        std::fprintf(trace, "\n");
    }
    unsigned long long mismatches = 0, compared = 0, ink = 0;
    unsigned long long hist[4][17] = {};  // aacount: compared cycles by the value (0..16) of s, sd, sn, ss
    np_cosim_cycle c{};
    uint32_t ro[NP_COSIM_OUTS];
    auto t0 = std::chrono::steady_clock::now();
    for (unsigned long long cy = 0; cy < cycles; cy++) {
        np_cosim_drive(m, &c, traffic);
        np_cosim_eval(m, &c);
        rtl.drive(c);
        rtl.outs(ro, wave_normals);
        int bad = rtl.top->in_ready != c.in_ready || rtl.top->out_valid != c.out_valid;
        if (c.out_valid && rtl.top->out_valid) {
            compared++;
            for (unsigned k = 0; k < nout; k++) bad |= ro[k] != c.out[k];
            if (aac_bits)
                for (unsigned k = 0; k < 4; k++) hist[k][c.out[k == 0 ? 0 : k + 1] & 31u]++;
#ifdef NP_COSIM_HATCH
            if (c.out_valid && c.out_ready) ink += c.out[0] != 255u;  // a result with ink (c < 255)
#endif
        }
        if (bad) {
            if (++mismatches <= 10) {
                std::printf("cycle %llu: in_valid %d out_ready %d | rtl: in_ready %d out_valid %d", cy, c.in_valid,
                            c.out_ready, rtl.top->in_ready, rtl.top->out_valid);
                for (unsigned k = 0; k < nout; k++) std::printf(" %x", ro[k]);
                std::printf(" | model: in_ready %d out_valid %d", c.in_ready, c.out_valid);
                for (unsigned k = 0; k < nout; k++) std::printf(" %x", c.out[k]);
                std::printf("\n");
            }
        }
        if (trace) {
            if (np_cosim_is_wave(m))  // i j t ph u v r g
                std::fprintf(trace, "%llu %d %d %04x %04x %08x %08x %04x %04x %02x %04x %d %d", cy, c.in_valid,
                             c.in_ready, c.win[0], c.win[1], c.win[2], c.win[3], c.win[4], c.win[5], c.win[6],
                             c.win[7], c.out_valid, c.out_ready);
            else if (aac_bits) {
                std::fprintf(trace, "%llu %d %d ", cy, c.in_valid, c.in_ready);
                for (int d = (int)((aac_bits + 3) / 4) - 1; d >= 0; d--)
                    std::fprintf(trace, "%x", (unsigned)(c.bus[d / 16] >> (4 * (d % 16))) & 15u);
                std::fprintf(trace, " %d %d", c.out_valid, c.out_ready);
            } else if (nin) {
                std::fprintf(trace, "%llu %d %d", cy, c.in_valid, c.in_ready);
                for (unsigned k = 0; k < nin; k++)
                    std::fprintf(trace, " %0*llx", (int)((np_cosim_in_bits(m, k) + 3) / 4), (unsigned long long)c.in[k]);
                std::fprintf(trace, " %d %d", c.out_valid, c.out_ready);
            } else
                std::fprintf(trace, "%llu %d %d %04x %04x %04x %d %d", cy, c.in_valid, c.in_ready, c.x, c.y, c.z,
                             c.out_valid, c.out_ready);
            for (unsigned k = 0; k < nout; k++) {
                if (c.out_valid)
                    std::fprintf(trace, " %0*x", (int)((np_cosim_out_bits(m, k) + 3) / 4), c.out[k]);
                else
                    std::fprintf(trace, " -");
            }
            std::fprintf(trace, "\n");
        }
        rtl.edge();
        np_cosim_clock(m, &c);
    }
    if (trace && std::fclose(trace) == 0) std::printf("trace: %llu cycles written to %s\n", cycles, trace_path);
    double t_both = seconds_since(t0);
    uint64_t n[5];
    np_cosim_counts(m, n);
    // Results delivered: each compared at its transfer (and on every stalled cycle before it: out_valid cycles).
    std::printf("cosim %s cfg %s%s%s: %llu cycles, %llu inputs, %llu results delivered, %llu out_valid cycles compared, "
                "%llu input bubbles, %llu output stalls: %llu mismatches (%.2f s)\n",
                unit, cfg, in_reg ? " in_reg" : "", out_skid ? " out_skid" : "", (unsigned long long)n[0],
                (unsigned long long)n[1], (unsigned long long)n[2], compared, (unsigned long long)n[3],
                (unsigned long long)n[4], mismatches, t_both);
#ifdef NP_COSIM_HATCH
    std::printf("results with ink (c < 255): %llu of %llu\n", ink, (unsigned long long)n[2]);
#else
    (void)ink;
#endif
    if (aac_bits) {
        // How the compared windows spread over the counts: each value 0..16 with its number of cycles.
        static const char *const name[4] = {"s", "sd", "sn", "ss"};
        std::printf("counts over the compared cycles:");
        for (unsigned k = 0; k < 4; k++) {
            unsigned distinct = 0;
            std::printf("%s %s", k ? ";" : "", name[k]);
            for (unsigned v = 0; v <= 16; v++)
                if (hist[k][v]) {
                    distinct++;
                    std::printf(" %u:%llu", v, hist[k][v]);
                }
            std::printf(" (%u values)", distinct);
        }
        std::printf("\n");
    }
    np_cosim_close(m);

    if (bench && mismatches == 0) {
        // The same stimulus (same seed) through each model alone. The
        // stimulus generator runs in both loops (it lives in np_cosim), so
        // the two figures carry the same overhead.
        np_cosim *mm = open_model();
        np_cosim_cycle d{};
        auto t1 = std::chrono::steady_clock::now();
        for (unsigned long long cy = 0; cy < cycles; cy++) {
            np_cosim_drive(mm, &d, traffic);
            np_cosim_eval(mm, &d);
            np_cosim_clock(mm, &d);
        }
        double t_model = seconds_since(t1);
        np_cosim_close(mm);
        // The Verilated RTL alone: the same generator, moved on by the RTL's
        // own in_ready (equal to the model's, as the lock-step run showed).
        np_cosim *g = open_model();
        Rtl r2;
        r2.bus_bits = aac_bits;
        r2.nin = nin;
#ifdef NP_COSIM_WAVE
        r2.regs(*np_cosim_wave_regs(g));
#endif
#ifdef NP_COSIM_TEXEL
        r2.regs(*np_cosim_tex_regs(g));
#endif
        r2.reset();
        np_cosim_cycle e{};
        auto t2 = std::chrono::steady_clock::now();
        for (unsigned long long cy = 0; cy < cycles; cy++) {
            np_cosim_drive(g, &e, traffic);
            r2.drive(e);
            e.in_ready = r2.top->in_ready;
            r2.edge();
            np_cosim_accept(g, &e);
        }
        double t_rtl = seconds_since(t2);
        np_cosim_close(g);
        std::printf("bench %s cfg %s%s: C cycle model %.3g cycles/s, Verilated RTL %.3g cycles/s, "
                    "both in lock step %.3g cycles/s (same stimulus, %llu cycles); "
                    "the C cycle model is %.2fx the Verilated RTL's speed\n",
                    unit, cfg, traffic ? " with bubbles and stalls" : " streaming", cycles / t_model,
                    cycles / t_rtl, cycles / t_both, cycles, t_rtl / t_model);
    }
    return mismatches == 0 ? 0 : 1;
}
