/*
 * cs_srgb_compact.h - the layout of the compact sRGB encoding table
 * (CS_CFG_SRGB_COMPACT; cs_srgb_compact.c, generated data in
 * cs_srgb_compact_table.c by tools/gen_srgb_compact.c).
 *
 * The 1025 floats of cs__srgb_by_sqrt take 4 KB, a tenth of a 64 KiB
 * board's flash, for a curve that is smooth but for its start. So entries
 * 0..63 are kept as they are (the curve is 12.92 s^2 there and bends
 * hardest), and from 64 on every eighth entry is kept (an anchor); an
 * entry between is the cubic through the four anchors around it, computed
 * in float, plus a correction of at most 127 in the float's bits, stored
 * as one signed byte: 1.7 KB for the same 1025 floats. The generator
 * writes the corrections by running this very cubic, and checks every
 * entry comes back bit for bit; tests/test_srgb_compact.c checks again.
 */
#ifndef CS_SRGB_COMPACT_H
#define CS_SRGB_COMPACT_H

#include "cs_internal.h"

#define CS__SRGB_HEAD 64u    /* entries kept whole */
#define CS__SRGB_STEP 8u     /* entries per anchor after them */
#define CS__SRGB_ANCHORS 121u /* (1024 - 64) / 8 + 1 */

extern const float cs__srgb_head[CS__SRGB_HEAD];
extern const float cs__srgb_anchor[CS__SRGB_ANCHORS];
extern const int8_t cs__srgb_fix[1025u - CS__SRGB_HEAD];

/*
 * The cubic's value at entry CS__SRGB_HEAD + m: Newton's forward form over
 * the anchors k0 .. k0 + 3, the interval of m in their middle where there
 * is one (t in [1, 2); [0, 1) before the second anchor, up to 3 after the
 * last but one).
 */
static inline float cs__srgb_cubic(const float *anchor, uint32_t m)
{
    uint32_t k = m / CS__SRGB_STEP, k0 = k == 0u ? 0u : k - 1u;
    if (k0 > CS__SRGB_ANCHORS - 4u)
        k0 = CS__SRGB_ANCHORS - 4u;
    const float *a = &anchor[k0];
    float t = (float)(m - k0 * CS__SRGB_STEP) * (1.0f / (float)CS__SRGB_STEP);
    float d1 = a[1] - a[0], d2 = (a[2] - a[1]) - d1, d3 = ((a[3] - a[2]) - (a[2] - a[1])) - d2;
    return ((d3 * (1.0f / 6.0f) * (t - 2.0f) + d2 * 0.5f) * (t - 1.0f) + d1) * t + a[0];
}

#endif /* CS_SRGB_COMPACT_H */
