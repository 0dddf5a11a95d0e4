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
  if ! clang-format --dry-run --Werror "$f" >/dev/null 2>&1; then
    echo "not formatted: $f"
    bad=$((bad + 1))
  fi
done < <(find libs apps tests \( -name '*.cpp' -o -name '*.h' \) -print0 | sort -z)
echo "check-format.sh: $bad file(s) not formatted"
[ "$bad" -eq 0 ]
