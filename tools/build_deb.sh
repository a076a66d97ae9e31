#!/bin/sh
# build_deb.sh - builds the celscan Debian packages from a copy of the tree (`make deb`).
#
# The copy holds the files git knows, committed or not, minus the ignored
# ones, so neither build/ nor stray files are packaged and the tree itself
# stays clean. dpkg-buildpackage runs debian/rules there with nocheck (the
# tests are `make test`, which calls this), then lintian judges the result:
# an error fails the build, warnings are listed.
#
# usage: build_deb.sh OUT_DIR VERSION      -> OUT_DIR/*.deb, build.log, lintian.txt
set -eu
out=$1 version=$2
src=$out/src/celscan-$version
rm -rf "$out/src"
mkdir -p "$src"
if git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
    git ls-files -co --exclude-standard | grep -v '^build/' | while IFS= read -r f; do
        if [ -e "$f" ] || [ -L "$f" ]; then printf '%s\n' "$f"; fi
    done
else
    find . -path ./build -prune -o \( -type f -o -type l \) -print | sed 's|^\./||'
fi | tr '\n' '\0' | xargs -0 cp -P --parents -t "$src"

echo "deb: dpkg-buildpackage in $src (log: $out/build.log)"
# Called from make: the outer make's job server is not ours.
unset MAKEFLAGS MFLAGS MAKELEVEL
if ! (cd "$src" && DEB_BUILD_OPTIONS="nocheck parallel=2" dpkg-buildpackage -b -us -uc) \
        >"$out/build.log" 2>&1; then
    tail -30 "$out/build.log" >&2
    echo "deb: dpkg-buildpackage failed (whole log: $out/build.log)" >&2
    exit 1
fi
for f in "$out"/src/*.deb "$out"/src/*.changes "$out"/src/*.buildinfo; do
    mv -f "$f" "$out/"
done
rm -rf "$out/src"
changes=$(ls "$out"/celscan_"$version"_*.changes)
status=0
lintian --fail-on error --info "$changes" >"$out/lintian.txt" 2>&1 || status=$?
echo "deb: lintian: $(grep -c '^E:' "$out/lintian.txt") errors, $(grep -c '^W:' "$out/lintian.txt") warnings, $(grep -c '^I:' "$out/lintian.txt") info ($out/lintian.txt)"
grep '^[EW]:' "$out/lintian.txt" || true
exit $status
