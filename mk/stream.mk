# mk/stream.mk - the cel stream: unit tests, sanitizer build, fuzzing (of the decoder, and of
# the scene JSON loader).
#
#   make stream-test        tests/test_stream against the freestanding core
#   make stream-test-asan   the same under ASan + UBSan (core included)
#   make fuzz               libFuzzer on the decoder for FUZZ_TIME s (default 60)
#   make fuzz-smoke         a short fuzz run (FUZZ_SMOKE_TIME, default 45 s), part of `make test`
#   make fuzz-json          libFuzzer on the scene JSON loader for FUZZ_TIME s (default 60)
#   make fuzz-json-smoke    a short run of it (FUZZ_JSON_SMOKE_TIME, default 20 s), part of `make test`
#   make stream-seeds       regenerate tests/fuzz-corpus/ from the test program

STREAM_TEST_OBJ := $(HOST)/obj/tests/test_stream.o $(HOST)/obj/tools/cels_write.o \
        $(HOST)/obj/tools/cels_read.o
$(STREAM_TEST_OBJ): HOST_CFLAGS += -Itools

$(HOST)/test_stream: $(STREAM_TEST_OBJ) $(HOST)/libcelscan.a
	$(Q)$(CC) $^ -o $@ -lm

# Sanitizers over everything, the core too: the decoder is what they are for.
STREAM_ASAN := $(ASAN)/stream
# (the core: the shared sanitizer build, build/asan/libcelscan.a)
$(eval $(call flags_record,stream-asan,$(CC) $(HOST_CFLAGS) $(SAN_FLAGS)))
$(STREAM_ASAN)/obj/%.o: %.c $(FLAGS_DIR)/stream-asan
	@mkdir -p $(dir $@)
	$(Q)$(CC) $(HOST_CFLAGS) -Itools $(SAN_FLAGS) -c $< -o $@
$(STREAM_ASAN)/test_stream: $(STREAM_ASAN)/obj/tests/test_stream.o \
        $(STREAM_ASAN)/obj/tools/cels_write.o $(STREAM_ASAN)/obj/tools/cels_read.o $(ASAN)/libcelscan.a
	$(Q)$(CC) $(SAN_FLAGS) $^ -o $@ -lm

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
FUZZ_GUIDED := core/cs_stream.c core/cs_stream_apply.c core/cs_scene.c core/cs_edit.c \
        core/cs_anim.c core/cs_status.c tools/cels_write.c tests/fuzz_stream.c
FUZZ_PLAIN := $(filter-out $(FUZZ_GUIDED),$(CORE_SRC))
# Every fuzz build (the JSON loader's below and the SVG importer's in mk/svg.mk too).
FUZZ_BASE_CFLAGS := -std=c11 -g -O1 $(FP_FLAGS) -fno-sanitize-recover=all
# clang 14 at -O1 with ASan and UBSan together took 330-360 s on cs_composite.c
# alone (its folds are always_inline copies of one large loop; UBSan's
# pointer-overflow checks on them are most of it), most of `make test`'s
# wall time; at -O0, with every check still in, 3 s. The fuzzers render only
# tiny scenes, so the slower code costs them few executions.
FUZZ_O0_SRC := core/cs_composite.c
FUZZ_O0_FLAGS = $(if $(filter $(FUZZ_O0_SRC),$<),-O0)
FUZZ_CFLAGS := $(FUZZ_BASE_CFLAGS) $(FUZZ_CAPS) -Icore -Itools
$(eval $(call flags_record,fuzz,$(FUZZ_CC) $(FUZZ_CFLAGS) -O0:$(FUZZ_O0_SRC)))
$(FUZZ)/guided/%.o: %.c $(CORE_HDR) tools/cels_write.h tests/fuzz_check.h $(FLAGS_DIR)/fuzz
	@mkdir -p $(dir $@)
	$(Q)$(FUZZ_CC) $(FUZZ_CFLAGS) -fsanitize=fuzzer-no-link,address,undefined -c $< -o $@
$(FUZZ)/plain/%.o: %.c $(CORE_HDR) $(FLAGS_DIR)/fuzz
	@mkdir -p $(dir $@)
	$(Q)$(FUZZ_CC) $(FUZZ_CFLAGS) $(FUZZ_O0_FLAGS) -fsanitize=address,undefined -c $< -o $@
$(FUZZ)/fuzz_stream: $(patsubst %.c,$(FUZZ)/guided/%.o,$(FUZZ_GUIDED)) \
        $(patsubst %.c,$(FUZZ)/plain/%.o,$(FUZZ_PLAIN))
	$(Q)$(FUZZ_CC) -fsanitize=fuzzer,address,undefined $^ -o $@

# The core with full capacities under the fuzzers' coverage and sanitizers,
# one build shared by the JSON loader's, the SVG importer's (mk/svg.mk) and
# the Lottie importer's (mk/zlottie.mk) fuzzers, which had each compiled it.
FUZZ_CORE_CFLAGS := $(FUZZ_BASE_CFLAGS) -Icore
$(eval $(call flags_record,fuzz-core,$(FUZZ_CC) $(FUZZ_CORE_CFLAGS) -O0:$(FUZZ_O0_SRC)))
$(FUZZ)/core/%.o: core/%.c $(CORE_HDR) $(FLAGS_DIR)/fuzz-core
	@mkdir -p $(dir $@)
	$(Q)$(FUZZ_CC) $(FUZZ_CORE_CFLAGS) $(FUZZ_O0_FLAGS) -fsanitize=fuzzer-no-link,address,undefined \
		-c $< -o $@
FUZZ_CORE_OBJ := $(patsubst core/%.c,$(FUZZ)/core/%.o,$(CORE_SRC))

# Runs fuzzer $(1) (a program in $(FUZZ)) for $(2) seconds in a scratch corpus,
# $(FUZZ)/$(1).corpus, filled by FUZZ_SEEDS_$(1) (shell commands) and run
# with FUZZ_OPTS_$(1); $(3) names it in the summary line. Findings (crash-*,
# timeout-*) and the log ($(1).log) land in $(FUZZ)/.
define run_fuzzer
	@rm -rf $(FUZZ)/$(1).corpus && mkdir -p $(FUZZ)/$(1).corpus
	$(Q)$(FUZZ_SEEDS_$(1))
	$(Q)cd $(FUZZ) && ./$(1) -max_total_time=$(2) -print_final_stats=1 $(FUZZ_OPTS_$(1)) \
		$(1).corpus 2>$(1).log; rc=$$?; \
		grep -E '^(#[0-9]+.*DONE|stat::number_of_executed_units|stat::peak_rss_mb|$(1):)' $(1).log; \
		if [ $$rc -ne 0 ]; then tail -40 $(1).log; echo "$(3): 0 passed, 1 failed"; exit 1; fi; \
		echo "$(3): $$(sed -n 's/^stat::number_of_executed_units: *//p' $(1).log) executions, no finding"; \
		echo "$(3): 1 passed, 0 failed"
endef
FUZZ_SEEDS_fuzz_stream = cp tests/fuzz-corpus/* $(FUZZ)/fuzz_stream.corpus/
FUZZ_OPTS_fuzz_stream = -timeout=5 -dict=$(CURDIR)/tests/fuzz_stream.dict -rss_limit_mb=1024
fuzz: $(FUZZ)/fuzz_stream
	$(call run_fuzzer,fuzz_stream,$(FUZZ_TIME),fuzz)
fuzz-smoke: $(FUZZ)/fuzz_stream
	$(call run_fuzzer,fuzz_stream,$(FUZZ_SMOKE_TIME),fuzz-smoke)

stream-seeds: $(HOST)/test_stream
	$(Q)$< --seeds tests/fuzz-corpus

# The scene JSON loader (host code on hand-written files): the loader and the
# core under the fuzzer's coverage and sanitizers, full store capacities,
# cJSON from Debian. Seeds are the committed scenes.
FUZZ_JSON_SMOKE_TIME ?= 20
FUZZ_JSON_SRC := tests/fuzz_scene_json.c host-sim/scene_json.c host-sim/paint_json.c
FUZZ_JSON_CFLAGS := $(FUZZ_BASE_CFLAGS) -Icore -Ihost-sim $(shell pkg-config --cflags libcjson)
$(eval $(call flags_record,fuzz-json,$(FUZZ_CC) $(FUZZ_JSON_CFLAGS)))
$(FUZZ)/json/%.o: %.c $(CORE_HDR) tests/fuzz_check.h host-sim/scene_json.h host-sim/paint_json.h $(FLAGS_DIR)/fuzz-json
	@mkdir -p $(dir $@)
	$(Q)$(FUZZ_CC) $(FUZZ_JSON_CFLAGS) -fsanitize=fuzzer-no-link,address,undefined -c $< -o $@
$(FUZZ)/fuzz_scene_json: $(patsubst %.c,$(FUZZ)/json/%.o,$(FUZZ_JSON_SRC)) $(FUZZ_CORE_OBJ)
	$(Q)$(FUZZ_CC) -fsanitize=fuzzer,address,undefined $^ $(shell pkg-config --libs libcjson) -o $@

FUZZ_SEEDS_fuzz_scene_json = cp scenes/*.json $(FUZZ)/fuzz_scene_json.corpus/
FUZZ_OPTS_fuzz_scene_json = -timeout=10 -dict=$(CURDIR)/tests/fuzz_scene_json.dict -max_len=65536 \
        -rss_limit_mb=2048
.PHONY: fuzz-json fuzz-json-smoke
fuzz-json: $(FUZZ)/fuzz_scene_json
	$(call run_fuzzer,fuzz_scene_json,$(FUZZ_TIME),fuzz-json)
fuzz-json-smoke: $(FUZZ)/fuzz_scene_json
	$(call run_fuzzer,fuzz_scene_json,$(FUZZ_JSON_SMOKE_TIME),fuzz-json-smoke)

TEST_TARGETS += stream-test stream-test-asan fuzz-smoke fuzz-json-smoke
