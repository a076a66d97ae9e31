# threads.mk - a frame's lines on several threads (host-sim/bands.c), for
# celsim --threads and celfw --threads on Linux hosts.
#
#   make test-bands       1, 2, 3 and 4 threads against one, every AA mode (part of make test)
#   make test-bands-tsan  the same under ThreadSanitizer (clang), core included (make test)
#   make test-bands-asan  the same under AddressSanitizer + UBSan, core included (make test)
#   make bench-threads    1 and 2 threads against cairo on Many-blobs, and the critical
#                         path of 1, 2 and 4 threads from callgrind (BENCHMARKS.md; ~2-3 min)
#
# The core has no threads: each thread renders lines of the one prepared
# frame in its own workspace (cs_frame_share), so what is tested here is
# that the bytes do not depend on the split, and that the pool shares
# nothing it should not.

BANDS_TEST_OBJ := $(HOST)/obj/tests/test_bands.o $(HOST)/obj/host-sim/bands.o \
        $(HOST)/obj/host-sim/scene_json.o $(HOST)/obj/host-sim/paint_json.o \
        $(HOST)/obj/hal/linux/lx_scene_source.o $(HOST)/obj/hal/host/display_host.o
$(HOST)/obj/tests/test_bands.o: HOST_CFLAGS += -Itests -Ihal/linux

$(HOST)/test_bands: $(BANDS_TEST_OBJ) $(HOST)/libcelscan.a
	$(Q)$(CC) -o $@ $^ $(PKG_LIBS) -lm -pthread

.PHONY: test-bands test-bands-tsan test-bands-asan bench-threads
test-bands: $(HOST)/test_bands
	$(Q)$(HOST)/test_bands scenes

TEST_TARGETS += test-bands

# The sanitizers want every object instrumented, the core's too; -O1 keeps a
# run within seconds. ThreadSanitizer is clang's here (as fuzzing is), with a
# build of the core of its own; AddressSanitizer + UBSan is GCC's, linking the
# one sanitizer build of the core (build/asan/libcelscan.a) the other ASan
# tests link.
#   $(1) the name (tsan, asan), $(2) the sanitizer flags, $(3) the run's
#   environment, $(4) the compiler, $(5) the core's objects
BANDS_SAN_SRC := tests/test_bands.c host-sim/bands.c host-sim/scene_json.c host-sim/paint_json.c \
        hal/linux/lx_scene_source.c hal/host/display_host.c
define bands_san
$$(eval $$(call flags_record,bands-$(1),$(4) $(2)))
$(BUILD)/bands-$(1)/%.o: %.c $(FLAGS_DIR)/bands-$(1)
	@mkdir -p $$(dir $$@)
	$$(Q)$(4) -std=c11 $(2) -O1 -g $(FP_FLAGS) -Icore -Ihal -Ihost-sim -Ihal/linux -Itests \
		-D_POSIX_C_SOURCE=200809L $$(PKG_CFLAGS) -MMD -MP -c $$< -o $$@
$(BUILD)/bands-$(1)/test_bands: $(patsubst %.c,$(BUILD)/bands-$(1)/%.o,$(BANDS_SAN_SRC)) $(5)
	$$(Q)$(4) $(2) -o $$@ $$^ $$(PKG_LIBS) -lm -pthread
test-bands-$(1): $(BUILD)/bands-$(1)/test_bands
	$$(Q)$(3) $$< scenes >$$<.log 2>&1; \
		rc=$$$$?; sed 's/^test_bands:/test_bands_$(1):/' $$<.log; exit $$$$rc
endef
$(eval $(call bands_san,tsan,-fsanitize=thread,TSAN_OPTIONS=halt_on_error=1,clang,\
        $(patsubst %.c,$(BUILD)/bands-tsan/%.o,$(CORE_SRC))))
$(eval $(call bands_san,asan,$(SAN_FLAGS),$(ASAN_ENV),$(CC),$(ASAN)/libcelscan.a))

TEST_TARGETS += test-bands-tsan test-bands-asan

bench-threads: $(BENCH_BIN) $(HOST)/celsim
	@mkdir -p $(BENCH_RESULTS) $(BUILD)/bench
	$(Q)tools/bench_threads.sh $(BENCH_BIN) $(HOST)/celsim $(BENCH_RESULTS) $(BUILD)/bench
	$(Q)python3 tools/bench_md.py $(BENCH_RESULTS) BENCHMARKS.md
