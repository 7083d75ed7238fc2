#!/usr/bin/env bash
# Bad input anywhere: a non-zero exit code and exactly one line on stderr (and no CSV on stdout).
set -euo pipefail
anyphys="$1"
dir="$2"
scene="$dir/scenes/projectile.json"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

printf '{ "settings": { "gravity": [0, -10, 0] }, "bodies": [ \n' > "$work/truncated.json"
printf '{ "bodies": [ { "name": "ball", "shape": { "type": "sphere", "radius": -1 } } ] }\n' > "$work/negative_radius.json"

failures=0
expect_error() {  # description, command...
    local what="$1"; shift
    local status=0
    "$@" > "$work/out" 2> "$work/err" || status=$?
    local lines; lines=$(wc -l < "$work/err")
    if (( status == 0 )); then
        echo "FAIL $what: exit code 0"; failures=$((failures + 1))
    elif (( lines != 1 )); then
        echo "FAIL $what: $lines stderr lines:"; cat "$work/err"; failures=$((failures + 1))
    elif [[ -s "$work/out" ]]; then
        echo "FAIL $what: wrote to stdout:"; head -n 3 "$work/out"; failures=$((failures + 1))
    else
        echo "ok $what (exit $status): $(cat "$work/err")"
    fi
}

expect_error "missing file"        "$anyphys" run "$work/no_such_scene.json"
expect_error "invalid JSON"        "$anyphys" run "$work/truncated.json"
expect_error "invalid scene value" "$anyphys" run "$work/negative_radius.json"
expect_error "unknown backend"     "$anyphys" run "$scene" --backend no_such_engine
expect_error "--steps -1"          "$anyphys" run "$scene" --steps -1
expect_error "--steps abc"         "$anyphys" run "$scene" --steps abc
expect_error "--dt 0"              "$anyphys" run "$scene" --dt 0
expect_error "--dt -0.5"           "$anyphys" run "$scene" --dt -0.5
expect_error "--integrator foo"    "$anyphys" run "$scene" --integrator foo
expect_error "no scene argument"   "$anyphys" run
expect_error "unknown flag"        "$anyphys" run "$scene" --frobnicate
expect_error "no subcommand"       "$anyphys"
expect_error "unknown subcommand"  "$anyphys" frobnicate
expect_error "unknown scene"       "$anyphys" scene no_such_scene
expect_error "compare bad backend" "$anyphys" compare --backends no_such_engine
expect_error "compare bad scene"   "$anyphys" compare --scenes no_such_scene
expect_error "compare bad integrator" "$anyphys" compare --integrators foo

# The unknown-backend message lists the known backends.
"$anyphys" run "$scene" --backend no_such_engine 2> "$work/err" || true
grep -q native "$work/err" || { echo "FAIL: unknown backend message does not list native: $(cat "$work/err")"; failures=$((failures + 1)); }
# A rejected --out file is not created when the input was bad.
"$anyphys" run "$scene" --dt 0 --out "$work/never.csv" 2> /dev/null || true
[[ ! -e "$work/never.csv" ]] || { echo "FAIL: --out file written despite bad input"; failures=$((failures + 1)); }

(( failures == 0 )) || { echo "FAIL bad_input: $failures case(s)"; exit 1; }
echo "PASS bad_input"
