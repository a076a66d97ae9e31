/*
 * cels_sign.h - signed cel streams on the host: Ed25519 keys, the signed
 * envelope (docs/STREAM.md, "Signed transactions"), signing and verifying.
 *
 * One implementation of the envelope for everything that signs or checks:
 * `celc keygen` / `celc sign` / `celc compile --sign` write with it, celfw's
 * trust check (firmware/linux/celfw_trust.c) and the fuzz target read with
 * it. The cryptography is libsodium's (Ed25519ph through crypto_sign_init /
 * update / final, so a transaction of megabytes is signed and checked where
 * it lies, with no copy behind a domain prefix).
 *
 * Key files are one line of text: "celscan-ed25519-secret-key-1 <seed hex>"
 * (NAME.key, mode 0600) and "celscan-ed25519-public-key-1 <key hex>"
 * (NAME.pub). Readers check the file's mode before they trust its content:
 * a private key others can read is refused, and so is a public key others
 * can write (whoever can rewrite a trusted key owns the sign).
 *
 * Host code: libc and libsodium. Not in the core.
 */
#ifndef CELS_SIGN_H
#define CELS_SIGN_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "cels_write.h"

#define CELS_PUBLIC_KEY_SIZE 32
#define CELS_SEED_SIZE 32

typedef struct cels_public_key {
    uint8_t id[CS_WIRE_SIG_KEYID_SIZE]; /* first bytes of BLAKE2b-256(key) */
    uint8_t pk[CELS_PUBLIC_KEY_SIZE];
} cels_public_key;

typedef struct cels_secret_key {
    cels_public_key pub;
    uint8_t sk[64]; /* libsodium's form: seed and public key */
} cels_secret_key;

/* A parsed envelope; the pointers point into the frame it was parsed from. */
typedef struct cels_envelope {
    const uint8_t *key_id; /* CS_WIRE_SIG_KEYID_SIZE bytes */
    uint64_t sequence;
    const uint8_t *signature; /* CS_WIRE_SIG_SIZE bytes */
    const uint8_t *inner;     /* one whole transaction: header, body, trailer */
    size_t inner_len;
    cs_status status;         /* parse failures: CS_ERR_STREAM_CRC, _VERSION, _TRUNCATED or _RECORD */
} cels_envelope;

/* Initialises libsodium; false if it cannot (no entropy source). */
bool cels_sign_init(void);

/*
 * Writes NAME.key (0600) and NAME.pub (0644) for a new key pair. Refuses if
 * either file exists (a key is never overwritten). 0, or -1 with err.
 */
int cels_keygen(const char *name, char *err, size_t errlen);

/* The key pair of a 32-byte seed (what NAME.key holds): for key files and test keys. */
void cels_secret_key_from_seed(const uint8_t seed[CELS_SEED_SIZE], cels_secret_key *k);
/* Reads a private key file (mode checked: no access for group or others). */
int cels_read_secret_key(const char *path, cels_secret_key *k, char *err, size_t errlen);
/* Reads a public key file (mode checked: not writable by group or others). */
int cels_read_public_key(const char *path, cels_public_key *k, char *err, size_t errlen);
/* "0123456789abcdef": a key id in hex, as logs and docs show it. */
void cels_key_id_hex(const uint8_t id[CS_WIRE_SIG_KEYID_SIZE], char out[2 * CS_WIRE_SIG_KEYID_SIZE + 1]);

/* Appends an envelope around one whole transaction `txn`; 0, or -1 (out of memory). */
int cels_sign_txn(cels_buf *out, const cels_secret_key *k, uint64_t sequence, const uint8_t *txn,
                  size_t len);

/*
 * Signs a whole stream: stream headers are copied, every transaction is
 * wrapped in an envelope with sequence *sequence, then *sequence + 1, ...
 * The input must be a clean stream (every header and trailer CRC right,
 * nothing between frames, nothing signed already): a signer vouches for
 * what it signs. 0, or -1 with err naming the byte offset.
 */
int cels_sign_stream(const uint8_t *in, size_t len, const cels_secret_key *k, uint64_t *sequence,
                     cels_buf *out, char *err, size_t errlen);

/*
 * Parses a whole envelope frame (header, body, trailer), checking its CRCs
 * and that the body holds the signature block and exactly one transaction
 * whose header CRC matches. Returns NULL, or what is wrong (and e->status its kind).
 */
const char *cels_envelope_parse(const uint8_t *frame, size_t len, cels_envelope *e);

/* Whether the envelope's signature is the key's over its key id, sequence and inner transaction. */
bool cels_envelope_verify(const cels_envelope *e, const cels_public_key *k);

#endif /* CELS_SIGN_H */
