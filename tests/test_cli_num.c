/*
 * test_cli_num.c - the typed-number reader every host program shares
 * (tools/cli_num.c): what it takes, and the texts strtol, strtod, atoi and
 * sscanf would have let through that it must refuse.
 *
 * The reader is compiled into this test directly, so the plain and the
 * sanitizer builds of the tests (Makefile: test-unit, test-asan) need no
 * rule of their own for it.
 */
#include "../tools/cli_num.c"

#include "testlib.h"

static bool int_ok(const char *s, int base, long lo, long hi, long want)
{
    long v = -12345;
    const char *rest = cli_int(s, base, '\0', lo, hi, &v);
    return rest != NULL && *rest == '\0' && v == want;
}

static bool int_refused(const char *s, int base, long lo, long hi)
{
    long v = -12345;
    return cli_int(s, base, '\0', lo, hi, &v) == NULL && v == -12345;
}

static void test_int(void)
{
    CHECK(int_ok("0", 10, 0, 10, 0), "0");
    CHECK(int_ok("42", 10, 0, 100, 42), "42");
    CHECK(int_ok("007", 10, 0, 100, 7), "leading zeros are decimal");
    CHECK(int_ok("-3", 10, -5, 5, -3), "negative where the range allows");
    CHECK(int_ok("1d50", 16, 0, 0xffff, 0x1d50), "hex digits in base 16");
    CHECK(int_ok("0x1F", 0, 0, 255, 31), "base 0: hex after 0x");
    CHECK(int_ok("010", 0, 0, 255, 10), "base 0: a leading zero is not octal");
    CHECK(int_ok("-0x10", 0, -100, 0, -16), "base 0: negative hex");
    CHECK(int_ok("2147483647", 10, 0, 2147483647L, 2147483647L), "top of the range");
    const char *bad[] = {"", " 5", "+5", "5 ", "abc", "5x", "1e3", "0.5", "--5", "- 5",
                         "99999999999999999999999", "-99999999999999999999999"};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++)
        CHECK(int_refused(bad[i], 10, -1000, 1000), "'%s' refused", bad[i]);
    CHECK(int_refused("-3", 10, 0, 10), "a sign where the range has no negatives");
    CHECK(int_refused("11", 10, 0, 10), "above the range");
    CHECK(int_refused("0x1d50", 16, 0, 0xffff), "base 16 takes digits only");
    CHECK(int_refused("0x0x1", 0, 0, 100), "base 0: one prefix");
    CHECK(int_refused("0x", 0, 0, 100), "base 0: a prefix with no digits");
    CHECK(int_refused("12", 8, 0, 100), "an unsupported base");
    long v = 0;
    const char *rest = cli_int("640x360", 10, 'x', 1, 4096, &v);
    CHECK(rest && v == 640 && strcmp(rest, "360") == 0, "stops at the separator and steps over it");
    CHECK(cli_int("640", 10, 'x', 1, 4096, &v) == NULL, "separator missing");
    CHECK(cli_int("640:1", 10, 'x', 1, 4096, &v) == NULL, "wrong separator");
}

static void test_real(void)
{
    double v = -1.0;
    CHECK(cli_real("0.25", '\0', 0.0, 1.0, &v) && v == 0.25, "0.25");
    CHECK(cli_real(".5", '\0', 0.0, 1.0, &v) && v == 0.5, ".5");
    CHECK(cli_real("-2.5e1", '\0', -100.0, 0.0, &v) && v == -25.0, "exponent and sign");
    CHECK(cli_real("1e-400", '\0', 0.0, 1.0, &v) && v < 1e-300, "underflow is near enough zero");
    const char *bad[] = {"", " 1", "+1", "nan", "inf", "-inf", "1e400", "0x1p3", "1.5.", "1,5",
                         ".", "-", "abc", "1 "};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        v = -7.0;
        CHECK(cli_real(bad[i], '\0', -1e9, 1e9, &v) == NULL && v == -7.0, "'%s' refused", bad[i]);
    }
    CHECK(cli_real("2", '\0', 0.0, 1.0, &v) == NULL, "above the range");
    const char *rest = cli_real("1.5,-2", ',', -10.0, 10.0, &v);
    CHECK(rest && v == 1.5 && strcmp(rest, "-2") == 0, "a pair's first half");
}

static void test_size(void)
{
    int w = 0, h = 0;
    CHECK(cli_size("1920x1080", 4096, 4096, &w, &h) && w == 1920 && h == 1080, "1920x1080");
    const char *bad[] = {"", "x", "64", "64x", "x64", "0x64", "64x0", "64x64x", "64X64", " 64x64",
                         "64x 64", "64x+64", "-64x64", "4097x1", "1x4097", "64.5x64"};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        w = h = -1;
        CHECK(!cli_size(bad[i], 4096, 4096, &w, &h) && w == -1 && h == -1, "'%s' refused",
              bad[i]);
    }
}

static void test_aa(void)
{
    cs_aa_mode m = CS_AA_SUBSCAN;
    int sub = 0;
    CHECK(cli_aa("none", &m, &sub) && m == CS_AA_NONE, "none");
    CHECK(cli_aa("exact", &m, &sub) && m == CS_AA_EXACT, "exact");
    CHECK(cli_aa("5", &m, &sub) && m == CS_AA_SUBSCAN && sub == 5, "5 sub-scanlines");
    char top[16];
    snprintf(top, sizeof top, "%d", CS_CFG_MAX_SUBSCANLINES);
    CHECK(cli_aa(top, &m, &sub) && sub == CS_CFG_MAX_SUBSCANLINES, "the configured maximum");
    snprintf(top, sizeof top, "%d", CS_CFG_MAX_SUBSCANLINES + 1);
    const char *bad[] = {"0", "-1", "abc", "", "16x", "Exact", top};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++)
        CHECK(!cli_aa(bad[i], &m, &sub), "'%s' refused", bad[i]);
}

int main(int argc, char **argv)
{
    (void)argc;
    TL_RUN(test_int);
    TL_RUN(test_real);
    TL_RUN(test_size);
    TL_RUN(test_aa);
    return tl_summary(argv[0]);
}
