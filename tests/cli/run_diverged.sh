#!/usr/bin/env bash
# A run that diverges stops with a non-zero exit and one line on stderr naming the body, on every
# backend, instead of writing inf and NaN rows; a scene with absurd finite values (a body 1e308 m
# away, a spin of 1e308 rad/s, a gravity of 1e19 m/s^2) is refused naming the field, and never
# aborts inside an engine. The rows written before the divergence are all finite.
set -euo pipefail
anyphys="$1"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

# A ball falls freely; maxSpeed 5 m/s is passed after about half a second (g t = 5 at t = 0.51 s).
diverging() {  # backend, planar -> a scene file
    cat > "$work/diverging.json" <<JSON
{ "settings": { "backend": "$1", "planar": $2, "maxSpeed": 5 },
  "bodies": [ { "name": "faller", "position": [0, 100, 0], "shape": { "type": "sphere", "radius": 0.5 } } ] }
JSON
}
ball='"shape": { "type": "sphere", "radius": 0.5 }'
printf '{ "bodies": [ { "name": "far", "position": [1e308, 0, 0], %s } ] }\n' "$ball" > "$work/far.json"
printf '{ "bodies": [ { "name": "spinner", "angularVelocity": [0, 0, 1e308], %s } ] }\n' "$ball" > "$work/spin.json"
printf '{ "settings": { "gravity": [0, -1e19, 0] }, "bodies": [ { "name": "a", %s } ] }\n' "$ball" > "$work/gravity.json"

failures=0
fail() { echo "FAIL $*"; failures=$((failures + 1)); }

# run_expecting_error description pattern command...: exit 1 (not a crash), one stderr line matching pattern.
run_expecting_error() {
    local what="$1" pattern="$2"; shift 2
    local status=0
    "$@" > "$work/out" 2> "$work/err" || status=$?
    local lines; lines=$(wc -l < "$work/err")
    if (( status != 1 )); then
        fail "$what: exit code $status, want 1; stderr: $(head -c 300 "$work/err")"
    elif (( lines != 1 )); then
        fail "$what: $lines stderr lines:"; cat "$work/err"
    elif ! grep -q -- "$pattern" "$work/err"; then
        fail "$what: stderr lacks '$pattern': $(cat "$work/err")"
    elif grep -qiE 'nan|inf' "$work/out"; then
        fail "$what: wrote non-finite rows: $(grep -iE 'nan|inf' "$work/out" | head -n 2)"
    else
        echo "ok $what: $(cat "$work/err")"
    fi
}

# "name:planar" per backend: a backend without 3D worlds runs the scene planar.
backends="$("$anyphys" backends --json | python3 -c 'import json, sys; print(" ".join(b["name"] + ":" + ("true" if b["capabilities"]["dimensions"] < 3 else "false") for b in json.load(sys.stdin)["backends"]))')"
for entry in $backends; do
    backend="${entry%%:*}"
    diverging "$backend" "${entry##*:}"
    run_expecting_error "$backend: diverging run" 'body "faller"' "$anyphys" run "$work/diverging.json" --steps 120
    grep -q 'diverged' "$work/err" || fail "$backend: message does not say diverged: $(cat "$work/err")"
done

run_expecting_error "body 1e308 m away" 'bodies\[0\].position' "$anyphys" run "$work/far.json" --steps 10
run_expecting_error "spin of 1e308 rad/s" 'bodies\[0\].angularVelocity' "$anyphys" run "$work/spin.json" --steps 10
run_expecting_error "gravity of 1e19 m/s^2" 'settings.gravity' "$anyphys" run "$work/gravity.json" --steps 10

(( failures == 0 )) || { echo "$failures failure(s)"; exit 1; }
echo "all ok"
