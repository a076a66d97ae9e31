/*
 * cels_sign.c - Ed25519 keys and signed envelopes of the cel stream (see
 * cels_sign.h and docs/STREAM.md).
 *
 * What a signature covers is fixed by one function, feed_message(), used by
 * both the signer and the verifier: a domain string (so a signature made for
 * this purpose can never be replayed as one for another protocol that uses
 * the same key), the key id, the sequence number and the inner transaction's
 * bytes, header to trailer. The envelope's own header and CRC are framing,
 * outside the signature: damaging them is caught by the CRCs.
 *
 * Key files are created with O_EXCL (a private key is never overwritten:
 * losing one would lock its signs out) and read through the open descriptor's
 * fstat, so the mode checked is that of the file actually read.
 */
#include "cels_sign.h"

#include <errno.h>
#include <fcntl.h>
#include <sodium.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define SECRET_TAG "celscan-ed25519-secret-key-1"
#define PUBLIC_TAG "celscan-ed25519-public-key-1"

/* The domain-separation prefix of every signed message, NUL included. */
static const char domain[] = "celscan signed transaction v1";

static uint32_t rd_u32(const uint8_t *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static uint64_t rd_u64(const uint8_t *p)
{
    return (uint64_t)rd_u32(p) | (uint64_t)rd_u32(p + 4) << 32;
}

static void wr_u64(uint8_t *p, uint64_t v)
{
    for (int i = 0; i < 8; i++)
        p[i] = (uint8_t)(v >> (8 * i));
}

bool cels_sign_init(void)
{
    return sodium_init() >= 0;
}

static void key_id(const uint8_t pk[CELS_PUBLIC_KEY_SIZE], uint8_t id[CS_WIRE_SIG_KEYID_SIZE])
{
    uint8_t h[crypto_generichash_BYTES];
    crypto_generichash(h, sizeof h, pk, CELS_PUBLIC_KEY_SIZE, NULL, 0);
    memcpy(id, h, CS_WIRE_SIG_KEYID_SIZE);
}

void cels_key_id_hex(const uint8_t id[CS_WIRE_SIG_KEYID_SIZE], char out[2 * CS_WIRE_SIG_KEYID_SIZE + 1])
{
    sodium_bin2hex(out, 2 * CS_WIRE_SIG_KEYID_SIZE + 1, id, CS_WIRE_SIG_KEYID_SIZE);
}

/* Writes "TAG hex\n" to a new file of `mode`; refuses an existing one. */
static int write_key_file(const char *path, int mode, const char *tag, const uint8_t *key, size_t n,
                          char *err, size_t errlen)
{
    char hex[2 * 64 + 1];
    sodium_bin2hex(hex, sizeof hex, key, n);
    char line[200];
    int len = snprintf(line, sizeof line, "%s %s\n", tag, hex);
    sodium_memzero(hex, sizeof hex);
    int fd = open(path, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC | O_NOFOLLOW, mode);
    if (fd < 0) {
        snprintf(err, errlen, "%s: %s", path,
                 errno == EEXIST ? "exists already; a key is never overwritten (remove it first, "
                                   "knowing that signs trusting it will refuse the new one)"
                                 : strerror(errno));
        sodium_memzero(line, sizeof line);
        return -1;
    }
    /* the umask may be stricter than `mode`, never looser */
    bool ok = fchmod(fd, (mode_t)mode) == 0 && write(fd, line, (size_t)len) == len && fsync(fd) == 0;
    int saved = errno;
    sodium_memzero(line, sizeof line);
    if (close(fd) != 0 && ok) {
        ok = false;
        saved = errno;
    }
    if (!ok) {
        snprintf(err, errlen, "%s: cannot write: %s", path, strerror(saved));
        unlink(path);
        return -1;
    }
    return 0;
}

int cels_keygen(const char *name, char *err, size_t errlen)
{
    size_t n = strlen(name) + 5;
    char *key_path = malloc(n), *pub_path = malloc(n);
    int rc = -1;
    if (!key_path || !pub_path) {
        snprintf(err, errlen, "out of memory");
        goto out;
    }
    snprintf(key_path, n, "%s.key", name);
    snprintf(pub_path, n, "%s.pub", name);
    struct stat st;
    if (lstat(pub_path, &st) == 0) {
        snprintf(err, errlen, "%s: exists already; a key is never overwritten", pub_path);
        goto out;
    }
    uint8_t pk[crypto_sign_PUBLICKEYBYTES], sk[crypto_sign_SECRETKEYBYTES];
    crypto_sign_keypair(pk, sk);
    /* the seed is the first half of libsodium's secret key */
    if (write_key_file(key_path, 0600, SECRET_TAG, sk, CELS_SEED_SIZE, err, errlen) == 0) {
        if (write_key_file(pub_path, 0644, PUBLIC_TAG, pk, sizeof pk, err, errlen) == 0)
            rc = 0;
        else
            unlink(key_path);
    }
    sodium_memzero(sk, sizeof sk);
out:
    free(key_path);
    free(pub_path);
    return rc;
}

/*
 * Reads the one line of a key file into `key` (n bytes) after checking the
 * file: a regular file, owned by us or root, with no mode bits in `forbidden`.
 */
static int read_key_file(const char *path, const char *tag, mode_t forbidden, const char *why,
                         uint8_t *key, size_t n, char *err, size_t errlen)
{
    int fd = open(path, O_RDONLY | O_CLOEXEC);
    if (fd < 0) {
        snprintf(err, errlen, "%s: %s", path, strerror(errno));
        return -1;
    }
    struct stat st;
    char text[256];
    ssize_t got = -1;
    int rc = -1;
    if (fstat(fd, &st) != 0) {
        snprintf(err, errlen, "%s: %s", path, strerror(errno));
    } else if (!S_ISREG(st.st_mode)) {
        snprintf(err, errlen, "%s: not a regular file", path);
    } else if (st.st_uid != geteuid() && st.st_uid != 0) {
        snprintf(err, errlen, "%s: owned by uid %u, neither this user nor root", path, (unsigned)st.st_uid);
    } else if (st.st_mode & forbidden) {
        snprintf(err, errlen, "%s: mode %04o %s (chmod %s it)", path, (unsigned)(st.st_mode & 07777), why,
                 forbidden == 077 ? "600" : "644");
    } else if ((got = read(fd, text, sizeof text - 1)) < 0) {
        snprintf(err, errlen, "%s: %s", path, strerror(errno));
    } else {
        text[got] = 0;
        size_t tl = strlen(tag);
        const char *hex = text + tl + 1;
        size_t bin_len = 0;
        const char *end = NULL;
        if ((size_t)got <= tl || strncmp(text, tag, tl) != 0 || text[tl] != ' ' ||
            sodium_hex2bin(key, n, hex, strlen(hex), NULL, &bin_len, &end) != 0 || bin_len != n ||
            (strcmp(end, "\n") != 0 && *end != 0)) {
            snprintf(err, errlen, "%s: not a celscan key file (expected one line '%s <%zu hex digits>')", path,
                     tag, 2 * n);
        } else {
            rc = 0;
        }
    }
    sodium_memzero(text, sizeof text);
    close(fd);
    return rc;
}

void cels_secret_key_from_seed(const uint8_t seed[CELS_SEED_SIZE], cels_secret_key *k)
{
    crypto_sign_seed_keypair(k->pub.pk, k->sk, seed);
    key_id(k->pub.pk, k->pub.id);
}

int cels_read_secret_key(const char *path, cels_secret_key *k, char *err, size_t errlen)
{
    uint8_t seed[CELS_SEED_SIZE];
    if (read_key_file(path, SECRET_TAG, 077, "lets others read the private key", seed, sizeof seed, err,
                      errlen) != 0)
        return -1;
    cels_secret_key_from_seed(seed, k);
    sodium_memzero(seed, sizeof seed);
    return 0;
}

int cels_read_public_key(const char *path, cels_public_key *k, char *err, size_t errlen)
{
    if (read_key_file(path, PUBLIC_TAG, 022, "lets others replace a trusted key", k->pk, sizeof k->pk, err,
                      errlen) != 0)
        return -1;
    key_id(k->pk, k->id);
    return 0;
}

/* The signed message: domain, key id, sequence, inner transaction. */
static void feed_message(crypto_sign_state *st, const uint8_t *id, uint64_t sequence, const uint8_t *txn,
                         size_t len)
{
    uint8_t seq[8];
    wr_u64(seq, sequence);
    crypto_sign_update(st, (const uint8_t *)domain, sizeof domain);
    crypto_sign_update(st, id, CS_WIRE_SIG_KEYID_SIZE);
    crypto_sign_update(st, seq, sizeof seq);
    crypto_sign_update(st, txn, len);
}

int cels_sign_txn(cels_buf *out, const cels_secret_key *k, uint64_t sequence, const uint8_t *txn, size_t len)
{
    crypto_sign_state st;
    uint8_t sig[CS_WIRE_SIG_SIZE], seq[8];
    crypto_sign_init(&st);
    feed_message(&st, k->pub.id, sequence, txn, len);
    crypto_sign_final_create(&st, sig, NULL, k->sk);
    wr_u64(seq, sequence);
    cels_envelope_begin(out);
    cels_put_bytes(out, k->pub.id, CS_WIRE_SIG_KEYID_SIZE);
    cels_put_bytes(out, seq, sizeof seq);
    cels_put_bytes(out, sig, sizeof sig);
    cels_put_bytes(out, txn, len);
    cels_txn_end(out);
    return out->oom ? -1 : 0;
}

/* Whether p (at least 16 bytes) is a header with this magic and a matching CRC. */
static bool is_header(const uint8_t *p, const char *magic)
{
    return memcmp(p, magic, 4) == 0 && cs_crc32(0, p, 12) == rd_u32(p + 12);
}

/* Checks a whole frame of 16 + L + 4 bytes at p: length fits, trailer CRC right. */
static const char *check_frame(const uint8_t *p, size_t avail, size_t *frame_len)
{
    uint64_t body = rd_u32(p + 8);
    uint64_t n = CS_WIRE_HEADER_SIZE + body + CS_WIRE_TRAILER_SIZE;
    if (n > avail)
        return "transaction cut short";
    if (cs_crc32(0, p, (size_t)n - CS_WIRE_TRAILER_SIZE) != rd_u32(p + n - CS_WIRE_TRAILER_SIZE))
        return "transaction CRC mismatch";
    *frame_len = (size_t)n;
    return NULL;
}

int cels_sign_stream(const uint8_t *in, size_t len, const cels_secret_key *k, uint64_t *sequence,
                     cels_buf *out, char *err, size_t errlen)
{
    size_t at = 0;
    while (at < len) {
        const uint8_t *p = in + at;
        size_t frame = 0;
        const char *why = NULL;
        if (len - at < CS_WIRE_HEADER_SIZE) {
            why = "bytes after the last transaction";
        } else if (is_header(p, CS_WIRE_STREAM_MAGIC)) {
            cels_put_bytes(out, p, CS_WIRE_HEADER_SIZE);
            at += CS_WIRE_HEADER_SIZE;
            continue;
        } else if (is_header(p, CS_WIRE_SIGNED_MAGIC)) {
            why = "already signed";
        } else if (!is_header(p, CS_WIRE_TXN_MAGIC)) {
            why = "not a stream or transaction header";
        } else if ((why = check_frame(p, len - at, &frame)) == NULL) {
            if (cels_sign_txn(out, k, (*sequence)++, p, frame) != 0)
                why = "out of memory";
        }
        if (why) {
            snprintf(err, errlen, "byte %zu: %s; nothing signed", at, why);
            return -1;
        }
        at += frame;
    }
    return 0;
}

/* A parse failure of kind st. */
static const char *refuse(cels_envelope *e, cs_status st, const char *why)
{
    e->status = st;
    return why;
}

const char *cels_envelope_parse(const uint8_t *frame, size_t len, cels_envelope *e)
{
    size_t n = 0;
    const char *why;
    if (len < CS_WIRE_HEADER_SIZE || !is_header(frame, CS_WIRE_SIGNED_MAGIC))
        return refuse(e, CS_ERR_STREAM_SYNC, "not a signed envelope header");
    if (frame[4] != CS_WIRE_MAJOR)
        return refuse(e, CS_ERR_STREAM_VERSION, "signed envelope of an unsupported major version");
    if ((why = check_frame(frame, len, &n)) != NULL)
        return refuse(e, strstr(why, "CRC") ? CS_ERR_STREAM_CRC : CS_ERR_STREAM_TRUNCATED, why);
    if (n != len)
        return refuse(e, CS_ERR_STREAM_RECORD, "bytes after the envelope's trailer");
    size_t body = n - CS_WIRE_HEADER_SIZE - CS_WIRE_TRAILER_SIZE;
    if (body < CS_WIRE_SIGNED_MIN_BODY)
        return refuse(e, CS_ERR_STREAM_RECORD, "signed envelope too short for a signature and a transaction");
    const uint8_t *b = frame + CS_WIRE_HEADER_SIZE;
    e->key_id = b;
    e->sequence = rd_u64(b + CS_WIRE_SIG_KEYID_SIZE);
    e->signature = b + CS_WIRE_SIG_KEYID_SIZE + 8;
    e->inner = b + CS_WIRE_SIG_BLOCK_SIZE;
    e->inner_len = body - CS_WIRE_SIG_BLOCK_SIZE;
    e->status = CS_OK;
    if (!is_header(e->inner, CS_WIRE_TXN_MAGIC) ||
        (uint64_t)rd_u32(e->inner + 8) + CS_WIRE_HEADER_SIZE + CS_WIRE_TRAILER_SIZE != e->inner_len)
        return refuse(e, CS_ERR_STREAM_RECORD, "signed envelope does not hold exactly one transaction");
    return NULL;
}

bool cels_envelope_verify(const cels_envelope *e, const cels_public_key *k)
{
    if (memcmp(e->key_id, k->id, CS_WIRE_SIG_KEYID_SIZE) != 0)
        return false;
    crypto_sign_state st;
    crypto_sign_init(&st);
    feed_message(&st, e->key_id, e->sequence, e->inner, e->inner_len);
    return crypto_sign_final_verify(&st, e->signature, k->pk) == 0;
}
