#!/bin/bash
# The filters' requests ahead are in the code the compiler made: each function named below holds
# a prefetch instruction. GCC deletes prefetches it finds no effect of (a call to a function that
# only prefetches, a loop that only does); core::prefetchObject() is written so that it cannot.
# Usage: check-prefetch-emitted.sh <build dir>
set -euo pipefail
case "$(uname -m)" in
  x86_64 | i?86) ;;
  *) echo "SKIPPED: the prefetch instructions are looked for on x86 only"; exit 77 ;;
esac
build="${1:?usage: check-prefetch-emitted.sh <build dir>}"
fail=0
# check <library> <function name part>...: a function whose name holds each part has a prefetch
check() {
  local name="$1" lib="$build/lib/$1"
  shift
  if [[ ! -f "$lib" ]]; then
    echo "check-prefetch-emitted: $lib: not found" >&2
    exit 1
  fi
  local with
  with=$(objdump -d --no-show-raw-insn -C "$lib" |
    awk '/^[0-9a-f]+ <.*>:$/ { fn = $0 } /\tprefetch/ { has[fn] = 1 } END { for (f in has) print f }')
  for part in "$@"; do
    if grep -qF -- "$part" <<<"$with"; then
      echo "ok: $name ${part}"
    else
      echo "FAILED: no prefetch instruction in a function of $name named *${part}*"
      fail=1
    fi
  done
}
check libmrpt_vslam_multirobot.so 'CVisualLandmarksMap::associate(' \
  'CVisualLandmarksMap::prefetchAssociation(' 'ParticleFilterDataImpl<mrpt_vslam::multirobot::CMultiRobotVisualSLAM,' \
  'CMultiRobotVisualSLAM::runStep(' 'CMultiRobotVisualSLAM::forEachParticle('
check libmrpt_vslam_omni_fastslam.so 'ParticleFilterDataImpl<mrpt_vslam::omni_fastslam::COmniFastSLAM,'
exit $fail
