#!/usr/bin/env bash
# Never lose work (issue 14): two strokes drawn with real input events, the app autosaves (every
# second here), SIGKILL; the recovery file holds both strokes, the next start restores them
# (--restore), and `facesketch sketch` replays them all.
# Usage: autosave_input.sh FACESKETCH WORK
set -euo pipefail
# An X server of its own, whatever DISPLAY is: on a display shared with the tests beside it
# (ctest -j2 under one xvfb-run), their windows took the keyboard focus and covered this one.
if [ "${FACESKETCH_OWN_X:-}" != 1 ]; then FACESKETCH_OWN_X=1 exec xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" bash "$0" "$@"; fi
FACESKETCH=$1 WORK=$2
source "$(dirname "$0")/input_lib.sh"
make_data
# Through the Vulkan swapchain, which the other gui tests (MIT-SHM under Xvfb) do not use.
start_app --autosave-seconds 1 --present swapchain
wait_for "gui: presenting through swapchain$"
drag "$(guide upper_lip 0,0)"
wait_for "gui: stroke 1: [0-9]+ vertices mapped"
key 3
wait_for "^guide nose_profile view 90,0:"
drag "$(guide nose_profile 90,0)"
wait_for "gui: stroke 2: [0-9]+ vertices mapped"
recovery="$WORK/state/recovery-session.json"
for ((i = 0; i < 100; ++i)); do
  if [ -f "$recovery" ] && python3 -c "import json,sys; sys.exit(len(json.load(open('$recovery'))['actions']) != 2)"; then break; fi
  sleep 0.1
done
kill -KILL "$APP"
wait "$APP" 2> /dev/null || true
APP=
python3 - "$recovery" << 'PY'
import json, sys
s = json.load(open(sys.argv[1]))
views = [a["stroke"]["view"]["azimuth"] for a in s["actions"]]
assert views == [0, 90], f"recovery file views {views}"
PY

"$FACESKETCH" gui "$WORK/faces.model" "$WORK/faces" --size 1000x760 --restore --quit-after-frames 3 > "$WORK/app.log" 2>&1 \
  || fail "the restoring app exited with code $?"
grep -q "gui: restored 2 strokes from the recovery file" "$WORK/app.log" || fail "the app did not restore both strokes"
"$FACESKETCH" sketch "$WORK/faces.model" "$WORK/faces" --session "$recovery" -o "$WORK/replay.ply" > "$WORK/replay.log"
grep -q "2 strokes applied, 0 refused" "$WORK/replay.log" || fail "replay of the recovery file: $(cat "$WORK/replay.log")"
echo "ok: the recovery file restores both strokes"
