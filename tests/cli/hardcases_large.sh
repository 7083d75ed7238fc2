#!/usr/bin/env bash
# The hard cases `--fast` leaves out (over 100 bodies: the two pyramids and the ragdoll piles)
# pass or miss only as each backend declares. Without this, a declared miss that a solver change
# fixed ("passes but declared") or a pile that got worse went unseen until someone ran the full
# matrix by hand: native's ragdoll pile did, on 2026-11-29.
# ODE and Bullet skip the 5 050-box planar pyramid, their one case of minutes (1.06 s per step
# on ODE); both declare it a known miss. They skip the 20-row pyramids too (9 s of CI's CPU time):
# the contract's TwentyRowPyramidStandsOverTheWholeRun holds both to the same criteria.
set -euo pipefail
anyphys="$1"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

piles=hard_ragdoll_pile,hard_ragdoll_pile_planar
large=pyramid_20,pyramid_20_planar,$piles
built=$("$anyphys" backends | awk '/^[a-z0-9]+ /{print $1}')
pick() { local out=() b; for b in "$@"; do grep -qx "$b" <<< "$built" && out+=("$b"); done; local IFS=,; echo "${out[*]}"; }
cheap=$(pick native box2d)  # every case in seconds
slow=$(pick ode bullet)     # the ragdoll piles
"$anyphys" hardcases --fast --backends native > "$work/fast.txt"
for c in ${large//,/ } hard_pyramid_100_planar; do
  if grep -q "^$c " "$work/fast.txt"; then echo "FAIL: $c is in --fast: this script would run it twice"; exit 1; fi
done

# The tool exits 1 on any FAIL cell, including a declared miss that now passes.
"$anyphys" hardcases --cases "$large,hard_pyramid_100_planar" --backends "$cheap" | tee "$work/a.txt"
[[ -z "$slow" ]] || "$anyphys" hardcases --cases "$piles" --backends "$slow" | tee "$work/b.txt"

# Every case got a row with a verdict for each backend named (not an empty matrix).
verdicts() { local n=$(( $(tr -cd , <<< "$1" | wc -c) + 1 )) r='' k; for ((k = 0; k < n; ++k)); do r+='.*(pass|known|n/a)'; done; echo "$r"; }
for c in ${large//,/ }; do
  grep -Eq "^$c $(verdicts "$cheap")" "$work/a.txt" || { echo "FAIL: no row for $c on $cheap"; exit 1; }
done
for c in ${piles//,/ }; do
  [[ -z "$slow" ]] || grep -Eq "^$c $(verdicts "$slow")" "$work/b.txt" || { echo "FAIL: no row for $c on $slow"; exit 1; }
done
# Native is the engine these piles were built to hold: it passes every one.
for c in ${large//,/ } hard_pyramid_100_planar; do
  grep -Eq "^$c +.*\) +[0-9.e+-]+ pass" "$work/a.txt" || { echo "FAIL: native does not pass $c"; exit 1; }
done
echo "ok: the large hard cases pass or miss as declared"
