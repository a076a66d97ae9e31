/*
 * cs_srgb_compact.c - the sRGB encoding table's entries from its compact
 * form (CS_CFG_SRGB_COMPACT, layout in cs_srgb_compact.h), and the
 * decoding of sRGB blending over it.
 *
 * A board that blends in sRGB (imported SVG and Lottie scenes ask for it)
 * needs the encoding curve; one that keeps its flash for the line code
 * rebuilds each entry it reads from an anchor cubic and a one-byte
 * correction: the same floats, so the same frames, for about 25
 * instructions an entry, paid only under sRGB blending (RGB565 panels
 * convert through their own threshold tables). The decoding is
 * cs_srgb_decode's search and interpolation (cs__srgb_decode_in) over these
 * entries, after a search over the anchors, which are stored whole, so that
 * three entries are rebuilt; the table is strictly increasing, so the cell,
 * and with it every bit of the result, is the one cs_srgb_decode finds.
 */
#include "cs_srgb_compact.h"

float cs__srgb_compact_at(uint32_t i)
{
    if (i < CS__SRGB_HEAD)
        return cs__srgb_head[i];
    uint32_t m = i - CS__SRGB_HEAD;
    union {
        float f;
        int32_t b;
    } v = {cs__srgb_cubic(cs__srgb_anchor, m)};
    v.b += cs__srgb_fix[m];
    return v.f;
}

/* Entry CS__SRGB_STEP j of the table, stored whole (j <= 1024 / CS__SRGB_STEP). */
static float coarse(uint32_t j)
{
    uint32_t i = j * CS__SRGB_STEP;
    return i < CS__SRGB_HEAD ? cs__srgb_head[i] : cs__srgb_anchor[(i - CS__SRGB_HEAD) / CS__SRGB_STEP];
}

float cs__srgb_decode_compact(float encoded)
{
    if (!(encoded > 0.0f))
        return 0.0f;
    if (encoded >= 1.0f)
        return 1.0f;
    uint32_t lo = CS__SRGB_STEP * cs__srgb_cell(coarse, 0u, 1024u / CS__SRGB_STEP, encoded);
    /* entry lo <= encoded < entry lo + CS__SRGB_STEP */
    return cs__srgb_decode_in(cs__srgb_compact_at, lo, lo + CS__SRGB_STEP, encoded);
}
