#!/bin/sh
# Runs CMD inside the test VM and returns its exit status.
#   tests/vm/run-vm.sh CMD [OUTDIR]
# The VM: qemu-system-x86_64 (KVM if the CPU has vmx/svm and /dev/kvm works,
# else TCG with -cpu max,-avx,-avx2), Debian's kernel (/boot/vmlinuz-<ver>)
# and the initramfs of mkinitramfs.sh, which mounts the host's / read-only
# over 9p and runs CMD as `chroot /host /bin/sh -c CMD` in the current
# directory, with vcan0/vcan1 up and an 8-line gpio-sim chip (see init.sh for
# the FT_* environment CMD gets).
# In the guest, /tmp is an empty tmpfs (the host's /tmp is hidden), /proc,
# /sys, /dev are the guest's, and everything else is the host's, read-only,
# except OUTDIR: it is shared writable and appears at the same path, so CMD
# writes results there (also in $FT_VM_OUT). Default OUTDIR: a new directory
# under $FT_VM_DIR. OUTDIR/console.log is the serial console.
# CMD and OUTDIR/cwd must not contain a double quote or a newline (they go on
# the kernel command line), and OUTDIR/cwd no whitespace.
# Environment:
#   FT_VM_DIR      where gpio-sim and the initramfs are built/cached
#                  (default: <repo>/build/vm)
#   FT_VM_TIMEOUT  seconds before qemu is killed (default 300)
#   FT_VM_ACCEL    tcg | kvm (default: kvm only if usable, see above)
#   FT_VM_KVER     guest kernel version (default: newest installed)
#   FT_VM_DISPLAY  bochs | virtio: add a display device (-device VGA,edid=on or
#                  -device virtio-gpu-pci, preferred mode FT_VM_DISPLAY_SIZE,
#                  default 1024x768), its DRM modules in the guest
#                  (/dev/dri/card0) and a QMP socket OUTDIR/qmp.sock from which
#                  the host can take a `screendump` of the scanout. Unset
#                  (default): no display device, no QMP, as before.
# Missing qemu, kernel, headers or busybox is an error (exit 1), never a skip.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
. "$here/common.sh"
[ $# -ge 1 ] && [ $# -le 2 ] || { echo "usage: $0 CMD [OUTDIR]" >&2; exit 2; }
cmd=$1
vmdir=${FT_VM_DIR:-$(cd "$here/../.." && pwd)/build/vm}
timeout_s=${FT_VM_TIMEOUT:-300}
ft_vm_need_cmd qemu-system-x86_64 timeout
qemu="qemu-system-x86_64"

case $cmd in *'"'*|*'
'*) ft_vm_die "CMD must not contain a double quote or newline: $cmd" ;; esac

mkdir -p "$vmdir"
if command -v flock >/dev/null 2>&1; then  # VMs started in parallel share vmdir
  flock "$vmdir/.build-lock" "$here/mkinitramfs.sh" "$vmdir" >&2
else
  "$here/mkinitramfs.sh" "$vmdir" >&2
fi
kernel=$(cat "$vmdir/kernel")
initrd=$vmdir/initramfs.cpio.gz
[ -f "$kernel" ] || ft_vm_die "kernel image $kernel missing"
[ -r "$kernel" ] || ft_vm_die "kernel image $kernel not readable"

if [ $# -ge 2 ]; then
  mkdir -p "$2"
  out=$(cd "$2" && pwd)
else
  mkdir -p "$vmdir/runs"
  out=$(mktemp -d "$vmdir/runs/run.XXXXXX")
fi
cwd=$(pwd)
for p in "$out" "$cwd"; do
  case $p in *[[:space:]\"]*) ft_vm_die "path with whitespace or quote not supported: '$p'" ;; esac
done
log=$out/console.log
rm -f "$log"

accel=${FT_VM_ACCEL:-}
if [ -z "$accel" ]; then
  accel=tcg
  if grep -Eqw 'vmx|svm' /proc/cpuinfo && [ -w /dev/kvm ]; then accel=kvm; fi
fi
case $accel in
  kvm) accel_opts="-accel kvm -cpu host" ;;
  tcg) accel_opts="-accel tcg -cpu max,-avx,-avx2" ;;
  *) ft_vm_die "FT_VM_ACCEL must be tcg or kvm, not '$accel'" ;;
esac

append="console=ttyS0 panic=-1 loglevel=4 ft.cmd=\"$cmd\" ft.cwd=$cwd ft.out=$out"
display_opts=
case ${FT_VM_DISPLAY:-} in
  '') ;;
  bochs|virtio)
    size=${FT_VM_DISPLAY_SIZE:-1024x768}
    xres=${size%x*}; yres=${size#*x}
    case "$xres$yres" in *[!0-9]*|'') ft_vm_die "FT_VM_DISPLAY_SIZE must be WxH, not '$size'" ;; esac
    if [ "$FT_VM_DISPLAY" = bochs ]; then dev="VGA,edid=on,xres=$xres,yres=$yres"
    else dev="virtio-gpu-pci,edid=on,xres=$xres,yres=$yres"; fi
    qmp=$out/qmp.sock
    [ ${#qmp} -lt 100 ] || ft_vm_die "QMP socket path too long for a unix socket: $qmp"
    rm -f "$qmp"
    display_opts="-device $dev -qmp unix:$qmp,server=on,wait=off"
    append="$append ft.display=$FT_VM_DISPLAY" ;;
  *) ft_vm_die "FT_VM_DISPLAY must be bochs or virtio, not '$FT_VM_DISPLAY'" ;;
esac
echo "vm: $accel, $(basename "$kernel"), timeout ${timeout_s}s, out $out${FT_VM_DISPLAY:+, display $FT_VM_DISPLAY}" >&2
echo "vm: running: $cmd" >&2
# One retry, only when qemu itself died of a signal (exit > 128, not the
# timeout's kill) before the guest started the command (no FT-VM-BEGIN on the
# console): an emulator crash on the host, not a result of the command. Seen
# once: qemu with the bochs display segfaulted in the BIOS, 4 s in. Any
# other failure, or a second crash, fails the run.
t0=$(date +%s.%N)
attempt=1
while :; do
  [ -z "${qmp:-}" ] || rm -f "$qmp"
  set +e
  # shellcheck disable=SC2086
  timeout -k 5 "$timeout_s" "$qemu" $accel_opts -m 1024 -smp 2 \
    -nodefaults -nographic -no-reboot -no-user-config \
    -serial "file:$log" -monitor none $display_opts \
    -kernel "$kernel" -initrd "$initrd" -append "$append" \
    -virtfs local,path=/,mount_tag=hostroot,security_model=none,readonly=on,multidevs=remap \
    -virtfs "local,path=$out,mount_tag=ftout,security_model=none" \
    < /dev/null > "$out/qemu.log" 2>&1
  qrc=$?
  set -e
  if [ "$attempt" -eq 1 ] && [ "$qrc" -gt 128 ] && [ "$qrc" -ne 137 ] &&
     ! tr -d '\r' < "$log" 2>/dev/null | grep -q '^FT-VM-BEGIN$'; then
    echo "vm: qemu died (exit $qrc) before the guest started the command; retrying once" >&2
    cat "$out/qemu.log" >&2
    attempt=2
    continue
  fi
  break
done
t1=$(date +%s.%N)
secs=$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.1f", b - a }')

rc=$(tr -d '\r' < "$log" 2>/dev/null | sed -n 's/^FT-VM-EXIT=\([0-9][0-9]*\)$/\1/p' | tail -n 1)
# The command's own output (between the markers) always.
tr -d '\r' < "$log" 2>/dev/null | sed -n '/^FT-VM-BEGIN$/,/^FT-VM-END$/p' | sed '1d;$d'
why=
if [ "$qrc" -eq 124 ] || [ "$qrc" -eq 137 ]; then
  why="timed out after ${timeout_s}s (qemu killed)"
elif [ -z "$rc" ]; then
  why="no FT-VM-EXIT line on the console (qemu exit $qrc)"
elif [ "$rc" -eq 125 ]; then
  why="VM setup failed (FT-VM-EXIT=125)"
elif [ "$rc" -ne 0 ]; then
  why="command exited $rc"
fi
if [ -n "$why" ]; then
  echo "vm: FAILED: $why; boot-to-poweroff ${secs}s" >&2
  echo "----- qemu output ($out/qemu.log) -----" >&2
  cat "$out/qemu.log" >&2
  echo "----- console log ($log) -----" >&2
  tr -d '\r' < "$log" >&2 2>/dev/null || echo "(no console log)" >&2
  echo "----- end of console log -----" >&2
  if [ -n "$rc" ] && [ "$rc" -ne 0 ]; then exit "$rc"; fi
  exit 1
fi
echo "vm: ok: command exited 0; boot-to-poweroff ${secs}s" >&2
exit 0
