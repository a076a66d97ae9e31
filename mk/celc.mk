# mk/celc.mk - the scene compiler (celc) and the tests of scenes as streams.
#
#   make build/host/celc    celc compile SCENE.json -o OUT.cels (and celc import, when built in)
#   make test-scenes        every scenes/*.json against its compiled stream, JSON animation,
#                           and the celc / celsim command-line contract (part of `make test`)
#
# celc reuses celsim's scene JSON loader (host-sim/scene_json.c, paint_json.c)
# and the host stream writer (tools/cels_write.c).
#
# The SVG importer (celc import) is written separately as tools/celc_import.c,
# `int celc_import_main(int argc, char **argv)`. It is compiled in when that file
# exists; its author adds any further sources to CELC_IMPORT_SRC and libraries
# to CELC_IMPORT_LIBS here.
CELC_IMPORT_SRC := $(wildcard tools/celc_import.c)
CELC_IMPORT_LIBS :=
CELC_SRC := tools/celc.c tools/cels_write.c host-sim/scene_json.c host-sim/paint_json.c \
        $(CELC_IMPORT_SRC)
CELC_OBJ := $(patsubst %.c,$(HOST)/obj/%.o,$(CELC_SRC))
ifneq ($(CELC_IMPORT_SRC),)
$(HOST)/obj/tools/celc.o: HOST_CFLAGS += -DCELC_HAVE_IMPORT
endif

$(HOST)/celc: $(CELC_OBJ) $(HOST)/libcelscan.a
	$(Q)$(CC) -o $@ $(CELC_OBJ) $(HOST)/libcelscan.a $(PKG_LIBS) $(CELC_IMPORT_LIBS) -lm

HOST_PROGRAMS += $(HOST)/celc

# test_scenes: in process, every scene of scenes/ loaded from JSON and from its
# encoded stream gives the same store and the same frames; the JSON "animate"
# syntax, its semantics and its error paths. cli_stream.sh: the same through
# the programs (celc compile, celsim render --crc on .json and .cels, damaged
# streams, exit statuses and messages).
TEST_SCENES_OBJ := $(HOST)/obj/tests/test_scenes.o $(HOST)/obj/tools/cels_write.o \
        $(HOST)/obj/tools/cels_read.o $(HOST)/obj/host-sim/scene_json.o \
        $(HOST)/obj/host-sim/paint_json.o
$(HOST)/obj/tests/test_scenes.o: HOST_CFLAGS += -Itests

$(HOST)/test_scenes: $(TEST_SCENES_OBJ) $(HOST)/libcelscan.a
	$(Q)$(CC) -o $@ $^ $(PKG_LIBS) -lm

.PHONY: test-scenes
test-scenes: $(HOST)/test_scenes $(HOST)/celc $(HOST)/celsim
	$(Q)sh tests/run.sh -- "$(HOST)/test_scenes scenes" "sh tests/cli_stream.sh $(HOST) $(BUILD)/cli-stream"

TEST_TARGETS += test-scenes
