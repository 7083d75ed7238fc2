#!/usr/bin/env bash
# `anyphys compare` runs every catalogue scene x backend x that backend's integrators and reports
# each combination, either measured or "unsupported: <reason>" (never dropped); integrators named
# with --integrators get a row on every backend, "unsupported" where a backend lacks them. Analytic checks on the
# native backend use the same bounds as run_projectile.sh (Euler variants 1/6 m off at t = 2 s,
# higher-order methods exact to rounding) and RK4's fourth order on the damped scene.
set -euo pipefail
anyphys="$1"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

"$anyphys" compare --json > "$work/all.json"
"$anyphys" compare --json --scenes projectile --integrators rk4 > "$work/named.json"
"$anyphys" scenes --json > "$work/scenes.json"
"$anyphys" backends --json > "$work/backends.json"
python3 - "$work/all.json" "$work/scenes.json" "$work/backends.json" "$work/named.json" <<'PY'
import json, sys
results = json.load(open(sys.argv[1]))["results"]
# Heavy benchmark loads (compareByDefault false) run only when named with --scenes.
scenes = [s["name"] for s in json.load(open(sys.argv[2]))["scenes"] if s["compareByDefault"]]
backends = json.load(open(sys.argv[3]))["backends"]

# Every combination of a scene, a backend and one of its integrators has exactly one row.
seen = {(r["scene"], r["backend"], r["integrator"]) for r in results}
want = {(s, b["name"], i) for s in scenes for b in backends for i in b["capabilities"]["integrators"]}
assert seen == want and len(results) == len(want), (want - seen, seen - want)
for r in results:
    assert r["status"] in ("ok", "unsupported"), r
    if r["status"] == "unsupported":
        assert r["reason"], r

def row(scene, integrator):
    return next(r for r in results if (r["scene"], r["backend"], r["integrator"]) == (scene, "native", integrator))

sixth = 1 / 6
assert abs(row("projectile", "explicit_euler")["positionError"] - sixth) < 1e-9
assert abs(row("projectile", "semi_implicit_euler")["positionError"] - sixth) < 1e-9
for integrator in ("verlet", "midpoint", "rk4"):
    r = row("projectile", integrator)
    assert r["positionError"] < 1e-9, r
    assert abs(r["energyDrift"]) < 1e-12, r
    assert row("free_fall_drop", integrator)["positionError"] < 1e-9
assert row("projectile", "explicit_euler")["energyDrift"] > 0  # explicit Euler gains energy
assert row("projectile", "semi_implicit_euler")["energyDrift"] < 0
# Damped decay: RK4 is far closer than the first-order methods (fourth vs first order at h = 1/60).
assert row("damped_motion", "rk4")["positionError"] < 1e-8, row("damped_motion", "rk4")
assert row("damped_motion", "explicit_euler")["positionError"] > 1e-3
# Scenes without an analytic answer report none; scenes that conserve nothing report no drift.
assert row("torque_free_spin", "rk4")["positionError"] is None
assert row("damped_motion", "rk4")["energyDrift"] is None
# A declared miss is known only within the backend's ceiling for it (a deviation that grew past
# its ceiling is a regression, and compare would have exited 1 above).
for r in results:
    c = r.get("check")
    if r["status"] != "ok" or c is None or c["passed"]:
        continue
    assert c["knownDeviation"] and not c["overCeiling"], r
    if c["ceiling"] is not None:
        assert c["value"] <= c["ceiling"], r
print(f"ok compare: {len(results)} rows")

# A named integrator is answered on every backend: measured, or unsupported with the reason.
named = json.load(open(sys.argv[4]))["results"]
assert {r["backend"] for r in named} == {b["name"] for b in backends}, named
for r in named:
    offered = "rk4" in next(b for b in backends if b["name"] == r["backend"])["capabilities"]["integrators"]
    assert r["status"] == ("ok" if offered else "unsupported"), r
PY

# The table has a header and one line per combination, and filters narrow it.
lines=$("$anyphys" compare --scenes projectile,free_fall_drop --backends native --integrators verlet,rk4 | grep -c '^projectile\|^free_fall_drop')
(( lines == 4 )) || { echo "FAIL: filtered table has $lines rows, want 4"; exit 1; }
"$anyphys" compare --scenes projectile | head -n 1 | grep -q '^scene *backend *integrator *steps *wall ms' \
    || { echo "FAIL: table header"; exit 1; }
echo "PASS compare"
