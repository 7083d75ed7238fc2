#!/usr/bin/env bash
# The testbed renders box_stack_10 off-screen (run under xvfb-run) on two backends: the picture
# is not blank, bodies appear in their colours where their projected positions say, and the two
# views differ only where the engines' states differ (the same backend twice: not at all).
# Usage: render_two_backends.sh TESTBED ANYPHYS_CLI
set -euo pipefail
testbed="$1"
anyphys="$2"
here="$(cd "$(dirname "$0")" && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
common=(--scene box_stack_10 --headless --frames 30 --size 800x400 --hide-ui)

"$testbed" "${common[@]}" --backends native,native --screenshot "$work/same.png" --dump-projections "$work/same.json"
python3 "$here/check_render.py" "$work/same.png" "$work/same.json" --same

# native beside the first other backend with 3D worlds (ode in a full build).
other=$("$anyphys" backends --json | python3 -c '
import json, sys
names = [b["name"] for b in json.load(sys.stdin)["backends"] if b["name"] != "native" and b["capabilities"]["dimensions"] == 3]
print(names[0] if names else "")')
if [[ -z "$other" ]]; then
  echo "skipped the two-engine picture: no 3D backend besides native is built"
  exit 0
fi
"$testbed" "${common[@]}" --backends "native,$other" --screenshot "$work/two.png" --dump-projections "$work/two.json"
python3 "$here/check_render.py" "$work/two.png" "$work/two.json"
