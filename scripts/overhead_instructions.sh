#!/usr/bin/env bash
# The wrapper overhead in instructions: runs the overhead/ rows of the raw-engine programs
# (anyphys_bench_direct_{ode,bullet,box2d}) under valgrind's callgrind and prints, per row, the
# instructions of the last fifth of the scene's steps (the pile landed; the rest of the run goes
# uncounted) on each side (anyphys with no one reading the events, anyphys with a listener
# reading every event, the same listener with settings.contactImpulses false, the engine called
# directly) and the overhead 100 (anyphys / raw - 1). Then, for each row, the functions whose
# instructions differ most between the anyphys and the raw side.
#
# Why: on a shared virtual machine a side's time moves by up to 10 % between rounds, more than the
# 3 % the target allows; its instruction count is exact and the same on every run. Instructions
# are not time (a cache miss costs more than an add), so this is the layer's extra work, next to
# the timed rows of scripts/bench.sh, not a replacement for them.
#
# Usage: scripts/overhead_instructions.sh [--quick] [BUILD_DIR] [FILTER]
#   --quick    the programs' --quick: a fifth of each scene's steps, of which the last fifth counts;
#              checks that the instrument works
#   BUILD_DIR  default `build`; configured with -DANYPHYS_BUILD_BENCH=ON and built unless NOBUILD=1
#   FILTER     regular expression over the rows (default: every overhead/ row)
#   OUT=DIR    where the callgrind files go (default BUILD_DIR/overhead-instructions)
# Needs valgrind (Debian package `valgrind`).
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
quick=""
build_dir=""
filter="^overhead/"
for arg in "$@"; do
  case "$arg" in
    --quick) quick=1 ;;
    -h|--help) awk 'NR > 1 && !/^#/ { exit } NR > 1 { print }' "${BASH_SOURCE[0]}"; exit 0 ;;
    -*) echo "overhead_instructions.sh: unknown option $arg (see --help)" >&2; exit 2 ;;
    *) if [[ -z "$build_dir" ]]; then build_dir="$arg"; else filter="$arg"; fi ;;
  esac
done
command -v valgrind >/dev/null ||
  { echo "overhead_instructions.sh: valgrind not found (apt-get install valgrind)" >&2; exit 1; }
build_dir="${build_dir:-build}"
case "$build_dir" in
  /*) ;;
  *) build_dir="$root/$build_dir" ;;
esac
out="${OUT:-$build_dir/overhead-instructions}"
if [[ -z "${NOBUILD:-}" ]]; then
  bash "$root/scripts/build.sh" "$build_dir" -DANYPHYS_BUILD_BENCH=ON >&2
fi
mkdir -p "$out"
rm -f "$out"/cg.*

echo "# Wrapper overhead in instructions${quick:+ (QUICK: a fifth of the steps)}"
echo
echo "- anyphys: $(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo unknown); build: $build_dir"
echo "- started $(date -u +%FT%TZ)"
for engine in ode bullet box2d; do
  program="$build_dir/bench/anyphys_bench_direct_$engine"
  if [[ ! -x "$program" ]]; then
    echo "- anyphys_bench_direct_$engine: not built (its engine was not found); skipped"
    continue
  fi
  # Nothing is instrumented or counted but the steps measure() times (it turns both on around
  # them); each side ends with a dump named after its row and side.
  valgrind --tool=callgrind --instr-atstart=no --collect-atstart=no --callgrind-out-file="$out/cg.$engine" \
    "$program" ${quick:+--quick} --benchmark_filter="$filter" --benchmark_color=false \
    >"$out/$engine.log" 2>&1 ||
    { echo "overhead_instructions.sh: $program failed under valgrind; see $out/$engine.log" >&2; exit 1; }
done
echo "- finished $(date -u +%FT%TZ)"
echo

# Each dump file names its row and side in its "desc: Trigger: Client Request:" line and holds
# the instructions in its "totals:" line; callgrind_annotate lists its functions.
shopt -s nullglob
dumps=("$out"/cg.*.*)
if [[ ${#dumps[@]} -eq 0 ]]; then
  echo "no overhead row matched $filter" >&2
  exit 1
fi
python3 - "${dumps[@]}" <<'PY'
import collections, re, subprocess, sys

sides = collections.defaultdict(dict)  # row -> side -> dump file
totals = {}
for dump in sys.argv[1:]:
    label = total = None
    with open(dump) as f:
        for line in f:
            if line.startswith("desc: Trigger: Client Request: "):
                label = line.removeprefix("desc: Trigger: Client Request: ").strip()
            elif line.startswith("totals:"):
                total = int(line.split()[1])
    row, side = label.rsplit(" ", 1)
    sides[row][side] = dump
    totals[dump] = total

def functions(dump):
    """Instructions (self) per function of one dump."""
    out = subprocess.run(["callgrind_annotate", "--inclusive=no", "--threshold=100", dump],
                         capture_output=True, text=True, check=True).stdout
    cost = collections.Counter()
    for line in out.splitlines():
        m = re.match(r"\s*([\d,]+)\s+(?:\([^)]*\)\s+)?(\S.*)$", line)
        if not m or "PROGRAM TOTALS" in line:
            continue
        name = re.sub(r" \[[^\]]*\]$", "", m.group(2))   # the object file
        name = re.sub(r"^[^:]*:(?!:)", "", name, count=1)  # the source file ("???:")
        cost[name] += int(m.group(1).replace(",", ""))
    return cost

print("| row | anyphys Ir | listening Ir | raw Ir | overhead | with a listener | listener, no impulses |")
print("|---|---:|---:|---:|---:|---:|---:|")
for row in sorted(sides):
    ir = {side: totals[dump] for side, dump in sides[row].items()}
    raw = ir["raw"]
    pct = lambda side: f"{100 * (ir[side] / raw - 1):.2f} %" if side in ir else "-"
    print(f"| {row} | {ir['anyphys']:,} | {ir['listening']:,} | {raw:,} | "
          f"{pct('anyphys')} | {pct('listening')} | {pct('points')} |")

# Where the difference lies: per function, the anyphys side's instructions less the raw side's,
# as a share of the raw side. Code both sides run (the engine, physics the raw program mirrors)
# cancels; what remains is the layer's own work and the engine work it asks for.
for row in sorted(sides):
    layer, raw = functions(sides[row]["anyphys"]), functions(sides[row]["raw"])
    base = totals[sides[row]["raw"]]
    diff = {name: layer[name] - raw[name] for name in set(layer) | set(raw)}
    print(f"\n## {row}: where the anyphys side executes more (or fewer) instructions than raw\n")
    for name, d in sorted(diff.items(), key=lambda kv: -abs(kv[1]))[:12]:
        print(f"- {100 * d / base:+.2f} %  {name[:160]}")
PY
