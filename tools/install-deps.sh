#!/bin/sh
# Installs the Debian 12 packages fixterrain needs (run as root).
#   tools/install-deps.sh runtime   build + render (no GDAL, no test tools)
#   tools/install-deps.sh vm        the test VM only (qemu, Debian kernel, vcan, gpio-sim)
#   tools/install-deps.sh all       everything: import tool (GDAL), tests and the test VM
# Each package and what it is for is listed in README.md.
set -eu
runtime="build-essential cmake pkg-config
  libegl-dev libegl-mesa0 libgles-dev libgl1-mesa-dri
  libosmesa6-dev libpng-dev zlib1g-dev libinih-dev libx11-dev libgpiod-dev
  libdrm-dev libgbm-dev"
tools="libgdal-dev glslang-tools clang libclang-rt-14-dev xvfb xauth ferret-datasets"
# Test VM (tests/vm/): qemu boots Debian's kernel with a busybox initramfs;
# vcan + can-utils and an out-of-tree gpio-sim (built from linux-source-6.1
# against linux-headers) + libgpiod tools run in it.
vm="qemu-system-x86 linux-image-amd64 linux-headers-amd64 linux-source-6.1
  busybox-static can-utils gpiod libgpiod-dev kmod cpio xz-utils gzip
  make gcc libc6-dev iproute2"
case "${1:-}" in
  runtime) pkgs=$runtime ;;
  vm) pkgs=$vm ;;
  all) pkgs="$runtime $tools $vm" ;;
  *) echo "usage: $0 runtime|vm|all" >&2; exit 2 ;;
esac
export DEBIAN_FRONTEND=noninteractive
apt-get update -q
# shellcheck disable=SC2086
apt-get install -y -q --no-install-recommends $pkgs
