#!/usr/bin/env bash
# Builds and runs the benchmark suite (docs/benchmarks.md), then prints one Markdown report: every
# scene on every backend beside the raw engines, the per-body cost from 1 000 to 50 000 bodies,
# the 2-worker speed-up, the wrapper overhead, allocations per steady step, and the targets of
# issue 9 with PASS / FAIL. All figures come from this one run; the machine's load is printed at
# the start, after each program and at the end (timings on a loaded machine are not worth
# comparing across runs).
#
# Usage: scripts/bench.sh [--quick] [--all] [--effects] [BUILD_DIR]
#   --quick     (or QUICK=1) a fifth of each scene's steps and one round of each side-by-side
#               comparison, about 4 minutes: checks that the instruments work; its figures are
#               not measurements
#   --all       (or ALL=1) also what a default run leaves out for time (listed in its output): ODE
#               on the 5 050-box pyramids (about 1 s per step) and the per-body cost series on
#               every backend; about 15 minutes more
#   --effects   (or EFFECTS=1) only the special effects (anyphys_bench_effects): a pile with none
#               through World::step against its bare backend peer, and each effect's cost per step,
#               REPS (default 3) repetitions, medians printed; about 20 minutes. A default run
#               includes them once.
#   BUILD_DIR   default `build`, relative to the repository root; configured and built with
#               scripts/build.sh (Release for a fresh directory) unless NOBUILD=1
#   OUT=DIR     where the JSON results and console logs go (default BUILD_DIR/bench-results)
# A default run steps the engines for about 12 minutes of CPU time on a 2-core machine (longer in
# wall time when the machine is busy). Exits non-zero only when something could not be built or
# run; a failed target is a finding, not an error.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
quick="${QUICK:-}"
all="${ALL:-}"
effects="${EFFECTS:-}"
build_dir=""
for arg in "$@"; do
  case "$arg" in
    --quick) quick=1 ;;
    --all) all=1 ;;
    --effects) effects=1 ;;
    -h|--help) awk 'NR > 1 && !/^#/ { exit } NR > 1 { print }' "${BASH_SOURCE[0]}"; exit 0 ;;
    -*) echo "bench.sh: unknown option $arg (see --help)" >&2; exit 2 ;;
    *) build_dir="$arg" ;;
  esac
done
build_dir="${build_dir:-build}"
case "$build_dir" in
  /*) ;;
  *) build_dir="$root/$build_dir" ;;
esac
out="${OUT:-$build_dir/bench-results}"

if [[ -z "${NOBUILD:-}" ]]; then
  bash "$root/scripts/build.sh" "$build_dir" -DANYPHYS_BUILD_BENCH=ON >&2
fi
bin="$build_dir/bench"
main_program=anyphys_bench_scenes
[[ -n "$effects" ]] && main_program=anyphys_bench_effects
[[ -x "$bin/$main_program" && -x "$bin/anyphys_bench_report" ]] ||
  { echo "bench.sh: no benchmark programs in $bin (built with -DANYPHYS_BUILD_BENCH=OFF?)" >&2; exit 1; }
mkdir -p "$out"
rm -f "$out"/anyphys_bench_*.json "$out"/anyphys_bench_*.log  # this run's only

loadavg() { cut -d' ' -f1-3 /proc/loadavg; }
mode_args=()
[[ -n "$quick" ]] && mode_args=(--quick)

echo "# anyphys benchmarks${quick:+ (QUICK: a fifth of the steps; not a measurement)}"
echo
echo "- machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), $(nproc) cores"
commit=$(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo unknown)
if [[ -n "$(git -C "$root" status --porcelain 2>/dev/null)" ]]; then commit="$commit + uncommitted changes"; fi
echo "- anyphys: $commit; build: $build_dir"
echo "- started $(date -u +%FT%TZ), load $(loadavg)"

# run NAME FILTER [ARGS...]: one program, JSON into $out/NAME.json, its console table into
# $out/NAME.log.
run() {
  local name=$1 filter=$2 start=$SECONDS
  shift 2
  if [[ ! -x "$bin/$name" ]]; then
    echo "- $name: not built (its engine was not found); skipped"
    return
  fi
  "$bin/$name" "${mode_args[@]}" "$@" --benchmark_filter="$filter" --benchmark_color=false \
    --benchmark_out="$out/$name.json" --benchmark_out_format=json >"$out/$name.log" 2>&1 ||
    { echo "bench.sh: $name failed; see $out/$name.log" >&2; exit 1; }
  echo "- $name: $((SECONDS - start)) s, load after it $(loadavg)"
}

if [[ -n "$effects" ]]; then
  run anyphys_bench_effects '.' --benchmark_repetitions="${REPS:-3}"
  echo "- finished $(date -u +%FT%TZ), load $(loadavg)"
  echo
  "$bin/anyphys_bench_report" --effects "$out/anyphys_bench_effects.json"
  exit 0
fi

# Every scene and the 2-worker runs on every backend, but (unless --all) without ODE on the
# 5 050-box pyramids, which alone would take 15 minutes, and with the per-body cost series on
# native only (the target is native's). Filters are Google Benchmark regular expressions over
# kind/scene/engine (docs/benchmarks.md).
if [[ -n "$all" ]]; then
  run anyphys_bench_scenes '.'
  run anyphys_bench_direct_ode '.'
else
  small_scenes='^scene/(drop1000|drop10000|pyramid20|drop_planar|pyramid20_planar)/'
  large_pyramids='^scene/(pyramid3d|pyramid_planar)/(native|bullet|box2d)/'
  run anyphys_bench_scenes "$small_scenes|$large_pyramids|^workers/|^scaling/[^/]+/native/"
  run anyphys_bench_direct_ode '^raw/(drop1000|drop10000|pyramid20)/|^overhead/'
  echo "- left out for time (--all runs them): ODE and raw ODE on pyramid3d, ODE on pyramid_planar," \
       "the per-body cost series on ode and bullet"
fi
run anyphys_bench_direct_bullet '.'
run anyphys_bench_direct_box2d '.'
run anyphys_bench_effects '.'
echo "- finished $(date -u +%FT%TZ), load $(loadavg)"
echo

reports=("$out"/anyphys_bench_*.json)
"$bin/anyphys_bench_report" "${reports[@]}"
