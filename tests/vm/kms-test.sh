#!/bin/sh
# The cockpit display path proven in the test VM, one boot per
# display device (bochs-drm, virtio-gpu):
#   kms-test.sh BUILD_DIR OUT_DIR COMPARE_IMAGE QMP_SCREENDUMP KMS_CRTC [DEVICES]
# On the host: the scene (320x240, set as the preferred mode of the emulated
# monitor's EDID; a 65^2 synthetic terrain; 250 ms frames, which TCG keeps),
# its offscreen render (ref.png), a deliberately wrong frame (the
# same with the heading 1 degree off: wrong.png) and the frame `run` draws
# without CAN data (the scene pose with the failure annunciation, from
# `fixterrain replay` of a one-line log: ref-run.png).
# In the VM (guest-kms.sh): fixterrain shows those frames on KMS; the host
# serves its screendump requests over QMP (scanout -> PPM) and then compares:
#   render.ppm vs offscreen.png (the guest's own offscreen render of the
#     scene, another process, no display) and guest.png (the readback of the
#     shown frame)                       must be IDENTICAL (every byte)
#   render.ppm vs ref.png (host)         must MATCH within the tolerance below
#   render.ppm vs wrong.png              must DIFFER (beyond that tolerance)
#   run.ppm vs the guest's offscreen replay frame: IDENTICAL; vs ref-run.png: MATCH
#   console-after.ppm vs console-before  must MATCH loosely (the console is
#                                        back; its cursor may blink)
# Tolerance against the host's frames: a pixel differs when a channel differs
# by more than 2 levels; at most 0.1% of the pixels may differ and the mean
# absolute channel difference must be <= 0.5 levels. Why not exact: the host's
# llvmpipe uses AVX2, the guest's (-cpu max,-avx,-avx2) SSE; a few silhouette
# pixels come out differently. The display path itself adds no difference.
# DEVICES defaults to "bochs virtio".
set -eu
build=$(cd "$1" && pwd); out=$2; compare=$3; qmpdump=$4; crtc=$5
devices=${6:-bochs virtio}
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$out"; out=$(cd "$out" && pwd)
fail() { echo "kms-test: FAIL: $*" >&2; exit 1; }
fx=$build/fixterrain
period_ms=${FT_KMS_PERIOD_MS:-250}

cat > "$out/kms.ini" <<EOS
[scene]
name = vm-kms
method = brute
backend = egl-gles3
[view]
width_px = 320
height_px = 240
[terrain]
dem =
synth_side = 65
synth_spacing_m = 120
synth_anchor_lat_deg = 46.5
synth_anchor_lon_deg = 8.0
[pose]
lat_deg = 46.52
lon_deg = 8.03
alt_m = 3800
heading_deg = 30
pitch_deg = -15
roll_deg = 0
[frame]
period_ms = $period_ms
[can]
interface = vcan0
EOS
"$fx" render --scene "$out/kms.ini" --display none --out "$out/ref.png" --quiet ||
  fail "host render"
"$fx" render --scene "$out/kms.ini" --display none --pose 46.52,8.03,3800,31,-15,0 \
  --out "$out/wrong.png" --quiet || fail "host render (wrong pose)"
echo "(1000.000000) vcan0 7FF#0000000000000000" > "$out/one.log"
rm -rf "$out/ref-run"; mkdir -p "$out/ref-run"
"$fx" replay --log "$out/one.log" --scene "$out/kms.ini" --frames-out "$out/ref-run" --quiet ||
  fail "host replay (annunciated frame)"
cp "$out/ref-run/frame_000000.png" "$out/ref-run.png"
"$compare" "$out/ref.png" "$out/wrong.png" --expect-differ > /dev/null ||
  fail "the wrong pose renders the same frame: the test would prove nothing"

summary=$out/summary.txt
: > "$summary"
for dev in $devices; do
  d=$out/$dev
  rm -rf "$d"; mkdir -p "$d"
  echo "kms-test: $dev: booting" >&2
  t0=$(date +%s.%N)
  FT_VM_DISPLAY=$dev FT_VM_DISPLAY_SIZE=320x240 FT_VM_TIMEOUT=${FT_VM_TIMEOUT:-300} \
    "$here/run-vm.sh" "tests/vm/guest-kms.sh $fx $out/kms.ini $crtc $out/one.log" "$d" > "$d/vm.txt" 2>&1 &
  vm=$!
  # serve the guest's screendump requests until the VM is gone (bounded)
  served=' '
  i=0
  while kill -0 "$vm" 2>/dev/null; do
    i=$((i + 1)); [ "$i" -lt 20000 ] || { kill "$vm"; fail "$dev: VM did not finish"; }
    [ -f "$d/console.log" ] || { sleep 0.05; continue; }
    for name in $(tr -d '\r' < "$d/console.log" | sed -n 's/^FT-KMS-DUMP \([a-z-]*\)$/\1/p'); do
      case $served in *" $name "*) continue ;; esac
      served="$served$name "
      if [ "$name" = render ]; then
        awk -v a="$t0" -v b="$(date +%s.%N)" \
          'BEGIN { printf "%.1f\n", b - a }' > "$d/host-first-frame-s.txt"
      fi
      "$qmpdump" "$d/qmp.sock" "$d/$name.ppm" >> "$d/dumps.txt" 2>&1 ||
        { cat "$d/dumps.txt" >&2; kill "$vm"; fail "$dev: screendump $name"; }
      touch "$d/$name.ack"
    done
    sleep 0.05
  done
  rc=0; wait "$vm" || rc=$?
  cat "$d/vm.txt"
  [ "$rc" -eq 0 ] || fail "$dev: the guest part failed (exit $rc)"
  cat "$d/dumps.txt"

  c() { "$compare" "$@" | tee -a "$d/compare.txt"; }
  exact="--level 0 --max-fraction 0 --max-mean 0"
  # shellcheck disable=SC2086
  {
    c "$d/render.ppm" "$d/offscreen.png" $exact ||
      fail "$dev: the KMS scanout is not the guest's offscreen render of the frame"
    c "$d/render.ppm" "$d/guest.png" $exact ||
      fail "$dev: the KMS scanout is not the frame's own readback"
    c "$d/render.ppm" "$out/ref.png" ||
      fail "$dev: the KMS scanout is not the host's offscreen frame (within tolerance)"
    c "$d/render.ppm" "$out/wrong.png" --expect-differ || fail "$dev: a wrong frame matched"
    c "$d/run.ppm" "$d/replay/frame_000000.png" $exact ||
      fail "$dev: the run frame on KMS is not the guest's offscreen replay frame"
    c "$d/run.ppm" "$out/ref-run.png" || fail "$dev: the run frame on KMS is not the host's"
  }
  c "$d/console-after.ppm" "$d/console-before.ppm" --level 0 --max-fraction 0.01 --max-mean 5 ||
    fail "$dev: the console is not back after SIGTERM"
  c "$d/console-after.ppm" "$out/ref.png" --expect-differ || fail "$dev: the terrain is still shown"

  frames=$(sed -n 's/^  "frames": \([0-9]*\).*/\1/p' "$d/run.json")
  misses=$(sed -n 's/.*"deadline_misses": \([0-9]*\).*/\1/p' "$d/run.json")
  slowest=$(sed -n 's/.*"frame_ms_max": \([0-9.]*\).*/\1/p' "$d/run.json")
  if [ -z "$frames" ] || [ -z "$misses" ]; then fail "$dev: no frames/deadline_misses in run.json"; fi
  [ "$frames" -gt 0 ] || fail "$dev: run drew no frames"
  # Misses are counted and reported, not required to be 0: under TCG a frame
  # costs 100-200 ms (more when the host is busy) and the first frames also
  # compile shaders. What the display path owes: at least one frame on time,
  # one flip per frame, and flips that take a small part of the period.
  [ "$misses" -lt "$frames" ] || fail "$dev: every frame missed its deadline ($misses of $frames)"
  flips=$(sed -n 's/^kms: restored CRTC.*; \([0-9]*\) flips, flip time mean \([0-9.]*\) ms, max \([0-9.]*\) ms.*/\1 flips, mean \2 ms, max \3 ms/p' "$d/run.log")
  flip_n=${flips%% *}; flip_mean=$(echo "$flips" | sed 's/.*mean \([0-9.]*\) ms.*/\1/')
  # one flip per presented frame: the loop's frames plus its warm-up frame
  # (live.c presents a lamp-test frame before the schedule starts)
  if [ -z "$flip_n" ] || [ "$flip_n" -lt "$frames" ] || [ "$flip_n" -gt $((frames + 2)) ]; then
    fail "$dev: $flip_n flips for $frames frames"
  fi
  awk -v m="$flip_mean" -v p="$period_ms" 'BEGIN { exit !(m < p / 5) }' ||
    fail "$dev: mean flip time $flip_mean ms is not small against the $period_ms ms period"
  first=$(sed -n 's/^kms: first frame on screen \([0-9.]*\) ms after open.*/\1/p' "$d/render.log")
  boot=$(sed -n 's/^guest-kms: render: start at [0-9.]* s, frame shown by \([0-9.]*\) s.*/\1/p' "$d/vm.txt")
  {
    echo "$dev: boot to first terrain frame: ${boot} s uptime (host: $(cat "$d/host-first-frame-s.txt") s from qemu start); display open to first flip ${first} ms"
    echo "$dev: run at ${period_ms} ms: $frames frames, $misses deadline misses (slowest frame ${slowest} ms); flips: $flips"
    sed -n 's/^qmp-screendump: .*\/\([a-z-]*\.ppm\) in \(.*\)/screendump \1: \2/p' "$d/dumps.txt" | sed "s/^/$dev: /"
    sed -n 's/^compare-image: .*\/\([a-z0-9_-]*\.[a-z]*\) vs .*\/\([a-z0-9_-]*\.[a-z]*\): [0-9x]*, \(.*\)/\1 vs \2: \3/p' "$d/compare.txt" | sed "s/^/$dev: /"
  } >> "$summary"
done
echo "----- kms-test summary"
cat "$summary"
echo "kms-test: ok"
