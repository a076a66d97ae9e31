#!/bin/sh
# install_meta.sh - writes the pkg-config files and the CMake package of the installed library.
#
# Called by `make install-lib` (mk/install.mk) with the install directories;
# fills dist/celscan.pc.in once per library variant and dist/celscanConfig.cmake.in
# once, and has CMake itself write the version file. The CMake package finds
# its files relative to itself; the pkg-config files hold absolute paths, as
# pkg-config expects (PKG_CONFIG_SYSROOT_DIR serves staged trees).
#
# usage: install_meta.sh DESTDIR VERSION PREFIX LIBDIR DATADIR INCLUDEDIR CROSSLIBDIR
#                        CFG_NAME "VARIANTS" "CORTEX_M4F_FLAGS" "RV32_FLAGS"
set -eu
destdir=$1 version=$2 prefix=$3 libdir=$4 datadir=$5 includedir=$6 crosslibdir=$7
cfg=$8 variants=$9
shift 9
m4flags=$1 rvflags=$2
[ -n "$version" ] || { echo "install_meta.sh: no version (debian/changelog)" >&2; exit 1; }

# pc VARIANT_SUFFIX WHAT LIBDIR CPUFLAGS CFGFLAG OUT
pc() {
    sed -e "s|@PREFIX@|$prefix|" -e "s|@LIBDIR@|$3|" -e "s|@INCLUDEDIR@|$includedir|" \
        -e "s|@CPUFLAGS@|$4|" -e "s|@SUFFIX@|$1|" -e "s|@WHAT@|$2|" -e "s|@VERSION@|$version|" \
        -e "s|@CFGFLAG@|$5|" dist/celscan.pc.in > "$6"
    chmod 0644 "$6"
}
pc "" "for this machine" "$libdir" "" "" "$destdir$libdir/pkgconfig/celscan.pc"
for v in $variants; do
    case $v in
    cortex-m4f) flags=$m4flags ;;
    rv32imafc) flags=$rvflags ;;
    *) echo "install_meta.sh: unknown variant $v" >&2; exit 1 ;;
    esac
    pc "-$v" "$v build" "$crosslibdir/$v" "$flags" "-DCS_CFG_FILE=\\\\\"$cfg\\\\\"" \
        "$destdir$datadir/pkgconfig/celscan-$v.pc"
done

cmakedir=$libdir/cmake/celscan
rel() { realpath -m --relative-to="$cmakedir" "$1"; }
sed -e "s|@TO_PREFIX@|$(rel "$prefix")|" \
    -e "s|@INCLUDE_REL@|$(realpath -m --relative-to="$prefix" "$includedir")|" \
    -e "s|@LIB_REL@|$(realpath -m --relative-to="$prefix" "$libdir")|" \
    -e "s|@CROSS_REL@|$(realpath -m --relative-to="$prefix" "$crosslibdir")|" \
    -e "s|@CFG_NAME@|$cfg|" -e "s|@VARIANTS@|$variants|" \
    -e "s|@VARIANTS_TEXT@|$(echo "$variants" | sed 's/ /, /g')|" \
    dist/celscanConfig.cmake.in > "$destdir$cmakedir/celscanConfig.cmake"
chmod 0644 "$destdir$cmakedir/celscanConfig.cmake"
cmake -DOUT="$destdir$cmakedir/celscanConfigVersion.cmake" -DVERSION="$version" \
    -P tools/cmake_version.cmake
