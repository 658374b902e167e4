#!/bin/sh
# Runs INSIDE the test VM with a display device (tests/vm/kms-test.sh starts
# it through run-vm.sh with FT_VM_DISPLAY=bochs|virtio):
#   guest-kms.sh FIXTERRAIN SCENE KMS_CRTC ONE_LINE_LOG   (results in $FT_VM_OUT)
# 1. `fixterrain render` (scene.display = kms:CARD) shows the scene's frame
#    and holds it; the host takes a screendump of the scanout while it is
#    shown ("render"), the guest keeps its own PNG of the same frame
#    (guest.png). First thing after boot, so its time is boot-to-first-frame;
# 2. the offscreen references in the guest (offscreen.png, replay/);
# 3. the clear errors: a missing card, another process holding the DRM master,
#    a view size the connector has no mode for, an unknown connector;
# 4. `fixterrain run --display kms` (no CAN traffic: the scene's pose with
#    the failure annunciation) at the scene's frame rate for a few seconds
#    ("run" screendump), then SIGTERM; kms-crtc holds the card open meanwhile
#    (so the kernel does not restore the console by itself on the last close)
#    and prints the CRTC state before and after: fixterrain's teardown must
#    put the console's framebuffer back ("console-before"/"console-after").
# Screendump handshake: the guest prints "FT-KMS-DUMP NAME" on the console
# and waits for $FT_VM_OUT/NAME.ack, which the host writes after the dump.
set -u
bin=$1; scene=$2; crtc=$3; log1=$4
out=${FT_VM_OUT:?run it with tests/vm/run-vm.sh}
card=${FT_DRM_CARD:?no display device: run-vm.sh needs FT_VM_DISPLAY=bochs or virtio}
fail() { echo "guest-kms: FAIL: $*"; exit 1; }
up() { cut -d' ' -f1 /proc/uptime; }
[ "${FT_VM:-}" = 1 ] || fail "not inside the test VM"

dump() { # dump NAME: the host takes a screendump now; wait for its ack
  echo "FT-KMS-DUMP $1"
  i=0
  until [ -f "$out/$1.ack" ]; do
    i=$((i + 1)); [ "$i" -lt 600 ] || fail "no ack for screendump $1 in 30 s"
    sleep 0.05
  done
}
wait_for() { # wait_for FILE TEXT PID SECONDS: until FILE has TEXT (PID alive)
  i=0
  until grep -q "$2" "$1" 2>/dev/null; do
    i=$((i + 1)); [ "$i" -lt $(($4 * 10)) ] || fail "no '$2' in $1 after $4 s: $(cat "$1")"
    kill -0 "$3" 2>/dev/null || { sleep 0.2; grep -q "$2" "$1" 2>/dev/null && return 0
                                  fail "exited before '$2': $(cat "$1")"; }
    sleep 0.1
  done
}
expect_error() { # expect_error NAME TEXT ARGS...: fixterrain must fail saying TEXT
  name=$1; text=$2; shift 2
  "$bin" "$@" > "$out/err-$name.log" 2>&1; rc=$?
  [ "$rc" -eq 1 ] || fail "$name: exit $rc, expected 1: $(cat "$out/err-$name.log")"
  grep -q "$text" "$out/err-$name.log" || fail "$name: no '$text' in: $(cat "$out/err-$name.log")"
  echo "guest-kms: error ($name): $(grep -m 1 "$text" "$out/err-$name.log")"
}
echo "guest-kms: display $FT_VM_DISPLAY, $card ($(sed -n 's/^DRIVER=//p' /sys/class/drm/card0/device/uevent 2>/dev/null)), uptime $(up) s"
echo "guest-kms: connector modes: $(cat /sys/class/drm/card0-*/modes | tr '\n' ' ')"

# 1. first thing after boot: one frame on KMS, held while the host takes the
#    screendump; the display comes from the scene file this time
#    (scene.display = kms:CARD)
dump console-before
{ cat "$scene"; printf '[scene]\ndisplay = kms:%s\n' "$card"; } > /tmp/kms-display.ini
t0=$(up)
"$bin" render --scene /tmp/kms-display.ini --out "$out/guest.png" --hold-ms 5000 \
  > "$out/render.log" 2>&1 &
pid=$!
wait_for "$out/render.log" "showing the frame" "$pid" 180
t1=$(up)
dump render
kill -0 "$pid" 2>/dev/null || fail "render exited before the screendump was taken"
wait "$pid"; rc=$?
[ "$rc" -eq 0 ] || fail "render --display kms exit $rc: $(cat "$out/render.log")"
echo "guest-kms: render: start at $t0 s, frame shown by $t1 s (uptime); $(grep '^kms: first' "$out/render.log")"

# 2. the same frames offscreen in this VM (same CPU features as the KMS run):
#    the scene's frame and the annunciated frame `run` draws without CAN data
"$bin" render --scene "$scene" --display none --out "$out/offscreen.png" --quiet ||
  fail "offscreen render"
mkdir -p "$out/replay"
"$bin" replay --log "$log1" --scene "$scene" --frames-out "$out/replay" --quiet ||
  fail "offscreen replay"

# 3. errors
expect_error missing-card "cannot open /dev/dri/card7" render --scene "$scene" \
  --display kms:/dev/dri/card7 --quiet --out /tmp/x.png
expect_error no-mode "offers no 100x80 mode" render --scene "$scene" --display kms \
  --size 100x80 --quiet --out /tmp/x.png
{ cat "$scene"; printf '[display]\nconnector = DP-9\n'; } > /tmp/bad-connector.ini
expect_error no-connector "no connector 'DP-9'" render --scene /tmp/bad-connector.ini \
  --display kms --quiet --out /tmp/x.png
rm -f "$out/master.stop"
"$crtc" master "$card" "$out/master.stop" > "$out/master.txt" 2>&1 &
holder=$!
wait_for "$out/master.txt" "kms-crtc: ready" "$holder" 10
expect_error not-master "not the DRM master" render --scene "$scene" --display kms \
  --quiet --out /tmp/x.png
touch "$out/master.stop"; wait "$holder" || fail "kms-crtc master: $(cat "$out/master.txt")"

# 4. the live loop on KMS: frame rate, deadline misses, SIGTERM restores the CRTC
rm -f "$out/watch.stop"
"$crtc" watch "$card" "$out/watch.stop" > "$out/watch.txt" 2>&1 &
watcher=$!
wait_for "$out/watch.txt" "kms-crtc: ready" "$watcher" 10
"$bin" run --scene "$scene" --display kms --stats "$out/run.json" > "$out/run.log" 2>&1 &
pid=$!
wait_for "$out/run.log" "kms: first frame on screen" "$pid" 180
sleep 2   # past the loop's warm-up (lamp test) frame: the live frames
dump run
sleep 3
t_term=$(up)
kill -TERM "$pid"
wait "$pid"; rc=$?
[ "$rc" -eq 0 ] || fail "run --display kms exit $rc after SIGTERM: $(cat "$out/run.log")"
grep -q "stopped by a signal" "$out/run.log" || fail "run did not stop on SIGTERM: $(cat "$out/run.log")"
grep -q "^kms: restored CRTC" "$out/run.log" || fail "no CRTC restore: $(cat "$out/run.log")"
dump console-after
touch "$out/watch.stop"; wait "$watcher" || fail "kms-crtc watch: $(cat "$out/watch.txt")"
cat "$out/watch.txt"
before=$(sed -n 's/^before: //p' "$out/watch.txt")
after=$(sed -n 's/^after: //p' "$out/watch.txt")
if [ -z "$before" ] || [ "$before" != "$after" ]; then
  fail "the CRTC state after SIGTERM is not the one before the run: '$before' -> '$after'"
fi
echo "guest-kms: CRTC restored after SIGTERM: $after"
# paced by the monotonic clock: never more frames than periods (uptime is
# the same clock as the loop's t_start_ns here: no suspend in the VM)
period=$(sed -n 's/^period_ms *= *//p' "$scene")
frames=$(sed -n 's/^  "frames": \([0-9]*\).*/\1/p' "$out/run.json")
t_start=$(sed -n 's/.*"t_start_ns": \([0-9]*\).*/\1/p' "$out/run.json")
awk -v f="$frames" -v ts="$t_start" -v te="$t_term" -v p="$period" 'BEGIN {
  d = te - ts / 1e9; slots = d * 1000 / p
  printf "guest-kms: run: %d frames in %.2f s at %s ms: %.1f periods\n", f, d, p, slots
  exit !(f >= 1 && f <= slots + 2) }' || fail "run drew more frames than periods (not paced)"
echo "----- run.log"; cat "$out/run.log"
echo "----- run.json"; cat "$out/run.json"
echo "guest-kms: done"
