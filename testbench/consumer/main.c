/* SPDX-License-Identifier: MIT */
/*
 * A consumer of the installed noisepipe package: evaluates the classic unit's
 * bit-exact model on a few known inputs, compares it with the float reference
 * and with the unit registry, and runs the cycle-accurate pipe for a few
 * cycles. Exit status 0 when every check holds, 1 otherwise.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>

#include <noisepipe/np_classic.h>
#include <noisepipe/np_ref.h>
#include <noisepipe/np_unit.h>

static int failures;

static void check(int ok, const char *what)
{
    if (!ok) {
        printf("FAIL: %s\n", what);
        failures++;
    }
}

int main(void)
{
    const np_classic_cfg cfg = np_classic_cfg_default(8);
    check(np_classic_cfg_check(&cfg) == NULL, "default configuration is valid");
    const double lsb = ldexp(1.0, -(int)np_classic_out_frac(&cfg));
    const double bound = np_classic_error_bound_lsb(&cfg);
    printf("classic3 out_bits=%u s_frac=%u lerp_frac=%u, error bound %.4f LSB\n", cfg.out_bits,
           cfg.s_frac, cfg.lerp_frac, bound);

    /* Lattice points: every offset is 0 or -1 and s = 0, so noise is exactly 0. */
    static const uint16_t lattice[][3] = { { 0x0000, 0x0000, 0x0000 },
                                           { 0x0100, 0x0200, 0x0300 },
                                           { 0xff00, 0xff00, 0xff00 } };
    for (unsigned i = 0; i < sizeof lattice / sizeof lattice[0]; i++) {
        int32_t v = np_classic_eval(&cfg, lattice[i][0], lattice[i][1], lattice[i][2]);
        printf("eval(%04x %04x %04x) = %d (lattice point)\n", lattice[i][0], lattice[i][1],
               lattice[i][2], (int)v);
        check(v == 0, "noise is 0 on a lattice point");
    }

    /* Inside cells: the model is within its error bound of the float reference. */
    enum { N_IN = 8 };
    static const uint16_t in[N_IN][3] = {
        { 0x0080, 0x0080, 0x0080 }, { 0x1234, 0x5678, 0x9abc }, { 0xffff, 0xffff, 0xffff },
        { 0x0001, 0x00ff, 0x7f80 }, { 0xff80, 0x0040, 0x00c0 }, { 0x5555, 0xaaaa, 0x5555 },
        { 0x0a0a, 0xb0b0, 0x0c0c }, { 0x8000, 0x8080, 0x80ff },
    };
    int32_t want[N_IN];
    const np_unit *u = np_unit_find("classic3");
    check(u != NULL, "the registry has classic3");
    np_unit_cfg ucfg;
    if (u)
        np_unit_cfg_default(u, ucfg.bytes);
    for (unsigned i = 0; i < N_IN; i++) {
        want[i] = np_classic_eval(&cfg, in[i][0], in[i][1], in[i][2]);
        double ref = np_ref_classic3_q88(in[i][0], in[i][1], in[i][2]);
        double err = fabs((double)want[i] * lsb - ref) / lsb;
        printf("eval(%04x %04x %04x) = %4d  reference %+.6f  error %.4f LSB\n", in[i][0],
               in[i][1], in[i][2], (int)want[i], ref, err);
        check(err <= bound, "model within its error bound of the reference");
        if (u) {
            uint64_t w[3] = { in[i][0], in[i][1], in[i][2] }, out = 0;
            u->eval(ucfg.bytes, w, &out);
            check(out == ((uint64_t)(int64_t)want[i] & NP_MASK(8)),
                  "registry eval equals np_classic_eval");
        }
    }

    /* Cycle model: feed the inputs back to back, downstream always ready. */
    np_pipe pipe;
    if (np_classic_pipe_init(&pipe, &cfg) != 0) {
        printf("FAIL: np_classic_pipe_init\n");
        return 1;
    }
    unsigned sent = 0, got = 0, first_out = 0;
    np_classic_sig sig = { 0 };
    for (unsigned cycle = 0; cycle < 100 && got < N_IN; cycle++) {
        np_pipe_port port = { 0 };
        if (sent < N_IN) {
            sig.x = in[sent][0];
            sig.y = in[sent][1];
            sig.z = in[sent][2];
            port.in_valid = 1;
            port.in_sig = &sig;
        }
        port.out_ready = 1;
        np_pipe_eval(&pipe, &port);
        if (port.out_valid) {
            const np_classic_sig *o = port.out_sig;
            printf("cycle %2u: out %04x %04x %04x => %4d\n", cycle, o->x, o->y, o->z, (int)o->out);
            if (got == 0)
                first_out = cycle;
            check(o->out == want[got], "pipe output equals the bit-exact model");
            got++;
        }
        if (port.in_valid && port.in_ready)
            sent++;
        np_pipe_clock(&pipe, &port);
    }
    printf("pipe: %u stages, latency %u, first output in cycle %u, %u of %u outputs\n",
           NP_CLASSIC_STAGES, np_pipe_latency(&pipe), first_out, got, (unsigned)N_IN);
    check(got == N_IN, "every input came out");
    check(first_out == np_pipe_latency(&pipe), "first output after the pipe's latency");
    np_pipe_free(&pipe);

    printf("consumer: %s (%d failures)\n", failures ? "FAILED" : "ok", failures);
    return failures ? 1 : 0;
}
