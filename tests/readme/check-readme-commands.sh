#!/usr/bin/env bash
# Runs the per-app commands of README.md ("Run each app on its shipped dataset") as a user would
# after scripts/run-demo.sh, and checks that each writes what the README says: the run folder's
# files, a completed run.json, vslam-eval's plots; and that every repository or build path the
# README names exists. Usage: check-readme-commands.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
src="$(cd "$1" && pwd)"
build="$(cd "$2" && pwd)"
readme="$src/README.md"
scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT
fail() { echo "README.md: $*" >&2; exit 1; }

# The user's view: the repository's folders, and build/ holding the build tree.
ln -s "$src/share" "$scratch/share"
ln -s "$src/datasets" "$scratch/datasets"
mkdir "$scratch/build"
ln -s "$build/bin" "$scratch/build/bin"
ln -s "$build/lib" "$scratch/build/lib"

# The fenced bash blocks that start with build/bin/ (one command each, joined at its backslashes).
mapfile -t commands < <(awk '
  /^```bash$/ { block = 1; cmd = ""; next }
  /^```$/ { if (block && cmd ~ /^build\/bin\//) print cmd; block = 0; next }
  block { line = $0; sub(/^[ \t]+/, "", line); cont = sub(/[ \t]*\\$/, " ", line); cmd = cmd line }
' "$readme")
[ "${#commands[@]}" -eq 3 ] || fail "expected 3 app commands, found ${#commands[@]}"

for cmd in "${commands[@]}"; do
  out="$(sed -n 's/.*--out \([^ ]*\).*/\1/p' <<< "$cmd")"
  [ -n "$out" ] || fail "no --out in: $cmd"
  echo "running: $cmd"
  (cd "$scratch" && eval "$cmd" --quiet > "$scratch/log" 2>&1) || { cat "$scratch/log" >&2; fail "failed: $cmd"; }
  for f in config.ini run.json metrics.json map.txt final_map.gz final.3Dscene; do
    [ -s "$scratch/$out/$f" ] || fail "$cmd: no $out/$f"
  done
  compgen -G "$scratch/$out/estimated_path*.tum" > /dev/null || fail "$cmd: no $out/estimated_path*.tum"
  grep -q '"completed": true' "$scratch/$out/run.json" || fail "$cmd: run.json does not say completed"
  # metrics.json: every estimate's position error finite and below 1 m (the shipped datasets'
  # runs are far better; dead reckoning is not checked)
  python3 - "$scratch/$out/metrics.json" <<'PY' || fail "$cmd: metrics.json without a plausible estimate ATE"
import json, math, sys
def ates(j, in_estimate=False):
    if isinstance(j, dict):
        for k, v in j.items():
            if k == "ate_rmse_m" and in_estimate: yield v
            else: yield from ates(v, in_estimate or k == "estimate")
    elif isinstance(j, list):
        for v in j: yield from ates(v, in_estimate)
a = list(ates(json.load(open(sys.argv[1]))))
print("estimate ATE RMSE [m]:", " ".join("%.3f" % x for x in a))
sys.exit(0 if a and all(math.isfinite(x) and 0 <= x < 1 for x in a) else 1)
PY
  (cd "$scratch" && build/bin/vslam-eval "$out" > "$scratch/eval.log" 2>&1) || { cat "$scratch/eval.log" >&2; fail "vslam-eval $out failed"; }
  for f in paths.png errors.png; do [ -s "$scratch/$out/$f" ] || fail "vslam-eval $out: no $f"; done
done

# Every path the README names in backquotes or links (repository files, build outputs) exists.
{ tr '\n' ' ' < "$readme" | grep -o '`[^`]*`' | tr -d '`'; grep -o '](\([^)]*\))' "$readme" | sed -e 's/^](\(.*\))$/\1/' -e 's/#.*//'; } |
  tr ' ' '\n' |
  grep -E '^(build/(bin|lib)|datasets|share|doc|scripts)/' | sort -u | while read -r p; do
    case "$p" in
      build/*) [ -e "$scratch/$p" ] || fail "names $p, which the build does not have" ;;
      *) [ -e "$src/$p" ] || fail "names $p, which the repository does not have" ;;
    esac
  done
echo "README commands: ${#commands[@]} apps ran and wrote what the README says"
