#!/usr/bin/env bash
# Installs what is missing, builds into build/ and runs every test through ctest.
# SANITIZE=ON builds into build-asan/ with AddressSanitizer + UBSan instead.
set -euo pipefail
REPO_DIR="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
if [ "${SANITIZE:-OFF}" = "ON" ]; then
  export BUILD_DIR="${BUILD_DIR:-$REPO_DIR/build-asan}"
  # third-party allocations kept until exit (tests/lsan.supp says which)
  export LSAN_OPTIONS="suppressions=$REPO_DIR/tests/lsan.supp${LSAN_OPTIONS:+:$LSAN_OPTIONS}"
fi
source "$REPO_DIR/scripts/setup.sh"
cd "$BUILD_DIR"
ctest --output-on-failure -j "${JOBS}" "$@"
