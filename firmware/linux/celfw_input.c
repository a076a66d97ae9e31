/*
 * celfw_input.c - the byte sources behind celfw's cel stream.
 *
 * TCP listens on one port and serves one client at a time; others wait in
 * the backlog until the current one leaves (a kiosk has one content server).
 * A tty is put in raw mode at the given baud rate. A file is read in chunks
 * so that a large file cannot hold up a frame. All descriptors are
 * non-blocking and only read when poll() says so.
 */
#include <arpa/inet.h>
#include <errno.h>
#include <fcntl.h>
#include <netdb.h>
#include <netinet/in.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>

#include "celfw_input.h"
#include "celfw_mqtt.h"
#include "cli_num.h"

typedef enum kind { IN_NONE, IN_STDIN, IN_FILE, IN_TCP, IN_TTY, IN_MQTT } kind;

struct celfw_input {
    kind k;
    int fd;       /* the data descriptor, -1 when none is open */
    int listen_fd;
    char desc[300];
    char peer[80];
    uint64_t session_bytes;
    char spec[256];          /* tty: reopened from this after the port goes away */
    time_t next_reopen;
    celfw_mqtt *mqtt;        /* IN_MQTT: the fleet input (celfw_mqtt.c) */
    uint8_t buf[65536]; /* one read's worth: bounds the time a read takes from a frame */
};

static int set_nonblock(int fd)
{
    int fl = fcntl(fd, F_GETFL);
    return fl < 0 ? -1 : fcntl(fd, F_SETFL, fl | O_NONBLOCK);
}

static speed_t baud_of(long b)
{
    switch (b) {
    case 9600: return B9600;
    case 19200: return B19200;
    case 38400: return B38400;
    case 57600: return B57600;
    case 115200: return B115200;
    case 230400: return B230400;
    case 460800: return B460800;
    case 921600: return B921600;
    case 1000000: return B1000000;
    case 2000000: return B2000000;
    case 3000000: return B3000000;
    case 4000000: return B4000000;
    }
    return 0;
}

static int open_tcp(celfw_input *in, const char *spec, char *err, size_t errlen)
{
    char host[256] = "0.0.0.0", port[32];
    const char *colon = strrchr(spec, ':');
    if (colon) {
        snprintf(host, sizeof host, "%.*s", (int)(colon - spec), spec);
        snprintf(port, sizeof port, "%s", colon + 1);
    } else {
        snprintf(port, sizeof port, "%s", spec);
    }
    struct addrinfo hints = {0}, *ai = NULL;
    hints.ai_family = AF_UNSPEC;
    hints.ai_socktype = SOCK_STREAM;
    hints.ai_flags = AI_PASSIVE | AI_NUMERICSERV;
    int r = getaddrinfo(host, port, &hints, &ai);
    if (r != 0) {
        snprintf(err, errlen, "input tcp:%s: %s", spec, gai_strerror(r));
        return -1;
    }
    int fd = socket(ai->ai_family, SOCK_STREAM | SOCK_CLOEXEC, 0);
    int one = 1;
    if (fd < 0 || setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one) != 0 ||
        bind(fd, ai->ai_addr, ai->ai_addrlen) != 0 || listen(fd, 4) != 0 || set_nonblock(fd) != 0) {
        snprintf(err, errlen, "input tcp:%s: cannot listen: %s", spec, strerror(errno));
        if (fd >= 0)
            close(fd);
        freeaddrinfo(ai);
        return -1;
    }
    freeaddrinfo(ai);
    struct sockaddr_storage ss;
    socklen_t sl = sizeof ss;
    getsockname(fd, (struct sockaddr *)&ss, &sl);
    char h[INET6_ADDRSTRLEN] = "?";
    int p = 0;
    if (ss.ss_family == AF_INET) {
        struct sockaddr_in *a = (struct sockaddr_in *)&ss;
        inet_ntop(AF_INET, &a->sin_addr, h, sizeof h);
        p = ntohs(a->sin_port);
    } else if (ss.ss_family == AF_INET6) {
        struct sockaddr_in6 *a = (struct sockaddr_in6 *)&ss;
        inet_ntop(AF_INET6, &a->sin6_addr, h, sizeof h);
        p = ntohs(a->sin6_port);
    }
    in->listen_fd = fd;
    snprintf(in->desc, sizeof in->desc, "tcp:%s:%d", h, p);
    return 0;
}

static int open_tty(celfw_input *in, const char *spec, char *err, size_t errlen)
{
    char dev[256];
    long baud = 115200;
    snprintf(dev, sizeof dev, "%s", spec);
    char *colon = strrchr(dev, ':');
    if (colon) {
        if (!cli_int(colon + 1, 10, '\0', 1, 4000000, &baud) || !baud_of(baud)) {
            snprintf(err, errlen, "input tty:%s: '%s' is not a supported baud rate", spec, colon + 1);
            return -1;
        }
        *colon = 0;
    }
    snprintf(in->spec, sizeof in->spec, "%s", spec);
    int fd = open(dev, O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
        snprintf(err, errlen, "input tty:%s: cannot open %s: %s", spec, dev, strerror(errno));
        return -1;
    }
    struct termios t;
    if (tcgetattr(fd, &t) != 0) {
        snprintf(err, errlen, "input tty:%s: %s is not a terminal: %s", spec, dev, strerror(errno));
        close(fd);
        return -1;
    }
    cfmakeraw(&t);
    cfsetispeed(&t, baud_of(baud));
    cfsetospeed(&t, baud_of(baud));
    t.c_cflag |= CLOCAL | CREAD;
    t.c_cc[VMIN] = 0;
    t.c_cc[VTIME] = 0;
    tcsetattr(fd, TCSANOW, &t);
    in->fd = fd;
    snprintf(in->desc, sizeof in->desc, "tty:%s:%ld", dev, baud);
    return 0;
}

int celfw_input_open(celfw_input **out, const char *spec, char *err, size_t errlen)
{
    return celfw_input_open_with(out, spec, NULL, err, errlen);
}

int celfw_input_open_with(celfw_input **out, const char *spec, const celfw_mqtt_config *mc,
                          char *err, size_t errlen)
{
    celfw_input *in = calloc(1, sizeof *in);
    if (!in)
        return -1;
    in->fd = in->listen_fd = -1;
    int r = 0;
    if (!strcmp(spec, "none")) {
        in->k = IN_NONE;
        snprintf(in->desc, sizeof in->desc, "none");
    } else if (!strcmp(spec, "stdin")) {
        in->k = IN_STDIN;
        in->fd = 0;
        set_nonblock(0);
        snprintf(in->desc, sizeof in->desc, "stdin");
    } else if (!strncmp(spec, "file:", 5)) {
        in->k = IN_FILE;
        in->fd = open(spec + 5, O_RDONLY | O_CLOEXEC);
        if (in->fd < 0) {
            snprintf(err, errlen, "input %s: %s", spec, strerror(errno));
            r = -1;
        }
        snprintf(in->desc, sizeof in->desc, "%s", spec);
    } else if (!strncmp(spec, "tcp:", 4)) {
        in->k = IN_TCP;
        r = open_tcp(in, spec + 4, err, errlen);
    } else if (!strncmp(spec, "tty:", 4)) {
        in->k = IN_TTY;
        r = open_tty(in, spec + 4, err, errlen);
    } else if (celfw_mqtt_spec(spec) && mc) {
        in->k = IN_MQTT;
        r = celfw_mqtt_open(&in->mqtt, spec, mc, err, errlen);
        if (r == 0)
            snprintf(in->desc, sizeof in->desc, "%s", celfw_mqtt_describe(in->mqtt));
    } else {
        snprintf(err, errlen, "input '%s': expected none, stdin, file:PATH, tcp:[HOST:]PORT or tty:DEV[:BAUD]",
                 spec);
        r = -1;
    }
    if (r != 0) {
        celfw_input_close(in);
        return -1;
    }
    *out = in;
    return 0;
}

int celfw_input_pollfds(celfw_input *in, struct pollfd *pfd, int max)
{
    if (in->k == IN_MQTT)
        return celfw_mqtt_pollfds(in->mqtt, pfd, max);
    int n = 0;
    if (in->fd >= 0 && n < max)
        pfd[n++] = (struct pollfd){in->fd, POLLIN, 0};
    else if (in->listen_fd >= 0 && n < max) /* accept only while no client is being served */
        pfd[n++] = (struct pollfd){in->listen_fd, POLLIN, 0};
    return n;
}

static void end_session(celfw_input *in, const celfw_input_sink *sink, const char *why)
{
    char what[512];
    snprintf(what, sizeof what, "input %s: %s after %llu bytes", in->k == IN_TCP ? in->peer : in->desc, why,
             (unsigned long long)in->session_bytes);
    if (sink->note)
        sink->note(sink->user, what);
    if (sink->reset)
        sink->reset(sink->user, why);
    if (in->fd > 0) /* never close stdin's 0: the process may still want it */
        close(in->fd);
    in->fd = -1;
    in->session_bytes = 0;
}

void celfw_input_service(celfw_input *in, const struct pollfd *pfd, int n, const celfw_input_sink *sink)
{
    if (in->k == IN_MQTT) {
        celfw_mqtt_service(in->mqtt, sink);
        return;
    }
    for (int i = 0; i < n; i++) {
        if (!pfd[i].revents)
            continue;
        if (pfd[i].fd == in->listen_fd && in->fd < 0) {
            struct sockaddr_storage ss;
            socklen_t sl = sizeof ss;
            int c = accept(in->listen_fd, (struct sockaddr *)&ss, &sl);
            if (c < 0)
                continue;
            set_nonblock(c);
            fcntl(c, F_SETFD, FD_CLOEXEC);
            char h[INET6_ADDRSTRLEN] = "?";
            int port = 0;
            if (ss.ss_family == AF_INET) {
                inet_ntop(AF_INET, &((struct sockaddr_in *)&ss)->sin_addr, h, sizeof h);
                port = ntohs(((struct sockaddr_in *)&ss)->sin_port);
            } else if (ss.ss_family == AF_INET6) {
                inet_ntop(AF_INET6, &((struct sockaddr_in6 *)&ss)->sin6_addr, h, sizeof h);
                port = ntohs(((struct sockaddr_in6 *)&ss)->sin6_port);
            }
            snprintf(in->peer, sizeof in->peer, "tcp client %s:%d", h, port);
            in->fd = c;
            in->session_bytes = 0;
            char what[160];
            snprintf(what, sizeof what, "input %s connected", in->peer);
            if (sink->note)
                sink->note(sink->user, what);
            continue;
        }
        if (pfd[i].fd != in->fd || in->fd < 0)
            continue;
        ssize_t got = read(in->fd, in->buf, sizeof in->buf);
        if (got > 0) {
            in->session_bytes += (uint64_t)got;
            sink->bytes(sink->user, in->buf, (size_t)got);
        } else if (got == 0) {
            if (in->k == IN_TTY)
                continue; /* a tty with no data reads 0 in raw non-blocking mode */
            end_session(in, sink, in->k == IN_TCP ? "closed" : "ended");
        } else if (errno != EAGAIN && errno != EINTR) {
            char why[120];
            snprintf(why, sizeof why, "read failed: %s", strerror(errno));
            end_session(in, sink, why);
        }
    }
}

void celfw_input_tick(celfw_input *in, const celfw_input_sink *sink)
{
    if (in->k == IN_MQTT)
        celfw_mqtt_tick(in->mqtt);
    /* a USB serial adapter that was pulled out may come back: try once a second */
    if (in->k != IN_TTY || in->fd >= 0)
        return;
    time_t now = time(NULL);
    if (now < in->next_reopen)
        return;
    in->next_reopen = now + 1;
    char err[300], spec[256];
    snprintf(spec, sizeof spec, "%s", in->spec);
    if (open_tty(in, spec, err, sizeof err) == 0 && sink->note) {
        char what[400];
        snprintf(what, sizeof what, "input %s reopened", in->desc);
        sink->note(sink->user, what);
    }
}

const char *celfw_input_describe(const celfw_input *in)
{
    return in->desc;
}

void celfw_input_report(celfw_input *in, const celfw_report *r)
{
    if (in && in->k == IN_MQTT)
        celfw_mqtt_report(in->mqtt, r);
}

void celfw_input_close(celfw_input *in)
{
    if (!in)
        return;
    celfw_mqtt_close(in->mqtt);
    if (in->fd > 0)
        close(in->fd);
    if (in->listen_fd >= 0)
        close(in->listen_fd);
    free(in);
}
