# mk/mqtt.mk - the fleet: celfw's MQTT input (firmware/linux/celfw_mqtt.c), celc
# publish, and their tests against a real mosquitto broker.
#
#   make test-fleet    a broker on a loopback port with passwords, an ACL and TLS,
#                      three celfw signs and celc publish (part of `make test`)
#
# Included after mk/linuxhal.mk: celfw links libmosquitto, and libsodium for the
# BLAKE2b digest that names a message's content.
LX_PKGS += libmosquitto libsodium


.PHONY: test-fleet
test-fleet: $(HOST)/celfw $(HOST)/celc
	$(Q)sh tests/fleet_broker.sh $(HOST) $(BUILD)/fleet-test

TEST_TARGETS += test-fleet
