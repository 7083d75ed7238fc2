#!/usr/bin/env bash
# Sharded sweeps: three shards run in parallel and merged give the rows of one unsharded run
# (timing and load columns aside); merge names a missing and a duplicated configuration; the
# Slurm and Kubernetes environment variables pick the same shard as --shard.
set -euo pipefail
anyphys="$1"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

args=(--scenes projectile,free_fall_drop,slope_slide --backends native,ode --sweep timeStep=1/30,1/60 --repeat 1)
"$anyphys" compare "${args[@]}" --out "$work/all.csv" > /dev/null 2>&1
for k in 1 2 3; do
  "$anyphys" compare "${args[@]}" --shard "$k/3" --out "$work/part$k.csv" > /dev/null 2>&1 &
done
wait
"$anyphys" merge "$work/part1.csv" "$work/part2.csv" "$work/part3.csv" --out "$work/merged.csv"

# Fallbacks: a Slurm array task 11 of 10..12 is shard 2/3; Kubernetes index 1 is shard 2/3.
SLURM_ARRAY_TASK_ID=11 SLURM_ARRAY_TASK_MIN=10 SLURM_ARRAY_TASK_COUNT=3 \
  "$anyphys" compare "${args[@]}" --out "$work/slurm.csv" > /dev/null 2>&1
JOB_COMPLETION_INDEX=1 "$anyphys" compare "${args[@]}" --shards 3 --out "$work/k8s.csv" > /dev/null 2>&1
JOB_COMPLETION_INDEX=1 ANYPHYS_SHARD_COUNT=3 "$anyphys" compare "${args[@]}" --out "$work/k8s_env.csv" > /dev/null 2>&1
if JOB_COMPLETION_INDEX=1 "$anyphys" compare "${args[@]}" --out "$work/none.csv" > /dev/null 2> "$work/err.txt"; then
  echo "FAIL: JOB_COMPLETION_INDEX without a shard count succeeded" >&2; exit 1
fi
grep -q "ANYPHYS_SHARD_COUNT" "$work/err.txt"

python3 - "$work" <<'PY'
import csv, sys
work = sys.argv[1]
read = lambda name: list(csv.DictReader(open(f"{work}/{name}")))
timing = {"ms_per_step_min", "ms_per_step_median", "ms_per_sim_second", "machine_load", "shard"}
strip = lambda rows: [{k: v for k, v in r.items() if k not in timing} for r in rows]
whole, merged = read("all.csv"), read("merged.csv")
assert len(whole) == 3 * 2 * 2, len(whole)
assert strip(merged) == strip(whole), "merged shards differ from the unsharded run"
parts = [read(f"part{k}.csv") for k in (1, 2, 3)]
assert all(parts), [len(p) for p in parts]   # every shard got work
assert sum(len(p) for p in parts) == len(whole)
assert {r["shard"] for r in parts[1]} == {"2/3"}
for other in ("slurm.csv", "k8s.csv", "k8s_env.csv"):
    assert strip(read(other)) == strip(parts[1]), other
    assert {r["shard"] for r in read(other)} == {"2/3"}, other
# A missing part and a duplicated part, for the merge failures below.
with open(f"{work}/part2_dup.csv", "w") as f:
    f.write(open(f"{work}/part2.csv").read())
print("ok shard_merge:", [len(p) for p in parts])
PY

# Merge fails, one stderr line, naming a missing configuration (with its scene, backend and swept
# value, though no part holds it) and a duplicated one.
first_row() {
  python3 -c "import csv,sys; r = next(csv.DictReader(open(sys.argv[1]))); print(r['config_id'], r['scene'], r['backend'], r['sweep'])" "$1"
}
read -r missing_id missing_scene missing_backend missing_sweep < <(first_row "$work/part3.csv")
read -r dup_id _ < <(first_row "$work/part2.csv")
if "$anyphys" merge "$work/part1.csv" "$work/part2.csv" "$work/part2_dup.csv" --out "$work/bad.csv" 2> "$work/err.txt"; then
  echo "FAIL: merge with a part missing and one twice succeeded" >&2; exit 1
fi
[[ $(wc -l < "$work/err.txt") -eq 1 ]] || { cat "$work/err.txt" >&2; exit 1; }
want_missing="missing: $missing_id (scene=$missing_scene backend=$missing_backend $missing_sweep)"
grep -qF "$want_missing" "$work/err.txt" || { echo "FAIL: lacks \"$want_missing\":" >&2; cat "$work/err.txt" >&2; exit 1; }
grep -qF "more than once: $dup_id (" "$work/err.txt" || { echo "FAIL: duplicate $dup_id not named:" >&2; cat "$work/err.txt" >&2; exit 1; }
[[ ! -e "$work/bad.csv" ]]
# Parts of different sweeps do not merge.
"$anyphys" compare --scenes projectile --backends native --sweep timeStep=1/30 --repeat 1 --out "$work/other.csv" > /dev/null 2>&1
if "$anyphys" merge "$work/part1.csv" "$work/other.csv" --out "$work/bad.csv" 2> "$work/err.txt"; then
  echo "FAIL: merge of two sweeps succeeded" >&2; exit 1
fi
grep -q "not of one sweep" "$work/err.txt" || { cat "$work/err.txt" >&2; exit 1; }
echo "ok shard_merge: merge failures"
