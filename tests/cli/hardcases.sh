#!/usr/bin/env bash
# `anyphys hardcases --fast`: the hard cases of at most 100 bodies on every built backend pass
# or miss only as their backend declares (within its ceiling); the matrix and its JSON agree;
# an unknown case is a usage error naming the allowed ones.
set -euo pipefail
anyphys="$1"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

"$anyphys" hardcases --fast | tee "$work/matrix.txt"
grep -q '^hard_stack_20 ' "$work/matrix.txt" || { echo "FAIL: hard_stack_20 missing from the fast matrix"; exit 1; }
if grep -q '^hard_pyramid_100_planar ' "$work/matrix.txt"; then echo "FAIL: --fast ran the 5050-box pyramid"; exit 1; fi

# JSON: every case has a bound, and a verdict per backend.
"$anyphys" hardcases --fast --cases hard_overlap_25,hard_far_stack_planar --json > "$work/cases.json"
python3 - "$work/cases.json" <<'PY'
import json, sys
cases = json.load(open(sys.argv[1]))["hardcases"]
assert [c["name"] for c in cases] == ["hard_overlap_25", "hard_far_stack_planar"], cases
for c in cases:
    assert c["bound"] > 0 and c["why"] and c["criterion"], c
    for backend, r in c["results"].items():
        assert r["verdict"] in ("pass", "known", "n/a"), (c["name"], backend, r)
        if r["verdict"] != "n/a":
            assert "value" in r and "msPerStep" in r, (c["name"], backend, r)
print("ok json:", len(cases), "cases")
PY

# A name that is not a hard case is refused with one line naming the field.
if "$anyphys" hardcases --cases projectile 2> "$work/err.txt"; then echo "FAIL: projectile accepted as a hard case"; exit 1; fi
grep -q -- '--cases' "$work/err.txt" || { echo "FAIL: the error does not name --cases: $(cat "$work/err.txt")"; exit 1; }
echo "ok: refused $(cat "$work/err.txt")"
