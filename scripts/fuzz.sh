#!/usr/bin/env bash
# Builds the libFuzzer targets (tests/fuzz) with clang, ASan and UBSan into build-fuzz/ (the
# library and the fuzzers only) and runs both, side by side. See docs/reliability.md.
#   scripts/fuzz.sh --short      30 s (both fuzzers at once; a quick check at a session's stop)
#   scripts/fuzz.sh --long       until each fuzzer has run FUZZ_RUNS inputs (default 1000000)
#   scripts/fuzz.sh --time N     N seconds per fuzzer
# New inputs that reach new code go to build-fuzz/corpus/<target>/ (seeded from the repository's
# tests/fuzz/corpus/<target>/, which stays small); a crash is written to build-fuzz/crashes/ and
# fails the script. Copy a fixed crash into tests/fuzz/corpus/<target>/ so the normal test suite
# (fuzz.replay.*) replays it from then on. FUZZ_BUILD_DIR overrides the build folder.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"

mode=short
seconds=30
runs=${FUZZ_RUNS:-1000000}
case "${1:---short}" in
  --short) mode=short; seconds=30 ;;
  --long) mode=long ;;
  --time) mode=short; seconds=${2:?--time needs seconds} ;;
  *) echo "usage: scripts/fuzz.sh [--short|--long|--time SECONDS]" >&2; exit 2 ;;
esac

if ! command -v clang++ >/dev/null || ! ls /usr/lib/llvm-*/lib/clang/*/lib/linux/libclang_rt.fuzzer-x86_64.a >/dev/null 2>&1; then
  echo "fuzz.sh: needs clang and libFuzzer: run scripts/setup.sh --fuzz (apt-get install clang libclang-rt-14-dev)" >&2
  exit 1
fi
build_dir="${FUZZ_BUILD_DIR:-$root/build-fuzz}"
launcher=()
if command -v ccache >/dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
cmake -S "$root" -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG" \
  -DCMAKE_CXX_COMPILER=clang++ "${launcher[@]}" -DANYPHYS_BUILD_FUZZERS=ON \
  -DANYPHYS_BUILD_TESTS=OFF -DANYPHYS_BUILD_TOOLS=OFF -DANYPHYS_BUILD_BENCH=OFF \
  -DANYPHYS_BUILD_DEMOS=OFF -DANYPHYS_BUILD_TESTBED=OFF -DANYPHYS_UNITY_BUILD_LIBRARY=ON >/dev/null
cmake --build "$build_dir" --target anyphys_fuzz_scene_json anyphys_fuzz_api_calls

export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1}"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
mkdir -p "$build_dir/crashes"
limit=(-max_total_time="$seconds")
if [[ $mode == long ]]; then limit=(-runs="$runs"); fi
targets=(scene_json api_calls)
# The two fuzzers run side by side, one per core (this machine and CI have two).
pids=()
for target in "${targets[@]}"; do
  corpus="$build_dir/corpus/$target"
  mkdir -p "$corpus"
  echo "==== fuzz.sh: $target (${limit[*]}), log $build_dir/$target.log"
  # -timeout: an input that takes more than 30 s is a hang worth a look (inputs are capped to be
  # cheap: the slowest of 1.2 million took under a second on a quiet core).
  # -entropic=0: libFuzzer's entropic scheduling spent half the time updating its feature
  # frequencies (perf), 135 -> 2200 inputs/s on the scene fuzzer without it.
  "$build_dir/tests/fuzz/anyphys_fuzz_$target" "$corpus" "tests/fuzz/corpus/$target" \
    "${limit[@]}" -entropic=0 -timeout=30 -rss_limit_mb=2048 -max_len=4096 -print_final_stats=1 \
    -artifact_prefix="$build_dir/crashes/$target-" 2>"$build_dir/$target.log" &
  pids+=($!)
done
start=$SECONDS
status=0
for i in "${!targets[@]}"; do
  target=${targets[$i]}
  if ! wait "${pids[$i]}"; then
    echo "fuzz.sh: $target FAILED after $((SECONDS - start)) s; log: $build_dir/$target.log" >&2
    tail -40 "$build_dir/$target.log" >&2
    status=1
  else
    grep -E "stat::number_of_executed_units|stat::peak_rss_mb" "$build_dir/$target.log" | sed "s/^/$target /" || true
    echo "fuzz.sh: $target passed"
  fi
done
exit $status
