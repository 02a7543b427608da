#!/bin/sh
# SPDX-License-Identifier: MIT
# wave.lit_hashes: render scenarios 1 and 2 lit (noisepipe wave SCENE --grid N --frames F --render
# TEMPLATE) and compare every lit image's SHA-256 (binary PPM, np_image_hash) with
# vectors/images/wave_hashes.txt. Usage: wave_lit_hashes.sh NOISEPIPE SCENES_DIR GOLDEN OUT_DIR
# A change to any bit of these images fails here; refresh the list only for an intended change:
#   the 'got' lines printed below are the new list's lines.
np=$1 scenes=$2 golden=$3 out=$4
rm -rf "$out" && mkdir -p "$out" || exit 1
# scene, grid, frames: scenario 1 at 64^2 and 2 at 128^2 (the least its 16 m boxes allow), frames 0 and 15; scenario 1 at its 256^2, frame 0 (docs/wave.md's image)
for run in "wave_scenario1 64 2" "wave_scenario2 128 2" "wave_scenario1 256 1"; do
    set -- $run
    d="$out/$1-$2"
    mkdir -p "$d" && "$np" wave "$scenes/$1.json" --grid "$2" --frames "$3" -o "$d" --render "$scenes/wave_render.json" \
        >"$d.txt" || { cat "$d.txt"; echo "wave $1 --grid $2 failed"; exit 1; }
    sed -n "s|^ *lit: .*/\([^/ ]*\)\.png (.*) sha256 \([0-9a-f]\{64\}\)\$|\1 $2 \2|p" "$d.txt" >>"$out/got.txt"
done
grep -v '^#' "$golden" >"$out/want.txt"
sed 's/^/got  /' "$out/got.txt"
test -s "$out/got.txt" || { echo "no lit image hashes printed"; exit 1; }
if diff "$out/want.txt" "$out/got.txt"; then
    echo "wave.lit_hashes: $(wc -l <"$out/got.txt") lit images identical to $golden"
else
    echo "wave.lit_hashes: lit images differ from $golden (above: < golden, > rendered)"
    exit 1
fi
