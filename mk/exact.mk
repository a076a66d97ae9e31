# mk/exact.mk - exact-area anti-aliasing (issue 3): its test against an
# independent reference, plain and under ASan/UBSan, and the AA-mode bench.
#
#   make test-exact          tests/test_exact.c vs tests/exact_ref.c
#   make test-exact-asan     the same, core and test built with sanitizers
#   make bench-aa            exact vs --aa 5 / 16 on a demo-like and a heavy scene

EXACT_TEST_OBJ := tests/test_exact.o tests/exact_ref.o
EXACT_ASAN := $(ASAN)/exact

$(HOST)/tests/test_exact: $(addprefix $(HOST)/obj/,$(EXACT_TEST_OBJ)) $(HOST)/libcelscan.a
	@mkdir -p $(dir $@)
	$(Q)$(CC) $^ -lm -o $@

# Sanitizer builds keep their objects apart from the plain ones.
# The core is the shared sanitizer build (Makefile, ASAN_CORE_CFLAGS).
$(eval $(call flags_record,exact-asan,$(CC) $(HOST_CFLAGS) $(SAN_FLAGS)))
$(EXACT_ASAN)/obj/%.o: %.c $(FLAGS_DIR)/exact-asan
	@mkdir -p $(dir $@)
	$(Q)$(CC) $(HOST_CFLAGS) -Itests $(SAN_FLAGS) -DTEST_NAME='"test_exact_asan"' -c $< -o $@
$(EXACT_ASAN)/test_exact: $(addprefix $(EXACT_ASAN)/obj/,$(EXACT_TEST_OBJ)) $(ASAN)/libcelscan.a
	$(Q)$(CC) $(SAN_FLAGS) $^ -lm -o $@

$(HOST)/bench_aa_modes: $(HOST)/obj/bench/aa_modes.o $(HOST)/obj/tools/cli_num.o $(HOST)/libcelscan.a
	@mkdir -p $(dir $@)
	$(Q)$(CC) $^ -lm -o $@

.PHONY: test-exact test-exact-asan bench-aa
test-exact: $(HOST)/tests/test_exact
	$(Q)$<
test-exact-asan: $(EXACT_ASAN)/test_exact
	$(Q)$<
bench-aa: $(HOST)/bench_aa_modes
	$(Q)$<

TEST_TARGETS += test-exact test-exact-asan
HOST_PROGRAMS += $(HOST)/bench_aa_modes
