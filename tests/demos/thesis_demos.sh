#!/usr/bin/env bash
# anyphys_demos: every demo on every built backend (planar scenes on a 2D engine) exits 0 and
# writes the run CSV; the dynamics demo matches its closed forms; bad input is one line on stderr.
source "$(dirname "${BASH_SOURCE[0]}")/preamble.bash"

[[ $("$bin/anyphys_demos" --list | wc -l) -eq 5 ]] || { echo "FAIL: --list does not list 5 demos"; exit 1; }
for backend in $backends; do
  for demo in volumes materials joints dynamics; do
    "$bin/anyphys_demos" "$demo" --backend "$backend" --seconds 1 --out "$work/d.csv" > "$work/summary.txt" \
      || { echo "FAIL $demo on $backend:"; cat "$work/summary.txt"; exit 1; }
    head -1 "$work/d.csv" | grep -q '^step,time,body,px,py,pz,' || { echo "FAIL $demo on $backend: CSV header"; exit 1; }
  done
  # Free-body closed forms: exact to the printed digits on every engine.
  "$bin/anyphys_demos" dynamics --backend "$backend" --seconds 2 > "$work/dyn.txt"
  [[ $(grep -c '(expected .*, [+-]0.0 %)' "$work/dyn.txt") -eq 3 ]] || { echo "FAIL dynamics on $backend:"; cat "$work/dyn.txt"; exit 1; }
  echo "ok $backend"
done
"$bin/anyphys_demos" simultaneous --seconds 1 --out "$work/s.csv" > "$work/sim.txt"
for backend in $backends; do
  grep -q ",$backend/ball," "$work/s.csv" || { echo "FAIL simultaneous: no $backend/ball rows"; exit 1; }
done
for bad in "flying" "volumes --seconds 0" "volumes --backend nosuch" "simultaneous --backends native,nosuch"; do
  if "$bin/anyphys_demos" $bad > "$work/out.txt" 2> "$work/err.txt"; then echo "FAIL: '$bad' was accepted"; exit 1; fi
  [[ $(wc -l < "$work/err.txt") -eq 1 ]] || { echo "FAIL: '$bad' printed more than one line:"; cat "$work/err.txt"; exit 1; }
done
echo "PASS thesis demos"
