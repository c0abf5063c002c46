#!/usr/bin/env bash
# run.sh BUILD_DIR SECONDS: runs every libFuzzer target built in BUILD_DIR/fuzz for SECONDS each.
# Seeds come from fuzz/corpus/NAME (read-only) and keywords from fuzz/NAME.dict; inputs the
# fuzzer finds go to BUILD_DIR/fuzz-corpus/NAME, crashes to BUILD_DIR/fuzz-artifacts/. Exits
# non-zero if any target found a crash, leak, timeout or out-of-memory input.
set -uo pipefail
build=${1:?usage: fuzz/run.sh BUILD_DIR SECONDS}
seconds=${2:?usage: fuzz/run.sh BUILD_DIR SECONDS}
here=$(cd "$(dirname "$0")" && pwd)
shopt -s nullglob
targets=("$build"/fuzz/fuzz_*)
if [ ${#targets[@]} -eq 0 ]; then
  echo "fuzz/run.sh: no fuzz targets in $build/fuzz (configure with -DTG_FUZZ=ON and clang)" >&2
  exit 1
fi
mkdir -p "$build/fuzz-artifacts"
failed=()
for bin in "${targets[@]}"; do
  [ -x "$bin" ] || continue
  name=$(basename "$bin")
  corpus=${name#fuzz_}
  work="$build/fuzz-corpus/$corpus"
  mkdir -p "$work"
  dict=()
  [ -f "$here/$corpus.dict" ] && dict=(-dict="$here/$corpus.dict")
  echo "== $name: ${seconds}s (seeds: fuzz/corpus/$corpus)"
  if ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
     "$bin" "${dict[@]}" -max_total_time="$seconds" -max_len=65536 -rss_limit_mb=2048 -timeout=10 -print_final_stats=1 \
            -artifact_prefix="$build/fuzz-artifacts/$name-" "$work" "$here/corpus/$corpus" \
            >"$build/fuzz-artifacts/$name.log" 2>&1; then
    grep -E '^stat::(number_of_executed_units|new_units_added)' "$build/fuzz-artifacts/$name.log" | tr '\n' ' '
    echo
  else
    echo "FAILED: $name (log: $build/fuzz-artifacts/$name.log)"
    tail -n 30 "$build/fuzz-artifacts/$name.log"
    failed+=("$name")
  fi
done
if [ ${#failed[@]} -gt 0 ]; then
  echo "fuzz/run.sh: ${#failed[@]} target(s) failed: ${failed[*]}"
  exit 1
fi
echo "fuzz/run.sh: all targets ran ${seconds}s without findings"
