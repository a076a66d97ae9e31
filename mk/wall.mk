# mk/wall.mk - video walls: viewports of one output across several boards.
#
#   make test-wall   the tiles of a 2x2 and a 3x1 wall, rendered through
#                    viewports, against the single render of the whole wall,
#                    float for float, in every AA mode; celsim --viewport's
#                    and celfw --wall/--viewport's command lines (part of `make test`)
#   make test-wall-asan  the tiles under AddressSanitizer + UBSan (part of `make test`)
#
# The test loads scenes with the host scene JSON loader (host-sim/scene_json.c).
WALL_TEST_OBJ := $(HOST)/obj/tests/wall_tiles.o $(HOST)/obj/host-sim/scene_json.o \
        $(HOST)/obj/host-sim/paint_json.o
$(HOST)/obj/tests/wall_tiles.o: HOST_CFLAGS += -Itests

$(HOST)/wall_tiles: $(WALL_TEST_OBJ) $(HOST)/libcelscan.a
	$(Q)$(CC) -o $@ $^ $(PKG_LIBS) -lm

.PHONY: test-wall
test-wall: $(HOST)/wall_tiles $(HOST)/celsim $(HOST)/celfw
	$(Q)sh tests/run.sh -- "$(HOST)/wall_tiles scenes" "sh tests/cli_viewport.sh $(HOST)"

TEST_TARGETS += test-wall

# The same tiles under ASan + UBSan, the core included: the viewport's index
# arithmetic (accumulator entries shifted by the window's origin) checked at
# every access. Objects as mk/celc.mk's test-scenes-asan builds them, the
# core the shared sanitizer build.
$(SCENES_ASAN)/wall_tiles: $(patsubst %.o,$(SCENES_ASAN)/obj/%.o,tests/wall_tiles.o \
        host-sim/scene_json.o host-sim/paint_json.o) $(ASAN)/libcelscan.a
	$(Q)$(CC) $(SAN_FLAGS) $^ -o $@ $(PKG_LIBS) -lm

.PHONY: test-wall-asan
test-wall-asan: $(SCENES_ASAN)/wall_tiles
	$(Q)ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 $< scenes >$<.log 2>&1; \
		rc=$$?; sed 's/^wall_tiles:/wall_tiles_asan:/' $<.log; exit $$rc

TEST_TARGETS += test-wall-asan
