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
printf '{ "settings": { "backend": "no_such_engine" }, "bodies": [] }\n' > "$work/file_backend.json"
printf '{ "settings": { "backendOptions": { "no_such_option": 1 } }, "bodies": [] }\n' > "$work/file_option.json"
# A NUL in a name would go raw into the CSV: refused, the one stderr line escaping it.
printf '{ "bodies": [ { "name": "a\\u0000b", "shape": { "type": "sphere", "radius": 1 } } ] }\n' > "$work/nul_name.json"

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
expect_error "file's unknown backend" "$anyphys" run "$work/file_backend.json"
expect_error "file's unknown backend option" "$anyphys" run "$work/file_option.json"
expect_error "NUL in a body name"  "$anyphys" run "$work/nul_name.json"

# Errors about a scene file's settings name the file and the value's JSON path in it, as its
# parse errors do (the API's own names are WorldSettings.backend and backend).
expect_naming() {  # file, text the one line must hold
    "$anyphys" run "$work/$1" 2> "$work/err" > /dev/null || true
    grep -qF "$2" "$work/err" || { echo "FAIL: $1: want \"$2\" in: $(cat "$work/err")"; failures=$((failures + 1)); }
}
expect_naming file_backend.json "file_backend.json: settings.backend: must be one of the built backends"
expect_naming file_option.json "file_option.json: settings: backend"
expect_naming negative_radius.json "negative_radius.json: bodies[0].shape.radius"
expect_naming nul_name.json 'nul_name.json: bodies[0].name: must not hold control characters (found U+0000 at byte 1), got "a\u0000b"'
# A flag's bad value is named by the flag.
expect_flag() {  # text the one line must hold, command...
    local want="$1"; shift
    "$@" 2> "$work/err" > /dev/null || true
    grep -qF "$want" "$work/err" || { echo "FAIL: $*: want \"$want\" in: $(cat "$work/err")"; failures=$((failures + 1)); }
}
expect_flag "anyphys: --backend: must be one of the built backends" "$anyphys" run "$scene" --backend no_such_engine
expect_flag "anyphys: --backends: must be one of the built backends" "$anyphys" compare --backends no_such_engine
expect_flag "anyphys: --backends: must be one of the built backends" "$anyphys" hardcases --backends no_such_engine

# The unknown-backend message lists the known backends.
"$anyphys" run "$scene" --backend no_such_engine 2> "$work/err" || true
grep -q native "$work/err" || { echo "FAIL: unknown backend message does not list native: $(cat "$work/err")"; failures=$((failures + 1)); }
# A rejected --out file is not created when the input was bad.
"$anyphys" run "$scene" --dt 0 --out "$work/never.csv" 2> /dev/null || true
[[ ! -e "$work/never.csv" ]] || { echo "FAIL: --out file written despite bad input"; failures=$((failures + 1)); }

(( failures == 0 )) || { echo "FAIL bad_input: $failures case(s)"; exit 1; }
echo "PASS bad_input"
