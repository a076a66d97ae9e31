/*
 * celfw_input.h - where celfw's cel stream comes from: TCP, a serial tty, stdin, a file.
 *
 * Every source is a file descriptor that celfw's main loop polls between
 * frames, so reading never stalls the display. Bytes go to a sink as they
 * arrive, in whatever chunks the source gives: the stream decoder takes any
 * chunking. When a source's byte sequence ends (a TCP client goes away, a
 * file reaches its end) the sink hears `reset`, because a transaction cut
 * there can never be completed by the next client.
 */
#ifndef CELFW_INPUT_H
#define CELFW_INPUT_H

#include <poll.h>
#include <stddef.h>
#include <stdint.h>

typedef struct celfw_input_sink {
    void *user;
    void (*bytes)(void *user, const uint8_t *p, size_t n);
    void (*reset)(void *user, const char *why);
    void (*note)(void *user, const char *what); /* connection events, for the log */
} celfw_input_sink;

typedef struct celfw_input celfw_input;

struct celfw_mqtt_config;
struct celfw_report;

/* Opens spec (none, stdin, file:PATH, tcp:[HOST:]PORT, tty:DEV[:BAUD]). */
int celfw_input_open(celfw_input **in, const char *spec, char *err, size_t errlen);
/* As celfw_input_open, also mqtt[s]://HOST:PORT[/TOPIC] with its settings
 * (celfw_mqtt.h; mc may be NULL for the other specs). */
int celfw_input_open_with(celfw_input **in, const char *spec, const struct celfw_mqtt_config *mc,
                          char *err, size_t errlen);
/* celfw's state for inputs that report it (MQTT's status topic); others ignore it. */
void celfw_input_report(celfw_input *in, const struct celfw_report *r);
/* The descriptors to poll now (at most 2). */
int celfw_input_pollfds(celfw_input *in, struct pollfd *pfd, int max);
/* Handles what poll reported for those descriptors. */
void celfw_input_service(celfw_input *in, const struct pollfd *pfd, int n, const celfw_input_sink *sink);
/* Called once per frame: reopens a tty that went away. */
void celfw_input_tick(celfw_input *in, const celfw_input_sink *sink);
/* What the input is, resolved (e.g. "tcp:127.0.0.1:40123" for port 0). */
const char *celfw_input_describe(const celfw_input *in);
void celfw_input_close(celfw_input *in);

#endif /* CELFW_INPUT_H */
