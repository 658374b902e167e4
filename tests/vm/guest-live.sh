#!/bin/sh
# Runs INSIDE the test VM (tests/vm/live-test.sh starts it): the live renderer
# on vcan0 + gpio-sim while canplayer replays a generated flight, with GPIO
# freeze and annunciation-test pulses, a heartbeat sampler, and SIGTERM.
#   guest-live.sh FIXTERRAIN LOG SCENE HB_SAMPLER LOG_BACKUP SCENE_FAILOVER
# Phase 2 (same boot): the primary log on vcan0 stalls, the backup log on
# vcan1 does not; gpio source line 2 forces the backup for 1 s.
set -u
bin=$1; log=$2; scene=$3; sampler=$4; log_backup=$5; scene_failover=$6
out=${FT_VM_OUT:?run it with tests/vm/run-vm.sh}
fail() { echo "guest-live: FAIL: $*" >&2; exit 1; }
[ "${FT_VM:-}" = 1 ] || fail "not inside the test VM"
sim=${FT_GPIO_SIM_SYSFS:?no gpio-sim}
pull() { echo "$2" > "$sim/sim_gpio$1/pull" || fail "pull line $1 $2"; }
pull 0 pull-down; pull 1 pull-down; pull 2 pull-down

"$bin" run --scene "$scene" --poses "$out/live.csv" --stats "$out/live.json" \
  > "$out/run.log" 2>&1 &
pid=$!
# wait until init is done (it prints its first line then; the pose record
# only appears under its name when the run ends)
i=0
until grep -q "^fixterrain run:" "$out/run.log" 2>/dev/null; do
  i=$((i + 1)); [ "$i" -lt 1200 ] || fail "the renderer never started: $(cat "$out/run.log")"
  kill -0 "$pid" 2>/dev/null || fail "the renderer exited: $(cat "$out/run.log")"
  sleep 0.1
done
# the first presented frame toggles the heartbeat (after shader compilation,
# which takes seconds in the emulated VM): start the bus only then
i=0
until [ "$(cat "$sim/sim_gpio7/value")" = 1 ]; do
  i=$((i + 1)); [ "$i" -lt 1200 ] || fail "no heartbeat from the renderer"
  sleep 0.05
done
sleep 0.5

# heartbeat sampler (a C program: a shell loop is too slow under emulation)
"$sampler" "$sim/sim_gpio7/value" "$pid" "$out/hb.txt" &
hb=$!

canplayer -I "$log" &
player=$!
# the GPIO pulses stay well clear of the stall (8..9 s of log time)
sleep 1.5; pull 0 pull-up      # freeze for 1 s
sleep 1;   pull 0 pull-down
sleep 0.5; pull 1 pull-up      # annunciation test for 0.5 s
sleep 0.5; pull 1 pull-down
sleep 0.5; pull 3 pull-up      # night palette for 0.5 s
sleep 0.5; pull 3 pull-down
wait "$player" || fail "canplayer failed"
sleep 1
kill -TERM "$pid"
t0=$(cut -d' ' -f1 /proc/uptime)
wait "$pid"; rc=$?
t1=$(cut -d' ' -f1 /proc/uptime)
echo "renderer exit status $rc after SIGTERM ($t0 -> $t1 s)" | tee "$out/term.txt"
wait "$hb" || fail "heartbeat sampler"
cat "$out/run.log"
[ "$rc" -eq 0 ] || fail "renderer exit status $rc"

# ---- phase 2: failover to the backup interface, and the source line ----
"$bin" run --scene "$scene_failover" --poses "$out/live2.csv" --stats "$out/live2.json" \
  > "$out/run2.log" 2>&1 &
pid=$!
i=0
until grep -q "^fixterrain run:" "$out/run2.log" 2>/dev/null; do
  i=$((i + 1)); [ "$i" -lt 1200 ] || fail "phase 2: the renderer never started"
  kill -0 "$pid" 2>/dev/null || fail "phase 2: the renderer exited: $(cat "$out/run2.log")"
  sleep 0.1
done
sleep 2
canplayer -I "$log" &
p1=$!
canplayer -I "$log_backup" &
p2=$!
sleep 3;   pull 2 pull-up      # source select: the backup for 1 s
sleep 1;   pull 2 pull-down
wait "$p1" || fail "canplayer (primary)"
wait "$p2" || fail "canplayer (backup)"
sleep 0.5
kill -TERM "$pid"
wait "$pid"; rc=$?
cat "$out/run2.log"
[ "$rc" -eq 0 ] || fail "phase 2: renderer exit status $rc"
echo "guest-live: done"
