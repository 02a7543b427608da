# SPDX-License-Identifier: MIT
# Fuzzing (docs/fuzzing.md), label "fuzz" (`ctest -L fuzz`):
#   fuzz.replay_<h>     every build, any compiler, sanitizers included: the
#                       checked-in corpus testbench/fuzz/corpus/<h> through the harness;
#   fuzz.clang_build    builds the libFuzzer targets with clang in build/fuzz-clang
#                       (skipped when clang's libFuzzer is not installed);
#   fuzz.libfuzzer_<h>  a short fixed number of libFuzzer runs from that corpus.
# Longer runs: docs/fuzzing.md.
set(NP_FUZZ_DIR ${CMAKE_CURRENT_SOURCE_DIR}/fuzz)
set(NP_FUZZ_HARNESSES vectors results config scene)
foreach(h ${NP_FUZZ_HARNESSES})
  add_executable(fuzz_replay_${h} fuzz/fuzz_${h}.c fuzz/fuzz_util.c fuzz/replay_main.c)
  target_include_directories(fuzz_replay_${h} PRIVATE ${NP_FUZZ_DIR})
  target_link_libraries(fuzz_replay_${h} PRIVATE np_tools)
  if(h STREQUAL "scene")
    target_link_libraries(fuzz_replay_${h} PRIVATE np_render)
  endif()
  np_project_target(fuzz_replay_${h})
  add_test(NAME fuzz.replay_${h} COMMAND fuzz_replay_${h} ${NP_FUZZ_DIR}/corpus/${h})
  set_tests_properties(fuzz.replay_${h} PROPERTIES LABELS fuzz)
endforeach()

# The libFuzzer build is only worth it in the plain build (the sanitizer pass
# would build it again); it is labelled nosan so `ctest -LE nosan` skips it.
find_program(NP_CLANG NAMES clang clang-14)
set(np_fuzz_bin ${CMAKE_BINARY_DIR}/fuzz-clang)
add_test(NAME fuzz.clang_build
  COMMAND ${CMAKE_COMMAND} -DSRC=${PROJECT_SOURCE_DIR} -DBIN=${np_fuzz_bin} -DCLANG=${NP_CLANG}
          -P ${NP_FUZZ_DIR}/build.cmake)
set_tests_properties(fuzz.clang_build PROPERTIES LABELS "fuzz;nosan" FIXTURES_SETUP np_fuzzers
  SKIP_REGULAR_EXPRESSION "fuzz: SKIP" TIMEOUT 900)
set(np_fuzz_runs_vectors 20000)
set(np_fuzz_runs_results 20000)
set(np_fuzz_runs_config 20000)
set(np_fuzz_runs_scene 1500)
foreach(h ${NP_FUZZ_HARNESSES})
  # New inputs go to a scratch folder first on the command line; the checked-in corpus is only read.
  add_test(NAME fuzz.libfuzzer_${h}
    COMMAND sh -c "test -x \"$0\" || { echo 'fuzz: SKIP (no libFuzzer build)'; exit 77; }
                   rm -rf \"$1\" && mkdir -p \"$1\" &&
                   exec \"$0\" -runs=$3 -max_total_time=120 -seed=1 -timeout=10 -rss_limit_mb=4096 \"$1\" \"$2\""
            ${np_fuzz_bin}/fuzz_${h} ${np_fuzz_bin}/scratch_${h} ${NP_FUZZ_DIR}/corpus/${h} ${np_fuzz_runs_${h}})
  set_tests_properties(fuzz.libfuzzer_${h} PROPERTIES LABELS "fuzz;nosan" FIXTURES_REQUIRED np_fuzzers
    SKIP_RETURN_CODE 77 TIMEOUT 300)
endforeach()
