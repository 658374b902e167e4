#!/bin/sh
# Runs INSIDE the test VM and proves that vcan + can-utils, AF_CAN sockets,
# and gpio-sim + libgpiod tools work there:
#   tests/vm/run-vm.sh "tests/vm/guest-smoke.sh [CAN_SOCKET_CHECK_BINARY]"
# (a C compiler in the host root is needed only when no binary is given).
# Exits non-zero with a message on the first failure.
set -u
here=$(cd "$(dirname "$0")" && pwd)
fail() { echo "guest-smoke: FAIL: $*" >&2; exit 1; }
ok() { echo "guest-smoke: ok: $*"; }
[ "${FT_VM:-}" = 1 ] || fail "not inside the test VM (run it with tests/vm/run-vm.sh)"
for c in candump cansend canplayer gpiodetect gpioinfo gpiofind gpioget gpioset gpiomon timeout; do
  command -v "$c" >/dev/null 2>&1 || fail "'$c' not found"
done
t=$(mktemp -d /tmp/smoke.XXXXXX)
out=${FT_VM_OUT:-$t}

# ---- CAN: cansend + canplayer onto vcan0, candump -L counts them all ----
# canplayer's log format needs exactly 6 decimal places in the timestamp.
cat > "$t/replay.log" <<'EOF'
(1700000000.000000) vcan0 100#0001
(1700000000.005000) vcan0 101#0102
(1700000000.010000) vcan0 102#010203
(1700000000.015000) vcan0 103#
(1700000000.020000) vcan0 12345678#DEADBEEF
(1700000000.025000) vcan0 104#R
(1700000000.030000) vcan0 105#1122334455667788
(1700000000.035000) vcan0 106#AA
EOF
n_send=4
n_replay=$(wc -l < "$t/replay.log")
want=$((n_send + n_replay))
timeout 20 candump -L -n "$want" vcan0 > "$t/dump.log" 2> "$t/candump.err" &
dump_pid=$!
i=0  # wait until candump's socket is bound (an rx_all receiver on vcan0)
until grep -Eq '^ +vcan0 +0+ +0+ ' /proc/net/can/rcvlist_all; do
  i=$((i + 1)); [ "$i" -lt 100 ] || fail "candump never bound to vcan0: $(cat "$t/candump.err")"
  sleep 0.1
done
cansend vcan0 123#DEADBEEF || fail "cansend 123#DEADBEEF"
cansend vcan0 456#01 || fail "cansend 456#01"
cansend vcan0 1F334455#1122334455667788 || fail "cansend extended id"
cansend vcan0 7FF# || fail "cansend 7FF#"
canplayer -I "$t/replay.log" || fail "canplayer -I replay.log"
wait "$dump_pid"
drc=$?
cp "$t/dump.log" "$out/smoke-candump.log" 2>/dev/null
got=$(wc -l < "$t/dump.log")
[ "$drc" -eq 0 ] || fail "candump -n $want exited $drc (saw $got frames; stderr: $(cat "$t/candump.err"))"
[ "$got" -eq "$want" ] || fail "candump saw $got frames, want $want"
for f in 123#DEADBEEF 456#01 1F334455#1122334455667788 7FF#; do
  grep -q " vcan0 $f\$" "$t/dump.log" || fail "cansend frame $f not in candump output"
done
# every replayed frame, in order, with the 6-decimal log format preserved
sed 's/^([0-9.]*) //' "$t/replay.log" > "$t/want.txt"
grep -E '^\([0-9]+\.[0-9]{6}\) ' "$t/dump.log" | sed 's/^([0-9.]*) //' | tail -n "$n_replay" > "$t/got.txt"
cmp -s "$t/want.txt" "$t/got.txt" || { diff "$t/want.txt" "$t/got.txt" >&2; fail "replayed frames differ"; }
ok "candump -L saw all $got frames ($n_send cansend + $n_replay canplayer)"

# ---- AF_CAN socket from a host-built C program ----
# $1: can-socket-check built on the host (CMake target vm_can_socket_check);
# without it, build it here with the host's cc (about 6 s under TCG).
check=${1:-}
if [ -z "$check" ]; then
  check=$t/can-socket-check
  cc -std=c11 -Wall -Wextra -Werror -o "$check" "$here/can-socket-check.c" ||
    fail "building can-socket-check.c"
fi
[ -x "$check" ] || fail "$check is not an executable"
"$check" vcan0 || fail "AF_CAN raw socket on vcan0"
"$check" vcan1 || fail "AF_CAN raw socket on vcan1"

# ---- gpio-sim + libgpiod 1.6 tools ----
chip=${FT_GPIO_CHIP:-}
sim=${FT_GPIO_SIM_SYSFS:-}
[ -n "$chip" ] && [ -d "$sim" ] || fail "FT_GPIO_CHIP/FT_GPIO_SIM_SYSFS not set by the VM init"
gpiodetect > "$t/detect.txt" || fail "gpiodetect"
grep -q "^$chip \[ft-gpio-sim\] (8 lines)" "$t/detect.txt" ||
  fail "gpiodetect does not show $chip [ft-gpio-sim] (8 lines): $(cat "$t/detect.txt")"
ok "gpiodetect: $(cat "$t/detect.txt")"
[ "$(gpiofind ft-line5)" = "$chip 5" ] || fail "gpiofind ft-line5 gave '$(gpiofind ft-line5)'"
gpioinfo "$chip" | grep -Eq 'line +7: +"ft-line7"' || fail "gpioinfo lacks named line 7: $(gpioinfo "$chip")"

# input: pull set through gpio-sim's sysfs (values "pull-up"/"pull-down")
echo pull-up > "$sim/sim_gpio0/pull" || fail "set sim_gpio0 pull-up"
[ "$(gpioget "$chip" 0)" = 1 ] || fail "gpioget $chip 0 after pull-up: $(gpioget "$chip" 0)"
echo pull-down > "$sim/sim_gpio0/pull" || fail "set sim_gpio0 pull-down"
[ "$(gpioget "$chip" 0)" = 0 ] || fail "gpioget $chip 0 after pull-down: $(gpioget "$chip" 0)"
ok "gpioget follows the simulated pull (1 then 0)"

# edge: gpiomon waits for one rising edge on line 1
echo pull-down > "$sim/sim_gpio1/pull"
timeout 20 gpiomon --num-events=1 --rising-edge "$chip" 1 > "$t/mon.txt" 2>&1 &
mon_pid=$!
i=0  # wait until gpiomon holds the line (gpioinfo shows it "used")
until gpioinfo "$chip" | grep -E 'line +1:' | grep -q '"gpiomon"'; do
  i=$((i + 1)); [ "$i" -lt 100 ] || fail "gpiomon never requested line 1"
  sleep 0.1
done
echo pull-up > "$sim/sim_gpio1/pull" || fail "set sim_gpio1 pull-up"
wait "$mon_pid" || fail "gpiomon exited $? without an edge: $(cat "$t/mon.txt")"
grep -q 'RISING EDGE offset: 1' "$t/mon.txt" || fail "gpiomon output lacks the rising edge: $(cat "$t/mon.txt")"
ok "gpiomon saw: $(head -n 1 "$t/mon.txt")"

# output: gpioset drives line 2; the simulator's value follows
gpioset --mode=signal "$chip" 2=1 &
set_pid=$!
i=0
until [ "$(cat "$sim/sim_gpio2/value")" = 1 ]; do
  i=$((i + 1)); [ "$i" -lt 100 ] || { kill "$set_pid"; fail "sim_gpio2/value never became 1 under gpioset 2=1"; }
  sleep 0.1
done
gpioinfo "$chip" | grep -E 'line +2:' | grep -q 'output' || { kill "$set_pid"; fail "line 2 not an output under gpioset"; }
kill "$set_pid"; wait "$set_pid" 2>/dev/null
# released: gpio-sim puts the line back to its pull (pull-down by default)
[ "$(cat "$sim/sim_gpio2/value")" = 0 ] || fail "sim_gpio2/value not back to 0 after gpioset exited"
ok "gpioset drives an output line (sim_gpio2/value 1 while held, 0 after release)"

rm -rf "$t"
echo "guest-smoke: all checks passed"
