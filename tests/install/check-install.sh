#!/usr/bin/env bash
# Installs the build tree into a scratch prefix and builds and runs an outside program that
# find_package(mrpt_vslam)s it. Usage: check-install.sh BUILD_DIR
set -euo pipefail
build="$1"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT
cmake --install "$build" --prefix "$scratch/prefix" >/dev/null
cmake -S "$here/consumer" -B "$scratch/build" -DCMAKE_PREFIX_PATH="$scratch/prefix" >/dev/null
cmake --build "$scratch/build" >/dev/null
# the installed programs find the project's libraries by their RPATH alone
env -u LD_LIBRARY_PATH "$scratch/build/consumer"
test -f "$scratch/prefix/share/mrpt-vslam/config/omni-fastslam/sports-hall.ini"
env -u LD_LIBRARY_PATH "$scratch/prefix/bin/omni-fastslam" --version | grep -q omni-fastslam
# --gui's window module sits beside the project's libraries, where LiveView loads it from
core_dir="$(dirname "$(find "$scratch/prefix" -name 'libmrpt_vslam_core.so.*' | head -1)")"
test -f "$core_dir/libmrpt_vslam_liveview.so"
