#!/bin/sh
# install-deps.sh - installs the Debian packages celscan builds and tests with.
#
# Called by `make deps` (and so by `make demo` and `make test`). It asks dpkg
# first and runs apt-get only for what is missing, so on a prepared machine
# it costs a fraction of a second and needs no network.
set -eu
PACKAGES="make gcc g++ pkg-config python3 libcjson-dev libpng-dev libcairo2-dev libfreetype-dev libagg-dev
 libexpat1-dev zlib1g-dev fonts-dejavu-core gcc-arm-none-eabi libnewlib-arm-none-eabi qemu-system-arm
 libfontconfig-dev libharfbuzz-dev libfribidi-dev fonts-noto-core fonts-noto-cjk fonts-hosny-amiri
 libgpiod-dev libusb-1.0-0-dev umockdev libumockdev-dev liblz4-dev libdrm-dev
 librsvg2-bin adwaita-icon-theme breeze-icon-theme clang libclang-rt-14-dev valgrind
 libmosquitto-dev mosquitto mosquitto-clients openssl libsodium-dev
 gcc-riscv64-unknown-elf libsystemd-dev systemd man-db cmake build-essential debhelper dpkg-dev fakeroot lintian appstream
 librlottie-dev"
missing=""
for p in $PACKAGES; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing="$missing $p"
done
[ -z "$missing" ] && exit 0
echo "install-deps: installing:$missing"
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
# shellcheck disable=SC2086
$SUDO apt-get install -y -qq --no-install-recommends $missing
