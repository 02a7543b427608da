# SPDX-License-Identifier: MIT
# libFuzzer targets (docs/fuzzing.md): included by the top-level CMakeLists.txt
# when NOISEPIPE_FUZZ=ON, which needs clang and its libFuzzer runtime (Debian:
# clang, libclang-rt-14-dev). The libraries are then built with
# -fsanitize=fuzzer-no-link,address,undefined so the fuzzer sees their coverage.
set(NP_FUZZ_HARNESSES vectors results config scene)
foreach(h ${NP_FUZZ_HARNESSES})
  add_executable(fuzz_${h} ${CMAKE_CURRENT_LIST_DIR}/fuzz_${h}.c ${CMAKE_CURRENT_LIST_DIR}/fuzz_util.c)
  target_include_directories(fuzz_${h} PRIVATE ${CMAKE_CURRENT_LIST_DIR})
  target_link_libraries(fuzz_${h} PRIVATE np_tools)
  if(h STREQUAL "scene")
    target_link_libraries(fuzz_${h} PRIVATE np_render)
  endif()
  target_compile_options(fuzz_${h} PRIVATE -fsanitize=fuzzer)
  target_link_options(fuzz_${h} PRIVATE -fsanitize=fuzzer)
  np_project_target(fuzz_${h})
endforeach()
add_custom_target(fuzzers DEPENDS fuzz_vectors fuzz_results fuzz_config fuzz_scene)
