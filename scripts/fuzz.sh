#!/usr/bin/env bash
# Runs every libFuzzer target of a configured-and-built AVAR_LIBFUZZER tree for a bounded time,
# one after the other, each on a copy of its seed corpus (fuzz/corpus/<name>, never written to)
# with its dictionary (fuzz/dict/<name>.dict) when there is one, and prints one line per target:
#   fuzz,target=<name>,seconds=<s>,execs=<n>,execs_per_s=<r>,cov=<edges>,ft=<features>,corpus=<files>,crashes=<k>
# Crashes, leaks, timeouts (-timeout=2 s: a hang) and out-of-memory inputs are saved in
# <build>/artifacts/ and make the script exit 1. Usage: scripts/fuzz.sh BUILD SECONDS [TARGET...]
# FUZZ_RUNS=N in the environment also ends a target after N executions (whichever comes first), so
# a long report run (FUZZ_RUNS=1000000 FUZZ_SECONDS=3600) spends on each target only what it needs.
set -uo pipefail
build=${1:?usage: fuzz.sh BUILD SECONDS [TARGET...]}
seconds=${2:?usage: fuzz.sh BUILD SECONDS [TARGET...]}
shift 2
source_dir=$(cd "$(dirname "$0")/.." && pwd)
if [ $# -gt 0 ]; then targets=("$@"); else mapfile -t targets < "$build/fuzz/targets.txt"; fi
artifacts="$build/artifacts"
mkdir -p "$artifacts"
failed=0
for name in "${targets[@]}"; do
  [ -n "$name" ] || continue
  binary="$build/fuzz/avar_fuzz_$name"
  if [ ! -x "$binary" ]; then
    echo "fuzz,target=$name,error=not built ($binary)"
    failed=1
    continue
  fi
  work="$build/fuzz-work/$name"
  rm -rf "$work"
  mkdir -p "$work/corpus"
  cp -r "$source_dir/fuzz/corpus/$name/." "$work/corpus/" 2>/dev/null
  runs=()
  [ -n "${FUZZ_RUNS:-}" ] && runs=("-runs=$FUZZ_RUNS")
  dict=()
  [ -f "$source_dir/fuzz/dict/$name.dict" ] && dict=("-dict=$source_dir/fuzz/dict/$name.dict")
  start=$(date +%s)
  before=$(find "$artifacts" -name "$name-*" | wc -l)
  # -close_fd_mask=3: the targets' own output (urdfdom's console) is dropped; libFuzzer's and the
  # sanitizers' reports still reach the log.
  ASAN_OPTIONS=detect_leaks=1:allocator_may_return_null=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    "$binary" "$work/corpus" "${dict[@]}" "${runs[@]}" -max_total_time="$seconds" -timeout=2 -rss_limit_mb=2048 -max_len=8192 \
    -print_final_stats=1 -close_fd_mask=3 -artifact_prefix="$artifacts/$name-" > "$work/log" 2>&1
  status=$?
  took=$(($(date +%s) - start))
  after=$(find "$artifacts" -name "$name-*" | wc -l)
  crashes=$((after - before))
  [ $status -ne 0 ] && [ $crashes -eq 0 ] && crashes=1
  stat() { sed -n "s/^stat::$1: *//p" "$work/log" | tail -1; }
  execs=$(stat number_of_executed_units)
  rate=$(stat average_exec_per_sec)
  last=$(grep -E '^#[0-9]+' "$work/log" | grep ' cov: ' | tail -1)
  cov=$(sed -n 's/.* cov: \([0-9]*\).*/\1/p' <<< "$last")
  ft=$(sed -n 's/.* ft: \([0-9]*\).*/\1/p' <<< "$last")
  files=$(find "$work/corpus" -type f | wc -l)
  echo "fuzz,target=$name,seconds=$took,execs=${execs:-0},execs_per_s=${rate:-0},cov=${cov:-0},ft=${ft:-0},corpus=$files,crashes=$crashes"
  if [ $crashes -ne 0 ]; then
    failed=1
    echo "  log: $work/log; artifacts: $artifacts/$name-*" >&2
    grep -m1 -E 'ERROR: |runtime error|deadly signal|Timeout|out-of-memory' "$work/log" | sed 's/^/  /' >&2
  fi
done
exit $failed
