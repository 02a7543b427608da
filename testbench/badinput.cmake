# SPDX-License-Identifier: MIT
# Bad input end to end (docs/bad-input.md): each case runs the command on a
# malformed input and wants exit status 2 and a message naming the field.
function(np_bad_scene name geometry want)
  set(f ${CMAKE_CURRENT_BINARY_DIR}/bad_${name}.json)
  file(WRITE ${f} "{ \"noisepipe_scene\": 1, \"name\": \"${name}\", \"image\": { \"width\": 32, \"height\": 32 },
  \"camera\": { \"projection\": \"orthographic\", \"eye\": [0, 0, 5], \"target\": [0, 0, 0], \"up\": [0, 1, 0], \"height\": 3 },
  \"geometry\": [ ${geometry} ],
  \"texture\": { \"octaves\": [ { \"amplitude\": 1, \"scale\": [4, 4, 4] } ],
                 \"colormap\": { \"mode\": \"clamp\", \"domain\": [-1, 1], \"colors\": [[0, 0, 0], [255, 255, 255]] } },
  \"probe_row\": 16 }\n")
  add_test(NAME badinput.scene_${name} COMMAND ${CMAKE_COMMAND}
    -DCMD=$<TARGET_FILE:noisepipe> -DARGS=render\;${f}\;-o\;${CMAKE_CURRENT_BINARY_DIR}/bad_${name}_out
    -DWANT_RC=2 "-DWANT=${want}" -P ${CMAKE_CURRENT_SOURCE_DIR}/render_expect.cmake)
endfunction()
set(np_tc "\"texcoords\": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]]")
np_bad_scene(zero_area
  "{ \"type\": \"polygon\", \"vertices\": [[0,0,0],[1,0,0],[2,0,0]], \"texcoords\": [[0,0,0],[1,0,0],[1,1,0]] }"
  "field 'geometry[0].vertices': the polygon has no area")
np_bad_scene(coincident
  "{ \"type\": \"polygon\", \"vertices\": [[0,0,0],[1,0,0],[1,0,0],[0,1,0]], ${np_tc} }"
  "field 'geometry[0].vertices': vertices 1 and 2 are the same point")
np_bad_scene(non_convex
  "{ \"type\": \"polygon\", \"vertices\": [[-1,-1,0],[1,-1,0],[0,-0.5,0],[0,1,0]], ${np_tc} }"
  "field 'geometry[0].vertices': the polygon is not convex at vertex 2")
np_bad_scene(non_planar
  "{ \"type\": \"polygon\", \"vertices\": [[-1,-1,0],[1,-1,0],[1,1,0.5],[-1,1,0]], ${np_tc} }"
  "off the plane of the polygon")
# A camera inside a cube sees only back faces (culled): no pixel covered is exit 2, not "PSNR inf".
set(f ${CMAKE_CURRENT_BINARY_DIR}/bad_camera_inside.json)
file(WRITE ${f} "{ \"noisepipe_scene\": 1, \"name\": \"inside\", \"image\": { \"width\": 32, \"height\": 32 },
  \"camera\": { \"projection\": \"perspective\", \"eye\": [0.5, 0.5, 0.5], \"target\": [0, 0, 0], \"up\": [0, 0, 1], \"focal\": 1 },
  \"geometry\": [ { \"type\": \"cube\", \"min\": [0, 0, 0], \"max\": [1, 1, 1], \"texture_min\": [0, 0, 0], \"texture_max\": [1, 1, 1] } ],
  \"texture\": { \"octaves\": [ { \"amplitude\": 1, \"scale\": [4, 4, 4] } ],
                 \"colormap\": { \"mode\": \"clamp\", \"domain\": [-1, 1], \"colors\": [[0, 0, 0], [255, 255, 255]] } } }\n")
add_test(NAME badinput.scene_camera_inside COMMAND ${CMAKE_COMMAND}
  -DCMD=$<TARGET_FILE:noisepipe> -DARGS=render\;${f}\;-o\;${CMAKE_CURRENT_BINARY_DIR}/bad_inside_out
  -DWANT_RC=2 "-DWANT=the scene covers no pixel" -P ${CMAKE_CURRENT_SOURCE_DIR}/render_expect.cmake)
# ... unless the scene says an empty image is expected.
file(READ ${f} np_inside)
string(REPLACE "\"name\": \"inside\"," "\"name\": \"inside\", \"allow_empty\": true," np_inside "${np_inside}")
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/ok_camera_inside_allowed.json "${np_inside}")
add_test(NAME badinput.scene_empty_allowed COMMAND ${CMAKE_COMMAND}
  -DCMD=$<TARGET_FILE:noisepipe> -DARGS=render\;${CMAKE_CURRENT_BINARY_DIR}/ok_camera_inside_allowed.json\;-o\;${CMAKE_CURRENT_BINARY_DIR}/ok_inside_out
  -DWANT_RC=0 "-DWANT=" -P ${CMAKE_CURRENT_SOURCE_DIR}/render_expect.cmake)
# JSON nested past cJSON's limit: said so, not just "not valid JSON".
string(REPEAT "[" 1200 np_open)
string(REPEAT "]" 1200 np_close)
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/bad_deep.json "{ \"noisepipe_scene\": ${np_open}${np_close} }\n")
add_test(NAME badinput.scene_deep_nesting COMMAND ${CMAKE_COMMAND}
  -DCMD=$<TARGET_FILE:noisepipe> -DARGS=render\;${CMAKE_CURRENT_BINARY_DIR}/bad_deep.json
  -DWANT_RC=2 "-DWANT=JSON nested deeper than 1000 levels" -P ${CMAKE_CURRENT_SOURCE_DIR}/render_expect.cmake)

# Vector and results files (issue 11 items 4 and 9): each wants exit 2 and the hint.
function(np_bad_sh name script)
  add_test(NAME badinput.${name}
    COMMAND sh -c "set -u; np=\"$0\"; d=\"$1\"; rm -rf \"$d\"; mkdir -p \"$d\"; cd \"$d\" || exit 1
                   want() { \"$@\" > out.txt 2> err.txt; s=$?; cat err.txt; test $s -eq 2 || { echo \"exit $s, want 2\"; exit 1; }; }
                   has() { grep -qF -- \"$1\" err.txt || { echo \"stderr does not say: $1\"; exit 1; }; }
                   ${script}"
            $<TARGET_FILE:noisepipe> ${CMAKE_CURRENT_BINARY_DIR}/badinput_${name})
endfunction()
np_bad_sh(results_other_unit "\"$np\" vectors --unit classic3 -n 3 -o c.vec && \"$np\" vectors --unit simplex3 -n 3 -o s.vec &&
  \"$np\" device s.vec --format results -o s.res && want \"$np\" verify --results s.res c.vec && has \"s.res:2: field 'unit': the results are for unit simplex3, the vectors for unit classic3\"")
np_bad_sh(results_other_count "\"$np\" vectors --unit classic3 -n 3 -o c.vec && \"$np\" device c.vec --format results -o c.res &&
  sed 's|^// count .*|// count 5|' c.res > c5.res && want \"$np\" verify --results c5.res c.vec && has \"field 'count': the results are for count 5\"")
np_bad_sh(vectors_bom "\"$np\" vectors --unit classic3 -n 3 -o c.vec && printf '\\357\\273\\277' > b.vec && cat c.vec >> b.vec &&
  want \"$np\" verify b.vec && has 'b.vec:1: the file starts with a UTF-8 byte-order mark'")
np_bad_sh(vectors_cr_only "\"$np\" vectors --unit classic3 -n 3 -o c.vec && tr '\\n' '\\r' < c.vec > r.vec &&
  want \"$np\" verify r.vec && has 'CR-only (classic Mac) line endings'")
np_bad_sh(vectors_coe "\"$np\" vectors --unit classic3 -n 3 --format coe -o c.coe &&
  want \"$np\" verify c.coe && has 'this is a Xilinx .coe export'")
np_bad_sh(config_not_a_number "want \"$np\" vectors --unit classic3 --config out_bits=abc -n 2 && has 'out_bits=abc: not a number'")
