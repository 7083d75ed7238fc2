#!/usr/bin/env bash
# `anyphys run` reproduces the projectile's analytic case with every integrator:
# v0 = (10,10,0), g = 10, dt = 1/60, 120 steps -> t = 2 s, exact height 10*2 - 5*2^2 = 0.
# The Euler variants are off by g*h*T/2 = 10 * (1/60) * 2 / 2 = 1/6 m: explicit Euler above (it
# moves with the start-of-step velocity), semi-implicit below (end-of-step velocity). Verlet,
# midpoint and RK4 integrate a quadratic exactly, so only rounding remains; 1e-9 m is far above
# the rounding of 120 steps in doubles (~1e-14) and far below the Euler error.
set -euo pipefail
anyphys="$1"
dir="$2"
scene="$dir/scenes/projectile.json"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

header='step,time,body,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz'
bodies="$(python3 -c 'import json,sys; print(len(json.load(open(sys.argv[1]))["bodies"]))' "$scene")"

check() {  # integrator, expected final py, tolerance
    local integrator="$1" expected="$2" tolerance="$3" csv="$work/$1.csv"
    "$anyphys" run "$scene" --steps 120 --integrator "$integrator" --out "$csv"
    [[ "$(head -n 1 "$csv")" == "$header" ]] || { echo "FAIL $integrator: header is '$(head -n 1 "$csv")'"; exit 1; }
    local rows=$(( $(wc -l < "$csv") - 1 ))
    (( rows == 121 * bodies )) || { echo "FAIL $integrator: $rows data rows, want $((121 * bodies))"; exit 1; }
    # Last row of the ball: step 120 at t = 2 (the world's accumulated time), py against the exact answer.
    python3 - "$csv" "$integrator" "$expected" "$tolerance" <<'PY'
import csv, sys
path, integrator, expected, tolerance = sys.argv[1], sys.argv[2], eval(sys.argv[3]), float(sys.argv[4])
rows = [r for r in csv.DictReader(open(path)) if r["body"] == "ball"]
first, last = rows[0], rows[-1]
assert first["step"] == "0" and float(first["time"]) == 0.0, f"{integrator}: first row {first}"
assert float(first["vx"]) == 10.0 and float(first["vy"]) == 10.0, f"{integrator}: initial velocity {first}"
assert last["step"] == "120", f"{integrator}: last step {last['step']}"
assert abs(float(last["time"]) - 2.0) < 1e-12, f"{integrator}: last time {last['time']}"
py, px = float(last["py"]), float(last["px"])
assert abs(py - expected) <= tolerance, f"{integrator}: py = {py!r}, want {expected!r} +- {tolerance}"
assert abs(px - 20.0) <= 1e-9, f"{integrator}: px = {px!r}, want 20"
print(f"ok {integrator}: py = {py:.17g}")
PY
}

check explicit_euler      '1/6'  1e-9
check semi_implicit_euler '-1/6' 1e-9
check verlet              '0'    1e-9
check midpoint            '0'    1e-9
check rk4                 '0'    1e-9

# Without --out the CSV goes to stdout and matches the file byte for byte; the default step
# count is one simulated second (60 steps of 1/60 s).
"$anyphys" run "$scene" --steps 120 --integrator rk4 > "$work/stdout.csv"
cmp "$work/stdout.csv" "$work/rk4.csv" || { echo "FAIL: stdout differs from --out"; exit 1; }
rows=$(( $("$anyphys" run "$scene" | wc -l) - 1 ))
(( rows == 61 * bodies )) || { echo "FAIL: default run has $rows rows, want $((61 * bodies))"; exit 1; }
# --dt overrides the time step: 0.01 s -> 100 steps by default.
rows=$(( $("$anyphys" run "$scene" --dt 0.01 | wc -l) - 1 ))
(( rows == 101 * bodies )) || { echo "FAIL: --dt 0.01 run has $rows rows, want $((101 * bodies))"; exit 1; }
echo "PASS run_projectile"
