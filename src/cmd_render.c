/* SPDX-License-Identifier: MIT */
#include "np_cli.h"
#include "np_cmd.h"

int np_cmd_render(int argc, char **argv)
{
    (void)argc;
    (void)argv;
    np_err("render", "not implemented yet");
    return NP_EXIT_USAGE;
}
