/*
 * celfw_trust.c - trusted keys, the verification of signed envelopes and
 * the persistent last applied sequences (see celfw_trust.h).
 *
 * The envelope itself (layout, what the signature covers) is parsed and
 * verified by tools/cels_sign.c, the code that signs; this file decides.
 * Order of the checks: an envelope that does not parse is damaged (its
 * CRCs, its lengths), not a trust question; then the key id, the signature
 * and only then the sequence, so a forgery carrying an old number is called
 * a forgery.
 *
 * The state file is text, one "KEYID SEQUENCE" line per key after a version
 * line; keys no longer trusted keep their line, so trusting one again does
 * not reopen its old streams. It is rewritten whole on every signed commit:
 * a handful of lines, and correctness after a power cut matters more than
 * the fsync it costs.
 */
#include "celfw_trust.h"

#include <errno.h>
#include <fcntl.h>
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cels_sign.h"

#define STATE_NAME "trust-state"
#define STATE_TAG "celscan-trust-state-1"
#define MAX_KEYS 64    /* trusted keys */
#define MAX_STATE 1024 /* keys remembered in the state file */

typedef struct applied {
    char id[2 * CS_WIRE_SIG_KEYID_SIZE + 1];
    uint64_t sequence;
} applied;

struct celfw_trust {
    cels_public_key keys[MAX_KEYS];
    int key_count;
    applied state[MAX_STATE];
    int state_count;
    char dir[256];
};

celfw_trust *celfw_trust_new(void)
{
    if (!cels_sign_init())
        return NULL;
    return calloc(1, sizeof(celfw_trust));
}

void celfw_trust_free(celfw_trust *t)
{
    free(t);
}

int celfw_trust_key_count(const celfw_trust *t)
{
    return t->key_count;
}

int celfw_trust_add_key(celfw_trust *t, const char *path, char *err, size_t errlen)
{
    if (t->key_count == MAX_KEYS) {
        snprintf(err, errlen, "trust %s: at most %d keys", path, MAX_KEYS);
        return -1;
    }
    cels_public_key k;
    char why[400];
    if (cels_read_public_key(path, &k, why, sizeof why) != 0) {
        snprintf(err, errlen, "trust %s", why);
        return -1;
    }
    for (int i = 0; i < t->key_count; i++)
        if (!memcmp(t->keys[i].id, k.id, sizeof k.id)) {
            snprintf(err, errlen, "trust %s: the same key (or its id) is trusted twice", path);
            return -1;
        }
    t->keys[t->key_count++] = k;
    return 0;
}

static applied *find_state(const celfw_trust *t, const char *hex)
{
    for (int i = 0; i < t->state_count; i++)
        if (!strcmp(t->state[i].id, hex))
            return (applied *)&t->state[i];
    return NULL;
}

uint64_t celfw_trust_last(const celfw_trust *t, const char *key_hex)
{
    const applied *a = find_state(t, key_hex);
    return a ? a->sequence : 0;
}

/* Parses the state file's text; -1 with err naming the line. */
static int parse_state(celfw_trust *t, char *text, const char *path, char *err, size_t errlen)
{
    int no = 0;
    char *save = NULL;
    t->state_count = 0;
    for (char *line = strtok_r(text, "\n", &save); line; line = strtok_r(NULL, "\n", &save)) {
        no++;
        if (no == 1) {
            if (strcmp(line, STATE_TAG) != 0) {
                snprintf(err, errlen, "%s:1: not a celfw trust state file (expected '%s')", path, STATE_TAG);
                return -1;
            }
            continue;
        }
        /* "KEYID SEQUENCE": 16 lower-case hex digits, one space, decimal digits, nothing else */
        char id[2 * CS_WIRE_SIG_KEYID_SIZE + 1];
        const char *digits = line + 2 * CS_WIRE_SIG_KEYID_SIZE + 1;
        char *end = NULL;
        bool ok = strlen(line) > 2 * CS_WIRE_SIG_KEYID_SIZE + 1 && line[2 * CS_WIRE_SIG_KEYID_SIZE] == ' ' &&
                  strspn(line, "0123456789abcdef") == 2 * CS_WIRE_SIG_KEYID_SIZE &&
                  strspn(digits, "0123456789") == strlen(digits);
        errno = 0;
        unsigned long long seq = ok ? strtoull(digits, &end, 10) : 0;
        if (!ok || errno == ERANGE || *end != 0) {
            snprintf(err, errlen, "%s:%d: damaged (expected 'KEYID SEQUENCE'); refusing to guess which "
                     "sequences were applied", path, no);
            return -1;
        }
        snprintf(id, sizeof id, "%.*s", 2 * CS_WIRE_SIG_KEYID_SIZE, line);
        if (find_state(t, id) || t->state_count == MAX_STATE) {
            snprintf(err, errlen, "%s:%d: key %s listed twice, or more than %d keys", path, no, id, MAX_STATE);
            return -1;
        }
        snprintf(t->state[t->state_count].id, sizeof t->state[0].id, "%s", id);
        t->state[t->state_count++].sequence = seq;
    }
    if (no == 0) {
        snprintf(err, errlen, "%s: empty (a damaged write?); refusing to guess which sequences were applied",
                 path);
        return -1;
    }
    return 0;
}

int celfw_trust_open_state(celfw_trust *t, const char *dir, bool *fresh, char *err, size_t errlen)
{
    struct stat st;
    *fresh = false;
    if (snprintf(t->dir, sizeof t->dir, "%s", dir) >= (int)sizeof t->dir) {
        snprintf(err, errlen, "state-dir %s: path too long", dir);
        return -1;
    }
    if (stat(dir, &st) != 0) {
        snprintf(err, errlen, "state-dir %s: %s", dir, strerror(errno));
        return -1;
    }
    if (!S_ISDIR(st.st_mode)) {
        snprintf(err, errlen, "state-dir %s: not a directory", dir);
        return -1;
    }
    if (st.st_mode & 022) {
        snprintf(err, errlen, "state-dir %s: mode %04o lets others replace the trust state (chmod 700 it)", dir,
                 (unsigned)(st.st_mode & 07777));
        return -1;
    }
    char path[300];
    snprintf(path, sizeof path, "%s/" STATE_NAME, dir);
    int fd = open(path, O_RDONLY | O_CLOEXEC | O_NOFOLLOW);
    if (fd < 0) {
        if (errno == ENOENT) {
            *fresh = true;
            t->state_count = 0;
            return 0;
        }
        snprintf(err, errlen, "%s: %s", path, strerror(errno));
        return -1;
    }
    size_t cap = MAX_STATE * 48 + 64;
    char *text = malloc(cap);
    ssize_t got = -1;
    int rc = -1;
    if (!text) {
        snprintf(err, errlen, "%s: out of memory", path);
    } else if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        snprintf(err, errlen, "%s: not a regular file", path);
    } else if (st.st_mode & 022) {
        snprintf(err, errlen, "%s: mode %04o lets others rewrite the trust state (chmod 600 it)", path,
                 (unsigned)(st.st_mode & 07777));
    } else if (st.st_uid != geteuid() && st.st_uid != 0) {
        snprintf(err, errlen, "%s: owned by uid %u, neither this user nor root", path, (unsigned)st.st_uid);
    } else if ((got = read(fd, text, cap - 1)) < 0) {
        snprintf(err, errlen, "%s: %s", path, strerror(errno));
    } else if ((size_t)got == cap - 1) {
        snprintf(err, errlen, "%s: larger than a trust state can be", path);
    } else {
        text[got] = 0;
        rc = parse_state(t, text, path, err, errlen);
    }
    free(text);
    close(fd);
    return rc;
}

/* Writes the state whole: temporary file, fsync, rename over, fsync the directory. */
static int save_state(const celfw_trust *t, char *err, size_t errlen)
{
    char path[300], tmp[310];
    snprintf(path, sizeof path, "%s/" STATE_NAME, t->dir);
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    int fd = open(tmp, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC | O_NOFOLLOW, 0600);
    if (fd < 0) {
        snprintf(err, errlen, "%s: %s", tmp, strerror(errno));
        return -1;
    }
    FILE *f = fdopen(fd, "w");
    if (!f) {
        close(fd);
        snprintf(err, errlen, "%s: %s", tmp, strerror(errno));
        return -1;
    }
    fprintf(f, "%s\n", STATE_TAG);
    for (int i = 0; i < t->state_count; i++)
        fprintf(f, "%s %" PRIu64 "\n", t->state[i].id, t->state[i].sequence);
    bool ok = fflush(f) == 0 && fsync(fd) == 0;
    int saved = errno;
    if (fclose(f) != 0 && ok) {
        ok = false;
        saved = errno;
    }
    if (ok && rename(tmp, path) != 0) {
        ok = false;
        saved = errno;
    }
    if (!ok) {
        unlink(tmp);
        snprintf(err, errlen, "%s: cannot save: %s", path, strerror(saved));
        return -1;
    }
    int dfd = open(t->dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (dfd >= 0) {
        fsync(dfd); /* the rename itself must survive a power cut */
        close(dfd);
    }
    return 0;
}

celfw_verdict celfw_trust_check(const celfw_trust *t, const uint8_t *frame, size_t len, bool is_signed,
                                celfw_trust_txn *out)
{
    out->txn = frame;
    out->len = len;
    out->offset = 0;
    out->key = -1;
    out->sequence = 0;
    out->status = CS_OK;
    out->why[0] = 0;
    if (!is_signed) {
        if (t->key_count == 0)
            return CELFW_TRUST_PASS;
        snprintf(out->why, sizeof out->why, "a transaction outside a signed envelope");
        return CELFW_TRUST_UNSIGNED;
    }
    cels_envelope e;
    const char *bad = cels_envelope_parse(frame, len, &e);
    if (bad) {
        snprintf(out->why, sizeof out->why, "%s", bad);
        out->status = e.status;
        return CELFW_TRUST_MALFORMED;
    }
    out->txn = e.inner;
    out->len = e.inner_len;
    out->offset = (size_t)(e.inner - frame);
    out->sequence = e.sequence;
    if (t->key_count == 0)
        return CELFW_TRUST_PASS; /* nothing to verify against: unwrapped as the core does */
    char hex[2 * CS_WIRE_SIG_KEYID_SIZE + 1];
    cels_key_id_hex(e.key_id, hex);
    int k = 0;
    while (k < t->key_count && memcmp(t->keys[k].id, e.key_id, CS_WIRE_SIG_KEYID_SIZE) != 0)
        k++;
    if (k == t->key_count) {
        snprintf(out->why, sizeof out->why, "key %s is not trusted here", hex);
        return CELFW_TRUST_UNKNOWN_KEY;
    }
    if (!cels_envelope_verify(&e, &t->keys[k])) {
        snprintf(out->why, sizeof out->why, "key %s, sequence %" PRIu64 ": the signature does not match", hex,
                 e.sequence);
        return CELFW_TRUST_BAD_SIGNATURE;
    }
    uint64_t last = celfw_trust_last(t, hex);
    if (e.sequence <= last) {
        snprintf(out->why, sizeof out->why, "key %s, sequence %" PRIu64 ", not above %" PRIu64 " applied already",
                 hex, e.sequence, last);
        return CELFW_TRUST_REPLAYED;
    }
    out->key = k;
    return CELFW_TRUST_PASS;
}

int celfw_trust_applied(celfw_trust *t, const celfw_trust_txn *tx, char *err, size_t errlen)
{
    if (tx->key < 0)
        return 0;
    char hex[2 * CS_WIRE_SIG_KEYID_SIZE + 1];
    cels_key_id_hex(t->keys[tx->key].id, hex);
    applied *a = find_state(t, hex);
    if (!a) {
        if (t->state_count == MAX_STATE) {
            snprintf(err, errlen, "trust state full (%d keys)", MAX_STATE);
            return -1;
        }
        a = &t->state[t->state_count++];
        snprintf(a->id, sizeof a->id, "%s", hex);
    }
    a->sequence = tx->sequence;
    return t->dir[0] ? save_state(t, err, errlen) : 0;
}

const char *celfw_verdict_word(celfw_verdict v)
{
    switch (v) {
    case CELFW_TRUST_PASS: return "accepted";
    case CELFW_TRUST_UNSIGNED: return "unsigned";
    case CELFW_TRUST_UNKNOWN_KEY: return "unknown key";
    case CELFW_TRUST_BAD_SIGNATURE: return "bad signature";
    case CELFW_TRUST_REPLAYED: return "replayed sequence";
    default: return "malformed envelope";
    }
}
