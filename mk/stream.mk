# mk/stream.mk - the cel stream: unit tests, sanitizer build, fuzzing.
#
#   make stream-test        tests/test_stream against the freestanding core
#   make stream-test-asan   the same under ASan + UBSan (core included)
#   make fuzz               libFuzzer on the decoder for FUZZ_TIME s (default 60)
#   make fuzz-smoke         a short fuzz run (FUZZ_SMOKE_TIME, default 45 s), part of `make test`
#   make stream-seeds       regenerate tests/fuzz-corpus/ from the test program

STREAM_TEST_OBJ := $(HOST)/obj/tests/test_stream.o $(HOST)/obj/tools/cels_write.o \
        $(HOST)/obj/tools/cels_read.o
$(STREAM_TEST_OBJ): HOST_CFLAGS += -Itools

$(HOST)/test_stream: $(STREAM_TEST_OBJ) $(HOST)/libcelscan.a
	$(Q)$(CC) $^ -o $@ -lm

# Sanitizers over everything, the core too: the decoder is what they are for.
STREAM_SAN := -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer
STREAM_ASAN := $(ASAN)/stream
$(eval $(call flags_record,stream-asan,$(CC) $(CORE_CFLAGS) $(HOST_CFLAGS) $(STREAM_SAN)))
$(STREAM_ASAN)/core/%.o: core/%.c $(CORE_HDR) $(FLAGS_DIR)/stream-asan
	@mkdir -p $(dir $@)
	$(Q)$(CC) $(CORE_CFLAGS) $(STREAM_SAN) -c $< -o $@
$(STREAM_ASAN)/obj/%.o: %.c $(FLAGS_DIR)/stream-asan
	@mkdir -p $(dir $@)
	$(Q)$(CC) $(HOST_CFLAGS) -Itools $(STREAM_SAN) -c $< -o $@
$(STREAM_ASAN)/test_stream: $(STREAM_ASAN)/obj/tests/test_stream.o \
        $(STREAM_ASAN)/obj/tools/cels_write.o $(STREAM_ASAN)/obj/tools/cels_read.o $(patsubst core/%.c,$(STREAM_ASAN)/core/%.o,$(CORE_SRC))
	$(Q)$(CC) $(STREAM_SAN) $^ -o $@ -lm

.PHONY: stream-test stream-test-asan fuzz fuzz-smoke stream-seeds
stream-test: $(HOST)/test_stream
	$(Q)$<
stream-test-asan: $(STREAM_ASAN)/test_stream
	$(Q)ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 $< | sed 's/^test_stream:/test_stream_asan:/'

# libFuzzer build: clang, sanitizers, and small store capacities so that
# capacity limits are reached and every execution stays cheap.
FUZZ_CC ?= clang
FUZZ := $(BUILD)/fuzz
FUZZ_TIME ?= 60
FUZZ_SMOKE_TIME ?= 45
FUZZ_CAPS := -DCS_CFG_MAX_CELS=8 -DCS_CFG_MAX_REGIONS=32 -DCS_CFG_MAX_CONTOURS=64 \
        -DCS_CFG_MAX_POINTS=512 -DCS_CFG_MAX_TRACKS=16 -DCS_CFG_MAX_KEYS=64 \
        -DCS_CFG_MAX_KEY_VALUES=1024 -DCS_CFG_MAX_ANIM_POINTS=64 -DCS_CFG_MAX_WIDTH=64 \
        -DCS_CFG_MAX_CROSSINGS=128
# Coverage guidance (and its cost) only where the input steers: the decoder,
# the store and the writer. The renderer that checks committed scenes runs
# under the same sanitizers without coverage tracing, ~3x faster.
FUZZ_GUIDED := core/cs_stream.c core/cs_scene.c core/cs_edit.c core/cs_anim.c core/cs_status.c \
        tools/cels_write.c tests/fuzz_stream.c
FUZZ_PLAIN := $(filter-out $(FUZZ_GUIDED),$(CORE_SRC))
FUZZ_CFLAGS := -std=c11 -g -O1 $(FP_FLAGS) -fno-sanitize-recover=all $(FUZZ_CAPS) -Icore -Itools
$(eval $(call flags_record,fuzz,$(FUZZ_CC) $(FUZZ_CFLAGS)))
$(FUZZ)/guided/%.o: %.c $(CORE_HDR) tools/cels_write.h $(FLAGS_DIR)/fuzz
	@mkdir -p $(dir $@)
	$(Q)$(FUZZ_CC) $(FUZZ_CFLAGS) -fsanitize=fuzzer-no-link,address,undefined -c $< -o $@
$(FUZZ)/plain/%.o: %.c $(CORE_HDR) $(FLAGS_DIR)/fuzz
	@mkdir -p $(dir $@)
	$(Q)$(FUZZ_CC) $(FUZZ_CFLAGS) -fsanitize=address,undefined -c $< -o $@
$(FUZZ)/fuzz_stream: $(patsubst %.c,$(FUZZ)/guided/%.o,$(FUZZ_GUIDED)) \
        $(patsubst %.c,$(FUZZ)/plain/%.o,$(FUZZ_PLAIN))
	$(Q)$(FUZZ_CC) -fsanitize=fuzzer,address,undefined $^ -o $@

# Runs in a scratch copy of the seed corpus; findings land in $(FUZZ)/.
define run_fuzz
	@rm -rf $(FUZZ)/corpus && mkdir -p $(FUZZ)/corpus && cp tests/fuzz-corpus/* $(FUZZ)/corpus/
	$(Q)cd $(FUZZ) && ./fuzz_stream -max_total_time=$(1) -print_final_stats=1 -timeout=5 \
		-dict=$(CURDIR)/tests/fuzz_stream.dict \
		-rss_limit_mb=1024 corpus 2>fuzz.log; rc=$$?; \
		grep -E '^(#[0-9]+.*DONE|stat::number_of_executed_units|stat::peak_rss_mb|fuzz_stream:)' fuzz.log; \
		if [ $$rc -ne 0 ]; then tail -40 fuzz.log; echo "$(2): 0 passed, 1 failed"; exit 1; fi; \
		echo "$(2): $$(sed -n 's/^stat::number_of_executed_units: *//p' fuzz.log) executions, no finding"; \
		echo "$(2): 1 passed, 0 failed"
endef
fuzz: $(FUZZ)/fuzz_stream
	$(call run_fuzz,$(FUZZ_TIME),fuzz)
fuzz-smoke: $(FUZZ)/fuzz_stream
	$(call run_fuzz,$(FUZZ_SMOKE_TIME),fuzz-smoke)

stream-seeds: $(HOST)/test_stream
	$(Q)$< --seeds tests/fuzz-corpus

TEST_TARGETS += stream-test stream-test-asan fuzz-smoke
