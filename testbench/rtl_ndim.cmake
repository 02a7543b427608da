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
        ${PROJECT_SOURCE_DIR}/vectors/${unit}/${file}.memh pass "${cycles} cycles: ${pass_re}" "rtl")
    endforeach()
    # The pipe options (IN_REG, OUT_SKID: one clock more) on the n = 4 default set.
    get_filename_component(g4 ${golden4} NAME_WE)
    string(REGEX REPLACE "-.*" "" u4 ${g4})
    np_rtl_check(rtl.${module}.${sim}.golden.${u4}.opts ${module} ${sim} ok ${tb} ${opts_cfg}
      ${golden4} pass "${pass_re}" "rtl")
    # A set for another configuration is refused (the header's config is checked).
    np_rtl_check(rtl.${module}.${sim}.wrong_config ${module} ${sim} ok ${tb} ${wrong_cfg}
      ${golden4} fail "${wrong_msg}" "rtl")
    # Faults: a flipped bit of f and a broken stall path must each be caught.
    np_rtl_check(rtl.${module}.${sim}.fault_flip ${module} ${sim} fault_flip ${tb} ${cfg4}
      ${golden4} fail "In 1661 tests, [1-9][0-9]* errors found" "rtl")
    np_rtl_check(rtl.${module}.${sim}.fault_stall ${module} ${sim} fault_stall ${tb} ${cfg4}
      ${golden4} fail "no output for 1000 cycles|errors found" "rtl")
  endforeach()
endfunction()

# ------------------------------------------------------------------ the benches
# NP_RTL_SN_RTL, NP_RTL_CN_RTL: the RTL of each module (the co-simulation builds it too); its bench
# rtl_<module>_tb.v built plain and as the two fault copies.
foreach(m "simplexn;SN" "classicn;CN")
  list(GET m 0 module)
  list(GET m 1 key)
  set(NP_RTL_${key}_RTL ${NP_RTL_SRC}/np_${module}.v ${NP_RTL_PIPE_SRC})
  foreach(v ok fault_flip fault_stall)
    np_rtl_builds(${module} ${v} rtl_${module}_tb ${NP_RTL_TB}/rtl_${module}_tb.v ${NP_RTL_${key}_RTL})
  endforeach()
endforeach()

# ------------------------------------------------------------------ simplexn
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

# ------------------------------------------------------------------ co-simulation
# The n-D RTL against the registry's cycle model of its n (np_cosim_open_spec: simplex2/4/5 and
# simplexn3, the n-D simplex at n = 3; classic2/4/5 and classic3, the classic family's n = 3),
# every cycle in_ready, out_valid and f, with random bubbles and stalls (cosim_main.cpp). One
# Verilated build per (unit, n, configuration), shared by its runs. Names:
#   rtl.<module>.cosim.build.<name>   the Verilated RTL with the harness (fixture)
#   rtl.<module>.cosim.<name>         a run: 0 mismatches; or, for a fault copy, caught
# The default configuration of each n, every key written out (the -G parameters and --cfg).
set(NP_COSIM_SN_s2 "-GDIMS=2;-GOUT_BITS=16;-GT_FRAC=25;-GP_FRAC=25")
set(NP_COSIM_SN_s3 "-GDIMS=3;-GOUT_BITS=16;-GT_FRAC=23;-GP_FRAC=20;-GK_FRAC=22")
set(NP_COSIM_SN_s4 "-GDIMS=4;-GOUT_BITS=16;-GT_FRAC=25;-GP_FRAC=25")
set(NP_COSIM_SN_s5 "-GDIMS=5;-GOUT_BITS=16;-GT_FRAC=25;-GP_FRAC=25")
set(NP_COSIM_CN_c2 "-GDIMS=2;-GOUT_BITS=8;-GS_FRAC=12;-GLERP_FRAC=11")
set(NP_COSIM_CN_c3 "-GDIMS=3;-GOUT_BITS=8;-GS_FRAC=12;-GLERP_FRAC=11")
set(NP_COSIM_CN_c4 "-GDIMS=4;-GOUT_BITS=8;-GS_FRAC=12;-GLERP_FRAC=10")
set(NP_COSIM_CN_c5 "-GDIMS=5;-GOUT_BITS=8;-GS_FRAC=12;-GLERP_FRAC=10")
# Other configurations (the benches' s3_coarse, s5_narrow, c4_wide_l): K_FRAC off its default at
# n = 3; the widest f (20 bits) with t_frac = 3, where P2 and P4 round hardest; and every classic
# key off its default (s_frac = 3 < lerp_frac = 12).
set(NP_COSIM_SN_s3_coarse "-GDIMS=3;-GOUT_BITS=16;-GT_FRAC=20;-GP_FRAC=14;-GK_FRAC=16")
set(NP_COSIM_SN_s5_narrow "-GDIMS=5;-GOUT_BITS=20;-GT_FRAC=3;-GP_FRAC=14")
set(NP_COSIM_CN_c4_wide_l "-GDIMS=4;-GOUT_BITS=12;-GS_FRAC=3;-GLERP_FRAC=12")
# The fault copies (np_simplexn.v, np_classicn.v: NP_FAULT_FLIP flips bit 0 of f on about 1 input
# in 16, NP_FAULT_STALL lets a bank load while its successor stalls) at n = 4, the default.
set(NP_COSIM_SN_fault_flip "${NP_COSIM_SN_s4}")
set(NP_COSIM_SN_fault_stall "${NP_COSIM_SN_s4}")
set(NP_COSIM_CN_fault_flip "${NP_COSIM_CN_c4}")
set(NP_COSIM_CN_fault_stall "${NP_COSIM_CN_c4}")
# Every build runs in CI except the defaults at n = 3 and 4 (s3 s4 c3 c4): n = 3 is checked against
# the 3-D units by the golden sets and by s3_coarse, n = 4 by c4_wide_l and the fault copies; they are
# registered with -DNOISEPIPE_FULL_RTL_TESTS=ON (4 Verilator builds fewer in CI).
set(NP_COSIM_SN_names s2 s5 s3_coarse s5_narrow fault_flip fault_stall)
set(NP_COSIM_CN_names c2 c5 c4_wide_l fault_flip fault_stall)
if(NOISEPIPE_FULL_RTL_TESTS)
  list(APPEND NP_COSIM_SN_names s3 s4)
  list(APPEND NP_COSIM_CN_names c3 c4)
endif()
foreach(m "simplexn;SN;${NP_COSIM_SN_names}" "classicn;CN;${NP_COSIM_CN_names}")
  list(POP_FRONT m module key)
  foreach(name ${m})
    set(defs "")
    if(name MATCHES "^fault_")
      string(TOUPPER "NP_${name}" def)
      set(defs "-D${def}")
    endif()
    np_rtl_cosim_build(${module} ${name} np_${module} "${defs}" "${NP_COSIM_${key}_${name}}" ${NP_RTL_${key}_RTL})
  endforeach()
endforeach()
# 10^6 cycles at each default (1 to 7 s a run: docs/rtl.md), 300,000 at the others; the fault copies
# must show mismatches within 20,000 cycles (the first at cycles 72 and 37 (flip), 225 (stall)).
set(cosim_1m "1000000 cycles, .* 0 mismatches")
foreach(name ${NP_COSIM_SN_names} ${NP_COSIM_CN_names})
  if(name MATCHES "^fault_")
    continue()
  endif()
  set(module simplexn)
  if(name MATCHES "^c")
    set(module classicn)
  endif()
  if(name MATCHES "_")
    np_rtl_cosim(rtl.${module}.cosim.${name} ${module} ${name} pass "300000 cycles, .* 0 mismatches" --cycles 300000)
  else()
    np_rtl_cosim(rtl.${module}.cosim.${name} ${module} ${name} pass "${cosim_1m}" --cycles 1000000)
  endif()
endforeach()
foreach(module simplexn classicn)
  foreach(f flip stall)
    np_rtl_cosim(rtl.${module}.cosim.fault_${f} ${module} fault_${f} fail "20000 cycles, .* [1-9][0-9]* mismatches" --cycles 20000)
  endforeach()
endforeach()
# The binary refuses a configuration or a unit other than its RTL's (the run would compare two
# different circuits), and writes the cycle trace with the n-D inputs (the 80-bit port at n = 5).
np_rtl_cosim(rtl.simplexn.cosim.wrong_cfg simplexn s2 fail
  "this binary is the RTL of --unit simplex2 --cfg dims=2,out_bits=16,t_frac=25,p_frac=25: the model's configuration is dims=2 out_bits=16 t_frac=24"
  --cfg dims=2,out_bits=16,t_frac=24,p_frac=25 --cycles 10)
np_rtl_cosim(rtl.classicn.cosim.wrong_unit classicn c5 fail
  "this binary is the RTL of --unit classic5 --cfg dims=5,out_bits=8,s_frac=12,lerp_frac=10"
  --unit classic3 --cfg out_bits=8,s_frac=12,lerp_frac=11 --cycles 10)
np_rtl_cosim(rtl.simplexn.cosim.trace simplexn s5 pass "trace: 2000 cycles written to"
  --cycles 2000 --trace ${NP_RTL_WORK}/simplexn/cosim-trace.txt)
