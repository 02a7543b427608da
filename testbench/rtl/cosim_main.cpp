// SPDX-License-Identifier: MIT
// cosim_main - drives a Verilated unit (top renamed Vcosim: np_classic3, or
// np_simplex3 with NP_COSIM_SIMPLEX) clock by clock beside the C cycle model
// (np_pipe, through np_cosim.h) with the same stimulus, and compares in_ready,
// out_valid and, when valid, every output word, every cycle.
//
//   cosim --unit classic3 --cfg 8,12,11 [--in-reg] [--out-skid] [--cycles N]
//         [--seed S] [--no-traffic] [--bench] [--trace FILE]
// --cfg lists the configuration the RTL was Verilated with (-G parameters),
// in the order of np_cosim_open. --bench also times the two models alone on
// the same stimulus and prints their cycles/s. Exit status 0: no mismatch;
// 1: a mismatch (the first 10 are printed); 2: bad usage.
//
// --trace FILE writes the cycle-level trace of the run (the ports, which
// both models drive identically when there is no mismatch), one line per
// cycle, after '#' header lines:
//   cycle in_valid in_ready x y z out_valid out_ready out...
// decimal cycle, 0/1 handshake bits, hex x y z (4 digits) and, when
// out_valid, each output word in hex (ceil(bits/4) digits), else '-'.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "Vcosim.h"
#include "np_cosim.h"
#include "verilated.h"

namespace {

struct Rtl {
    std::unique_ptr<VerilatedContext> ctx{new VerilatedContext};
    std::unique_ptr<Vcosim> top{new Vcosim{ctx.get()}};
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
    void drive(const np_cosim_cycle &c)
    {
        top->in_valid = c.in_valid;
        top->x = c.x;
        top->y = c.y;
        top->z = c.z;
        top->out_ready = c.out_ready;
        top->eval();
    }
    void outs(uint32_t o[NP_COSIM_OUTS]) const
    {
        o[0] = top->f;
#ifdef NP_COSIM_SIMPLEX
        o[1] = top->dfdx;
        o[2] = top->dfdy;
        o[3] = top->dfdz;
#else
        o[1] = o[2] = o[3] = 0;
#endif
    }
};

double seconds_since(std::chrono::steady_clock::time_point t0)
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

int usage()
{
    std::fprintf(stderr, "usage: cosim --unit U --cfg V,V,... [--in-reg] [--out-skid] [--cycles N] "
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
    std::vector<unsigned> p;
    for (const char *s = cfg; *s;) {
        char *end;
        p.push_back((unsigned)std::strtoul(s, &end, 10));
        if (end == s) return usage();
        s = *end == ',' ? end + 1 : end;
    }
    char err[200];
    np_cosim *m = np_cosim_open(unit, p.data(), (unsigned)p.size(), in_reg, out_skid, seed, err, sizeof err);
    if (!m) {
        std::fprintf(stderr, "cosim: %s\n", err);
        return 2;
    }
    const unsigned nout = np_cosim_outputs(m);
    Rtl rtl;
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
        std::fprintf(trace, "# columns cycle in_valid in_ready x y z out_valid out_ready");
        for (unsigned k = 0; k < nout; k++) std::fprintf(trace, " out%u(%u bits)", k, np_cosim_out_bits(m, k));
        std::fprintf(trace, "\n");
    }
    unsigned long long mismatches = 0, compared = 0;
    np_cosim_cycle c{};
    uint32_t ro[NP_COSIM_OUTS];
    auto t0 = std::chrono::steady_clock::now();
    for (unsigned long long cy = 0; cy < cycles; cy++) {
        np_cosim_drive(m, &c, traffic);
        np_cosim_eval(m, &c);
        rtl.drive(c);
        rtl.outs(ro);
        int bad = rtl.top->in_ready != c.in_ready || rtl.top->out_valid != c.out_valid;
        if (c.out_valid && rtl.top->out_valid) {
            compared++;
            for (unsigned k = 0; k < nout; k++) bad |= ro[k] != c.out[k];
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
    std::printf("cosim %s cfg %s%s%s: %llu cycles, %llu inputs, %llu out_valid cycles compared, %llu input bubbles, "
                "%llu output stalls: %llu mismatches (%.2f s)\n",
                unit, cfg, in_reg ? " in_reg" : "", out_skid ? " out_skid" : "", (unsigned long long)n[0],
                (unsigned long long)n[1], compared, (unsigned long long)n[3], (unsigned long long)n[4], mismatches,
                t_both);
    np_cosim_close(m);

    if (bench && mismatches == 0) {
        // The same stimulus (same seed) through each model alone. The
        // stimulus generator runs in both loops (it lives in np_cosim), so
        // the two figures carry the same overhead.
        np_cosim *mm = np_cosim_open(unit, p.data(), (unsigned)p.size(), in_reg, out_skid, seed, err, sizeof err);
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
        np_cosim *g = np_cosim_open(unit, p.data(), (unsigned)p.size(), in_reg, out_skid, seed, err, sizeof err);
        Rtl r2;
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
