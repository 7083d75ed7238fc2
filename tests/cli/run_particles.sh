#!/usr/bin/env bash
# `anyphys run SCENE --particles FILE.csv`: one row per fluid particle and cloth node per step, the
# columns the issue names; the fluid stays in its tank and the pinned cloth nodes stay put; bad
# fluids and cloths exit 1 naming the JSON path.
set -euo pipefail
anyphys="$1"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

# A planar tank 0.2 m wide with 4 x 4 particles of water, and a 2 x 2 cell cloth pinned at two
# corners hanging beside it.
cat > "$work/tank.json" <<'JSON'
{ "settings": {"backend": "native", "planar": true},
  "bodies": [
    {"name": "floor", "type": "static", "position": [0.1, -0.05, 0], "shape": {"type": "box", "halfExtents": [0.3, 0.05, 0.1]}},
    {"name": "left", "type": "static", "position": [-0.05, 0.5, 0], "shape": {"type": "box", "halfExtents": [0.05, 0.5, 0.1]}},
    {"name": "right", "type": "static", "position": [0.25, 0.5, 0], "shape": {"type": "box", "halfExtents": [0.05, 0.5, 0.1]}} ],
  "fluids": [ {"name": "water", "box": {"min": [0, 0, -0.05], "max": [0.2, 0.2, 0.05]},
               "spacing": 0.05, "density": 1000, "viscosity": 0.001} ],
  "cloths": [ {"name": "flag", "corner": [1, 2, 0], "size": [0.4, 0.4], "resolution": [2, 2],
               "areaDensity": 0.2, "stiffness": 1e4, "damping": 0.1, "pinned": [[0, 0], [2, 0]]} ] }
JSON
"$anyphys" run "$work/tank.json" --steps 30 --out "$work/states.csv" --particles "$work/particles.csv"
python3 - "$work/particles.csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert list(rows[0].keys()) == "step,time,system,index,px,py,pz,vx,vy,vz".split(","), rows[0].keys()
assert len(rows) == 31 * (16 + 9), len(rows)   # steps 0..30, 16 particles and 9 nodes each
last = [r for r in rows if r["step"] == "30"]
water = [r for r in last if r["system"] == "water"]
flag = [r for r in last if r["system"] == "flag"]
assert len(water) == 16 and len(flag) == 9
for r in water:  # in the tank: above the floor and between the walls, by the particle radius 0.025
    x, y = float(r["px"]), float(r["py"])
    assert -1e-9 < y and 0.025 - 1e-6 <= x <= 0.175 + 1e-6, (x, y)
    assert float(r["pz"]) == 0.0
for r in flag:
    if r["index"] in ("0", "2"):  # pinned: node (0, 0) and (2, 0)
        assert float(r["vx"]) == 0.0 and float(r["vy"]) == 0.0, r
        assert float(r["py"]) == 2.0, r
print("ok particles csv")
PY

# Bad fluids and cloths exit 1 with one line naming the JSON path.
sed 's/"spacing": 0.05/"spacing": -1/' "$work/tank.json" > "$work/bad.json"
if err="$("$anyphys" run "$work/bad.json" 2>&1 >/dev/null)"; then echo "FAIL: bad spacing accepted"; exit 1; fi
grep -q 'fluids\[0\].spacing: must be > 0, got -1' <<< "$err" || { echo "FAIL: unexpected error: $err"; exit 1; }
sed 's/\[2, 0\]\]/[3, 0]]/' "$work/tank.json" > "$work/bad2.json"
if err="$("$anyphys" run "$work/bad2.json" 2>&1 >/dev/null)"; then echo "FAIL: bad pinned node accepted"; exit 1; fi
grep -q 'cloths\[0\].pinned\[1\]' <<< "$err" || { echo "FAIL: unexpected error: $err"; exit 1; }
echo "PASS run_particles"
