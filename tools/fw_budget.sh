#!/bin/sh
# fw_budget.sh BOARD ELF MAP - prints a firmware image's memory use and fails
# if it breaks the product budgets (issue: bare-metal firmware):
#
#   flash  (everything stored in rom: vectors, code, constants, the .data
#          initialisers)                                  <= FW_FLASH_MAX (64 KiB)
#   RAM    (stack with its guard + .data + .bss + .noinit) <= FW_RAM_MAX   (64 KiB)
#   both with FW_HEADROOM percent of the budget free (10: room to spare for
#   the next feature, issue 29), so flash and RAM <= 58,982 B each
#   scene store (the symbol scene_store)                  >= FW_SCENE_MIN (15 KiB:
#          the 480x272 boards' store, 600 points, holds the full signage
#          demo, which qemu-test streams; it was 16 KiB with room for 520)
#   the stream decoder's staging store, a second cs_scene that shares RAM
#   with the render workspace (the union `work`, see firmware/fw_render.c):
#   the union must be at least a scene store large, so that the staging
#   store has the front store's full capacity
#   no heap: no allocator symbol in the image and no C library in the link
#
# Figures come from arm-none-eabi-size -A (section sizes) and nm (symbols);
# the libraries the linker actually used come from the map file.
set -eu
board=$1 elf=$2 map=$3
FLASH_MAX=${FW_FLASH_MAX:-65536}
RAM_MAX=${FW_RAM_MAX:-65536}
SCENE_MIN=${FW_SCENE_MIN:-15360}
HEADROOM=${FW_HEADROOM:-10}

# mawk has no strtonum: hex symbol sizes by hand.
HEX='function hex(s,  i, v) { v = 0; s = tolower(s); for (i = 1; i <= length(s); i++) v = v * 16 + index("0123456789abcdef", substr(s, i, 1)) - 1; return v }'
sizes=$(arm-none-eabi-size -A "$elf")
sec() { echo "$sizes" | awk -v s="$1" '$1 == s {print $2; found=1} END {if (!found) print 0}'; }
vectors=$(sec .vectors) text=$(sec .text) extab=$(sec .ARM.extab) exidx=$(sec .ARM.exidx)
stack=$(sec .stack) data=$(sec .data) bss=$(sec .bss) noinit=$(sec .noinit)
flash=$((vectors + text + extab + exidx + data))
ram=$((stack + data + bss + noinit))
scene=$(arm-none-eabi-nm -S "$elf" | awk "$HEX"' ($4 == "scene_store" || $4 ~ /^scene_store\.lto_priv\./) {print hex($2)}')
scene=${scene:-0}
work=$(arm-none-eabi-nm -S "$elf" | awk "$HEX"' ($4 == "work" || $4 ~ /^work\.lto_priv\./) {print hex($2)}')
work=${work:-0}
# Read-only data alone, for the report: the .rodata input sections the map
# file lists as placed (GNU ld puts the size on the next line after a long
# section name).
rodata=$(awk "$HEX"'
    /^Linker script and memory map/ {placed = 1}
    !placed {next}
    pending {s += hex(substr($2, 3)); pending = 0; next}
    /^ \.rodata/ {if (NF >= 3) s += hex(substr($3, 3)); else pending = 1}
    END {print s + 0}' "$map")

pct() { awk -v a="$1" -v b="$2" 'BEGIN {printf "%.1f%%", 100 * a / b}'; }
flash_cap=$((FLASH_MAX * (100 - HEADROOM) / 100))
ram_cap=$((RAM_MAX * (100 - HEADROOM) / 100))
echo "celfw $board memory use (budgets: flash $FLASH_MAX B, RAM $RAM_MAX B, each with $HEADROOM% free; two scene stores >= $SCENE_MIN B each):"
printf "  flash %6d B %7s  (vectors %d, code+rodata %d of which rodata %d, unwind %d, .data init %d)\n" \
    "$flash" "$(pct "$flash" "$FLASH_MAX")" "$vectors" "$text" "$rodata" $((extab + exidx)) "$data"
printf "  RAM   %6d B %7s  (stack %d incl. 32 B guard, .data %d, .bss %d, .noinit %d)\n" \
    "$ram" "$(pct "$ram" "$RAM_MAX")" "$stack" "$data" "$bss" "$noinit"
printf "  scene stores: front %d B (scene_store), staging %d B sharing the %d B render workspace (work)\n" \
    "$scene" "$scene" "$work"
printf "  largest RAM objects:\n"
arm-none-eabi-nm -S --size-sort "$elf" | awk '$3 ~ /^[bBdD]$/ {print}' | tail -5 |
    awk "$HEX"' {printf "    %-16s %6d B\n", $4, hex($2)}'

status=0
if [ "$flash" -gt "$FLASH_MAX" ]; then
    echo "fw_budget: $board: flash $flash B exceeds $FLASH_MAX B" >&2; status=1
fi
if [ "$ram" -gt "$RAM_MAX" ]; then
    echo "fw_budget: $board: RAM $ram B exceeds $RAM_MAX B" >&2; status=1
fi
if [ "$flash" -gt "$flash_cap" ]; then
    echo "fw_budget: $board: flash $flash B leaves less than $HEADROOM% of $FLASH_MAX B free (at most $flash_cap B)" >&2
    status=1
fi
if [ "$ram" -gt "$ram_cap" ]; then
    echo "fw_budget: $board: RAM $ram B leaves less than $HEADROOM% of $RAM_MAX B free (at most $ram_cap B)" >&2
    status=1
fi
if [ "$scene" -lt "$SCENE_MIN" ]; then
    echo "fw_budget: $board: scene store $scene B is below $SCENE_MIN B" >&2; status=1
fi
if [ "$work" -lt "$scene" ]; then
    echo "fw_budget: $board: the workspace/staging union ($work B) is smaller than a scene store ($scene B)" >&2
    status=1
fi
heap=$(arm-none-eabi-nm "$elf" | awk '{print $NF}' |
    grep -E '^_?(malloc|calloc|realloc|free|sbrk|_sbrk|_malloc_r|_free_r|__malloc_.*|end|_end|__heap_.*)$' || true)
if [ -n "$heap" ]; then
    echo "fw_budget: $board: heap or allocator symbols in the image:" $heap >&2; status=1
fi
libs=$(grep -oE '[^ (]*/lib(c|c_nano|m|g|g_nano|nosys|rdimon|rdimon_nano)\.a' "$map" | sort -u || true)
if [ -n "$libs" ]; then
    echo "fw_budget: $board: C library linked in:" $libs >&2; status=1
fi
[ $status -eq 0 ] && echo "  heap: none (no allocator symbol, no libc/libm in the link); budgets met"
exit $status
