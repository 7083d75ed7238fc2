#!/usr/bin/env bash
# `anyphys run --events` writes step,time,phase,bodyA,bodyB rows whose step and time match the
# state CSV. A ball (restitution 0.5 against the ground, threshold 2 m/s) dropped so that it hits
# at 6 m/s bounces at 6 and 3 m/s and stays at 1.5 m/s: 3 enters and 2 exits (see
# tests/contract/test_events.cpp), and it passes through a sensor on the way down: one
# trigger_enter and one trigger_exit. Checked only where the backend has contacts and events.
set -euo pipefail
anyphys="$1"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

if ! "$anyphys" backends --json | python3 -c '
import json, sys
native = next(b for b in json.load(sys.stdin)["backends"] if b["name"] == "native")
sys.exit(0 if {"contacts", "events", "restitution"} <= set(native["capabilities"]["effects"]) else 1)'; then
    echo "SKIP run_events: native lacks contacts, events or restitution"
    exit 0
fi

# h = 6^2 / (2 g) = 1.834862385 m drop of the ball's bottom; radius 0.25.
cat > "$work/bounce.json" <<'JSON'
{ "settings": { "restitutionThreshold": 2 },
  "materials": { "rubber": { "restitution": 0.5 } },
  "bodies": [ { "name": "ground", "type": "static", "shape": { "type": "plane", "normal": [0, 1, 0] } },
              { "name": "gate", "type": "static", "isTrigger": true, "position": [0, 1.5, 0],
                "shape": { "type": "box", "halfExtents": [1, 0.1, 1] } },
              { "name": "ball, red", "position": [0, 2.084862385321101, 0], "material": "rubber",
                "shape": { "type": "sphere", "radius": 0.25 } } ] }
JSON
"$anyphys" run "$work/bounce.json" --steps 240 --out "$work/states.csv" --events "$work/events.csv"
python3 - "$work/states.csv" "$work/events.csv" <<'PY'
import csv, sys
states = list(csv.DictReader(open(sys.argv[1])))
assert open(sys.argv[2]).readline().strip() == "step,time,phase,bodyA,bodyB", "events header"
events = list(csv.DictReader(open(sys.argv[2])))
times = {r["step"]: r["time"] for r in states}
for e in events:
    assert times[e["step"]] == e["time"], f"event time differs from the state CSV: {e}"
    assert e["phase"] in ("enter", "stay", "exit", "trigger_enter", "trigger_exit"), e
ground = [e for e in events if {e["bodyA"], e["bodyB"]} == {"ground", "ball, red"}]
gate = [e for e in events if {e["bodyA"], e["bodyB"]} == {"gate", "ball, red"}]
count = lambda rows, phase: sum(1 for e in rows if e["phase"] == phase)
assert all(e["bodyA"] == "ground" for e in ground), "pair order: ground was created first"
assert count(ground, "enter") == 3 and count(ground, "exit") == 2, [(e["step"], e["phase"]) for e in ground if e["phase"] != "stay"]
assert count(ground, "stay") > 0
# The gate is passed once on the way down; the first rebound (0.46 m) stays below it.
assert count(gate, "trigger_enter") == 1 and count(gate, "trigger_exit") == 1, gate
assert not any(e["phase"] in ("enter", "stay", "exit") for e in gate), "a sensor never collides"
print(f"ok events: {len(events)} rows")
PY
# "ball, red" holds a comma: the reader above found it only because both files quote it.
grep -q '"ball, red"' "$work/events.csv" || { echo "FAIL: name not quoted"; exit 1; }
echo "PASS run_events"
