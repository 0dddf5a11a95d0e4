# Sourced by the command-line scripts, with their arguments, after their `set -euo pipefail`:
# defines usage (the script's header comment, from its second line to that `set` line) and
# prints it on -h or --help (exit 0), or on stderr without arguments or with an unknown option
# (exit 2).
usage() { sed -n '2,/^set -euo/p' "$0" | sed -e '$d' -e 's/^# \{0,1\}//'; }
case "${1:-}" in
  -h | --help) usage; exit 0 ;;
  "" | -*) usage >&2; exit 2 ;;
esac
