#!/bin/sh
# /init of the test VM's initramfs (busybox ash, PID 1). Copied in by
# mkinitramfs.sh. Kernel command line parameters it reads (from /proc/cmdline):
#   ft.cmd="CMD"   command run as `chroot /host /bin/sh -c CMD` (no `"` in it)
#   ft.cwd=DIR     working directory for CMD inside the chroot (default /)
#   ft.out=DIR     host directory shared writable (9p tag ftout), mounted at
#                  the same path DIR inside the chroot; exported as FT_VM_OUT
#   ft.display=NAME  bochs | virtio: load that display device's DRM modules
#                  (run-vm.sh FT_VM_DISPLAY) and wait for /dev/dri/card0;
#                  exported as FT_VM_DISPLAY (and FT_DRM_CARD=/dev/dri/card0)
# Environment for CMD: FT_VM=1, FT_VM_OUT, FT_CAN_IFS="vcan0 vcan1",
# FT_GPIO_CHIP (e.g. gpiochip0), FT_GPIO_SIM_SYSFS (dir holding sim_gpioN/pull
# and sim_gpioN/value), FT_GPIO_LINES (8 line names, offset order).
# Last console line: FT-VM-EXIT=<status of CMD>; 125 = VM setup failed.
/bin/busybox mkdir -p /proc /sys /dev /tmp /host /usr/bin /usr/sbin /sbin
/bin/busybox --install -s
export PATH=/sbin:/usr/sbin:/bin:/usr/bin

mount -t proc proc /proc
mount -t sysfs sysfs /sys
mount -t devtmpfs devtmpfs /dev 2>/dev/null
exec </dev/console >/dev/console 2>&1

finish() {
  echo "FT-VM-EXIT=$1"
  sync
  poweroff -f
  sleep 10
}
fail() {
  echo "ft-vm-init: ERROR: $*"
  finish 125
}
step() { "$@" || fail "failed: $*"; }
say() { read -r up _ < /proc/uptime; echo "ft-vm-init: [$up] $*"; }

cmdline=$(cat /proc/cmdline)
param() { # param NAME: value of NAME="..." or NAME=word from the cmdline
  v=$(printf '%s\n' " $cmdline" | sed -n "s/.* $1=\"\([^\"]*\)\".*/\1/p")
  [ -n "$v" ] || v=$(printf '%s\n' " $cmdline" | sed -n "s/.* $1=\([^ \"]*\).*/\1/p")
  printf '%s' "$v"
}
FT_CMD=$(param ft.cmd)
FT_CWD=$(param ft.cwd)
FT_OUT=$(param ft.out)
FT_DISPLAY=$(param ft.display)
[ -n "$FT_CMD" ] || fail "no ft.cmd= on the kernel command line"

say "loading modules"
while read -r ko; do
  insmod "/lib/ft-modules/$ko" || fail "insmod $ko"
done < /lib/ft-modules/order

if [ -n "$FT_DISPLAY" ]; then
  say "display $FT_DISPLAY: DRM modules"
  [ -f "/lib/ft-modules/display-$FT_DISPLAY.order" ] ||
    fail "no modules for display '$FT_DISPLAY' (bochs, virtio)"
  while read -r ko; do
    insmod "/lib/ft-modules/$ko" || fail "insmod $ko"
  done < "/lib/ft-modules/display-$FT_DISPLAY.order"
  n=0
  until [ -e /dev/dri/card0 ]; do
    n=$((n + 1)); [ "$n" -le 50 ] || fail "/dev/dri/card0 did not appear"
    sleep 0.1
  done
  say "display $FT_DISPLAY: /dev/dri/card0"
fi

mkdir -p /sys/kernel/config
grep -q ' /sys/kernel/config ' /proc/mounts ||
  step mount -t configfs configfs /sys/kernel/config

step mount -t 9p -o ro,trans=virtio,version=9p2000.L,cache=loose,msize=262144 hostroot /host
[ -x /host/bin/sh ] || fail "host root over 9p has no /bin/sh"
step mount -t proc proc /host/proc
step mount -o bind /sys /host/sys
grep -q ' /host/sys/kernel/config ' /proc/mounts ||
  mount -o bind /sys/kernel/config /host/sys/kernel/config 2>/dev/null
step mount -o bind /dev /host/dev
# /tmp: the host's /tmp (read-only, so build trees under /tmp stay visible)
# under a writable tmpfs layer; plain tmpfs if overlayfs refuses 9p.
mkdir -p /ovl && mount -t tmpfs -o mode=755 tmpfs /ovl && mkdir -p /ovl/up /ovl/work &&
  chmod 1777 /ovl/up &&
  mount -t overlay -o lowerdir=/host/tmp,upperdir=/ovl/up,workdir=/ovl/work overlay /host/tmp ||
  { echo "ft-vm-init: overlay on /tmp failed, using an empty tmpfs"
    mount -t tmpfs -o mode=1777 tmpfs /host/tmp || fail "tmpfs on /host/tmp"; }
mount -t tmpfs tmpfs /host/run 2>/dev/null
if [ -n "$FT_OUT" ]; then
  mkdir -p "/host$FT_OUT" 2>/dev/null
  [ -d "/host$FT_OUT" ] || fail "out dir $FT_OUT does not exist in the guest view"
  step mount -t 9p -o trans=virtio,version=9p2000.L,msize=262144 ftout "/host$FT_OUT"
fi

step ip link set lo up
say "CAN"
for i in vcan0 vcan1; do
  if ! ip link add dev "$i" type vcan 2>/dev/null; then
    # busybox ip may lack "type vcan": use the host's iproute2.
    chroot /host ip link add dev "$i" type vcan || fail "ip link add $i type vcan"
  fi
  step ip link set up "$i"
done

say "gpio-sim"
g=/sys/kernel/config/gpio-sim/ft
step mkdir "$g" "$g/bank0"
echo ft-gpio-sim > "$g/bank0/label" || fail "gpio-sim label"
echo 8 > "$g/bank0/num_lines" || fail "gpio-sim num_lines"
FT_GPIO_LINES=
for n in 0 1 2 3 4 5 6 7; do
  step mkdir "$g/bank0/line$n"
  echo "ft-line$n" > "$g/bank0/line$n/name" || fail "gpio-sim line$n name"
  FT_GPIO_LINES="$FT_GPIO_LINES ft-line$n"
done
echo 1 > "$g/live" || fail "gpio-sim live"
FT_GPIO_CHIP=$(cat "$g/bank0/chip_name")
FT_GPIO_SIM_SYSFS=/sys/devices/platform/$(cat "$g/dev_name")/$FT_GPIO_CHIP
[ -e "/dev/$FT_GPIO_CHIP" ] || fail "/dev/$FT_GPIO_CHIP missing"
[ -d "$FT_GPIO_SIM_SYSFS/sim_gpio0" ] || fail "$FT_GPIO_SIM_SYSFS/sim_gpio0 missing"

export FT_VM=1 FT_VM_OUT="$FT_OUT" FT_CAN_IFS="vcan0 vcan1"
[ -z "$FT_DISPLAY" ] || export FT_VM_DISPLAY="$FT_DISPLAY" FT_DRM_CARD=/dev/dri/card0
export FT_GPIO_CHIP FT_GPIO_SIM_SYSFS FT_GPIO_LINES="${FT_GPIO_LINES# }"
export HOME=/tmp TERM=dumb LANG=C.UTF-8
export PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin
say "$FT_GPIO_CHIP ($FT_GPIO_SIM_SYSFS), vcan0 vcan1; running: $FT_CMD"
echo "FT-VM-BEGIN"
chroot /host /bin/sh -c 'cd "$1" && shift && exec /bin/sh -c "$1"' ft-vm "${FT_CWD:-/}" "$FT_CMD"
rc=$?
echo "FT-VM-END"
say "command exited $rc"
if [ -n "$FT_OUT" ]; then sync; umount "/host$FT_OUT" 2>/dev/null; fi
finish "$rc"
