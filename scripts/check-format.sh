#!/usr/bin/env bash
# Checks that every C++ file of libs/, apps/ and tests/ is formatted as .clang-format says
# (clang-format 14, Debian 12); prints the files that are not and exits 1. Fix with:
#   find libs apps tests -name '*.cpp' -o -name '*.h' | xargs clang-format -i
set -euo pipefail
REPO_DIR="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$REPO_DIR"
command -v clang-format >/dev/null || { echo "check-format.sh: clang-format is not installed" >&2; exit 2; }
bad=0
while IFS= read -r -d '' f; do
  status=0
  out="$(clang-format --dry-run --Werror "$f" 2>&1 >/dev/null)" || status=$?
  if [ "$status" -ne 0 ]; then
    if grep -q 'clang-format-violations' <<<"$out"; then
      echo "not formatted: $f"
    else  # clang-format itself failed: say how, so that it is not taken for a format error
      echo "clang-format failed on $f (exit $status): $(head -n 1 <<<"$out")"
    fi
    bad=$((bad + 1))
  fi
done < <(find libs apps tests \( -name '*.cpp' -o -name '*.h' \) -print0 | sort -z)
echo "check-format.sh: $bad file(s) not formatted"
[ "$bad" -eq 0 ]
