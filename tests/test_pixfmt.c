/*
 * test_pixfmt.c - pixel output and CRC against exact formulas.
 *
 * The core has no libm, so it encodes sRGB through a table; here the truth is
 * the IEC 61966-2-1 formula evaluated with libm in double:
 *   s = 12.92 v                    for v <= 0.0031308
 *   s = 1.055 v^(1/2.4) - 0.055    otherwise.
 * cs_srgb_encode16 must be within 1 code of 65535 s. The packed formats must
 * round to nearest (within half a code plus 1% of a code: no truncation bias)
 * and lay out their bytes as documented: RGB565 little-endian with red in the
 * top five bits, RGB16 big-endian (PNG order). CRC-32 is checked against the
 * published check values and a bitwise reference.
 *
 * Rounded 8-bit sRGB comes from tables (cs__srgb8) that must give exactly
 * the code of the interpolating encoder: checked at both floats around
 * every step and cell boundary of the tables, and on a sweep of floats.
 * The RGB565 channel codes come from threshold tables (cs__rgb5, cs__rgb6),
 * compared with the interpolating encoder on every float in [0, 1].
 * Built for x86-64-v3 (make test-runs-v3), the display path's lookup of a
 * pixel's three codes at once (cs__srgb8_lanes) is compared with cs__srgb8
 * likewise, in every lane.
 */
#include <string.h>

#include "common.h"
#include "cs_internal.h"
#include "cs_rgb888.h"

static double srgb_exact(double v)
{
    if (v <= 0)
        return 0;
    if (v >= 1)
        return 1;
    return v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1 / 2.4) - 0.055;
}

static void test_srgb_encode16(void)
{
    double worst = 0, worst_v = 0;
    int nonmono = 0;
    unsigned prev = 0;
    const int N = 200000;
    for (int k = 0; k <= N; k++) {
        /* Dense near zero (the linear toe) and uniform elsewhere. */
        double v = k < N / 2 ? pow((double)k / (N / 2), 3) * 0.01 : 0.01 + 0.99 * (k - N / 2) / (N / 2.0);
        float f = (float)v;
        unsigned got = cs_srgb_encode16(f);
        double want = 65535.0 * srgb_exact((double)f);
        double d = fabs(got - want);
        if (d > worst) {
            worst = d;
            worst_v = f;
        }
        if (got < prev)
            nonmono++;
        prev = got;
    }
    CHECK(worst <= 1.0, "cs_srgb_encode16: worst at linear %.9g: off by %.3f codes from 65535*srgb "
                        "(limit 1)",
          worst_v, worst);
    CHECK(nonmono == 0, "cs_srgb_encode16 decreases %d times over an increasing ramp", nonmono);
    CHECK_EQ_INT(cs_srgb_encode16(0.0f), 0, "encode16(0)");
    CHECK_EQ_INT(cs_srgb_encode16(1.0f), 65535, "encode16(1)");
    CHECK_EQ_INT(cs_srgb_encode16(-0.5f), 0, "encode16(-0.5) clamps");
    CHECK_EQ_INT(cs_srgb_encode16(7.0f), 65535, "encode16(7) clamps");
    CHECK_EQ_INT(cs_srgb_encode16(-INFINITY), 0, "encode16(-inf) clamps");
    CHECK_EQ_INT(cs_srgb_encode16(INFINITY), 65535, "encode16(inf) clamps");
    CHECK_EQ_INT(cs_srgb_encode16(1e-40f), 0, "encode16(denormal)");
    /* Mid grey: linear 0.214041 is sRGB 0.5 (code 32767.5 -> 32767 or 32768). */
    unsigned mid = cs_srgb_encode16(0.21404114f);
    CHECK(mid == 32767 || mid == 32768, "encode16(0.21404114) = %u, expected 32767 or 32768", mid);
}

/* |code - max * s| <= 0.5 + 0.01: round to nearest, no truncation. */
static void test_packed_formats(void)
{
    const int N = 4097;
    float *rgb = tl_calloc(3 * (size_t)N, sizeof *rgb);
    uint8_t *out = tl_calloc(6 * (size_t)N, 1);
    for (int k = 0; k < N; k++) {
        double v = (double)k / (N - 1);
        rgb[3 * k] = (float)v;
        rgb[3 * k + 1] = (float)(v * v);
        rgb[3 * k + 2] = (float)(1 - v);
    }
    CHECK_EQ_INT(cs_pixfmt_bytes_per_pixel(CS_PIX_RGB888_SRGB), 3, "bytes per pixel RGB888_SRGB");
    CHECK_EQ_INT(cs_pixfmt_bytes_per_pixel(CS_PIX_RGB565_SRGB), 2, "bytes per pixel RGB565_SRGB");
    CHECK_EQ_INT(cs_pixfmt_bytes_per_pixel(CS_PIX_RGB16_LINEAR), 6, "bytes per pixel RGB16_LINEAR");
    CHECK_EQ_INT(cs_pixfmt_bytes_per_pixel(CS_PIX_RGB888_LINEAR), 3,
                 "bytes per pixel RGB888_LINEAR");
    static const struct {
        cs_pixfmt fmt;
        const char *name;
    } fmts[] = {{CS_PIX_RGB888_SRGB, "RGB888_SRGB"},
                {CS_PIX_RGB565_SRGB, "RGB565_SRGB"},
                {CS_PIX_RGB16_LINEAR, "RGB16_LINEAR"},
                {CS_PIX_RGB888_LINEAR, "RGB888_LINEAR"}};
    for (int f = 0; f < 4; f++) {
        memset(out, 0x5A, 6 * (size_t)N);
        /* One byte past the line must stay untouched. */
        size_t bytes = cs_pixfmt_bytes_per_pixel(fmts[f].fmt) * (size_t)(N - 1);
        cs_pixfmt_convert(fmts[f].fmt, rgb, N - 1, out);
        CHECK(out[bytes] == 0x5A, "%s: wrote past the end of the line", fmts[f].name);
        double worst = 0;
        int wk = 0, wc = 0;
        for (int k = 0; k < N - 1; k++)
            for (int c = 0; c < 3; c++) {
                double v = rgb[3 * k + c], want, got;
                switch (fmts[f].fmt) {
                case CS_PIX_RGB888_SRGB:
                    want = 255 * srgb_exact(v);
                    got = out[3 * k + c];
                    break;
                case CS_PIX_RGB565_SRGB: {
                    unsigned px = out[2 * k] | (unsigned)out[2 * k + 1] << 8;
                    unsigned bits[3] = {px >> 11, (px >> 5) & 63, px & 31};
                    want = (c == 1 ? 63 : 31) * srgb_exact(v);
                    got = bits[c];
                    break;
                }
                case CS_PIX_RGB16_LINEAR:
                    want = 65535 * v;
                    got = (unsigned)out[6 * k + 2 * c] << 8 | out[6 * k + 2 * c + 1];
                    break;
                default:
                    want = 255 * v;
                    got = out[3 * k + c];
                    break;
                }
                double d = fabs(got - want);
                if (d > worst) {
                    worst = d;
                    wk = k;
                    wc = c;
                }
            }
        CHECK(worst <= 0.51, "%s: pixel %d channel %d (linear %.6f) off by %.3f codes from the "
                             "exact value (limit 0.51: round to nearest)",
              fmts[f].name, wk, wc, (double)rgb[3 * wk + wc], worst);
    }
    /* Byte layout with pure primaries. */
    float prim[12] = {1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1};
    uint8_t o[24];
    cs_pixfmt_convert(CS_PIX_RGB565_SRGB, prim, 4, o);
    static const uint8_t want565[8] = {0x00, 0xF8, 0xE0, 0x07, 0x1F, 0x00, 0xFF, 0xFF};
    CHECK(memcmp(o, want565, 8) == 0,
          "RGB565 of red, green, blue, white: expected 00 F8 E0 07 1F 00 FF FF, got %02X %02X "
          "%02X %02X %02X %02X %02X %02X",
          o[0], o[1], o[2], o[3], o[4], o[5], o[6], o[7]);
    cs_pixfmt_convert(CS_PIX_RGB16_LINEAR, prim, 1, o);
    static const uint8_t want16[6] = {0xFF, 0xFF, 0, 0, 0, 0};
    CHECK(memcmp(o, want16, 6) == 0, "RGB16 of red: expected FF FF 00 00 00 00");
    float half[3] = {0.5f, 0.25f, 1.0f / 65535};
    cs_pixfmt_convert(CS_PIX_RGB16_LINEAR, half, 1, o);
    CHECK(o[0] == 0x80 && o[1] == 0x00 && o[2] == 0x40 && o[3] == 0x00 && o[4] == 0 && o[5] == 1,
          "RGB16 of (0.5, 0.25, 1/65535): expected 80 00 40 00 00 01, got %02X %02X %02X %02X "
          "%02X %02X",
          o[0], o[1], o[2], o[3], o[4], o[5]);
    /* Out-of-range input clamps. */
    float wild[6] = {-1, 2, -INFINITY, INFINITY, 1.0000001f, -0.0f};
    for (int f = 0; f < 4; f++) {
        cs_pixfmt_convert(fmts[f].fmt, wild, 2, o);
        uint8_t ref[24];
        float tame[6] = {0, 1, 0, 1, 1, 0};
        cs_pixfmt_convert(fmts[f].fmt, tame, 2, ref);
        CHECK(memcmp(o, ref, cs_pixfmt_bytes_per_pixel(fmts[f].fmt) * 2) == 0,
              "%s: out-of-range values do not clamp to 0..1", fmts[f].name);
    }
    /* NaN has no place in a frame, but if one arrives it must become a defined code (0, as the
     * sRGB formats already do), not a float-to-integer conversion out of range (undefined
     * behaviour, caught by make test-asan). */
    float nan3[3] = {NAN, NAN, NAN};
    for (int f = 0; f < 4; f++) {
        memset(o, 0x5A, sizeof o);
        cs_pixfmt_convert(fmts[f].fmt, nan3, 1, o);
        int zero = 1;
        for (size_t b = 0; b < cs_pixfmt_bytes_per_pixel(fmts[f].fmt); b++)
            zero &= o[b] == 0;
        CHECK(zero, "%s: NaN should encode as 0", fmts[f].name);
    }
    CHECK_EQ_INT(cs_srgb_encode16(NAN), 0, "encode16(NaN)");
    free(rgb);
    free(out);
}

/* In place: `out` may be the float line itself (the MCU firmware converts
 * into the line it rendered, saving a panel line of RAM). Every format, both
 * the plain and the dithered conversion, must give the bytes a separate
 * buffer gets. */
static void test_in_place(void)
{
    static const cs_pixfmt all[] = {CS_PIX_RGB888_SRGB, CS_PIX_RGB565_SRGB, CS_PIX_RGB16_LINEAR,
                                    CS_PIX_RGB888_LINEAR, CS_PIX_RGB444_SRGB, CS_PIX_RGB332_SRGB};
    enum { W = 97 };
    float src[3 * W], line[3 * W];
    uint8_t want[6 * W];
    tc_seed(21);
    for (int i = 0; i < 3 * W; i++)
        src[i] = (float)(tc_rand() * 1.2 - 0.1);
    for (size_t f = 0; f < sizeof all / sizeof all[0]; f++)
        for (int dither = 0; dither < 2; dither++) {
            size_t n = cs_pixfmt_bytes_per_pixel(all[f]) * W;
            memcpy(line, src, sizeof line);
            if (dither) {
                cs_pixfmt_convert_dither(all[f], src, W, 5, want);
                cs_pixfmt_convert_dither(all[f], line, W, 5, (uint8_t *)line);
            } else {
                cs_pixfmt_convert(all[f], src, W, want);
                cs_pixfmt_convert(all[f], line, W, (uint8_t *)line);
            }
            CHECK(memcmp(want, line, n) == 0, "format %d%s: in-place conversion differs",
                  (int)all[f], dither ? " dithered" : "");
        }
}

static uint32_t crc_bitwise(uint32_t crc, const uint8_t *p, size_t n)
{
    crc = ~crc;
    for (size_t i = 0; i < n; i++) {
        crc ^= p[i];
        for (int b = 0; b < 8; b++)
            crc = crc & 1 ? (crc >> 1) ^ 0xEDB88320u : crc >> 1;
    }
    return ~crc;
}

static void test_crc32(void)
{
    CHECK(cs_crc32(0, "123456789", 9) == 0xCBF43926u, "crc32(\"123456789\") = %08X, expected CBF43926",
          (unsigned)cs_crc32(0, "123456789", 9));
    CHECK(cs_crc32(0, "", 0) == 0, "crc32 of nothing = %08X, expected 0", (unsigned)cs_crc32(0, "", 0));
    const char *fox = "The quick brown fox jumps over the lazy dog";
    CHECK(cs_crc32(0, fox, strlen(fox)) == 0x414FA339u, "crc32(fox) = %08X, expected 414FA339",
          (unsigned)cs_crc32(0, fox, strlen(fox)));
    uint32_t part = cs_crc32(cs_crc32(0, fox, 10), fox + 10, strlen(fox) - 10);
    CHECK(part == 0x414FA339u, "crc32 in two pieces = %08X, expected 414FA339", (unsigned)part);
    uint8_t buf[4096];
    tc_seed(9);
    for (size_t i = 0; i < sizeof buf; i++)
        buf[i] = (uint8_t)(tc_rand() * 256);
    int bad = 0;
    for (size_t n = 0; n < sizeof buf; n = n * 3 + 1)
        for (size_t off = 0; off < 8; off++)
            if (off + n <= sizeof buf && cs_crc32(0, buf + off, n) != crc_bitwise(0, buf + off, n))
                bad++;
    CHECK(bad == 0, "crc32 differs from the bitwise reference on %d random buffers", bad);
    /* Every entry of the byte table, from a zero and a busy register. */
    bad = 0;
    for (uint32_t b = 0; b < 256u; b++) {
        uint8_t one = (uint8_t)b;
        if (cs_crc32(0, &one, 1) != crc_bitwise(0, &one, 1) ||
            cs_crc32(0x5A5AC3C3u, &one, 1) != crc_bitwise(0x5A5AC3C3u, &one, 1))
            bad++;
    }
    CHECK(bad == 0, "crc32 of a single byte differs from the bitwise reference for %d bytes", bad);
}

static uint32_t srgb8_interpolated(float v)
{
    uint32_t c = (uint32_t)(cs__srgb_encode(v) * 255.0f + 0.5f);
    return c > 255u ? 255u : c;
}

/* Compares cs__srgb8 with the interpolation at the floats around b. */
static void srgb8_near(uint32_t b, int *bad, int *checked, float *first_bad)
{
    for (uint32_t d = b < 4u ? 0u : b - 4u; d <= b + 4u; d++) {
        float v = tl_float_of(d);
        (*checked)++;
        if (cs__srgb8(v) != srgb8_interpolated(v) && (*bad)++ == 0)
            *first_bad = v;
    }
}

static void test_srgb8_table(void)
{
    int bad = 0, checked = 0;
    float first_bad = 0.0f;
#if CS_CFG_SRGB8_BITS
    /* Around each bits cell's start and its step (the first cell's start
     * is where the code-0 floats below the table end). */
    for (uint32_t i = 0; i <= CS__SRGB8_BITS_CELLS; i++) {
        srgb8_near((CS__SRGB8_BITS_FIRST + i) << 16, &bad, &checked, &first_bad);
        if (i < CS__SRGB8_BITS_CELLS)
            srgb8_near(tl_bits_of(cs__srgb8_bits_step[i]), &bad, &checked, &first_bad);
    }
#else
    for (int i = 0; i <= 1024; i++) {
        /* Around the cell boundary (i / 1024)^2 and the cell's step. */
        float edge = (float)((double)i / 1024.0 * ((double)i / 1024.0));
        srgb8_near(tl_bits_of(edge), &bad, &checked, &first_bad);
        srgb8_near(tl_bits_of(i < 1024 ? cs__srgb8_step[i] : 1.0f), &bad, &checked, &first_bad);
    }
#endif
    for (uint32_t b = 1u; b < 0x3F800000u; b += 97u) { /* a sweep of (0, 1) */
        float v = tl_float_of(b);
        checked++;
        if (cs__srgb8(v) != srgb8_interpolated(v) && bad++ == 0)
            first_bad = v;
    }
    CHECK(bad == 0, "8-bit sRGB table differs from the encoder at %d of %d floats (first %a)", bad,
          checked, (double)first_bad);
    const float odd[] = {0.0f, -0.0f, -1.0f, 1.0f, 2.0f, 1e-40f, NAN, INFINITY, -INFINITY,
                         0.99999994f};
    for (size_t k = 0; k < sizeof odd / sizeof odd[0]; k++)
        CHECK(cs__srgb8(odd[k]) == srgb8_interpolated(odd[k]), "srgb8(%g): %u, not %u",
              (double)odd[k], cs__srgb8(odd[k]), srgb8_interpolated(odd[k]));
}

static uint32_t packed_interpolated(float v, uint32_t max)
{
    uint32_t c = (uint32_t)(cs__srgb_encode(v) * (float)max + 0.5f);
    return c > max ? max : c;
}

/*
 * The RGB565 threshold tables against the interpolating encoder on every
 * float in [0, 1], both depths: a proof, not a sample (about 10 s). Under
 * the sanitizers, which make it minutes, and in the x86-64-v3 build (the
 * same tables, proved by the baseline's run) every 61st float and the
 * floats around every threshold and cell boundary.
 */
static void test_rgb565_table(void)
{
#if defined(__SANITIZE_ADDRESS__) || CS__RGB888_VEC
    const uint32_t stride = 61u;
#else
    const uint32_t stride = 1u;
#endif
    uint32_t bad = 0, checked = 0;
    float first_bad = 0.0f;
    for (uint32_t b = 0u; b <= 0x3F800000u; b += stride) {
        float v = tl_float_of(b);
        checked++;
        if ((cs__rgb5(v) != packed_interpolated(v, 31u) ||
             cs__rgb6(v) != packed_interpolated(v, 63u)) && bad++ == 0)
            first_bad = v;
    }
    for (uint32_t k = 0; k < 64u; k++) {
        float points[4] = {cs__rgb6_step[k], k < 32u ? cs__rgb5_step[k] : 0.5f,
                           (float)((double)k / 64.0 * ((double)k / 64.0)),
                           (float)((double)k / 32.0 * ((double)k / 32.0))};
        for (int p = 0; p < 4; p++) {
            uint32_t c = tl_bits_of(points[p]);
            for (uint32_t d = c < 4u ? 0u : c - 4u; d <= c + 4u; d++) {
                float v = tl_float_of(d);
                checked++;
                if ((cs__rgb5(v) != packed_interpolated(v, 31u) ||
                     cs__rgb6(v) != packed_interpolated(v, 63u)) && bad++ == 0)
                    first_bad = v;
            }
        }
    }
    CHECK(bad == 0, "RGB565 tables differ from the encoder at %u of %u floats (first %a)",
          (unsigned)bad, (unsigned)checked, (double)first_bad);
    const float odd[] = {0.0f, -0.0f, -1.0f, 1.0f, 2.0f, 1e-40f, NAN, -NAN, INFINITY, -INFINITY,
                         0.99999994f, 3e38f};
    for (size_t k = 0; k < sizeof odd / sizeof odd[0]; k++)
        CHECK(cs__rgb5(odd[k]) == packed_interpolated(odd[k], 31u) &&
                  cs__rgb6(odd[k]) == packed_interpolated(odd[k], 63u),
              "rgb565 codes of %g: %u %u, not %u %u", (double)odd[k], cs__rgb5(odd[k]),
              cs__rgb6(odd[k]), packed_interpolated(odd[k], 31u), packed_interpolated(odd[k], 63u));
}

#if CS__RGB888_VEC
/* cs__srgb8_lanes of v in each lane (the others w) against cs__srgb8,
 * counted into bad; its domain is [0, 1], a finished pixel's. */
static void lanes_at(float v, float w, int *bad, int *checked, float *first_bad)
{
    if (!(v >= 0.0f && v <= 1.0f))
        return;
    for (int lane = 0; lane < 3; lane++) {
        cs__v4f x = {w, w, w, 0.0f};
        x[lane] = v;
        px16_u8 c = cs__srgb8_lanes(x);
        (*checked)++;
        bool ok = c[12] == 0;
        for (int k = 0; k < 3; k++)
            ok = ok && c[4 * k] == cs__srgb8(x[k]);
        if (!ok && (*bad)++ == 0)
            *first_bad = v;
    }
}

static void test_srgb8_lanes(void)
{
    int bad = 0, checked = 0;
    float first_bad = 0.0f;
    for (uint32_t i = 0; i <= CS__SRGB8_BITS_CELLS; i++) /* around each cell's start and step */
        for (uint32_t d = 0; d <= 8u; d++) {
            float w = (float)i / (float)CS__SRGB8_BITS_CELLS;
            lanes_at(tl_float_of(((CS__SRGB8_BITS_FIRST + i) << 16) + d - 4u), w, &bad, &checked,
                     &first_bad);
            if (i < CS__SRGB8_BITS_CELLS)
                lanes_at(tl_float_of(tl_bits_of(cs__srgb8_bits_step[i]) + d - 4u), w, &bad,
                         &checked, &first_bad);
        }
    for (uint32_t b = 0u; b <= 0x3F800000u; b += 97u) /* a sweep of [0, 1] */
        lanes_at(tl_float_of(b), tl_float_of(0x3F800000u - b), &bad, &checked, &first_bad);
    const float ends[] = {0.0f, 1e-40f, 1e-10f, 0.5f, 0x1.fffffep-1f, 1.0f};
    for (size_t k = 0; k < sizeof ends / sizeof ends[0]; k++)
        lanes_at(ends[k], ends[(k + 1) % 6], &bad, &checked, &first_bad);
    CHECK(bad == 0, "cs__srgb8_lanes differs from cs__srgb8 at %d of %d floats (first %a)", bad,
          checked, (double)first_bad);
}
#endif

int main(int argc, char **argv)
{
    (void)argc;
    TL_RUN(test_srgb_encode16);
    TL_RUN(test_srgb8_table);
#if CS__RGB888_VEC
    TL_RUN(test_srgb8_lanes);
#endif
    TL_RUN(test_rgb565_table);
    TL_RUN(test_packed_formats);
    TL_RUN(test_in_place);
    TL_RUN(test_crc32);
    return tl_summary(argv[0]);
}
