# SPDX-License-Identifier: MIT
# Reference RTL of the wave unit (rtl_model/verilog/np_wave.v, np_wave_sin.v,
# np_wave_rom.v) under Icarus Verilog and Verilator, with the mechanisms of
# rtl.cmake (np_rtl_builds, np_rtl_gen, np_rtl_check, np_rtl_cosim_build,
# np_rtl_cosim); docs/rtl.md and docs/wave.md ("Reference RTL") say what each
# test checks. Names as there: rtl.wave.<sim>.build[.<fault>],
# rtl.wave.<sim>.golden.<set>, rtl.wave.<sim>.l1.<cfg>, rtl.wave.verilator.l2.<cfg>,
# rtl.wave.<sim>.fault_<f>, rtl.wave.cosim.*, rtl.wave.rom_table, rtl.wave.yosys_check.*.
if(NOT COMMAND np_rtl_check)
  return()
endif()
set(NP_RTL_WV_RTL ${NP_RTL_SRC}/np_wave.v ${NP_RTL_SRC}/np_wave_sin.v ${NP_RTL_SRC}/np_wave_rom.v ${NP_RTL_PIPE_SRC})
set(NP_RTL_WV_SRC ${NP_RTL_TB}/rtl_wave_tb.v ${NP_RTL_WV_RTL})
# fault_flip: bit 0 of y flipped when Y's 4 low bits are 0101; fault_stall: bank M overwrites
# its content under a stall; fault_mirror: the one's complement ROM mirror 2^30 - 1 - x;
# fault_fold: det J without the jxz jzx product (the fold flag and ny wrong); fault_foldsign:
# the fold compare unsigned (the bug co-simulation once found: fold = (ny == 0), ny still right).
foreach(v ok fault_flip fault_stall fault_mirror fault_fold fault_foldsign)
  np_rtl_builds(wave ${v} rtl_wave_tb ${NP_RTL_WV_SRC})
endforeach()
# The bench's configurations without a checked-in set: level-1 sets generated here.
set(NP_RTL_WV_fold "trains=1,irr=0,cap=0,fold=1")
set(NP_RTL_WV_normals "trains=3,normals=1")
set(NP_RTL_WV_jac "normals=1,fold=1")
set(wv_vec ${NP_RTL_WORK}/wave/vec)
set(wv_dir ${PROJECT_SOURCE_DIR}/vectors/wave)
set(wv_golden ${wv_dir}/wave-l1-seed1.memh)
set(wv_pass "In [1-9][0-9]* tests, no errors found\\.")
# The checked-in sets: bench cfg | file (sincos=recurrence's seed3 has no RTL: refused by name).
set(NP_RTL_WV_GOLDEN "default|wave-l1-seed1" "opts|wave-l1-seed1" "rom6|wave-l1-seed1-rom6"
  "rom10|wave-l1-seed1-rom10" "irr0_cap0|wave-l1-seed1-irr0_cap0" "trains4|wave-l1-seed1-trains4"
  "jac|wave-l1-seed2")
foreach(sim icarus verilator)
  set(lab "rtl;nosan")  # Icarus runs are seconds each; the sanitizer pass does not reach the simulators
  np_rtl_golden_sets(wave ${sim} rtl_wave_tb ${wv_dir} "${wv_pass}" 3677 ${NP_RTL_WV_GOLDEN})
  np_rtl_check(rtl.wave.${sim}.golden.recurrence_refused wave ${sim} ok rtl_wave_tb default
    ${wv_dir}/wave-l1-seed3.memh fail "is for sincos=recurrence, which has no RTL" "${lab}")
  foreach(cfg fold normals)
    np_rtl_check(rtl.wave.${sim}.l1.${cfg} wave ${sim} ok rtl_wave_tb ${cfg} ${wv_vec}/wave-l1-${cfg}.memh pass
      "${wv_pass}" "${lab}" rtl_wave_l1_${cfg})
  endforeach()
  np_rtl_check(rtl.wave.${sim}.fault_flip wave ${sim} fault_flip rtl_wave_tb default ${wv_golden} fail
    "In 2514 tests, [1-9][0-9]* errors found" "${lab}")
  np_rtl_check(rtl.wave.${sim}.fault_stall wave ${sim} fault_stall rtl_wave_tb default ${wv_golden} fail
    "no output for 1000 cycles|errors found" "${lab}")
  np_rtl_check(rtl.wave.${sim}.fault_mirror wave ${sim} fault_mirror rtl_wave_tb default ${wv_golden} fail
    "In 2514 tests, [1-9][0-9]* errors found" "${lab}")
  np_rtl_check(rtl.wave.${sim}.fault_fold wave ${sim} fault_fold rtl_wave_tb jac ${wv_dir}/wave-l1-seed2.memh fail
    "In 2514 tests, [1-9][0-9]* errors found" "${lab}")
  np_rtl_check(rtl.wave.${sim}.fault_foldsign wave ${sim} fault_foldsign rtl_wave_tb jac ${wv_dir}/wave-l1-seed2.memh fail
    "In 2514 tests, 214 errors found" "${lab}")
  # A set that ends early, or has no count, cannot pass.
  np_rtl_check(rtl.wave.${sim}.count_short wave ${sim} ok rtl_wave_tb default ${wv_vec}/wave-golden-short.memh fail
    "the header's count is 2514 but the file holds 2513 vectors" "${lab}")
endforeach()
foreach(cfg fold normals)
  np_rtl_gen(wave l1 ${cfg} "${NP_RTL_WV_${cfg}}")
endforeach()
foreach(cfg default jac)
  np_rtl_gen(wave l2 ${cfg} "${NP_RTL_WV_${cfg}}")
  np_rtl_check(rtl.wave.verilator.l2.${cfg} wave verilator ok rtl_wave_tb ${cfg} ${wv_vec}/wave-l2-${cfg}.memh pass
    "In 1[0-9][0-9][0-9][0-9][0-9][0-9] tests, no errors found\\." "rtl;nosan" rtl_wave_l2_${cfg})
endforeach()
file(MAKE_DIRECTORY ${wv_vec})
file(READ ${wv_golden} wv_text)
string(REGEX REPLACE "[0-9a-fA-F]+\n$" "" wv_short "${wv_text}")
file(WRITE ${wv_vec}/wave-golden-short.memh "${wv_short}")

# The ROM's 1,025 words against the C model's table.
add_test(NAME rtl.wave.rom_table COMMAND ${CMAKE_COMMAND} -DC_SRC=${PROJECT_SOURCE_DIR}/rtl_model/np_wave.c
  -DV_SRC=${NP_RTL_SRC}/np_wave_rom.v -P ${NP_RTL_TB}/wave_rom_check.cmake)
set_tests_properties(rtl.wave.rom_table PROPERTIES LABELS "rtl"
  PASS_REGULAR_EXPRESSION "1025 ROM words, the RTL's equal the C model's")

# Yosys elaborates the unit: proc, opt, check -assert (default; both Jacobian outputs, 4 lanes).
foreach(u "default;" "jac;-set TRAINS 4 -set NORMALS 1 -set FOLD 1")
  list(GET u 0 name)
  list(GET u 1 params)
  np_rtl_yosys_check(wave ${name} np_wave "${params}" ${NP_RTL_WV_RTL})
endforeach()

# Co-simulation against the wave cycle model (np_cosim.c, cosim_main.cpp): every cycle in_ready,
# out_valid and each output word, random bubbles and stalls, the test register set regs=1.
np_rtl_cosim_build(wave default np_wave "" "" ${NP_RTL_WV_RTL})
np_rtl_cosim_build(wave jac np_wave "" "-GNORMALS=1;-GFOLD=1" ${NP_RTL_WV_RTL})
np_rtl_cosim_build(wave opts np_wave "" "-GIN_REG=1;-GOUT_SKID=1" ${NP_RTL_WV_RTL})
np_rtl_cosim_build(wave fold1 np_wave "" "-GTRAINS=1;-GIRR=0;-GCAP=0;-GFOLD=1;-GROM_LOG2=6" ${NP_RTL_WV_RTL})
foreach(f flip stall mirror)
  string(TOUPPER ${f} F)
  np_rtl_cosim_build(wave fault_${f} np_wave "-DNP_FAULT_${F}" "" ${NP_RTL_WV_RTL})
endforeach()
np_rtl_cosim_build(wave fault_fold np_wave "-DNP_FAULT_FOLD" "-GNORMALS=1;-GFOLD=1" ${NP_RTL_WV_RTL})
np_rtl_cosim(rtl.wave.cosim.default wave default pass "1000000 cycles, .* 0 mismatches"
  --cfg 2,1,1,8,0,0 --cycles 1000000 --bench)
np_rtl_cosim(rtl.wave.cosim.jac wave jac pass "1000000 cycles, .* 0 mismatches" --cfg 2,1,1,8,1,1 --cycles 1000000)
np_rtl_cosim(rtl.wave.cosim.opts wave opts pass "300000 cycles, .* 0 mismatches"
  --cfg 2,1,1,8,0,0 --in-reg --out-skid --cycles 300000)
np_rtl_cosim(rtl.wave.cosim.fold1 wave fold1 pass "300000 cycles, .* 0 mismatches" --cfg 1,0,0,6,0,1 --cycles 300000)
np_rtl_cosim(rtl.wave.cosim.trace wave default pass "trace: 2000 cycles written to"
  --cfg 2,1,1,8,0,0 --cycles 2000 --trace ${NP_RTL_WORK}/wave/cosim-trace.txt)
np_rtl_cosim(rtl.wave.cosim.wrong_cfg wave default fail "this binary is np_wave with TRAINS=2" --cfg 4,1,1,8,0,0 --cycles 10)
foreach(f flip stall mirror)
  np_rtl_cosim(rtl.wave.cosim.fault_${f} wave fault_${f} fail "[1-9][0-9]* mismatches" --cfg 2,1,1,8,0,0 --cycles 100000)
endforeach()
np_rtl_cosim(rtl.wave.cosim.fault_fold wave fault_fold fail "[1-9][0-9]* mismatches" --cfg 2,1,1,8,1,1 --cycles 100000)
