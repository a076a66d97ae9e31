/*
 * celfw_mqtt.h - celfw's fleet input: cel streams from an MQTT broker.
 *
 * A sign subscribes (QoS 1) to its own topic and to its groups' topics; a
 * retained message on a topic is that topic's current content, so a sign
 * that connects or reconnects gets it at once. Each message is one cel
 * stream, handed to celfw's input sink as one byte sequence followed by a
 * reset: the same decoder and the same checks as the same bytes over TCP.
 * The sign publishes a retained status to signs/<id>/status (online, the
 * applied content's BLAKE2b-128 digest and topic, frame rate, last error) and leaves a last will that marks
 * it offline, so `mosquitto_sub -t 'signs/+/status'` shows the fleet.
 *
 * libmosquitto runs its threaded loop (connect, TLS, keepalive, reconnect
 * with a backoff growing to 10 s); its callbacks only queue what arrived and wake
 * celfw's poll loop through an eventfd, and celfw delivers the queue between
 * frames, so the network never blocks a frame and the decoder runs on
 * celfw's thread alone.
 */
#ifndef CELFW_MQTT_H
#define CELFW_MQTT_H

#include <poll.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "celfw_input.h"

#define CELFW_MQTT_MAX_TOPICS 8

/* The settings; credentials come from the config file only (celfw_config.c). */
typedef struct celfw_mqtt_config {
    char sign_id[65];                              /* client id and status topic */
    char topics[CELFW_MQTT_MAX_TOPICS][256];       /* --mqtt-topic: group topics */
    int topic_count;
    char username[128];
    char password_file[256];                       /* first line is the password; mode 0600 */
    char ca_file[256];                             /* mqtts: the CA that signed the broker */
    char cert_file[256], key_file[256];            /* mqtts: client certificate, if any */
    double status_interval;                        /* seconds between status refreshes */
} celfw_mqtt_config;

/* What celfw reports about itself, for the status topic. */
typedef struct celfw_report {
    uint64_t commits;        /* streams applied so far */
    uint64_t stream_errors;  /* refused or damaged transactions so far */
    double fps;              /* frames per second lately; < 0: unknown */
    const char *last_error;  /* the latest refusal or error, or NULL */
    uint64_t seq;            /* the applied stream's signature sequence; 0 = unsigned/unknown */
} celfw_report;

typedef struct celfw_mqtt celfw_mqtt;

/* Whether an input spec is for this module (mqtt:// or mqtts://). */
bool celfw_mqtt_spec(const char *spec);

/*
 * Starts the client for spec mqtt[s]://HOST:PORT[/TOPIC] (TOPIC defaults to
 * signs/<sign-id>). Fails on a malformed spec or unusable credentials
 * (unreadable files, a password file others may read); a broker that is not
 * there is not a failure: the client keeps trying.
 */
int celfw_mqtt_open(celfw_mqtt **m, const char *spec, const celfw_mqtt_config *cfg, char *err,
                    size_t errlen);
int celfw_mqtt_pollfds(celfw_mqtt *m, struct pollfd *pfd, int max);
/* Delivers queued messages and events to the sink (after poll, or any time). */
void celfw_mqtt_service(celfw_mqtt *m, const celfw_input_sink *sink);
/* Once per frame: sends a status that is due. */
void celfw_mqtt_tick(celfw_mqtt *m);
/* celfw's state changed (a commit, an error) or a periodic refresh is due. */
void celfw_mqtt_report(celfw_mqtt *m, const celfw_report *r);
const char *celfw_mqtt_describe(const celfw_mqtt *m);
/* Publishes an offline status, disconnects and frees. */
void celfw_mqtt_close(celfw_mqtt *m);

#endif /* CELFW_MQTT_H */
