#!/usr/bin/env bash
# `anyphys run --hash`: the same scene run twice on one backend gives the same state hash (the
# backends are deterministic), a different run gives another, and --out still writes the CSV.
set -euo pipefail
anyphys="$1"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

"$anyphys" scene box_stack_10_planar > "$work/stack.json"
backends=$("$anyphys" backends --json | python3 -c 'import json,sys; print(" ".join(b["name"] for b in json.load(sys.stdin)["backends"]))')
for backend in $backends; do
  first=$("$anyphys" run "$work/stack.json" --backend "$backend" --steps 20 --hash)
  second=$("$anyphys" run "$work/stack.json" --backend "$backend" --steps 20 --hash --out "$work/run.csv")
  longer=$("$anyphys" run "$work/stack.json" --backend "$backend" --steps 21 --hash)
  [[ "$first" =~ ^state-hash\ [0-9a-f]{16}$ ]] || { echo "FAIL $backend: bad hash line '$first'"; exit 1; }
  [[ "$first" == "$second" ]] || { echo "FAIL $backend: two runs differ: $first / $second"; exit 1; }
  [[ "$first" != "$longer" ]] || { echo "FAIL $backend: one more step gives the same hash"; exit 1; }
  head -1 "$work/run.csv" | grep -q '^step,time,body,' || { echo "FAIL $backend: --out lost its CSV"; exit 1; }
  echo "ok $backend: $first"
done
# Native's result does not depend on its worker count.
python3 - "$work/stack.json" "$work/stack2.json" <<'PY'
import json, sys
scene = json.load(open(sys.argv[1]))
scene["settings"]["workers"] = 2
json.dump(scene, open(sys.argv[2], "w"))
PY
one=$("$anyphys" run "$work/stack.json" --backend native --steps 20 --hash)
two=$("$anyphys" run "$work/stack2.json" --backend native --steps 20 --hash)
[[ "$one" == "$two" ]] || { echo "FAIL native: 1 and 2 workers differ: $one / $two"; exit 1; }
echo "PASS run_hash"
