# Shared by the real-input tests of `facesketch gui` (tests/gui/*.sh): small data, the X display,
# starting the app and driving it with xdotool (real X input events through XTEST).
# Sourced with FACESKETCH (the executable) and WORK (a scratch folder) set.

set -euo pipefail

fail() {
  echo "FAILED: $*" >&2
  if [ -f "$WORK/app.log" ]; then echo "--- app log:" >&2; tail -n 40 "$WORK/app.log" >&2; fi
  exit 1
}

# The small synthetic set and model of tests/cli/sketch.cmake.
make_data() {
  rm -rf "$WORK"
  mkdir -p "$WORK/state" "$WORK/cache"
  "$FACESKETCH" synth -o "$WORK/faces" --identities 60 --seed 3 > /dev/null
  "$FACESKETCH" train "$WORK/faces" -o "$WORK/faces.model" -k 7 --folds 3 --latent-dim 6 --cleanup-dim 12 --correlation-dim 10 \
    --restarts 1 -q > /dev/null
}

# Waits until the app log has a line matching $1 (extended regex); fails after $2 seconds.
wait_for() {
  local pattern=$1 seconds=${2:-120} i
  for ((i = 0; i < seconds * 10; ++i)); do
    if grep -Eq "$pattern" "$WORK/app.log" 2> /dev/null; then return 0; fi
    if [ -n "${APP:-}" ] && ! kill -0 "$APP" 2> /dev/null; then fail "the app exited while waiting for '$pattern'"; fi
    sleep 0.1
  done
  fail "no '$pattern' in the app's output after $seconds s"
}

# Waits (up to $3 s, default 120) until at least $2 lines of the app's output match $1.
wait_for_count() {
  local pattern=$1 n=$2 seconds=${3:-120} i
  for ((i = 0; i < seconds * 10; ++i)); do
    if [ "$(grep -Ec "$pattern" "$WORK/app.log" 2> /dev/null || true)" -ge "$n" ]; then return 0; fi
    if [ -n "${APP:-}" ] && ! kill -0 "$APP" 2> /dev/null; then fail "the app exited while waiting for $n lines of '$pattern'"; fi
    sleep 0.1
  done
  fail "fewer than $n lines of '$pattern' in the app's output after $seconds s"
}

# Starts the app on the small data with the extra arguments; sets APP (pid) and WID (window).
start_app() {
  export FACESKETCH_STATE_DIR="$WORK/state" FACESKETCH_CACHE_DIR="$WORK/cache"
  "$FACESKETCH" gui "$WORK/faces.model" "$WORK/faces" --size 1000x760 --print-guides "$@" > "$WORK/app.log" 2>&1 &
  APP=$!
  attach_app
}

# For an app started in the background as APP, writing to $WORK/app.log: waits for its first
# frame, sets WID (its window) and gives that window the keyboard focus.
attach_app() {
  wait_for "gui: first frame" 300
  WID=$(xdotool search --sync --limit 1 --pid "$APP" --name '^FaceSketch$')
  [ -n "$WID" ] || fail "no FaceSketch window"
  xdotool windowfocus --sync "$WID" 2> /dev/null || xdotool windowfocus "$WID"
  sleep 0.3
}

# The points "x,y ..." of a lip traced as a smile: its ends raised by up to $1 pixels, its middle kept.
smile() {
  python3 -c '
import sys
lift, p = float(sys.argv[1]), [tuple(map(int, q.split(","))) for q in sys.argv[2].split()]
xs = [x for x, _ in p]
c, h = (min(xs) + max(xs)) / 2, (max(xs) - min(xs)) / 2
print(" ".join(f"{x},{round(y - lift * ((x - c) / h) ** 2)}" for x, y in p))' "$1" "$2"
}

# The last guide line for $1 in view $2 ("0,0", "90,0"): its points, "x,y x,y ...".
guide() {
  grep -E "^guide $1 view $2:" "$WORK/app.log" | tail -n 1 | sed -e 's/^[^:]*: //'
}

# Drags with the left button through the points "x,y x,y ..." (window coordinates), in one
# xdotool call: the events arrive far faster than the app draws frames, so they queue up as a
# quick hand's do on a slow machine, and the app must take each position from its own event
# (sketch_input.sh checks that the stroke holds every point).
drag() {
  local points=($1) args=() first=1 p
  for p in "${points[@]}"; do
    args+=(mousemove --window "$WID" "${p%,*}" "${p#*,}")
    if [ $first = 1 ]; then
      args+=(mousedown 1)
      first=0
    fi
  done
  xdotool "${args[@]}" mouseup 1
}

key() {
  xdotool key --clearmodifiers "$1"
}
