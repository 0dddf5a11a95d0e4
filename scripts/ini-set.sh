#!/usr/bin/env bash
# A copy of an .ini file with some keys set: SRC with the line of each KEY replaced by
# "KEY = VALUE". Every KEY must occur exactly once in SRC (in any section); otherwise one line
# names the key and the count, DST is not written and the exit status is 1.
# Usage: scripts/ini-set.sh SRC DST [KEY=VALUE ...]
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/command-usage.sh" "$@"
[ $# -ge 2 ] || { usage >&2; exit 2; }
src="$1" dst="$2"; shift 2
[ -r "$src" ] || { echo "$src: cannot read" >&2; exit 1; }
tmp="$(mktemp)"
trap 'rm -f "$tmp" "$tmp.next"' EXIT
cp "$src" "$tmp"
for kv in "$@"; do
  key="${kv%%=*}"
  [[ "$kv" == *=* && "$key" =~ ^[A-Za-z0-9_]+$ ]] ||
    { echo "$kv: expected KEY=VALUE with a key of letters, digits and _" >&2; exit 1; }
  n=$(grep -c -E "^[[:space:]]*${key}[[:space:]]*=" "$tmp" || true)
  [ "$n" = 1 ] || { echo "$src: key $key found $n times, expected once" >&2; exit 1; }
  awk -v k="$key" -v line="$key = ${kv#*=}" \
    '$0 ~ "^[ \t]*" k "[ \t]*=" { print line; next } { print }' "$tmp" > "$tmp.next"
  mv "$tmp.next" "$tmp"
done
mv "$tmp" "$dst"
