#!/usr/bin/env bash
# Shared set-up for run-demo.sh and run-tests.sh: installs the Debian packages the project needs
# (only those missing), then configures and builds into build/ (not with --packages-only).
# Idempotent.
# Environment: BUILD_DIR (default build), BUILD_TYPE (RelWithDebInfo), SANITIZE (OFF|ON), JOBS,
# BUILD_TARGETS (default: everything; else the CMake targets to build, e.g. "view-slam vslam-eval").
set -euo pipefail

REPO_DIR="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD_DIR="${BUILD_DIR:-$REPO_DIR/build}"
BUILD_TYPE="${BUILD_TYPE:-RelWithDebInfo}"
SANITIZE="${SANITIZE:-OFF}"
JOBS="${JOBS:-$(nproc)}"
BUILD_TARGETS="${BUILD_TARGETS:-}"

DEBIAN_PACKAGES=(
  build-essential cmake ccache git clang-format python3
  libmrpt-dev mrpt-apps
  libopencv-dev libeigen3-dev nlohmann-json3-dev zlib1g-dev
  libgtest-dev libbenchmark-dev
  libplplot-dev plplot-driver-cairo
  libzmq3-dev cppzmq-dev
)

# Installs those of the given Debian packages that are missing. Another apt run (a second set-up,
# unattended-upgrades after boot) may hold apt's locks: the install waits up to 10 min for the dpkg
# lock; the package lists, whose lock apt does not wait for, are retried for a minute.
install_missing_packages() {
  local missing=()
  for p in "$@"; do
    if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
      missing+=("$p")
    fi
  done
  if [ ${#missing[@]} -eq 0 ]; then
    return 0
  fi
  echo "Installing missing Debian packages: ${missing[*]}"
  local SUDO=""
  if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
  local tries=1
  until $SUDO apt-get update -qq; do
    if [ $tries -ge 6 ]; then return 1; fi
    tries=$((tries + 1))
    echo "apt-get update failed (another apt run holding its lock?): try $tries of 6 in 10 s" >&2
    sleep 10
  done
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends \
    -o DPkg::Lock::Timeout=600 "${missing[@]}"
}

configure_and_build() {
  local generator=()
  if command -v ninja >/dev/null 2>&1; then generator=(-G Ninja); fi
  if [ ! -f "$BUILD_DIR/CMakeCache.txt" ]; then
    cmake -S "$REPO_DIR" -B "$BUILD_DIR" "${generator[@]}" -DCMAKE_BUILD_TYPE="$BUILD_TYPE" \
      -DMRPT_VSLAM_SANITIZE="$SANITIZE"
  else
    cmake -S "$REPO_DIR" -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE="$BUILD_TYPE" \
      -DMRPT_VSLAM_SANITIZE="$SANITIZE" >/dev/null
  fi
  # shellcheck disable=SC2086  # BUILD_TARGETS is a list
  cmake --build "$BUILD_DIR" -j "$JOBS" ${BUILD_TARGETS:+--target $BUILD_TARGETS}
}

install_missing_packages "${DEBIAN_PACKAGES[@]}"
# `source scripts/setup.sh --packages-only`: the packages, no build (scripts/fuzz.sh builds its own)
[ "${1:-}" = --packages-only ] || configure_and_build
