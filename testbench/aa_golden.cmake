# SPDX-License-Identifier: MIT
# cmake -DNOISEPIPE=prog -DOUT=dir -DLIST=hashes.txt -P aa_golden.cmake:
# `noisepipe render --aa m=2,4 --gt 4 --sweep -o OUT embedded:marble` (the adaptive supersampling
# pipeline, its report and its sweep): the SHA-256 of its stdout and of every file it writes
# (PNG, SVG, Markdown) must be the checked-in list LIST, line for line ("HASH  NAME", names
# sorted), so a change of any byte, a file more or a file less shows in `git diff` of LIST.
# Then the check must bite: one byte of one output flipped must make the list differ.
file(REMOVE_RECURSE ${OUT})
execute_process(COMMAND ${NOISEPIPE} render --aa m=2,4 --gt 4 --sweep -o ${OUT} embedded:marble
  RESULT_VARIABLE rc OUTPUT_VARIABLE stdout ERROR_VARIABLE stderr)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "render --aa exited ${rc}\nstdout: ${stdout}\nstderr: ${stderr}")
endif()
file(WRITE ${OUT}/stdout.txt "${stdout}")

function(aa_hash_list dir result)
  file(GLOB names RELATIVE ${dir} ${dir}/*)
  list(SORT names)
  set(text "")
  foreach(n ${names})
    file(SHA256 ${dir}/${n} h)
    string(APPEND text "${h}  ${n}\n")
  endforeach()
  set(${result} "${text}" PARENT_SCOPE)
endfunction()

aa_hash_list(${OUT} got)
file(READ ${LIST} want)
if(NOT got STREQUAL want)
  message(FATAL_ERROR "render --aa's outputs differ from ${LIST}; got:\n${got}")
endif()

# The check bites: the first byte of the first PNG (0x89 in every PNG) made 0x88, the list must differ.
file(GLOB pngs ${OUT}/*.png)
list(SORT pngs)
list(GET pngs 0 victim)
execute_process(COMMAND sh -c "printf '\\210' > \"$0\" && tail -c +2 \"$1\" >> \"$0\" && mv \"$0\" \"$1\""
  ${OUT}/flipped.tmp ${victim} RESULT_VARIABLE frc)
if(NOT frc EQUAL 0)
  message(FATAL_ERROR "could not flip a byte of ${victim}")
endif()
aa_hash_list(${OUT} bitten)
if(bitten STREQUAL want)
  message(FATAL_ERROR "a flipped byte in ${victim} did not change the list: the check cannot fail")
endif()
message(STATUS "render --aa: ${OUT} matches ${LIST}; a flipped byte in one PNG is caught")
