#!/usr/bin/env bash
# Builds the libFuzzer targets (tests/fuzz) with clang, ASan and UBSan into build-fuzz/ (the
# library and the fuzzers only) and runs each one. See docs/reliability.md.
#   scripts/fuzz.sh --short      about 60 s per fuzzer (CI)
#   scripts/fuzz.sh --long       until each fuzzer has run FUZZ_RUNS inputs (default 1000000)
#   scripts/fuzz.sh --time N     N seconds per fuzzer
# New inputs that reach new code go to build-fuzz/corpus/<target>/ (seeded from the repository's
# tests/fuzz/corpus/<target>/, which stays small); a crash is written to build-fuzz/crashes/ and
# fails the script. Copy a fixed crash into tests/fuzz/corpus/<target>/ so the normal test suite
# (fuzz.replay.*) replays it from then on.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"

mode=short
seconds=60
runs=${FUZZ_RUNS:-1000000}
case "${1:---short}" in
  --short) mode=short; seconds=60 ;;
  --long) mode=long ;;
  --time) mode=short; seconds=${2:?--time needs seconds} ;;
  *) echo "usage: scripts/fuzz.sh [--short|--long|--time SECONDS]" >&2; exit 2 ;;
esac

build_dir="$root/build-fuzz"
launcher=()
if command -v ccache >/dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
cmake -S "$root" -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG" \
  -DCMAKE_CXX_COMPILER=clang++ "${launcher[@]}" -DANYPHYS_BUILD_FUZZERS=ON \
  -DANYPHYS_BUILD_TESTS=OFF -DANYPHYS_BUILD_TOOLS=OFF -DANYPHYS_BUILD_BENCH=OFF \
  -DANYPHYS_BUILD_DEMOS=OFF -DANYPHYS_BUILD_TESTBED=OFF >/dev/null
cmake --build "$build_dir" --target anyphys_fuzz_scene_json anyphys_fuzz_api_calls

export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1}"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
mkdir -p "$build_dir/crashes"
status=0
for target in scene_json api_calls; do
  corpus="$build_dir/corpus/$target"
  mkdir -p "$corpus"
  limit=(-max_total_time="$seconds")
  if [[ $mode == long ]]; then limit=(-runs="$runs"); fi
  echo "==== fuzz.sh: $target (${limit[*]})"
  start=$SECONDS
  # -timeout: an input that takes more than 10 s is a hang worth a look (inputs are capped to be cheap).
  # -entropic=0: libFuzzer's entropic scheduling spent half the time updating its feature
  # frequencies (perf), 135 -> 2200 inputs/s on the scene fuzzer without it.
  if ! "$build_dir/tests/fuzz/anyphys_fuzz_$target" "$corpus" "tests/fuzz/corpus/$target" \
      "${limit[@]}" -entropic=0 -timeout=10 -rss_limit_mb=2048 -max_len=4096 -print_final_stats=1 \
      -artifact_prefix="$build_dir/crashes/$target-" 2>"$build_dir/$target.log"; then
    echo "fuzz.sh: $target FAILED after $((SECONDS - start)) s; log: $build_dir/$target.log" >&2
    tail -40 "$build_dir/$target.log" >&2
    status=1
  else
    grep -E "stat::number_of_executed_units|stat::peak_rss_mb" "$build_dir/$target.log" || true
    echo "fuzz.sh: $target passed in $((SECONDS - start)) s"
  fi
done
exit $status
