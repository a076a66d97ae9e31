/*
 * celfw_input.c - the byte sources behind celfw's cel stream.
 *
 * TCP listens on one port, on loopback unless an address is given, and
 * serves several clients at once, each with its own framer, so no client
 * waits behind another: an idle one, a one-byte-a-second one or an intruder
 * holding a connection open costs a slot and its buffer, never the sign.
 * Clients that get no transaction applied in time are dropped (checked every
 * frame): one that sends nothing, crawls, or sends only what is refused.
 * Keepalive probes catch peers that vanished, and a full house makes room by
 * dropping the client that has gone longest without a transaction applied,
 * so a crowd of intruders cannot keep the operator out.
 * A tty is put in raw mode at the given baud rate. A file is read in chunks
 * so that a large file cannot hold up a frame. All descriptors are
 * non-blocking and only read when poll() says so.
 */
#include <arpa/inet.h>
#include <errno.h>
#include <fcntl.h>
#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
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

/* One byte sequence being read: the tty, stdin, a file, or a TCP client. */
typedef struct session {
    int fd;               /* -1 when none is open */
    uint64_t bytes;
    uint64_t progress_ns; /* when it connected or last had a transaction applied */
    uint64_t applied;     /* its framer's count at progress_ns */
    celfw_framer fr;
} session;

struct celfw_input {
    kind k;
    session one;  /* stdin, file, tty */
    session client[CELFW_INPUT_MAX_CLIENTS];
    int listen_fd;
    bool public;  /* listening beyond loopback */
    uint64_t timeout_ns;
    char desc[300];
    char spec[256];          /* tty: reopened from this after the port goes away */
    time_t next_reopen;
    celfw_mqtt *mqtt;        /* IN_MQTT: the fleet input (celfw_mqtt.c) */
    uint8_t buf[65536]; /* one read's worth: bounds the time a read takes from a frame */
};

static uint64_t now_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint64_t)ts.tv_sec * 1000000000u + (uint64_t)ts.tv_nsec;
}

/* "127.0.0.1:5000" or "[::1]:5000" of an address. */
static void format_addr(const struct sockaddr_storage *ss, char *out, size_t n, bool *loopback)
{
    char h[INET6_ADDRSTRLEN] = "?";
    int port = 0;
    bool lo = false;
    if (ss->ss_family == AF_INET) {
        const struct sockaddr_in *a = (const struct sockaddr_in *)ss;
        inet_ntop(AF_INET, &a->sin_addr, h, sizeof h);
        port = ntohs(a->sin_port);
        lo = (ntohl(a->sin_addr.s_addr) >> 24) == 127;
        snprintf(out, n, "%s:%d", h, port);
    } else if (ss->ss_family == AF_INET6) {
        const struct sockaddr_in6 *a = (const struct sockaddr_in6 *)ss;
        inet_ntop(AF_INET6, &a->sin6_addr, h, sizeof h);
        port = ntohs(a->sin6_port);
        lo = IN6_IS_ADDR_LOOPBACK(&a->sin6_addr) ||
             (IN6_IS_ADDR_V4MAPPED(&a->sin6_addr) && a->sin6_addr.s6_addr[12] == 127);
        snprintf(out, n, "[%s]:%d", h, port);
    } else {
        snprintf(out, n, "?");
    }
    if (loopback)
        *loopback = lo;
}

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
    /* PORT, HOST:PORT or [ADDR]:PORT; a bare port is loopback only */
    char host[256] = "127.0.0.1", port[32];
    const char *colon = strrchr(spec, ':');
    if (spec[0] == '[') {
        const char *close_br = strchr(spec, ']');
        if (!close_br || close_br[1] != ':') {
            snprintf(err, errlen, "input tcp:%s: expected [ADDRESS]:PORT", spec);
            return -1;
        }
        snprintf(host, sizeof host, "%.*s", (int)(close_br - spec - 1), spec + 1);
        snprintf(port, sizeof port, "%s", close_br + 2);
    } else if (colon) {
        snprintf(host, sizeof host, "%.*s", (int)(colon - spec), spec);
        snprintf(port, sizeof port, "%s", colon + 1);
    } else {
        snprintf(port, sizeof port, "%s", spec);
    }
    long pn;
    if (!cli_int(port, 10, '\0', 0, 65535, &pn)) {
        snprintf(err, errlen, "input tcp:%s: '%s' is not a port 0..65535", spec, port);
        return -1;
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
        bind(fd, ai->ai_addr, ai->ai_addrlen) != 0 || listen(fd, 16) != 0 || set_nonblock(fd) != 0) {
        snprintf(err, errlen, "input tcp:%s: cannot listen: %s", spec, strerror(errno));
        if (fd >= 0)
            close(fd);
        freeaddrinfo(ai);
        return -1;
    }
    freeaddrinfo(ai);
    struct sockaddr_storage ss;
    socklen_t sl = sizeof ss;
    memset(&ss, 0, sizeof ss);
    getsockname(fd, (struct sockaddr *)&ss, &sl);
    char a[INET6_ADDRSTRLEN + 16];
    bool lo = false;
    format_addr(&ss, a, sizeof a, &lo);
    in->listen_fd = fd;
    in->public = !lo;
    snprintf(in->desc, sizeof in->desc, "tcp:%s", a);
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
    in->one.fd = fd;
    snprintf(in->desc, sizeof in->desc, "tty:%s:%ld", dev, baud);
    celfw_framer_init(&in->one.fr, in->desc);
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
    in->one.fd = in->listen_fd = -1;
    for (int i = 0; i < CELFW_INPUT_MAX_CLIENTS; i++)
        in->client[i].fd = -1;
    in->timeout_ns = 10000000000u;
    int r = 0;
    if (!strcmp(spec, "none")) {
        in->k = IN_NONE;
        snprintf(in->desc, sizeof in->desc, "none");
    } else if (!strcmp(spec, "stdin")) {
        in->k = IN_STDIN;
        in->one.fd = 0;
        set_nonblock(0);
        snprintf(in->desc, sizeof in->desc, "stdin");
        celfw_framer_init(&in->one.fr, in->desc);
    } else if (!strncmp(spec, "file:", 5)) {
        in->k = IN_FILE;
        in->one.fd = open(spec + 5, O_RDONLY | O_CLOEXEC);
        if (in->one.fd < 0) {
            snprintf(err, errlen, "input %s: %s", spec, strerror(errno));
            r = -1;
        }
        snprintf(in->desc, sizeof in->desc, "%s", spec);
        celfw_framer_init(&in->one.fr, in->desc);
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

void celfw_input_set_timeout(celfw_input *in, double seconds)
{
    in->timeout_ns = (uint64_t)(seconds * 1e9);
}

bool celfw_input_public(const celfw_input *in)
{
    return in->public;
}

int celfw_input_pollfds(celfw_input *in, struct pollfd *pfd, int max)
{
    if (in->k == IN_MQTT)
        return celfw_mqtt_pollfds(in->mqtt, pfd, max);
    int n = 0;
    if (in->one.fd >= 0 && n < max)
        pfd[n++] = (struct pollfd){in->one.fd, POLLIN, 0};
    /* always accepting: a full house makes room (see accept_client) */
    if (in->listen_fd >= 0 && n < max)
        pfd[n++] = (struct pollfd){in->listen_fd, POLLIN, 0};
    for (int i = 0; i < CELFW_INPUT_MAX_CLIENTS && n < max; i++)
        if (in->client[i].fd >= 0)
            pfd[n++] = (struct pollfd){in->client[i].fd, POLLIN, 0};
    return n;
}

static void end_session(session *s, const celfw_input_sink *sink, const char *why)
{
    char what[512];
    snprintf(what, sizeof what, "input %s: %s after %llu bytes", s->fr.name, why, (unsigned long long)s->bytes);
    if (sink->note)
        sink->note(sink->user, what);
    if (sink->reset)
        sink->reset(sink->user, &s->fr, why);
    celfw_framer_free(&s->fr);
    if (s->fd > 0) /* never close stdin's 0: the process may still want it */
        close(s->fd);
    s->fd = -1;
    s->bytes = 0;
}

static void accept_client(celfw_input *in, const celfw_input_sink *sink)
{
    struct sockaddr_storage ss;
    socklen_t sl = sizeof ss;
    int c = accept(in->listen_fd, (struct sockaddr *)&ss, &sl);
    if (c < 0)
        return;
    set_nonblock(c);
    fcntl(c, F_SETFD, FD_CLOEXEC);
    /* peers that vanish without a FIN (power cut, cable) are found in about a minute */
    int one = 1, idle = 30, intvl = 10, cnt = 3;
    setsockopt(c, SOL_SOCKET, SO_KEEPALIVE, &one, sizeof one);
    setsockopt(c, IPPROTO_TCP, TCP_KEEPIDLE, &idle, sizeof idle);
    setsockopt(c, IPPROTO_TCP, TCP_KEEPINTVL, &intvl, sizeof intvl);
    setsockopt(c, IPPROTO_TCP, TCP_KEEPCNT, &cnt, sizeof cnt);
    session *slot = NULL, *stalest = NULL;
    for (int i = 0; i < CELFW_INPUT_MAX_CLIENTS; i++) {
        session *s = &in->client[i];
        if (s->fd < 0 && !slot)
            slot = s;
        if (s->fd >= 0 && (!stalest || s->progress_ns < stalest->progress_ns))
            stalest = s;
    }
    if (!slot) {
        end_session(stalest, sink, "dropped to make room for a new client (every slot taken)");
        slot = stalest;
    }
    char a[INET6_ADDRSTRLEN + 16], name[96];
    format_addr(&ss, a, sizeof a, NULL);
    snprintf(name, sizeof name, "tcp client %s", a);
    slot->fd = c;
    slot->bytes = 0;
    slot->progress_ns = now_ns();
    slot->applied = 0;
    celfw_framer_init(&slot->fr, name);
    char what[160];
    snprintf(what, sizeof what, "input %s connected", name);
    if (sink->note)
        sink->note(sink->user, what);
}

/*
 * A transaction of the session was applied since the last look: it made
 * progress. The sink counts in the framer, when it applies, which may be
 * after the read that brought the bytes (celfw holds frames that arrive
 * while a picture is drawn), so the tick looks too.
 */
static void note_progress(session *s, uint64_t now)
{
    if (s->fr.applied != s->applied) {
        s->applied = s->fr.applied;
        s->progress_ns = now;
    }
}

/* Reads what one session has; its bytes go to the sink with its framer. */
static void read_session(celfw_input *in, session *s, const celfw_input_sink *sink)
{
    ssize_t got = read(s->fd, in->buf, sizeof in->buf);
    if (got > 0) {
        s->bytes += (uint64_t)got;
        sink->bytes(sink->user, &s->fr, in->buf, (size_t)got);
        note_progress(s, now_ns());
    } else if (got == 0) {
        if (in->k == IN_TTY)
            return; /* a tty with no data reads 0 in raw non-blocking mode */
        end_session(s, sink, in->k == IN_TCP ? "closed" : "ended");
    } else if (errno != EAGAIN && errno != EINTR) {
        char why[120];
        snprintf(why, sizeof why, "read failed: %s", strerror(errno));
        end_session(s, sink, why);
    }
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
        if (pfd[i].fd == in->listen_fd) {
            accept_client(in, sink);
            continue;
        }
        if (pfd[i].fd == in->one.fd) {
            read_session(in, &in->one, sink);
            continue;
        }
        for (int k = 0; k < CELFW_INPUT_MAX_CLIENTS; k++)
            if (in->client[k].fd >= 0 && in->client[k].fd == pfd[i].fd)
                read_session(in, &in->client[k], sink);
    }
}

void celfw_input_tick(celfw_input *in, const celfw_input_sink *sink)
{
    if (in->k == IN_MQTT)
        celfw_mqtt_tick(in->mqtt);
    if (in->k == IN_TCP && in->timeout_ns) {
        uint64_t now = now_ns();
        for (int i = 0; i < CELFW_INPUT_MAX_CLIENTS; i++) {
            session *s = &in->client[i];
            if (s->fd >= 0)
                note_progress(s, now);
            if (s->fd >= 0 && now - s->progress_ns > in->timeout_ns) {
                char why[120];
                snprintf(why, sizeof why, "timed out (no whole transaction for %.3g s)", (double)in->timeout_ns / 1e9);
                end_session(s, sink, why);
            }
        }
    }
    /* a USB serial adapter that was pulled out may come back: try once a second */
    if (in->k != IN_TTY || in->one.fd >= 0)
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
    if (in->one.fd > 0)
        close(in->one.fd);
    celfw_framer_free(&in->one.fr);
    for (int i = 0; i < CELFW_INPUT_MAX_CLIENTS; i++) {
        if (in->client[i].fd >= 0)
            close(in->client[i].fd);
        celfw_framer_free(&in->client[i].fr);
    }
    if (in->listen_fd >= 0)
        close(in->listen_fd);
    free(in);
}
