# mk/mqtt.mk - the fleet: celfw's MQTT input (firmware/linux/celfw_mqtt.c), celc
# publish, and their tests against a real mosquitto broker.
#
#   make test-fleet    a broker on a loopback port with passwords, an ACL and TLS,
#                      three celfw signs and celc publish (part of `make test`)
#   make bench-fleet   the fleet figure: 200 celfw signs, 10 publishes (BENCHMARKS.md)
#
# Included after mk/linuxhal.mk: celfw links libmosquitto, and libsodium for the
# BLAKE2b digest that names a message's content.
LX_PKGS += libmosquitto libsodium

.PHONY: test-fleet
test-fleet: $(HOST)/celfw $(HOST)/celc
	$(Q)sh tests/fleet_broker.sh $(HOST) $(BUILD)/fleet-test

TEST_TARGETS += test-fleet

# The fleet figure of BENCHMARKS.md: one mosquitto, FLEET_SIGNS celfw processes
# (null display), 10 publishes of the demo to their group (about 10 s for 200).
FLEET_SIGNS ?= 200
.PHONY: bench-fleet
bench-fleet: $(HOST)/celfw $(HOST)/celc
	$(Q)python3 tools/fleet_bench.py $(HOST) --signs $(FLEET_SIGNS) --publishes 10
