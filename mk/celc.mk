# mk/celc.mk - the scene compiler (celc) and the tests of scenes as streams.
#
#   make build/host/celc    celc compile SCENE.json -o OUT.cels (and celc import, when built in)
#   make test-scenes        every scenes/*.json against its compiled stream, JSON animation,
#                           and the celc / celsim command-line contract (part of `make test`)
#
# celc reuses celsim's scene JSON loader (host-sim/scene_json.c, paint_json.c)
# and the host stream writer (tools/cels_write.c).
#
# celc publish sends a stream to an MQTT broker (tools/celc_publish.c, libmosquitto).
#
# celc import / celc text are the SVG and text importer (tools/celc_import.c
# over tools/svg/, built by mk/svg.mk into libsvgimport.a).
CELC_SRC := tools/celc.c tools/cels_write.c host-sim/scene_json.c host-sim/paint_json.c \
        tools/celc_import.c tools/cli.c tools/cli_num.c tools/cels_sign.c tools/celc_publish.c
CELC_OBJ := $(patsubst %.c,$(HOST)/obj/%.o,$(CELC_SRC))
$(HOST)/obj/tools/celc.o: HOST_CFLAGS += -Itools

$(HOST)/celc: $(CELC_OBJ) $(HOST)/libsvgimport.a $(HOST)/libcelscan.a
	$(Q)$(CC) -o $@ $(CELC_OBJ) $(HOST)/libsvgimport.a $(HOST)/libcelscan.a $(PKG_LIBS) \
		$(SVG_LIBS) $(SODIUM_LIBS) $(shell pkg-config --libs libmosquitto 2>/dev/null)

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
test-scenes: $(HOST)/test_scenes $(HOST)/celc $(HOST)/celsim $(HOST)/svgimport
	$(Q)sh tests/run.sh -- "$(HOST)/test_scenes scenes" "sh tests/cli_stream.sh $(HOST) $(BUILD)/cli-stream"

TEST_TARGETS += test-scenes

# The same in-process tests under ASan + UBSan, the JSON loader and the core
# included (mk/stream.mk does the same for the decoder's own tests).
SCENES_ASAN := $(ASAN)/scenes
# (the core: the shared sanitizer build, build/asan/libcelscan.a)
$(eval $(call flags_record,scenes-asan,$(CC) $(HOST_CFLAGS) $(PKG_CFLAGS) $(SAN_FLAGS)))
$(SCENES_ASAN)/obj/%.o: %.c $(FLAGS_DIR)/scenes-asan
	@mkdir -p $(dir $@)
	$(Q)$(CC) $(HOST_CFLAGS) $(PKG_CFLAGS) -Itests $(SAN_FLAGS) -c $< -o $@
$(SCENES_ASAN)/test_scenes: $(patsubst %.o,$(SCENES_ASAN)/obj/%.o,tests/test_scenes.o \
        tools/cels_write.o tools/cels_read.o host-sim/scene_json.o host-sim/paint_json.o) \
        $(ASAN)/libcelscan.a
	$(Q)$(CC) $(SAN_FLAGS) $^ -o $@ $(PKG_LIBS) -lm

.PHONY: test-scenes-asan
test-scenes-asan: $(SCENES_ASAN)/test_scenes
	$(Q)ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 $< scenes >$<.log 2>&1; \
		rc=$$?; sed 's/^test_scenes:/test_scenes_asan:/' $<.log; exit $$rc

TEST_TARGETS += test-scenes-asan

# `make demo` also compiles the demo to a stream, as a board would receive it.
$(DEMO)/demo.cels: scenes/demo.json $(HOST)/celc
	@mkdir -p $(dir $@)
	@echo "celc compile $< -o $@"
	$(Q)$(HOST)/celc compile $< -o $@
DEMO_TARGETS += $(DEMO)/demo.cels
