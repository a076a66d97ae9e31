#!/bin/sh
# cli_viewport.sh - celsim render --viewport through the simulated display.
#
#   sh tests/cli_viewport.sh BUILD_HOST_DIR
#
# The tiles' bits are wall_tiles.c's subject; this checks the command line
# around them: a viewport covering the whole output gives the whole render's
# frame CRC, a tile's CRC does not, a wall wider than a line renders through a
# viewport (and is refused without one), and a viewport that does not fit is
# a usage error (status 2) naming it. celfw --wall/--viewport: a board of a
# wall runs (its display the viewport's size), and a wall without a viewport,
# a viewport that does not fit and a display of another size are refused
# with status 2 and the reason; --clock at:S shows S less the scene's epoch,
# and a malformed S is refused. Last line: "cli_viewport: N passed, M failed".
TL_NAME=cli_viewport
. "$(dirname "$0")/testlib.sh"
bin=$1/celsim
fw=$1/celfw
crc() { "$bin" render "$@" --crc 2>&1; }

for aa in none 16 exact; do
    whole=$(crc scenes/motion.json --size 641x363 --time 1.1 --aa $aa)
    full=$(crc scenes/motion.json --size 641x363 --time 1.1 --aa $aa --viewport 0,0,641,363)
    tile=$(crc scenes/motion.json --size 641x363 --time 1.1 --aa $aa --viewport 213,0,214,363)
    [ -n "$whole" ] && [ "$whole" = "$full" ] && ok || bad "--aa $aa: whole '$whole', full viewport '$full'"
    [ "$tile" != "$whole" ] && case $tile in "frame crc32 "*) true;; *) false;; esac && ok ||
        bad "--aa $aa: tile gave '$tile'"
    # A window that starts below the top, on one thread and on three bands' threads.
    one=$(crc scenes/motion.json --size 641x363 --time 1.1 --aa $aa --viewport 100,77,300,200 --threads 1)
    three=$(crc scenes/motion.json --size 641x363 --time 1.1 --aa $aa --viewport 100,77,300,200 --threads 3)
    case $one in "frame crc32 "*) [ "$one" = "$three" ] ;; *) false ;; esac && ok ||
        bad "--aa $aa: viewport on 1 thread '$one', on 3 threads '$three'"
done

out=$("$bin" render scenes/demo.json --size 6000x200 --viewport 5000,0,1000,200 --crc 2>&1)
case $out in "frame crc32 "*) ok ;; *) bad "6000-wide wall viewport: $out" ;; esac
out=$("$bin" render scenes/demo.json --size 6000x200 --crc 2>&1)
rc=$?
[ $rc -eq 2 ] && echo "$out" | grep -q 'needs --viewport' && ok || bad "6000 wide without viewport: rc $rc: $out"
out=$("$bin" render scenes/demo.json --size 640x360 --viewport 600,0,41,10 --crc 2>&1)
rc=$?
[ $rc -eq 2 ] && echo "$out" | grep -q 'does not fit in the 640x360 output' && ok ||
    bad "viewport past the edge: rc $rc: $out"
out=$("$bin" render scenes/demo.json --viewport 1,2,3 --crc 2>&1)
rc=$?
[ $rc -eq 2 ] && echo "$out" | grep -q 'expects X,Y,W,H' && ok || bad "malformed viewport: rc $rc: $out"

# celfw: "expect STATUS TEXT -- celfw args": the exit status and a line of stderr.
expect() {
    want=$1 text=$2
    shift 3
    out=$("$fw" --backend null --frames 2 --fps 0 --log-interval 0 "$@" 2>&1)
    rc=$?
    [ $rc -eq "$want" ] && echo "$out" | grep -q -- "$text" && ok || bad "celfw $*: rc $rc: $out"
}
expect 0 'display=640x360' -- --wall 1280x720 --viewport 640,360,640,360 --aa 16
expect 2 'needs both --wall WxH and --viewport' -- --wall 1280x720 --size 640x360
expect 2 'does not fit in the 1280x720 wall' -- --wall 1280x720 --viewport 700,0,640,360
expect 2 "differs from the viewport's 640x360" -- --size 320x180 --wall 1280x720 \
    --viewport 0,0,640,360
expect 2 'is not a viewport X,Y,W,H' -- --wall 1280x720 --viewport 0,0,0,360
# --clock at:S: every frame shows the fixed wall-clock instant S less the
# scene's epoch (before it: time 0); refused unless S is a finite number of
# seconds in range.
epoch_scene=$(mktemp --suffix=.json /tmp/cli_viewport-XXXXXX)
sed 's/"canvas": {/"canvas": {"epoch": 1795000000,/' scenes/motion.json >"$epoch_scene"
expect 0 'anim_t=2.5$' -- --size 64x36 --scene "$epoch_scene" --clock at:1795000002.5
expect 0 'anim_t=0$' -- --size 64x36 --scene "$epoch_scene" --clock at:1794999999
rm -f "$epoch_scene"
for bad in at: at:x at:nan at:-1 at:1e10 at:5s; do
    expect 2 "'$bad' is not a clock (monotonic, realtime, or at:SECONDS" -- --clock $bad
done

tl_summary
