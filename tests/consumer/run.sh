#!/usr/bin/env bash
# Installs the built rtlab tree into a scratch prefix with cmake --install, then configures, builds
# and runs tests/consumer against that prefix, and renders an image with the installed rtlab.
# Usage: run.sh SOURCE_DIR BUILD_DIR WORK_DIR CXX
set -euo pipefail
src=$1 build=$2 work=$3 cxx=$4
rm -rf "$work" && mkdir -p "$work"
cmake --install "$build" --prefix "$work/prefix" >"$work/install.log"
cmake -S "$src/tests/consumer" -B "$work/consumer-build" -G Ninja \
    -DCMAKE_PREFIX_PATH="$work/prefix" -DCMAKE_CXX_COMPILER="$cxx" >"$work/consumer.log"
cmake --build "$work/consumer-build" >>"$work/consumer.log"
"$work/consumer-build/consumer"
# The installed rtlab writes images through the installed OpenImageIO module (lib/rtlab), not the
# build tree's (render/image.cpp looks there first).
"$work/prefix/bin/rtlab" gen flake --size 1 -o "$work/f1.json" >/dev/null
LD_DEBUG=files "$work/prefix/bin/rtlab" render "$work/f1.json" -o "$work/f1.png" --width 8 \
    --height 8 >/dev/null 2>"$work/render.log"
grep -q "$work/prefix/lib[^ ]*/rtlab/librtlab_oiio.so" "$work/render.log" ||
    { echo "installed rtlab did not load the installed image module"; exit 1; }
[[ -s $work/f1.png ]] || { echo "installed rtlab wrote no image"; exit 1; }
echo "installed rtlab renders through the installed image module"
