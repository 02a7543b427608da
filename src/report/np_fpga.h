/* SPDX-License-Identifier: MIT */
/*
 * np_fpga.h - `noisepipe report fpga`: a unit's reference RTL through the open
 * iCE40 flow (Yosys synth_ice40, nextpnr-ice40, icepack, icetime): LUT4s,
 * flip-flops, carries and block RAMs of the unit, logic cells of the placed
 * design, the achieved Fmax and its critical path, results per second, and
 * the bitstream (docs/fpga.md).
 *
 * The unit's ports are far more than a package's pins (aacount's input bus is
 * 472 bits), so the unit is placed inside a generated I/O harness: every input
 * bit comes from a shift register fed by one pin, every output bit is loaded
 * into a shift register read out on another. The harness's flip-flops make every
 * path of the unit a register-to-register path that nextpnr times; its cost is
 * stated beside the unit's own (Yosys counts the unit's module hierarchy alone:
 * `synth_ice40 -noflatten`, `stat -top`).
 */
#ifndef NP_FPGA_H
#define NP_FPGA_H

#include <stdint.h>

#include "np_unit.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct np_fpga_opts {
    const char *device;  /* "hx8k" (iCE40-HX8K, default) or "up5k" (iCE40-UP5K) */
    const char *package; /* NULL: the device's board package (ct256, sg48) */
    double freq_mhz;     /* nextpnr's target clock (--freq), default 12 (the boards' oscillator) */
    uint64_t seed;       /* nextpnr --seed (default 1): Fmax moves a few per cent with it */
    int retime;          /* also synthesise with synth_ice40 -retime and place that: what retiming gains */
    const char *out_dir; /* keep DIR/fpga.md and DIR/fpga-UNIT.{bin,asc,json,log} (NULL: Markdown on stdout only) */
    const char *rtl_dir; /* the RTL folder (NULL: the source tree's rtl_model/verilog) */
} np_fpga_opts;

/* Defaults: hx8k, its package, 12 MHz, seed 1. */
void np_fpga_opts_init(np_fpga_opts *o);

/*
 * The command: every unit with RTL (or only), each at its default or at spec
 * (K=V,...; --rtl-param through np_synth_set_rtl_params first). NP_EXIT_OK when
 * every unit placed, routed and packed; NP_EXIT_FAIL when one did not (it does
 * not fit the device, or the flow failed: the tool's message is printed);
 * NP_EXIT_USAGE for bad input or a tool missing.
 */
int np_report_fpga(const np_unit *only, const char *spec, const np_fpga_opts *o);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* NP_FPGA_H */
