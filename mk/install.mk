# mk/install.mk - installing celscan: programs, service, library variants, the Debian package.
#
#   make install [PREFIX=/usr/local] [DESTDIR=...]
#                        celfw, celc, celsim, their man pages, celfw.service, the udev
#                        rules (announced in AppStream metadata), the sysusers.d entry,
#                        the default /etc config, and the core as a library (host,
#                        Cortex-M4F, RV32) with headers, pkg-config files and a CMake
#                        package
#   make install-lib     only the library part
#   make deb             build/pkg/deb/celscan_VERSION_ARCH.deb and libcelscan-dev_...deb
#                        (debhelper, from a copy of the tree; lintian's verdict printed)
#   make test-pkg        the package: files, unit (systemd-analyze), the installed celfw
#                        runs a frame (part of `make test`)
#   make test-consumers  examples/consumer-{make,cmake} built against `make install
#                        DESTDIR=build/pkg/stage` for host and Cortex-M4F; the host ones render
#                        the demo with celsim's CRC; consumer-make's Cortex-M4F build against
#                        a library installed with MCU_CFG=examples/sign/sign_config_160x128.h
#                        (part of `make test`)
#
# The library variants differ in target and capacities: the host one has the
# defaults of core/cs_config.h; the microcontroller ones are built with the
# configuration header MCU_CFG (default the 480x272 boards'), installed next
# to celscan.h, and their pkg-config and CMake entries define CS_CFG_FILE as
# that header, so a consumer compiles celscan.h with the capacities the
# library was built with. `make install MCU_CFG=my_board_config.h` installs
# libraries with other capacities: CS_CFG_FILE is the one knob.

# The package's version, from debian/changelog: one place to change it.
PKG_VERSION := $(shell sed -n '1s/[^0-9.]*\([0-9.]*\).*/\1/p' debian/changelog)
PREFIX ?= /usr/local
DESTDIR ?=
BINDIR ?= $(PREFIX)/bin
LIBDIR ?= $(PREFIX)/lib
INCLUDEDIR ?= $(PREFIX)/include
DATADIR ?= $(PREFIX)/share
MANDIR ?= $(DATADIR)/man
DOCDIR ?= $(DATADIR)/doc/celscan
# /etc for a system install, PREFIX/etc for one in /usr/local or a home directory.
SYSCONFDIR ?= $(if $(filter /usr,$(PREFIX)),/etc,$(PREFIX)/etc)
UNITDIR ?= $(PREFIX)/lib/systemd/system
UDEVRULESDIR ?= $(PREFIX)/lib/udev/rules.d
# Empty: the sysusers.d entry is not installed (debhelper installs it from debian/).
SYSUSERSDIR ?= $(PREFIX)/lib/sysusers.d
# Cross libraries are the same on every host: PREFIX/lib/celscan/<variant>/.
CROSSLIBDIR ?= $(PREFIX)/lib/celscan
MCU_CFG ?= firmware/boards/cs_config_480x272.h

LIB_MCU_VARIANTS := cortex-m4f rv32imafc
LIB_CC_cortex-m4f := $(ARM_CC)
LIB_AR_cortex-m4f := arm-none-eabi-ar
LIB_FLAGS_cortex-m4f := $(ARM_CORE_FLAGS)
LIB_CC_rv32imafc := $(RISCV_CC)
LIB_AR_rv32imafc := riscv64-unknown-elf-ar
LIB_FLAGS_rv32imafc := $(RISCV_CORE_FLAGS)
LIB_CFG_NAME := $(notdir $(MCU_CFG))

define LIB_VARIANT_RULES
$$(eval $$(call flags_record,lib-$(1),$(LIB_CC_$(1)) $(LIB_FLAGS_$(1)) $(CORE_CFLAGS) $(MCU_CFG)))
$(BUILD)/lib/$(1)/%.o: core/%.c $(CORE_HDR) $(MCU_CFG) $(FLAGS_DIR)/lib-$(1)
	@mkdir -p $$(dir $$@)
	$(Q)$(LIB_CC_$(1)) $(LIB_FLAGS_$(1)) $(CORE_CFLAGS) -Werror -I$(dir $(MCU_CFG)) \
		-DCS_CFG_FILE='"$(LIB_CFG_NAME)"' -c $$< -o $$@
$(BUILD)/lib/$(1)/libcelscan.a: $(patsubst core/%.c,$(BUILD)/lib/$(1)/%.o,$(CORE_SRC))
	$(Q)rm -f $$@ && $(LIB_AR_$(1)) rcs $$@ $$^
endef
$(foreach v,$(LIB_MCU_VARIANTS),$(eval $(call LIB_VARIANT_RULES,$(v))))

# The host archive; test-consumers points it at the main build's when it
# builds microcontroller variants alone in a build directory of their own.
LIB_HOST ?= $(HOST)/libcelscan.a
LIB_ARCHIVES := $(LIB_HOST) $(foreach v,$(LIB_MCU_VARIANTS),$(BUILD)/lib/$(v)/libcelscan.a)
INSTALL_PROGRAMS := $(HOST)/celfw $(HOST)/celc $(HOST)/celsim
MAN_PAGES := dist/man/celfw.1 dist/man/celc.1 dist/man/celsim.1 dist/man/celfw.conf.5

.PHONY: install install-programs install-lib build-install deb test-pkg test-consumers
build-install: $(INSTALL_PROGRAMS) $(LIB_ARCHIVES)

install: install-programs install-lib

install-programs: $(INSTALL_PROGRAMS)
	$(Q)install -d $(DESTDIR)$(BINDIR) $(DESTDIR)$(MANDIR)/man1 $(DESTDIR)$(MANDIR)/man5 \
		$(DESTDIR)$(UNITDIR) $(DESTDIR)$(UDEVRULESDIR) $(DESTDIR)$(DOCDIR)/examples \
		$(DESTDIR)$(SYSCONFDIR)/celscan $(DESTDIR)$(DATADIR)/metainfo
	$(Q)install -d -m 0755 $(DESTDIR)$(SYSCONFDIR)/celscan/keys
	$(Q)install -m 0755 $(INSTALL_PROGRAMS) $(DESTDIR)$(BINDIR)/
	$(Q)install -m 0644 $(filter %.1,$(MAN_PAGES)) $(DESTDIR)$(MANDIR)/man1/
	$(Q)install -m 0644 $(filter %.5,$(MAN_PAGES)) $(DESTDIR)$(MANDIR)/man5/
	$(Q)sed -e 's|@BINDIR@|$(BINDIR)|g' -e 's|@SYSCONFDIR@|$(SYSCONFDIR)|g' dist/celfw.service.in \
		> $(DESTDIR)$(UNITDIR)/celfw.service && chmod 0644 $(DESTDIR)$(UNITDIR)/celfw.service
	$(Q)install -m 0644 dist/60-celscan.rules $(DESTDIR)$(UDEVRULESDIR)/
	$(Q)install -m 0644 dist/org.celscan.celfw.metainfo.xml $(DESTDIR)$(DATADIR)/metainfo/
	$(Q)install -m 0644 firmware/linux/celfw.conf.example $(DESTDIR)$(DOCDIR)/examples/
	$(Q)$(if $(SYSUSERSDIR),install -D -m 0644 dist/celscan.sysusers \
		$(DESTDIR)$(SYSUSERSDIR)/celscan.conf)
	@# an administrator's edited config is never overwritten
	$(Q)[ -e $(DESTDIR)$(SYSCONFDIR)/celscan/celfw.conf ] || \
		install -m 0644 dist/celfw.conf $(DESTDIR)$(SYSCONFDIR)/celscan/celfw.conf

install-lib: $(LIB_ARCHIVES)
	$(Q)install -d $(DESTDIR)$(LIBDIR)/pkgconfig $(DESTDIR)$(DATADIR)/pkgconfig \
		$(DESTDIR)$(LIBDIR)/cmake/celscan $(DESTDIR)$(INCLUDEDIR)/celscan
	$(Q)install -m 0644 core/celscan.h core/celscan_private.h core/cs_config.h $(MCU_CFG) \
		$(DESTDIR)$(INCLUDEDIR)/celscan/
	$(Q)install -m 0644 $(LIB_HOST) $(DESTDIR)$(LIBDIR)/
	$(Q)$(foreach v,$(LIB_MCU_VARIANTS),install -D -m 0644 $(BUILD)/lib/$(v)/libcelscan.a \
		$(DESTDIR)$(CROSSLIBDIR)/$(v)/libcelscan.a &&) true
	$(Q)tools/install_meta.sh "$(DESTDIR)" "$(PKG_VERSION)" "$(PREFIX)" "$(LIBDIR)" "$(DATADIR)" \
		"$(INCLUDEDIR)" "$(CROSSLIBDIR)" "$(LIB_CFG_NAME)" "$(LIB_MCU_VARIANTS)" \
		"$(LIB_FLAGS_cortex-m4f)" "$(LIB_FLAGS_rv32imafc)"

# ------------------------------------------------------------ package
# The package is built from a copy of the files git knows (committed or
# not, minus the ignored), so the tree stays clean and a build/ left in it
# is not shipped; the .deb is rebuilt only when one of them changed.
DEB_DIR := $(BUILD)/pkg/deb
DEB_ARCH := $(shell dpkg --print-architecture 2>/dev/null)
DEB_FILE := $(DEB_DIR)/celscan_$(PKG_VERSION)_$(DEB_ARCH).deb
DEB_DEV_FILE := $(DEB_DIR)/libcelscan-dev_$(PKG_VERSION)_$(DEB_ARCH).deb
DEB_SOURCES := $(shell git ls-files -co --exclude-standard 2>/dev/null | grep -v '^build/')
deb: $(DEB_FILE)
$(DEB_FILE) $(DEB_DEV_FILE) &: $(DEB_SOURCES)
	$(Q)tools/build_deb.sh $(DEB_DIR) $(PKG_VERSION)

test-pkg: $(DEB_FILE) $(DEB_DEV_FILE) $(HOST)/celsim
	$(Q)sh tests/pkg_test.sh $(DEB_FILE) $(DEB_DEV_FILE) $(DEB_DIR)/check

# ---------------------------------------------------------- consumers
STAGE := $(BUILD)/pkg/stage
test-consumers: build-install $(HOST)/celc
	$(Q)rm -rf $(STAGE)
	$(Q)$(MAKE) --no-print-directory install DESTDIR=$(abspath $(STAGE)) PREFIX=/usr >/dev/null
	@# CS_CFG_FILE, the one knob: the Cortex-M4F library again with a small sign's capacities
	$(Q)rm -rf $(STAGE)-small
	$(Q)$(MAKE) --no-print-directory install-lib DESTDIR=$(abspath $(STAGE))-small PREFIX=/usr \
		BUILD=$(BUILD)/pkg/small LIB_HOST=$(HOST)/libcelscan.a LIB_MCU_VARIANTS=cortex-m4f \
		MCU_CFG=examples/sign/sign_config_160x128.h >/dev/null
	$(Q)sh tests/consumer_test.sh $(abspath $(STAGE)) $(abspath $(BUILD)/pkg/consumers) $(HOST) \
		$(abspath $(STAGE))-small

TEST_TARGETS += test-pkg test-consumers
