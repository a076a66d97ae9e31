# variant.mk - the host programs' core, built twice on x86-64 (tools/core_variant.h):
# for baseline x86-64 (the objects of libcelscan.a) and at -O3 for x86-64-v3, both
# with the same FP_FLAGS, so the same bytes. celsim, celfw and bench link
# libcelscan_host.a, in which the frame's entry points forward to the build the CPU
# (or CELSCAN_CORE, or celsim --core) chooses.
#
#   make test-core-variant   the two builds render every scene alike (make test)
#   make test-runs-v3        tests/test_runs on the x86-64-v3 build's objects, and
#                            tests/test_pixfmt built for it (make test)
#
# Each build is merged into one relocatable object and its symbols renamed with
# objcopy, so the two sit side by side: in the baseline build only the forwarded
# functions (base_cs_*), in the v3 build every symbol it defines (v3_*); what the
# core leaves undefined (memcpy, memset) keeps its name.

CORE_HOST_LIB := $(HOST)/libcelscan_host.a
# The functions tools/core_variant.c forwards (its CORE_VARIANT_FUNCS).
CORE_VARIANT_FORWARDED := cs_frame_begin cs_frame_begin_cached cs_frame_begin_part cs_frame_join \
        cs_cache_build cs_render_line \
        cs_render_line_runs cs_render_line_px cs_render_frame cs_line_pixels \
        cs_line_pixels_scratch cs_line_run
CORE_VARIANT_V3 := $(if $(filter x86_64-%,$(shell $(CC) -dumpmachine)),1,0)
V3 := $(BUILD)/host-v3

$(HOST)/core-base.o: $(CORE_OBJ)
	$(Q)ld -r -o $@.tmp $^ && \
	objcopy $(foreach f,$(CORE_VARIANT_FORWARDED),--redefine-sym $(f)=base_$(f)) $@.tmp $@ && \
	rm -f $@.tmp

CORE_HOST_OBJ := $(HOST)/core-base.o $(HOST)/obj/tools/core_variant.o
$(HOST)/obj/tools/core_variant.o: HOST_CFLAGS += -DCORE_VARIANT_V3=$(CORE_VARIANT_V3)

ifeq ($(CORE_VARIANT_V3),1)
# -fipa-pta: points-to analysis across the file's functions, so that GCC
# knows more of the workspace's arrays apart after inlining (-0.2 M
# instructions of a Many-blobs exact frame, 86.66 M -> 86.47 M; no change
# to the arithmetic).
V3_CORE_CFLAGS := $(filter-out $(OPT),$(CORE_CFLAGS)) -O3 -march=x86-64-v3 -fipa-pta

# Profile-guided (V3_PGO=1, the default): the v3 build is compiled first with
# -fprofile-generate, tools/pgo_train.c renders V3_PGO_SCENES with it (exact, 5
# and 16 sub-scanlines, 1920x1080), and the build proper is compiled from those
# counts. The arithmetic is the same (no fast-math; -ffp-contract=off), so the
# bytes are (make test-core-variant); what changes is layout, inlining and
# unrolling where the training went: -5.0 % instructions in a Many-blobs exact
# frame (98.71 M -> 93.80 M), a scene the training does not render; the
# training adds ~0.5 s to a build. Functions it never ran are
# compiled as without a profile (-fprofile-partial-training). Both compilations
# name their auxiliary files (the gcda counts among them) by one folder and the
# source's name (-dumpdir, -dumpbase): by default the object's path goes into
# the names and into the profile ids of static functions, and the two objects'
# paths differ. Inlining by the counts makes GCC see uninitialised reads that
# cannot happen (cs__line_stack's cel_ranges beyond its count), so that warning
# is off in this compilation; the other builds keep it. V3_PGO=0 builds it as
# before.
V3_PGO ?= 1
V3_PGO_SCENES := scenes/demo.json scenes/bench/thin.json scenes/bench/rational.json
ifeq ($(V3_PGO),1)
V3_GEN := $(BUILD)/host-v3-gen
V3_PROFILE := $(abspath $(V3_GEN))/profile
V3_AUX := -dumpdir $(abspath $(V3_GEN))/aux/
V3_GEN_CFLAGS := $(V3_CORE_CFLAGS) -fprofile-generate -fprofile-update=single \
        -fprofile-dir=$(V3_PROFILE) $(V3_AUX)
$(eval $(call flags_record,host-v3-gen,$(CC) $(V3_GEN_CFLAGS)))
$(V3_GEN)/core/%.o: core/%.c $(CORE_HDR) $(FLAGS_DIR)/host-v3-gen
	@mkdir -p $(dir $@) $(V3_GEN)/aux
	$(Q)$(CC) $(V3_GEN_CFLAGS) -dumpbase $(notdir $<) -c $< -o $@

$(V3_GEN)/pgo_train: $(HOST)/obj/tools/pgo_train.o $(HOST)/obj/host-sim/scene_json.o \
        $(HOST)/obj/host-sim/paint_json.o $(HOST)/obj/tools/cli_num.o \
        $(patsubst core/%.c,$(V3_GEN)/core/%.o,$(CORE_SRC))
	$(Q)$(CC) -fprofile-generate -o $@ $^ $(PKG_LIBS) -lm

# The list of training scenes is recorded too, so that changing it trains again.
$(eval $(call flags_record,host-v3-train,$(V3_PGO_SCENES)))
$(V3_GEN)/profile.stamp: $(V3_GEN)/pgo_train $(V3_PGO_SCENES) $(FLAGS_DIR)/host-v3-train
	$(Q)rm -rf $(V3_PROFILE) && $(V3_GEN)/pgo_train $(V3_PGO_SCENES) && touch $@

V3_CORE_CFLAGS += -fprofile-use -fprofile-partial-training -fprofile-dir=$(V3_PROFILE) \
        $(V3_AUX) -Wno-missing-profile -Wno-maybe-uninitialized
V3_PROFILE_STAMP := $(V3_GEN)/profile.stamp
endif

$(eval $(call flags_record,host-v3,$(CC) $(V3_CORE_CFLAGS)))
$(V3)/core/%.o: core/%.c $(CORE_HDR) $(FLAGS_DIR)/host-v3 $(V3_PROFILE_STAMP)
	@mkdir -p $(dir $@)
	$(Q)$(CC) $(V3_CORE_CFLAGS) $(if $(V3_PROFILE_STAMP),-dumpbase $(notdir $<)) -c $< -o $@

$(HOST)/core-v3.o: $(patsubst core/%.c,$(V3)/core/%.o,$(CORE_SRC))
	$(Q)ld -r -o $@.tmp $^ && \
	nm -g --defined-only $@.tmp | awk '{ print $$3, "v3_" $$3 }' >$@.syms && \
	objcopy --redefine-syms=$@.syms $@.tmp $@ && rm -f $@.tmp $@.syms
CORE_HOST_OBJ += $(HOST)/core-v3.o

# tests/test_runs links libcelscan.a, the baseline build; the v3 build writes
# 8-bit runs its own way (SSSE3 shuffles, ahead of a run: cs_pixfmt.c), so the
# test also runs on the v3 objects themselves (not renamed), where the CPU has
# them (celsim --core x86-64-v3 is refused otherwise).
V3_TEST_RUNS := $(HOST)/tests/test_runs_v3
$(V3_TEST_RUNS): $(HOST)/tests/test_runs.o $(HOST_TEST_REF_OBJ) \
        $(patsubst core/%.c,$(V3)/core/%.o,$(CORE_SRC))
	$(Q)$(CC) $(TEST_CFLAGS) $^ -lm -o $@

# test_pixfmt built for x86-64-v3 itself checks the display path's vector
# lookup of 8-bit codes (cs__srgb8_lanes, cs_rgb888.h) against the scalar one.
V3_TEST_PIXFMT := $(HOST)/tests/test_pixfmt_v3
$(HOST)/tests/test_pixfmt_v3.o: tests/test_pixfmt.c Makefile $(FLAGS_DIR)/host-test
	@mkdir -p $(dir $@)
	$(Q)$(CC) $(TEST_CFLAGS) -march=x86-64-v3 -c $< -o $@
$(V3_TEST_PIXFMT): $(HOST)/tests/test_pixfmt_v3.o $(HOST_TEST_REF_OBJ) \
        $(patsubst core/%.c,$(V3)/core/%.o,$(CORE_SRC))
	$(Q)$(CC) $(TEST_CFLAGS) $^ -lm -o $@

.PHONY: test-runs-v3
test-runs-v3: $(V3_TEST_RUNS) $(V3_TEST_PIXFMT) $(HOST)/celsim
	$(Q)if $(HOST)/celsim render scenes/demo.json --crc --core x86-64-v3 >/dev/null 2>&1; then \
		{ $(V3_TEST_RUNS) && $(V3_TEST_PIXFMT); } >$(HOST)/test-runs-v3.log 2>&1; rc=$$?; \
		cat $(HOST)/test-runs-v3.log; \
		awk -v rc=$$rc '/: [0-9]+ passed, [0-9]+ failed$$/ { p += $$(NF - 3); f += $$(NF - 1) } \
			END { if (rc != 0 && f == 0) f = 1; \
			      printf "test-runs-v3: %d passed, %d failed\n", p, f }' $(HOST)/test-runs-v3.log; \
		exit $$rc; \
	else \
		echo "test-runs-v3: this CPU has no x86-64-v3, skipped"; \
		echo "test-runs-v3: 0 passed, 0 failed"; \
	fi

TEST_TARGETS += test-runs-v3
endif

# The forwarders' object changes with the choice of builds.
$(eval $(call flags_record,core-variant,$(CORE_VARIANT_V3)))
$(HOST)/obj/tools/core_variant.o: $(FLAGS_DIR)/core-variant

$(CORE_HOST_LIB): $(CORE_HOST_OBJ)
	$(Q)rm -f $@ && ar rcs $@ $^

.PHONY: test-core-variant
test-core-variant: $(HOST)/celsim
	$(Q)sh tests/core_variant.sh $(HOST)/celsim

TEST_TARGETS += test-core-variant
