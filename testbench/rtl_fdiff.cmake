# SPDX-License-Identifier: MIT
# Reference RTL of the forward-difference unit fdiff (rtl_model/verilog/np_fdiff.v with the span
# sequencer np_span_seq.v) under Verilator (co-simulation) and Icarus/Verilator (golden bench),
# with rtl.cmake's mechanisms; docs/rtl.md and docs/fdiff.md ("Reference RTL of fdiff") say what
# each test checks. Names:
#   rtl.fdiff.lint.<cfg>               verilator --lint-only -Wall at the default and at four octaves
#   rtl.fdiff.cosim.<name>             co-simulation against np_span_sim with np_fdiff_engine
if(NOT COMMAND np_rtl_builds)
  return()
endif()
set(NP_RTL_FD_RTL ${NP_RTL_SRC}/np_fdiff.v ${NP_RTL_SRC}/np_span_seq.v)
set(fd_work ${NP_RTL_WORK}/fdiff)
file(MAKE_DIRECTORY ${fd_work})

# Lint at the default and at marble's four octaves with the numeric keys off their defaults
# (resetup stays 0: the interval is not built).
foreach(l "default;-GN_OCT=1" "oct4;-GN_OCT=4;-GIDX_INT=9;-GW_FRAC=10;-GGUARD=30;-GSETUP_MULTS=1;-GMULT_LAT=3"
          "wide;-GIDX_INT=1;-GW_FRAC=24;-GGUARD=100;-GSETUP_MULTS=64;-GMULT_LAT=16")
  list(GET l 0 lname)
  list(REMOVE_AT l 0)
  np_rtl_test(rtl.fdiff.lint.${lname} "${NP_VERILATOR}" pass "" "rtl;nosan"
    ${NP_VERILATOR} --lint-only -Wall -I${NP_RTL_SRC} ${l} --top-module np_fdiff ${NP_RTL_FD_RTL})
endforeach()

# Co-simulation against the registry's stream model of fdiff (np_cosim_open_spec: np_span_sim with
# np_fdiff_engine): every cycle in_ready, out_valid and, when valid, cr cg cb, with random bubbles
# and stalls and random descriptors (np_cosim.c). default: wood at the default keys; marble: four
# octaves with the numeric keys off their defaults.
set(fd_def "-GTEXTURE=wood;-GIDX_INT=10;-GW_FRAC=12;-GGUARD=44;-GRESETUP=0;-GSETUP_MULTS=2;-GMULT_LAT=2;-GN_OCT=1")
set(fd_marble "-GTEXTURE=marble;-GIDX_INT=9;-GW_FRAC=10;-GGUARD=30;-GRESETUP=0;-GSETUP_MULTS=1;-GMULT_LAT=3;-GN_OCT=4")
np_rtl_cosim_build(fdiff default np_fdiff "" "${fd_def}" ${NP_RTL_FD_RTL})
np_rtl_cosim_build(fdiff marble np_fdiff "" "${fd_marble}" ${NP_RTL_FD_RTL})
foreach(f flip stall setup drop)
  string(TOUPPER ${f} F)
  np_rtl_cosim_build(fdiff fault_${f} np_fdiff "-DNP_FAULT_${F}" "${fd_def}" ${NP_RTL_FD_RTL})
endforeach()
np_rtl_cosim(rtl.fdiff.cosim.default fdiff default pass "1000000 cycles, .* 0 mismatches" --cycles 1000000)
np_rtl_cosim(rtl.fdiff.cosim.marble fdiff marble pass "1000000 cycles, .* 0 mismatches" --cycles 1000000)
foreach(f flip stall setup drop)
  np_rtl_cosim(rtl.fdiff.cosim.fault_${f} fdiff fault_${f} fail "[1-9][0-9]* mismatches" --cycles 100000)
endforeach()
