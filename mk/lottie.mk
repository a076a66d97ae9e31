# mk/lottie.mk - the Lottie importer (tools/lottie), in `celc import ANIM.json`.
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
#   make test-lottie          a bounded part for `make test`: a few files, 4 frames each, floor 90 %
LOTTIE_DIR ?= ../shared/conformance/lottie
LOTTIE_CONF_OBJ := $(HOST)/obj/tests/lottie_conf.o $(HOST)/obj/host-sim/scene_json.o \
        $(HOST)/obj/host-sim/png_out.o \
        $(HOST)/obj/host-sim/paint_json.o $(HOST)/obj/tools/cels_write.o \
        $(HOST)/obj/tools/cli_num.o $(LOTTIE_OBJ)
$(HOST)/obj/tests/lottie_conf.o: PKG_CFLAGS += $(shell pkg-config --cflags rlottie 2>/dev/null)

$(HOST)/lottie_conf: $(LOTTIE_CONF_OBJ) $(HOST)/libsvgimport.a $(HOST)/libcelscan.a
	$(Q)$(CC) -o $@ $^ $(SVG_LIBS) $(shell pkg-config --libs rlottie 2>/dev/null)

LOTTIE_SMOKE := anubis.json,gears.json,mask.json,loading_rectangles.json,like.json
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
