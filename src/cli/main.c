/* SPDX-License-Identifier: MIT */
/* noisepipe - one command, git style: noisepipe <command> [options]. */
#include <stdio.h>
#include <string.h>

#include "np_common.h"
#include "np_cmd.h"
#include "np_outfile.h"

static int cmd_help(int argc, char **argv);

static const np_cmd commands[] = {
    { "run", np_cmd_run, "the default job: golden vectors for the classic unit, verified on the cycle model" },
    { "units", np_cmd_units, "list the hardware units and their configuration keys" },
    { "vectors", np_cmd_vectors, "write golden test vectors (TestFloat style; text, $readmemh or .coe)" },
    { "verify", np_cmd_verify, "check vectors on the cycle-accurate model, or a device's results" },
    { "device", np_cmd_device, "act as a device: read vector lines, append the cycle model's results" },
    { "sweep", np_cmd_sweep, "exhaustive error sweep of one z slice (2^32 inputs) on all cores" },
    { "search", np_cmd_search, "adversarial error search: worst roundings, faces, extremes, hill-climb; the verdict" },
    { "bench", np_cmd_bench, "benchmark the models and the sweep, print the figures" },
    { "render", np_cmd_render, "render a scene with the float reference and the texture units (EXR + PNG)" },
    { "report", np_cmd_report, "write reports: gate and latency estimates, error against run time" },
    { "stream", np_cmd_stream, "stream vectors over USB to an FPGA board and verify the results" },
    { "wave", np_cmd_wave, "the Gerstner wave unit on a scene: frames, the check against the reference, the benchmark" },
    { "seeds", np_cmd_seeds, "de Bruijn seed sets of the hatching unit: cell proof, spacing, search" },
    { "help", cmd_help, "this list, or `noisepipe help COMMAND`" },
};
enum { N_COMMANDS = sizeof commands / sizeof commands[0] };

static const np_cmd *find(const char *name)
{
    for (unsigned i = 0; i < N_COMMANDS; i++)
        if (strcmp(commands[i].name, name) == 0)
            return &commands[i];
    return NULL;
}

static void usage(FILE *f)
{
    fputs("usage: noisepipe <command> [options]   (noisepipe <command> --help for its options)\n"
          "every command also takes --progress (progress on stderr even when it is not a terminal)\n"
          "and --quiet (no progress)\n\n"
          "commands:\n",
          f);
    for (unsigned i = 0; i < N_COMMANDS; i++)
        fprintf(f, "  %-8s %s\n", commands[i].name, commands[i].summary);
}

static int cmd_help(int argc, char **argv)
{
    if (argc >= 2) {
        const np_cmd *c = find(argv[1]);
        if (!c) {
            np_err("help", "unknown command '%s'", argv[1]);
            return NP_EXIT_USAGE;
        }
        char *args[] = { argv[1], (char *)"--help", NULL };
        return c->fn(2, args);
    }
    usage(stdout);
    return NP_EXIT_OK;
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        usage(stderr);
        return NP_EXIT_USAGE;
    }
    if (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0)
        return cmd_help(1, argv);
    const np_cmd *c = find(argv[1]);
    if (!c) {
        fprintf(stderr, "noisepipe: unknown command '%s'\n\n", argv[1]);
        usage(stderr);
        return NP_EXIT_USAGE;
    }
    np_interrupt_install();
    /*
     * --progress / --quiet are every command's: taken out here, wherever they
     * stand (stream keeps its --quiet too: there it also drops per-vector lines).
     */
    int n = 1, keep_quiet = strcmp(c->name, "stream") == 0;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--progress") == 0) {
            np_progress_set_mode(NP_PROGRESS_ALWAYS);
        } else if (strcmp(argv[i], "--quiet") == 0) {
            np_progress_set_mode(NP_PROGRESS_NEVER);
            if (keep_quiet)
                argv[n++] = argv[i];
        } else {
            argv[n++] = argv[i];
        }
    }
    argv[n] = NULL;
    argc = n;
    int rc = c->fn(argc - 1, argv + 1);
    /* Output lost on the way out (`verify > /dev/full`) is an error, never exit 0. */
    if (np_stdout_check(argv[1]) != 0)
        rc = NP_EXIT_USAGE;
    return rc;
}
