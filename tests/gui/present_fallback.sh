#!/usr/bin/env bash
# How frames reach the window when the X server has no MIT-SHM (a remote display, or a server
# without the extension; here Xvfb started with `-extension MIT-SHM`): `--present auto` falls back
# to the Vulkan swapchain and says why, and `--present shm` fails with that reason instead of
# drawing nothing. Usage: present_fallback.sh FACESKETCH WORK
set -euo pipefail
FACESKETCH=$1 WORK=$2
if [ "${FACESKETCH_OWN_X:-}" != 1 ]; then
  export FACESKETCH_OWN_X=1
  exec xvfb-run -a -s "-screen 0 1280x1024x24 -extension MIT-SHM -noreset" bash "$0" "$@"
fi
source "$(dirname "$0")/input_lib.sh"
make_data
export FACESKETCH_STATE_DIR="$WORK/state" FACESKETCH_CACHE_DIR="$WORK/cache"
"$FACESKETCH" gui "$WORK/faces.model" "$WORK/faces" --size 640x480 --quit-after-frames 5 --screenshot "$WORK/shot.png" \
  > "$WORK/app.log" 2>&1 || fail "the app failed without MIT-SHM"
grep -q "^gui: presenting through swapchain (MIT-SHM: the X server has no MIT-SHM)$" "$WORK/app.log" \
  || fail "no fallback to the swapchain named in the log"
[ -s "$WORK/shot.png" ] || fail "no screenshot through the swapchain"
if "$FACESKETCH" gui "$WORK/faces.model" "$WORK/faces" --size 640x480 --quit-after-frames 5 --present shm > "$WORK/shm.log" 2>&1; then
  fail "--present shm ran without MIT-SHM"
fi
grep -q "cannot present by MIT-SHM: the X server has no MIT-SHM" "$WORK/shm.log" || fail "--present shm: $(cat "$WORK/shm.log")"
grep -q "validation" "$WORK/app.log" && fail "validation messages"
echo "ok: $(grep presenting "$WORK/app.log")"
