#!/usr/bin/env bash
# anyphys_ragdoll runs every mode on every built backend (the planar ragdoll on a 2D engine),
# writes the `anyphys run` CSV with the prefixed body names, and refuses bad input with one line.
source "$(dirname "${BASH_SOURCE[0]}")/preamble.bash"

for backend in $backends; do
  for mode in drop pile animated; do
    "$bin/anyphys_ragdoll" --backend "$backend" --mode "$mode" --count 3 --seconds 1 --out "$work/r.csv" > "$work/summary.txt"
    head -1 "$work/r.csv" | grep -q '^step,time,body,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz$' \
      || { echo "FAIL $backend $mode: CSV header"; exit 1; }
    grep -q ',r0/pelvis,' "$work/r.csv" || { echo "FAIL $backend $mode: no r0/pelvis rows"; exit 1; }
    grep -q 'worst joint gap' "$work/summary.txt" || { echo "FAIL $backend $mode: no summary"; cat "$work/summary.txt"; exit 1; }
  done
  echo "ok $backend"
done
"$bin/anyphys_ragdoll" --mode pile --count 3 --seconds 1 --out "$work/p.csv" > /dev/null
grep -q ',r2/head,' "$work/p.csv" || { echo "FAIL: pile of 3 lacks r2/"; exit 1; }
! grep -q ',r3/head,' "$work/p.csv" || { echo "FAIL: pile of 3 has r3/"; exit 1; }
rows=$(($(wc -l < "$work/p.csv") - 1))
[[ $rows -eq $((61 * 34)) ]] || { echo "FAIL: $rows rows, want 61 steps x 34 bodies"; exit 1; }

for bad in "--mode fly" "--count 0" "--count 201" "--strength 2" "--seconds -1" "--backend nosuch"; do
  if "$bin/anyphys_ragdoll" $bad > "$work/out.txt" 2> "$work/err.txt"; then
    echo "FAIL: '$bad' was accepted"; exit 1
  fi
  [[ $(wc -l < "$work/err.txt") -eq 1 ]] || { echo "FAIL: '$bad' printed more than one line:"; cat "$work/err.txt"; exit 1; }
done
echo "PASS ragdoll demo"
