#!/usr/bin/env bash
# Pose mode and the timeline as a person would use them (issue 14): under an X server of its own
# (Xvfb), real input events from xdotool: Tab (pose mode), K (a keyframe at 0 s from
# the neutral pose), a pose stroke along a smiling upper lip, Up (time 1 s), K (a second keyframe),
# Up, K and Delete (a third keyframe at 2 s, deleted again), Down, Space (play, looping from the end), Space (pause), Ctrl+Z and Ctrl+Shift+Z, Ctrl+S (to
# --session-out), Ctrl+E (the posed face), Ctrl+G (the timeline as .glb), Ctrl+Q. Then: the session
# holds the five pose actions; `facesketch pose` replaying it gives the app's posed face to
# 1e-5 mm, `facesketch animate` the identical .glb; the posed face moved from the neutral one; the
# autosave on exit restores the pose actions at the next start.
# Usage: pose_input.sh FACESKETCH WORK
set -euo pipefail
# An X server of its own, whatever DISPLAY is: on a display shared with the tests beside it
# (ctest -j2 under one xvfb-run), their windows took the keyboard focus and covered this one.
if [ "${FACESKETCH_OWN_X:-}" != 1 ]; then FACESKETCH_OWN_X=1 exec xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" bash "$0" "$@"; fi
FACESKETCH=$1 WORK=$2
source "$(dirname "$0")/input_lib.sh"
make_data
# The small posed set and pose model of tests/cli/poses.cmake (the same topology as make_data's).
"$FACESKETCH" synth -o "$WORK/posed" --identities 14 --poses --seed 4 > /dev/null
"$FACESKETCH" train-poses "$WORK/posed" -o "$WORK/posed.poses" --components 1,3 --latent-dims 4 > /dev/null
start_app --poses "$WORK/posed.poses" --session-out "$WORK/app.json" --export-out "$WORK/app.obj" --glb-out "$WORK/app.glb"

key Tab
wait_for "gui: pose mode"
key k
wait_for "gui: keyframe at 0.000 s \(1 keyframes\)"
lip=$(guide upper_lip 0,0)
[ -n "$lip" ] || fail "no upper lip guide in the front view"
# A smile: the lip's ends raised by up to 14 pixels, its middle kept.
drag "$(smile 14 "$lip")"
wait_for "gui: pose stroke: [1-9][0-9]* feature points"
key Up
wait_for "gui: time 1.000 s"
key k
wait_for "gui: keyframe at 1.000 s \(2 keyframes\)"
# A third keyframe at 2 s, deleted again with Delete (the keyframe under the time cursor).
key Up
wait_for "gui: time 2.000 s"
key k
wait_for "gui: keyframe at 2.000 s \(3 keyframes\)"
key Delete
wait_for "gui: keyframe at 2.000 s deleted"
key Down
wait_for "gui: time 1.000 s"
key space
wait_for "gui: playing from 1.000 s"
sleep 0.5
key space
wait_for "gui: paused at [01]\.[0-9]+ s"
key ctrl+z
wait_for "gui: undone, 0 strokes in effect, 4 pose actions"
key ctrl+shift+z
wait_for "gui: redone, 0 strokes in effect, 5 pose actions"
key ctrl+s
wait_for "gui: saved .*app.json \(0 strokes\) with 5 pose actions"
key ctrl+e
wait_for "gui: exported .*app.obj"
key ctrl+g
wait_for "gui: exported .*app.glb \([0-9]+ frames at 30 fps\)"
key ctrl+q
wait "$APP" || fail "the app exited with code $?"
APP=
grep -q "validation" "$WORK/app.log" && fail "validation messages"

"$FACESKETCH" pose "$WORK/posed.poses" --session "$WORK/app.json" -o "$WORK/replay.obj" > "$WORK/replay.log" \
  || fail "facesketch pose could not replay the session: $(cat "$WORK/replay.log")"
grep -q "1 pose strokes, 2 keyframes replayed" "$WORK/replay.log" || fail "pose replay: $(cat "$WORK/replay.log")"
"$FACESKETCH" animate "$WORK/app.json" -o "$WORK/replay.glb" --fps 30 > "$WORK/animate.log" \
  || fail "facesketch animate could not play the session: $(cat "$WORK/animate.log")"
cmp -s "$WORK/app.glb" "$WORK/replay.glb" || fail "the app's .glb differs from facesketch animate's"

# The autosave on exit holds the pose actions too, and the next start restores them.
"$FACESKETCH" gui "$WORK/faces.model" "$WORK/faces" --poses "$WORK/posed.poses" --size 1000x760 --restore --quit-after-frames 3 \
  > "$WORK/restore.log" 2>&1 || fail "the restoring app exited with code $?: $(tail -n 5 "$WORK/restore.log")"
grep -q "gui: restored 5 pose actions from the recovery file" "$WORK/restore.log" || fail "the app did not restore the pose actions"
"$FACESKETCH" pose "$WORK/posed.poses" --session "$WORK/state/recovery-session.json" -o "$WORK/recovered.obj" > /dev/null \
  || fail "facesketch pose could not replay the recovery file"
cmp -s "$WORK/app.obj" "$WORK/recovered.obj" || fail "the recovery file poses another face than the app's"
grep -q "validation" "$WORK/restore.log" && fail "validation messages on restoring"

python3 - "$WORK" << 'PY'
import json, sys
work = sys.argv[1]
s = json.load(open(f"{work}/app.json"))
kinds = [(a["type"], a.get("time")) for a in s["actions"]]
assert kinds == [("keyframe", 0), ("pose-stroke", None), ("keyframe", 1), ("keyframe", 2), ("keyframe-delete", 2)], f"actions {kinds}"
assert s["poses"] and s["face"], "the session names no pose model or face"

def vertices(path):
    return [tuple(map(float, l.split()[1:4])) for l in open(path) if l.startswith("v ")]
a, b = vertices(f"{work}/app.obj"), vertices(f"{work}/replay.obj")
assert len(a) == len(b) > 0, f"{len(a)} against {len(b)} vertices"
worst = max(abs(x - y) for p, q in zip(a, b) for x, y in zip(p, q))
assert worst <= 1e-5, f"the replayed posed face differs from the app's by {worst} mm"
# The pose moved the face: the posed face against the neutral the session names.
import struct
data = open(f"{work}/app.face.ply", "rb").read()
header, body = data.split(b"end_header\n", 1)
count = int([l for l in header.decode().splitlines() if l.startswith("element vertex")][0].split()[2])
neutral = [struct.unpack_from("<3f", body, 12 * i) for i in range(count)]
assert count == len(a), f"face file of {count} vertices, posed face of {len(a)}"
moved = max(sum((x - y) ** 2 for x, y in zip(p, q)) ** 0.5 for p, q in zip(a, neutral))
assert moved > 0.5, f"the pose stroke moved no vertex more than {moved} mm"
print(f"ok: {kinds}, worst {worst} mm, largest motion {moved:.2f} mm, identical .glb")
PY
