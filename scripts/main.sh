#!/usr/bin/env bash
# The main job: set up, build, then sweep the built-in scenes over every built backend (what
# accuracy costs in time) and write the report. Each sweep runs as one shard per core, merged.
# The results stay in results/*.csv, the report in results/report/ (docs/report.md).
# Usage: scripts/main.sh
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
bash scripts/setup.sh
bash scripts/build.sh build
anyphys=build/bin/anyphys
results=results
mkdir -p "$results"

# Free flight and joints, which have closed forms: error against step and integrator.
free=(--scenes projectile,damped_motion,free_fall_drop,slider_spring,slider_spring_planar,hinge_pendulum,hinge_pendulum_planar
      --sweep timeStep=1/30,1/60,1/120,1/240,1/480
      --sweep integrator=explicit_euler,semi_implicit_euler,midpoint,verlet,rk4)
# Contacts: step against solver iterations (stability map); planar twins for box2d.
contacts=(--scenes box_stack_10,box_stack_10_planar,bouncing_ball,bouncing_ball_planar,slope_slide,slope_slide_planar
          --sweep timeStep=1/30,1/60,1/120 --sweep iterations=1,2,4,8)
# The cost of each effect: each switched off in turn against the scene's derived set.
effects=(--scenes box_stack_10,box_stack_10_planar,bouncing_ball,damped_motion,torque_free_spin
         --sweep effectOff=none,damping,gyroscopic,friction,restitution,events,sleeping,continuousCollision)

cores=$(nproc 2>/dev/null || echo 2)
(( cores > 4 )) && cores=4
sweep() {  # name, shards, repeat, compare arguments...
  local name="$1" shards="$2" repeat="$3"; shift 3
  local parts=() pids=()
  echo "main: sweep $name ($shards shards, $repeat timed runs each)" >&2
  for k in $(seq "$shards"); do
    # The progress bar of the first shard only: the shards advance together.
    if [[ $k -eq 1 ]]; then
      "$anyphys" compare "$@" --repeat "$repeat" --shard "$k/$shards" --out "$results/$name.part$k.csv" > /dev/null &
    else
      "$anyphys" compare "$@" --repeat "$repeat" --shard "$k/$shards" --out "$results/$name.part$k.csv" > /dev/null 2>&1 &
    fi
    pids+=($!)
    parts+=("$results/$name.part$k.csv")
  done
  for pid in "${pids[@]}"; do wait "$pid"; done
  "$anyphys" merge "${parts[@]}" --out "$results/$name.csv"
  rm -f "${parts[@]}" "${parts[@]/%.csv/.jsonl}"
}
sweep free "$cores" 3 "${free[@]}"
sweep contacts "$cores" 3 "${contacts[@]}"
# Effect costs are ratios of a few per cent: one process with the machine to itself and more
# timed runs (shards side by side disturb each other's timings by up to 25 %, measured).
sweep effects 1 9 "${effects[@]}"

echo
echo "Headline: per scene and backend, the fastest configuration within the scene's error target"
"$anyphys" report "$results/free.csv" "$results/contacts.csv" "$results/effects.csv" --out "$results/report"
