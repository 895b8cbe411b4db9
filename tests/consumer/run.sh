#!/usr/bin/env bash
# Installs the built rtlab tree into a scratch prefix with cmake --install, then configures, builds
# and runs tests/consumer against that prefix. Usage: run.sh SOURCE_DIR BUILD_DIR WORK_DIR CXX
set -euo pipefail
src=$1 build=$2 work=$3 cxx=$4
rm -rf "$work" && mkdir -p "$work"
cmake --install "$build" --prefix "$work/prefix" >"$work/install.log"
cmake -S "$src/tests/consumer" -B "$work/consumer-build" -G Ninja \
    -DCMAKE_PREFIX_PATH="$work/prefix" -DCMAKE_CXX_COMPILER="$cxx" >"$work/consumer.log"
cmake --build "$work/consumer-build" >>"$work/consumer.log"
"$work/consumer-build/consumer"
