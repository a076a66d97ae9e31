# mk/svg.mk - the SVG/text importer (tools/svg), `celc import` / `celc text`
# (tools/celc_import.c), the standalone build/host/svgimport and test_svg.
#
#   make build/host/svgimport     the importer on its own (import, text, render)
#   make test-svg                 unit, coverage and librsvg comparison checks
#   make svg-rsvg-full            every installed icon against rsvg-convert (report only)
#   make svg-conformance          resvg's conformance suite (../shared/conformance/resvg), per category
#   make svg-conformance-doc      the same, written to docs/SVG-CONFORMANCE.md
#   make fuzz-svg                 libFuzzer on the importer for FUZZ_TIME s (default 60)
#   make fuzz-svg-smoke           a short run of it (FUZZ_SVG_SMOKE_TIME, default 20 s), in `make test`
#
# The importer is host code: expat, FreeType, fontconfig, HarfBuzz, FriBidi, cJSON and libpng
# from Debian, linked with the freestanding core library built as the main Makefile does.

SVG_PKGS := expat freetype2 fontconfig harfbuzz fribidi libcjson libpng
SVG_CFLAGS = $(shell pkg-config --cflags $(SVG_PKGS) 2>/dev/null)
SVG_LIBS = $(shell pkg-config --libs $(SVG_PKGS) 2>/dev/null) -lm

SVG_LIB_SRC := $(sort $(wildcard tools/svg/sv_*.c))
SVG_LIB_OBJ := $(patsubst %.c,$(HOST)/obj/%.o,$(SVG_LIB_SRC))
SVG_CELC_OBJ := $(HOST)/obj/tools/celc_import.o $(HOST)/obj/tools/cli_num.o
SVG_TEST_SRC := tests/test_svg.c tests/test_svg_unit.c tests/test_svg_cov.c \
        tests/test_svg_beta.c tests/test_svg_rsvg.c tests/test_svg_hostile.c tests/svg_refscan.c
SVG_TEST_OBJ := $(patsubst %.c,$(HOST)/obj/%.o,$(SVG_TEST_SRC))
# celsim's scene loader, to check that the JSON the importer writes loads
# into the scene its cs_scene back end builds
SVG_TEST_LOADER := $(HOST)/obj/host-sim/scene_json.o $(HOST)/obj/host-sim/paint_json.o

$(SVG_LIB_OBJ) $(SVG_CELC_OBJ) $(HOST)/obj/tools/svg/svgimport_main.o: \
        PKG_CFLAGS += $(SVG_CFLAGS) -Wconversion -Wno-sign-conversion -Wno-float-conversion
$(SVG_TEST_OBJ): PKG_CFLAGS += $(SVG_CFLAGS)

$(HOST)/libsvgimport.a: $(SVG_LIB_OBJ)
	$(Q)rm -f $@ && ar rcs $@ $^

$(HOST)/svgimport: $(HOST)/obj/tools/svg/svgimport_main.o $(SVG_CELC_OBJ) $(HOST)/obj/tools/cli.o \
        $(HOST)/obj/tools/cels_write.o $(HOST)/libsvgimport.a $(HOST)/libcelscan.a
	$(Q)$(CC) -o $@ $^ $(SVG_LIBS)

$(HOST)/tests/test_svg: $(SVG_TEST_OBJ) $(SVG_TEST_LOADER) $(HOST)/libsvgimport.a \
        $(HOST)/libcelscan.a
	@mkdir -p $(dir $@)
	$(Q)$(CC) -o $@ $^ $(SVG_LIBS)

# The CI run: unit checks, stroke and text coverage at 16, 128 and 512 px,
# and a deterministic subset of installed icons against rsvg-convert.
.PHONY: test-svg svg-rsvg-full
test-svg: $(HOST)/tests/test_svg
	$(Q)$(HOST)/tests/test_svg --outdir $(BUILD)/svg-test

# Every icon of the installed themes (minutes): statistics and failure causes.
svg-rsvg-full: $(HOST)/tests/test_svg
	$(Q)$(HOST)/tests/test_svg --only rsvg --all --outdir $(BUILD)/svg-full

# resvg's conformance suite, beside the project and never copied into it:
# each test through `celc import` and `celsim render` in a process of its
# own (10 s, 512 MB), against the reference over white (tests/svg_conformance.c).
# The run fails if a test crashes or runs over its limits, or if fewer than
# SVG_CONF_FLOOR tests pass; without the suite it says so and skips.
SVG_CONF_SUITE ?= $(CURDIR)/../shared/conformance/resvg
SVG_CONF_FLOOR ?= 600
SVG_CONF_RUN = $(HOST)/tests/svg_conformance $(SVG_CONF_SUITE) --celc $(HOST)/celc \
        --celsim $(HOST)/celsim --notes tests/svg_conformance_notes.txt --outdir $(BUILD)/svg-conformance
$(HOST)/tests/svg_conformance: $(HOST)/obj/tests/svg_conformance.o $(HOST)/obj/tools/cli_num.o \
        $(HOST)/libsvgimport.a $(HOST)/libcelscan.a
	@mkdir -p $(dir $@)
	$(Q)$(CC) -o $@ $^ $(SVG_LIBS)
.PHONY: svg-conformance svg-conformance-doc
svg-conformance: $(HOST)/tests/svg_conformance $(HOST)/celc $(HOST)/celsim
	$(Q)$(SVG_CONF_RUN) --floor $(SVG_CONF_FLOOR)
svg-conformance-doc: $(HOST)/tests/svg_conformance $(HOST)/celc $(HOST)/celsim
	$(Q)$(SVG_CONF_RUN) --report docs/SVG-CONFORMANCE.md

# Demo: imported artwork and text through the product's own path: `celc
# import` / `celc text` to scene JSON and to a cel stream, rendered by celsim
# (imported scenes ask for sRGB blending in their JSON, as SVG renderers blend).
SVG_DEMO := $(BUILD)/demo/svg
SVG_DEMO_ICON := /usr/share/icons/breeze/apps/48/kstars.svg
.PHONY: svg-demo
svg-demo: $(HOST)/celc $(HOST)/celsim
	@mkdir -p $(SVG_DEMO)
	@echo "celc import scenes/svg/sign.svg -> $(SVG_DEMO)/sign.{json,cels,png}"
	$(Q)$(HOST)/celc import scenes/svg/sign.svg -o $(SVG_DEMO)/sign.json -q
	$(Q)$(HOST)/celc import scenes/svg/sign.svg -o $(SVG_DEMO)/sign.cels -q
	$(Q)$(HOST)/celsim render $(SVG_DEMO)/sign.cels -o $(SVG_DEMO)/sign.png --size 1280x720
	$(Q)$(HOST)/celc text "celscan: signage in real fonts" -o $(SVG_DEMO)/text.json \
		--size 48 --position 24,64 --color '#ffd23f' --background '#101820' 2>/dev/null
	$(Q)$(HOST)/celsim render $(SVG_DEMO)/text.json -o $(SVG_DEMO)/text.png
	$(Q)if [ -f $(SVG_DEMO_ICON) ]; then \
		$(HOST)/celc import $(SVG_DEMO_ICON) -o $(SVG_DEMO)/icon.json -q && \
		$(HOST)/celsim render $(SVG_DEMO)/icon.json -o $(SVG_DEMO)/icon.png --size 256x256; fi
	@echo "svg-demo: $(SVG_DEMO)/{sign,text,icon}.png"

# Fuzzing (FUZZ, FUZZ_CC from mk/stream.mk): the importer, celsim's loader
# (the JSON round trip) and the core, under coverage and sanitizers. Seeds:
# the demo sign, every 40th small icon of the themes the tests install and
# every 4th small test of the conformance suite (when it is beside the project).
FUZZ_SVG_SMOKE_TIME ?= 20
FUZZ_SVG_SRC := tests/fuzz_svg.c $(SVG_LIB_SRC) host-sim/scene_json.c host-sim/paint_json.c
FUZZ_SVG_CFLAGS := $(FUZZ_BASE_CFLAGS) -D_GNU_SOURCE -Icore -Ihost-sim -Itools/svg -Itools \
        $(shell pkg-config --cflags $(SVG_PKGS) 2>/dev/null)
$(eval $(call flags_record,fuzz-svg,$(FUZZ_CC) $(FUZZ_SVG_CFLAGS)))
$(FUZZ)/svg/%.o: %.c $(CORE_HDR) tests/fuzz_check.h $(wildcard tools/svg/*.h) host-sim/scene_json.h $(FLAGS_DIR)/fuzz-svg
	@mkdir -p $(dir $@)
	$(Q)$(FUZZ_CC) $(FUZZ_SVG_CFLAGS) -fsanitize=fuzzer-no-link,address,undefined -c $< -o $@
$(FUZZ)/fuzz_svg: $(patsubst %.c,$(FUZZ)/svg/%.o,$(FUZZ_SVG_SRC)) $(FUZZ_CORE_OBJ)
	$(Q)$(FUZZ_CC) -fsanitize=fuzzer,address,undefined $^ $(SVG_LIBS) -o $@

FUZZ_SEEDS_fuzz_svg = cp scenes/svg/*.svg $(FUZZ)/fuzz_svg.corpus/ && \
        { [ ! -d $(SVG_CONF_SUITE) ] || find $(SVG_CONF_SUITE) -name '*.svg' -size -3k | LC_ALL=C sort | \
          awk 'NR % 4 == 0' | while read -r f; do cp "$$f" "$(FUZZ)/fuzz_svg.corpus/c$$(echo "$$f" | cksum | cut -d' ' -f1).svg"; done; } && \
        find /usr/share/icons -name '*.svg' -size -6k 2>/dev/null | LC_ALL=C sort | awk 'NR % 40 == 0' | \
        while read -r f; do cp "$$f" "$(FUZZ)/fuzz_svg.corpus/$$(echo "$$f" | cksum | cut -d' ' -f1).svg"; done
FUZZ_OPTS_fuzz_svg = -timeout=10 -dict=$(CURDIR)/tests/fuzz_svg.dict -max_len=16384 -rss_limit_mb=2048
.PHONY: fuzz-svg fuzz-svg-smoke
fuzz-svg: $(FUZZ)/fuzz_svg
	$(call run_fuzzer,fuzz_svg,$(FUZZ_TIME),fuzz-svg)
fuzz-svg-smoke: $(FUZZ)/fuzz_svg
	$(call run_fuzzer,fuzz_svg,$(FUZZ_SVG_SMOKE_TIME),fuzz-svg-smoke)

HOST_PROGRAMS += $(HOST)/svgimport
TEST_TARGETS += test-svg fuzz-svg-smoke svg-conformance
DEMO_TARGETS += svg-demo
