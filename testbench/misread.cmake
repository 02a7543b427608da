# SPDX-License-Identifier: MIT
# Golden vector sets at non-default configurations (vectors/<unit>/*-l1-seed1-<name>.*):
#   misread.<unit>              misread variants of the model must each fail one of them
#   misread.<unit>_regen_<name> the set regenerates byte for byte (text and $readmemh)
np_test_program(test_misread test_misread.c)
target_compile_definitions(test_misread PRIVATE NP_VEC_DIR="${PROJECT_SOURCE_DIR}/vectors")
np_add_cases(test_misread misread classic3 simplex3 hatch simplex2 simplex4 simplex5 classic2 classic4 classic5 wave)

file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/np_regen_cfg_set.cmake [=[
# Written by testbench/misread.cmake: regenerate SET.{vec,memh} of UNIT at CONFIG and compare.
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
foreach(pair "text;vec" "readmemh;memh")
  list(GET pair 0 fmt)
  list(GET pair 1 ext)
  execute_process(COMMAND ${NOISEPIPE} vectors --unit ${UNIT} --config ${CONFIG} --format ${fmt}
                  -o ${WORK}/v.${ext} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "noisepipe vectors --unit ${UNIT} --config ${CONFIG} failed (${rc})")
  endif()
  execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${WORK}/v.${ext} ${SET}.${ext} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "regenerated vectors differ from ${SET}.${ext}; refresh with: noisepipe vectors "
            "--unit ${UNIT} --config ${CONFIG} --format ${fmt} -o ${SET}.${ext}")
  endif()
endforeach()
]=])
foreach(set "classic3;cheap;out_bits=8,s_frac=4,lerp_frac=6"
            "classic3;wide_l;out_bits=15,s_frac=3,lerp_frac=20"
            "simplex3;t1;t_frac=1"
            "simplex3;coarse;t_frac=20,p_frac=14,k_frac=16"
            "hatch;onebyone;fade=onebyone"
            "hatch;best64;set=best64"
            "hatch;g0;guard=0"
            "hatch;rot45;rot=45"
            "hatch;fkm16_l1;set=fkm16,layers=1"
            "simplex2;coarse;t_frac=14,p_frac=20" "simplex2;narrow;out_bits=20,t_frac=3,p_frac=14"
            "simplex4;coarse;t_frac=14,p_frac=20" "simplex4;narrow;out_bits=20,t_frac=3,p_frac=14"
            "simplex5;coarse;t_frac=14,p_frac=20" "simplex5;narrow;out_bits=20,t_frac=3,p_frac=14"
            "classic2;wide_l;out_bits=12,s_frac=3,lerp_frac=12"
            "classic4;wide_l;out_bits=12,s_frac=3,lerp_frac=12"
            "classic5;wide_l;out_bits=12,s_frac=3,lerp_frac=12"
            "wave;rom6;rom_log2=6"
            "wave;rom10;rom_log2=10"
            "wave;irr0_cap0;irr=0,cap=0"
            "wave;trains4;trains=4")
  list(GET set 0 unit)
  list(GET set 1 name)
  list(GET set 2 config)
  add_test(NAME misread.${unit}_regen_${name} COMMAND ${CMAKE_COMMAND}
    -DNOISEPIPE=$<TARGET_FILE:noisepipe> -DUNIT=${unit} -DCONFIG=${config}
    -DSET=${PROJECT_SOURCE_DIR}/vectors/${unit}/${unit}-l1-seed1-${name}
    -DWORK=${CMAKE_CURRENT_BINARY_DIR}/misread-work-${unit}-${name} -P ${CMAKE_CURRENT_BINARY_DIR}/np_regen_cfg_set.cmake)
endforeach()
