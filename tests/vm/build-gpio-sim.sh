#!/bin/sh
# Builds gpio-sim.ko and irq_sim.ko (Debian's kernel has neither
# CONFIG_GPIO_SIM nor CONFIG_IRQ_SIM) out of tree against linux-headers.
#   tests/vm/build-gpio-sim.sh OUTDIR
# Sources: only drivers/gpio/gpio-sim.c, drivers/gpio/gpiolib.h and
# kernel/irq/irq_sim.c, extracted from /usr/src/linux-source-6.1.tar.xz.
# irq_sim.c is patched to build as a module: irq_to_desc() is not exported,
# so handle_simple_irq(irq_to_desc(irq)) becomes generic_handle_irq(irq) (the
# irq_work is IRQ_WORK_INIT_HARD, so this runs in hardirq context as
# generic_handle_irq wants), plus MODULE_LICENSE.
# Idempotent: does nothing when OUTDIR/gpio-sim.stamp matches the kernel
# version, the source tarball and this script.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
. "$here/common.sh"
[ $# -eq 1 ] || { echo "usage: $0 OUTDIR" >&2; exit 2; }
out=$1
ft_vm_need_kver
src_tar=/usr/src/linux-source-6.1.tar.xz
kbuild=/lib/modules/$KVER/build
[ -f "$src_tar" ] || ft_vm_die "$src_tar missing (install linux-source-6.1: tools/install-deps.sh vm)"
[ -f "$kbuild/Makefile" ] || ft_vm_die "$kbuild missing (install linux-headers-$KVER / linux-headers-amd64: tools/install-deps.sh vm)"
ft_vm_need_cmd make gcc tar xz

stamp="kver=$KVER src=$(stat -c '%s-%Y' "$src_tar") script=$(cksum < "$0" | cut -d' ' -f1)"
mkdir -p "$out"
out=$(cd "$out" && pwd)
if [ -f "$out/gpio-sim.ko" ] && [ -f "$out/irq_sim.ko" ] &&
   [ "$(cat "$out/gpio-sim.stamp" 2>/dev/null)" = "$stamp" ]; then
  echo "gpio-sim: up to date in $out ($KVER)"
  exit 0
fi

w=$out/gpio-sim-build
rm -rf "$w" "$out/gpio-sim.ko" "$out/irq_sim.ko" "$out/gpio-sim.stamp"
mkdir -p "$w/x" "$w/src"
echo "gpio-sim: extracting sources from $src_tar"
tar -xJf "$src_tar" -C "$w/x" --wildcards \
  '*/drivers/gpio/gpio-sim.c' '*/drivers/gpio/gpiolib.h' '*/kernel/irq/irq_sim.c'
top=$(find "$w/x" -mindepth 1 -maxdepth 1 -type d | head -n 1)
for f in drivers/gpio/gpio-sim.c drivers/gpio/gpiolib.h kernel/irq/irq_sim.c; do
  [ -f "$top/$f" ] || ft_vm_die "$f not found in $src_tar"
  cp "$top/$f" "$w/src/"
done
rm -rf "$w/x"

grep -q 'handle_simple_irq(irq_to_desc(irqnum));' "$w/src/irq_sim.c" ||
  ft_vm_die "irq_sim.c: expected handle_simple_irq(irq_to_desc(irqnum)) to patch; source changed"
sed -i 's/handle_simple_irq(irq_to_desc(irqnum));/generic_handle_irq(irqnum);/' "$w/src/irq_sim.c"
sed -i 's|^#include <linux/irq.h>|#include <linux/module.h>\n#include <linux/irq.h>|' "$w/src/irq_sim.c"
cat >> "$w/src/irq_sim.c" <<'EOC'

MODULE_LICENSE("GPL");
MODULE_DESCRIPTION("Interrupt simulator (out-of-tree build for fixterrain tests)");
EOC
printf 'obj-m := irq_sim.o gpio-sim.o\n' > "$w/src/Kbuild"

echo "gpio-sim: building against $kbuild"
if ! make -C "$kbuild" M="$w/src" -j"$(nproc 2>/dev/null || echo 2)" modules > "$w/build.log" 2>&1; then
  cat "$w/build.log" >&2
  ft_vm_die "gpio-sim module build failed"
fi
grep -i warning "$w/build.log" >&2 || true
cp "$w/src/irq_sim.ko" "$w/src/gpio-sim.ko" "$out/"
printf '%s\n' "$stamp" > "$out/gpio-sim.stamp"
echo "gpio-sim: built $out/gpio-sim.ko $out/irq_sim.ko ($KVER)"
