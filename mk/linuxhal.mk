# linuxhal.mk - celfw (firmware for Linux boards), its GPIO (HUB75 through
# libgpiod), USB (GUD through libusb) and DRM/KMS (libdrm) backends, and their
# tests against emulated kernel devices (umockdev, in process).
#
#   make build/host/celfw     the board program
#   make test-linuxhal        the emulated-device tests (also part of make test)

LX_PKGS := libgpiod libusb-1.0 liblz4 libsystemd libdrm
LX_PKG_CFLAGS = $(shell pkg-config --cflags $(LX_PKGS) 2>/dev/null)
LX_PKG_LIBS = $(shell pkg-config --libs $(LX_PKGS) 2>/dev/null)
LX_UMOCKDEV_CFLAGS = $(shell pkg-config --cflags umockdev-1.0 2>/dev/null)
LX_UMOCKDEV_LIBS = $(shell pkg-config --libs umockdev-1.0 2>/dev/null)
LX_INC := -Ihal/linux -Ihal/gpio -Ihal/usb -Ihal/drm -Ifirmware/linux

LX_HAL_SRC := $(wildcard hal/host/*.c hal/linux/*.c hal/gpio/*.c hal/usb/*.c hal/drm/*.c)
LX_FW_SRC := $(filter-out firmware/linux/celfw.c,$(wildcard firmware/linux/*.c))
LX_HAL_OBJ := $(patsubst %.c,$(HOST)/obj/%.o,$(LX_HAL_SRC))
LX_FW_OBJ := $(patsubst %.c,$(HOST)/obj/%.o,$(LX_FW_SRC))
LX_TEST_SUPPORT := $(patsubst %.c,$(HOST)/obj/%.o,$(filter-out tests/linuxhal/test_%.c,$(wildcard tests/linuxhal/*.c)))
LX_TESTS := $(patsubst tests/linuxhal/%.c,$(HOST)/tests/%,$(wildcard tests/linuxhal/test_*.c))

LX_ALL_OBJ := $(LX_HAL_OBJ) $(LX_FW_OBJ) $(HOST)/obj/firmware/linux/celfw.o $(LX_TEST_SUPPORT) \
        $(patsubst $(HOST)/tests/%,$(HOST)/obj/tests/linuxhal/%.o,$(LX_TESTS))
$(LX_ALL_OBJ): HOST_CFLAGS += -D_DEFAULT_SOURCE $(LX_INC) $(LX_PKG_CFLAGS) $(LX_UMOCKDEV_CFLAGS)
$(patsubst $(HOST)/tests/%,$(HOST)/obj/tests/linuxhal/%.o,$(LX_TESTS)): HOST_CFLAGS += -Ihost-sim -Itests

# celfw shows scene JSON files (--scene FILE.json) with celsim's loader.
LX_JSON_OBJ := $(HOST)/obj/host-sim/scene_json.o $(HOST)/obj/host-sim/paint_json.o
LX_JSON_LIBS = $(PKG_LIBS)
$(HOST)/obj/firmware/linux/celfw_scene_json.o: HOST_CFLAGS += -Ihost-sim
# ... and renders on celsim's thread pool (--threads).
LX_BANDS_OBJ := $(HOST)/obj/host-sim/bands.o

# celfw checks signed streams with the signer's own envelope code (tools/cels_sign.c, libsodium).
$(HOST)/celfw: $(HOST)/obj/firmware/linux/celfw.o $(LX_FW_OBJ) $(LX_HAL_OBJ) $(LX_JSON_OBJ) $(LX_BANDS_OBJ) \
        $(HOST)/obj/tools/cli_num.o $(HOST)/obj/tools/cels_sign.o $(HOST)/obj/tools/cels_write.o \
        $(HOST)/libcelscan_host.a
	@mkdir -p $(dir $@)
	$(Q)$(CC) -o $@ $^ $(LX_PKG_LIBS) $(LX_JSON_LIBS) $(SODIUM_LIBS) -lm -pthread

# The tests also write cel streams (tools/cels_write.c) to feed celfw.
$(HOST)/tests/test_%: $(HOST)/obj/tests/linuxhal/test_%.o $(LX_TEST_SUPPORT) $(LX_FW_OBJ) \
        $(LX_HAL_OBJ) $(LX_JSON_OBJ) $(LX_BANDS_OBJ) $(HOST)/obj/tools/cels_write.o $(HOST)/obj/tools/cli_num.o \
        $(HOST)/obj/tools/cels_sign.o $(HOST)/obj/tools/cels_read.o $(HOST)/libcelscan.a
	@mkdir -p $(dir $@)
	$(Q)$(CC) -o $@ $^ $(LX_PKG_LIBS) $(LX_JSON_LIBS) $(LX_UMOCKDEV_LIBS) $(SODIUM_LIBS) -lm -lpthread

# umockdev does not forward mmap: the emulated DRM card's dumb buffers are
# mapped by this mmap(), linked into test_drm and preloaded into its celfw.
$(HOST)/tests/test_drm: $(HOST)/obj/tests/linuxhal/shim/drm_mmap.o
$(HOST)/tests/drm_mmap.so: tests/linuxhal/shim/drm_mmap.c tests/linuxhal/shim/drm_mmap.h
	@mkdir -p $(dir $@)
	$(Q)$(CC) -shared -fPIC -O2 -Wall -Wextra -o $@ $<

# The tests run the real libgpiod, libusb and libdrm against emulated device
# nodes: libumockdev-preload redirects /dev and /sys into the test's own testbed.
LX_PRELOAD := umockdev-wrapper
.PHONY: test-linuxhal
test-linuxhal: $(LX_TESTS) $(HOST)/celfw $(HOST)/tests/drm_mmap.so
	$(Q)CELFW=$(HOST)/celfw tests/run.sh -- $(foreach t,$(LX_TESTS),"$(LX_PRELOAD) $(t)")

all: $(HOST)/celfw
HOST_PROGRAMS += $(HOST)/celfw
TEST_TARGETS += test-linuxhal
