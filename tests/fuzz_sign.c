/*
 * fuzz_sign.c - libFuzzer target for signed streams: celfw's framer, trust
 * check and decoder seam (firmware/linux/celfw_frame.c, celfw_trust.c,
 * celfw_stream.c) and the envelope code they share with the signer
 * (tools/cels_sign.c), plus the core decoder unwrapping the same bytes.
 *
 * Input: byte 0 chooses the chunking, whether the fixed test key
 * (tests/sign_test_key.h, the key of the seeds in tests/fuzz-sign-corpus/)
 * is trusted, and whether every header, trailer and envelope CRC is made
 * right again first (envelopes from the inside out), so that mutations get
 * past the CRCs to the signature and sequence checks. The rest is what a
 * TCP client would send.
 *
 * Beyond "no crash, no sanitizer report, no hang", every execution checks:
 *   - the framer consumes no more than it was given, hands out frames that
 *     start with their header and are exactly 16 + L + 4 bytes, and offsets
 *     that only grow;
 *   - with the key trusted, nothing but an envelope that verifies under it,
 *     with a sequence above the last one applied, reaches the decoder, and
 *     the applied sequences only grow;
 *   - the scene on display changes only at a commit (CRC of its used part);
 *   - the core decoder fed the same bytes stays within them.
 * A violated check aborts, which libFuzzer reports as a crash.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cels_sign.h"
#include "celfw_frame.h"
#include "celfw_stream.h"
#include "celfw_trust.h"
#include "celscan_private.h"
#include "sign_test_key.h"

#define FUZZ_NAME "fuzz_sign"
#include "fuzz_check.h"

static cs_scene store[2], core_a, core_b;
static cels_public_key test_pub;
static char pub_path[64];
static unsigned long long n_inputs, n_frames, n_commits, n_verdicts[6];

static void print_stats(void)
{
    fprintf(stderr, "fuzz_sign: %llu inputs, %llu frames, %llu commits; verdicts:", n_inputs, n_frames,
            n_commits);
    for (int v = 0; v < 6; v++)
        fprintf(stderr, " %s %llu;", celfw_verdict_word((celfw_verdict)v), n_verdicts[v]);
    fputc('\n', stderr);
    if (pub_path[0])
        unlink(pub_path);
}

int LLVMFuzzerInitialize(int *argc, char ***argv);
int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    if (!cels_sign_init())
        abort();
    cels_secret_key k;
    sign_test_key(&k);
    test_pub = k.pub;
    /* celfw reads trusted keys from files: write the test key's once */
    snprintf(pub_path, sizeof pub_path, "/tmp/fuzz-sign-%d.pub", (int)getpid());
    FILE *f = fopen(pub_path, "w");
    if (!f)
        abort();
    fputs("celscan-ed25519-public-key-1 ", f);
    for (int i = 0; i < CELS_PUBLIC_KEY_SIZE; i++)
        fprintf(f, "%02x", k.pub.pk[i]);
    fputc('\n', f);
    fclose(f);
    chmod(pub_path, 0644);
    atexit(print_stats);
    return 0;
}

static uint32_t rd32(const uint8_t *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static void put32(uint8_t *p, uint32_t v)
{
    for (int i = 0; i < 4; i++)
        p[i] = (uint8_t)(v >> (8 * i));
}

static uint32_t scene_crc(const cs_scene *s)
{
    uint32_t c = cs_crc32(0, s, offsetof(cs_scene, cels));
    c = cs_crc32(c, s->cels, s->cel_count * sizeof s->cels[0]);
    c = cs_crc32(c, s->regions, s->region_count * sizeof s->regions[0]);
    c = cs_crc32(c, s->contours, s->contour_count * sizeof s->contours[0]);
    return cs_crc32(c, s->points, s->point_count * sizeof s->points[0]);
}

/* Makes every header's CRC and every trailer that fits right, last frames first (inner before outer). */
static void reseal(uint8_t *d, size_t n)
{
    for (size_t i = n >= 16 ? n - 16 + 1 : 0; i-- > 0;) {
        bool txn = !memcmp(d + i, "CSTX", 4) || !memcmp(d + i, "CSSG", 4);
        if (!txn && memcmp(d + i, "CELS", 4) != 0)
            continue;
        put32(d + i + 12, cs_crc32(0, d + i, 12));
        uint64_t len = rd32(d + i + 8);
        if (txn && len + 20 <= n - i)
            put32(d + i + 16 + len, cs_crc32(0, d + i, 16 + (size_t)len));
    }
}

/* The core decoder on the same bytes: it unwraps envelopes and stays within its input. */
static void core_decode(const uint8_t *data, size_t size)
{
    cs_stream st;
    cs_scene_init(&core_a, 100, 100);
    REQUIRE(cs_stream_init(&st, &core_a, true, &core_b) == CS_OK);
    for (int guard = 0; guard < (int)size + 8; guard++) {
        size_t used = 0;
        cs_stream_event ev = cs_stream_feed(&st, data, size, &used);
        REQUIRE(used <= size);
        data += used;
        size -= used;
        if (ev == CS_STREAM_MORE && size == 0 && cs_stream_finish(&st) == CS_STREAM_MORE)
            break;
        if (ev == CS_STREAM_COMMIT)
            cs_stream_swap(&st);
        if (ev == CS_STREAM_ERROR) {
            const cs_stream_error *e = cs_stream_last_error(&st);
            REQUIRE(e->what && e->offset <= e->at && e->at <= st.offset);
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
    bool trusted = (mode & 0x80) != 0;
    celfw_trust *t = celfw_trust_new();
    REQUIRE(t);
    char err[400];
    if (trusted)
        REQUIRE(celfw_trust_add_key(t, pub_path, err, sizeof err) == 0);
    celfw_stream *cs = celfw_stream_new();
    celfw_framer f;
    celfw_framer_init(&f, "fuzz");
    cs_scene_init(&store[0], 100, 100);
    int front = 0;
    uint32_t front_crc = scene_crc(&store[0]);
    uint64_t last_seq = 0, last_offset = 0;
    uint32_t rng = 0x9E3779B9u ^ mode;
    size_t off = 0;
    bool ended = false;
    while (!ended) {
        celfw_frame fr;
        if (off < size) {
            size_t want = size - off;
            rng = rng * 1664525u + 1013904223u;
            if ((mode & 3) == 1)
                want = 1;
            else if ((mode & 3) >= 2)
                want = 1 + (rng >> 16) % ((mode & 3) == 2 ? 7u : 300u);
            if (want > size - off)
                want = size - off;
            size_t used = celfw_framer_push(&f, data + off, want, &fr);
            REQUIRE(used <= want);
            off += used;
            if (fr.kind == CELFW_FRAME_NONE)
                continue;
        } else if (!celfw_framer_end(&f, &fr)) {
            break;
        } else {
            ended = true;
        }
        REQUIRE(fr.offset >= last_offset || fr.kind == CELFW_FRAME_ERROR);
        if (fr.kind == CELFW_FRAME_ERROR) {
            REQUIRE(fr.what && fr.offset <= fr.at && fr.at <= off);
            continue;
        }
        last_offset = fr.offset;
        n_frames++;
        REQUIRE(fr.len >= 16 && fr.offset + fr.len <= off);
        REQUIRE(fr.kind == CELFW_FRAME_STREAM ? fr.len == 16 : fr.len == 16 + (size_t)rd32(fr.data + 8) + 4);
        REQUIRE(!memcmp(fr.data, fr.kind == CELFW_FRAME_STREAM ? "CELS" : fr.kind == CELFW_FRAME_TXN ? "CSTX" : "CSSG",
                        4));
        celfw_trust_txn tx = {.txn = fr.data, .len = fr.len, .key = -1};
        if (fr.kind != CELFW_FRAME_STREAM) {
            celfw_verdict v = celfw_trust_check(t, fr.data, fr.len, fr.kind == CELFW_FRAME_SIGNED, &tx);
            REQUIRE(v <= CELFW_TRUST_MALFORMED);
            n_verdicts[v]++;
            if (v != CELFW_TRUST_PASS)
                continue;
            REQUIRE(tx.txn >= fr.data && tx.txn + tx.len <= fr.data + fr.len);
            if (trusted) {
                /* only a verified envelope with a fresh sequence passes */
                cels_envelope e;
                REQUIRE(fr.kind == CELFW_FRAME_SIGNED && tx.key == 0);
                REQUIRE(cels_envelope_parse(fr.data, fr.len, &e) == NULL && cels_envelope_verify(&e, &test_pub));
                REQUIRE(e.sequence == tx.sequence && tx.sequence > last_seq);
            }
        }
        celfw_stream_error se;
        celfw_stream_result r =
            celfw_stream_frame(cs, tx.txn, tx.len, fr.offset + tx.offset, &store[front], &store[front ^ 1], &se);
        if (r == CELFW_STREAM_COMMIT) {
            front ^= 1;
            front_crc = scene_crc(&store[front]);
            n_commits++;
            REQUIRE(celfw_trust_applied(t, &tx, err, sizeof err) == 0);
            if (tx.key >= 0)
                last_seq = tx.sequence;
        } else {
            REQUIRE(scene_crc(&store[front]) == front_crc);
        }
    }
    celfw_framer_free(&f);
    celfw_stream_free(cs);
    celfw_trust_free(t);
    core_decode(data, size);
    return 0;
}
