/*
 * sign_test_key.h - the fixed Ed25519 key pair of the signed-stream fuzz
 * target (tests/fuzz_sign.c) and of the seeds test_trust writes for it
 * (tests/fuzz-sign-corpus/): a known key, so that the committed seeds carry
 * signatures the fuzzer's verifier accepts and mutations start from there.
 * Test material only; no board trusts it.
 */
#ifndef SIGN_TEST_KEY_H
#define SIGN_TEST_KEY_H

#include "cels_sign.h"

static inline void sign_test_key(cels_secret_key *k)
{
    uint8_t seed[CELS_SEED_SIZE];
    for (int i = 0; i < CELS_SEED_SIZE; i++)
        seed[i] = (uint8_t)(i * 7 + 1);
    cels_secret_key_from_seed(seed, k);
}

#endif /* SIGN_TEST_KEY_H */
