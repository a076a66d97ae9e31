/*
 * celfw_child.h - celfw as a child process of a test (see celfw_child.c).
 *
 * The program is $CELFW, else build/host/celfw. Its stderr is collected
 * into `log` as it arrives; wait_line finds the next line containing a
 * needle after the last line found, so a test reads the log in order.
 */
#ifndef CELFW_CHILD_H
#define CELFW_CHILD_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <sys/types.h>

#include "celscan_private.h"

typedef struct child {
    pid_t pid;
    int err_fd, in_fd;
    char log[65536];
    size_t len, seen;
} child;

/* The celfw binary the tests run. */
const char *celfw_child_path(void);
/* Seconds on the monotonic clock. */
double now_s(void);
/* Starts celfw with args (NULL-terminated); stdin is a pipe if want_stdin. */
bool spawn(child *c, const char *const *args, bool want_stdin);
/* Reads what celfw has written to stderr so far. */
void drain(child *c);
/* Waits for a log line containing needle (after the last one found); copies it out. */
bool wait_line(child *c, const char *needle, double timeout, char *out, size_t outlen);
/* Waits for exit; kills after the timeout. Returns the exit status, 128 + signal, or -1. */
int wait_exit(child *c, double timeout);
/* The number after " key=" in a status line, ~0 if absent. */
unsigned long long field(const char *line, const char *key);
/* A TCP connection to 127.0.0.1:port, or -1. */
int tcp_connect(int port);
/* Writes all n bytes; false if the peer went away. */
bool send_all(int fd, const uint8_t *p, size_t n);

typedef struct fake_gud fake_gud;
/* The core's rendering of s at time t over a w x h output with celfw's
 * defaults (4 sub-scanlines), as an RGB565 panel gets it: w * h * 2 bytes to
 * free(), or NULL if it cannot render. */
uint8_t *render_panel_rgb565(const cs_scene *s, float t, int w, int h);
/* Pixels of the emulated panel (w x h, RGB565) that differ from the window at
 * x,y of want (an RGB565 image want_w pixels wide); all of them if want is NULL. */
int compare_panel_tile(fake_gud *dev, const uint8_t *want, int want_w, int x, int y, int w, int h);
/* Pixels of the emulated panel (w x h) that differ from render_panel_rgb565(s, t, w, h). */
int compare_panel_scene(fake_gud *dev, const cs_scene *s, float t, int w, int h);

#endif /* CELFW_CHILD_H */
