#!/usr/bin/env bash
# Tested as a person would use it (issue 14): under an X server of its own (Xvfb),
# real input events from xdotool: a stroke along the upper lip, key 3 (profile), a stroke along
# the nose profile, Ctrl+Z, Ctrl+Shift+Z, Ctrl+S (to --session-out); then Ctrl+Z (work that differs
# from the file), Ctrl+O (opening the file over it), Ctrl+Z (the open undone: the work is back,
# one stroke in effect), Ctrl+Shift+Z (its second stroke); Ctrl+E (export), Ctrl+Q.
# Then: the session holds the two strokes with their views; `facesketch sketch` replaying it
# gives the app's exported face to 1e-5 mm; the screenshot shows the face (not blank).
# Usage: sketch_input.sh FACESKETCH WORK
set -euo pipefail
# An X server of its own, whatever DISPLAY is: on a display shared with the tests beside it
# (ctest -j2 under one xvfb-run), their windows took the keyboard focus and covered this one.
if [ "${FACESKETCH_OWN_X:-}" != 1 ]; then FACESKETCH_OWN_X=1 exec xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" bash "$0" "$@"; fi
FACESKETCH=$1 WORK=$2
source "$(dirname "$0")/input_lib.sh"
make_data
start_app --session-out "$WORK/app.json" --export-out "$WORK/app.obj" --screenshot "$WORK/shot.png"
# It names the data it opened, one path a line (tools/gui-shots.sh finds the built-in data that way).
grep -qxF "gui: model $WORK/faces.model" "$WORK/app.log" && grep -qxF "gui: dataset $WORK/faces" "$WORK/app.log" \
  || fail "the app did not name its model and dataset: $(head -5 "$WORK/app.log")"

lip=$(guide upper_lip 0,0)
[ -n "$lip" ] || fail "no upper lip guide in the front view"
drag "$lip"
wait_for "gui: stroke 1: [0-9]+ vertices mapped"
key 3
wait_for "^guide nose_profile view 90,0:"
nose=$(guide nose_profile 90,0)
drag "$nose"
wait_for "gui: stroke 2: [0-9]+ vertices mapped"
key ctrl+z
wait_for "gui: undone, 1 strokes in effect"
key ctrl+shift+z
wait_for "gui: redone, 2 strokes in effect"
key ctrl+s
wait_for "gui: saved .*app.json \(2 strokes\)"
key ctrl+z
wait_for_count "gui: undone, 1 strokes in effect" 2
key ctrl+o
wait_for "gui: opened .*app.json \(2 strokes\)"
key ctrl+z
wait_for "gui: undone the open, 1 strokes in effect"
key ctrl+shift+z
wait_for_count "gui: redone, 2 strokes in effect" 2
key ctrl+e
wait_for "gui: exported .*app.obj"
key ctrl+q
wait "$APP" || fail "the app exited with code $?"
APP=
grep -q "validation" "$WORK/app.log" && fail "validation messages"

"$FACESKETCH" sketch "$WORK/faces.model" "$WORK/faces" --session "$WORK/app.json" -o "$WORK/replay.obj" > "$WORK/replay.log" \
  || fail "facesketch sketch could not replay the session: $(cat "$WORK/replay.log")"
grep -q "2 strokes applied, 0 refused" "$WORK/replay.log" || fail "replay: $(cat "$WORK/replay.log")"

python3 - "$WORK" "$lip" "$nose" << 'PY'
import json, struct, sys, zlib
work = sys.argv[1]
s = json.load(open(f"{work}/app.json"))
actions = s["actions"]
assert len(actions) == 2, f"{len(actions)} strokes in the session"
views = [(a["stroke"]["view"]["azimuth"], a["stroke"]["view"]["elevation"]) for a in actions]
assert abs(views[0][0]) < 1e-9 and abs(views[1][0] - 90) < 1e-9, f"views {views}"
# Every position the drag passed through is in the stroke, in order (a repeated position adds
# nothing): the events were queued faster than frames, so this fails if the app read the pointer's
# latest position instead of each event's.
for action, dragged in zip(actions, sys.argv[2:4]):
    want = []
    for p in dragged.split():
        xy = tuple(float(c) for c in p.split(","))
        if not want or want[-1] != xy:
            want.append(xy)
    got = [(p["x"], p["y"]) for p in action["stroke"]["points"]]
    assert got == want, f"the stroke holds {got}, the drag went through {want}"

def vertices(path):
    return [tuple(map(float, l.split()[1:4])) for l in open(path) if l.startswith("v ")]
a, b = vertices(f"{work}/app.obj"), vertices(f"{work}/replay.obj")
assert len(a) == len(b) > 0, f"{len(a)} against {len(b)} vertices"
worst = max(abs(x - y) for p, q in zip(a, b) for x, y in zip(p, q))
assert worst <= 1e-5, f"the replayed face differs from the app's by {worst} mm"

# The screenshot: decode the PNG (8-bit RGB/RGBA, any filter) and look for the face.
data = open(f"{work}/shot.png", "rb").read()
pos, idat, w = 8, b"", 0
while pos < len(data):
    n, kind = struct.unpack(">I4s", data[pos:pos + 8])
    body = data[pos + 8:pos + 8 + n]
    if kind == b"IHDR":
        w, h, depth, ctype = struct.unpack(">IIBB", body[:10])
        assert depth == 8 and ctype in (2, 6), f"PNG depth {depth} colour type {ctype}"
        bpp = 4 if ctype == 6 else 3
    elif kind == b"IDAT":
        idat += body
    pos += 12 + n
raw, stride, rows, prev = zlib.decompress(idat), w * bpp, [], bytearray(w * bpp)
for y in range(h):
    f, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
    for i in range(stride):
        left = line[i - bpp] if i >= bpp else 0
        up, ul = prev[i], prev[i - bpp] if i >= bpp else 0
        if f == 1: line[i] = (line[i] + left) & 255
        elif f == 2: line[i] = (line[i] + up) & 255
        elif f == 3: line[i] = (line[i] + (left + up) // 2) & 255
        elif f == 4:
            p = left + up - ul
            pa, pb, pc = abs(p - left), abs(p - up), abs(p - ul)
            line[i] = (line[i] + (left if pa <= pb and pa <= pc else up if pb <= pc else ul)) & 255
    rows.append(line)
    prev = line
# The middle third of the window: mostly face (shaded skin, not the light grey background).
counts, total = {}, 0
for y in range(h // 3, 2 * h // 3):
    for x in range(w // 3, 2 * w // 3):
        px = tuple(rows[y][x * bpp:x * bpp + 3])
        counts[px] = counts.get(px, 0) + 1
        total += 1
background = counts.get((237, 237, 240), 0)
assert len(counts) > 200, f"only {len(counts)} colours in the middle of the screenshot"
assert background < total / 2, f"{background} of {total} middle pixels are background"
print(f"ok: 2 strokes, views {views}, worst {worst} mm, {len(counts)} colours in the middle")
PY
