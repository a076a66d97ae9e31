# mk/beta.mk - the beta colour model: tests and the cache benchmark.
#
#   make test-beta        closed-form beta model, mattes, gradients, cache, CSG, dithering
#   make test-beta-asan   the same under AddressSanitizer + UBSan
#   make bench-cache      pre-combination benchmark (static background, moving front)
#
# The tests link the core sources directly (not the freestanding library
# objects) so that the sanitizer build instruments the core too.

BETA_CFLAGS := -std=c11 -O2 -g $(FP_FLAGS) -Wall -Wextra -Wshadow -Icore -Itests -D_POSIX_C_SOURCE=200809L -MMD -MP
$(eval $(call flags_record,beta,$(CC) $(BETA_CFLAGS) $(SAN_FLAGS)))

$(HOST)/test_beta: tests/test_beta.c $(CORE_SRC) $(CORE_HDR) $(FLAGS_DIR)/beta
	@mkdir -p $(dir $@)
	$(Q)$(CC) $(BETA_CFLAGS) tests/test_beta.c $(CORE_SRC) -lm -o $@

$(ASAN)/test_beta: tests/test_beta.c $(CORE_SRC) $(CORE_HDR) $(FLAGS_DIR)/beta
	@mkdir -p $(dir $@)
	$(Q)$(CC) $(BETA_CFLAGS) -O1 $(SAN_FLAGS) tests/test_beta.c $(CORE_SRC) -lm -o $@

$(HOST)/bench_cache_anim: bench/cache_anim.c tools/cli_num.c $(CORE_SRC) $(CORE_HDR) $(FLAGS_DIR)/beta
	@mkdir -p $(dir $@)
	$(Q)$(CC) $(BETA_CFLAGS) -Itools bench/cache_anim.c tools/cli_num.c $(CORE_SRC) -lm -o $@

.PHONY: test-beta test-beta-asan bench-cache
test-beta: $(HOST)/test_beta
	$(Q)$(HOST)/test_beta

test-beta-asan: $(ASAN)/test_beta
	$(Q)ASAN_OPTIONS=detect_leaks=1 $(ASAN)/test_beta

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
