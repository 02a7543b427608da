# SPDX-License-Identifier: MIT
# Reference RTL of the n-D units (rtl_model/verilog/np_simplexn.v, np_classicn.v)
# under Icarus Verilog and Verilator, through rtl.cmake's functions (np_rtl_builds,
# np_rtl_check, np_rtl_gen, np_rtl_cosim_build, np_rtl_cosim); docs/rtl.md and
# docs/noise-nd.md say what each test checks. Names:
#   rtl.simplexn.<sim>.build[.<fault>]          the bench (one DUT per configuration, fixture)
#   rtl.simplexn.<sim>.golden.<unit>[.<set>]    a checked-in set: every simplex2/4/5 set and
#                                               simplex3's three (f only: DIMS = 3 is simplex3's f)
#   rtl.simplexn.<sim>.fault_{flip,stall}       the fault copies must fail
#   rtl.simplexn.verilator.l2.simplex4          the level-2 set at one representative n
# Verilator tests are labelled "nosan", as in rtl.cmake.
if(NOT COMMAND np_rtl_check)
  return()
endif()

# np_rtl_ndim_tests(MODULE TB SETS GOLDEN4 CFG4 OPTS_CFG WRONG_CFG WRONG_MSG): under Icarus and
# Verilator, every set of SETS ("unit|set|cfg|cycles"; cycles pin the latency and throughput),
# the pipe options on GOLDEN4 (the n = 4 default set, bench cfg CFG4) at OPTS_CFG, the refusal
# of GOLDEN4 at WRONG_CFG (message WRONG_MSG), and the two fault copies on GOLDEN4.
function(np_rtl_ndim_tests module tb sets golden4 cfg4 opts_cfg wrong_cfg wrong_msg)
  set(pass_re "In [1-9][0-9]* tests, no errors found\\.")
  foreach(sim icarus verilator)
    set(lab "rtl")
    if(sim STREQUAL "verilator")
      set(lab "rtl;nosan")
    endif()
    foreach(s ${sets})
      string(REPLACE "|" ";" sl "${s}")
      list(GET sl 0 unit)
      list(GET sl 1 set)
      list(GET sl 2 cfg)
      list(GET sl 3 cycles)
      set(file ${unit}-l1-seed1)
      set(tname rtl.${module}.${sim}.golden.${unit})
      if(set)
        string(APPEND file "-${set}")
        string(APPEND tname ".${set}")
      endif()
      np_rtl_check(${tname} ${module} ${sim} ok ${tb} ${cfg}
        ${PROJECT_SOURCE_DIR}/vectors/${unit}/${file}.memh pass "${cycles} cycles: ${pass_re}" "${lab}")
    endforeach()
    # The pipe options (IN_REG, OUT_SKID: one clock more) on the n = 4 default set.
    get_filename_component(g4 ${golden4} NAME_WE)
    string(REGEX REPLACE "-.*" "" u4 ${g4})
    np_rtl_check(rtl.${module}.${sim}.golden.${u4}.opts ${module} ${sim} ok ${tb} ${opts_cfg}
      ${golden4} pass "${pass_re}" "${lab}")
    # A set for another configuration is refused (the header's config is checked).
    np_rtl_check(rtl.${module}.${sim}.wrong_config ${module} ${sim} ok ${tb} ${wrong_cfg}
      ${golden4} fail "${wrong_msg}" "${lab}")
    # Faults: a flipped bit of f and a broken stall path must each be caught.
    np_rtl_check(rtl.${module}.${sim}.fault_flip ${module} ${sim} fault_flip ${tb} ${cfg4}
      ${golden4} fail "In 1661 tests, [1-9][0-9]* errors found" "${lab}")
    np_rtl_check(rtl.${module}.${sim}.fault_stall ${module} ${sim} fault_stall ${tb} ${cfg4}
      ${golden4} fail "no output for 1000 cycles|errors found" "${lab}")
  endforeach()
endfunction()

# ------------------------------------------------------------------ simplexn
set(NP_RTL_SN_RTL ${NP_RTL_SRC}/np_simplexn.v ${NP_RTL_PIPE_SRC})
set(NP_RTL_SN_SRC ${NP_RTL_TB}/rtl_simplexn_tb.v ${NP_RTL_SN_RTL})
foreach(v ok fault_flip fault_stall)
  np_rtl_builds(simplexn ${v} rtl_simplexn_tb ${NP_RTL_SN_SRC})
endforeach()
# The checked-in sets: unit | set suffix ("" = the default set) | the bench's +cfg and the
# cycles the bench takes with its bubbles and stalls (pins the latency and the throughput).
set(NP_RTL_SN_SETS
  "simplex2||s2|1926" "simplex2|coarse|s2_coarse|1926" "simplex2|narrow|s2_narrow|1926"
  "simplex3||s3|2191" "simplex3|t1|s3_t1|2191" "simplex3|coarse|s3_coarse|2191"
  "simplex4||s4|2393" "simplex4|coarse|s4_coarse|2393" "simplex4|narrow|s4_narrow|2393"
  "simplex5||s5|2631" "simplex5|coarse|s5_coarse|2631" "simplex5|narrow|s5_narrow|2631")
set(sn_golden4 ${PROJECT_SOURCE_DIR}/vectors/simplex4/simplex4-l1-seed1.memh)
np_rtl_ndim_tests(simplexn rtl_simplexn_tb "${NP_RTL_SN_SETS}" ${sn_golden4} s4 s4_opts s2
  "is for dims=4 out_bits=16 t_frac=25 p_frac=25 k_frac=0, not for cfg s2")
# Level 2 (about 10^6 vectors) at one representative n, under Verilator.
np_rtl_gen(simplex4 l2 default "")
np_rtl_check(rtl.simplexn.verilator.l2.simplex4 simplexn verilator ok rtl_simplexn_tb s4
  ${NP_RTL_WORK}/simplex4/vec/simplex4-l2-default.memh pass "In [1-9][0-9][0-9][0-9][0-9][0-9][0-9] tests, no errors found\\."
  "rtl;nosan" rtl_simplex4_l2_default)

# ------------------------------------------------------------------ classicn
#   rtl.classicn.<sim>.build[.<fault>]          the bench (one DUT per configuration, fixture)
#   rtl.classicn.<sim>.golden.<unit>[.<set>]    a checked-in set: every classic2/4/5 set and all
#                                               three of classic3's (DIMS = 3 is classic3 bit for bit)
#   rtl.classicn.<sim>.golden.classic4.opts     IN_REG and OUT_SKID on classic4's default set
#   rtl.classicn.<sim>.wrong_config             a set for another configuration is refused
#   rtl.classicn.<sim>.fault_{flip,stall}       the fault copies must fail
set(NP_RTL_CN_RTL ${NP_RTL_SRC}/np_classicn.v ${NP_RTL_PIPE_SRC})
set(NP_RTL_CN_SRC ${NP_RTL_TB}/rtl_classicn_tb.v ${NP_RTL_CN_RTL})
foreach(v ok fault_flip fault_stall)
  np_rtl_builds(classicn ${v} rtl_classicn_tb ${NP_RTL_CN_SRC})
endforeach()
# unit | set suffix ("" = the default set) | the bench's +cfg | the cycles the bench takes with its
# bubbles and stalls (pins the latency 2n + 3 and the throughput; classic3's default set takes
# np_classic3.v's 6084 cycles).
set(NP_RTL_CN_SETS
  "classic2||c2|1944" "classic2|wide_l|c2_wide_l|1944"
  "classic3||c3|6084" "classic3|cheap|c3_cheap|6084" "classic3|wide_l|c3_wide_l|6084"
  "classic4||c4|2390" "classic4|wide_l|c4_wide_l|2390"
  "classic5||c5|2608" "classic5|wide_l|c5_wide_l|2608")
set(cn_golden4 ${PROJECT_SOURCE_DIR}/vectors/classic4/classic4-l1-seed1.memh)
np_rtl_ndim_tests(classicn rtl_classicn_tb "${NP_RTL_CN_SETS}" ${cn_golden4} c4 c4_opts c2
  "is for dims=4 out_bits=8 s_frac=12 lerp_frac=10, not for cfg c2")
