/*
 * gen_srgb8_table.c - writes core/cs_srgb8_table.c: 8-bit sRGB codes by table.
 *
 * The core encodes linear light to an 8-bit sRGB code as
 * round(255 * encode(v)), where encode interpolates cs__srgb_by_sqrt at
 * pos = sqrt(v) * 1024. Within one cell i = floor(pos) that code changes
 * at most once (the curve climbs at most ~0.35 codes a cell), so it equals
 * base[i] + (v >= step[i]): the code at the cell's start, plus one from
 * the first float v at which the core's own arithmetic rounds up. This
 * program finds both by running that arithmetic on every float in (0, 1),
 * and checks the two facts the table relies on (the code is monotone in
 * v within a cell, and rises by at most one) before writing anything.
 * The table is then the core's arithmetic, not an approximation of it;
 * tests/test_pixfmt.c checks it again at every step and cell boundary.
 *
 * The second table (CS_CFG_SRGB8_BITS, the host's) has the same form with
 * cells cut by the float's bits instead of its square root: cell
 * (bits >> 16) - CS__SRGB8_BITS_FIRST, 128 cells per power of two, over
 * which the code also rises at most once; every float below the first
 * cell has code 0. The lookup then needs no square root, multiply or
 * conversion. The program checks CS__SRGB8_BITS_FIRST and _CELLS
 * (cs_internal.h) against what it finds.
 *
 *   cc -O2 -ffp-contract=off -fno-math-errno -fno-trapping-math -Icore \
 *      tools/gen_srgb8_table.c core/cs_srgb_table.c \
 *      -o gen_srgb8_table && ./gen_srgb8_table > core/cs_srgb8_table.c
 */
#include <stdbool.h>
#include <stdio.h>
#include <string.h>

#include "cs_internal.h"

#define CELLS 1024
#define BITS_SHIFT 16

static uint32_t reference(float v)
{
    uint32_t c = (uint32_t)(cs__srgb_encode(v) * 255.0f + 0.5f);
    return c > 255u ? 255u : c;
}

/* The cell of float v (bits `bits`) in the sqrt table (`by_bits` false)
 * or the bits table, or -1 where the lookup needs no table. */
static int32_t cell_of(float v, uint32_t bits, bool by_bits)
{
    if (by_bits)
        return bits >> BITS_SHIFT < CS__SRGB8_BITS_FIRST ? -1
                                                          : (int32_t)((bits >> BITS_SHIFT) -
                                                                      CS__SRGB8_BITS_FIRST);
    int32_t i = (int32_t)(cs__sqrtf(v) * 1024.0f);
    return i >= CELLS ? -1 : i; /* encoded as 1.0: code 255 without the table */
}

/* base[] and step[] of `cells` cells; 0 if the facts the lookup relies on hold. */
static int make_table(bool by_bits, int cells, int *base, float *step)
{
    static int seen[CS__SRGB8_BITS_CELLS > CELLS ? CS__SRGB8_BITS_CELLS : CELLS];
    static int last[CS__SRGB8_BITS_CELLS > CELLS ? CS__SRGB8_BITS_CELLS : CELLS];
    memset(seen, 0, sizeof seen);
    for (uint32_t bits = 1u; bits < 0x3F800000u; bits++) { /* every float in (0, 1) */
        float v;
        memcpy(&v, &bits, sizeof v);
        int c = (int)reference(v);
        int32_t i = cell_of(v, bits, by_bits);
        if (i < 0) {
            if (by_bits && c != 0) {
                fprintf(stderr, "%a below the first bits cell has code %d\n", (double)v, c);
                return 1;
            }
            continue;
        }
        if (i >= cells) {
            fprintf(stderr, "%a: cell %d of %d\n", (double)v, (int)i, cells);
            return 1;
        }
        if (!seen[i]) {
            seen[i] = 1;
            base[i] = last[i] = c;
            step[i] = 2.0f; /* no step: never reached by v < 1 */
            continue;
        }
        if (c < last[i] || c > base[i] + 1) {
            fprintf(stderr, "cell %d: code %d after %d (base %d) at %a\n", (int)i, c, last[i],
                    base[i], (double)v);
            return 1;
        }
        if (c > last[i])
            step[i] = v;
        last[i] = c;
    }
    for (int i = 0; i < cells; i++)
        if (!seen[i]) {
            fprintf(stderr, "cell %d: no float\n", i);
            return 1;
        }
    if (by_bits && !(base[0] == 0 && step[0] < 2.0f)) { /* the first code 1 is in cell 0 */
        fprintf(stderr, "CS__SRGB8_BITS_FIRST: not the cell of the first code 1\n");
        return 1;
    }
    return 0;
}

/* `pad` zero bytes follow the base table (for dword gathers: cs__srgb8_px). */
static void print_table(const char *name, int cells, int pad, const int *base, const float *step)
{
    printf("const uint8_t cs__%s_base[%d] = {\n", name, cells + pad);
    for (int i = 0; i < cells + pad; i++)
        printf("%s%d,%s", i % 16 == 0 ? "    " : "", i < cells ? base[i] : 0,
               i % 16 == 15 || i + 1 == cells + pad ? "\n" : " ");
    printf("};\n\nconst float cs__%s_step[%d] = {\n", name, cells);
    for (int i = 0; i < cells; i++)
        printf("%s%af,%s", i % 4 == 0 ? "    " : "", (double)step[i],
               i % 4 == 3 || i + 1 == cells ? "\n" : " ");
    printf("};\n");
}

int main(void)
{
    static int base[CELLS], bbase[CS__SRGB8_BITS_CELLS + 1];
    static float step[CELLS], bstep[CS__SRGB8_BITS_CELLS + 1];
    if (make_table(false, CELLS, base, step) != 0 ||
        make_table(true, CS__SRGB8_BITS_CELLS, bbase, bstep) != 0)
        return 1;
    /* One cell more, 1.0's (code 255, no step), for lookups of [0, 1]
     * without an upper bound test (cs__srgb8_px). */
    bbase[CS__SRGB8_BITS_CELLS] = 255;
    bstep[CS__SRGB8_BITS_CELLS] = 2.0f;
    /* The last cell reaches 1.0: every float in (0, 1) has a cell. */
    if ((0x3F800000u >> BITS_SHIFT) - CS__SRGB8_BITS_FIRST != CS__SRGB8_BITS_CELLS) {
        fprintf(stderr, "CS__SRGB8_BITS_CELLS: the cells end before 1.0\n");
        return 1;
    }
    printf("/*\n * cs_srgb8_table.c - 8-bit sRGB codes by sqrt cell, generated by\n"
           " * tools/gen_srgb8_table.c from the core's own encoding arithmetic. Do not edit.\n"
           " *\n * For linear v in (0, 1) with i = (int)(sqrt(v) * 1024) < 1024, the code\n"
           " * round(255 * cs__srgb_encode(v)) is cs__srgb8_base[i] + (v >= cs__srgb8_step[i]).\n"
           " * With CS_CFG_SRGB8_BITS, i = (bits of v >> 16) - CS__SRGB8_BITS_FIRST in the\n"
           " * cs__srgb8_bits tables instead (below the first cell the code is 0; one\n"
           " * cell more holds 1.0, and 3 zero bytes follow the base table).\n"
           " */\n#include \"cs_internal.h\"\n\n#if CS_CFG_SRGB8_BITS\n\n");
    print_table("srgb8_bits", CS__SRGB8_BITS_CELLS + 1, CS__SRGB8_BITS_PAD, bbase, bstep);
    printf("\n#elif CS_CFG_SRGB8_TABLE\n\n");
    print_table("srgb8", CELLS, 0, base, step);
    printf("\n#endif /* CS_CFG_SRGB8_BITS, CS_CFG_SRGB8_TABLE */\n");
    return 0;
}
