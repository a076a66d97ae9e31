# mk/beta.mk - the beta colour model: tests and the cache benchmark.
#
#   make test-beta        closed-form beta model, mattes, gradients, dithering (test_beta),
#                         the cache (test_cache) and CSG (test_csg)
#   make test-beta-asan   the same under AddressSanitizer + UBSan
#   make bench-cache      pre-combination benchmark (static background, moving front)
#
# The tests link the core library; the sanitizer build links the sanitizer
# build of the core (Makefile, ASAN_CORE_CFLAGS), so the core is instrumented
# too.

BETA_CFLAGS := -std=c11 -O2 -g $(FP_FLAGS) -Wall -Wextra -Wshadow -Icore -Itests -D_POSIX_C_SOURCE=200809L -MMD -MP
$(eval $(call flags_record,beta,$(CC) $(BETA_CFLAGS) $(SAN_FLAGS)))

BETA_TESTS := test_beta test_cache test_csg
BETA_HOST := $(addprefix $(HOST)/,$(BETA_TESTS))
BETA_ASAN := $(addprefix $(ASAN)/,$(BETA_TESTS))

$(BETA_HOST): $(HOST)/%: tests/%.c tests/beta_common.h $(HOST)/libcelscan.a $(CORE_HDR) \
        $(FLAGS_DIR)/beta
	@mkdir -p $(dir $@)
	$(Q)$(CC) $(BETA_CFLAGS) $< $(HOST)/libcelscan.a -lm -o $@

$(BETA_ASAN): $(ASAN)/%: tests/%.c tests/beta_common.h $(ASAN)/libcelscan.a $(CORE_HDR) \
        $(FLAGS_DIR)/beta
	@mkdir -p $(dir $@)
	$(Q)$(CC) $(BETA_CFLAGS) -O1 $(SAN_FLAGS) $< $(ASAN)/libcelscan.a -lm -o $@

$(HOST)/bench_cache_anim: bench/cache_anim.c tools/cli_num.c $(CORE_SRC) $(CORE_HDR) $(FLAGS_DIR)/beta
	@mkdir -p $(dir $@)
	$(Q)$(CC) $(BETA_CFLAGS) -Itools bench/cache_anim.c tools/cli_num.c $(CORE_SRC) -lm -o $@

.PHONY: test-beta test-beta-asan bench-cache
test-beta: $(BETA_HOST)
	$(Q)sh tests/run.sh $(BETA_HOST)

test-beta-asan: $(BETA_ASAN)
	$(Q)ASAN_OPTIONS=detect_leaks=1 sh tests/run.sh $(BETA_ASAN)

bench-cache: $(HOST)/bench_cache_anim
	$(Q)$(HOST)/bench_cache_anim

TEST_TARGETS += test-beta test-beta-asan
HOST_PROGRAMS += $(HOST)/bench_cache_anim

# The JSON helper for paints and CSG (host code: cJSON from Debian).
$(HOST)/test_paint_json: tests/test_paint_json.c host-sim/paint_json.c host-sim/paint_json.h \
		$(CORE_SRC) $(CORE_HDR) $(FLAGS_DIR)/beta
	@mkdir -p $(dir $@)
	$(Q)$(CC) $(BETA_CFLAGS) -Ihost-sim $(shell pkg-config --cflags libcjson) \
		tests/test_paint_json.c host-sim/paint_json.c $(CORE_SRC) \
		$(shell pkg-config --libs libcjson) -lm -o $@

.PHONY: test-paint-json
test-paint-json: $(HOST)/test_paint_json
	$(Q)$(HOST)/test_paint_json

TEST_TARGETS += test-paint-json
