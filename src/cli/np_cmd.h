/* SPDX-License-Identifier: MIT */
/* np_cmd.h - the noisepipe subcommands. Each returns an NP_EXIT_* status. */
#ifndef NP_CMD_H
#define NP_CMD_H

typedef int (*np_cmd_fn)(int argc, char **argv); /* argv[0] is the command name */

typedef struct np_cmd {
    const char *name;
    np_cmd_fn fn;
    const char *summary;
} np_cmd;

int np_cmd_run(int argc, char **argv);
int np_cmd_units(int argc, char **argv);
int np_cmd_vectors(int argc, char **argv);
int np_cmd_verify(int argc, char **argv);
int np_cmd_device(int argc, char **argv);
int np_cmd_sweep(int argc, char **argv);
int np_cmd_search(int argc, char **argv);
int np_cmd_bench(int argc, char **argv);
int np_cmd_render(int argc, char **argv);
int np_cmd_report(int argc, char **argv);
int np_cmd_stream(int argc, char **argv);
int np_cmd_wave(int argc, char **argv);
int np_cmd_seeds(int argc, char **argv);

#endif /* NP_CMD_H */
