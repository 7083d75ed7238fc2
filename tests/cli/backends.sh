#!/usr/bin/env bash
# `anyphys backends` lists native; `--json` is valid JSON carrying every capability field.
set -euo pipefail
anyphys="$1"

text="$("$anyphys" backends)"
grep -q '^native' <<< "$text" || { echo "FAIL: 'backends' does not list native:"; echo "$text"; exit 1; }

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
"$anyphys" backends --json > "$work/backends.json"
python3 -m json.tool "$work/backends.json" > /dev/null || { echo "FAIL: 'backends --json' is not valid JSON"; exit 1; }
python3 - "$work/backends.json" <<'PY'
import json, sys
doc = json.load(open(sys.argv[1]))
names = [b["name"] for b in doc["backends"]]
assert "native" in names, names
fields = {"dimensions", "unitRoundoff", "planar", "shapes", "bodyTypes", "jointTypes", "effects", "integrators", "solvers",
          "gyroscopicModes", "forceEvaluation", "parameters", "options"}
for b in doc["backends"]:
    caps = b["capabilities"]
    assert fields <= caps.keys(), (b["name"], fields - caps.keys())
    assert caps["forceEvaluation"] in ("per_stage", "per_step"), caps["forceEvaluation"]
    assert caps["unitRoundoff"] in (2.0 ** -53, 2.0 ** -24), caps["unitRoundoff"]  # double or float engines
native = next(b for b in doc["backends"] if b["name"] == "native")["capabilities"]
assert set(native["integrators"]) == {"explicit_euler", "semi_implicit_euler", "verlet", "midpoint", "rk4"}, native["integrators"]
# The fields the layer honours itself show on every backend; settings.planar where planar.
for b in doc["backends"]:
    caps = b["capabilities"]
    for p in ("settings.maxSpeed", "settings.maxAngularSpeed", "settings.divergencePolicy", "settings.capabilityPolicy",
              "settings.maxStepsPerUpdate", "body.name", "body.userData", "body.dragCoefficient"):
        assert p in caps["parameters"], (b["name"], p)
    assert ("settings.planar" in caps["parameters"]) == caps["planar"], b["name"]
print("ok backends --json:", names)
PY

# The catalogue listings are well formed too.
# Captured first: `grep -q` stops reading at the first match, and the writer's SIGPIPE would
# fail the pipeline under pipefail.
scenes="$("$anyphys" scenes)"
grep -q '^projectile' <<< "$scenes" || { echo "FAIL: 'scenes' does not list projectile"; exit 1; }
"$anyphys" scenes --json | python3 -m json.tool > /dev/null || { echo "FAIL: 'scenes --json' is not valid JSON"; exit 1; }
"$anyphys" scene projectile | python3 -m json.tool > /dev/null || { echo "FAIL: 'scene projectile' is not valid JSON"; exit 1; }
# The scene-format key tables come out of `schema`, each between its doc markers.
tables="$("$anyphys" schema --markdown)"
for name in settings material body shape-placement shape-types shape-child; do
    grep -q "^<!-- schema:$name -->" <<< "$tables" || { echo "FAIL: 'schema --markdown' lacks the $name table"; exit 1; }
done
grep -q '^| `timeStep` | s |' <<< "$tables" || { echo "FAIL: 'schema --markdown' lacks the timeStep row"; exit 1; }
echo "PASS backends"
