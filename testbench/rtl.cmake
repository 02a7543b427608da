# SPDX-License-Identifier: MIT
# Reference RTL (rtl_model/verilog/) under Icarus Verilog and Verilator;
# docs/rtl.md says what each test checks. Names:
#   rtl.<unit>.<sim>.build[.<fault>]       compile the bench (fixture)
#   rtl.<unit>.gen.<level>.<cfg>           vectors at that configuration (fixture)
#   rtl.<unit>.<sim>.golden.default        the checked-in golden set
#   rtl.<unit>.<sim>.<level>.<cfg>         a set generated at <cfg> (l1: ~4k, l2: ~10^6 vectors)
#   rtl.<unit>.<sim>.<fault>               the bench on a fault-injected RTL copy must fail
#   rtl.classic3.<sim>.<variant>[.<what>]  the circuit variants S_TABLE, HASH_SERIAL, LERP_SERIAL
#                                          (s_table, hash_serial, both, l_serial): golden, cheap,
#                                          l2, fault; l_serial also .table (with S_TABLE), .wide_l
# Verilator tests are labelled "nosan" (the C sanitizers do not reach them,
# and the sanitizer pass need not pay for their builds); so is the slow Icarus
# level-2 run. Without iverilog or verilator the tests report themselves skipped.
find_program(NP_VERILATOR verilator)
if(NOT NP_VERILATOR)
  message(STATUS "verilator not found: the rtl.*.verilator.* tests will be skipped (apt-get install verilator)")
endif()
# Every Verilated build compiles Verilator's runtime again (verilated.cpp, verilated_threads.cpp,
# and verilated_timing.cpp for --binary: about 5 s of CPU of a 10-20 s build). With ccache (Debian's
# ccache, in .ci/debian-packages) each is compiled once per set of flags and the other builds take it
# from a cache in this build tree (CCACHE_DIR below: nothing is kept from another build or machine);
# the design's own files differ from build to build and always compile. Without ccache, as before.
find_program(NP_CCACHE ccache)
set(NP_VERILATOR_CACHE)
if(NP_CCACHE)
  set(NP_VERILATOR_CACHE -MAKEFLAGS OBJCACHE=${NP_CCACHE})
endif()
set(NP_RTL_SRC ${PROJECT_SOURCE_DIR}/rtl_model/verilog)
set(NP_RTL_TB ${CMAKE_CURRENT_SOURCE_DIR}/rtl)
set(NP_RTL_WORK ${CMAKE_CURRENT_BINARY_DIR}/rtl)
set(NP_RTL_RUN ${NP_RTL_TB}/rtl_run.cmake)
# The pipe's handshake (np_pipe_ctrl.v: every unit but classic3, simplexn and classicn, which keep
# their own) and options (np_pipe_opts.v around np_pipe_in_reg.v and np_pipe_skid.v; those three
# instantiate the two directly). The three are built with the whole list; they leave the two unused.
set(NP_RTL_PIPE_SRC ${NP_RTL_SRC}/np_pipe_ctrl.v ${NP_RTL_SRC}/np_pipe_opts.v ${NP_RTL_SRC}/np_pipe_in_reg.v
  ${NP_RTL_SRC}/np_pipe_skid.v)

# np_rtl_test(name tool expect pattern labels command...): expect pass or fail.
# An Icarus or Verilator build or run, or a Yosys check, is labelled nosan too: iverilog, vvp, yosys and
# the Verilated models are not built with the sanitizers, so the sanitizer pass would only run the
# same tool again (the Icarus runs were about 60 % of that pass's test time). The vector generation (rtl.*.gen.*, noisepipe) stays in it.
function(np_rtl_test name tool expect pattern labels)
  if(tool AND (tool STREQUAL "${NP_IVERILOG}" OR tool STREQUAL "${NP_VVP}" OR tool STREQUAL "${NP_YOSYS}"
               OR tool STREQUAL "${NP_VERILATOR}")
     AND NOT labels MATCHES "nosan")
    set(labels "${labels};nosan")
  endif()
  string(JOIN "|" cmd ${ARGN})
  add_test(NAME ${name} COMMAND ${CMAKE_COMMAND} "-DTOOL=${tool}" -DEXPECT=${expect}
    "-DPATTERN=${pattern}" "-DCMD=${cmd}" -P ${NP_RTL_RUN})
  set_tests_properties(${name} PROPERTIES TIMEOUT 900 LABELS "${labels}"
    SKIP_REGULAR_EXPRESSION "rtl: SKIPPED: " ENVIRONMENT "CCACHE_DIR=${NP_RTL_WORK}/ccache")
endfunction()

# Bench builds of <unit>: variant ok, fault_flip, fault_stall (the RTL with
# `define NP_FAULT_FLIP / NP_FAULT_STALL), or for classic3's circuit variants
# fault_stable, fault_serial, fault_lserial (NP_FAULT_STABLE / NP_FAULT_SERIAL / NP_FAULT_LSERIAL).
# Fixtures rtl_<unit>_<sim>_<variant>. -I${NP_RTL_TB}: the benches' shared np_tb_vec.vh.
# A fault copy only runs the golden set (4,224 vectors), so its Verilated C++ is compiled at -O0:
# classic3's bench (17 DUT instances) builds in 19 s instead of 27 s on an idle core.
function(np_rtl_builds unit variant top)
  set(defs)
  set(vopt)
  if(variant MATCHES "^fault_(flip|stall|stable|serial|lserial|mirror|fold|foldsign|setup|drop)$")
    string(TOUPPER "${variant}" def)
    set(defs -DNP_${def})
    set(vopt -MAKEFLAGS OPT_FAST=-O0 -MAKEFLAGS OPT_SLOW=-O0 -MAKEFLAGS OPT_GLOBAL=-O0)
  endif()
  set(dir ${NP_RTL_WORK}/${unit}/${variant})
  file(MAKE_DIRECTORY ${dir})
  set(sfx "")
  if(NOT variant STREQUAL "ok")
    set(sfx ".${variant}")
  endif()
  np_rtl_test(rtl.${unit}.icarus.build${sfx} "${NP_IVERILOG}" pass "" "rtl"
    ${NP_IVERILOG} -g2012 -Wall -I${NP_RTL_SRC} -I${NP_RTL_TB} ${defs} -o ${dir}/${top}.vvp -s ${top} ${ARGN})
  set_tests_properties(rtl.${unit}.icarus.build${sfx} PROPERTIES FIXTURES_SETUP rtl_${unit}_icarus_${variant})
  # The Verilator copy of a fault bench checks the same bench source Icarus checks in every
  # build: registered only with -DNOISEPIPE_FULL_RTL_TESTS=ON (np_rtl_check skips its runs too).
  if(defs AND NOT NOISEPIPE_FULL_RTL_TESTS)
    return()
  endif()
  np_rtl_test(rtl.${unit}.verilator.build${sfx} "${NP_VERILATOR}" pass "" "rtl;nosan"
    ${NP_VERILATOR} --binary -j 1 -Wall -I${NP_RTL_SRC} -I${NP_RTL_TB} ${defs} ${vopt} ${NP_VERILATOR_CACHE} --top-module ${top} -Mdir ${dir}/verilator -o ${top} ${ARGN})
  set_tests_properties(rtl.${unit}.verilator.build${sfx} PROPERTIES
    FIXTURES_SETUP rtl_${unit}_verilator_${variant})
endfunction()

# np_rtl_golden_sets(unit sim tb dir pass cycles sets...): the bench tb (plain build) on each
# checked-in set "cfg|file" (dir/file.memh at the bench's +cfg=cfg), passing with the verdict pass;
# the default set's run also pins the cycles the bench takes (throughput and latency under its
# bubbles and stalls).
function(np_rtl_golden_sets unit sim tb dir pass cycles)
  foreach(gs ${ARGN})
    string(REPLACE "|" ";" gl "${gs}")
    list(GET gl 0 gcfg)
    list(GET gl 1 gfile)
    set(pat "${pass}")
    if(gcfg STREQUAL "default")
      set(pat "${cycles} cycles: ${pass}")
    endif()
    np_rtl_check(rtl.${unit}.${sim}.golden.${gcfg} ${unit} ${sim} ok ${tb} ${gcfg} ${dir}/${gfile}.memh pass
      "${pat}" "rtl")
  endforeach()
endfunction()

# Vector set <unit>-<level>-<cfg>.memh; config "" = the default. Fixture rtl_<unit>_<level>_<cfg>.
function(np_rtl_gen unit level cfg config)
  file(MAKE_DIRECTORY ${NP_RTL_WORK}/${unit}/vec)
  set(args vectors --unit ${unit} --format readmemh -o ${NP_RTL_WORK}/${unit}/vec/${unit}-${level}-${cfg}.memh)
  if(level STREQUAL "l2")
    list(APPEND args --level 2)
  else()
    list(APPEND args --level 1)
  endif()
  if(config)
    list(APPEND args --config ${config})
  endif()
  set(labels "rtl")
  if(level STREQUAL "l2")
    set(labels "rtl;nosan")
  endif()
  np_rtl_test(rtl.${unit}.gen.${level}.${cfg} "$<TARGET_FILE:noisepipe>" pass "" "${labels}"
    $<TARGET_FILE:noisepipe> ${args})
  set_tests_properties(rtl.${unit}.gen.${level}.${cfg} PROPERTIES FIXTURES_SETUP rtl_${unit}_${level}_${cfg})
endfunction()

# Run the bench of <sim> (icarus | verilator) on a vector file.
#   np_rtl_check(name unit sim variant top cfg file expect pattern labels fixtures...)
function(np_rtl_check name unit sim variant top cfg file expect pattern labels)
  set(dir ${NP_RTL_WORK}/${unit}/${variant})
  if(sim STREQUAL "icarus")
    set(cmd ${NP_VVP} -n ${dir}/${top}.vvp)
    set(tool "${NP_VVP}")
  else()
    if(variant MATCHES "^fault_" AND NOT NOISEPIPE_FULL_RTL_TESTS)
      return()  # its build is not registered (np_rtl_builds)
    endif()
    set(cmd ${dir}/verilator/${top})
    set(tool "${NP_VERILATOR}")
  endif()
  np_rtl_test(${name} "${tool}" ${expect} "${pattern}" "${labels}" ${cmd} +vectors=${file} +cfg=${cfg})
  set_tests_properties(${name} PROPERTIES FIXTURES_REQUIRED "rtl_${unit}_${sim}_${variant};${ARGN}")
endfunction()

# ------------------------------------------------------------------ classic3
set(NP_RTL_C3_SRC ${NP_RTL_TB}/rtl_classic3_tb.v ${NP_RTL_SRC}/np_classic3.v ${NP_RTL_PIPE_SRC})
foreach(v ok fault_flip fault_stall fault_stable fault_serial fault_lserial)
  np_rtl_builds(classic3 ${v} rtl_classic3_tb ${NP_RTL_C3_SRC})
endforeach()
# The configurations of rtl_classic3_tb.v's table (name and config string).
set(NP_RTL_C3_CFGS default s_frac10 cheap exact_s wide_l opts)
set(NP_RTL_C3_default "")
set(NP_RTL_C3_s_frac10 "out_bits=8,s_frac=10,lerp_frac=11")
set(NP_RTL_C3_cheap "out_bits=8,s_frac=4,lerp_frac=6")
set(NP_RTL_C3_exact_s "out_bits=12,s_frac=24,lerp_frac=30")
set(NP_RTL_C3_wide_l "out_bits=15,s_frac=3,lerp_frac=20")
set(NP_RTL_C3_opts "") # the default configuration with the input register and the skid buffer
# The circuit variants (np_classic3.v's S_TABLE, HASH_SERIAL, LERP_SERIAL; docs/rtl.md): test name,
# then the bench's +cfg names at the default and at cheap (out_bits=8 s_frac=4 lerp_frac=6), and the
# fault builds that must be caught. HASH_SERIAL and LERP_SERIAL deliver one result per 8 clocks; the
# bench takes it.
# name | bench cfg | cheap cfg | fault copies | cycles the bench takes for the golden set's 4,224
# vectors (pins each variant's throughput and latency: the pipeline's 6,084 with the bench's
# bubbles and stalls; 1 / 8 clocks: 8 x 4,224 plus the latency, 16 for HASH_SERIAL, 17 for LERP_SERIAL)
set(NP_RTL_C3_VARIANTS "s_table|s_table|st_cheap|fault_stable|6084" "hash_serial|h_serial|hs_cheap|fault_serial|33806"
  "both|both|bo_cheap|fault_stable,fault_serial|33806" "l_serial|l_serial|ls_cheap|fault_lserial|33807")
set(c3_vec ${NP_RTL_WORK}/classic3/vec)
set(c3_golden ${PROJECT_SOURCE_DIR}/vectors/classic3/classic3-l1-seed1.memh)
set(pass_re "In [1-9][0-9]* tests, no errors found\\.")
foreach(sim icarus verilator)
  np_rtl_check(rtl.classic3.${sim}.golden.default classic3 ${sim} ok rtl_classic3_tb default
    ${c3_golden} pass "6084 cycles: ${pass_re}" "rtl")
  np_rtl_check(rtl.classic3.${sim}.golden.opts classic3 ${sim} ok rtl_classic3_tb opts
    ${c3_golden} pass "${pass_re}" "rtl")
  foreach(g cheap wide_l)  # the checked-in sets at non-default configurations
    np_rtl_check(rtl.classic3.${sim}.golden.${g} classic3 ${sim} ok rtl_classic3_tb ${g}
      ${PROJECT_SOURCE_DIR}/vectors/classic3/classic3-l1-seed1-${g}.memh pass "${pass_re}" "rtl")
  endforeach()
  foreach(cfg ${NP_RTL_C3_CFGS})
    if(NOT cfg STREQUAL "default" AND NOT cfg STREQUAL "opts")
      np_rtl_check(rtl.classic3.${sim}.l1.${cfg} classic3 ${sim} ok rtl_classic3_tb ${cfg}
        ${c3_vec}/classic3-l1-${cfg}.memh pass "${pass_re}" "rtl" rtl_classic3_l1_${cfg})
    endif()
  endforeach()
  # Faults: a flipped datapath bit and a broken stall path must each be caught.
  np_rtl_check(rtl.classic3.${sim}.fault_flip classic3 ${sim} fault_flip rtl_classic3_tb default
    ${c3_golden} fail "In 4224 tests, [1-9][0-9]* errors found" "rtl")
  np_rtl_check(rtl.classic3.${sim}.fault_stall classic3 ${sim} fault_stall rtl_classic3_tb default
    ${c3_golden} fail "no output for 1000 cycles|errors found" "rtl")
  # The variants: the golden set (default configuration), the checked-in cheap set, and each
  # variant's fault copy must fail on the golden set.
  foreach(vr ${NP_RTL_C3_VARIANTS})
    string(REPLACE "|" ";" vl "${vr}")
    list(GET vl 0 vname)
    list(GET vl 1 vcfg)
    list(GET vl 2 vcheap)
    list(GET vl 3 vfaults)
    list(GET vl 4 vcycles)
    np_rtl_check(rtl.classic3.${sim}.${vname} classic3 ${sim} ok rtl_classic3_tb ${vcfg}
      ${c3_golden} pass "${vcycles} cycles: ${pass_re}" "rtl")
    np_rtl_check(rtl.classic3.${sim}.${vname}.cheap classic3 ${sim} ok rtl_classic3_tb ${vcheap}
      ${PROJECT_SOURCE_DIR}/vectors/classic3/classic3-l1-seed1-cheap.memh pass "${pass_re}" "rtl")
    string(REPLACE "," ";" vfaults "${vfaults}")
    foreach(flt ${vfaults})
      set(tname rtl.classic3.${sim}.${vname}.fault)
      if(vname STREQUAL "both")
        set(tname ${tname}_${flt})
        string(REPLACE "fault_fault_" "fault_" tname "${tname}")
      endif()
      np_rtl_check(${tname} classic3 ${sim} ${flt} rtl_classic3_tb ${vcfg}
        ${c3_golden} fail "In 4224 tests, [1-9][0-9]* errors found" "rtl")
    endforeach()
  endforeach()
  # LERP_SERIAL with the table s-curve (default configuration), and at wide_l (lerp_frac=20 >
  # s_frac + 8: level-1 lerps shift left, not round): the checked-in sets, under Verilator only
  # (Icarus takes about 8 s a set at 8 clocks a result; the lerp engine is the same code).
  if(sim STREQUAL "verilator")
    np_rtl_check(rtl.classic3.${sim}.l_serial.table classic3 ${sim} ok rtl_classic3_tb ls_table
      ${c3_golden} pass "${pass_re}" "rtl")
    np_rtl_check(rtl.classic3.${sim}.l_serial.wide_l classic3 ${sim} ok rtl_classic3_tb ls_wide
      ${PROJECT_SOURCE_DIR}/vectors/classic3/classic3-l1-seed1-wide_l.memh pass "${pass_re}" "rtl")
  endif()
  # S_TABLE at the widest table: s_frac=24 (25-bit entries), the level-1 set of exact_s.
  np_rtl_check(rtl.classic3.${sim}.s_table.exact_s classic3 ${sim} ok rtl_classic3_tb st_exact
    ${c3_vec}/classic3-l1-exact_s.memh pass "${pass_re}" "rtl" rtl_classic3_l1_exact_s)
endforeach()
foreach(cfg ${NP_RTL_C3_CFGS})
  if(NOT cfg STREQUAL "default" AND NOT cfg STREQUAL "opts")
    np_rtl_gen(classic3 l1 ${cfg} "${NP_RTL_C3_${cfg}}")
  endif()
  if(NOT cfg STREQUAL "opts")
    np_rtl_gen(classic3 l2 ${cfg} "${NP_RTL_C3_${cfg}}")
    np_rtl_check(rtl.classic3.verilator.l2.${cfg} classic3 verilator ok rtl_classic3_tb ${cfg}
      ${c3_vec}/classic3-l2-${cfg}.memh pass "In 10[0-9][0-9][0-9][0-9][0-9] tests, no errors found\\." "rtl;nosan"
      rtl_classic3_l2_${cfg})
  endif()
endforeach()
np_rtl_check(rtl.classic3.verilator.l2.opts classic3 verilator ok rtl_classic3_tb opts
  ${c3_vec}/classic3-l2-default.memh pass "In 1031952 tests, no errors found\\." "rtl;nosan" rtl_classic3_l2_default)
# The variants on the level-2 set of the default configuration (Icarus: with the slow tests below).
foreach(vr "s_table;s_table" "hash_serial;h_serial" "both;both" "l_serial;l_serial")
  list(GET vr 0 vname)
  list(GET vr 1 vcfg)
  np_rtl_check(rtl.classic3.verilator.${vname}.l2 classic3 verilator ok rtl_classic3_tb ${vcfg}
    ${c3_vec}/classic3-l2-default.memh pass "In 1031952 tests, no errors found\\." "rtl;nosan" rtl_classic3_l2_default)
  if(NOISEPIPE_SLOW_TESTS)
    np_rtl_check(rtl.classic3.icarus.${vname}.l2 classic3 icarus ok rtl_classic3_tb ${vcfg}
      ${c3_vec}/classic3-l2-default.memh pass "In 1031952 tests, no errors found\\." "rtl;nosan;slow"
      rtl_classic3_l2_default)
  endif()
endforeach()
# Icarus runs about 5,000 vectors/s here: level 2 only at the default, 4-8 minutes on one core,
# so only with -DNOISEPIPE_SLOW_TESTS=ON (Verilator runs the level-2 sets in every build).
if(NOISEPIPE_SLOW_TESTS)
  np_rtl_check(rtl.classic3.icarus.l2.default classic3 icarus ok rtl_classic3_tb default
    ${c3_vec}/classic3-l2-default.memh pass "In 1031952 tests, no errors found\\." "rtl;nosan;slow"
    rtl_classic3_l2_default)
endif()

# ------------------------------------------------------------------ co-simulation
# The C side (np_cosim.c: the cycle model and the stimulus) is a static
# library built with the project's flags; each Verilated build links it,
# with the unit registry (np_tools: np_cosim_open_spec opens its units).
add_library(np_cosim STATIC ${NP_RTL_TB}/np_cosim.c)
target_link_libraries(np_cosim PUBLIC np_tools np_rtl_model)
np_project_target(np_cosim)

# np_rtl_cosim_build(unit name top rtl_defines gparams sources...): a Verilated
# co-simulation binary ${NP_RTL_WORK}/<unit>/cosim-<name>/cosim. Fixture rtl_<unit>_cosim_<name>.
function(np_rtl_cosim_build unit name top defs gparams)
  set(dir ${NP_RTL_WORK}/${unit}/cosim-${name})
  file(MAKE_DIRECTORY ${dir})
  set(cflags "-I${NP_RTL_TB} -O2")
  set(model)
  set(vopt)
  if(unit STREQUAL "simplex3")
    string(APPEND cflags " -DNP_COSIM_SIMPLEX")
  elseif(unit STREQUAL "wave")  # the harness sets np_wave's register inputs: it needs np_wave.h and TRAINS
    set(trains 2)
    if(gparams MATCHES "-GTRAINS=([0-9]+)")
      set(trains ${CMAKE_MATCH_1})
    endif()
    string(APPEND cflags " -DNP_COSIM_WAVE -DNP_COSIM_TRAINS=${trains} -I${PROJECT_SOURCE_DIR}/rtl_model")
  elseif(unit STREQUAL "aacount")  # the harness checks --cfg against the RTL's parameters (np_aacount.v's defaults)
    set(acfg)
    foreach(kv M=3 DEPTH=1 NORMAL=1 LUMA=1 LUMA_TAPS=4 C_D=1000000 C_N=32 C_S=128 T_MIN=16 T_EDGE=32)
      string(REPLACE "=" ";" kv "${kv}")
      list(GET kv 0 key)
      list(GET kv 1 val)
      if(gparams MATCHES "(^|;)-G${key}=([0-9]+'d)?([0-9]+)")  # 8'd255 or 255
        set(val ${CMAKE_MATCH_3})
      endif()
      list(APPEND acfg ${val})
    endforeach()
    string(JOIN "," acfg ${acfg})
    string(APPEND cflags " -DNP_COSIM_AACOUNT -DNP_COSIM_AAC_CFG=${acfg}")
  elseif(unit STREQUAL "texel" OR unit STREQUAL "fdiff")
    # np_texel.v (np_fdiff.v: the same ports) against the registry's stream model of texel (np_cosim_open_spec: np_span_sim):
    # gparams give every key of the unit as the parameter of its name in capitals, N_OCT (the
    # RTL's octave lanes: the texture's n_oct, which the harness checks) and -GTEXTURE=<name>,
    # which is not a parameter (the texture whose registers drive the register inputs): taken
    # out of the Verilator command here and given to the model as texture=<name>.
    set(keys)
    set(vg)
    set(noct 1)
    set(tex)
    foreach(g ${gparams})
      if(g MATCHES "^-GTEXTURE=(.+)$")
        set(tex ${CMAKE_MATCH_1})
        continue()
      endif()
      list(APPEND vg ${g})
      string(REGEX REPLACE "^-G([A-Z_]+)=(.*)$" "\\1;\\2" kv "${g}")
      list(GET kv 0 key)
      list(GET kv 1 val)
      if(key STREQUAL "N_OCT")
        set(noct ${val})
      else()
        string(TOLOWER ${key} key)
        list(APPEND keys ${key}=${val})
      endif()
    endforeach()
    if(NOT tex)
      message(FATAL_ERROR "np_rtl_cosim_build(${unit} ${name}): gparams must name -GTEXTURE=<texture>")
    endif()
    set(gparams ${vg})
    string(JOIN "," keys texture=${tex} ${keys})
    set(model ${unit})
    string(APPEND cflags " -DNP_COSIM_NDIM=${unit} -DNP_COSIM_TEXEL=${noct} -DNP_COSIM_KEYS=${keys} -I${PROJECT_SOURCE_DIR}/rtl_model")
    if(name MATCHES "^fault_")
      set(vopt -MAKEFLAGS OPT_FAST=-O0 -MAKEFLAGS OPT_SLOW=-O0 -MAKEFLAGS OPT_GLOBAL=-O0)
    endif()
    set_property(GLOBAL PROPERTY np_cosim_unit_${unit}_${name} "${model}")
    set_property(GLOBAL PROPERTY np_cosim_keys_${unit}_${name} "${keys}")
  elseif(unit STREQUAL "hatch")
    # np_hatch.v against the registry's hatch (np_cosim_open_spec): gparams are np_hatch.v's
    # parameters (the keys in capitals, SET, FADE and ROT as the indices of their words; INV_LEN,
    # INV_WID 0 or absent: the key's default for the set); every key goes to the model.
    set(hv SET 1 LAYERS 4 FADE 0 GUARD 9 LANES 1 ROT 0 INV_LEN 0 INV_WID 0)
    set(keys)
    foreach(key SET LAYERS FADE GUARD LANES ROT INV_LEN INV_WID)
      list(FIND hv ${key} at)
      math(EXPR at "${at} + 1")
      list(GET hv ${at} val)
      if(gparams MATCHES "(^|;)-G${key}=([0-9]+'d)?([0-9]+)")
        set(val ${CMAKE_MATCH_3})
      endif()
      set(hk_${key} ${val})
    endforeach()
    set(hw_set fkm16 best16 fkm64 best64)
    set(hw_fade smooth onebyone)
    set(hw_rot pin 0 45 90 1e-4)
    list(GET hw_set ${hk_SET} hs)
    list(GET hw_fade ${hk_FADE} hf)
    list(GET hw_rot ${hk_ROT} hr)
    if(hk_INV_LEN EQUAL 0)
      set(hk_INV_LEN 1024)
      if(hk_SET GREATER 1)
        set(hk_INV_LEN 2048)
      endif()
    endif()
    if(hk_INV_WID EQUAL 0)
      set(hk_INV_WID 8533)
      if(hk_SET GREATER 1)
        set(hk_INV_WID 17067)
      endif()
    endif()
    set(keys "set=${hs},layers=${hk_LAYERS},fade=${hf},guard=${hk_GUARD},lanes=${hk_LANES},rot=${hr},inv_len=${hk_INV_LEN},inv_wid=${hk_INV_WID}")
    set(model hatch)
    string(APPEND cflags " -DNP_COSIM_NDIM=hatch -DNP_COSIM_HATCH -DNP_COSIM_KEYS=${keys}")
    set_property(GLOBAL PROPERTY np_cosim_unit_${unit}_${name} "${model}")
    set_property(GLOBAL PROPERTY np_cosim_keys_${unit}_${name} "${keys}")
  elseif(unit STREQUAL "simplexn" OR unit STREQUAL "classicn")
    # The n-D RTL against the registry's unit of its DIMS (simplex2/4/5, simplexn3; classic2/4/5,
    # classic3, which is the family's n = 3): gparams must set DIMS and every other key of that
    # unit, each the parameter of its name in capitals (IN_REG, OUT_SKID are the pipe options, not
    # keys). The harness refuses a --unit or --cfg other than these; np_rtl_cosim passes them.
    if(NOT gparams MATCHES "(^|;)-GDIMS=([2-5])(;|$)")
      message(FATAL_ERROR "np_rtl_cosim_build(${unit} ${name}): gparams must set -GDIMS=2..5")
    endif()
    set(dims ${CMAKE_MATCH_2})
    string(REGEX REPLACE "n$" "" model ${unit})
    if(dims EQUAL 3 AND unit STREQUAL "simplexn")
      set(model simplexn3)
    else()
      set(model ${model}${dims})
    endif()
    set(keys)
    foreach(g ${gparams})
      string(REGEX REPLACE "^-G([A-Z_]+)=(.*)$" "\\1;\\2" kv "${g}")
      list(GET kv 0 key)
      list(GET kv 1 val)
      string(TOLOWER ${key} key)
      if(NOT key MATCHES "^(in_reg|out_skid)$" AND NOT (model STREQUAL "classic3" AND key STREQUAL "dims"))
        list(APPEND keys ${key}=${val})
      endif()
    endforeach()
    string(JOIN "," keys ${keys})
    string(APPEND cflags " -DNP_COSIM_NDIM=${model} -DNP_COSIM_KEYS=${keys}")
    set_property(GLOBAL PROPERTY np_cosim_unit_${unit}_${name} "${model}")
    set_property(GLOBAL PROPERTY np_cosim_keys_${unit}_${name} "${keys}")
  endif()
  # A fault copy runs only until its mismatches show (20,000 to 100,000 cycles): its Verilated C++
  # at -O0, as np_rtl_builds' fault benches (simplexn n = 4: 17.5 s -> 10.2 s to build, 0.5 s to run).
  if(name MATCHES "^fault_")
    set(vopt -MAKEFLAGS OPT_FAST=-O0 -MAKEFLAGS OPT_SLOW=-O0 -MAKEFLAGS OPT_GLOBAL=-O0)
  endif()
  # np_cosim, the registry it opens units from (np_tools), the models, and what np_tools links.
  set(libs "$<TARGET_FILE:np_cosim> $<TARGET_FILE:np_tools> $<TARGET_FILE:np_rtl_model> -lm -lpthread")
  np_rtl_test(rtl.${unit}.cosim.build.${name} "${NP_VERILATOR}" pass "" "rtl;nosan"
    ${NP_VERILATOR} --cc --exe --build -j 1 -Wall -I${NP_RTL_SRC} ${defs} ${gparams} ${NP_VERILATOR_CACHE} --top-module ${top} --prefix Vcosim
    -Mdir ${dir} -o cosim -CFLAGS ${cflags} -LDFLAGS "${libs}" ${vopt}
    ${NP_RTL_TB}/cosim_main.cpp ${ARGN})
  set_tests_properties(rtl.${unit}.cosim.build.${name} PROPERTIES FIXTURES_SETUP rtl_${unit}_cosim_${name})
endfunction()

# np_rtl_cosim(test unit name expect pattern args...); an n-D build's run gets --unit (the registry
# unit) and, unless args give one, --cfg (the keys it was built with).
function(np_rtl_cosim test unit name expect pattern)
  get_property(model GLOBAL PROPERTY np_cosim_unit_${unit}_${name})
  set(args --unit ${unit} ${ARGN})
  if(model)
    get_property(keys GLOBAL PROPERTY np_cosim_keys_${unit}_${name})
    set(args --unit ${model})
    if(NOT "--cfg" IN_LIST ARGN)
      list(APPEND args --cfg ${keys})
    endif()
    list(APPEND args ${ARGN})
  endif()
  np_rtl_test(${test} "${NP_VERILATOR}" ${expect} "${pattern}" "rtl;nosan"
    ${NP_RTL_WORK}/${unit}/cosim-${name}/cosim ${args})
  set_tests_properties(${test} PROPERTIES FIXTURES_REQUIRED rtl_${unit}_cosim_${name})
endfunction()

set(NP_RTL_C3_RTL ${NP_RTL_SRC}/np_classic3.v ${NP_RTL_PIPE_SRC})
np_rtl_cosim_build(classic3 default np_classic3 "" "" ${NP_RTL_C3_RTL})
np_rtl_cosim_build(classic3 opts np_classic3 "" "-GIN_REG=1;-GOUT_SKID=1" ${NP_RTL_C3_RTL})
np_rtl_cosim_build(classic3 cheap np_classic3 "" "-GS_FRAC=4;-GLERP_FRAC=6" ${NP_RTL_C3_RTL})
# S_TABLE keeps the timing, so the cycle model applies to it; HASH_SERIAL's does not (docs/rtl.md).
np_rtl_cosim_build(classic3 s_table np_classic3 "" "-GS_TABLE=1" ${NP_RTL_C3_RTL})
np_rtl_cosim_build(classic3 fault_flip np_classic3 "-DNP_FAULT_FLIP" "" ${NP_RTL_C3_RTL})
np_rtl_cosim_build(classic3 fault_stall np_classic3 "-DNP_FAULT_STALL" "" ${NP_RTL_C3_RTL})
set(cosim_ok "cycles, .* 0 mismatches")
np_rtl_cosim(rtl.classic3.cosim.default classic3 default pass "1000000 cycles, .* 0 mismatches"
  --cfg 8,12,11 --cycles 1000000 --bench)
np_rtl_cosim(rtl.classic3.cosim.stream classic3 default pass "${cosim_ok}"
  --cfg 8,12,11 --cycles 100000 --no-traffic)
np_rtl_cosim(rtl.classic3.cosim.opts classic3 opts pass "1000000 cycles, .* 0 mismatches"
  --cfg 8,12,11 --in-reg --out-skid --cycles 1000000)
np_rtl_cosim(rtl.classic3.cosim.cheap classic3 cheap pass "${cosim_ok}" --cfg 8,4,6 --cycles 300000)
np_rtl_cosim(rtl.classic3.cosim.s_table classic3 s_table pass "${cosim_ok}" --cfg 8,12,11 --cycles 300000)
# A cycle-level trace of a run (format: docs/rtl.md), 2000 cycles.
np_rtl_cosim(rtl.classic3.cosim.trace classic3 default pass "trace: 2000 cycles written to"
  --cfg 8,12,11 --cycles 2000 --trace ${NP_RTL_WORK}/classic3/cosim-trace.txt)
# The options must show: the plain model against the RTL with options differs.
np_rtl_cosim(rtl.classic3.cosim.opts_differ classic3 opts fail "[1-9][0-9]* mismatches"
  --cfg 8,12,11 --cycles 10000)
np_rtl_cosim(rtl.classic3.cosim.fault_flip classic3 fault_flip fail "[1-9][0-9]* mismatches"
  --cfg 8,12,11 --cycles 100000)
np_rtl_cosim(rtl.classic3.cosim.fault_stall classic3 fault_stall fail "[1-9][0-9]* mismatches"
  --cfg 8,12,11 --cycles 100000)

# ------------------------------------------------------------------ simplex3
set(NP_RTL_S3_RTL ${NP_RTL_SRC}/np_simplex3.v ${NP_RTL_PIPE_SRC})
set(NP_RTL_S3_SRC ${NP_RTL_TB}/rtl_simplex3_tb.v ${NP_RTL_S3_RTL})
foreach(v ok fault_flip fault_stall)
  np_rtl_builds(simplex3 ${v} rtl_simplex3_tb ${NP_RTL_S3_SRC})
endforeach()
# The configurations of rtl_simplex3_tb.v's table.
set(NP_RTL_S3_CFGS default f_only t1 narrow wide_p coarse)
set(NP_RTL_S3_default "")
set(NP_RTL_S3_f_only "deriv=0")   # f only: 9 banks, default widths t23 p20 k22
set(NP_RTL_S3_t1 "t_frac=1")      # the output saturates; intermediates exceed their nominal ranges
set(NP_RTL_S3_narrow "out_bits=8,dout_bits=8")
set(NP_RTL_S3_wide_p "out_bits=12,dout_bits=10,t_frac=10,p_frac=30,k_frac=4")
set(NP_RTL_S3_coarse "t_frac=20,p_frac=14,k_frac=16")  # checked-in set: catches e_neg_after, kd_3kf, tau_rounded
set(s3_vec ${NP_RTL_WORK}/simplex3/vec)
set(s3_golden ${PROJECT_SOURCE_DIR}/vectors/simplex3/simplex3-l1-seed1.memh)
foreach(sim icarus verilator)
  np_rtl_check(rtl.simplex3.${sim}.golden.default simplex3 ${sim} ok rtl_simplex3_tb default
    ${s3_golden} pass "${pass_re}" "rtl")
  np_rtl_check(rtl.simplex3.${sim}.golden.opts simplex3 ${sim} ok rtl_simplex3_tb opts
    ${s3_golden} pass "${pass_re}" "rtl")
  foreach(g t1 coarse)
    np_rtl_check(rtl.simplex3.${sim}.golden.${g} simplex3 ${sim} ok rtl_simplex3_tb ${g}
      ${PROJECT_SOURCE_DIR}/vectors/simplex3/simplex3-l1-seed1-${g}.memh pass "${pass_re}" "rtl")
  endforeach()
  foreach(cfg ${NP_RTL_S3_CFGS})
    if(NOT cfg STREQUAL "default")
      np_rtl_check(rtl.simplex3.${sim}.l1.${cfg} simplex3 ${sim} ok rtl_simplex3_tb ${cfg}
        ${s3_vec}/simplex3-l1-${cfg}.memh pass "${pass_re}" "rtl" rtl_simplex3_l1_${cfg})
    endif()
  endforeach()
  np_rtl_check(rtl.simplex3.${sim}.fault_flip simplex3 ${sim} fault_flip rtl_simplex3_tb default
    ${s3_golden} fail "In 1520 tests, [1-9][0-9]* errors found" "rtl")
  np_rtl_check(rtl.simplex3.${sim}.fault_stall simplex3 ${sim} fault_stall rtl_simplex3_tb default
    ${s3_golden} fail "no output for 1000 cycles|errors found" "rtl")
endforeach()
foreach(cfg ${NP_RTL_S3_CFGS})
  if(NOT cfg STREQUAL "default")
    np_rtl_gen(simplex3 l1 ${cfg} "${NP_RTL_S3_${cfg}}")
  endif()
  np_rtl_gen(simplex3 l2 ${cfg} "${NP_RTL_S3_${cfg}}")
  np_rtl_check(rtl.simplex3.verilator.l2.${cfg} simplex3 verilator ok rtl_simplex3_tb ${cfg}
    ${s3_vec}/simplex3-l2-${cfg}.memh pass "In 10[0-9][0-9][0-9][0-9][0-9] tests, no errors found\\." "rtl;nosan"
    rtl_simplex3_l2_${cfg})
endforeach()
np_rtl_check(rtl.simplex3.verilator.l2.opts simplex3 verilator ok rtl_simplex3_tb opts
  ${s3_vec}/simplex3-l2-default.memh pass "In 10[0-9][0-9][0-9][0-9][0-9] tests, no errors found\\." "rtl;nosan"
  rtl_simplex3_l2_default)

# Co-simulation of simplex3: the default, f only, t_frac = 1, the options, a fault.
np_rtl_cosim_build(simplex3 default np_simplex3 "" "" ${NP_RTL_S3_RTL})
np_rtl_cosim_build(simplex3 f_only np_simplex3 "" "-GDERIV=0;-GT_FRAC=23;-GP_FRAC=20" ${NP_RTL_S3_RTL})
np_rtl_cosim_build(simplex3 t1 np_simplex3 "" "-GT_FRAC=1" ${NP_RTL_S3_RTL})
np_rtl_cosim_build(simplex3 opts np_simplex3 "" "-GIN_REG=1;-GOUT_SKID=1" ${NP_RTL_S3_RTL})
np_rtl_cosim_build(simplex3 fault_stall np_simplex3 "-DNP_FAULT_STALL" "" ${NP_RTL_S3_RTL})
np_rtl_cosim(rtl.simplex3.cosim.default simplex3 default pass "1000000 cycles, .* 0 mismatches"
  --cfg 16,16,1,24,22,22 --cycles 1000000 --bench)
np_rtl_cosim(rtl.simplex3.cosim.f_only simplex3 f_only pass "${cosim_ok}" --cfg 16,16,0,23,20,22 --cycles 300000)
np_rtl_cosim(rtl.simplex3.cosim.t1 simplex3 t1 pass "${cosim_ok}" --cfg 16,16,1,1,22,22 --cycles 300000)
np_rtl_cosim(rtl.simplex3.cosim.opts simplex3 opts pass "1000000 cycles, .* 0 mismatches"
  --cfg 16,16,1,24,22,22 --in-reg --out-skid --cycles 1000000)
np_rtl_cosim(rtl.simplex3.cosim.fault_stall simplex3 fault_stall fail "[1-9][0-9]* mismatches"
  --cfg 16,16,1,24,22,22 --cycles 100000)

# ------------------------------------------------------------------ aacount
# The parallel variant (np_aacount.v, docs/aacount.md "Reference RTL"): the checked-in golden set
# (default configuration) under both simulators, with the options; level-1 sets at the other
# configurations of rtl_aacount_tb.v's table under Verilator (Icarus: m2 and m4); level 2 at the
# default under Verilator (2,552,496 windows, about 40 s); the fault copies on the golden set.
set(NP_RTL_AAC_RTL ${NP_RTL_SRC}/np_aacount.v ${NP_RTL_PIPE_SRC})
set(NP_RTL_AAC_SRC ${NP_RTL_TB}/rtl_aacount_tb.v ${NP_RTL_AAC_RTL})
foreach(v ok fault_flip fault_stall)
  np_rtl_builds(aacount ${v} rtl_aacount_tb ${NP_RTL_AAC_SRC})
endforeach()
set(NP_RTL_AAC_CFGS m2 m4 m1 taps5 strict)
set(NP_RTL_AAC_m2 "m=2")
set(NP_RTL_AAC_m4 "m=4,normal=0,luma_taps=5")  # m = 4 with normals is 808 bits: over a vector line
set(NP_RTL_AAC_m1 "m=1")
set(NP_RTL_AAC_taps5 "depth=0,luma_taps=5,c_n=60,c_s=40,t_min=8,t_edge=64")
set(NP_RTL_AAC_strict "luma=0,c_d=4000000000,c_n=255")
set(aac_vec ${NP_RTL_WORK}/aacount/vec)
set(aac_golden ${PROJECT_SOURCE_DIR}/vectors/aacount/aacount-l1-seed1.memh)
foreach(cfg ${NP_RTL_AAC_CFGS})
  np_rtl_gen(aacount l1 ${cfg} "${NP_RTL_AAC_${cfg}}")
endforeach()
np_rtl_gen(aacount l2 default "")
foreach(sim icarus verilator)
  np_rtl_check(rtl.aacount.${sim}.golden.default aacount ${sim} ok rtl_aacount_tb default
    ${aac_golden} pass "7563 cycles: ${pass_re}" "rtl")
  np_rtl_check(rtl.aacount.${sim}.golden.opts aacount ${sim} ok rtl_aacount_tb opts
    ${aac_golden} pass "${pass_re}" "rtl")
  foreach(cfg ${NP_RTL_AAC_CFGS})
    if(sim STREQUAL "verilator" OR cfg STREQUAL "m2" OR cfg STREQUAL "m4")
      np_rtl_check(rtl.aacount.${sim}.l1.${cfg} aacount ${sim} ok rtl_aacount_tb ${cfg}
        ${aac_vec}/aacount-l1-${cfg}.memh pass "${pass_re}" "rtl" rtl_aacount_l1_${cfg})
    endif()
  endforeach()
  np_rtl_check(rtl.aacount.${sim}.fault_flip aacount ${sim} fault_flip rtl_aacount_tb default
    ${aac_golden} fail "In 5040 tests, [1-9][0-9]* errors found" "rtl")
  np_rtl_check(rtl.aacount.${sim}.fault_stall aacount ${sim} fault_stall rtl_aacount_tb default
    ${aac_golden} fail "no output for 1000 cycles|errors found" "rtl")
endforeach()
np_rtl_check(rtl.aacount.verilator.l2.default aacount verilator ok rtl_aacount_tb default
  ${aac_vec}/aacount-l2-default.memh pass "In 2552496 tests, no errors found\\." "rtl;nosan" rtl_aacount_l2_default)

# Co-simulation against the parallel cycle model (np_cosim.c, cosim_main.cpp): every cycle in_ready,
# out_valid, s, mask, sd, sn, ss; random windows with edges (np_cosim.c random_window), random
# bubbles and stalls. --cfg: m,depth,normal,luma,luma_taps,c_d,c_n,c_s,t_min,t_edge.
np_rtl_cosim_build(aacount default np_aacount "" "" ${NP_RTL_AAC_RTL})
np_rtl_cosim_build(aacount opts np_aacount "" "-GIN_REG=1;-GOUT_SKID=1" ${NP_RTL_AAC_RTL})
np_rtl_cosim_build(aacount m4 np_aacount "" "-GM=4;-GNORMAL=0;-GLUMA_TAPS=5" ${NP_RTL_AAC_RTL})
np_rtl_cosim_build(aacount m2 np_aacount "" "-GM=2;-GC_D=32'd4000000000;-GC_N=8'd255;-GC_S=16'd40;-GT_MIN=8'd8;-GT_EDGE=8'd64" ${NP_RTL_AAC_RTL})
foreach(f flip stall)
  string(TOUPPER ${f} F)
  np_rtl_cosim_build(aacount fault_${f} np_aacount "-DNP_FAULT_${F}" "" ${NP_RTL_AAC_RTL})
endforeach()
set(aac_def 3,1,1,1,4,1000000,32,128,16,32)
np_rtl_cosim(rtl.aacount.cosim.default aacount default pass "1000000 cycles, .* 0 mismatches"
  --cfg ${aac_def} --cycles 1000000 --bench)
np_rtl_cosim(rtl.aacount.cosim.opts aacount opts pass "300000 cycles, .* 0 mismatches"
  --cfg ${aac_def} --in-reg --out-skid --cycles 300000)
np_rtl_cosim(rtl.aacount.cosim.m4 aacount m4 pass "300000 cycles, .* 0 mismatches"
  --cfg 4,1,0,1,5,1000000,32,128,16,32 --cycles 300000)
np_rtl_cosim(rtl.aacount.cosim.m2 aacount m2 pass "300000 cycles, .* 0 mismatches"
  --cfg 2,1,1,1,4,4000000000,255,40,8,64 --cycles 300000)
np_rtl_cosim(rtl.aacount.cosim.trace aacount default pass "trace: 2000 cycles written to"
  --cfg ${aac_def} --cycles 2000 --trace ${NP_RTL_WORK}/aacount/cosim-trace.txt)
np_rtl_cosim(rtl.aacount.cosim.wrong_cfg aacount default fail "this binary is np_aacount with --cfg 3,1,1,1,4,"
  --cfg 3,1,1,1,4,1000000,32,128,16,33 --cycles 10)
np_rtl_cosim(rtl.aacount.cosim.opts_differ aacount opts fail "[1-9][0-9]* mismatches" --cfg ${aac_def} --cycles 10000)
foreach(f flip stall)
  np_rtl_cosim(rtl.aacount.cosim.fault_${f} aacount fault_${f} fail "[1-9][0-9]* mismatches"
    --cfg ${aac_def} --cycles 100000)
endforeach()

# ------------------------------------------------------------------ DPI-C
# The models as DPI-C functions (rtl_model/verilog/dpi), built as C with the
# project's flags; the example SV bench links them (and the fault copy must fail).
add_library(np_dpi STATIC ${NP_RTL_SRC}/dpi/np_dpi.c)
target_link_libraries(np_dpi PUBLIC np_rtl_model)
np_project_target(np_dpi)
foreach(v ok fault_flip)
  set(defs)
  set(sfx "")
  if(v STREQUAL "fault_flip")
    set(defs -DNP_FAULT_FLIP)
    set(sfx ".fault_flip")
  endif()
  set(dir ${NP_RTL_WORK}/dpi/${v})
  file(MAKE_DIRECTORY ${dir})
  np_rtl_test(rtl.dpi.build${sfx} "${NP_VERILATOR}" pass "" "rtl;nosan"
    ${NP_VERILATOR} --binary -j 1 -Wall -I${NP_RTL_SRC} -I${NP_RTL_TB} ${defs} ${NP_VERILATOR_CACHE} --top-module dpi_classic3_tb -Mdir ${dir} -o dpi_classic3_tb
    ${NP_RTL_SRC}/dpi/np_dpi_pkg.sv ${NP_RTL_TB}/dpi_classic3_tb.sv ${NP_RTL_C3_RTL}
    $<TARGET_FILE:np_dpi> $<TARGET_FILE:np_rtl_model>)
  set_tests_properties(rtl.dpi.build${sfx} PROPERTIES FIXTURES_SETUP rtl_dpi_${v})
endforeach()
np_rtl_test(rtl.dpi.classic3 "${NP_VERILATOR}" pass "200000 transactions in [0-9]+ cycles: 0 scoreboard errors"
  "rtl;nosan" ${NP_RTL_WORK}/dpi/ok/dpi_classic3_tb)
set_tests_properties(rtl.dpi.classic3 PROPERTIES FIXTURES_REQUIRED rtl_dpi_ok)
np_rtl_test(rtl.dpi.classic3.fault_flip "${NP_VERILATOR}" fail "[1-9][0-9]* scoreboard errors, [1-9][0-9]* lock-step mismatches"
  "rtl;nosan" ${NP_RTL_WORK}/dpi/fault_flip/dpi_classic3_tb)
set_tests_properties(rtl.dpi.classic3.fault_flip PROPERTIES FIXTURES_REQUIRED rtl_dpi_fault_flip)

# ------------------------------------------------------------------ synthesizable
# Yosys elaborates each unit (default and with the options / f only), runs proc
# and opt, and `check -assert` (no undriven or multiply driven signals, no logic loops).
find_program(NP_YOSYS yosys)
# np_rtl_yosys_check(unit name top params files...): the script yosys-<unit>-<name>.ys (top at
# params, "-set NAME value ..." or "") and the test rtl.<unit>.yosys_check.<name> that runs it.
function(np_rtl_yosys_check unit name top params)
  string(JOIN " " src ${ARGN})
  set(ys "read_verilog -I${NP_RTL_SRC} ${src}\n")
  if(params)
    string(APPEND ys "chparam ${params} ${top}\n")
  endif()
  string(APPEND ys "hierarchy -top ${top}\nproc\nopt\ncheck -assert\n")
  file(WRITE ${NP_RTL_WORK}/yosys-${unit}-${name}.ys "${ys}")
  np_rtl_test(rtl.${unit}.yosys_check.${name} "${NP_YOSYS}" pass "" "rtl"
    ${NP_YOSYS} -q -s ${NP_RTL_WORK}/yosys-${unit}-${name}.ys)
endfunction()
foreach(u "classic3;np_classic3;;default" "classic3;np_classic3;-set IN_REG 1 -set OUT_SKID 1;opts"
          "classic3;np_classic3;-set S_TABLE 1;s_table" "classic3;np_classic3;-set HASH_SERIAL 1;hash_serial"
          "classic3;np_classic3;-set S_TABLE 1 -set HASH_SERIAL 1;both"
          "classic3;np_classic3;-set LERP_SERIAL 1;l_serial" "classic3;np_classic3;-set S_TABLE 1 -set LERP_SERIAL 1;ls_table"
          "simplex3;np_simplex3;;default" "simplex3;np_simplex3;-set DERIV 0 -set T_FRAC 23 -set P_FRAC 20;f_only"
          "aacount;np_aacount;;default" "aacount;np_aacount;-set M 4 -set NORMAL 0 -set LUMA_TAPS 5;m4")
  list(GET u 0 unit)
  list(GET u 1 top)
  list(GET u 2 params)
  list(GET u 3 name)
  np_rtl_yosys_check(${unit} ${name} ${top} "${params}" ${NP_RTL_SRC}/${top}.v ${NP_RTL_PIPE_SRC})
endforeach()

# ----------------------------------------------- vector files end by count
# A $readmemh set ends where its header's "// count N" says (docs/vectors.md),
# not where a simulator's unwritten memory happens to stop the bench. Each
# bench is given the checked-in golden set with its last vector cut off, and
# the set without its count line: both must fail, naming the count.
foreach(unit classic3 simplex3 aacount)
  if(unit STREQUAL "classic3")
    set(golden ${c3_golden})
  elseif(unit STREQUAL "aacount")
    set(golden ${aac_golden})
  else()
    set(golden ${s3_golden})
  endif()
  file(MAKE_DIRECTORY ${NP_RTL_WORK}/${unit}/vec)
  file(READ ${golden} text)
  string(REGEX MATCH "// count ([0-9]+)\n" m "${text}")
  set(n ${CMAKE_MATCH_1})
  math(EXPR n_short "${n} - 1")
  string(REGEX REPLACE "[0-9a-fA-F]+\n$" "" short "${text}")
  string(REGEX REPLACE "// count [0-9]+\n" "" nocount "${text}")
  file(WRITE ${NP_RTL_WORK}/${unit}/vec/${unit}-golden-short.memh "${short}")
  file(WRITE ${NP_RTL_WORK}/${unit}/vec/${unit}-golden-nocount.memh "${nocount}")
  foreach(sim icarus verilator)
    np_rtl_check(rtl.${unit}.${sim}.count_short ${unit} ${sim} ok rtl_${unit}_tb default
      ${NP_RTL_WORK}/${unit}/vec/${unit}-golden-short.memh fail
      "the header's count is ${n} but the file holds ${n_short} vectors" "rtl")
    np_rtl_check(rtl.${unit}.${sim}.count_missing ${unit} ${sim} ok rtl_${unit}_tb default
      ${NP_RTL_WORK}/${unit}/vec/${unit}-golden-nocount.memh fail "has no '// count N' header line" "rtl")
  endforeach()
endforeach()
