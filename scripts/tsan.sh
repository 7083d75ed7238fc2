#!/usr/bin/env bash
# ThreadSanitizer stage (docs/threads.md): builds the library and the one test target that steps
# worlds of every backend concurrently (tests/threads) into build-tsan/ with -fsanitize=thread,
# and runs it. Nothing else is built, to keep the stage cheap.
# Usage: scripts/tsan.sh   (TSAN_BUILD_DIR overrides the build folder)
# The engines (ODE, Bullet, Box2D) are Debian's uninstrumented libraries: TSan sees what our code
# does around them (their globals reached through our calls), not races inside them.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build_dir="${TSAN_BUILD_DIR:-$root/build-tsan}"
launcher=()
if command -v ccache >/dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
cmake -S "$root" -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG" \
  "-DCMAKE_CXX_FLAGS=-fsanitize=thread" "-DCMAKE_EXE_LINKER_FLAGS=-fsanitize=thread" \
  "${launcher[@]}" -DANYPHYS_BUILD_TESTS=ON -DANYPHYS_BUILD_TOOLS=OFF -DANYPHYS_BUILD_BENCH=OFF \
  -DANYPHYS_BUILD_DEMOS=OFF -DANYPHYS_BUILD_TESTBED=OFF -DANYPHYS_UNITY_BUILD_LIBRARY=ON >/dev/null
cmake --build "$build_dir" --target anyphys_thread_tests
# halt_on_error: the first race fails the stage; second_deadlock_stack: full lock-order reports.
TSAN_OPTIONS="halt_on_error=1:second_deadlock_stack=1" "$build_dir/tests/anyphys_thread_tests"
