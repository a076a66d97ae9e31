# mk/trust.mk - signed cel streams: keys, the signed envelope (tools/cels_sign.c, over libsodium),
# celfw's trust check (firmware/linux/celfw_trust.c), their tests and their fuzz target.
#
#   make test-sign          celc keygen / sign / compile --sign through the programs (tests/cli_sign.sh)
#   make fuzz-sign          libFuzzer on the envelope framer and verifier for FUZZ_TIME s
#   make fuzz-sign-smoke    a short run of it (FUZZ_SIGN_SMOKE_TIME, default 15 s), part of `make test`
#
# The in-process tests of keys, envelopes and the state file (tests/linuxhal/test_trust.c) and the
# signed streams against the real celfw (tests/linuxhal/test_celfw.c) run in test-linuxhal.
# (Read after mk/stream.mk, whose fuzz build this one extends; SODIUM_LIBS is used by recipes
# of earlier fragments, which expand it only when they run.)
SODIUM_LIBS = $(shell pkg-config --libs libsodium 2>/dev/null || echo -lsodium)

# libFuzzer build of the signed-stream path: celfw's framer, trust check and decoder seam, the
# envelope code, under coverage and sanitizers; the core as the stream fuzzer builds it (mk/stream.mk,
# small capacities), libsodium from Debian. Seeds: tests/fuzz-sign-corpus/ (`make sign-seeds`
# rewrites them with test_trust), signed by the fixed test key of tests/sign_test_key.h.
FUZZ_SIGN_SMOKE_TIME ?= 15
FUZZ_SIGN_SRC := tests/fuzz_sign.c firmware/linux/celfw_frame.c firmware/linux/celfw_trust.c \
        firmware/linux/celfw_stream.c tools/cels_sign.c
FUZZ_SIGN_CFLAGS := $(FUZZ_CFLAGS) -D_DEFAULT_SOURCE -Ifirmware/linux -Itests
$(eval $(call flags_record,fuzz-sign,$(FUZZ_CC) $(FUZZ_SIGN_CFLAGS)))
$(FUZZ)/sign/%.o: %.c $(CORE_HDR) tools/cels_sign.h tools/cels_write.h tests/fuzz_check.h \
        tests/sign_test_key.h $(wildcard firmware/linux/celfw_*.h) $(FLAGS_DIR)/fuzz-sign
	@mkdir -p $(dir $@)
	$(Q)$(FUZZ_CC) $(FUZZ_SIGN_CFLAGS) -fsanitize=fuzzer-no-link,address,undefined -c $< -o $@
$(FUZZ)/fuzz_sign: $(patsubst %.c,$(FUZZ)/sign/%.o,$(FUZZ_SIGN_SRC)) \
        $(patsubst %.c,$(FUZZ)/guided/%.o,$(filter core/% tools/%,$(FUZZ_GUIDED))) \
        $(patsubst %.c,$(FUZZ)/plain/%.o,$(FUZZ_PLAIN))
	$(Q)$(FUZZ_CC) -fsanitize=fuzzer,address,undefined $^ $(SODIUM_LIBS) -o $@

FUZZ_SEEDS_fuzz_sign = cp tests/fuzz-sign-corpus/* $(FUZZ)/fuzz_sign.corpus/
FUZZ_OPTS_fuzz_sign = -timeout=5 -dict=$(CURDIR)/tests/fuzz_sign.dict -rss_limit_mb=1024 -max_len=8192
.PHONY: fuzz-sign fuzz-sign-smoke sign-seeds test-sign
fuzz-sign: $(FUZZ)/fuzz_sign
	$(call run_fuzzer,fuzz_sign,$(FUZZ_TIME),fuzz-sign)
fuzz-sign-smoke: $(FUZZ)/fuzz_sign
	$(call run_fuzzer,fuzz_sign,$(FUZZ_SIGN_SMOKE_TIME),fuzz-sign-smoke)
sign-seeds: $(HOST)/tests/test_trust
	$(Q)mkdir -p tests/fuzz-sign-corpus && $< --seeds tests/fuzz-sign-corpus

# The commands as a user types them: celc keygen, sign, compile --sign, and celsim on the result.
test-sign: $(HOST)/celc $(HOST)/celsim
	$(Q)sh tests/cli_sign.sh $(HOST) $(BUILD)/cli-sign

TEST_TARGETS += test-sign fuzz-sign-smoke
