#!/usr/bin/env bash
# One source for every figure: a results figure on a documentation page must come from a file
# under doc/results/ that a reproduce or bench script writes. Checked on the pages listed below:
# every number with two or more decimals (outside fenced code blocks) must appear in a results
# file, or be a parameter or constant that a shipped config or the libraries' code holds.
# Usage: check-doc-figures.sh SOURCE_DIR
set -euo pipefail
src="$(cd "$1" && pwd)"
cd "$src"
pages=(README.md doc/*.md)
# numbers NAME...: the numbers with two or more decimals in the files, one per line
numbers() { grep -ohE '(^|[^0-9.])[0-9]+\.[0-9]{2,}' "$@" | grep -oE '[0-9]+\.[0-9]+' || true; }
known="$(mktemp)"
trap 'rm -f "$known"' EXIT
{
  numbers doc/results/*.md
  mapfile -t sources < <(find share -name '*.ini'
    find libs -path '*/tests' -prune -o \( -name '*.h' -o -name '*.cpp' \) -print)
  numbers "${sources[@]}"
} | sort -u > "$known"
status=0
for page in "${pages[@]}"; do
  # the page without its fenced code blocks and code spans, with line numbers
  while IFS=: read -r line n; do
    grep -qxF "$n" "$known" || { echo "$page:$line: $n is in no results file under doc/results/"; status=1; }
  done < <(awk '/^```/ { code = !code; next } !code { gsub(/`[^`]*`/, ""); print NR ":" $0 }' "$page" |
           while IFS=: read -r line text; do
             for n in $(grep -oE '(^|[^0-9.])[0-9]+\.[0-9]{2,}' <<< "$text" | grep -oE '[0-9]+\.[0-9]+'); do
               echo "$line:$n"
             done
           done)
done
# every link to a file of the repository (the pages, doc/results/ and its plots) leads to one
for page in "${pages[@]}" doc/results/*.md; do
  while read -r target; do
    [ -e "$(dirname "$page")/${target%%#*}" ] ||
      { echo "$page: links to $target, which is not in the repository"; status=1; }
  done < <(grep -oE '\]\([^)#][^) ]*\)' "$page" | sed -E 's/^\]\((.*)\)$/\1/' |
           grep -vE '^[a-z]+:' || true)
done
[ "$status" = 0 ] && echo "doc figures: every figure on ${#pages[@]} pages is in a results file or" \
  "the code, and every link leads to a file"
exit "$status"
