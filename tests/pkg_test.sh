#!/bin/sh
# pkg_test.sh - the Debian packages as a board would get them (`make test-pkg`).
#
# Unpacks celscan and libcelscan-dev into a scratch root (dpkg -x), then
# checks: the files and their modes, the conffile, the libraries' target
# machines and float ABI (readelf), the unit's settings, `systemd-analyze
# verify` with nothing to say (its warnings go to stderr with status 0, so
# any output fails), the unit's exposure rating from `systemd-analyze
# security --offline`, lintian's verdict kept by `make deb`, and the
# installed programs: celfw runs frames on the null display with the
# installed config, celc and celsim turn the demo into the same frame CRC
# as the build tree's celsim.
#
# usage: pkg_test.sh CELSCAN.deb LIBCELSCAN-DEV.deb WORK_DIR
set -u
TL_NAME=test-pkg
TL_CHECK_LOG=/dev/null
. "$(dirname "$0")/testlib.sh"
deb=$1 devdeb=$2 work=$(realpath -m "$3")

rm -rf "$work"
root=$work/root
mkdir -p "$root" "$work/tmp"
dpkg -x "$deb" "$root" && dpkg -x "$devdeb" "$root" || { bad "dpkg -x"; tl_summary; exit 1; }

# ---------------------------------------------------------------- files
for f in usr/bin/celfw usr/bin/celc usr/bin/celsim; do
    check "$f executable" test -x "$root/$f"
done
for f in etc/celscan/celfw.conf lib/systemd/system/celfw.service lib/udev/rules.d/60-celscan.rules \
        usr/lib/sysusers.d/celscan.conf usr/share/man/man1/celfw.1.gz usr/share/man/man1/celc.1.gz \
        usr/share/man/man1/celsim.1.gz usr/share/man/man5/celfw.conf.5.gz \
        usr/share/doc/celscan/examples/celfw.conf.example usr/share/doc/celscan/copyright \
        usr/include/celscan/celscan.h usr/include/celscan/celscan_private.h \
        usr/include/celscan/cs_config.h \
        usr/include/celscan/cs_config_480x272.h usr/lib/celscan/cortex-m4f/libcelscan.a \
        usr/lib/celscan/rv32imafc/libcelscan.a usr/share/pkgconfig/celscan-cortex-m4f.pc \
        usr/share/pkgconfig/celscan-rv32imafc.pc; do
    check "$f in the packages" test -f "$root/$f"
done
check "etc/celscan/keys/ directory" test -d "$root/etc/celscan/keys"
ma=$(dpkg-architecture -qDEB_HOST_MULTIARCH)
for f in libcelscan.a pkgconfig/celscan.pc cmake/celscan/celscanConfig.cmake \
        cmake/celscan/celscanConfigVersion.cmake; do
    check "usr/lib/$ma/$f in libcelscan-dev" test -f "$root/usr/lib/$ma/$f"
done
dpkg-deb -e "$deb" "$work/control"
check "/etc/celscan/celfw.conf is a conffile" grep -qx /etc/celscan/celfw.conf "$work/control/conffiles"
check "postinst creates the user (systemd-sysusers)" grep -q 'systemd-sysusers.*celscan.conf' \
    "$work/control/postinst"
check "sysusers.d entry for user celscan" grep -q '^u celscan ' "$root/usr/lib/sysusers.d/celscan.conf"

# Each library holds code for its machine; the Cortex-M4F one passes floats in VFP registers.
machines() { readelf -h "$1" 2>/dev/null | sed -n 's/^ *Machine: *//p' | sort -u | tr '\n' ';'; }
check "host library is x86-64 / this machine" test "$(machines "$root/usr/lib/$ma/libcelscan.a")" = \
    "$(readelf -h "$root/usr/bin/celfw" | sed -n 's/^ *Machine: *//p');"
check "cortex-m4f library is ARM" test "$(machines "$root/usr/lib/celscan/cortex-m4f/libcelscan.a")" = "ARM;"
check "rv32imafc library is RISC-V" test "$(machines "$root/usr/lib/celscan/rv32imafc/libcelscan.a")" = "RISC-V;"
check "cortex-m4f library uses the hard-float ABI" sh -c \
    "readelf -A '$root/usr/lib/celscan/cortex-m4f/libcelscan.a' | grep -q 'Tag_ABI_VFP_args: VFP registers'"

# ----------------------------------------------------------------- unit
unit=$root/lib/systemd/system/celfw.service
for kv in Type=notify NotifyAccess=main WatchdogSec=10s Restart=on-failure User=celscan \
        StateDirectory=celscan ProtectSystem=strict PrivateTmp=yes NoNewPrivileges=yes \
        ReadWritePaths=/var/lib/celscan "ExecStart=/usr/bin/celfw --config /etc/celscan/celfw.conf" \
        "RestrictAddressFamilies=AF_UNIX AF_INET AF_INET6 AF_NETLINK" CapabilityBoundingSet= \
        DevicePolicy=closed WantedBy=multi-user.target; do
    check "unit sets $kv" grep -qx "$kv" "$unit"
done
# verify the unit as shipped, but with ExecStart and the man pages it names
# found in the scratch root rather than on this machine
mkdir -p "$work/unit"
sed "s|^ExecStart=/usr/bin/celfw|ExecStart=$root/usr/bin/celfw|" "$unit" > "$work/unit/celfw.service"
out=$(MANPATH=$root/usr/share/man systemd-analyze verify "$work/unit/celfw.service" 2>&1)
if [ $? -eq 0 ] && [ -z "$out" ]; then ok; else bad "systemd-analyze verify: $out"; fi
exposure=$(systemd-analyze security --offline=true "$work/unit/celfw.service" 2>/dev/null |
    sed -n 's/.*Overall exposure level for celfw.service: \([0-9.]*\).*/\1/p')
echo "test-pkg: systemd-analyze security: exposure ${exposure:-?} (0 safest, 10 unsafe)"
check "exposure ${exposure:-?} <= 2.0" awk -v e="${exposure:-99}" 'BEGIN { exit !(e <= 2.0) }'
lint=$(dirname "$deb")/lintian.txt
check "lintian reports no errors" sh -c "test -f '$lint' && ! grep -q '^E:' '$lint'"
check "AppStream metadata validates" appstreamcli validate --no-net \
    "$root/usr/share/metainfo/org.celscan.celfw.metainfo.xml"
check "AppStream metadata announces the udev rule's device" grep -q \
    '<modalias>usb:v1D50p614Dd\*</modalias>' "$root/usr/share/metainfo/org.celscan.celfw.metainfo.xml"
check "udev rule gives the GUD device to group celscan" grep -q \
    'ATTR{idVendor}=="1d50", ATTR{idProduct}=="614d", GROUP="celscan"' "$root/lib/udev/rules.d/60-celscan.rules"

# ------------------------------------------------------------- programs
# The installed config parses; the command line puts it on the null display.
log=$work/celfw.log
timeout 20 "$root/usr/bin/celfw" --config "$root/etc/celscan/celfw.conf" --backend null --input none \
    --frames 3 --log-interval 0 2>"$log"
rc=$?
check "installed celfw with the installed config: exit 0 (was $rc)" test "$rc" -eq 0
check "installed celfw showed 3 frames on the null display" grep -q \
    '^celfw: exit reason=frames .* frames=3 dropped=0 ' "$log"
check "installed celfw started the null display at the configured size" grep -q \
    '^celfw: start backend=null display=320x240 ' "$log"
"$root/usr/bin/celc" compile scenes/demo.json -o "$work/demo.cels" >/dev/null 2>&1
want=$(build/host/celsim render scenes/demo.json --size 320x180 --time 1.5 --crc 2>/dev/null)
got=$("$root/usr/bin/celsim" render "$work/demo.cels" --size 320x180 --time 1.5 --crc 2>/dev/null)
if [ -n "$want" ] && [ "$got" = "$want" ]; then ok; else
    bad "installed celc+celsim: '$got', build tree celsim: '$want'"; fi
# Firmware built against libcelscan-dev as unpacked: pkg-config and CMake
# find the host library in the multiarch directory and the Cortex-M4F one.
check "consumer-make builds against libcelscan-dev" \
    make --no-print-directory -C examples/consumer-make SYSROOT="$root" O="$work/consumer-make"
check "consumer-cmake builds against libcelscan-dev" sh -c \
    "cmake -S examples/consumer-cmake -B '$work/consumer-cmake' -DCMAKE_PREFIX_PATH='$root/usr' &&
     cmake --build '$work/consumer-cmake'"
for prog in "$work/consumer-make/host/sign" "$work/consumer-cmake/sign"; do
    got=$("$prog" "$work/demo.cels" 320x180 1.5 2>&1)
    if [ -n "$want" ] && [ "$got" = "$want" ]; then ok; else
        bad "$prog against libcelscan-dev: '$got', celsim: '$want'"; fi
done
check "celfw(1) renders without warnings" sh -c \
    "! man --warnings -l '$root/usr/share/man/man1/celfw.1.gz' 2>&1 >/dev/null | grep -q ."

tl_summary
