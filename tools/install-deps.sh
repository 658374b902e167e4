#!/bin/sh
# Installs the Debian 12 packages fixterrain needs (run as root).
#   tools/install-deps.sh runtime   build + render (no GDAL, no test tools)
#   tools/install-deps.sh all       everything: import tool (GDAL) and tests
# Each package and what it is for is listed in README.md.
set -eu
runtime="build-essential cmake pkg-config
  libegl-dev libegl-mesa0 libgles-dev libgl1-mesa-dri
  libosmesa6-dev libpng-dev zlib1g-dev libinih-dev libx11-dev"
tools="libgdal-dev glslang-tools clang xvfb xauth"
case "${1:-}" in
  runtime) pkgs=$runtime ;;
  all) pkgs="$runtime $tools" ;;
  *) echo "usage: $0 runtime|all" >&2; exit 2 ;;
esac
export DEBIAN_FRONTEND=noninteractive
apt-get update -q
# shellcheck disable=SC2086
apt-get install -y -q --no-install-recommends $pkgs
