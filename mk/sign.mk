# mk/sign.mk - signed cel streams: keys, the signed envelope (tools/cels_sign.c, over libsodium),
# celfw's trust check (firmware/linux/celfw_trust.c), their tests and their fuzz target.
#
#   make test-sign          celc keygen / sign / compile --sign through the programs (tests/cli_sign.sh)
#   make fuzz-sign          libFuzzer on the envelope framer and verifier for FUZZ_TIME s
#   make fuzz-sign-smoke    a short run of it (FUZZ_SIGN_SMOKE_TIME, default 15 s), part of `make test`
#
# The in-process tests of keys, envelopes and the state file (tests/linuxhal/test_trust.c) and the
# signed streams against the real celfw (tests/linuxhal/test_celfw.c) run in test-linuxhal.
SODIUM_LIBS = $(shell pkg-config --libs libsodium 2>/dev/null || echo -lsodium)
