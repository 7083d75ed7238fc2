#!/usr/bin/env bash
# `anyphys compare --sweep ... --out`: one results row per configuration of the full grid (scenes x
# backends x every axis), the contract columns, unsupported configurations marked with a reason,
# and the closed-form errors of the integrators on the projectile (semi-implicit Euler's error
# halves with the step; verlet and rk4 are exact to rounding). Bad --sweep input is a one-line
# usage error naming the value.
set -euo pipefail
anyphys="$1"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

"$anyphys" compare --scenes projectile,bouncing_ball --sweep timeStep=1/60,1/120 \
  --sweep integrator=semi_implicit_euler,verlet,rk4 --repeat 1 --out "$work/r.csv" > "$work/table.txt" 2> "$work/progress.txt"
"$anyphys" compare --scenes box_stack_10 --backends native --sweep iterations=1,4 --sweep effectOff=none,friction \
  --repeat 1 --out "$work/e.csv" > /dev/null 2>&1
"$anyphys" backends --json > "$work/backends.json"
python3 - "$work" "$anyphys" <<'PY'
import csv, json, subprocess, sys
work, anyphys = sys.argv[1], sys.argv[2]
rows = list(csv.DictReader(open(f"{work}/r.csv")))
lines = [json.loads(l) for l in open(f"{work}/r.jsonl")]
backends = {b["name"]: b["capabilities"] for b in json.load(open(f"{work}/backends.json"))["backends"]}

# The full grid: 2 time steps x 3 integrators x 2 scenes x every backend, each once.
assert len(rows) == 2 * 3 * 2 * len(backends) == len(lines), (len(rows), len(lines))
assert sorted(int(r["config_id"]) for r in rows) == list(range(len(rows)))
assert all(r["config_count"] == str(len(rows)) and r["shard"] == "1/1" for r in rows)
contract = ["scene", "backend", "timeStep", "substeps", "iterations", "integrator", "solver", "steps",
            "ms_per_step_min", "ms_per_step_median", "ms_per_sim_second", "pos_error", "vel_error", "energy_drift",
            "momentum_drift", "max_penetration", "joint_gap", "check_value", "check_ok", "anyphys_version", "commit",
            "status", "reason", "repeat", "error_reference", "pos_error_vs_engines", "scene_scale", "error_target",
            "check_label", "check_known_deviation", "machine_load", "config_id", "config_count", "shard"]
missing = [c for c in contract if c not in rows[0]]
assert not missing, missing
assert list(lines[0].keys()) == list(rows[0].keys())
assert rows[0]["anyphys_version"] and rows[0]["commit"]

# Settings as run: the swept values, and the backend's defaults filled in for the rest.
for r in rows:
    assert float(r["timeStep"]) in (1 / 60, 1 / 120), r["timeStep"]
    assert r["integrator"] in ("semi_implicit_euler", "verlet", "rk4")
    assert r["substeps"] and r["iterations"] and r["solver"], r
    caps = backends[r["backend"]]
    if r["integrator"] not in caps["integrators"] or r["status"] == "unsupported":
        assert r["status"] == "unsupported" and r["reason"], r
        assert r["ms_per_step_median"] == "" and r["pos_error"] == "", r
    else:
        assert r["status"] == "ok", r
        assert int(r["steps"]) == round(float(r["scene"] == "projectile" and 2 or 5) / float(r["timeStep"])), r
        assert float(r["ms_per_step_min"]) <= float(r["ms_per_step_median"]), r
        assert r["repeat"] == "1"

def native(scene, integrator, h):
    return next(r for r in rows if (r["scene"], r["backend"], r["integrator"]) == (scene, "native", integrator)
                and abs(float(r["timeStep"]) - h) < 1e-15)

# Semi-implicit Euler under constant acceleration g: v_n = v0 - n h g exactly, and
# y_n = y0 + h sum_{k=1..n} v_k = y0 + v0 t - g h^2 n (n + 1) / 2 = exact - 0.5 g h t, at t = n h.
# So at t = 2 s with g = 10 m/s^2 and h = 1/60: 0.5 * 10 * (1/60) * 2 = 1/6 = 0.166667 m, and
# halving h halves it. Verlet and RK4 integrate a constant acceleration exactly.
e60 = float(native("projectile", "semi_implicit_euler", 1 / 60)["pos_error"])
e120 = float(native("projectile", "semi_implicit_euler", 1 / 120)["pos_error"])
assert abs(e60 - 1 / 6) < 1e-9 * (1 / 6), e60
assert abs(e120 / e60 - 0.5) < 1e-9, (e60, e120)
for integrator in ("verlet", "rk4"):
    r = native("projectile", integrator, 1 / 60)
    assert float(r["pos_error"]) < 1e-9 and float(r["vel_error"]) < 1e-9, r
    assert r["error_reference"] == "closed_form"
# The projectile's motion spans 20 m (range); the target is 1 % of it.
assert abs(float(native("projectile", "rk4", 1 / 60)["scene_scale"]) - 20) < 1e-6
# A contact scene without a closed form: errors against the engine's converged run, a penetration,
# its rebound check, no joints.
b = native("bouncing_ball", "semi_implicit_euler", 1 / 60)
assert b["error_reference"] == "converged" and b["pos_error"] != "" and b["pos_error_vs_engines"] != "", b
assert b["max_penetration"] != "" and b["joint_gap"] == "" and b["check_ok"] in ("true", "false"), b
# JSONL: numbers as numbers, empty as null.
j = next(l for l in lines if l["config_id"] == int(b["config_id"]))
assert isinstance(j["pos_error"], float) and j["joint_gap"] is None and isinstance(j["steps"], int), j

# effectOff: a column of its own; friction off changes the stack.
e = list(csv.DictReader(open(f"{work}/e.csv")))
assert len(e) == 4 and {r["effectOff"] for r in e} == {"none", "friction"} and {r["iterations"] for r in e} == {"1", "4"}
assert all(r["status"] == "ok" for r in e), e
# A backend option some backends lack: their rows are unsupported, naming it; the others run.
offered = {name: {o for o in caps.get("options", {})} for name, caps in backends.items()}
partial = sorted({o for opts in offered.values() for o in opts if not all(o in x for x in offered.values())})
if partial:
    option = partial[0]
    subprocess.run([anyphys, "compare", "--scenes", "projectile", "--sweep", f"{option}=0", "--repeat", "1",
                    "--out", f"{work}/o.csv"], check=True, capture_output=True)
    for r in csv.DictReader(open(f"{work}/o.csv")):
        assert r[option] == "0", r
        if option in offered[r["backend"]]:
            assert r["status"] == "ok", r
        else:
            assert r["status"] == "unsupported" and option in r["reason"], r
print(f"ok compare_sweep: {len(rows)} rows")
PY
grep -q "projectile" "$work/table.txt"

# Bad input: exit 2, one line on stderr naming the value (or the setting) and what is allowed.
expect_usage_error() {
  local want="$1"
  shift
  if "$anyphys" compare --scenes projectile "$@" > /dev/null 2> "$work/err.txt"; then
    echo "FAIL: compare $* succeeded" >&2; exit 1
  fi
  [[ $(wc -l < "$work/err.txt") -eq 1 ]] || { echo "FAIL: not one stderr line for $*:" >&2; cat "$work/err.txt" >&2; exit 1; }
  grep -q -- "$want" "$work/err.txt" || { echo "FAIL: stderr for $* lacks $want:" >&2; cat "$work/err.txt" >&2; exit 1; }
}
expect_usage_error '"1/0"' --sweep timeStep=1/60,1/0
expect_usage_error '"fast"' --sweep integrator=rk4,fast
expect_usage_error 'unknown setting "stepsize"' --sweep stepsize=1
expect_usage_error '"2"' --sweep baumgarte=0.2,2
expect_usage_error '"-1"' --sweep substeps=-1
expect_usage_error '"gravityy"' --sweep effectOff=gravityy
echo "ok compare_sweep: bad input"
