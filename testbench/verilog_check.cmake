# SPDX-License-Identifier: MIT
# Driver of the verilog.* CTest cases (cmake -P): runs the Icarus Verilog
# scoreboard classic3_tb.v / np_vec_check.v on vector and result files.
#
#   -DMODE=readmemh   noisepipe vectors (readmemh) + noisepipe device (results),
#                     then the bench: must pass with "no errors found".
#   -DMODE=flip       the same, with bit FLIP_BIT of result number FLIP_AT (0-based)
#                     flipped: the bench must fail, print that vector's
#                     `x y z => got expected: want` line and count 1 error.
#   -DMODE=selftest   hand-made files, no noisepipe: a passing set, a flipped bit,
#                     missing and extra results, no vectors, a header count or unit
#                     that does not match, a valid bit of 0.
#
# Other inputs (-D): IVERILOG VVP (empty: the test reports itself skipped),
# TB_DIR (testbench/), WORK (scratch folder), NOISEPIPE (the command),
# VECTORS_ARGS DEVICE_ARGS (comma-separated extra arguments), FLIP_BIT FLIP_AT.
cmake_minimum_required(VERSION 3.18)

if(NOT IVERILOG OR NOT VVP)
  # SKIP_REGULAR_EXPRESSION of the test matches this line.
  message("verilog: SKIPPED: iverilog/vvp not found (Debian package iverilog)")
  return()
endif()

file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")

# classic3: {valid, x, y, z, f}; every field is a whole number of hex digits.
set(N_IN 3)
set(IN_DIGITS 4)
set(OUT_DIGITS 2)
math(EXPR VEC_DIGITS "1 + ${N_IN} * ${IN_DIGITS} + ${OUT_DIGITS}")

function(fail)
  string(JOIN "" msg ${ARGN})
  message(FATAL_ERROR "verilog: ${msg}")
endfunction()

# Run a command; stdout to out_file when given; stop the test when it fails.
function(run what out_file)
  if(out_file)
    execute_process(COMMAND ${ARGN} OUTPUT_FILE "${out_file}" ERROR_VARIABLE err RESULT_VARIABLE rc)
  else()
    execute_process(COMMAND ${ARGN} OUTPUT_VARIABLE err ERROR_VARIABLE err RESULT_VARIABLE rc)
  endif()
  if(NOT rc EQUAL 0)
    string(JOIN " " cmd ${ARGN})
    fail("${what} failed (exit status ${rc}): ${cmd}\n${err}")
  endif()
endfunction()

# Data words of a $readmemh file, comments and blank lines dropped.
function(read_words path out)
  file(STRINGS "${path}" lines)
  set(words)
  foreach(line IN LISTS lines)
    string(REGEX REPLACE "//.*" "" line "${line}")
    string(STRIP "${line}" line)
    if(NOT line STREQUAL "")
      list(APPEND words "${line}")
    endif()
  endforeach()
  set(${out} "${words}" PARENT_SCOPE)
endfunction()

# Write lines (a list) as a file, one a line.
function(write_lines path)
  string(JOIN "\n" text ${ARGN})
  file(WRITE "${path}" "${text}\n")
endfunction()

# Copy of a result file with bit `bit` of data word number `at` flipped.
function(flip_result src dst at bit)
  file(STRINGS "${src}" lines)
  set(out)
  set(n 0)
  set(done OFF)
  foreach(line IN LISTS lines)
    string(REGEX REPLACE "//.*" "" word "${line}")
    string(STRIP "${word}" word)
    if(NOT word STREQUAL "")
      if(n EQUAL at)
        string(LENGTH "${word}" digits)
        math(EXPR v "(0x${word}) ^ (1 << ${bit})" OUTPUT_FORMAT HEXADECIMAL)
        string(SUBSTRING "${v}" 2 -1 v)
        string(LENGTH "${v}" len)
        while(len LESS digits)
          string(PREPEND v "0")
          math(EXPR len "${len} + 1")
        endwhile()
        set(line "${v}")
        set(done ON)
      endif()
      math(EXPR n "${n} + 1")
    endif()
    list(APPEND out "${line}")
  endforeach()
  if(NOT done)
    fail("cannot flip result ${at}: ${src} has only ${n} results")
  endif()
  write_lines("${dst}" ${out})
endfunction()

# The line the bench prints for a mismatch of vector word `word`: x y z => got expected: want
function(mismatch_line word got out)
  set(line "")
  set(pos 1)
  foreach(k RANGE 1 ${N_IN})
    string(SUBSTRING "${word}" ${pos} ${IN_DIGITS} field)
    string(APPEND line "${field} ")
    math(EXPR pos "${pos} + ${IN_DIGITS}")
  endforeach()
  string(SUBSTRING "${word}" ${pos} ${OUT_DIGITS} want)
  string(TOLOWER "${line}=> ${got} expected: ${want}" line)
  set(${out} "${line}" PARENT_SCOPE)
endfunction()

# Compile the bench once per test.
set(vvp_file "${WORK}/classic3_tb.vvp")
run("iverilog" "" "${IVERILOG}" -g2012 -Wall -o "${vvp_file}" -s classic3_tb
    "${TB_DIR}/classic3_tb.v" "${TB_DIR}/np_vec_check.v")

# Run the bench; sets <prefix>_rc and <prefix>_out.
function(bench prefix vectors results)
  execute_process(COMMAND "${VVP}" -n "${vvp_file}" "+vectors=${vectors}" "+results=${results}"
                  OUTPUT_VARIABLE out ERROR_VARIABLE out RESULT_VARIABLE rc)
  message("--- bench on ${vectors} / ${results}: exit status ${rc}\n${out}")
  set(${prefix}_rc "${rc}" PARENT_SCOPE)
  set(${prefix}_out "${out}" PARENT_SCOPE)
endfunction()

function(expect_pass what vectors results)
  bench(b "${vectors}" "${results}")
  if(NOT b_rc EQUAL 0 OR NOT b_out MATCHES "classic3_tb: In [1-9][0-9]* tests, no errors found\\.")
    fail("${what}: the bench should pass")
  endif()
endfunction()

function(expect_fail what vectors results pattern)
  bench(b "${vectors}" "${results}")
  if(b_rc EQUAL 0)
    fail("${what}: the bench passed, it must fail")
  endif()
  string(FIND "${b_out}" "${pattern}" at)
  if(at EQUAL -1)
    fail("${what}: the bench's output does not contain '${pattern}'")
  endif()
  set(b_out "${b_out}" PARENT_SCOPE)
endfunction()

if(MODE STREQUAL "selftest")
  set(v "${WORK}/self.memh")
  set(r "${WORK}/self.hex")
  # Hand-made: the bench compares fields, so the f values need not be real noise.
  write_lines("${v}" "// hand-made classic3 vectors: valid x y z f"
    "1000000000000ff" "1123456789abc01" "1ffffffffffff80" "10100020003007f  // trailing comment")
  write_lines("${r}" "// results" "ff" "01" "80" "7f")
  expect_pass("selftest pass" "${v}" "${r}")

  write_lines("${r}.flip" "ff" "01" "81" "7f")
  expect_fail("selftest flipped bit" "${v}" "${r}.flip" "ffff ffff ffff => 81 expected: 80")
  if(NOT b_out MATCHES "In 4 tests, 1 errors found")
    fail("selftest flipped bit: verdict should count 1 error in 4 tests")
  endif()

  write_lines("${r}.short" "ff" "01" "80")
  expect_fail("selftest missing result" "${v}" "${r}.short" "4 vectors but 3 results")
  write_lines("${r}.long" "ff" "01" "80" "7f" "00")
  expect_fail("selftest extra result" "${v}" "${r}.long" "4 vectors but 5 results")
  write_lines("${v}.empty" "// no vectors")
  expect_fail("selftest no vectors" "${v}.empty" "${r}" "no valid vectors")

  # The noisepipe header's unit and count lines are checked (a truncated file fails).
  write_lines("${v}.count" "// unit classic3" "// count 5"
    "1000000000000ff" "1123456789abc01" "1ffffffffffff80" "10100020003007f")
  expect_fail("selftest truncated file" "${v}.count" "${r}" "the header's count is 5 but 4 vectors")
  write_lines("${v}.unit" "// unit simplex3" "1000000000000ff")
  expect_fail("selftest wrong unit" "${v}.unit" "${r}" "holds vectors of unit simplex3")

  # A word with valid = 0 ends the set: the words after it are not checked.
  write_lines("${v}.end" "1000000000000ff" "1123456789abc01" "000000000000000" "1ffffffffffff80")
  write_lines("${r}.end" "ff" "01")
  expect_pass("selftest valid bit 0 ends the set" "${v}.end" "${r}.end")
  message("verilog: selftest: all cases behaved")
  return()
endif()

# Golden vectors and the device's results from noisepipe.
string(REPLACE "," ";" vectors_args "${VECTORS_ARGS}")
string(REPLACE "," ";" device_args "${DEVICE_ARGS}")
set(memh "${WORK}/classic3.memh")
set(text "${WORK}/classic3.vec")
set(results "${WORK}/classic3.results")
run("noisepipe vectors (readmemh)" "${memh}"
    "${NOISEPIPE}" vectors --unit classic3 --format readmemh ${vectors_args})
run("noisepipe vectors (text)" "${text}"
    "${NOISEPIPE}" vectors --unit classic3 ${vectors_args})
run("noisepipe device (results)" "${results}"
    "${NOISEPIPE}" device --unit classic3 --format results ${device_args} "${text}")

read_words("${memh}" words)
read_words("${results}" res)
list(LENGTH words n_words)
list(LENGTH res n_res)
message("verilog: ${n_words} vector words in ${memh}, ${n_res} results in ${results}")
if(n_words EQUAL 0)
  fail("noisepipe vectors wrote no vector words")
endif()
list(GET words 0 w0)
string(LENGTH "${w0}" len)
if(NOT len EQUAL VEC_DIGITS)
  fail("vector word '${w0}' has ${len} hex digits, expected ${VEC_DIGITS}")
endif()

if(MODE STREQUAL "readmemh")
  expect_pass("golden vectors on the device's results" "${memh}" "${results}")
elseif(MODE STREQUAL "flip")
  if(FLIP_AT GREATER_EQUAL n_words)
    set(FLIP_AT 0)
  endif()
  flip_result("${results}" "${results}.flip" ${FLIP_AT} ${FLIP_BIT})
  read_words("${results}.flip" flipped)
  list(GET flipped ${FLIP_AT} got)
  list(GET words ${FLIP_AT} word)
  mismatch_line("${word}" "${got}" line)
  message("verilog: result ${FLIP_AT} bit ${FLIP_BIT} flipped; the bench must print: ${line}")
  expect_fail("flipped bit" "${memh}" "${results}.flip" "${line}")
  if(NOT b_out MATCHES "In ${n_words} tests, 1 errors found")
    fail("flipped bit: the verdict should count 1 error in ${n_words} tests")
  endif()
else()
  fail("unknown MODE '${MODE}'")
endif()
message("verilog: ${MODE}: ok")
