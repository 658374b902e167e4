#!/bin/sh
# Builds the test VM's initramfs: busybox-static, tests/vm/init.sh as /init,
# and the modules it needs (virtio-pci + 9p stack, configfs, CAN + vcan,
# out-of-tree irq_sim + gpio-sim) from Debian's kernel.
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
add_ko() { # add_ko PATH: copy (decompressed) into the image, append to order
  name=$(basename "$1")
  case $name in
    *.ko.xz) base=${name%.xz}; grep -qx "$base" "$root/lib/ft-modules/order" && return 0
             xz -dc "$1" > "$root/lib/ft-modules/$base" ;;
    *.ko.zst) base=${name%.zst}; grep -qx "$base" "$root/lib/ft-modules/order" && return 0
             ft_vm_need_cmd zstd; zstd -qdc "$1" > "$root/lib/ft-modules/$base" ;;
    *.ko.gz) base=${name%.gz}; grep -qx "$base" "$root/lib/ft-modules/order" && return 0
             gzip -dc "$1" > "$root/lib/ft-modules/$base" ;;
    *.ko) base=$name; grep -qx "$base" "$root/lib/ft-modules/order" && return 0
             cp "$1" "$root/lib/ft-modules/$base" ;;
    *) ft_vm_die "unexpected module file $1" ;;
  esac
  echo "$base" >> "$root/lib/ft-modules/order"
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

(cd "$root" && find . | LC_ALL=C sort | cpio -o -H newc --quiet) | gzip -6 > "$out/initramfs.cpio.gz.tmp"
mv "$out/initramfs.cpio.gz.tmp" "$out/initramfs.cpio.gz"
echo "/boot/vmlinuz-$KVER" > "$out/kernel"
printf '%s\n' "$stamp" > "$out/initramfs.stamp"
echo "initramfs: built $out/initramfs.cpio.gz ($(wc -c < "$out/initramfs.cpio.gz") bytes, $KVER; modules: $(tr '\n' ' ' < "$root/lib/ft-modules/order"))"
