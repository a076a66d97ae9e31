/*
 * fuzz_stream.c - libFuzzer target for the cel stream decoder.
 *
 * Input: byte 0 chooses how the rest is fed (whole, byte by byte, or in
 * chunks from a small generator seeded by it; with bit 0x20, link gaps
 * (cs_stream_gap) now and then between chunks), whether the decoder starts
 * with a built-in scene on display (so that patches apply at once), and
 * whether the harness first re-seals every transaction's CRCs: random
 * mutations nearly always break a CRC, and without re-sealing the fuzzer
 * would seldom get mutated records through to validation and commit.
 * Built with small store capacities (mk/stream.mk) so limits are reached.
 *
 * Beyond "no crash, no sanitizer report, no hang", every execution checks:
 *   - feed consumes no more than it was given, events and errors are
 *     well formed (status in range, a what-string, offset <= at <= position);
 *   - the front store never changes between swaps (CRC of its used part),
 *     so a transaction in progress or dropped cannot touch what is shown;
 *   - every committed scene renders (two instants, a small frame), and
 *     encoding it again with cels_write and decoding that gives a commit
 *     with no error and the same pixels, bit for bit: whatever hostile
 *     input got committed is a fully valid scene.
 * A violated check aborts, which libFuzzer reports as a crash.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cels_write.h"
#include "celscan_private.h"

#define FUZZ_NAME "fuzz_stream"
#include "fuzz_check.h"

static cs_scene store_a, store_b, store_c, store_d;

/* What the run reached, printed at exit: proof that mutated input gets
 * through to commits and to each kind of rejection, not only to CRC errors. */
static unsigned long long n_inputs, n_commits, n_errors[CS_ERR_COUNT_];

static void print_stats(void)
{
    fprintf(stderr, "fuzz_stream: %llu inputs, %llu commits;", n_inputs, n_commits);
    for (int i = 0; i < CS_ERR_COUNT_; i++)
        if (n_errors[i])
            fprintf(stderr, " %s %llu;", cs_status_str((cs_status)i), n_errors[i]);
    fputc('\n', stderr);
}

int LLVMFuzzerInitialize(int *argc, char ***argv);
int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    atexit(print_stats);
    return 0;
}
static cs_workspace ws;

static uint32_t crc_bytes(uint32_t c, const void *p, size_t n)
{
    return cs_crc32(c, p, n);
}

/* CRC of every used field of a store. */
static uint32_t scene_crc(const cs_scene *s)
{
    uint32_t c = crc_bytes(0, s, offsetof(cs_scene, cels));
    c = crc_bytes(c, s->cels, s->cel_count * sizeof s->cels[0]);
    c = crc_bytes(c, s->regions, s->region_count * sizeof s->regions[0]);
    c = crc_bytes(c, s->contours, s->contour_count * sizeof s->contours[0]);
    c = crc_bytes(c, s->points, s->point_count * sizeof s->points[0]);
    c = crc_bytes(c, s->intervals, s->point_count * sizeof s->intervals[0]);
    c = crc_bytes(c, s->funcs, s->func_count * sizeof s->funcs[0]);
    c = crc_bytes(c, s->tracks, s->track_count * sizeof s->tracks[0]);
    c = crc_bytes(c, s->key_times, s->key_count * sizeof s->key_times[0]);
    return crc_bytes(c, s->key_values, s->value_count * sizeof s->key_values[0]);
}

enum { FW = 16, FH = 12 };

static cs_status render(const cs_scene *s, float t, float *out)
{
    cs_renderer r;
    cs_render_opts o = {FW, FH, CS_AA_SUBSCAN, 3, t};
    cs_error err;
    cs_status st = fuzz_render(&r, &ws, s, &o, out, &err);
    return st != CS_OK ? st : r.sticky.status;
}

/* A committed scene must be valid through and through: it renders, and it
 * survives being encoded and decoded again with the same pixels. */
static void check_committed(const cs_scene *s)
{
    static float a[FW * FH * 3], b[FW * FH * 3];
    cels_buf buf;
    cels_buf_init(&buf);
    REQUIRE(cels_encode_scene(&buf, s) == 0);
    cs_stream st;
    REQUIRE(cs_stream_init(&st, &store_c, false, &store_d) == CS_OK);
    size_t used = 0;
    cs_stream_event ev = cs_stream_feed(&st, buf.data, buf.len, &used);
    REQUIRE(ev == CS_STREAM_COMMIT && used == buf.len);
    REQUIRE(cs_stream_swap(&st) == CS_OK);
    REQUIRE(cs_stream_finish(&st) == CS_STREAM_MORE);
    const cs_scene *again = cs_stream_scene(&st);
    REQUIRE(again && again->cel_count == s->cel_count && again->point_count == s->point_count &&
            again->track_count == s->track_count && again->value_count == s->value_count &&
            again->func_count == s->func_count);
    const float times[2] = {0.3f, 2.0f};
    for (int i = 0; i < 2; i++) {
        cs_status sa = render(s, times[i], a);
        cs_status sb = render(again, times[i], b);
        REQUIRE(sa == sb);
        if (sa == CS_OK)
            REQUIRE(memcmp(a, b, sizeof a) == 0);
    }
    cels_buf_free(&buf);
}

static void check_error(const cs_stream *st)
{
    const cs_stream_error *e = cs_stream_last_error(st);
    REQUIRE(e && e->what && e->what[0]);
    REQUIRE(e->status > CS_OK && e->status < CS_ERR_COUNT_);
    n_errors[e->status]++;
    REQUIRE(e->offset <= e->at && e->at <= st->offset);
}

/* A small scene on display before any input, so patches apply at once. */
static void builtin(cs_scene *s)
{
    cs_error e;
    cs_scene_init(s, 100, 100);
    cs_affine id = {1, 0, 0, 1, 0, 0};
    cs_scene_add_cel(s, &id, NULL, NULL, &e);
    cs_paint p = {{1, 0.5f, 0.25f}, {1, 1, 1}, 1};
    cs_scene_add_region(s, CS_FILL_NONZERO, &p, &e);
    cs_point sq[4] = {{10, 10, 1}, {30, 10, 1}, {30, 30, 1}, {10, 30, 1}};
    cs_scene_add_contour(s, 1, 4, sq, NULL, &e);
    cs_scene_add_track(s, CS_TRACK_TRANSFORM, 0, CS_EASE_SMOOTH, &e);
    cs_scene_add_key(s, 0, (float[6]){1, 0, 0, 1, 0, 0}, &e);
    cs_scene_add_key(s, 1, (float[6]){1, 0, 0, 1, 50, 20}, &e);
}

static void put_u32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)v;
    p[1] = (uint8_t)(v >> 8);
    p[2] = (uint8_t)(v >> 16);
    p[3] = (uint8_t)(v >> 24);
}

/* Recomputes header and trailer CRCs of every transaction that fits. */
static void reseal(uint8_t *d, size_t n)
{
    size_t i = 0;
    while (i + 16 <= n) {
        if (memcmp(d + i, "CSTX", 4) != 0 && memcmp(d + i, "CELS", 4) != 0) {
            i++;
            continue;
        }
        put_u32(d + i + 12, cs_crc32(0, d + i, 12));
        uint32_t len = (uint32_t)d[i + 8] | (uint32_t)d[i + 9] << 8 | (uint32_t)d[i + 10] << 16 |
                       (uint32_t)d[i + 11] << 24;
        if (d[i + 1] == 'S' && len <= n - i - 16 && n - i - 16 - len >= 4) {
            put_u32(d + i + 16 + len, cs_crc32(0, d + i, 16 + (size_t)len));
            i += 16 + (size_t)len + 4;
        } else {
            i += 16;
        }
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1)
        return 0;
    n_inputs++;
    uint8_t mode = data[0];
    data++;
    size--;
    static uint8_t sealed[1 << 20];
    if ((mode & 0x40) && size <= sizeof sealed) {
        memcpy(sealed, data, size);
        reseal(sealed, size);
        data = sealed;
    }
    bool front_valid = (mode & 0x80) != 0;
    if (front_valid)
        builtin(&store_a);
    cs_stream st;
    REQUIRE(cs_stream_init(&st, &store_a, front_valid, &store_b) == CS_OK);
    uint32_t front_crc = front_valid ? scene_crc(&store_a) : 0;
    uint32_t rng = 0x9E3779B9u ^ mode;
    size_t off = 0;
    int events = 0, gaps = 0;
    for (int phase = 0; phase < 3;) {
        cs_stream_event ev;
        size_t used = 0;
        if (phase == 0) { /* the input, in chunks */
            if (off == size) {
                phase++;
                continue;
            }
            size_t want = size - off;
            rng = rng * 1664525u + 1013904223u;
            if ((mode & 0x20) && (rng >> 28) == 0) { /* the link lost bytes here */
                ev = cs_stream_gap(&st);
                gaps++;
                goto event;
            }
            if ((mode & 3) == 1)
                want = 1;
            else if ((mode & 3) >= 2)
                want = 1 + (rng >> 16) % ((mode & 3) == 2 ? 7u : 300u);
            if (want > size - off)
                want = size - off;
            ev = cs_stream_feed(&st, data + off, want, &used);
            REQUIRE(used <= want);
            off += used;
        } else if (phase == 1) { /* errors still queued */
            ev = cs_stream_feed(&st, NULL, 0, &used);
        } else { /* end of input */
            ev = cs_stream_finish(&st);
        }
    event:
        REQUIRE(used == 0 || phase == 0);
        /* White box: inside a body the position never passes the length. */
        REQUIRE(st.body_pos <= st.body_len);
        if (cs_stream_scene(&st))
            REQUIRE(scene_crc(cs_stream_scene(&st)) == front_crc);
        if (ev == CS_STREAM_COMMIT) {
            REQUIRE(cs_stream_swap(&st) == CS_OK);
            const cs_scene *s = cs_stream_scene(&st);
            REQUIRE(s);
            check_committed(s);
            front_crc = scene_crc(s);
            n_commits++;
        } else if (ev == CS_STREAM_ERROR) {
            check_error(&st);
        } else if (phase > 0) {
            phase++;
        }
        if (ev != CS_STREAM_MORE)
            REQUIRE(++events <= (int)size + 4 + 2 * gaps); /* about one per byte or gap */
    }
    REQUIRE(st.offset == size);
    if (cs_stream_scene(&st))
        REQUIRE(scene_crc(cs_stream_scene(&st)) == front_crc);
    return 0;
}
