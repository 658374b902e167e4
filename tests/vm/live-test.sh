#!/bin/sh
# The live pose path on real vcan and GPIO lines, in one VM boot:
#   live-test.sh BUILD_DIR OUT_DIR COMPARE_LIVE_BINARY HB_SAMPLER_BINARY
# 1. fixterrain-flightgen writes a 12 s orbit as a CANaerospace candump log
#    with faults: a NaN pitch at 3 s, every 10th attitude frame dropped, a
#    stalled bus from 8 to 9 s, and the GPS velocity output stopping at 11 s
#    (the position goes on; the scene requires the velocity);
# 2. in the VM, `fixterrain run` draws from vcan0 while canplayer replays the
#    log; GPIO line 0 freezes the pose for 1 s, line 1 holds the annunciation
#    test for 0.5 s, line 7 is the heartbeat; then SIGTERM;
# 3. on the host, `fixterrain replay` of the same log, and compare-live checks
#    the live poses against it, the annunciation timing and recovery, freeze
#    and test; this script checks the heartbeat and the deadline misses.
set -eu
build=$(cd "$1" && pwd); out=$2; compare=$3; sampler=$4
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$out"; out=$(cd "$out" && pwd)
rm -f "$out"/live.* "$out"/hb.* "$out"/replay.*
fail() { echo "live-test: FAIL: $*" >&2; exit 1; }
period_ms=200
"$build/fixterrain-flightgen" --path orbit --centre 46.509,8.013 --radius 2000 --alt 2600 \
  --duration 12 --nan-at 3 --drop-every 10 --stall 8,9 --velocity-stop 11 \
  --out "$out/flight.log" --quiet
"$build/fixterrain-flightgen" --path orbit --centre 46.509,8.013 --radius 2000 --alt 2600 \
  --duration 12 --iface vcan1 --out "$out/flight_backup.log" --quiet
log_t0=$(head -n 1 "$out/flight.log" | sed 's/^(\([0-9.]*\)).*/\1/')
scene() { # $1 period_ms, $2 pose_input.velocity_required
  cat <<EOS
[scene]
name = vm-live
method = brute
backend = egl-gles3
[view]
width_px = 48
height_px = 36
[terrain]
dem =
synth_side = 65
synth_anchor_lat_deg = 46.5
synth_anchor_lon_deg = 8.0
[frame]
period_ms = $1
[pose_input]
velocity_required = $2
[can]
interface = vcan0
backup_interface = vcan1
[gpio]
chip = ft-gpio-sim
freeze_line = 0
test_line = 1
night_line = 3
heartbeat_line = 7
debounce_ms = 10
EOS
}
scene "$period_ms" 1 > "$out/live.ini"
{ scene "$period_ms" 0; printf 'source_line = 2\n[can]\nfailover_ms = 200\n'; } > "$out/failover.ini"
scene 5 1 > "$out/replay.ini"

FT_VM_TIMEOUT=${FT_VM_TIMEOUT:-300} "$here/run-vm.sh" \
  "tests/vm/guest-live.sh $build/fixterrain $out/flight.log $out/live.ini $sampler $out/flight_backup.log $out/failover.ini" "$out"

"$build/fixterrain" replay --log "$out/flight.log" --scene "$out/replay.ini" \
  --poses "$out/replay.csv" --quiet || fail "host replay"
"$compare" "$out/live.csv" "$out/live.json" "$out/replay.csv" "$log_t0" 8 9 \
  "$period_ms" 100 11 500 || fail "live poses against the replay"

# no missed frames; every presented frame toggled the heartbeat
frames=$(sed -n 's/^  "frames": \([0-9]*\).*/\1/p' "$out/live.json")
misses=$(sed -n 's/.*"deadline_misses": \([0-9]*\).*/\1/p' "$out/live.json")
toggles=$(sed -n 's/.*"heartbeat_toggles": \([0-9]*\).*/\1/p' "$out/live.json")
echo "live-test: $frames frames, $misses deadline misses, $toggles heartbeat toggles"
[ "$misses" -eq 0 ] || fail "$misses deadline misses at ${period_ms} ms frames"
[ "$toggles" -eq "$frames" ] || fail "heartbeat toggled $toggles times for $frames frames"
grep -q '"can_dropped": \[0, 0\]' "$out/live.json" || fail "the kernel dropped CAN frames"
# the night line was held 0.5 s (guest's sleep): the frames drawn in the
# night palette are those of its debounced span, switched on the next frame
night=$(sed -n 's/.*"frames_night": \([0-9]*\).*/\1/p' "$out/live.json")
echo "live-test: $night frames in the night palette (line held 0.5 s at ${period_ms} ms frames)"
awk -v n="$night" -v p="$period_ms" 'BEGIN { want = 500 / p; exit !(n >= 1 && n <= want + 4) }' \
  || fail "night palette on $night frames for a 0.5 s pulse"
# the position came from the velocity frames on vcan0: predicted on most
# frames, never snapped (the flight has no GPS jump), no velocity rejected
pos_pred=$(sed -n 's/.*"position": {"frames_predicted": \([0-9]*\).*/\1/p' "$out/live.json")
snaps=$(sed -n 's/.*"snaps": \([0-9]*\).*/\1/p' "$out/live.json")
vel_rej=$(sed -n 's/.*"velocity_rejects": \([0-9]*\).*/\1/p' "$out/live.json")
echo "live-test: position predicted on $pos_pred of $frames frames, $snaps snaps, $vel_rej velocity rejects"
[ "$snaps" -eq 0 ] && [ "$vel_rej" -eq 0 ] || fail "$snaps snaps, $vel_rej velocity rejects"
[ "$pos_pred" -ge $((frames / 3)) ] || fail "position predicted on only $pos_pred of $frames frames"
grep -q '"velocity_required": 1' "$out/live.json" || fail "the scene's velocity requirement"
# every frame's pose row was written (by the deferred jobs, or at the end)
rows=$(($(wc -l < "$out/live.csv") - 1))
jobs=$(sed -n 's/.*"jobs": {"run": \([0-9]*\).*/\1/p' "$out/live.json")
[ "$rows" -eq "$frames" ] || fail "$rows pose rows for $frames frames"
[ "$jobs" -eq "$frames" ] || fail "$jobs deferred row writes for $frames frames"
# the line itself, sampled every 2 ms in the guest: it changes once per
# frame while the renderer runs and stays put after it exits
read -r alive_s changes dead_s dead_changes < "$out/hb.txt"
echo "live-test: heartbeat line: $changes changes in $alive_s s alive, $dead_changes in $dead_s s after exit"
awk -v a="$alive_s" -v c="$changes" -v d="$dead_s" -v dc="$dead_changes" -v p="$period_ms" \
  'BEGIN { rate = c / a; want = 1000 / p; exit !(rate > 0.8 * want && rate < 1.2 * want && dc == 0 && d >= 0.5) }' \
  || fail "heartbeat line: not one change per frame while running, or changes after exit"
# phase 2: the primary stalls for 1 s and the backup does not. The source
# line accounts for 2 switches; failover and failback for 2 more. With the
# standby port's newest frames fed at the switch, the stall shows at most the
# frames between the attitude timeout (100 ms) and the failover (200 ms):
# <= 2 annunciated frames while the logs play (5 without a backup).
switches=$(sed -n 's/.*"source_switches": \([0-9]*\).*/\1/p' "$out/live2.json")
backup=$(sed -n 's/.*"frames_backup": \([0-9]*\).*/\1/p' "$out/live2.json")
misses2=$(sed -n 's/.*"deadline_misses": \([0-9]*\).*/\1/p' "$out/live2.json")
late_ann=$(awk -F, 'NR > 1 { if ($9 == 0) { if (good) n += pending; pending = 0; good = 1 } else if (good) pending++ }
                    END { print n + 0 }' "$out/live2.csv")
echo "live-test: failover: $switches source switches, $backup frames from the backup, $late_ann annunciated frames while data flowed, $misses2 deadline misses"
[ "$switches" -ge 4 ] || fail "expected >= 4 source switches (source line on/off, failover, failback)"
[ "$late_ann" -le 2 ] || fail "the backup did not bridge the primary's stall ($late_ann annunciated frames)"
[ "$misses2" -eq 0 ] || fail "phase 2: $misses2 deadline misses"
echo "live-test: ok"
