/* SPDX-License-Identifier: MIT */
#include "np_cli.h"
#include "np_cmd.h"

int np_cmd_stream(int argc, char **argv)
{
    (void)argc;
    (void)argv;
    np_err("stream", "not implemented yet");
    return NP_EXIT_USAGE;
}
