/*
 * test_trust.c - signed streams in process: key files (modes, refusals),
 * the envelope (what the signature covers, tampering, malformed frames),
 * signing whole streams, celfw's trust verdicts and its state file
 * (persisted, corrupt, missing, wrong mode), the framer that cuts inputs
 * into whole frames, and the log rate limit.
 *
 * Independent truths: the signature is checked against the message layout
 * docs/STREAM.md gives, rebuilt here byte by byte and handed to libsodium
 * directly; the key id against BLAKE2b computed here; the framer's reports
 * against the core decoder's reports on the same damaged bytes; a signed
 * stream decodes (core unwrapping) to the very store its unsigned original
 * gives.
 *
 *   test_trust                 run the tests
 *   test_trust --seeds DIR     write the fuzz seeds of tests/fuzz_sign.c
 */
#include <errno.h>
#include <sodium.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "celfw_frame.h"
#include "celfw_log.h"
#include "celfw_stream.h"
#include "celfw_trust.h"
#include "cels_read.h"
#include "cels_sign.h"
#include "scene_equal.h"
#include "sign_test_key.h"
#include "testlib.h"

static cs_scene scene_a, scene_b, scene_c;

static uint32_t rd32(const uint8_t *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static void wr32(uint8_t *p, uint32_t v)
{
    for (int i = 0; i < 4; i++)
        p[i] = (uint8_t)(v >> (8 * i));
}

/* A small scene: background and one square of `shade`. */
static void square_scene(cs_scene *s, float shade)
{
    cs_error e;
    const float bg[3] = {0.1f, 0.1f, 0.2f};
    const cs_affine id = {1, 0, 0, 1, 0, 0};
    const cs_paint p = {{shade, 0.2f, 0.2f}, {1, 1, 1}, 1.0f};
    const cs_point pts[4] = {{10, 10, 1}, {60, 10, 1}, {60, 60, 1}, {10, 60, 1}};
    cs_scene_init(s, 100, 100);
    cs_scene_set_background(s, bg);
    cs_scene_add_cel(s, &id, NULL, (const float[3]){0, 0, 0}, &e);
    cs_scene_add_region(s, CS_FILL_NONZERO, &p, &e);
    cs_scene_add_contour(s, 1, 4, pts, NULL, &e);
}

/* A patch transaction moving cel 0 by dx. */
static void patch(cels_buf *b, float dx)
{
    cels_txn_begin(b);
    cels_rec_begin(b, CS_REC_CEL_TRANSFORM);
    cels_put_u32(b, 0);
    const float m[6] = {1, 0, 0, 1, dx, 0};
    cels_put_f32s(b, m, 6);
    cels_rec_end(b);
    cels_rec_commit(b);
    cels_txn_end(b);
}

/* After bytes of an envelope's inner transaction changed: its CRCs made right again. */
static void reseal(uint8_t *env, size_t len)
{
    uint8_t *inner = env + CS_WIRE_HEADER_SIZE + CS_WIRE_SIG_BLOCK_SIZE;
    size_t inner_len = len - CS_WIRE_HEADER_SIZE - CS_WIRE_SIG_BLOCK_SIZE - CS_WIRE_TRAILER_SIZE;
    wr32(inner + inner_len - 4, cs_crc32(0, inner, inner_len - 4));
    wr32(env + len - 4, cs_crc32(0, env, len - 4));
}

static void test_keys(const char *dir)
{
    char name[300], key[320], pub[320], err[400];
    snprintf(name, sizeof name, "%s/k", dir);
    snprintf(key, sizeof key, "%s.key", name);
    snprintf(pub, sizeof pub, "%s.pub", name);
    umask(0); /* keygen must set the modes itself, whatever the umask */
    CHECK(cels_keygen(name, err, sizeof err) == 0, "keygen: %s", err);
    umask(022);
    struct stat st;
    CHECK(stat(key, &st) == 0 && (st.st_mode & 07777) == 0600, "NAME.key is mode 0600 (%o)",
          (unsigned)(st.st_mode & 07777));
    CHECK(stat(pub, &st) == 0 && (st.st_mode & 07777) == 0644, "NAME.pub is mode 0644 (%o)",
          (unsigned)(st.st_mode & 07777));
    uint8_t before[200] = {0};
    FILE *f = fopen(key, "rb");
    size_t n = f ? fread(before, 1, sizeof before, f) : 0;
    if (f)
        fclose(f);
    CHECK(cels_keygen(name, err, sizeof err) != 0 && strstr(err, "exists"), "keygen refuses to overwrite: %s",
          err);
    uint8_t after[200] = {0};
    f = fopen(key, "rb");
    CHECK(f && fread(after, 1, sizeof after, f) == n && !memcmp(before, after, n), "the key is unchanged");
    if (f)
        fclose(f);

    cels_secret_key sk;
    cels_public_key pk;
    CHECK(cels_read_secret_key(key, &sk, err, sizeof err) == 0, "read NAME.key: %s", err);
    CHECK(cels_read_public_key(pub, &pk, err, sizeof err) == 0, "read NAME.pub: %s", err);
    CHECK(!memcmp(sk.pub.pk, pk.pk, sizeof pk.pk) && !memcmp(sk.pub.id, pk.id, sizeof pk.id),
          "the private key's public half is NAME.pub");
    uint8_t h[32];
    crypto_generichash(h, sizeof h, pk.pk, sizeof pk.pk, NULL, 0);
    CHECK(!memcmp(h, pk.id, CS_WIRE_SIG_KEYID_SIZE), "key id = first 8 bytes of BLAKE2b-256(key)");

    chmod(key, 0640);
    CHECK(cels_read_secret_key(key, &sk, err, sizeof err) != 0 && strstr(err, "mode 0640"),
          "a private key the group can read is refused: %s", err);
    chmod(key, 0600);
    chmod(pub, 0666);
    CHECK(cels_read_public_key(pub, &pk, err, sizeof err) != 0 && strstr(err, "mode 0666"),
          "a public key others can write is refused: %s", err);
    chmod(pub, 0644);
    CHECK(cels_read_public_key(key, &pk, err, sizeof err) != 0 && strstr(err, "not a celscan key file"),
          "a private key is no public key: %s", err);
    char junk[310];
    snprintf(junk, sizeof junk, "%s/junk.key", dir);
    f = fopen(junk, "w");
    if (f) {
        fputs("celscan-ed25519-secret-key-1 0011\n", f);
        fclose(f);
    }
    chmod(junk, 0600);
    CHECK(cels_read_secret_key(junk, &sk, err, sizeof err) != 0 && strstr(err, "not a celscan key file"),
          "a short key is refused: %s", err);
    snprintf(junk, sizeof junk, "%s/none.pub", dir);
    CHECK(cels_read_public_key(junk, &pk, err, sizeof err) != 0 && strstr(err, "No such file"),
          "a missing key file: %s", err);
}

static void test_envelope(void)
{
    cels_secret_key k, other;
    sign_test_key(&k);
    uint8_t seed[CELS_SEED_SIZE];
    memset(seed, 0x5a, sizeof seed);
    cels_secret_key_from_seed(seed, &other);
    cels_buf t, e;
    cels_buf_init(&t);
    cels_buf_init(&e);
    patch(&t, 12.5f);
    CHECK(cels_sign_txn(&e, &k, 0x0102030405060708ull, t.data, t.len) == 0, "sign");
    CHECK(e.len == CS_WIRE_HEADER_SIZE + CS_WIRE_SIG_BLOCK_SIZE + t.len + CS_WIRE_TRAILER_SIZE,
          "envelope = header, signature block, transaction, trailer (%zu bytes)", e.len);
    CHECK(!memcmp(e.data, "CSSG", 4) && rd32(e.data + 8) == CS_WIRE_SIG_BLOCK_SIZE + t.len,
          "CSSG header with the body length");
    cels_envelope env;
    const char *why = cels_envelope_parse(e.data, e.len, &env);
    CHECK(why == NULL, "parse: %s", why ? why : "");
    if (why)
        goto out;
    CHECK(!memcmp(env.key_id, k.pub.id, 8) && env.sequence == 0x0102030405060708ull &&
              env.inner_len == t.len && !memcmp(env.inner, t.data, t.len),
          "key id, sequence and the transaction as given");
    CHECK(!memcmp(e.data + 16 + 8, "\x08\x07\x06\x05\x04\x03\x02\x01", 8), "sequence little-endian at 24");
    CHECK(cels_envelope_verify(&env, &k.pub), "the signer's key verifies");
    CHECK(!cels_envelope_verify(&env, &other.pub), "another key does not");

    /* The message as docs/STREAM.md lays it out, checked by libsodium alone. */
    static const char dom[] = "celscan signed transaction v1";
    size_t mlen = sizeof dom + 8 + 8 + t.len;
    uint8_t *msg = malloc(mlen);
    memcpy(msg, dom, sizeof dom);
    memcpy(msg + sizeof dom, k.pub.id, 8);
    memcpy(msg + sizeof dom + 8, e.data + 24, 8);
    memcpy(msg + sizeof dom + 16, t.data, t.len);
    crypto_sign_state st;
    crypto_sign_init(&st);
    crypto_sign_update(&st, msg, mlen);
    CHECK(crypto_sign_final_verify(&st, e.data + 32, k.pub.pk) == 0,
          "the signature is Ed25519ph over domain || key id || sequence || transaction");
    free(msg);

    /* Tampering, with every CRC made right again, is the signature's to catch. */
    uint8_t *copy = malloc(e.len);
    memcpy(copy, e.data, e.len);
    copy[16 + 80 + 16 + 6 + 4 + 16] ^= 0x40; /* the patch's dx */
    reseal(copy, e.len);
    CHECK(cels_envelope_parse(copy, e.len, &env) == NULL && !cels_envelope_verify(&env, &k.pub),
          "a changed transaction fails verification");
    memcpy(copy, e.data, e.len);
    copy[24] ^= 1; /* the sequence */
    reseal(copy, e.len);
    CHECK(cels_envelope_parse(copy, e.len, &env) == NULL && !cels_envelope_verify(&env, &k.pub),
          "a changed sequence fails verification");
    memcpy(copy, e.data, e.len);
    copy[40] ^= 1; /* the signature */
    reseal(copy, e.len);
    CHECK(cels_envelope_parse(copy, e.len, &env) == NULL && !cels_envelope_verify(&env, &k.pub),
          "a changed signature fails verification");
    memcpy(copy, e.data, e.len);
    copy[30] ^= 1;
    why = cels_envelope_parse(copy, e.len, &env);
    CHECK(why && strstr(why, "CRC") && env.status == CS_ERR_STREAM_CRC,
          "damage without resealing is a CRC mismatch: %s", why ? why : "");
    why = cels_envelope_parse(e.data, e.len - 1, &env);
    CHECK(why != NULL, "a cut envelope does not parse");
    free(copy);

    /* An envelope whose body is not one transaction. */
    cels_buf bad;
    cels_buf_init(&bad);
    cels_envelope_begin(&bad);
    uint8_t zeros[CS_WIRE_SIG_BLOCK_SIZE + 24] = {0};
    cels_put_bytes(&bad, zeros, sizeof zeros);
    cels_txn_end(&bad);
    why = cels_envelope_parse(bad.data, bad.len, &env);
    CHECK(why && strstr(why, "exactly one transaction"), "junk inside an envelope: %s", why ? why : "");
    cels_buf_free(&bad);
out:
    cels_buf_free(&t);
    cels_buf_free(&e);
}

/* A stream of the scene and a patch, signed whole; the core decodes both to the same store. */
static void test_sign_stream(void)
{
    cels_secret_key k;
    sign_test_key(&k);
    square_scene(&scene_a, 0.8f);
    cels_buf plain, sig;
    cels_buf_init(&plain);
    cels_buf_init(&sig);
    cels_stream_header(&plain);
    cels_encode_scene(&plain, &scene_a);
    patch(&plain, 7.0f);
    uint64_t seq = 1000;
    char err[300] = "";
    CHECK(cels_sign_stream(plain.data, plain.len, &k, &seq, &sig, err, sizeof err) == 0, "sign: %s", err);
    CHECK(seq == 1002, "two transactions, two sequence numbers (next %llu)", (unsigned long long)seq);
    CHECK(sig.len == plain.len + 2 * (CS_WIRE_HEADER_SIZE + CS_WIRE_SIG_BLOCK_SIZE + CS_WIRE_TRAILER_SIZE),
          "stream header kept, two envelopes (%zu bytes)", sig.len);
    cels_read_stats s1 = {0}, s2 = {0};
    const cs_scene *a = cels_decode_buffer(plain.data, plain.len, "plain", &scene_a, &scene_b, stderr, &s1);
    cs_scene_copy(&scene_c, a ? a : &scene_a);
    const cs_scene *b = cels_decode_buffer(sig.data, sig.len, "signed", &scene_a, &scene_b, stderr, &s2);
    char why[200] = "";
    CHECK(a && b && s2.commits == 2 && s2.errors == 0 && scene_equal(&scene_c, b, why, sizeof why),
          "the core unwraps the envelopes to the same store (%u commits, %u errors) %s", s2.commits, s2.errors,
          why);

    cels_buf out;
    cels_buf_init(&out);
    seq = 1;
    CHECK(cels_sign_stream(sig.data, sig.len, &k, &seq, &out, err, sizeof err) != 0 &&
              strstr(err, "byte 16: already signed"),
          "a signed stream is not signed again: %s", err);
    plain.data[plain.len - 1] ^= 1;
    out.len = 0;
    CHECK(cels_sign_stream(plain.data, plain.len, &k, &seq, &out, err, sizeof err) != 0 && strstr(err, "CRC"),
          "a damaged transaction is not signed: %s", err);
    plain.data[plain.len - 1] ^= 1;
    plain.data[0] = 'X';
    CHECK(cels_sign_stream(plain.data, plain.len, &k, &seq, &out, err, sizeof err) != 0 &&
              strstr(err, "byte 0: not a stream"),
          "stray bytes are not signed: %s", err);
    cels_buf_free(&out);
    cels_buf_free(&plain);
    cels_buf_free(&sig);
}

/* The core decoder's side of envelopes (no verification): a short one and one of another major
 * version are reported and skipped; the good one after them commits; nothing is called stray. */
static void test_core_unwrap(void)
{
    cels_secret_key k;
    sign_test_key(&k);
    cels_buf b, t;
    cels_buf_init(&b);
    cels_buf_init(&t);
    patch(&t, 5.0f);
    cels_envelope_begin(&b); /* 0: an envelope with only 20 bytes of body */
    uint8_t zeros[20] = {0};
    cels_put_bytes(&b, zeros, sizeof zeros);
    cels_txn_end(&b);
    size_t second = b.len;  /* 40: a whole envelope of major version 2 */
    cels_sign_txn(&b, &k, 1, t.data, t.len);
    b.data[second + 4] = 2;
    wr32(b.data + second + 12, cs_crc32(0, b.data + second, 12));
    size_t third = b.len;   /* 200: a good one */
    cels_sign_txn(&b, &k, 2, t.data, t.len);
    square_scene(&scene_a, 0.4f);
    cs_stream s;
    cs_stream_init(&s, &scene_a, true, &scene_b);
    const uint8_t *p = b.data;
    size_t n = b.len, used;
    char got[200] = "";
    size_t o = 0;
    for (int guard = 0; guard < 20; guard++) {
        cs_stream_event ev = cs_stream_feed(&s, p, n, &used);
        p += used;
        n -= used;
        if (ev == CS_STREAM_MORE && n == 0)
            ev = cs_stream_finish(&s);
        if (ev == CS_STREAM_COMMIT) {
            cs_stream_swap(&s);
            o += (size_t)snprintf(got + o, sizeof got - o, "C ");
        } else if (ev == CS_STREAM_ERROR) {
            const cs_stream_error *e = cs_stream_last_error(&s);
            o += (size_t)snprintf(got + o, sizeof got - o, "%d@%llu/%llu ", (int)e->status,
                                  (unsigned long long)e->offset, (unsigned long long)e->at);
        } else if (n == 0) {
            break;
        }
    }
    char want[200];
    snprintf(want, sizeof want, "%d@0/8 %d@%zu/%zu C ", CS_ERR_STREAM_RECORD, CS_ERR_STREAM_VERSION, second,
             second + 4);
    CHECK(third == 200 && !strcmp(got, want), "core decoder on envelopes:\n  got  %s\n  want %s", got, want);
    CHECK(s.front->cels[0].transform.e == 5.0f, "the good envelope's patch is applied");
    cels_buf_free(&b);
    cels_buf_free(&t);
}

static void write_file(const char *path, const char *text, int mode)
{
    FILE *f = fopen(path, "w");
    if (f) {
        fputs(text, f);
        fclose(f);
    }
    chmod(path, (mode_t)mode);
}

static void test_trust_state(const char *dir)
{
    char name[400], pub1[420], key1[420], pub2[420], key2[420], err[500] = "";
    snprintf(name, sizeof name, "%s/one", dir);
    cels_keygen(name, err, sizeof err);
    snprintf(pub1, sizeof pub1, "%s.pub", name);
    snprintf(key1, sizeof key1, "%s.key", name);
    snprintf(name, sizeof name, "%s/two", dir);
    cels_keygen(name, err, sizeof err);
    snprintf(pub2, sizeof pub2, "%s.pub", name);
    snprintf(key2, sizeof key2, "%s.key", name);
    cels_secret_key k1, k2;
    cels_read_secret_key(key1, &k1, err, sizeof err);
    cels_read_secret_key(key2, &k2, err, sizeof err);
    char state[310];
    snprintf(state, sizeof state, "%s/state", dir);
    mkdir(state, 0700);

    cels_buf t, e1, e2;
    cels_buf_init(&t);
    cels_buf_init(&e1);
    cels_buf_init(&e2);
    patch(&t, 3.0f);
    cels_sign_txn(&e1, &k1, 10, t.data, t.len);
    cels_sign_txn(&e2, &k2, 10, t.data, t.len);

    celfw_trust *tr = celfw_trust_new();
    celfw_trust_txn tx;
    CHECK(celfw_trust_check(tr, t.data, t.len, false, &tx) == CELFW_TRUST_PASS && tx.txn == t.data,
          "no key trusted: an unsigned transaction passes");
    CHECK(celfw_trust_check(tr, e2.data, e2.len, true, &tx) == CELFW_TRUST_PASS && tx.len == t.len &&
              !memcmp(tx.txn, t.data, t.len) && tx.offset == 96 && tx.key < 0,
          "no key trusted: an envelope is unwrapped unverified");
    CHECK(celfw_trust_add_key(tr, pub1, err, sizeof err) == 0, "trust one.pub: %s", err);
    CHECK(celfw_trust_add_key(tr, pub1, err, sizeof err) != 0 && strstr(err, "twice"), "twice: %s", err);
    bool fresh = false;
    CHECK(celfw_trust_open_state(tr, state, &fresh, err, sizeof err) == 0 && fresh, "a first start: %s", err);
    celfw_verdict v = celfw_trust_check(tr, t.data, t.len, false, &tx);
    CHECK(v == CELFW_TRUST_UNSIGNED && !strcmp(celfw_verdict_word(v), "unsigned"), "unsigned: %d", v);
    v = celfw_trust_check(tr, e2.data, e2.len, true, &tx);
    CHECK(v == CELFW_TRUST_UNKNOWN_KEY && !strcmp(celfw_verdict_word(v), "unknown key"), "unknown key: %d %s", v,
          tx.why);
    uint8_t *forged = malloc(e1.len);
    memcpy(forged, e1.data, e1.len);
    forged[e1.len - 12] ^= 0x10; /* a byte of the inner transaction's last record */
    reseal(forged, e1.len);
    v = celfw_trust_check(tr, forged, e1.len, true, &tx);
    CHECK(v == CELFW_TRUST_BAD_SIGNATURE && !strcmp(celfw_verdict_word(v), "bad signature"), "forged: %d %s",
          v, tx.why);
    /* k2's envelope carrying k1's id: a forgery too, not an unknown key */
    memcpy(forged, e2.data, e2.len);
    memcpy(forged + 16, k1.pub.id, 8);
    reseal(forged, e2.len);
    v = celfw_trust_check(tr, forged, e2.len, true, &tx);
    CHECK(v == CELFW_TRUST_BAD_SIGNATURE, "another key's signature under a trusted id: %d", v);
    forged[3] ^= 1;
    v = celfw_trust_check(tr, forged, e2.len, true, &tx);
    CHECK(v == CELFW_TRUST_MALFORMED, "a damaged envelope header: %d %s", v, tx.why);
    free(forged);
    v = celfw_trust_check(tr, e1.data, e1.len, true, &tx);
    CHECK(v == CELFW_TRUST_PASS && tx.key == 0 && tx.sequence == 10, "signed by a trusted key: %d %s", v, tx.why);
    CHECK(celfw_trust_applied(tr, &tx, err, sizeof err) == 0, "record sequence 10: %s", err);
    char hex[17];
    cels_key_id_hex(k1.pub.id, hex);
    char want[100], got[200] = "";
    snprintf(want, sizeof want, "celscan-trust-state-1\n%s 10\n", hex);
    snprintf(name, sizeof name, "%s/trust-state", state);
    FILE *f = fopen(name, "r");
    size_t n = f ? fread(got, 1, sizeof got - 1, f) : 0;
    got[n] = 0;
    if (f)
        fclose(f);
    CHECK(!strcmp(got, want), "state file: '%s', want '%s'", got, want);
    struct stat st;
    CHECK(stat(name, &st) == 0 && (st.st_mode & 07777) == 0600, "state file mode 0600");
    snprintf(name, sizeof name, "%s/trust-state.tmp", state);
    CHECK(access(name, F_OK) != 0, "no temporary file left");
    v = celfw_trust_check(tr, e1.data, e1.len, true, &tx);
    CHECK(v == CELFW_TRUST_REPLAYED && !strcmp(celfw_verdict_word(v), "replayed sequence"), "replay: %d %s", v,
          tx.why);
    celfw_trust_free(tr);

    /* A restart: the state is read back and still refuses the replay. */
    tr = celfw_trust_new();
    celfw_trust_add_key(tr, pub1, err, sizeof err);
    CHECK(celfw_trust_open_state(tr, state, &fresh, err, sizeof err) == 0 && !fresh &&
              celfw_trust_last(tr, hex) == 10,
          "state read back: last %llu (%s)", (unsigned long long)celfw_trust_last(tr, hex), err);
    CHECK(celfw_trust_check(tr, e1.data, e1.len, true, &tx) == CELFW_TRUST_REPLAYED, "replay after restart");
    cels_buf e3;
    cels_buf_init(&e3);
    cels_sign_txn(&e3, &k1, 11, t.data, t.len);
    CHECK(celfw_trust_check(tr, e3.data, e3.len, true, &tx) == CELFW_TRUST_PASS, "the next sequence passes");
    cels_buf_free(&e3);
    celfw_trust_free(tr);

    /* Damaged, empty, foreign and exposed state files stop celfw. */
    snprintf(name, sizeof name, "%s/trust-state", state);
    static const char *const bad[] = {"celscan-trust-state-1\nzz 5\n", "", "something else\n",
                                      "celscan-trust-state-1\n0123456789abcdef 12x\n",
                                      "celscan-trust-state-1\n0123456789abcdef -1\n",
                                      "celscan-trust-state-1\n0123456789abcdef 99999999999999999999999\n",
                                      "celscan-trust-state-1\n0123456789ABCDEF 5\n",
                                      "celscan-trust-state-1\n0123456789abcdef  5\n"};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        write_file(name, bad[i], 0600);
        tr = celfw_trust_new();
        err[0] = 0;
        CHECK(celfw_trust_open_state(tr, state, &fresh, err, sizeof err) != 0 && strstr(err, "trust-state"),
              "corrupt state %zu refused: %s", i, err);
        celfw_trust_free(tr);
    }
    write_file(name, want, 0666);
    tr = celfw_trust_new();
    CHECK(celfw_trust_open_state(tr, state, &fresh, err, sizeof err) != 0 && strstr(err, "mode 0666"),
          "a state file others can write is refused: %s", err);
    chmod(name, 0600);
    chmod(state, 0777);
    CHECK(celfw_trust_open_state(tr, state, &fresh, err, sizeof err) != 0 && strstr(err, "mode 0777"),
          "a state directory others can write is refused: %s", err);
    chmod(state, 0700);
    CHECK(celfw_trust_open_state(tr, pub1, &fresh, err, sizeof err) != 0 && strstr(err, "not a directory"),
          "a state-dir that is a file: %s", err);
    celfw_trust_free(tr);
    cels_buf_free(&t);
    cels_buf_free(&e1);
    cels_buf_free(&e2);
}

/* A framer's events for `data` fed in pieces of `piece` bytes, as one line per event. */
static void frame_events(const uint8_t *data, size_t len, size_t piece, char *out, size_t outlen)
{
    celfw_framer f;
    celfw_framer_init(&f, "test");
    size_t o = 0;
    out[0] = 0;
    celfw_frame fr;
    for (size_t at = 0; at < len; at += piece) {
        const uint8_t *p = data + at;
        size_t n = len - at < piece ? len - at : piece;
        do {
            size_t used = celfw_framer_push(&f, p, n, &fr);
            p += used;
            n -= used;
            if (fr.kind != CELFW_FRAME_NONE && o < outlen)
                o += (size_t)snprintf(out + o, outlen - o, "%d:%d@%llu/%llu/%zu ", (int)fr.kind,
                                      fr.kind == CELFW_FRAME_ERROR ? (int)fr.status : 0,
                                      (unsigned long long)fr.offset, (unsigned long long)fr.at, fr.len);
        } while (fr.kind != CELFW_FRAME_NONE);
    }
    if (celfw_framer_end(&f, &fr) && o < outlen)
        snprintf(out + o, outlen - o, "end %d@%llu/%llu", (int)fr.status, (unsigned long long)fr.offset,
                 (unsigned long long)fr.at);
    celfw_framer_free(&f);
}

/*
 * What a decoder reports on `data`, as "OFFSET/AT " per dropped piece and
 * "C " per commit: the decoder alone, or (framed) the framer and then the
 * decoder frame by frame, as celfw runs them. The two must agree.
 */
static void decoder_reports(const uint8_t *data, size_t len, bool framed, char *out, size_t outlen)
{
    size_t o = 0;
    out[0] = 0;
    square_scene(&scene_a, 0.3f);
    cs_scene *st[2] = {&scene_a, &scene_b};
#define ADD(...)                                                                                   \
    do {                                                                                           \
        if (o < outlen)                                                                            \
            o += (size_t)snprintf(out + o, outlen - o, __VA_ARGS__);                               \
    } while (0)
    if (!framed) {
        cs_stream s;
        cs_stream_init(&s, st[0], true, st[1]);
        size_t used;
        for (;;) {
            cs_stream_event ev = cs_stream_feed(&s, data, len, &used);
            data += used;
            len -= used;
            if (ev == CS_STREAM_MORE && len == 0)
                ev = cs_stream_finish(&s);
            if (ev == CS_STREAM_COMMIT) {
                cs_stream_swap(&s);
                ADD("C ");
            } else if (ev == CS_STREAM_ERROR) {
                const cs_stream_error *e = cs_stream_last_error(&s);
                ADD("%llu/%llu ", (unsigned long long)e->offset, (unsigned long long)e->at);
            } else if (len == 0) {
                break;
            }
        }
        return;
    }
    celfw_framer f;
    celfw_framer_init(&f, "test");
    celfw_stream *cs = celfw_stream_new();
    int front = 0;
    celfw_frame fr;
    for (bool more = true; more;) {
        size_t used = celfw_framer_push(&f, data, len, &fr);
        data += used;
        len -= used;
        if (fr.kind == CELFW_FRAME_NONE) {
            more = false;
            if (!celfw_framer_end(&f, &fr))
                break;
        }
        if (fr.kind == CELFW_FRAME_ERROR) {
            ADD("%llu/%llu ", (unsigned long long)fr.offset, (unsigned long long)fr.at);
            continue;
        }
        celfw_stream_error err;
        celfw_stream_result r = celfw_stream_frame(cs, fr.data, fr.len, fr.offset, st[front], st[front ^ 1], &err);
        if (r == CELFW_STREAM_COMMIT) {
            front ^= 1;
            ADD("C ");
        } else if (r == CELFW_STREAM_ERROR) {
            const char *m = strstr(err.what, "at byte ");
            ADD("%llu/%llu ", m ? strtoull(m + 8, NULL, 10) : 0ull, (unsigned long long)err.offset);
        }
    }
#undef ADD
    celfw_stream_free(cs);
    celfw_framer_free(&f);
}

static void test_framer(void)
{
    cels_secret_key k;
    sign_test_key(&k);
    cels_buf b, t;
    cels_buf_init(&b);
    cels_buf_init(&t);
    const uint8_t junk[5] = {1, 2, 3, 4, 5};
    cels_put_bytes(&b, junk, 5);                    /* 0: 5 stray bytes */
    cels_stream_header(&b);                         /* 5: stream header */
    patch(&b, 1.0f);                                /* 21: a transaction (60 bytes) */
    patch(&t, 2.0f);
    cels_sign_txn(&b, &k, 7, t.data, t.len);        /* 81: an envelope (160 bytes) */
    size_t cut = b.len;                             /* 241: a third of a transaction */
    cels_put_bytes(&b, t.data, 20);
    patch(&b, 3.0f);                                /* 261: the next one cuts it short */
    size_t tail = b.len;                            /* 321: the start of another, never finished */
    cels_put_bytes(&b, t.data, 30);
    CHECK(t.len == 60 && cut == 241 && tail == 321, "layout as planned (%zu, %zu, %zu)", t.len, cut, tail);
    char want[400], got[400];
    snprintf(want, sizeof want,
             "4:%d@0/0/0 1:0@5/0/16 2:0@21/0/60 3:0@81/0/160 4:%d@241/261/0 2:0@261/0/60 end %d@321/351",
             CS_ERR_STREAM_SYNC, CS_ERR_STREAM_TRUNCATED, CS_ERR_STREAM_TRUNCATED);
    frame_events(b.data, b.len, b.len, got, sizeof got);
    CHECK(!strcmp(got, want), "frames at once:\n  got  %s\n  want %s", got, want);
    frame_events(b.data, b.len, 1, got, sizeof got);
    CHECK(!strcmp(got, want), "frames byte by byte:\n  got  %s\n  want %s", got, want);
    frame_events(b.data, b.len, 7, got, sizeof got);
    CHECK(!strcmp(got, want), "frames in 7-byte pieces:\n  got  %s\n  want %s", got, want);

    /* A header announcing 4 GB: refused at once, its length skipped, a header on the way starts anew. */
    cels_buf big;
    cels_buf_init(&big);
    cels_txn_begin(&big);
    cels_txn_end(&big);
    wr32(big.data + 8, 0xfffffff0u);
    wr32(big.data + 12, cs_crc32(0, big.data, 12));
    big.len = 16;
    cels_put_bytes(&big, junk, 5);
    patch(&big, 4.0f);
    snprintf(want, sizeof want, "4:%d@0/8/0 2:0@21/0/60 ", CS_ERR_STREAM_TOO_BIG);
    frame_events(big.data, big.len, 3, got, sizeof got);
    CHECK(!strcmp(got, want), "oversized frame:\n  got  %s\n  want %s", got, want);
    cels_buf_free(&big);

    /* Against the decoder alone: the same damaged stream (and a bad CRC), the same reports. */
    b.len = tail;
    patch(&b, 5.0f);
    b.data[b.len - 1] ^= 1;
    char alone[600], framed[600];
    decoder_reports(b.data, b.len, false, alone, sizeof alone);
    decoder_reports(b.data, b.len, true, framed, sizeof framed);
    CHECK(!strcmp(alone, framed) && !strcmp(alone, "0/0 C C 241/261 C 321/377 "),
          "framer + decoder report what the decoder alone reports:\n  alone  %s\n  framed %s", alone, framed);
    cels_buf_free(&b);
    cels_buf_free(&t);
}

static void test_ratelimit(void)
{
    celfw_ratelimit r = {0};
    uint64_t held = 0, shown = 0, summary;
    for (int i = 0; i < 60000; i++) {
        shown += celfw_ratelimit_allow(&r, 1000u + (uint64_t)i, &summary);
        held += summary;
    }
    CHECK(shown == CELFW_LOG_BURST && held == 0, "60,000 lines in a window: %llu shown", (unsigned long long)shown);
    CHECK(celfw_ratelimit_due(&r, 5000000000u, false) == 0, "nothing told before the window ends");
    uint64_t end = 1000u + (uint64_t)CELFW_LOG_WINDOW_S * 1000000000u;
    CHECK(celfw_ratelimit_due(&r, end, false) == 60000 - CELFW_LOG_BURST, "the rest told as one count");
    CHECK(celfw_ratelimit_allow(&r, end + 1, &summary) && summary == 0, "a new window writes again");
    for (int i = 0; i < 20; i++)
        celfw_ratelimit_allow(&r, end + 2, &summary);
    CHECK(celfw_ratelimit_allow(&r, end + 3 * (end - 1000u), &summary) && summary == 11,
          "a line after a window with held-back lines brings their count (%llu)", (unsigned long long)summary);
    CHECK(celfw_ratelimit_due(&r, end + 3 * (end - 1000u), true) == 0, "final: nothing held");
}

/* Seeds for tests/fuzz_sign.c: signed by the fixed test key, and unsigned. */
static int write_seeds(const char *dir)
{
    cels_secret_key k;
    sign_test_key(&k);
    square_scene(&scene_a, 0.5f);
    cels_buf plain, sig;
    cels_buf_init(&plain);
    cels_buf_init(&sig);
    cels_stream_header(&plain);
    cels_encode_scene(&plain, &scene_a);
    patch(&plain, 9.0f);
    uint64_t seq = 100;
    char err[200], path[400];
    if (cels_sign_stream(plain.data, plain.len, &k, &seq, &sig, err, sizeof err) != 0)
        return 1;
    /* the same stream twice (the second time a replay), and signed by a key the fuzzer does not trust */
    cels_buf twice, other;
    cels_buf_init(&twice);
    cels_buf_init(&other);
    cels_put_bytes(&twice, sig.data, sig.len);
    cels_put_bytes(&twice, sig.data, sig.len);
    cels_secret_key stranger;
    uint8_t seed[CELS_SEED_SIZE];
    memset(seed, 0x5a, sizeof seed);
    cels_secret_key_from_seed(seed, &stranger);
    if (cels_sign_stream(plain.data, plain.len, &stranger, &seq, &other, err, sizeof err) != 0)
        return 1;
    /* byte 0 is the fuzzer's mode: 0x80 trusts the test key, the low bits choose the chunking */
    const struct {
        const char *name;
        uint8_t mode;
        cels_buf *b;
    } seeds[] = {{"signed-trusted.fuzz", 0x80, &sig},
                 {"signed-untrusted.fuzz", 0x02, &sig},
                 {"plain-trusted.fuzz", 0x81, &plain},
                 {"replay-trusted.fuzz", 0x80, &twice},
                 {"stranger-trusted.fuzz", 0x83, &other}};
    for (size_t i = 0; i < sizeof seeds / sizeof seeds[0]; i++) {
        snprintf(path, sizeof path, "%s/%s", dir, seeds[i].name);
        FILE *f = fopen(path, "wb");
        if (!f || fputc(seeds[i].mode, f) == EOF ||
            fwrite(seeds[i].b->data, 1, seeds[i].b->len, f) != seeds[i].b->len) {
            fprintf(stderr, "test_trust: cannot write %s\n", path);
            return 1;
        }
        fclose(f);
    }
    cels_buf_free(&plain);
    cels_buf_free(&sig);
    cels_buf_free(&twice);
    cels_buf_free(&other);
    return 0;
}

int main(int argc, char **argv)
{
    if (!cels_sign_init()) {
        fprintf(stderr, "test_trust: libsodium cannot start\n");
        return 2;
    }
    if (argc == 3 && !strcmp(argv[1], "--seeds"))
        return write_seeds(argv[2]);
    char dir[] = "/tmp/test-trust-XXXXXX";
    if (!mkdtemp(dir)) {
        fprintf(stderr, "test_trust: mkdtemp: %s\n", strerror(errno));
        return 2;
    }
    test_keys(dir);
    test_envelope();
    test_sign_stream();
    test_core_unwrap();
    test_trust_state(dir);
    test_framer();
    test_ratelimit();
    char cmd[200];
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    if (system(cmd) != 0)
        fprintf(stderr, "test_trust: could not remove %s\n", dir);
    return tl_summary("test_trust");
}
