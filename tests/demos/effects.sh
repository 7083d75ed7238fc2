#!/usr/bin/env bash
# anyphys_effects runs each special-effect demo on every built backend (planar on a 2D engine):
# each exits 0 only when what it shows happened (the boat rides the swell, the water carries the
# crates, the flag flies, the blast scatters the stack that stood), writes the run CSV, and bad
# input is one line on stderr.
source "$(dirname "${BASH_SOURCE[0]}")/preamble.bash"

for backend in $backends; do
  "$bin/anyphys_effects" boat --backend "$backend" --seconds 6 --out "$work/boat.csv" > "$work/boat.txt" || { cat "$work/boat.txt"; echo "FAIL boat on $backend"; exit 1; }
  grep -q ',boat,' "$work/boat.csv" || { echo "FAIL $backend: no boat rows"; exit 1; }
  "$bin/anyphys_effects" dambreak --backend "$backend" --seconds 1.5 > "$work/dam.txt" || { cat "$work/dam.txt"; echo "FAIL dambreak on $backend"; exit 1; }
  "$bin/anyphys_effects" flag --backend "$backend" --seconds 2 > "$work/flag.txt" || { cat "$work/flag.txt"; echo "FAIL flag on $backend"; exit 1; }
  "$bin/anyphys_effects" explosion --backend "$backend" --seconds 2 > "$work/boom.txt" || { cat "$work/boom.txt"; echo "FAIL explosion on $backend"; exit 1; }
  echo "ok $backend"
done
for bad in "nosuch" "boat --seconds 0" "flag --backend nosuch"; do
  if "$bin/anyphys_effects" $bad > "$work/out.txt" 2> "$work/err.txt"; then echo "FAIL: '$bad' was accepted"; exit 1; fi
  [[ $(wc -l < "$work/err.txt") -eq 1 ]] || { echo "FAIL: '$bad' printed more than one line:"; cat "$work/err.txt"; exit 1; }
done
echo "PASS effects demos"
