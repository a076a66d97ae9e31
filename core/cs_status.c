/*
 * cs_status.c - status descriptions and the stream error line.
 *
 * The strings are what users read in celsim's and the firmware's error
 * messages, so they say what was expected, not just that something failed.
 * cs_stream_error_text puts a decoder error in the one line that celsim,
 * celc, celfw and the MCU firmware print (no libc here, so it formats its
 * numbers itself). The CRC-32 is in cs_crc32.c.
 */
#include "cs_internal.h"

static const char *const status_text[CS_ERR_COUNT_] = {
    [CS_OK] = "ok",
    [CS_ERR_ARG] = "invalid argument",
    [CS_ERR_STATE] = "call out of order",
    [CS_ERR_NONFINITE] = "number is NaN or infinite",
    [CS_ERR_RANGE] = "coordinate magnitude beyond the limit of 1e6",
    [CS_ERR_DEGREE] = "degree must be 1, 2 or 3",
    [CS_ERR_TOO_FEW_POINTS] = "a contour needs at least degree+1 control points",
    [CS_ERR_WEIGHT] = "weight must be > 0",
    [CS_ERR_INTERVAL] = "knot interval must be finite and >= 0",
    [CS_ERR_ZERO_RUN] = "at most degree-1 zero knot intervals may stand in a row",
    [CS_ERR_DEGENERATE] = "every knot interval of the contour is zero",
    [CS_ERR_FILL_RULE] = "fill rule must be nonzero or evenodd",
    [CS_ERR_PAINT] = "paint components must lie in 0..1",
    [CS_ERR_SIZE] = "size must be > 0 and within the configured capacity",
    [CS_ERR_CAP_CELS] = "scene store full: too many cels",
    [CS_ERR_CAP_REGIONS] = "scene store full: too many regions",
    [CS_ERR_CAP_CONTOURS] = "scene store full: too many contours",
    [CS_ERR_CAP_POINTS] = "scene store full: too many control points",
    [CS_ERR_CAP_SEGMENTS] = "workspace full: too many segments in the frame",
    [CS_ERR_CAP_PIECES] = "workspace full: too many monotone pieces in the frame",
    [CS_ERR_CAP_CROSSINGS] = "workspace full: too many crossings on one scanline",
    [CS_ERR_IO] = "the display refused a line",
    [CS_ERR_CAP_FUNCS] = "scene store full: too many paint functions (gradients, maps)",
    [CS_ERR_FUNC] = "paint function malformed: kind, stops (1..max, offsets 0..1 in order) "
                    "or degenerate geometry",
    [CS_ERR_CSG] = "CSG program malformed: operand out of range, operator without two inputs, "
                   "or not exactly one result",
    [CS_ERR_CAP_CACHE] = "cache buffer too small for the pre-combined cels",
    [CS_ERR_INDEX] = "no such cel, region or contour",
    [CS_ERR_COUNT] = "point count differs from the contour's",
    [CS_ERR_TRACK] = "track kind must be 0..6 and ease linear (0), smooth (1), hold (2) or cubic (3)",
    [CS_ERR_KEY_ORDER] = "key times must be strictly increasing",
    [CS_ERR_CAP_TRACKS] = "scene store full: too many tracks",
    [CS_ERR_CAP_KEYS] = "scene store full: too many keys or key values",
    [CS_ERR_CAP_ANIM] = "animated contour has more points than the workspace holds",
    [CS_ERR_GROUP] = "cel parent would make a cycle or a group chain deeper than CS_CFG_MAX_GROUP_DEPTH",
    [CS_ERR_STREAM_SYNC] = "bytes outside any transaction were skipped",
    [CS_ERR_STREAM_VERSION] = "unsupported cel stream major version",
    [CS_ERR_STREAM_CRC] = "transaction CRC mismatch: data damaged",
    [CS_ERR_STREAM_TRUNCATED] = "transaction cut short",
    [CS_ERR_STREAM_TOO_BIG] = "transaction longer than the decoder accepts",
    [CS_ERR_STREAM_RECORD] = "malformed record: length, class, order or layout",
    [CS_ERR_STREAM_GAP] = "bytes lost on the link (receive overrun)",
};

const char *cs_status_str(cs_status status)
{
    if ((unsigned)status >= (unsigned)CS_ERR_COUNT_ || !status_text[status])
        return "unknown status";
    return status_text[status];
}

/* Error text is a cold path on boards whose flash is nearly full: compiled
 * for size, whatever the optimisation level of the rest. */
#if defined(__GNUC__)
#define TEXT_COLD __attribute__((cold))
#else
#define TEXT_COLD
#endif

/* Text into buf[0..len), counting what did not fit as well. */
typedef struct text_out {
    char *buf;
    size_t len, n;
} text_out;

static TEXT_COLD void put_char(text_out *t, char c)
{
    if (t->n + 1 < t->len)
        t->buf[t->n] = c;
    t->n++;
}

static TEXT_COLD void put_str(text_out *t, const char *s)
{
    while (*s)
        put_char(t, *s++);
}

/* Decimal by subtracting powers of ten, made by multiplying: a 64-bit
 * division would call a libgcc helper on 32-bit targets (check-core
 * forbids it), and a table of them would cost flash the boards lack. */
static TEXT_COLD void put_u64(text_out *t, uint64_t v)
{
    int top = 0; /* v has top + 1 digits */
    for (uint64_t p = 10u; top < 19 && p <= v; p *= 10u)
        top++;
    for (int i = top; i >= 0; i--) {
        uint64_t p = 1u;
        for (int k = 0; k < i; k++)
            p *= 10u;
        char c = '0';
        while (v >= p) {
            v -= p;
            c++;
        }
        put_char(t, c);
    }
}

static TEXT_COLD bool same_text(const char *a, const char *b)
{
    while (*a && *a == *b) {
        a++;
        b++;
    }
    return *a == *b;
}

TEXT_COLD size_t cs_stream_error_text(const cs_stream_error *e, uint64_t base, char *buf,
                                      size_t len)
{
    text_out t = {buf, len, 0};
    const char *status = cs_status_str(e->status);
    put_str(&t, status);
    if (e->what && !same_text(e->what, status)) {
        put_str(&t, ": ");
        put_str(&t, e->what);
    }
    if (e->where.cel >= 0) {
        static const char *const label[4] = {" (cel ", ", region ", ", contour ", ", item "};
        const int32_t at[4] = {e->where.cel, e->where.region, e->where.contour, e->where.item};
        for (int i = 0; i < 4; i++) {
            if (at[i] >= 0) {
                put_str(&t, label[i]);
                put_u64(&t, (uint64_t)at[i]);
            }
        }
        put_str(&t, ")");
    }
    bool sync = e->status == CS_ERR_STREAM_SYNC;
    put_str(&t, sync ? " (skipping from byte " : " (transaction at byte ");
    put_u64(&t, base + e->offset);
    put_str(&t, sync ? ")" : " dropped)");
    if (len > 0)
        buf[t.n < len ? t.n : len - 1] = '\0';
    return t.n;
}
