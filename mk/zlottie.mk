# mk/zlottie.mk - the Lottie importer (tools/lottie), in `celc import ANIM.json`.
# (Named to be included after mk/stream.mk and mk/svg.mk, whose variables it uses.)
#
#   make build/host/celc      celc import anim.json -o out.json|out.cels (Lottie files)
#
# Host code over cJSON and the SVG importer's geometry (libsvgimport.a).

LOTTIE_SRC := $(sort $(wildcard tools/lottie/lt_*.c))
LOTTIE_OBJ := $(patsubst %.c,$(HOST)/obj/%.o,$(LOTTIE_SRC))
$(LOTTIE_OBJ): PKG_CFLAGS += $(SVG_CFLAGS)

# celc links the importer; celc.c sends `import X.json` to it.
CELC_OBJ += $(LOTTIE_OBJ)
$(HOST)/celc: $(LOTTIE_OBJ)

# Conformance against rlottie (tests/lottie_conf.c; librlottie-dev is the reference renderer).
#   make lottie-conformance   every mappable file of the conformance set, 10 frames each, with
#                             speed; writes the table into docs/LOTTIE.md
#   make test-lottie          a bounded part for `make test`: a few files (a repeater, a track
#                             matte, and 104 precomps folded into 153 cels among them), 4 frames
#                             each, floor 90 % over every file tried (a refused one's frames fail)
LOTTIE_DIR ?= ../shared/conformance/lottie
LOTTIE_CONF_OBJ := $(HOST)/obj/tests/lottie_conf.o $(HOST)/obj/host-sim/scene_json.o \
        $(HOST)/obj/host-sim/png_out.o \
        $(HOST)/obj/host-sim/paint_json.o $(HOST)/obj/tools/cels_write.o \
        $(HOST)/obj/tools/cli_num.o $(LOTTIE_OBJ)
$(HOST)/obj/tests/lottie_conf.o: PKG_CFLAGS += $(shell pkg-config --cflags rlottie 2>/dev/null)

$(HOST)/lottie_conf: $(LOTTIE_CONF_OBJ) $(HOST)/libsvgimport.a $(HOST)/libcelscan.a
	$(Q)$(CC) -o $@ $^ $(SVG_LIBS) $(shell pkg-config --libs rlottie 2>/dev/null)

LOTTIE_SMOKE := gears.json,mask.json,loading_rectangles.json,like.json,telegram.json,done.json
LOTTIE_SMOKE := $(LOTTIE_SMOKE),abstract_circle.json,settings.json,1667-firework.json
.PHONY: lottie-conformance test-lottie
lottie-conformance: $(HOST)/lottie_conf
	@mkdir -p $(BUILD)/lottie
	$(Q)$(HOST)/lottie_conf $(LOTTIE_DIR) --frames 10 --speed --table $(BUILD)/lottie/table.md \
		| tee $(BUILD)/lottie/conformance.txt
	$(Q)python3 tools/lottie/put_table.py docs/LOTTIE.md $(BUILD)/lottie/table.md

test-lottie: $(HOST)/lottie_conf
	$(Q)$(HOST)/lottie_conf $(LOTTIE_DIR) --frames 4 --files $(LOTTIE_SMOKE) | tail -1

TEST_TARGETS += test-lottie
HOST_PROGRAMS += $(HOST)/lottie_conf

# The importer's own tests: what keys become, hostile files (tests/lottie_import.c).
LOTTIE_IMPORT_OBJ := $(HOST)/obj/tests/lottie_import.o $(HOST)/obj/host-sim/scene_json.o \
        $(HOST)/obj/host-sim/paint_json.o $(HOST)/obj/tools/cels_write.o \
        $(HOST)/obj/tools/cli_num.o $(LOTTIE_OBJ)
$(HOST)/obj/tests/lottie_import.o: HOST_CFLAGS += -Itests
$(HOST)/lottie_import: $(LOTTIE_IMPORT_OBJ) $(HOST)/libsvgimport.a $(HOST)/libcelscan.a
	$(Q)$(CC) -o $@ $^ $(SVG_LIBS)
TEST_PROGS += $(HOST)/lottie_import
TEST_DEPS += $(HOST)/lottie_import

# Fuzzing (FUZZ, FUZZ_CC from mk/stream.mk): the importer, celsim's loader and the core
# under coverage and sanitizers; seeds are the conformance set's files under 6 KB and
# scenes/lottie (a repeater, a track matte).
#   make fuzz-lottie         FUZZ_TIME s (default 60)
#   make fuzz-lottie-smoke   FUZZ_LOTTIE_SMOKE_TIME s (default 15), in `make test`
FUZZ_LOTTIE_SMOKE_TIME ?= 15
# The SVG library, the JSON writer and the core are the SVG fuzzer's objects
# (mk/svg.mk: the same flags) and the shared fuzz core (mk/stream.mk).
FUZZ_LOTTIE_SRC := tests/fuzz_lottie.c $(LOTTIE_SRC) tools/cels_write.c tools/cli_num.c
FUZZ_LOTTIE_CFLAGS := $(FUZZ_SVG_CFLAGS)
$(eval $(call flags_record,fuzz-lottie,$(FUZZ_CC) $(FUZZ_LOTTIE_CFLAGS)))
$(FUZZ)/lottie/%.o: %.c $(CORE_HDR) tests/fuzz_check.h $(wildcard tools/lottie/*.h) \
        $(wildcard tools/svg/*.h) host-sim/scene_json.h $(FLAGS_DIR)/fuzz-lottie
	@mkdir -p $(dir $@)
	$(Q)$(FUZZ_CC) $(FUZZ_LOTTIE_CFLAGS) -fsanitize=fuzzer-no-link,address,undefined -c $< -o $@
$(FUZZ)/fuzz_lottie: $(patsubst %.c,$(FUZZ)/lottie/%.o,$(FUZZ_LOTTIE_SRC)) \
        $(patsubst %.c,$(FUZZ)/svg/%.o,$(SVG_LIB_SRC) host-sim/scene_json.c host-sim/paint_json.c) \
        $(FUZZ_CORE_OBJ)
	$(Q)$(FUZZ_CC) -fsanitize=fuzzer,address,undefined $^ $(SVG_LIBS) -o $@

# Seeds: the small conformance files and scenes/lottie, and inputs that once failed (tests/fuzz-lottie-corpus).
FUZZ_SEEDS_fuzz_lottie = cp tests/fuzz-lottie-corpus/* $(FUZZ)/fuzz_lottie.corpus/; \
        find $(LOTTIE_DIR) scenes/lottie -name '*.json' -size -6k 2>/dev/null | \
        while read -r f; do cp "$$f" $(FUZZ)/fuzz_lottie.corpus/; done; true
FUZZ_OPTS_fuzz_lottie = -timeout=10 -dict=$(CURDIR)/tests/fuzz_lottie.dict -max_len=32768 \
        -rss_limit_mb=2048
.PHONY: fuzz-lottie fuzz-lottie-smoke
fuzz-lottie: $(FUZZ)/fuzz_lottie
	$(call run_fuzzer,fuzz_lottie,$(FUZZ_TIME),fuzz-lottie)
fuzz-lottie-smoke: $(FUZZ)/fuzz_lottie
	$(call run_fuzzer,fuzz_lottie,$(FUZZ_LOTTIE_SMOKE_TIME),fuzz-lottie-smoke)
TEST_TARGETS += fuzz-lottie-smoke

# `make demo`: scenes/lottie/spinner.json (a small Lottie file written for celscan: a null
# parent turning with easing, three rounded blades, a hold-keyed colour, a bouncing disc)
# imported to scene JSON and to a cel stream, and 6 frames of the stream rendered by celsim
# (frame-N.png at t = N/5 s).
LOTTIE_DEMO := $(BUILD)/demo/lottie
LOTTIE_DEMO_FRAMES := $(foreach n,0 1 2 3 4 5,$(LOTTIE_DEMO)/frame-$(n).png)
$(LOTTIE_DEMO)/spinner.json $(LOTTIE_DEMO)/spinner.cels: scenes/lottie/spinner.json $(HOST)/celc
	@mkdir -p $(dir $@)
	@echo "celc import $< -o $@"
	$(Q)$(HOST)/celc import $< -o $@
$(LOTTIE_DEMO)/frame-%.png: $(LOTTIE_DEMO)/spinner.cels $(HOST)/celsim
	$(Q)t=$$(awk -v n="$*" 'BEGIN { printf "%.6f", n / 5 }') && \
	echo "celsim render $< -o $@ --time $$t" && $(HOST)/celsim render $< -o $@ --time $$t
DEMO_TARGETS += $(LOTTIE_DEMO)/spinner.json $(LOTTIE_DEMO_FRAMES)

# Imported Lottie files on the 64 KiB board: the conformance files that fit it (make
# lottie-conformance's "fits a board" column) and scenes/groups.json (cel groups, TRS, cubic
# and hold easing) and scenes/lottie/matte_repeat.json (a repeater under a track matte, made for
# this check) streamed to the mps2-an386 firmware under QEMU, frame CRCs against celsim's
# (tools/lottie/qemu_check.sh, about 20 s; in `make test`). Scenes the host takes but the
# board cannot hold are refused there, naming the capacity: bounching_ball.json (66 keys,
# the board holds 64) and scenes/lottie/twenty_layers.json (20 cels, the board holds 16).
LOTTIE_QEMU_FILES := mask.json movie_loading.json spin__lil_loader_v2.json \
        gradient_sleepy_loader.json loading_animation.json scene:scenes/groups.json \
        lottie:scenes/lottie/matte_repeat.json too-many-keys:bounching_ball.json \
        too-many-cels:lottie:scenes/lottie/twenty_layers.json
.PHONY: lottie-qemu
lottie-qemu: firmware-mps2-an386 $(HOST)/celc $(HOST)/celsim
	$(Q)tools/lottie/qemu_check.sh $(HOST)/celc $(HOST)/celsim $(BUILD)/mps2-an386/celfw.elf \
		$(LOTTIE_DIR) $(LOTTIE_QEMU_FILES)
TEST_TARGETS += lottie-qemu
