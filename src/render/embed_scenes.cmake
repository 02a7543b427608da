# SPDX-License-Identifier: MIT
# Build step: embed the seed scenes (DIR/*.json) into OUT as C strings, so that
# `noisepipe run` and `noisepipe render` work from any directory and from an
# installed binary. np_scene_load("embedded:NAME") reads them (src/render/scene.c).
file(GLOB scenes ${DIR}/*.json)
list(SORT scenes)
set(body "/* Generated from vectors/scenes (one string per .json file) by src/render/embed_scenes.cmake; do not edit. */\n#include \"np_scene.h\"\n\n")
set(table "")
foreach(path ${scenes})
  get_filename_component(name ${path} NAME_WE)
  file(READ ${path} hex HEX)
  string(REGEX REPLACE "([0-9a-f][0-9a-f])" "0x\\1," bytes "${hex}")
  string(APPEND body "static const char scene_${name}[] = { ${bytes} 0 };\n")
  string(APPEND table "    { \"${name}\", scene_${name} },\n")
endforeach()
string(APPEND body "\nconst np_scene_embedded np_scenes_embedded[] = {\n${table}    { 0, 0 },\n};\n")
file(WRITE ${OUT}.tmp "${body}")
file(COPY_FILE ${OUT}.tmp ${OUT} ONLY_IF_DIFFERENT)
