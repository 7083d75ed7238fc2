#!/usr/bin/env bash
# The testbed's command line and outputs (run under xvfb-run): bad input is one line naming the
# option and exit 1 (usage errors 2); a 2D engine runs a scene's planar variant, or shows why it
# cannot; --record writes one PNG per frame; --video writes a GIF through ffmpeg.
# Usage: options_and_outputs.sh TESTBED ANYPHYS_CLI
set -euo pipefail
testbed="$1"
anyphys="$2"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

refuse() {  # refuse EXPECTED_CODE WORD ARGS...: the run fails with that code and names WORD
  local code="$1" word="$2"
  shift 2
  set +e
  "$testbed" "$@" > "$work/out.txt" 2> "$work/err.txt"
  local got=$?
  set -e
  [[ $got -eq $code ]] || { echo "FAIL: '$*' exited $got, want $code"; cat "$work/err.txt"; exit 1; }
  grep -q -- "$word" "$work/err.txt" || { echo "FAIL: '$*' does not name $word: $(cat "$work/err.txt")"; exit 1; }
  echo "ok refused $*: $(head -1 "$work/err.txt")"
}
refuse 1 --frames --headless
refuse 1 --backends --headless --frames 2 --backends nosuch
refuse 1 --backends --headless --frames 2 --backends native,native,native,native,native
refuse 1 --scene --headless --frames 2 --scene nosuch
refuse 1 --size --headless --frames 2 --size 10x10
refuse 2 --frames --frames -3

# A scene file's setting the world refuses is named as the file names it (settings, not the API's
# WorldSettings), after the file's name, as `anyphys run` reports it.
printf '{ "settings": { "backendOptions": { "no_such_option": 1 } }, "bodies": [] }\n' > "$work/option.json"
"$testbed" --scene "$work/option.json" --backends native --headless --frames 2 --size 320x200 2> "$work/err.txt" > /dev/null || true
grep -qF "option.json: settings" "$work/err.txt" || { echo "FAIL: the file's setting is not named as the file names it: $(cat "$work/err.txt")"; exit 1; }
grep -q "WorldSettings" "$work/err.txt" && { echo "FAIL: the API's name shows: $(cat "$work/err.txt")"; exit 1; }
echo "ok a scene file's refused setting: $(head -1 "$work/err.txt")"

# The record folder gets one PNG per frame; the GIF is made by ffmpeg.
"$testbed" --scene bouncing_ball --headless --frames 3 --size 320x200 --record "$work/frames" > /dev/null
[[ $(ls "$work/frames" | grep -c '^frame_0000[0-2]\.png$') -eq 3 ]] || { echo "FAIL: --record wrote $(ls "$work/frames")"; exit 1; }
echo "ok --record: 3 frames"
if command -v ffmpeg > /dev/null; then
  "$testbed" --scene bouncing_ball --headless --frames 6 --size 320x200 --video "$work/clip.gif" > /dev/null
  head -c 6 "$work/clip.gif" | grep -q GIF8 || { echo "FAIL: --video wrote no GIF"; exit 1; }
  echo "ok --video: GIF of $(stat -c %s "$work/clip.gif") bytes"
else
  echo "skipped --video: ffmpeg not found"
fi

# A 2D engine gets the planar variant of a hard case; a 3D-only scene shows why it cannot run.
if "$anyphys" backends --json | python3 -c 'import json,sys; sys.exit(0 if any(b["capabilities"]["dimensions"] == 2 for b in json.load(sys.stdin)["backends"]) else 1)'; then
  two_d=$("$anyphys" backends --json | python3 -c 'import json,sys; print([b["name"] for b in json.load(sys.stdin)["backends"] if b["capabilities"]["dimensions"] == 2][0])')
  "$testbed" --scene hard_far_stack --backends "native,$two_d" --headless --frames 2 --size 320x200 \
    --dump-projections "$work/p.json" > "$work/out.txt"
  python3 - "$work/p.json" "$two_d" <<'PY'
import json, sys
views = json.load(open(sys.argv[1]))["views"]
assert views[1]["backend"] == sys.argv[2] and views[1]["scene"] == "hard_far_stack_planar" and not views[1]["error"], views[1]
print("ok", sys.argv[2], "runs", views[1]["scene"])
PY
  "$testbed" --scene torque_free_spin --backends "$two_d" --headless --frames 2 --size 320x200 2> "$work/err.txt" > /dev/null
  grep -q "planar" "$work/err.txt" || { echo "FAIL: no reason given for a 3D scene on $two_d: $(cat "$work/err.txt")"; exit 1; }
  echo "ok $two_d on a 3D scene: $(cat "$work/err.txt")"
fi
