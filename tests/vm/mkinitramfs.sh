#!/bin/sh
# Builds the test VM's initramfs: busybox-static, tests/vm/init.sh as /init,
# and the modules it needs (virtio-pci + 9p stack, configfs, CAN + vcan,
# out-of-tree irq_sim + gpio-sim) from Debian's kernel, plus the DRM modules
# of the display devices (bochs, virtio-gpu), loaded only on request.
#   tests/vm/mkinitramfs.sh OUTDIR
# Writes OUTDIR/initramfs.cpio.gz and OUTDIR/kernel (the matching
# /boot/vmlinuz-<ver> path, for run-vm.sh). Builds gpio-sim into OUTDIR first
# (build-gpio-sim.sh, cached). Does nothing when OUTDIR/initramfs.stamp
# matches the kernel, busybox, gpio-sim and these scripts.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
. "$here/common.sh"
[ $# -eq 1 ] || { echo "usage: $0 OUTDIR" >&2; exit 2; }
mkdir -p "$1"
out=$(cd "$1" && pwd)
ft_vm_need_kver
ft_vm_need_cmd modprobe cpio gzip find
busybox=
for b in /bin/busybox /usr/bin/busybox; do [ -x "$b" ] && busybox=$b && break; done
[ -n "$busybox" ] || ft_vm_die "busybox not found (install busybox-static: tools/install-deps.sh vm)"
ldd "$busybox" 2>&1 | grep -Eq 'not a dynamic|statically linked' ||
  ft_vm_die "$busybox is not statically linked (install busybox-static)"

"$here/build-gpio-sim.sh" "$out"

stamp="kver=$KVER modules=$(stat -c %Y "/lib/modules/$KVER/modules.dep")"
stamp="$stamp busybox=$(cksum < "$busybox" | cut -d' ' -f1)"
stamp="$stamp gpio=$(cksum < "$out/gpio-sim.ko" | cut -d' ' -f1)"
stamp="$stamp scripts=$(cat "$0" "$here/init.sh" "$here/common.sh" | cksum | cut -d' ' -f1)"
if [ -f "$out/initramfs.cpio.gz" ] && [ "$(cat "$out/initramfs.stamp" 2>/dev/null)" = "$stamp" ]; then
  echo "initramfs: up to date in $out ($KVER)"
  exit 0
fi
rm -f "$out/initramfs.stamp"

root=$out/initramfs-root
rm -rf "$root"
mkdir -p "$root/bin" "$root/lib/ft-modules" "$root/dev" "$root/proc" "$root/sys" "$root/tmp" "$root/host"
cp "$busybox" "$root/bin/busybox"
ln -s busybox "$root/bin/sh"
cp "$here/init.sh" "$root/init"
chmod 755 "$root/init"

# Module load order: modprobe's dependency resolution, deduplicated.
: > "$root/lib/ft-modules/order"
add_ko() { # add_ko PATH [LIST]: copy (decompressed) into the image, append to LIST (order)
  name=$(basename "$1")
  ko_list=$root/lib/ft-modules/${2:-order}
  case $name in
    *.ko.xz) base=${name%.xz} ;;
    *.ko.zst) base=${name%.zst} ;;
    *.ko.gz) base=${name%.gz} ;;
    *.ko) base=$name ;;
    *) ft_vm_die "unexpected module file $1" ;;
  esac
  # loaded at boot already (order), or already in this list: nothing to do
  grep -qx "$base" "$root/lib/ft-modules/order" "$ko_list" 2>/dev/null && return 0
  if [ ! -f "$root/lib/ft-modules/$base" ]; then
    case $name in
      *.ko.xz) xz -dc "$1" > "$root/lib/ft-modules/$base" ;;
      *.ko.zst) ft_vm_need_cmd zstd; zstd -qdc "$1" > "$root/lib/ft-modules/$base" ;;
      *.ko.gz) gzip -dc "$1" > "$root/lib/ft-modules/$base" ;;
      *) cp "$1" "$root/lib/ft-modules/$base" ;;
    esac
  fi
  echo "$base" >> "$ko_list"
}
for m in virtio_pci 9pnet_virtio 9p overlay configfs can can-raw can-dev vcan; do
  deps=$(modprobe --show-depends -S "$KVER" "$m" 2>&1) ||
    ft_vm_die "modprobe --show-depends -S $KVER $m: $deps"
  # lines: "insmod /path/x.ko [opts]" or "builtin x" (nothing to load)
  for p in $(printf '%s\n' "$deps" | awk '$1 == "insmod" { print $2 }'); do
    add_ko "$p"
  done
done
add_ko "$out/irq_sim.ko"
add_ko "$out/gpio-sim.ko"
# Display devices (FT_VM_DISPLAY in run-vm.sh): DRM modules, loaded by init.sh
# only when the kernel command line has ft.display=NAME, in this order.
for d in bochs:bochs virtio:virtio-gpu; do
  list=display-${d%%:*}.order
  : > "$root/lib/ft-modules/$list"
  deps=$(modprobe --show-depends -S "$KVER" "${d#*:}" 2>&1) ||
    ft_vm_die "modprobe --show-depends -S $KVER ${d#*:}: $deps"
  for p in $(printf '%s\n' "$deps" | awk '$1 == "insmod" { print $2 }'); do
    add_ko "$p" "$list"
  done
done

(cd "$root" && find . | LC_ALL=C sort | cpio -o -H newc --quiet) | gzip -6 > "$out/initramfs.cpio.gz.tmp"
mv "$out/initramfs.cpio.gz.tmp" "$out/initramfs.cpio.gz"
echo "/boot/vmlinuz-$KVER" > "$out/kernel"
printf '%s\n' "$stamp" > "$out/initramfs.stamp"
echo "initramfs: built $out/initramfs.cpio.gz ($(wc -c < "$out/initramfs.cpio.gz") bytes, $KVER; modules: $(tr '\n' ' ' < "$root/lib/ft-modules/order"))"
