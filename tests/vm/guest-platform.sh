#!/bin/sh
# Runs INSIDE the test VM: the platform CAN and GPIO code (platform/
# can_socketcan.c, platform/gpio_gpiod.c) on vcan0 and the gpio-sim chip,
# through tests/vm/platform-check.c (CMake target vm_platform_check):
#   tests/vm/run-vm.sh "tests/vm/guest-platform.sh PLATFORM_CHECK_BINARY"
# The program drives cansend/canplayer and the gpio-sim pulls itself, so the
# port under test stays open while the stimuli arrive. Its report goes to
# stdout and to $FT_VM_OUT/platform-check.txt.
set -u
fail() { echo "guest-platform: FAIL: $*" >&2; exit 1; }
[ "${FT_VM:-}" = 1 ] || fail "not inside the test VM (run it with tests/vm/run-vm.sh)"
check=${1:-}
[ -n "$check" ] && [ -x "$check" ] || fail "usage: $0 PLATFORM_CHECK_BINARY (got '$check')"
for c in cansend canplayer; do
  command -v "$c" >/dev/null 2>&1 || fail "'$c' not found (can-utils)"
done
ip link show vcan0 >/dev/null 2>&1 || fail "vcan0 missing"

# gpio-sim's sysfs directory: /sys/devices/platform/gpio-sim.N/gpiochipM
sim=${FT_GPIO_SIM_SYSFS:-}
if [ -z "$sim" ]; then
  for d in /sys/devices/platform/gpio-sim.*/gpiochip*; do [ -d "$d/sim_gpio7" ] && sim=$d; done
fi
[ -n "$sim" ] && [ -f "$sim/sim_gpio7/value" ] || fail "no gpio-sim sysfs directory with sim_gpio7 ($sim)"
case $sim in /sys/devices/platform/gpio-sim.*/gpiochip*) ;; *) fail "unexpected gpio-sim path $sim" ;; esac

t=$(mktemp -d /tmp/platform.XXXXXX) || fail "mktemp"
out=${FT_VM_OUT:-$t}
read -r up0 _ < /proc/uptime
# the chip by its label, as a scene's gpio.chip may name it
"$check" vcan0 ft-gpio-sim "$sim" "$t" > "$t/report.txt" 2>&1
rc=$?
read -r up1 _ < /proc/uptime
cat "$t/report.txt"
cp "$t/report.txt" "$out/platform-check.txt" 2>/dev/null
[ "$rc" -eq 0 ] || fail "platform-check exited $rc"
echo "guest-platform: all checks passed ($(awk -v a="$up0" -v b="$up1" 'BEGIN { printf "%.2f", b - a }') s in the guest)"
rm -rf "$t"
