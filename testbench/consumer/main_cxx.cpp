// SPDX-License-Identifier: MIT
// The C++ consumer of the installed package, as a Verilator or SystemC
// testbench would use it: every public header is usable from C++ (extern "C",
// no C11-only keywords), the bit-exact model is the scoreboard, and the
// cycle-accurate pipe runs clock by clock. Exit status 0 when every check holds.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

#include <noisepipe/np_classic.h>
#include <noisepipe/np_pipe.h>
#include <noisepipe/np_ref.h>
#include <noisepipe/np_rng.h>
#include <noisepipe/np_simplex.h>
#include <noisepipe/np_unit.h>

static int failures;

static void check(bool ok, const char *what)
{
    if (!ok) {
        std::printf("FAIL: %s\n", what);
        failures++;
    }
}

int main()
{
    const np_classic_cfg cfg = np_classic_cfg_default(8);
    const double lsb = std::ldexp(1.0, -static_cast<int>(np_classic_out_frac(&cfg)));
    const double bound = np_classic_error_bound_lsb(&cfg);

    // Random stimulus from the project's own generator; the model is the scoreboard.
    np_rng rng;
    np_rng_seed(&rng, 7);
    std::vector<np_classic_sig> in(64);
    std::vector<int32_t> want(in.size());
    for (size_t i = 0; i < in.size(); i++) {
        np_classic_sig s = {};
        s.x = static_cast<uint16_t>(np_rng_next(&rng));
        s.y = static_cast<uint16_t>(np_rng_next(&rng));
        s.z = static_cast<uint16_t>(np_rng_next(&rng));
        in[i] = s;
        want[i] = np_classic_eval(&cfg, s.x, s.y, s.z);
        double err = std::fabs(want[i] * lsb - np_ref_classic3_q88(s.x, s.y, s.z)) / lsb;
        check(err <= bound, "classic3 within its error bound of the reference");
    }

    // The registry from C++: the same bits as the direct call.
    const np_unit *u = np_unit_find("classic3");
    check(u != nullptr, "the registry has classic3");
    if (u) {
        np_unit_cfg ucfg;
        np_unit_cfg_default(u, ucfg.bytes);
        uint64_t w[3] = { in[0].x, in[0].y, in[0].z }, out = 0;
        u->eval(ucfg.bytes, w, &out);
        check(out == (static_cast<uint64_t>(static_cast<int64_t>(want[0])) & NP_MASK(8)),
              "registry eval equals np_classic_eval");
    }

    // Cycle model with a stall every third cycle: outputs in order, equal to the scoreboard.
    np_pipe pipe;
    check(np_classic_pipe_init(&pipe, &cfg) == 0, "np_classic_pipe_init");
    size_t sent = 0, got = 0;
    for (unsigned cycle = 0; cycle < 1000 && got < in.size(); cycle++) {
        np_pipe_port port = {};
        port.in_valid = sent < in.size();
        port.in_sig = port.in_valid ? &in[sent] : nullptr;
        port.out_ready = cycle % 3 != 2;
        np_pipe_eval(&pipe, &port);
        if (port.out_valid && port.out_ready) {
            const np_classic_sig *o = static_cast<const np_classic_sig *>(port.out_sig);
            check(o->out == want[got], "pipe output equals the bit-exact model");
            got++;
        }
        if (port.in_valid && port.in_ready)
            sent++;
        np_pipe_clock(&pipe, &port);
    }
    check(got == in.size(), "every input came out");
    np_pipe_free(&pipe);

    // simplex3 from C++ too (value and derivative in one call).
    const np_simplex_cfg scfg = np_simplex_cfg_default(16, 16, 1);
    check(np_simplex_cfg_check(&scfg) == nullptr, "simplex3 default configuration is valid");

    std::printf("C++ consumer: %zu outputs checked, %s (%d failures)\n", got,
                failures ? "FAILED" : "ok", failures);
    return failures ? 1 : 0;
}
