# Sourced by the demo tests (tests/demos/*.sh, each given the anyphys tool and the bin folder):
# sets $anyphys, $bin, a scratch folder $work removed on exit, and $backends, every built backend.
set -euo pipefail
anyphys="$1"
bin="$2"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
backends=$("$anyphys" backends --json | python3 -c 'import json,sys; print(" ".join(b["name"] for b in json.load(sys.stdin)["backends"]))')
