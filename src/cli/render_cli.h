/* SPDX-License-Identifier: MIT */
/*
 * render_cli.h - internal to the command: `noisepipe render --aa`'s entry
 * (render_aa.c). What the render and report commands call on the renderer is
 * in src/render/np_render_tools.h and src/report/np_report_runtime.h.
 */
#ifndef RENDER_CLI_H
#define RENDER_CLI_H

#include "np_render_tools.h"
#include "np_report_runtime.h"

/* noisepipe render --aa: its options (render_aa.c), then the report (src/report/np_report_aa.h). */
int np_render_aa_main(int argc, char **argv);

#endif /* RENDER_CLI_H */
