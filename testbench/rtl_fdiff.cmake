# SPDX-License-Identifier: MIT
# Reference RTL of the forward-difference unit fdiff (rtl_model/verilog/np_fdiff.v with the span
# sequencer np_span_seq.v) under Verilator (co-simulation) and Icarus/Verilator (golden bench),
# with rtl.cmake's mechanisms; docs/rtl.md and docs/fdiff.md ("Reference RTL of fdiff") say what
# each test checks. Names:
#   rtl.fdiff.lint.<cfg>               verilator --lint-only -Wall at the default and at four octaves
#   rtl.fdiff.cosim.<name>             co-simulation against np_span_sim with np_fdiff_engine
#   rtl.fdiff.<sim>.build[.<fault>]    the golden bench (testbench/rtl/rtl_texel_tb.v built with
#                                      -DNP_TB_FDIFF: module rtl_fdiff_tb; fixtures)
#   rtl.fdiff.<sim>.golden.default     the checked-in set vectors/fdiff/fdiff-l1-seed1.vec, its cycle
#                                      count pinned
#   rtl.fdiff.<sim>.count_short, .wrong_regs   a set cut short, another texture's registers: refused
#   rtl.fdiff.<sim>.fault_<f>          (NOISEPIPE_FULL_RTL_TESTS) the fault copies fail, for their reason
if(NOT COMMAND np_rtl_builds)
  return()
endif()
set(NP_RTL_FD_RTL ${NP_RTL_SRC}/np_fdiff.v ${NP_RTL_SPAN_SRC})
set(fd_work ${NP_RTL_WORK}/fdiff)
file(MAKE_DIRECTORY ${fd_work})

# Lint at the default and at marble's four octaves with the numeric keys off their defaults
# (resetup stays 0: the interval is not built).
np_rtl_span_lint(fdiff np_fdiff NP_RTL_FD_RTL "default -GN_OCT=1"
  "oct4 -GN_OCT=4 -GIDX_INT=9 -GW_FRAC=10 -GGUARD=30 -GSETUP_MULTS=1 -GMULT_LAT=3"
  "wide -GIDX_INT=1 -GW_FRAC=24 -GGUARD=100 -GSETUP_MULTS=64 -GMULT_LAT=16")

# Co-simulation against the registry's stream model of fdiff (np_cosim_open_spec: np_span_sim with
# np_fdiff_engine): every cycle in_ready, out_valid and, when valid, cr cg cb, with random bubbles
# and stalls and random descriptors (np_cosim.c). default: wood at the default keys; marble: four
# octaves with the numeric keys off their defaults.
set(fd_def "-GTEXTURE=wood;-GIDX_INT=10;-GW_FRAC=12;-GGUARD=44;-GRESETUP=0;-GSETUP_MULTS=2;-GMULT_LAT=2;-GN_OCT=1")
set(fd_marble "-GTEXTURE=marble;-GIDX_INT=9;-GW_FRAC=10;-GGUARD=30;-GRESETUP=0;-GSETUP_MULTS=1;-GMULT_LAT=3;-GN_OCT=4")
np_rtl_cosim_build(fdiff default np_fdiff "" "${fd_def}" ${NP_RTL_FD_RTL})
np_rtl_cosim_build(fdiff marble np_fdiff "" "${fd_marble}" ${NP_RTL_FD_RTL})
foreach(f flip stall setup drop)
  string(TOUPPER ${f} F)
  np_rtl_cosim_build(fdiff fault_${f} np_fdiff "-DNP_FAULT_${F}" "${fd_def}" ${NP_RTL_FD_RTL})
endforeach()
np_rtl_cosim(rtl.fdiff.cosim.default fdiff default pass "1000000 cycles, .* 0 mismatches" --cycles 1000000)
# marble (4 octaves, 1 multiplier: 21,942 pixels in 10^6 cycles, the engine's arbiter always busy) costs
# about 67 s per 10^6 cycles here: 400,000 in the default suite, 10^6 with NOISEPIPE_FULL_RTL_TESTS.
np_rtl_cosim(rtl.fdiff.cosim.marble fdiff marble pass "400000 cycles, .* 0 mismatches" --cycles 400000)
if(NOISEPIPE_FULL_RTL_TESTS)
  np_rtl_cosim(rtl.fdiff.cosim.marble_full fdiff marble pass "1000000 cycles, .* 0 mismatches" --cycles 1000000)
  # wood with three multipliers of latency 1 (slots split between jobs) and 20 guard bits.
  np_rtl_cosim_build(fdiff p3 np_fdiff ""
    "-GTEXTURE=wood;-GIDX_INT=10;-GW_FRAC=12;-GGUARD=20;-GRESETUP=0;-GSETUP_MULTS=3;-GMULT_LAT=1;-GN_OCT=1" ${NP_RTL_FD_RTL})
  np_rtl_cosim(rtl.fdiff.cosim.p3 fdiff p3 pass "1000000 cycles, .* 0 mismatches" --cycles 1000000)
endif()
foreach(f flip stall setup drop)
  np_rtl_cosim(rtl.fdiff.cosim.fault_${f} fdiff fault_${f} fail "[1-9][0-9]* mismatches" --cycles 30000)
endforeach()

# The golden bench: the texel bench's source, built for fdiff. The texture registers are texel's
# fixture (rtl.texel.regs.<texture>: the same np_ut_regs registers).
set(NP_RTL_FD_SRC -DNP_TB_FDIFF ${NP_RTL_TB}/rtl_texel_tb.v ${NP_RTL_FD_RTL})
set(fd_variants ok)
if(NOISEPIPE_FULL_RTL_TESTS)
  list(APPEND fd_variants fault_flip fault_stall fault_setup fault_drop)
endif()
foreach(v ${fd_variants})
  np_rtl_builds(fdiff ${v} rtl_fdiff_tb ${NP_RTL_FD_SRC})
endforeach()

set(fd_golden ${PROJECT_SOURCE_DIR}/vectors/fdiff/fdiff-l1-seed1.vec)
# The bench's traffic (bubbles 2/8, stalls 2/8, seed 1) on the golden set's 24 runs (133,113 pixels
# simulated, 977 compared) takes 182,155 cycles: np_span_sim's count under the same traffic
# (rtl.fdiff.bench_cycles, below), pinned, so the timing is checked with the bits.
set(fd_cycles 182155)
# The fault copies' runs (their builds: fd_variants) only with NOISEPIPE_FULL_RTL_TESTS; a wrong
# cycle count or errors both count for fault_setup.
set(fd_faults)
if(NOISEPIPE_FULL_RTL_TESTS)
  set(fd_faults flip drop stall setup)
endif()
np_rtl_span_tests(fdiff ${fd_golden} ${fd_cycles} "|errors found" ${fd_faults})

# The pinned counts from the C cycle model: span_bench_cycles replays the bench's traffic on
# np_span_sim (texel's pin too, which checks the replay itself).
add_executable(span_bench_cycles ${NP_RTL_TB}/span_bench_cycles.c)
target_link_libraries(span_bench_cycles PRIVATE np_tools)
np_project_target(span_bench_cycles)
add_test(NAME rtl.fdiff.bench_cycles COMMAND span_bench_cycles fdiff wood ${fd_golden})
set_tests_properties(rtl.fdiff.bench_cycles PROPERTIES LABELS "rtl"
  PASS_REGULAR_EXPRESSION "^fdiff: 24 runs, ${fd_cycles} cycles")
if(DEFINED tx_cycles)
  add_test(NAME rtl.texel.bench_cycles COMMAND span_bench_cycles texel wood ${tx_golden})
  set_tests_properties(rtl.texel.bench_cycles PROPERTIES LABELS "rtl"
    PASS_REGULAR_EXPRESSION "^texel: 24 runs, ${tx_cycles} cycles")
endif()
