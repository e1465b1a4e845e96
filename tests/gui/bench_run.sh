#!/usr/bin/env bash
# `facesketch gui --bench-frames N` (issue 14): prints its figures, and neither offers nor
# replaces the recovery file, which holds a user's unsaved work: the run's scripted stroke is not
# work. A recovery file of another session is put in place first and must come out byte for byte.
# Usage: bench_run.sh FACESKETCH WORK
set -euo pipefail
# An X server of its own, whatever DISPLAY is: on a display shared with the tests beside it
# (ctest -j2 under one xvfb-run), their windows took the keyboard focus and covered this one.
if [ "${FACESKETCH_OWN_X:-}" != 1 ]; then FACESKETCH_OWN_X=1 exec xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" bash "$0" "$@"; fi
FACESKETCH=$1 WORK=$2
source "$(dirname "$0")/input_lib.sh"
make_data
export FACESKETCH_STATE_DIR="$WORK/state" FACESKETCH_CACHE_DIR="$WORK/cache"
"$FACESKETCH" strokes simulate "$WORK/faces" --model "$WORK/faces.model" --sample face_0055 --view front \
  -o "$WORK/state/recovery-session.json" > /dev/null
cp "$WORK/state/recovery-session.json" "$WORK/user-work.json"
"$FACESKETCH" gui "$WORK/faces.model" "$WORK/faces" --size 640x480 --bench-frames 40 > "$WORK/app.log" 2>&1 \
  || fail "the benchmark failed"
for figure in gui_frame_ms_ gui_frame_p95_ms_ gui_stroke_to_frame_ms_ gui_frame_cpu_ms_; do
  grep -Eq "^${figure}[0-9]+v [0-9]+\.[0-9]+$" "$WORK/app.log" || fail "no $figure figure"
done
grep -q "gui: stroke 1: [0-9]* vertices mapped" "$WORK/app.log" || fail "the scripted stroke was not read"
cmp -s "$WORK/state/recovery-session.json" "$WORK/user-work.json" || fail "the benchmark changed the recovery file"
grep -q "recovery file none (a benchmark)" "$WORK/app.log" || fail "the benchmark names a recovery file"
grep -q "restore" "$WORK/app.log" && fail "the benchmark offered to restore"
grep -q "validation" "$WORK/app.log" && fail "validation messages"
echo "ok: $(grep -E '^gui_frame_ms_' "$WORK/app.log")"
