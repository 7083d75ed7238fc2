#!/usr/bin/env bash
# anyphys_vehicle drives on every built backend (the planar car on a 2D engine), writes the run
# CSV with the chassis, follows a control file, and refuses bad input with one line on stderr.
source "$(dirname "${BASH_SOURCE[0]}")/preamble.bash"

printf 'time,throttle,steer,brake\n0,1,0,0\n1,0,0,1\n' > "$work/control.csv"
for backend in $backends; do
  "$bin/anyphys_vehicle" --backend "$backend" --seconds 2 --out "$work/v.csv" > "$work/summary.txt"
  head -1 "$work/v.csv" | grep -q '^step,time,body,px,py,pz,' || { echo "FAIL $backend: CSV header"; exit 1; }
  grep -q ',chassis,' "$work/v.csv" || { echo "FAIL $backend: no chassis rows"; exit 1; }
  grep -q 'wheel load' "$work/summary.txt" || { echo "FAIL $backend: no summary"; exit 1; }
  # One second at full throttle, then braked: it moved forward and is slower at the end than at its top.
  "$bin/anyphys_vehicle" --backend "$backend" --seconds 2 --control "$work/control.csv" > "$work/c.txt"
  python3 - "$work/c.txt" "$backend" <<'PY'
import re, sys
text = open(sys.argv[1]).read()
now, top = map(float, re.search(r"speed now / top\s+([-\d.]+) / ([-\d.]+)", text).groups())
x = float(re.search(r"chassis at \(([-\d.]+),", text).group(1))
assert x > 0.5 and top > 1.0 and now < 0.5 * top, (sys.argv[2], now, top, x, text)
PY
  echo "ok $backend"
done
for bad in "--throttle 2" "--steer 1" "--seconds 0" "--backend nosuch" "--control $work/missing.csv"; do
  if "$bin/anyphys_vehicle" $bad > "$work/out.txt" 2> "$work/err.txt"; then echo "FAIL: '$bad' was accepted"; exit 1; fi
  [[ $(wc -l < "$work/err.txt") -eq 1 ]] || { echo "FAIL: '$bad' printed more than one line:"; cat "$work/err.txt"; exit 1; }
done
if "$anyphys" backends --json | grep -q '"box2d"'; then
  if "$bin/anyphys_vehicle" --backend box2d --steer 0.2 > /dev/null 2> "$work/err.txt"; then echo "FAIL: a planar car was steered"; exit 1; fi
  grep -q -- '--steer' "$work/err.txt" || { echo "FAIL: the planar steer refusal does not name --steer"; exit 1; }
fi
echo "PASS vehicle demo"
