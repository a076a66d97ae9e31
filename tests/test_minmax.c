/*
 * test_minmax.c - the core's cs__minf, cs__maxf and cs__clampf give the bits
 * of their C definitions, `a < b ? a : b` and `a > b ? a : b`, for every
 * pair of special floats (NaN of either sign, +-0, +-inf, the smallest
 * normal and subnormal, 1, the largest) and for random pairs.
 *
 * On x86-64 the core states them as minss/maxss by inline asm
 * (core/cs_internal.h); this program, built for baseline x86-64, checks the
 * SSE form; the AVX form of the x86-64-v3 build is covered by
 * test-core-variant (the two builds render every scene to the same bytes).
 * The truth here is the C conditional itself, evaluated on volatile operands
 * so the compiler cannot fold it into the same instruction.
 */
#include <math.h>
#include <string.h>

#include "cs_internal.h"
#include "testlib.h"

static float ref_min(float a, float b)
{
    volatile float va = a, vb = b;
    return va < vb ? va : vb;
}

static float ref_max(float a, float b)
{
    volatile float va = a, vb = b;
    return va > vb ? va : vb;
}

/* Counts pairs whose min, max or clamp to [0, 1] differs from the C form. */
static int pair_differs(float a, float b)
{
    int bad = 0;
    bad += tl_bits_of(cs__minf(a, b)) != tl_bits_of(ref_min(a, b));
    bad += tl_bits_of(cs__maxf(a, b)) != tl_bits_of(ref_max(a, b));
    bad += tl_bits_of(cs__clampf(a, 0.0f, 1.0f)) != tl_bits_of(ref_min(ref_max(a, 0.0f), 1.0f));
    return bad;
}

static void test_special(void)
{
    const float v[] = {0.0f,    -0.0f,    1.0f,     -1.0f,   INFINITY, -INFINITY,
                       NAN,     -NAN,     FLT_MIN,  -FLT_MIN, 1e-45f,  -1e-45f,
                       FLT_MAX, -FLT_MAX, 0.5f,     2.0f};
    const size_t n = sizeof v / sizeof v[0];
    int bad = 0;
    for (size_t i = 0; i < n; i++)
        for (size_t j = 0; j < n; j++)
            bad += pair_differs(v[i], v[j]);
    CHECK(bad == 0, "min/max/clamp of %zu x %zu special pairs: %d results differ from the C "
          "conditional", n, n, bad);
    /* The cases the order of the operands decides, by name. */
    CHECK(tl_bits_of(cs__maxf(-0.0f, 0.0f)) == tl_bits_of(0.0f) &&
              tl_bits_of(cs__maxf(0.0f, -0.0f)) == tl_bits_of(-0.0f),
          "max of +-0 is the second operand");
    CHECK(cs__maxf(NAN, 1.0f) == 1.0f && isnan(cs__maxf(1.0f, NAN)),
          "max with one NaN is the second operand");
    CHECK(cs__clampf(NAN, 0.0f, 1.0f) == 0.0f, "a NaN clamps to the low end");
}

static void test_random(void)
{
    uint32_t s = 12345u;
    int bad = 0;
    for (int k = 0; k < 200000; k++) {
        uint32_t x[2];
        for (int i = 0; i < 2; i++) {
            s = s * 1664525u + 1013904223u;
            x[i] = s;
        }
        float a, b;
        memcpy(&a, &x[0], sizeof a);
        memcpy(&b, &x[1], sizeof b);
        bad += pair_differs(a, b);
        bad += pair_differs(a, -a);
    }
    CHECK(bad == 0, "min/max/clamp of 400,000 random pairs: %d results differ", bad);
}

int main(int argc, char **argv)
{
    (void)argc;
    TL_RUN(test_special);
    TL_RUN(test_random);
    return tl_summary(argv[0]);
}
