# shellcheck shell=bash
# Sourced by the reproduce and bench scripts: how a results file under doc/results/ says where
# its figures come from, and how the scripts read the lists given in their environment. Source it
# before the script's environment variables are changed.

# words LIST: the list on one line, one space between its items (SEEDS="$(seq 11 25)" gives
# one item a line, which the tables and file names that print a list cannot take)
words() {
  local -a items
  read -r -d '' -a items <<< "$1" || true
  echo "${items[*]}"
}

RESULTS_LOAD_START="$(cut -d' ' -f1-3 /proc/loadavg)"
RESULTS_T_START=$EPOCHREALTIME

# results_command SCRIPT VAR...: the command line that made the file, with those of the
# variables that were given to it (e.g. "SEEDS=1\ 2 scripts/reproduce-x.sh")
results_command() {
  local script="$1" v
  shift
  for v in "$@"; do
    [ -z "${!v+x}" ] || printf '%s=%q ' "$v" "${!v}"
  done
  echo "$script"
}

# results_header TITLE COMMAND: the file's title, then when, on which machine (CPU, cores, load
# at the start and at the end), with which MRPT, by which command and in how long it was made
results_header() {
  echo "# $1"
  echo
  echo "Made $(date -u '+%Y-%m-%d %H:%M UTC') on" \
    "$(sed -n 's/^model name[[:space:]]*: *//p' /proc/cpuinfo | head -1), $(nproc) cores" \
    "(load average $RESULTS_LOAD_START at the start, $(cut -d' ' -f1-3 /proc/loadavg) at the" \
    "end), MRPT $(dpkg-query -W -f='${Version}' libmrpt-dev 2>/dev/null || echo '?'), by" \
    "\`$2\` in $(awk -v a="$RESULTS_T_START" -v b="$EPOCHREALTIME" \
      'BEGIN { printf "%.1f", (b - a) / 60 }') min."
  echo
}
