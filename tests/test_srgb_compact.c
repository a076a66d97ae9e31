/*
 * test_srgb_compact.c - the compact sRGB encoding table (CS_CFG_SRGB_COMPACT,
 * core/cs_srgb_compact.c) gives the boards the host's floats.
 *
 * The truth is the full table, cs__srgb_by_sqrt, and the host's own
 * cs_srgb_decode and cs_srgb_encode16 in libcelscan (built without the
 * compact form): every one of the 1025 entries must come back bit for bit;
 * decoding must give the same float as cs_srgb_decode at every entry and
 * the floats around it, on a sweep of 4 M floats over [0, 1] and at the
 * special values; and this file, compiled as a board is
 * (CS_CFG_SRGB_COMPACT 1, so its cs__srgb_encode reads the compact form),
 * must encode the sweep to the library's 16-bit codes.
 */
#define CS_CFG_SRGB_COMPACT 1
#include <math.h>
#include <string.h>

#include "common.h"
#include "cs_internal.h"

static void test_entries(void)
{
    int bad = 0, first = -1;
    for (uint32_t i = 0; i <= 1024u; i++)
        if (tl_bits_of(cs__srgb_compact_at(i)) != tl_bits_of(cs__srgb_by_sqrt[i])) {
            if (first < 0)
                first = (int)i;
            bad++;
        }
    CHECK(bad == 0, "%d of 1025 entries differ from cs__srgb_by_sqrt (first: %d)", bad, first);
    int rising = 1;
    for (uint32_t i = 0; i < 1024u; i++)
        rising &= cs__srgb_by_sqrt[i] < cs__srgb_by_sqrt[i + 1];
    CHECK(rising, "the table rises strictly (the decoder's search relies on it)");
}

/* Counts the floats whose compact decoding differs from cs_srgb_decode's. */
static int decode_differs(float v, float *worst)
{
    float got = cs__srgb_decode_compact(v), want = cs_srgb_decode(v);
    if (tl_bits_of(got) == tl_bits_of(want))
        return 0;
    *worst = v;
    return 1;
}

static void test_decode(void)
{
    int bad = 0;
    float at = 0.0f;
    for (uint32_t i = 0; i <= 1024u; i++)
        for (int d = -2; d <= 2; d++) {
            uint32_t b = tl_bits_of(cs__srgb_by_sqrt[i]);
            if (d < 0 && b < (uint32_t)-d)
                continue;
            bad += decode_differs(tl_float_of(b + (uint32_t)d), &at);
        }
    CHECK(bad == 0, "decoding at the entries and their neighbours: %d differ (one at %a)", bad,
          (double)at);
    bad = 0;
    uint32_t one = tl_bits_of(1.0f);
    for (uint32_t b = 0; b <= one; b += 256u)
        bad += decode_differs(tl_float_of(b), &at);
    CHECK(bad == 0, "decoding every 256th float in [0, 1]: %d differ (one at %a)", bad, (double)at);
    const float special[] = {0.0f, -0.0f, -1.0f, 1.0f, 2.0f, INFINITY, -INFINITY, NAN, FLT_MIN};
    bad = 0;
    for (size_t k = 0; k < sizeof special / sizeof special[0]; k++)
        bad += decode_differs(special[k], &at);
    CHECK(bad == 0, "decoding 0, -0, -1, 1, 2, +-inf, NaN, FLT_MIN: %d differ", bad);
}

static void test_encode(void)
{
    int bad = 0;
    float at = 0.0f;
    uint32_t one = tl_bits_of(1.0f);
    for (uint32_t b = 0; b <= one; b += 256u) {
        float v = tl_float_of(b);
        uint32_t c = (uint32_t)(cs__srgb_encode(v) * 65535.0f + 0.5f);
        if ((c > 65535u ? 65535u : c) != cs_srgb_encode16(v)) {
            bad++;
            at = v;
        }
    }
    CHECK(bad == 0, "a board's encoding of every 256th float in [0, 1] to 16 bits: %d differ "
          "from cs_srgb_encode16 (one at %a)", bad, (double)at);
}

int main(int argc, char **argv)
{
    (void)argc;
    TL_RUN(test_entries);
    TL_RUN(test_decode);
    TL_RUN(test_encode);
    return tl_summary(argv[0]);
}
