#!/usr/bin/env bash
# Usage: scripts/lint-changed.sh [BASE]
# Lints only what changed since BASE (default: the commit in .ci/lint-base), working tree included:
#  - formatting (.clang-format) of the changed lines of every C++ file, tests included;
#  - clang-tidy (.clang-tidy) on the changed lines of the changed .cpp files that the lint tree's
#    compile_commands.json lists (the libraries, apps and benchmarks; tests are not tidied).
# The lint tree is $LINT_BUILD (default build-lint), configured only, one database entry per source
# file; `make lint` configures it and runs this script.
set -euo pipefail
cd "$(dirname "$0")/.."

build=${LINT_BUILD:-build-lint}
base=${1:-$(sed -n '/^[0-9a-f]\{7,40\}$/{p;q}' .ci/lint-base)}
if [ -z "$base" ]; then
  echo "lint: no commit in .ci/lint-base; give one: scripts/lint-changed.sh BASE" >&2
  exit 1
fi
if ! git rev-parse -q --verify "$base^{commit}" >/dev/null; then
  if ! git rev-parse -q --verify "HEAD~1^{commit}" >/dev/null; then
    echo "lint: neither $base nor HEAD~1 is in this clone (shallow, depth 1); nothing to compare against, lint skipped"
    exit 0
  fi
  echo "lint: $base is not in this clone (shallow?); checking the changes since HEAD~1 instead"
  base=HEAD~1
fi

mapfile -t files < <(git diff --name-only --diff-filter=ACMR "$base" -- '*.cpp' '*.hpp' '*.h')
if [ ${#files[@]} -eq 0 ]; then
  echo "lint: no C++ file changed since $(git rev-parse --short "$base")"
  exit 0
fi
changed_lines=$(git diff --numstat "$base" -- "${files[@]}" | awk '{ n += $1 } END { print n + 0 }')
failed=0

# Formatting: clang-format-diff reformats only the changed lines; any output is a difference.
# Its hunks carry 3 lines of context, so the first removed line of each hunk is reported.
format_diff=$(git diff -U0 --no-color "$base" -- "${files[@]}" | clang-format-diff-14 -p1 -binary clang-format-14)
if [ -n "$format_diff" ]; then
  failed=1
  echo "lint: changed lines are not formatted as .clang-format says:"
  awk '/^--- /   { sub(/^--- /, ""); sub(/\t.*/, ""); file = $0; next }
       /^\+\+\+ / { next }
       /^@@ /    { split($2, a, ","); line = -a[1]; shown = 0; next }
       /^ /      { line++; next }
       /^-/      { if (!shown) print "  " file ":" line ": format"; shown = 1; line++ }' <<<"$format_diff"
  echo "$format_diff"
  echo "lint: to fix, run: git clang-format-14 $base   (it rewrites only the changed lines; review, then commit)"
fi

# clang-tidy, on the .cpp files the lint tree knows (new files appear once CMake lists them).
database="$build/compile_commands.json"
if [ ! -f "$database" ]; then
  echo "lint: no $database; run make lint (it configures $build), or set LINT_BUILD to a configured tree" >&2
  exit 1
fi
tidy_files=()
for f in "${files[@]}"; do
  if [[ $f == *.cpp ]] && grep -qF "\"file\": \"$PWD/$f\"" "$database"; then tidy_files+=("$f"); fi
done
tidy_state="tidy ok (${#tidy_files[@]} files)"
if [ ${#tidy_files[@]} -gt 0 ]; then
  tidy_out=$(git diff -U0 --no-color "$base" -- "${tidy_files[@]}" |
             clang-tidy-diff-14.py -p1 -path "$build" -j 2 -quiet -clang-tidy-binary clang-tidy-14 2>&1 |
             grep -v -e '^$' -e '^[0-9]* warnings\? generated\.$' -e '^No relevant changes found\.$' || true)
  if grep -qE '^[^ ]+:[0-9]+:[0-9]+: (warning|error):' <<<"$tidy_out"; then
    failed=1
    tidy_state="tidy FAILED"
    echo "lint: clang-tidy on the changed lines:"
    echo "$tidy_out"
    grep -E '^[^ ]+:[0-9]+:[0-9]+: (warning|error):' <<<"$tidy_out" | sed -E 's/^([^ ]+:[0-9]+):[0-9]+: /  \1: /'
    echo "lint: fix these lines (the check's name is in brackets; .clang-tidy says which checks run and why)," \
         "then rerun: scripts/lint-changed.sh $base"
  fi
fi

if [ "$failed" -ne 0 ]; then
  echo "lint: FAILED since $(git rev-parse --short "$base"): ${#files[@]} files, $changed_lines changed lines" >&2
  exit 1
fi
echo "lint: ${#files[@]} files, $changed_lines changed lines, format ok, $tidy_state"
