# mk/svg.mk - the SVG/text importer (tools/svg), `celc import` / `celc text`
# (tools/celc_import.c), the standalone build/host/svgimport and test_svg.
#
#   make build/host/svgimport     the importer on its own (import, text, render)
#   make test-svg                 unit, coverage and librsvg comparison checks
#   make svg-rsvg-full            every installed icon against rsvg-convert (report only)
#
# The importer is host code: expat, FreeType, cJSON and libpng from Debian,
# linked with the freestanding core library built as the main Makefile does.

SVG_PKGS := expat freetype2 libcjson libpng
SVG_CFLAGS = $(shell pkg-config --cflags $(SVG_PKGS) 2>/dev/null)
SVG_LIBS = $(shell pkg-config --libs $(SVG_PKGS) 2>/dev/null) -lm

SVG_LIB_SRC := $(sort $(wildcard tools/svg/sv_*.c))
SVG_LIB_OBJ := $(patsubst %.c,$(HOST)/obj/%.o,$(SVG_LIB_SRC))
SVG_CELC_OBJ := $(HOST)/obj/tools/celc_import.o
SVG_TEST_SRC := tests/test_svg.c tests/test_svg_unit.c tests/test_svg_cov.c \
        tests/test_svg_beta.c tests/test_svg_rsvg.c tests/svg_refscan.c
SVG_TEST_OBJ := $(patsubst %.c,$(HOST)/obj/%.o,$(SVG_TEST_SRC))
# celsim's scene loader, to check that the JSON the importer writes loads
# into the scene its cs_scene back end builds
SVG_TEST_LOADER := $(HOST)/obj/host-sim/scene_json.o $(HOST)/obj/host-sim/paint_json.o

$(SVG_LIB_OBJ) $(SVG_CELC_OBJ) $(HOST)/obj/tools/svg/svgimport_main.o: \
        PKG_CFLAGS += $(SVG_CFLAGS) -Wconversion -Wno-sign-conversion -Wno-float-conversion
$(SVG_TEST_OBJ): PKG_CFLAGS += $(SVG_CFLAGS)

$(HOST)/libsvgimport.a: $(SVG_LIB_OBJ)
	$(Q)rm -f $@ && ar rcs $@ $^

$(HOST)/svgimport: $(HOST)/obj/tools/svg/svgimport_main.o $(SVG_CELC_OBJ) $(HOST)/obj/tools/cels_write.o \
        $(HOST)/libsvgimport.a $(HOST)/libcelscan.a
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

# Demo: imported artwork and text as scene JSON (for celsim) and as PNG
# rendered straight through the core; celsim renders the JSON too once built
# (imported artwork with --blend srgb, which its JSON also asks for with
# "canvas": {"blend": "srgb"} for a loader that reads it).
SVG_DEMO := $(BUILD)/demo/svg
SVG_DEMO_ICON := /usr/share/icons/breeze/apps/48/kstars.svg
.PHONY: svg-demo
svg-demo: $(HOST)/svgimport
	@mkdir -p $(SVG_DEMO)
	$(Q)$(HOST)/svgimport import scenes/svg/sign.svg -o $(SVG_DEMO)/sign.json -q
	$(Q)$(HOST)/svgimport render scenes/svg/sign.svg -o $(SVG_DEMO)/sign.png --size 640x360 -q
	$(Q)$(HOST)/svgimport text "celscan: signage in real fonts" -o $(SVG_DEMO)/text.json \
		--size 48 --position 24,64 --color '#ffd23f' --background '#101820' 2>/dev/null
	$(Q)if [ -f $(SVG_DEMO_ICON) ]; then \
		$(HOST)/svgimport import $(SVG_DEMO_ICON) -o $(SVG_DEMO)/icon.json -q && \
		$(HOST)/svgimport render $(SVG_DEMO_ICON) -o $(SVG_DEMO)/icon.png --size 256x256 -q; fi
	$(Q)if [ -x $(HOST)/celsim ]; then for j in sign icon; do \
		[ -f $(SVG_DEMO)/$$j.json ] && $(HOST)/celsim render $(SVG_DEMO)/$$j.json \
			--blend srgb -o $(SVG_DEMO)/$$j-celsim.png; done; \
		$(HOST)/celsim render $(SVG_DEMO)/text.json -o $(SVG_DEMO)/text-celsim.png; fi; true
	@echo "svg-demo: $(SVG_DEMO)/{sign,text,icon}.json and PNGs"

HOST_PROGRAMS += $(HOST)/svgimport
TEST_TARGETS += test-svg
DEMO_TARGETS += svg-demo
