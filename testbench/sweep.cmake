# SPDX-License-Identifier: MIT
# The exhaustive error sweep (src/sweep/sweep.c, `noisepipe sweep`) and the classic
# unit's accuracy over random inputs.
#
# This file is also the script (cmake -P) that runs the command-line checks
# registered below, which need an exact exit status or compare two outputs:
#   cmake -DNOISEPIPE=<exe> -DCHECK=exit -DARGS=<a|b|c> -DEXPECT=<status> [-DMATCH=<regex>] -P sweep.cmake
#   cmake -DNOISEPIPE=<exe> -DCHECK=resume|search_resume -DJOURNAL=<file> -P sweep.cmake
#   cmake -DNOISEPIPE=<exe> -DCHECK=usage -P sweep.cmake
if(CMAKE_SCRIPT_MODE_FILE)
  # Run noisepipe with the |-separated arguments; out: stdout + stderr.
  function(np_run args expect out)
    string(REPLACE "|" ";" argv "${args}")
    execute_process(COMMAND ${NOISEPIPE} ${argv} RESULT_VARIABLE rc OUTPUT_VARIABLE o ERROR_VARIABLE e)
    if(NOT rc STREQUAL "${expect}")
      message(FATAL_ERROR "noisepipe ${argv}: exit status ${rc}, expected ${expect}\n${o}${e}")
    endif()
    message("noisepipe ${argv} => exit ${rc}\n${o}${e}")
    set(${out} "${o}${e}" PARENT_SCOPE)
  endfunction()
  # The summary without what may differ between runs (time, resumed count).
  function(np_stable text out)
    string(REGEX REPLACE "\n(x cells|wall time)[^\n]*" "" t "${text}")
    set(${out} "${t}" PARENT_SCOPE)
  endfunction()

  if(CHECK STREQUAL "exit")
    np_run("${ARGS}" "${EXPECT}" out)
    if(DEFINED MATCH AND NOT out MATCHES "${MATCH}")
      message(FATAL_ERROR "output does not match '${MATCH}'")
    endif()
  elseif(CHECK STREQUAL "resume")
    file(REMOVE "${JOURNAL}")
    set(common "sweep|--z|0x0100|--threads|2")
    np_run("${common}|--x-cells|0:3|--journal|${JOURNAL}" 0 first)
    np_run("${common}|--x-cells|0:6|--journal|${JOURNAL}|--resume" 0 resumed)
    np_run("${common}|--x-cells|0:6" 0 whole)
    if(NOT resumed MATCHES "3 resumed from the journal")
      message(FATAL_ERROR "the resumed run did not take 3 blocks from the journal")
    endif()
    np_stable("${resumed}" a)
    np_stable("${whole}" b)
    if(NOT a STREQUAL b)
      message(FATAL_ERROR "resumed and uninterrupted summaries differ:\n${a}\n----\n${b}")
    endif()
    np_run("sweep|--z|0x0101|--x-cells|0:6|--journal|${JOURNAL}|--resume" 2 other_z)
    np_run("sweep|--z|0x0100|--config|s_frac=10|--x-cells|0:6|--journal|${JOURNAL}|--resume" 2 other_cfg)
    np_run("sweep|--z|0x0100|--x-cells|0:6|--journal|${JOURNAL}" 2 no_resume)
    if(NOT other_z MATCHES "was written for 'z=0x0100'" OR NOT other_cfg MATCHES "s_frac=12"
       OR NOT no_resume MATCHES "exists")
      message(FATAL_ERROR "a mismatched journal was not refused with a clear message")
    endif()
    file(REMOVE "${JOURNAL}")
  elseif(CHECK STREQUAL "usage")
    foreach(bad "sweep" "sweep|--z|0x10000" "sweep|--z|-1" "sweep|--z|0|--x-cells|5:5"
            "sweep|--z|0|--x-cells|0:257" "sweep|--z|0|--resume" "sweep|--z|0|--unit|nosuch"
            "sweep|--z|0|--config|bogus=1" "sweep|--z|0|--threads|0" "sweep|--z" "sweep|--frobnicate"
            "bench|--seconds|0" "bench|--nope")
      np_run("${bad}" 2 out)
    endforeach()
    np_run("sweep|--help" 0 out)
    np_run("bench|--help" 0 out)
  elseif(CHECK STREQUAL "search_resume")
    # A journal cut in the middle of a record (a kill), resumed on another thread count:
    # the same summary as a run without a journal; another seed is exit 2 naming seed=.
    file(REMOVE "${JOURNAL}")
    set(common "search|--unit|classic3|-n|65536")
    np_run("${common}|--threads|2|--journal|${JOURNAL}" 0 first)
    file(READ "${JOURNAL}" text)
    string(LENGTH "${text}" len)
    math(EXPR half "${len} / 2")
    string(SUBSTRING "${text}" 0 ${half} text)
    file(WRITE "${JOURNAL}" "${text}")
    np_run("${common}|--threads|1|--journal|${JOURNAL}|--resume" 0 resumed)
    np_run("${common}|--threads|1" 0 whole)
    if(NOT resumed MATCHES " [1-9][0-9]* resumed from the journal" OR NOT resumed MATCHES "dropping an incomplete last record")
      message(FATAL_ERROR "the resumed search took no chunk from the journal, or kept its torn tail")
    endif()
    string(REGEX REPLACE "(inputs evaluated|wall time|noisepipe: journal)[^\n]*\n?" "" a "${resumed}")
    string(REGEX REPLACE "(inputs evaluated|wall time)[^\n]*\n?" "" b "${whole}")
    if(NOT a STREQUAL b)
      message(FATAL_ERROR "resumed and uninterrupted searches differ:\n${a}\n----\n${b}")
    endif()
    np_run("${common}|--seed|2|--journal|${JOURNAL}|--resume" 2 other_seed)
    if(NOT other_seed MATCHES "was written for 'seed=1', this run is 'seed=2'")
      message(FATAL_ERROR "a journal of another seed was not refused naming seed=")
    endif()
    file(REMOVE "${JOURNAL}")
  elseif(CHECK STREQUAL "search_usage")
    foreach(bad "search" "search|--unit|nosuch" "search|--unit|classic3|-n|4095" "search|--unit|classic3|-n|x"
            "search|--unit|classic3|--config|bogus=1" "search|--unit|classic3|--resume" "search|--unit|classic3|--threads|0"
            "search|--unit|fdiff" "search|--unit|classic3|--frobnicate|1" "search|--unit")
      np_run("${bad}" 2 out)
    endforeach()
    np_run("search|--help" 0 out)
  else()
    message(FATAL_ERROR "sweep.cmake: unknown CHECK '${CHECK}'")
  endif()
  return()
endif()

np_test_program(test_sweep test_sweep.c)
np_add_cases(test_sweep sweep
  kernel_model_cell kernel_ref_cell kernel_lattice kernel_random kernel_vs_plain_stats simplex3_pinned
  random_1e7 random_widths
  threads journal_resume journal_refuse kill_resume cheap_fails)
set_tests_properties(sweep.kill_resume PROPERTIES ENVIRONMENT "NOISEPIPE=$<TARGET_FILE:noisepipe>")

# A representative slice of the full sweep for CI: 8 x cells of z = 0 and
# 8 x cells of the wrapping z cell (z = 0xff80) at the wrapping x cells.
add_test(NAME sweep.ci_slice_z0 COMMAND noisepipe sweep --z 0 --x-cells 0:8)
add_test(NAME sweep.ci_slice_zff80 COMMAND noisepipe sweep --z 0xff80 --x-cells 248:256)

set(np_sweep_script -DNOISEPIPE=$<TARGET_FILE:noisepipe> -P ${CMAKE_CURRENT_LIST_FILE})
# The check can fail: a cheap configuration exits 1.
add_test(NAME sweep.cli_cheap_fails COMMAND ${CMAKE_COMMAND} -DCHECK=exit
  "-DARGS=sweep|--config|s_frac=4,lerp_frac=6|--z|0|--x-cells|0:1" -DEXPECT=1
  "-DMATCH=verdict: FAIL" ${np_sweep_script})
add_test(NAME sweep.cli_resume COMMAND ${CMAKE_COMMAND} -DCHECK=resume
  -DJOURNAL=${CMAKE_CURRENT_BINARY_DIR}/sweep_cli.journal ${np_sweep_script})
add_test(NAME sweep.cli_usage COMMAND ${CMAKE_COMMAND} -DCHECK=usage ${np_sweep_script})

# The adversarial search (src/sweep/search.c, `noisepipe search`, docs/search.md).
np_test_program(test_search test_search.c)
np_add_cases(test_search search
  classic3_s8_l9_counterexample classic3_s9_l8_counterexample simplex3_t19_p19_counterexample
  simplex3_t19_p21_pinned defaults_faithful classes threads journal_resume journal_refuse
  ndim_defaults ndim_counterexample)
# n-input units (issue 18): the command names all n words of the worst input.
add_test(NAME search.cli_ndim COMMAND ${CMAKE_COMMAND} -DCHECK=exit
  "-DARGS=search|--unit|simplex5|-n|8192" -DEXPECT=0
  "-DMATCH=at \\(0x[0-9a-f]+, 0x[0-9a-f]+, 0x[0-9a-f]+, 0x[0-9a-f]+, 0x[0-9a-f]+\\).*verdict: faithful \\(proved\\)" ${np_sweep_script})
# The command: a counterexample is exit 1 with the verdict; bad usage is exit 2.
add_test(NAME search.cli_counterexample COMMAND ${CMAKE_COMMAND} -DCHECK=exit
  "-DARGS=search|--unit|classic3|--config|s_frac=4,lerp_frac=6|-n|4096"
  -DEXPECT=1 "-DMATCH=verdict: not faithful, counterexample \\(0x" ${np_sweep_script})
add_test(NAME search.cli_proved COMMAND ${CMAKE_COMMAND} -DCHECK=exit
  "-DARGS=search|--unit|classic3|-n|8192" -DEXPECT=0 "-DMATCH=verdict: faithful \\(proved\\)" ${np_sweep_script})
add_test(NAME search.cli_resume COMMAND ${CMAKE_COMMAND} -DCHECK=search_resume
  -DJOURNAL=${CMAKE_CURRENT_BINARY_DIR}/search_cli.journal ${np_sweep_script})
add_test(NAME search.cli_usage COMMAND ${CMAKE_COMMAND} -DCHECK=search_usage ${np_sweep_script})

# The sweep under MPI (issue 13): label mpi; they skip (exit 77) when noisepipe is built
# without MPI or mpirun is missing. Also nosan: OpenMPI's runtime leaves allocations of its
# dlopen'd components at MPI_Finalize, which LeakSanitizer reports (none in noisepipe's code),
# and the sanitised sweep is ~20x slower (6 min for mpi_same). The several-slices path
# without MPI runs under the sanitizers in sweep.cli_range.
foreach(c same kill_resume)
  add_test(NAME sweep.mpi_${c} COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/sweep_mpi.sh $<TARGET_FILE:noisepipe>
    "${NP_HAVE_MPI}" ${CMAKE_CURRENT_BINARY_DIR}/sweep_mpi_${c} ${c})
  set_tests_properties(sweep.mpi_${c} PROPERTIES LABELS "mpi;nosan" SKIP_RETURN_CODE 77 RUN_SERIAL ON)
endforeach()
add_test(NAME sweep.cli_range COMMAND ${CMAKE_COMMAND} -DCHECK=exit "-DARGS=sweep|--z|0xfffe:65536|--x-cells|255:256"
  -DEXPECT=0 "-DMATCH=slices z = 0xfffe..0xffff \\(2 slices\\).*inputs checked      33554432.*at x=0xff[0-9a-f][0-9a-f] y=0x[0-9a-f]+ z=0xfff[ef]:.*processes           1"
  ${np_sweep_script})
