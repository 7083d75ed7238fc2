#!/usr/bin/env bash
# `anyphys run SCENE --joints FILE.csv`: one row per joint per step, the columns the scene format
# names; a hinge pendulum's angle follows the small-angle closed form; bad joints exit 1 naming
# the JSON path.
set -euo pipefail
anyphys="$1"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

# A 1 m pendulum (a 1 kg ball of radius 0.01 m: a point mass within 1e-4) released at 0.05 rad
# on a hinge about +Z.
cat > "$work/pendulum.json" <<'JSON'
{ "settings": {"backend": "native"},
  "bodies": [ {"name": "bob", "position": [0.049979169270678331, -0.99875026039496628, 0],
               "shape": {"type": "sphere", "radius": 0.01}, "mass": 1, "allowSleep": false} ],
  "joints": [ {"name": "pivot", "type": "hinge", "bodyB": "bob", "anchor": [0, 0, 0], "axis": [0, 0, 1]} ] }
JSON
"$anyphys" run "$work/pendulum.json" --steps 120 --out "$work/states.csv" --joints "$work/joints.csv"
python3 - "$work/joints.csv" <<'PY'
import csv, math, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert list(rows[0].keys()) == "step,time,joint,position,speed,fx,fy,fz,tx,ty,tz".split(","), rows[0].keys()
assert len(rows) == 121, len(rows)          # steps 0..120, one joint
assert all(r["joint"] == "pivot" for r in rows)
omega = math.sqrt(9.81 / 1.0)
worst = 0.0
for r in rows:
    t = float(r["time"])
    exact = 0.05 * math.cos(omega * t)      # the angle about +Z, from the pose at creation (0.05 rad)
    worst = max(worst, abs(float(r["position"]) - (exact - 0.05)))
# 2e-3 rad: the small-angle form itself is off by theta0^3/16 ~ 1e-5, the integration by less;
# a sign error or an angle not measured from creation would be off by 0.05 or more.
assert worst < 2e-3, worst
last = rows[-1]
tension = math.hypot(float(last["fx"]), float(last["fy"]))
assert abs(tension - 9.81) < 0.2, tension   # the string pulls with about m g (plus m v^2 / L, tiny)
print("ok joints csv, worst angle error", worst)
PY

# Bad joints exit 1 with one line naming the JSON path.
sed 's/"bodyB": "bob"/"bodyB": "shin"/' "$work/pendulum.json" > "$work/bad.json"
if err="$("$anyphys" run "$work/bad.json" 2>&1 >/dev/null)"; then echo "FAIL: bad joint accepted"; exit 1; fi
grep -q 'joints\[0\].bodyB: no body named "shin"' <<< "$err" || { echo "FAIL: unexpected error: $err"; exit 1; }
echo "PASS run_joints"
