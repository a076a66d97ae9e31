/*
 * celfw_trust.h - which transactions celfw may apply: trusted keys, signed
 * envelopes, and the last applied sequence of each key.
 *
 * With no trusted key, every transaction passes (a bench, the simulator's
 * use); a signed envelope is unwrapped unverified. With one or more
 * (`--trust FILE`), a transaction passes only inside an envelope signed by a
 * trusted key with a sequence number above the last one applied from that
 * key; anything else is refused whole, with one word saying why. The check
 * sits in front of the decoder on the one path every input goes through
 * (celfw.c's input sink), so TCP, tty, stdin, files and fleet messages are
 * held to the same rule.
 *
 * The last applied sequences live in DIR/trust-state (`--state-dir DIR`), one
 * line per key, read at start and rewritten atomically (temporary file,
 * fsync, rename, fsync of the directory) each time a signed transaction
 * commits, so neither a restart nor a power cut reopens the door to replaying
 * an old signed stream to roll the sign back. A state file that is damaged,
 * or that others could write, stops celfw at start rather than being
 * silently taken as "nothing applied yet".
 */
#ifndef CELFW_TRUST_H
#define CELFW_TRUST_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "celscan.h"

typedef enum celfw_verdict {
    CELFW_TRUST_PASS = 0,      /* may go to the decoder */
    CELFW_TRUST_UNSIGNED,      /* a transaction outside an envelope, keys trusted */
    CELFW_TRUST_UNKNOWN_KEY,   /* signed by a key not trusted */
    CELFW_TRUST_BAD_SIGNATURE, /* signature does not match the key and content */
    CELFW_TRUST_REPLAYED,      /* sequence not above the last applied from the key */
    CELFW_TRUST_MALFORMED      /* a damaged or malformed envelope */
} celfw_verdict;

/* What passed: the transaction to decode and, if it was signed by a trusted key, who signed it. */
typedef struct celfw_trust_txn {
    const uint8_t *txn;  /* the transaction, header to trailer */
    size_t len;
    size_t offset;       /* of txn within the frame */
    int key;             /* index of the trusted key, -1 if none verified */
    uint64_t sequence;
    cs_status status;    /* malformed envelopes: what kind of fault (CS_ERR_STREAM_CRC, ...) */
    char why[200];       /* refusals and malformed envelopes: the details */
} celfw_trust_txn;

typedef struct celfw_trust celfw_trust;

celfw_trust *celfw_trust_new(void);
void celfw_trust_free(celfw_trust *t);
/* Trusts the public key in `path` (a `celc keygen` NAME.pub, mode checked). 0, or -1 with err. */
int celfw_trust_add_key(celfw_trust *t, const char *path, char *err, size_t errlen);
int celfw_trust_key_count(const celfw_trust *t);
/*
 * Keeps the state in dir/trust-state and reads it (a missing file is a
 * first start: *fresh is set). The directory and file must not be writable
 * by group or others. 0, or -1 with err.
 */
int celfw_trust_open_state(celfw_trust *t, const char *dir, bool *fresh, char *err, size_t errlen);
/* The last applied sequence of a key (by hex id), 0 if none: for tests and the log. */
uint64_t celfw_trust_last(const celfw_trust *t, const char *key_hex);

/* Checks one whole frame (a transaction or an envelope). */
celfw_verdict celfw_trust_check(const celfw_trust *t, const uint8_t *frame, size_t len, bool is_signed,
                                celfw_trust_txn *out);
/* The transaction that passed committed: records its sequence (and saves the state). 0, or -1 with err. */
int celfw_trust_applied(celfw_trust *t, const celfw_trust_txn *tx, char *err, size_t errlen);
/* "unsigned", "unknown key", "bad signature", "replayed sequence", "malformed envelope". */
const char *celfw_verdict_word(celfw_verdict v);

#endif /* CELFW_TRUST_H */
