# SPDX-License-Identifier: MIT
# Reference RTL of the hatching unit (rtl_model/verilog/np_hatch.v, np_hatch_seed.v) under Icarus
# Verilog and Verilator, with the mechanisms of rtl.cmake (np_rtl_builds, np_rtl_gen, np_rtl_check,
# np_rtl_cosim_build, np_rtl_cosim); docs/rtl.md and docs/hatch.md ("Reference RTL") say what each
# test checks and what it costs. Names: rtl.hatch.<sim>.build[.<fault>], rtl.hatch.<sim>.golden.<set>,
# rtl.hatch.<sim>.l1.lanes4, rtl.hatch.<sim>.fault_<f>, rtl.hatch.cosim.*.
# The unit is large (64 seed datapaths at the default, 256 for best64; the bench holds 8 DUTs): the
# Verilated bench takes about 3 minutes of CPU to build and Icarus 10-95 s a set, so the default
# suite runs Icarus on the default and fkm16_l1 sets and the fault copies on fkm16_l1, and the
# co-simulation (one DUT, Verilated); every set under both simulators with
# -DNOISEPIPE_FULL_RTL_TESTS=ON.
if(NOT COMMAND np_rtl_check)
  return()
endif()
set(NP_RTL_HT_RTL ${NP_RTL_SRC}/np_hatch.v ${NP_RTL_SRC}/np_hatch_seed.v ${NP_RTL_PIPE_SRC})
set(NP_RTL_HT_SRC ${NP_RTL_TB}/rtl_hatch_tb.v ${NP_RTL_HT_RTL})
# fault_flip: bit 0 of c flipped when the colour word is 5 mod 16 (inked points only);
# fault_stall: bank S0 overwrites its content when its successor stalls.
if(NOISEPIPE_FULL_RTL_TESTS)
  np_rtl_builds(hatch ok rtl_hatch_tb ${NP_RTL_HT_SRC})
else()  # np_rtl_builds' Icarus half: the Verilated bench is for the full set
  file(MAKE_DIRECTORY ${NP_RTL_WORK}/hatch/ok)
  np_rtl_test(rtl.hatch.icarus.build "${NP_IVERILOG}" pass "" "rtl"
    ${NP_IVERILOG} -g2012 -Wall -I${NP_RTL_SRC} -o ${NP_RTL_WORK}/hatch/ok/rtl_hatch_tb.vvp -s rtl_hatch_tb ${NP_RTL_HT_SRC})
  set_tests_properties(rtl.hatch.icarus.build PROPERTIES FIXTURES_SETUP rtl_hatch_icarus_ok)
endif()
foreach(v fault_flip fault_stall)
  np_rtl_builds(hatch ${v} rtl_hatch_tb ${NP_RTL_HT_SRC})
endforeach()
set(ht_dir ${PROJECT_SOURCE_DIR}/vectors/hatch)
set(ht_vec ${NP_RTL_WORK}/hatch/vec)
set(ht_pass "In [1-9][0-9]* tests, no errors found\\.")
# bench cfg | checked-in file
set(NP_RTL_HT_GOLDEN "default|hatch-l1-seed1" "fkm16_l1|hatch-l1-seed1-fkm16_l1" "onebyone|hatch-l1-seed1-onebyone"
  "best64|hatch-l1-seed1-best64" "g0|hatch-l1-seed1-g0" "rot45|hatch-l1-seed1-rot45" "opts|hatch-l1-seed1")
set(sims icarus)
if(NOISEPIPE_FULL_RTL_TESTS)
  set(sims icarus verilator)
  np_rtl_gen(hatch l1 lanes4 "lanes=4")
endif()
set(ht_golden)
foreach(gs ${NP_RTL_HT_GOLDEN})
  if(NOISEPIPE_FULL_RTL_TESTS OR gs MATCHES "^(default|fkm16_l1)[|]")
    list(APPEND ht_golden "${gs}")
  endif()
endforeach()
foreach(sim ${sims})
  np_rtl_golden_sets(hatch ${sim} rtl_hatch_tb ${ht_dir} "${ht_pass}" 3334 ${ht_golden})
  if(NOISEPIPE_FULL_RTL_TESTS)
    np_rtl_check(rtl.hatch.${sim}.l1.lanes4 hatch ${sim} ok rtl_hatch_tb lanes4 ${ht_vec}/hatch-l1-lanes4.memh pass
      "${ht_pass}" "rtl;nosan" rtl_hatch_l1_lanes4)
  endif()
  np_rtl_check(rtl.hatch.${sim}.fault_flip hatch ${sim} fault_flip rtl_hatch_tb fkm16_l1
    ${ht_dir}/hatch-l1-seed1-fkm16_l1.memh fail "In 2383 tests, [1-9][0-9]* errors found" "rtl;nosan")
  np_rtl_check(rtl.hatch.${sim}.fault_stall hatch ${sim} fault_stall rtl_hatch_tb fkm16_l1
    ${ht_dir}/hatch-l1-seed1-fkm16_l1.memh fail "no output for 1000 cycles|errors found" "rtl;nosan")
  # A set for another configuration than the DUT's is refused.
  np_rtl_check(rtl.hatch.${sim}.wrong_cfg hatch ${sim} ok rtl_hatch_tb fkm16_l1 ${ht_dir}/hatch-l1-seed1.memh fail
    "is for another configuration than cfg fkm16_l1" "rtl;nosan")
endforeach()

# Co-simulation against the hatch cycle model (np_cosim.c through the registry, cosim_main.cpp):
# every cycle in_ready, out_valid and c; random inputs (each field a random word of its width),
# random bubbles and stalls.
np_rtl_cosim_build(hatch default np_hatch "" "" ${NP_RTL_HT_RTL})
np_rtl_cosim(rtl.hatch.cosim.default hatch default pass "1000000 cycles, .* 0 mismatches" --cycles 1000000)
np_rtl_cosim(rtl.hatch.cosim.wrong_cfg hatch default fail "this binary is the RTL of --unit hatch"
  --cfg set=best16,layers=4,fade=onebyone,guard=9,lanes=1,rot=pin,inv_len=1024,inv_wid=8533 --cycles 10)
# The fault copies (Verilated at -O0: about 1 minute of CPU each to build) must show mismatches within
# 20,000 cycles; in the default suite Icarus catches the same two faults on the golden set (above).
if(NOISEPIPE_FULL_RTL_TESTS)
  foreach(f flip stall)
    string(TOUPPER ${f} F)
    np_rtl_cosim_build(hatch fault_${f} np_hatch "-DNP_FAULT_${F}" "" ${NP_RTL_HT_RTL})
    np_rtl_cosim(rtl.hatch.cosim.fault_${f} hatch fault_${f} fail "[1-9][0-9]* mismatches" --cycles 20000)
  endforeach()
endif()
