#!/usr/bin/env bash
# `--help` works on the tool and on every subcommand: exit 0, usage on stdout, nothing on stderr.
set -euo pipefail
anyphys="$1"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

for args in "" backends run compare scenes scene schema; do
    # shellcheck disable=SC2086  # $args is deliberately split (empty for the top level)
    "$anyphys" $args --help > "$work/out" 2> "$work/err" || { echo "FAIL: 'anyphys $args --help' exited non-zero"; exit 1; }
    [[ ! -s "$work/err" ]] || { echo "FAIL: 'anyphys $args --help' wrote to stderr:"; cat "$work/err"; exit 1; }
    grep -qi usage "$work/out" || { echo "FAIL: 'anyphys $args --help' printed no usage:"; cat "$work/out"; exit 1; }
    if [[ -n "$args" ]]; then
        grep -q "$args" "$work/out" || { echo "FAIL: 'anyphys $args --help' does not mention $args"; exit 1; }
    fi
    echo "ok anyphys $args --help"
done
# -h is the short form.
"$anyphys" run -h > /dev/null
echo "PASS help"
