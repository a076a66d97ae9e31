#!/bin/sh
# cli_damage.sh - celsim render --repeat N --time-step S: the damage report.
#
#   sh tests/cli_damage.sh BUILD_HOST_DIR
#
# The damaged frames' bits are test_damage.c's subject (and qemu-test's on
# the boards); this checks the command line: the first frame is the whole
# output, a frame of the board scene's ticker strip is a window of its rows
# (columns from 0 at aa 5, narrower at aa 16), a scene without tracks has
# nothing to redraw after its first frame, the mean is printed, and
# --time-step without --repeat or with a bad value is a usage error (2).
# Last line: "cli_damage: N passed, M failed".
TL_NAME=cli_damage
. "$(dirname "$0")/testlib.sh"
bin=$1/celsim

out=$("$bin" render scenes/board-anim.json --size 480x272 --aa 5 --repeat 3 --time-step 0.25 2>&1)
echo "$out" | grep -q '^frame 0 time 0 damage 0,0\.\.480,272 130560 pixels$' && ok ||
    bad "first frame not the whole output: $out"
echo "$out" | grep -q '^frame 1 time 0\.25 damage 0,2[0-9][0-9]\.\.[0-9]*,2[0-9][0-9] [0-9]* pixels$' && ok ||
    bad "aa 5: frame 1 not a window of the strip's rows from column 0: $out"
echo "$out" | grep -q '^damage: [0-9]* pixels rendered per frame on average' && ok ||
    bad "no mean: $out"
out=$("$bin" render scenes/board-anim.json --size 480x272 --aa 16 --repeat 2 --time-step 0.5 2>&1)
echo "$out" | grep -q '^frame 1 time 0\.5 damage [1-9][0-9]*,2' && ok ||
    bad "aa 16: frame 1 not a window narrower than the rows: $out"
out=$("$bin" render scenes/beta-stack.json --size 320x180 --repeat 3 --time-step 0.1 2>&1)
[ "$(echo "$out" | grep -c ' 0 pixels$')" -eq 2 ] && ok ||
    bad "a still scene redraws after its first frame: $out"
out=$("$bin" render scenes/board-anim.json --time-step 0.1 --crc 2>&1)
[ $? -eq 2 ] && echo "$out" | grep -q 'needs --repeat' && ok || bad "--time-step alone: $out"
out=$("$bin" render scenes/board-anim.json --repeat 2 --time-step -1 2>&1)
[ $? -eq 2 ] && echo "$out" | grep -q 'time-step expects' && ok || bad "--time-step -1: $out"
tl_summary
