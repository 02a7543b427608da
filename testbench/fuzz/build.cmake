# SPDX-License-Identifier: MIT
# Driver of fuzz.clang_build (cmake -P): configure and build the libFuzzer
# targets with clang in BIN. Prints "fuzz: SKIP" (and succeeds) when clang or
# its libFuzzer runtime is missing, so the fuzz tests are skipped, not failed.
if(NOT CLANG OR NOT EXISTS "${CLANG}")
  message("fuzz: SKIP (no clang; Debian: clang libclang-rt-14-dev)")
  return()
endif()
set(probe "${BIN}/probe")
file(MAKE_DIRECTORY "${probe}")
file(WRITE "${probe}/p.c" "#include <stddef.h>\n#include <stdint.h>\nint LLVMFuzzerTestOneInput(const uint8_t *d, size_t n);\nint LLVMFuzzerTestOneInput(const uint8_t *d, size_t n) { (void)d; (void)n; return 0; }\n")
execute_process(COMMAND "${CLANG}" -fsanitize=fuzzer "${probe}/p.c" -o "${probe}/p" RESULT_VARIABLE rc
                OUTPUT_QUIET ERROR_QUIET)
if(NOT rc EQUAL 0)
  message("fuzz: SKIP (clang has no libFuzzer runtime; Debian: libclang-rt-14-dev)")
  return()
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -S "${SRC}" -B "${BIN}" -DCMAKE_C_COMPILER=${CLANG}
                        -DCMAKE_BUILD_TYPE=RelWithDebInfo -DNOISEPIPE_FUZZ=ON -DNOISEPIPE_TESTS=OFF
                        -DNOISEPIPE_USB=OFF
                RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "fuzz: configuring the clang build in ${BIN} failed")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build "${BIN}" --target fuzzers -j2 RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "fuzz: building the libFuzzer targets failed")
endif()
