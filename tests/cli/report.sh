#!/usr/bin/env bash
# `anyphys report` on hand-made results (tests/cli/fixtures) whose answers are known in closed form:
# the Pareto front, the fitted convergence orders (1 and 4, the rk4 point at the rounding floor left
# out), the stability classes, the cheapest configurations, the effect-cost ratios and the headline;
# every plot written as PNG and SVG by gnuplot. Then a real sweep through compare -> report, and
# the errors for bad input.
set -euo pipefail
anyphys="$1"
fixtures="$(cd "$(dirname "${BASH_SOURCE[0]}")/fixtures" && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

"$anyphys" report "$fixtures/report_results.csv" "$fixtures/report_effects.csv" --out "$work/r" > "$work/stdout.txt"

python3 - "$work" <<'PY'
import os, re, sys
work = sys.argv[1]
out = open(f"{work}/stdout.txt").read().splitlines()
md = open(f"{work}/r/README.md").read()
html = open(f"{work}/r/index.html").read()
plots = f"{work}/r/plots"

# Headline, error target 0.01 m: native's cheapest within target is semi-implicit Euler at
# h = 0.02 (error 0.01 = target, 0.5 ms/sim s; rk4 meets it too but costs 1); bullet's is h = 0.01
# (0.008 m at 0.5); box_stack's only stable configuration within 0.005 m at the least cost.
assert out[0] == "projectile native: timeStep=0.02 integrator=semi_implicit_euler, 0.5 ms/sim s, pos_error 0.01 m", out[0]
assert out[1] == "projectile bullet: timeStep=0.01 integrator=semi_implicit_euler, 0.5 ms/sim s, pos_error 0.008 m", out[1]
assert out[2] == "box_stack native: timeStep=0.01 iterations=4 effectOff=none, 10 ms/sim s, pos_error 0.001 m", out[2]
assert out[-1] == f"report: {work}/r/index.html", out[-1]

# Every section, in both pages.
for page in (md, html):
    for title in ("Headline", "Provenance", "Error against cost", "Convergence", "Stability map",
                  "Cheapest configuration per error level", "Cost of each effect"):
        assert title in page, title

# Pareto front of the projectile: by cost, each row more accurate than every cheaper one.
# Hand-computed from the fixture: 8 of the 13 ok rows.
front = md.split("Pareto front:")[1].split("### Convergence")[0]
costs = re.findall(r"^\| (?:native|bullet) [^|]* \| ([0-9.e+-]+) \| ([0-9.e+-]+) \|$", front, re.M)
assert costs == [("0.125", "0.032"), ("0.25", "0.016"), ("0.5", "0.008"), ("1", "0.000256"),
                 ("2", "1.6e-05"), ("4", "1e-06"), ("8", "6.25e-08"), ("40", "1e-13")], costs

# Fitted orders: the fixture's errors fall exactly as h (Euler) and h^4 (rk4); rk4's h = 0.001
# error of 1e-13 is below the rounding floor (2.2e-16 x scene_scale 1 x 2000 steps = 4.4e-13) and
# must be left out, or the slope would be wrong. Four points each fitted.
assert re.search(r"\| native integrator=semi_implicit_euler \| 4 \| 0 \| 1.00 \| 1 \|", md), md
assert re.search(r"\| native integrator=rk4 \| 4 \| 1 \| 4.00 \| 4 \|", md), md
assert re.search(r"\| bullet integrator=semi_implicit_euler \| 4 \| 0 \| 1.00 \| 1 \|", md), md

# Stability of box_stack on native, iterations (rows) by timeStep (columns 0.01, 0.02):
# 4 iterations: stable, failed -> exploded; 8: stable (friction off is still within target), check
# false -> drifted.
assert "| 4 | stable | exploded |" in md, md
assert "| 8 | stable | drifted |" in md, md
assert "1 x failed: stepping threw: non-finite state" in md

# Cheapest per level (scale 1 m): at 1e-3 native needs rk4 h = 0.04 (cost 1); bullet has none.
assert "| 0.001 x scale (0.001 m) | native | timeStep=0.04 integrator=rk4 | 1 | 0.000256 |" in md, md
assert "| 0.001 x scale (0.001 m) | bullet | none | - | - |" in md, md
assert "| 0.0001 x scale (0.0001 m) | native | timeStep=0.02 integrator=rk4 | 2 | 1.6e-05 |" in md, md
assert "1 x unsupported: integrator rk4 not offered" in md

# Effect costs at timeStep 0.01, 8 iterations: friction off 0.186 / 0.2, sleeping off 0.25 / 0.2.
# Sleeping is not among the effects the baseline simulated: marked as not in the scene.
assert "| native | timeStep=0.01 iterations=8 | gravity+friction+events | 0.2 | 0.93x | 1.25x (not in scene) |" in md, md

# Plots: PNG (magic number) and SVG for each, referenced by the pages.
stems = ["projectile_cost", "projectile_convergence", "box_stack_cost", "box_stack_convergence",
         "box_stack_stability_native"]
for stem in stems:
    png = open(f"{plots}/{stem}.png", "rb").read()
    assert png[:8] == b"\x89PNG\r\n\x1a\n" and len(png) > 5000, stem
    svg = open(f"{plots}/{stem}.svg").read()
    assert "<svg" in svg and "</svg>" in svg, stem
    assert f"plots/{stem}.png" in md and f"plots/{stem}.svg" in html, stem
# The convergence plot names the fitted and theoretical orders in its legend.
assert "order 4.00 (theory 4)" in open(f"{plots}/projectile_convergence.svg").read()
print("ok report: fixture")
PY

# A real sweep: semi-implicit Euler on the projectile has error 0.5 g h t, exactly first order;
# the report must fit 1.00 on every backend that ran it.
"$anyphys" compare --scenes projectile --sweep timeStep=1/30,1/60,1/120 --repeat 1 \
  --out "$work/sweep.csv" > /dev/null 2>&1
"$anyphys" report "$work/sweep.csv" --out "$work/real" > "$work/real.txt"
python3 - "$work" <<'PY'
import re, sys
work = sys.argv[1]
md = open(f"{work}/real/README.md").read()
import csv
ran = {r["backend"] for r in csv.DictReader(open(f"{work}/sweep.csv")) if r["status"] == "ok"}
fits = re.findall(r"^\| (\w+) \| 3 \| 0 \| ([0-9.]+) \| 1 \|$", md, re.M)
assert {backend for backend, _ in fits} == ran, (fits, ran)
assert all(abs(float(order) - 1) < 0.01 for _, order in fits), fits
# Headline: one line per backend (box2d's 3D refusal reads "none within target") and the path.
heads = open(f"{work}/real.txt").read().splitlines()
backends = {r["backend"] for r in csv.DictReader(open(f"{work}/sweep.csv"))}
assert len(heads) == len(backends) + 1, heads
# The headline's numbers are the CSV's: per backend, the least ms_per_sim_second among ok rows
# within error_target, printed as %.3g.
rows = list(csv.DictReader(open(f"{work}/sweep.csv")))
for backend in sorted(backends):
    within = [r for r in rows if r["backend"] == backend and r["status"] == "ok"
              and float(r["pos_error"]) <= float(r["error_target"])]
    line = next(h for h in heads if h.startswith(f"projectile {backend}: "))
    if not within:
        assert line.endswith("not run (3D worlds (planar only))") or "none within target" in line, line
        continue
    best = min(within, key=lambda r: float(r["ms_per_sim_second"]))
    expected = "%.3g ms/sim s, pos_error %.3g m" % (float(best["ms_per_sim_second"]), float(best["pos_error"]))
    assert line.endswith(expected), (line, expected)
print("ok report: real sweep, fitted orders", fits)
PY

# Bad input: one line on stderr naming the file / row / column, exit 1, nothing written.
expect_error() {  # pattern, args...
  local pattern="$1"; shift
  if "$anyphys" report "$@" > /dev/null 2> "$work/err.txt"; then
    echo "FAIL: report $* succeeded" >&2; exit 1
  fi
  [[ $(wc -l < "$work/err.txt") -eq 1 ]] || { cat "$work/err.txt" >&2; exit 1; }
  grep -qF -- "$pattern" "$work/err.txt" || { echo "FAIL: expected '$pattern', got:" >&2; cat "$work/err.txt" >&2; exit 1; }
}
expect_error "$work/none.csv" "$work/none.csv" --out "$work/bad1"
printf 'scene,backend\nprojectile,native\n' > "$work/nocost.csv"
expect_error 'no column "ms_per_sim_second"' "$work/nocost.csv" --out "$work/bad2"
printf 'scene,backend,ms_per_sim_second,pos_error\nprojectile,native,1,fast\n' > "$work/word.csv"
expect_error 'row 1: column pos_error holds "fast", not a number' "$work/word.csv" --out "$work/bad3"
[[ ! -e "$work/bad1" && ! -e "$work/bad2" && ! -e "$work/bad3" ]] || { echo "FAIL: output written on error" >&2; exit 1; }
# Without gnuplot on PATH: a clear error naming the package.
mkdir -p "$work/empty_path"
if PATH="$work/empty_path" "$anyphys" report "$fixtures/report_results.csv" --out "$work/bad4" > /dev/null 2> "$work/err.txt"; then
  echo "FAIL: report without gnuplot succeeded" >&2; exit 1
fi
grep -qF "gnuplot not found; install gnuplot-nox" "$work/err.txt" || { cat "$work/err.txt" >&2; exit 1; }
echo "ok report: bad input"
