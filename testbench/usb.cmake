# SPDX-License-Identifier: MIT
# The USB link (docs/usb-protocol.md).
#   link.*  protocol, board emulator and host in one process (test_link): always.
#   usb.*   the real libusb path: `noisepipe stream --device` runs unmodified in a
#           child process and finds, claims and streams to a USB device emulated
#           by umockdev, whose answers come from the board emulator
#           (test_link_usb, run under umockdev-wrapper). Needs the libusb
#           transport (NOISEPIPE_USB) and umockdev (Debian: umockdev, libumockdev-dev).
np_test_program(test_link test_link.c)
target_link_libraries(test_link PRIVATE np_link)
# The cli_* cases run `noisepipe stream --emulate` in a child process.
target_compile_definitions(test_link PRIVATE NP_CLI="$<TARGET_FILE:noisepipe>")
add_dependencies(test_link noisepipe)
np_add_cases(test_link link
  crc_kat frame_codec rx_reassembly rx_short records payloads doc_session board_errors
  config_refused_halts hunting hello_bad_version min_payload stale_error
  board_vs_model e2e e2e_wrong_bit e2e_faults stale_input board_reports config_refused
  journal kill_resume cli_journal cli_interrupt)

# The command itself, in process, against the emulator: exit statuses and messages.
add_test(NAME link.cli_emulate COMMAND noisepipe stream --emulate --unit classic3 --random 100000)
set_tests_properties(link.cli_emulate PROPERTIES
  PASS_REGULAR_EXPRESSION "In 100000 tests, no errors found in classic3")
add_test(NAME link.cli_wrong_bit COMMAND noisepipe stream --emulate --unit classic3 --random 50000
  --inject wrong-bit:31337:2)
set_tests_properties(link.cli_wrong_bit PROPERTIES
  PASS_REGULAR_EXPRESSION "=> [0-9a-f]+ expected: [0-9a-f]+   vector 31337.*In 50000 tests, 1 error found in classic3")

if(NP_HAVE_USB)
  find_package(PkgConfig QUIET)
  if(PKG_CONFIG_FOUND)
    pkg_check_modules(UMOCKDEV QUIET IMPORTED_TARGET umockdev-1.0)
  endif()
  find_program(UMOCKDEV_WRAPPER umockdev-wrapper)
  if(UMOCKDEV_FOUND AND UMOCKDEV_WRAPPER)
    add_executable(test_link_usb test_link_usb.c)
    target_link_libraries(test_link_usb PRIVATE np_link PkgConfig::UMOCKDEV)
    # glib and the valac-generated umockdev.h do not pass the project's
    # -Wstrict-prototypes -Wconversion: relaxed for this one program only.
    target_compile_options(test_link_usb PRIVATE -Wall -Wextra -Werror -Wno-strict-prototypes
      -Wno-unused-parameter -ffp-contract=off)
    target_compile_definitions(test_link_usb PRIVATE _GNU_SOURCE
      NP_CLI="$<TARGET_FILE:noisepipe>")
    add_dependencies(test_link_usb noisepipe)
    set(np_usb_cases enumerate stream wrong_bit not_found config_refused disappear timeout stall
      corrupt short kill_resume timeout_out stream_1e6 journal_target interrupt hello_bad_version
      min_payload)
    foreach(c ${np_usb_cases})
      add_test(NAME usb.${c} COMMAND ${UMOCKDEV_WRAPPER} $<TARGET_FILE:test_link_usb> ${c})
      # The preload library comes before the sanitizer runtime: tell ASan that is fine.
      set_tests_properties(usb.${c} PROPERTIES TIMEOUT 120
        ENVIRONMENT "ASAN_OPTIONS=verify_asan_link_order=0:detect_leaks=0")
    endforeach()
    # usb.stream_1e6 prints the figures (vectors/s, MB/s, CPU per vector); for another size:
    #   umockdev-wrapper build/testbench/test_link_usb bench N
  else()
    message(STATUS "noisepipe: umockdev not found: the usb.* tests of the libusb path are not built")
  endif()
endif()

if(NP_HAVE_FTDI)
# noisepipe stream --ftdi (src/link/link_ftdi.c, libftdi1) without a board: the refusals, each
# exit 2 naming its option, and no FT2232H on the bus (exit 2, "no such USB device").
add_test(NAME link.ftdi_refusals
  COMMAND sh -c "chk() { want=\"$1\"; shift; \"$0\" stream \"$@\" > /dev/null 2> ftdi_err.txt; s=$?;
                   test $s -eq 2 || { echo \"$*: exit $s\"; exit 1; }; grep -q -- \"$want\" ftdi_err.txt || { echo \"$*:\"; cat ftdi_err.txt; exit 1; }; }
                 chk '--ftdi 0403:zz: expected VID:PID' --ftdi 0403:zz --unit classic3 --random 10
                 chk '--ftdi-interface E: expected A, B, C or D' --ftdi --ftdi-interface E --unit classic3 --random 10
                 chk '--baud 100: expected a decimal number in 300..12000000' --ftdi --baud 100 --unit classic3 --random 10
                 chk '--baud goes with --ftdi' --emulate --baud 9600 --unit classic3 --random 10
                 chk 'give one of --device' --ftdi --emulate --unit classic3 --random 10
                 chk '--ftdi 0403:6010: no such USB device' --ftdi --unit classic3 --random 10
                 echo 'refusals ok'"
          $<TARGET_FILE:noisepipe>)
set_tests_properties(link.ftdi_refusals PROPERTIES WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR} LABELS "link"
  PASS_REGULAR_EXPRESSION "refusals ok")
endif()
