# display.mk - the display contract's template backend (hal/template, built
# by `make` so that it always compiles) and the conformance case every
# display backend passes (tests/display_conformance.h).
#
#   make test-display-conformance   sim, null and template through the contract, and no
#                                   allocation per frame (malloc counted by --wrap);
#   make test-panel-ssd1963         the MCU's SSD1963 panel through the same case, on a
#                                   model of the controller's bus;
#                                   GUD, DRM and HUB75 run the same case in test-linuxhal

TPL_OBJ := $(HOST)/obj/hal/template/display_template.o
all: $(TPL_OBJ)

# What a conformance test links besides its backend: the frame driver, the source, scene loading.
CONF_SUPPORT := $(patsubst %.c,$(HOST)/obj/%.o,$(wildcard hal/host/*.c)) \
        $(HOST)/obj/hal/linux/lx_scene_source.o $(HOST)/obj/host-sim/bands.o \
        $(HOST)/obj/host-sim/scene_json.o $(HOST)/obj/host-sim/paint_json.o
CONF_OBJ := $(HOST)/obj/tests/test_display_conformance.o $(TPL_OBJ) $(HOST)/obj/hal/sim/display_sim.o \
        $(CONF_SUPPORT)
$(HOST)/obj/tests/test_display_conformance.o: HOST_CFLAGS += -Itests -Ihal/linux -Ihal/template

$(HOST)/test_display_conformance: $(CONF_OBJ) $(HOST)/libcelscan.a
	$(Q)$(CC) -o $@ $^ $(PKG_LIBS) -lm -pthread -Wl,--wrap=malloc,--wrap=calloc

.PHONY: test-display-conformance
test-display-conformance: $(HOST)/test_display_conformance $(HOST)/celsim
	$(Q)CELSIM=$(HOST)/celsim $(HOST)/test_display_conformance

# The MCU's SSD1963 panel on the host: its source compiled with the bus writes
# routed into the controller model (tests/ssd1963_model.h, forced in), so the
# object is the test's own, not the firmware's.
SSD_OBJ := $(HOST)/obj/tests/test_panel_ssd1963.o $(HOST)/obj/tests/ssd1963_model.o \
        $(HOST)/obj/tests/ssd1963/panel_ssd1963.o $(HOST)/obj/hal/mcu/mcu_display.o $(CONF_SUPPORT)
$(HOST)/obj/tests/test_panel_ssd1963.o: HOST_CFLAGS += -Itests -Ihal/linux -Ihal/mcu
$(HOST)/obj/tests/ssd1963/panel_ssd1963.o: hal/mcu/panel_ssd1963.c tests/ssd1963_model.h $(FLAGS_DIR)/host-obj
	@mkdir -p $(dir $@)
	$(Q)$(CC) $(HOST_CFLAGS) $(PKG_CFLAGS) -Ihal/mcu -include tests/ssd1963_model.h -c $< -o $@

$(HOST)/test_panel_ssd1963: $(SSD_OBJ) $(HOST)/libcelscan.a
	$(Q)$(CC) -o $@ $^ $(PKG_LIBS) -lm -pthread

.PHONY: test-panel-ssd1963
test-panel-ssd1963: $(HOST)/test_panel_ssd1963
	$(Q)$(HOST)/test_panel_ssd1963

TEST_TARGETS += test-display-conformance test-panel-ssd1963
