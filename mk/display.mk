# display.mk - the display contract's template backend (hal/template, built
# by `make` so that it always compiles) and the conformance case every
# display backend passes (tests/display_conformance.h).
#
#   make test-display-conformance   sim, null and template through the contract, and no
#                                   allocation per frame (malloc counted by --wrap);
#                                   GUD, DRM and HUB75 run the same case in test-linuxhal

TPL_OBJ := $(HOST)/obj/hal/template/display_template.o
all: $(TPL_OBJ)

CONF_OBJ := $(HOST)/obj/tests/test_display_conformance.o $(TPL_OBJ) \
        $(patsubst %.c,$(HOST)/obj/%.o,$(wildcard hal/host/*.c)) $(HOST)/obj/hal/sim/display_sim.o \
        $(HOST)/obj/hal/linux/lx_scene_source.o $(HOST)/obj/host-sim/bands.o \
        $(HOST)/obj/host-sim/scene_json.o $(HOST)/obj/host-sim/paint_json.o
$(HOST)/obj/tests/test_display_conformance.o: HOST_CFLAGS += -Itests -Ihal/linux -Ihal/template

$(HOST)/test_display_conformance: $(CONF_OBJ) $(HOST)/libcelscan.a
	$(Q)$(CC) -o $@ $^ $(PKG_LIBS) -lm -pthread -Wl,--wrap=malloc,--wrap=calloc

.PHONY: test-display-conformance
test-display-conformance: $(HOST)/test_display_conformance $(HOST)/celsim
	$(Q)CELSIM=$(HOST)/celsim $(HOST)/test_display_conformance

TEST_TARGETS += test-display-conformance
