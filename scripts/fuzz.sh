#!/usr/bin/env bash
# Coverage-guided fuzzing of one target of tests/fuzz with libFuzzer: installs clang and its
# fuzzer runtime if missing, builds the target with libFuzzer, AddressSanitizer and UBSan into
# build-fuzz/, and runs it for SECONDS on a corpus in out/fuzz/TARGET/ (kept between runs, started
# from the shipped data: rawlogs also gunzipped, configs, text files). Crashing inputs go to
# out/fuzz/TARGET/crashes/. Prints libFuzzer's last status line (executions, coverage), writes
# the run's figures as the target's row of doc/results/fuzz.md (or $RESULTS), and exits non-zero
# if the target crashed.
# Usage: scripts/fuzz.sh TARGET SECONDS     TARGET: rawlog, config, text_files,
#        filter_step or camera_fit
# Environment: BUILD_DIR (default build-fuzz), JOBS, OUT (default out/fuzz), RESULTS.
set -euo pipefail
REPO_DIR="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
TARGET="${1:-}"
SECONDS_TO_RUN="${2:-}"
case "$TARGET" in
  rawlog | config | text_files | filter_step | camera_fit) ;;
  *) echo "usage: scripts/fuzz.sh rawlog|config|text_files|filter_step|camera_fit SECONDS" >&2; exit 2 ;;
esac
[[ "$SECONDS_TO_RUN" =~ ^[0-9]+$ ]] || { echo "fuzz.sh: SECONDS must be a whole number" >&2; exit 2; }

BUILD_DIR="${BUILD_DIR:-$REPO_DIR/build-fuzz}"
OUT="${OUT:-$REPO_DIR/out/fuzz}/$TARGET"
JOBS="${JOBS:-$(nproc)}"
RESULTS="${RESULTS:-$REPO_DIR/doc/results/fuzz.md}"

# the project's own packages (scripts/setup.sh without building), then clang's fuzzer runtime
source "$REPO_DIR/scripts/setup.sh" --packages-only
install_missing_packages clang libclang-rt-14-dev

generator=()
command -v ninja >/dev/null 2>&1 && generator=(-G Ninja)
[ -f "$BUILD_DIR/CMakeCache.txt" ] ||
  CC=clang CXX=clang++ cmake -S "$REPO_DIR" -B "$BUILD_DIR" "${generator[@]}" \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo -DMRPT_VSLAM_FUZZ=ON -DMRPT_VSLAM_BUILD_BENCHMARKS=OFF
cmake --build "$BUILD_DIR" -j "$JOBS" --target "fuzz_$TARGET"

# the corpus: the shipped inputs the target reads, once
mkdir -p "$OUT/corpus" "$OUT/crashes"
if [ -z "$(ls -A "$OUT/corpus")" ]; then
  case "$TARGET" in
    rawlog)
      for f in "$REPO_DIR"/datasets/*/*.rawlog; do
        [ "$(stat -c %s "$f")" -le 200000 ] || continue
        cp "$f" "$OUT/corpus/"
        gzip -dc "$f" > "$OUT/corpus/$(basename "$f").plain" 2>/dev/null || true
      done ;;
    config)  # several apps ship a template.ini: the app's name in front
      for f in "$REPO_DIR"/share/mrpt-vslam/config/*/*.ini; do
        cp "$f" "$OUT/corpus/$(basename "$(dirname "$f")")-$(basename "$f")"
      done ;;
    *) cp "$REPO_DIR"/tests/fuzz/seeds/* "$OUT/corpus/" ;;
  esac
fi
max_len=4096
timeout=60
# the reader validates a rawlog within 10 min (RawlogReader::validate); under the sanitizers a
# corrupt count that fills its memory bound in small blocks takes minutes: not a hang
[ "$TARGET" = rawlog ] && max_len=300000 && timeout=700
[ "$TARGET" = config ] && max_len=20000
cd "$OUT"
set +e
"$BUILD_DIR/fuzz/fuzz_$TARGET" "$OUT/corpus" -max_total_time="$SECONDS_TO_RUN" \
  -max_len="$max_len" -timeout="$timeout" -rss_limit_mb=6000 -artifact_prefix="$OUT/crashes/" \
  -print_final_stats=1 2> "$OUT/fuzz.log"
status=$?
set -e
last="$(grep -E "^#[0-9]+" "$OUT/fuzz.log" | tail -1)"
echo "$last"
# libFuzzer's final statistics (the last ones: a child process it forked may print its own)
final_stat() { sed -n "s/^stat::$1: *//p" "$OUT/fuzz.log" | tail -1; }
echo "executions: $(final_stat number_of_executed_units), peak RSS: $(final_stat peak_rss_mb) MB"

# the target's row of the results table (the other targets' rows kept)
field() { sed -n "s|.* $1: *\([0-9]*\).*|\1|p" <<< "$last"; }
executions="$(final_stat number_of_executed_units)"
outcome="no crash, no hang, no sanitizer report"
[ "$status" = 0 ] || outcome="**failed (exit $status)**: input in out/fuzz/$TARGET/crashes/"
row="| $TARGET | $(date -u '+%Y-%m-%d %H:%M') | $(git -C "$REPO_DIR" rev-parse --short HEAD) |"
row+=" $SECONDS_TO_RUN | ${executions:-?} | $(final_stat average_exec_per_sec) | $(field cov) | $(field ft) |"
row+=" $(sed -n 's/.* corp: *\([0-9]*\).*/\1/p' <<< "$last") | $outcome |"
if [ ! -f "$RESULTS" ]; then
  {
    echo "# Fuzzing: the long runs"
    echo
    echo "One row per fuzz target: its last run of \`scripts/fuzz.sh TARGET SECONDS\` (libFuzzer with"
    echo "AddressSanitizer and UBSan, clang $(clang --version | sed -n 's/.*version \([0-9.]*\).*/\1/p' | head -1)),"
    echo "on $(sed -n 's/^model name[[:space:]]*: *//p' /proc/cpuinfo | head -1) ($(nproc) cores): a run is one process, on at"
    echo "most one core, and other runs may share the machine. The corpus grows from run to run"
    echo "(out/fuzz/TARGET/corpus, started from the shipped data); executions and coverage are those of"
    echo "the run the row names. Coverage: libFuzzer's instrumented edges (cov) and features (ft) at the"
    echo "end of the run. The rawlog target forks a validating child per input (as the apps do), hence"
    echo "its few executions per second; camera_fit fits two camera models per input, about a second per"
    echo "input under the instrumentation."
    echo
    echo "| target | run (UTC) | commit | seconds | executions | executions/s | cov | ft | corpus | outcome |"
    echo "|---|---|---|---|---|---|---|---|---|---|"
  } > "$RESULTS"
fi
awk -v t="$TARGET" -v row="$row" '
  $0 ~ "^\\| " t " \\|" { if (!done) print row; done = 1; next }
  { print }
  END { if (!done) print row }' "$RESULTS" > "$RESULTS.tmp"
mv "$RESULTS.tmp" "$RESULTS"
[ "$status" = 0 ] || echo "fuzz_$TARGET failed (exit $status): see $OUT/fuzz.log and $OUT/crashes/" >&2
exit "$status"
