/*
 * celfw_child.c - celfw as a child process of a test: start it, read its log
 * line by line as it runs, wait for its exit, and talk to it over TCP on
 * loopback, and check what it put on an emulated USB panel. Shared by the
 * tests that run the real binary (test_celfw, test_celfw_robust, test_wall);
 * see celfw_child.h.
 */
#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <glib.h>

#include "celfw_child.h"
#include "fake_gud.h"

const char *celfw_child_path(void)
{
    const char *p = getenv("CELFW");
    return p ? p : "build/host/celfw";
}

double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec / 1e9;
}

/* Starts celfw with args (NULL-terminated); stdin is a pipe if want_stdin. */
bool spawn(child *c, const char *const *args, bool want_stdin)
{
    int ep[2], ip[2] = {-1, -1};
    memset(c, 0, sizeof *c);
    if (pipe(ep) != 0 || (want_stdin && pipe(ip) != 0))
        return false;
    const char *argv[40];
    int n = 0;
    argv[n++] = celfw_child_path();
    for (int i = 0; args[i] && n < 39; i++)
        argv[n++] = args[i];
    argv[n] = NULL;
    c->pid = fork();
    if (c->pid == 0) {
        dup2(ep[1], 2);
        if (want_stdin)
            dup2(ip[0], 0);
        else
            close(0);
        close(ep[0]);
        if (want_stdin)
            close(ip[1]);
        execv(argv[0], (char *const *)argv);
        _exit(127);
    }
    close(ep[1]);
    c->err_fd = ep[0];
    fcntl(c->err_fd, F_SETFL, O_NONBLOCK);
    if (want_stdin) {
        close(ip[0]);
        c->in_fd = ip[1];
    } else {
        c->in_fd = -1;
    }
    return c->pid > 0;
}

void drain(child *c)
{
    for (;;) {
        if (c->len + 1 >= sizeof c->log)
            return;
        ssize_t r = read(c->err_fd, c->log + c->len, sizeof c->log - 1 - c->len);
        if (r <= 0)
            return;
        c->len += (size_t)r;
        c->log[c->len] = 0;
    }
}

/* Waits for a log line containing needle (after the last one found); copies it out. */
bool wait_line(child *c, const char *needle, double timeout, char *out, size_t outlen)
{
    double end = now_s() + timeout;
    do {
        drain(c);
        char *hit = strstr(c->log + c->seen, needle);
        if (hit) {
            char *bol = hit;
            while (bol > c->log && bol[-1] != '\n')
                bol--;
            char *eol = strchr(hit, '\n');
            if (!eol)
                goto again; /* line not complete yet */
            if (out)
                snprintf(out, outlen, "%.*s", (int)(eol - bol), bol);
            c->seen = (size_t)(eol - c->log);
            return true;
        }
    again:
        g_usleep(5000);
    } while (now_s() < end);
    return false;
}

/* Waits for exit; kills after the timeout. Returns the exit status, or -1. */
int wait_exit(child *c, double timeout)
{
    double end = now_s() + timeout;
    int st;
    for (;;) {
        drain(c);
        pid_t r = waitpid(c->pid, &st, WNOHANG);
        if (r == c->pid)
            break;
        if (now_s() > end) {
            kill(c->pid, SIGKILL);
            waitpid(c->pid, &st, 0);
            drain(c);
            fprintf(stderr, "  celfw did not exit; its log:\n%s\n", c->log);
            return -1;
        }
        g_usleep(5000);
    }
    drain(c);
    close(c->err_fd);
    if (c->in_fd >= 0)
        close(c->in_fd);
    return WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
}

unsigned long long field(const char *line, const char *key)
{
    char k[64];
    snprintf(k, sizeof k, " %s=", key);
    const char *p = strstr(line, k);
    return p ? strtoull(p + strlen(k), NULL, 10) : ~0ull;
}

int tcp_connect(int port)
{
    int fd = socket(AF_INET, SOCK_STREAM, 0);
    struct sockaddr_in a = {0};
    a.sin_family = AF_INET;
    a.sin_port = htons((uint16_t)port);
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (connect(fd, (struct sockaddr *)&a, sizeof a) != 0) {
        close(fd);
        return -1;
    }
    return fd;
}

bool send_all(int fd, const uint8_t *p, size_t n)
{
    while (n > 0) {
        ssize_t w = write(fd, p, n);
        if (w <= 0)
            return false;
        p += w;
        n -= (size_t)w;
    }
    return true;
}

/* The truth for the panel: the frame of `s` at time t, rendered by the core, as RGB565. */
uint8_t *render_panel_rgb565(const cs_scene *s, float t, int w, int h)
{
    cs_render_opts o = cs_render_defaults(w, h);
    o.subscanlines = 4;
    o.time = t;
    static cs_workspace ws;
    cs_renderer r;
    cs_error e;
    uint8_t *px = malloc((size_t)w * (size_t)h * 2u);
    float *line = malloc((size_t)w * 3u * sizeof(float));
    if (!px || !line || cs_frame_begin(&r, &ws, s, &o, &e) != CS_OK) {
        free(px);
        free(line);
        return NULL;
    }
    for (int y = 0; y < h; y++) {
        cs_render_line(&r, y, line);
        cs_pixfmt_convert(CS_PIX_RGB565_SRGB, line, w, px + (size_t)y * (size_t)w * 2u);
    }
    free(line);
    return px;
}

int compare_panel_tile(fake_gud *dev, const uint8_t *want, int want_w, int x, int y, int w, int h)
{
    uint8_t *got = malloc((size_t)w * (size_t)h * 2u);
    if (!want || !got) {
        free(got);
        return w * h;
    }
    fake_gud_framebuffer(dev, got, (size_t)w * (size_t)h * 2u);
    int bad = 0;
    for (int r = 0; r < h; r++)
        for (int c = 0; c < w; c++)
            bad += memcmp(got + ((size_t)r * (size_t)w + (size_t)c) * 2u,
                          want + ((size_t)(y + r) * (size_t)want_w + (size_t)(x + c)) * 2u, 2) != 0;
    free(got);
    return bad;
}

int compare_panel_scene(fake_gud *dev, const cs_scene *s, float t, int w, int h)
{
    uint8_t *want = render_panel_rgb565(s, t, w, h);
    int bad = compare_panel_tile(dev, want, w, 0, 0, w, h);
    free(want);
    return bad;
}
