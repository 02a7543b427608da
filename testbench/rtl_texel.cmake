# SPDX-License-Identifier: MIT
# Reference RTL of the per-pixel texturing unit texel (rtl_model/verilog/np_texel.v with the
# span sequencer np_span_seq.v) under Icarus Verilog and Verilator, with rtl.cmake's mechanisms
# (np_rtl_builds, np_rtl_test, np_rtl_cosim_build); docs/rtl.md and docs/fdiff.md ("Reference
# RTL of texel") say what each test checks. Names:
#   rtl.texel.regs.<texture>            the texture's registers for the bench (texel_regs; fixture)
#   rtl.texel.<sim>.build[.<fault>]     the bench (fixtures)
#   rtl.texel.<sim>.golden.default      the checked-in set vectors/texel/texel-l1-seed1.vec, its
#                                       cycle count pinned (+cycles: np_span_sim's timing)
#   rtl.texel.<sim>.fault_<f>           the fault copies must fail, for their reason
#   rtl.texel.<sim>.count_short, .wrong_regs   a set cut short, another texture's registers: refused
#   rtl.texel.lint.<cfg>                verilator --lint-only -Wall at the default and two others
if(NOT COMMAND np_rtl_builds)
  return()
endif()
# What every span unit's RTL builds on: the sequencer, the pipe's handshake, the colour banks
# (np_span_ports.vh, np_tex_quad.vh and np_tex_front.vh are included from -I${NP_RTL_SRC}).
set(NP_RTL_SPAN_SRC ${NP_RTL_SRC}/np_span_seq.v ${NP_RTL_SRC}/np_pipe_ctrl.v ${NP_RTL_SRC}/np_tex_colour.v)
set(NP_RTL_TX_RTL ${NP_RTL_SRC}/np_texel.v ${NP_RTL_SPAN_SRC})
set(NP_RTL_TX_SRC ${NP_RTL_TB}/rtl_texel_tb.v ${NP_RTL_TX_RTL})
set(tx_work ${NP_RTL_WORK}/texel)
file(MAKE_DIRECTORY ${tx_work})

# The texture registers np_ut_regs compiles for texture=NAME, as text the bench reads.
add_executable(texel_regs ${NP_RTL_TB}/texel_regs.c)
target_link_libraries(texel_regs PRIVATE np_tools)
np_project_target(texel_regs)
foreach(tex wood marble)
  add_test(NAME rtl.texel.regs.${tex} COMMAND texel_regs ${tex} ${tx_work}/regs-${tex}.txt)
  set_tests_properties(rtl.texel.regs.${tex} PROPERTIES LABELS "rtl" FIXTURES_SETUP rtl_texel_regs_${tex})
endforeach()

# fault_flip: bit 0 of cr flipped when x's 4 low bits are 0101 (bank S); fault_stall: bank I2
# overwrites its content under a stall; fault_setup: a set-up stall ends after one clock (the
# sequencer's counter): the bits stay right, the cycle count does not.
foreach(v ok fault_flip fault_stall fault_setup)
  np_rtl_builds(texel ${v} rtl_texel_tb ${NP_RTL_TX_SRC})
endforeach()

# np_rtl_span_check(name unit sim variant vec regs expect pattern plusargs...): the bench
# rtl_<unit>_tb (texel's source; fdiff's is built from it) on a vector set, with the texture
# registers of texel's fixture rtl.texel.regs.<regs> (the same np_ut_regs registers for both units).
function(np_rtl_span_check name unit sim variant vec regs expect pattern)
  set(dir ${NP_RTL_WORK}/${unit}/${variant})
  if(sim STREQUAL "icarus")
    set(cmd ${NP_VVP} -n ${dir}/rtl_${unit}_tb.vvp)
    set(tool "${NP_VVP}")
  else()
    if(variant MATCHES "^fault_" AND NOT NOISEPIPE_FULL_RTL_TESTS)
      return()  # its build is not registered (np_rtl_builds)
    endif()
    set(cmd ${dir}/verilator/rtl_${unit}_tb)
    set(tool "${NP_VERILATOR}")
  endif()
  np_rtl_test(${name} "${tool}" ${expect} "${pattern}" "rtl" ${cmd} +vectors=${vec}
    +regs=${NP_RTL_WORK}/texel/regs-${regs}.txt ${ARGN})
  set_tests_properties(${name} PROPERTIES FIXTURES_REQUIRED "rtl_${unit}_${sim}_${variant};rtl_texel_regs_${regs}")
endfunction()

# np_rtl_span_tests(unit golden cycles setup_alt faults...): under both simulators, the checked-in
# set (golden.default, its cycle count pinned), the set cut short by its last vector (count_short),
# another texture's registers (wrong_regs), and each fault copy named (fault_<f>), which must fail
# for its reason: flip, drop with errors; stall losing transactions or with errors; setup with
# the bits right and the cycle count wrong (or what setup_alt adds, "|..." or "").
function(np_rtl_span_tests unit golden cycles setup_alt)
  set(short ${NP_RTL_WORK}/${unit}/${unit}-golden-short.vec)
  file(READ ${golden} text)
  string(REGEX REPLACE "[^\n]+\n$" "" text "${text}")
  file(WRITE ${short} "${text}")
  foreach(sim icarus verilator)
    np_rtl_span_check(rtl.${unit}.${sim}.golden.default ${unit} ${sim} ok ${golden} wood pass
      "${cycles} cycles: In 977 tests, no errors found\\." +cycles=${cycles})
    np_rtl_span_check(rtl.${unit}.${sim}.count_short ${unit} ${sim} ok ${short} wood fail
      "the header's count is 977 but the file holds 976 vectors")
    np_rtl_span_check(rtl.${unit}.${sim}.wrong_regs ${unit} ${sim} ok ${golden} marble fail
      "has n_oct 4; the DUT is built for N_OCT=1")
    foreach(f ${ARGN})
      if(f STREQUAL "stall")
        set(pat "no output for 1000 cycles|errors found")
      elseif(f STREQUAL "setup")
        set(pat "all 977 tests right, but in [0-9]+ cycles, not the ${cycles}${setup_alt}")
      else()
        set(pat "In 977 tests, [1-9][0-9]* errors found")
      endif()
      np_rtl_span_check(rtl.${unit}.${sim}.fault_${f} ${unit} ${sim} fault_${f} ${golden} wood fail "${pat}"
        +cycles=${cycles})
    endforeach()
  endforeach()
endfunction()

# np_rtl_span_lint(unit top rtl_var configs...): verilator --lint-only -Wall of the files in
# ${rtl_var} at each configuration, "name -GKEY=value ..." (rtl.<unit>.lint.<name>).
function(np_rtl_span_lint unit top rtl_var)
  foreach(l ${ARGN})
    separate_arguments(l UNIX_COMMAND "${l}")
    list(GET l 0 lname)
    list(REMOVE_AT l 0)
    np_rtl_test(rtl.${unit}.lint.${lname} "${NP_VERILATOR}" pass "" "rtl;nosan"
      ${NP_VERILATOR} --lint-only -Wall -I${NP_RTL_SRC} ${l} --top-module ${top} ${${rtl_var}})
  endforeach()
endfunction()

set(tx_golden ${PROJECT_SOURCE_DIR}/vectors/texel/texel-l1-seed1.vec)
# The bench's traffic (bubbles 2/8, stalls 2/8, seed 1) on the golden set's 24 runs (133,113 pixels
# simulated, 977 compared) takes 177,709 cycles: pinned, so the timing is checked with the bits.
set(tx_cycles 177709)
np_rtl_span_tests(texel ${tx_golden} ${tx_cycles} "" flip stall setup)

# Lint at the default, at marble's four octaves with every key off its default, and at the widest
# index (I = 1, Fw = 24, G = 100: W = 126).
np_rtl_span_lint(texel np_texel NP_RTL_TX_RTL "default -GN_OCT=1"
  "oct4 -GN_OCT=4 -GIDX_INT=4 -GW_FRAC=8 -GGUARD=4 -GWEIGHT_FRAC=24 -GSETUP_MULTS=1 -GMULT_LAT=16"
  "wide -GIDX_INT=1 -GW_FRAC=24 -GGUARD=100 -GWEIGHT_FRAC=32")

# Co-simulation against the registry's stream model of texel (np_cosim_open_spec: np_span_sim with
# np_texel_engine; np_cosim.c, cosim_main.cpp): every cycle in_ready, out_valid and, when valid,
# cr cg cb, with random bubbles and stalls, random descriptors (1 in 16 empty). default: wood at
# the default keys; marble: four octaves with every numeric key off its default.
set(tx_def "-GTEXTURE=wood;-GIDX_INT=10;-GW_FRAC=12;-GGUARD=20;-GWEIGHT_FRAC=16;-GSETUP_MULTS=2;-GMULT_LAT=2;-GN_OCT=1")
np_rtl_cosim_build(texel default np_texel "" "${tx_def}" ${NP_RTL_TX_RTL})
np_rtl_cosim_build(texel marble np_texel ""
  "-GTEXTURE=marble;-GIDX_INT=9;-GW_FRAC=10;-GGUARD=6;-GWEIGHT_FRAC=8;-GSETUP_MULTS=1;-GMULT_LAT=3;-GN_OCT=4"
  ${NP_RTL_TX_RTL})
foreach(f flip stall setup)
  string(TOUPPER ${f} F)
  np_rtl_cosim_build(texel fault_${f} np_texel "-DNP_FAULT_${F}" "${tx_def}" ${NP_RTL_TX_RTL})
endforeach()
np_rtl_cosim(rtl.texel.cosim.default texel default pass "1000000 cycles, .* 0 mismatches" --cycles 1000000 --bench)
np_rtl_cosim(rtl.texel.cosim.marble texel marble pass "1000000 cycles, .* 0 mismatches" --cycles 1000000)
np_rtl_cosim(rtl.texel.cosim.trace texel default pass "trace: 2000 cycles written to" --cycles 2000
  --trace ${NP_RTL_WORK}/texel/cosim-trace.txt)
np_rtl_cosim(rtl.texel.cosim.wrong_cfg texel default fail "this binary is the RTL of --unit texel"
  --cfg texture=wood,idx_int=10,w_frac=12,guard=20,weight_frac=16,setup_mults=1,mult_lat=2 --cycles 10)
foreach(f flip stall setup)
  np_rtl_cosim(rtl.texel.cosim.fault_${f} texel fault_${f} fail "[1-9][0-9]* mismatches" --cycles 100000)
endforeach()
