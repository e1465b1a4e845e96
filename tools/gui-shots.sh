#!/usr/bin/env bash
# Takes the README's app pictures (docs/images/gui-sketch.png, gui-overlay.png, gui-pose.png) with
# the app itself on the built-in data, under Xvfb when there is no DISPLAY:
#   tools/gui-shots.sh [OUTDIR]       (default docs/images; needs a built build/app/facesketch)
# Sketch and overlay: a session of simulated strokes tracing test face face_0230 from the front.
# Pose: real input through xdotool, as tests/gui/pose_input.sh: Tab, K at 0 s, a pose stroke along
# a smiling upper lip, Up (1 s), K, Ctrl+S, Ctrl+Q (the picture is the last frame).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
out=$(realpath -m "${1:-$root/docs/images}")
if [ -z "${DISPLAY:-}" ]; then exec xvfb-run -a -s "-screen 0 1920x1080x24 -noreset" bash "$0" "$out"; fi
FACESKETCH=$root/build/app/facesketch
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
source "$root/tests/gui/input_lib.sh"
mkdir -p "$WORK/state" "$out"
export FACESKETCH_STATE_DIR="$WORK/state"
cd "$WORK"
# The built-in data, made and cached by the first run of the app (`facesketch gui` with no data),
# which prints the model and dataset it opened.
"$FACESKETCH" gui --quit-after-frames 2 > app.log 2>&1
model=$(sed -n 's/^gui: model //p' app.log)
faces=$(sed -n 's/^gui: dataset //p' app.log)
if [ -z "$model" ] || [ -z "$faces" ]; then echo "gui-shots: the app named no built-in data:" >&2; cat app.log >&2; exit 1; fi
"$FACESKETCH" strokes simulate "$faces" --model "$model" --sample face_0230 --view front -o front.json > /dev/null
"$FACESKETCH" gui front.json --size 1280x800 --screenshot "$out/gui-sketch.png" --quit-after-frames 40 > app.log 2>&1
"$FACESKETCH" gui front.json --size 1280x800 --overlay --screenshot "$out/gui-overlay.png" --quit-after-frames 40 > app.log 2>&1

# A fresh state folder: the runs above left a recovery file, whose restore offer would take the keys.
rm -rf "$WORK/state" && mkdir "$WORK/state"
"$FACESKETCH" gui --size 1280x800 --print-guides --session-out pose.json --screenshot "$out/gui-pose.png" > app.log 2>&1 &
APP=$!
attach_app
key Tab
wait_for "gui: pose mode"
key k
wait_for "gui: keyframe at 0.000 s"
drag "$(smile 16 "$(guide upper_lip 0,0)")"
wait_for "gui: pose stroke: [1-9][0-9]* feature points"
key Up
wait_for "gui: time 1.000 s"
key k
wait_for "gui: keyframe at 1.000 s"
key ctrl+s
wait_for "gui: saved"
key ctrl+q
wait "$APP"
echo "wrote $out/gui-sketch.png, gui-overlay.png, gui-pose.png"
