# Sourced by the simul-landmarks checks, with their arguments SOURCE_DIR BUILD_DIR: sets src and
# build (absolute), scratch (a folder removed on exit) and fail MESSAGE; exits 77 (skipped)
# without mrpt-apps' simul-landmarks and rawlog-edit.
set -euo pipefail
src="$(cd "$1" && pwd)"
build="$(cd "$2" && pwd)"
for tool in simul-landmarks rawlog-edit; do
  command -v "$tool" > /dev/null || { echo "skipped: $tool not found (mrpt-apps)"; exit 77; }
done
scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT
fail() { echo "FAILED: $*" >&2; exit 1; }
