#!/usr/bin/env bash
# Configures (Ninja, Release unless overridden) and builds anyphys.
# Usage: scripts/build.sh [BUILD_DIR] [extra cmake args...]
#   BUILD_DIR: default `build`; a relative path is taken relative to the repository root.
# Extra args go to the configure step, e.g.  scripts/build.sh build-dbg -DCMAKE_BUILD_TYPE=Debug
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build_dir="${1:-build}"
shift || true
case "$build_dir" in
  /*) ;;
  *) build_dir="$root/$build_dir" ;;
esac

# A fresh build directory gets Ninja and Release; an existing one keeps its generator and build
# type (so re-running on build-asan/ does not flip it to Release). Extra args always apply.
defaults=(-G Ninja -DCMAKE_BUILD_TYPE=Release)
if [[ -f "$build_dir/CMakeCache.txt" ]]; then
  defaults=()
fi
cmake -S "$root" -B "$build_dir" "${defaults[@]}" "$@"
cmake --build "$build_dir"
