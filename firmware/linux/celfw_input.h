/*
 * celfw_input.h - where celfw's cel stream comes from: TCP, a serial tty, stdin, a file.
 *
 * Every source is a file descriptor that celfw's main loop polls between
 * frames, so reading never stalls the display. Each byte sequence (a TCP
 * connection, the tty, stdin, a file) has its own framer (celfw_frame.h),
 * and bytes go to the sink with it, in whatever chunks they arrive: the
 * sink cuts them into whole frames there, so clients sending at the same
 * time never mix bytes. When a sequence ends (a TCP client goes away or is
 * dropped, a file reaches its end) the sink hears `reset` with its framer,
 * because a transaction cut there can never be completed by the next client.
 *
 * TCP serves up to CELFW_INPUT_MAX_CLIENTS clients at once. A client that
 * gets no transaction applied within the input timeout is dropped (the sink
 * counts applied transactions in the framer: celfw_framer.applied),
 * keepalive probes find peers that vanished without a word, and when every
 * slot is taken a new client takes the slot of the one that has gone longest
 * without a transaction applied: whoever connects first cannot hold the sign.
 */
#ifndef CELFW_INPUT_H
#define CELFW_INPUT_H

#include <poll.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "celfw_frame.h"

#define CELFW_INPUT_MAX_CLIENTS 8
#define CELFW_INPUT_MAX_FDS (1 + CELFW_INPUT_MAX_CLIENTS)

typedef struct celfw_input_sink {
    void *user;
    void (*bytes)(void *user, celfw_framer *src, const uint8_t *p, size_t n);
    void (*reset)(void *user, celfw_framer *src, const char *why);
    void (*note)(void *user, const char *what); /* connection events, for the log */
} celfw_input_sink;

typedef struct celfw_input celfw_input;

struct celfw_mqtt_config;
struct celfw_report;

/* Opens spec (none, stdin, file:PATH, tcp:[HOST:]PORT, tcp:[ADDR]:PORT, tty:DEV[:BAUD]);
 * tcp:PORT listens on 127.0.0.1 only. */
int celfw_input_open(celfw_input **in, const char *spec, char *err, size_t errlen);
/* As celfw_input_open, also mqtt[s]://HOST:PORT[/TOPIC] with its settings
 * (celfw_mqtt.h; mc may be NULL for the other specs). */
int celfw_input_open_with(celfw_input **in, const char *spec, const struct celfw_mqtt_config *mc,
                          char *err, size_t errlen);
/* celfw's state for inputs that report it (MQTT's status topic); others ignore it. */
void celfw_input_report(celfw_input *in, const struct celfw_report *r);
/* A TCP client that gets no transaction applied for this long is dropped (default 10 s). */
void celfw_input_set_timeout(celfw_input *in, double seconds);
/* Whether the input listens beyond loopback (a network can reach it). */
bool celfw_input_public(const celfw_input *in);
/* The descriptors to poll now (at most CELFW_INPUT_MAX_FDS). */
int celfw_input_pollfds(celfw_input *in, struct pollfd *pfd, int max);
/* Handles what poll reported for those descriptors. */
void celfw_input_service(celfw_input *in, const struct pollfd *pfd, int n, const celfw_input_sink *sink);
/* Called once per frame: drops TCP clients past their time-out, reopens a tty that went away. */
void celfw_input_tick(celfw_input *in, const celfw_input_sink *sink);
/* What the input is, resolved (e.g. "tcp:127.0.0.1:40123" for port 0). */
const char *celfw_input_describe(const celfw_input *in);
void celfw_input_close(celfw_input *in);

#endif /* CELFW_INPUT_H */
