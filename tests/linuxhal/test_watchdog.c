/*
 * test_watchdog.c - celfw under a small supervisor that speaks systemd's notify protocol.
 *
 * A user-level systemd does not run on the build machines, so this harness
 * plays the service manager of celfw.service (Type=notify, NotifyAccess=main,
 * WatchdogSec=): it binds a datagram socket, starts celfw with NOTIFY_SOCKET,
 * WATCHDOG_USEC and WATCHDOG_PID as systemd sets them, accepts messages only
 * from the main process (SO_PASSCRED, as NotifyAccess=main does), and
 *   - waits for READY=1, then sees WATCHDOG=1 pings come within the period;
 *   - freezes celfw with SIGSTOP (a hung renderer), sees the pings stop and
 *     the period run out, and does what systemd does on a watchdog timeout:
 *     SIGABRT (WatchdogSignal's default) followed by SIGCONT, then restarts it
 *     (Restart=on-failure), and sees READY=1 and pings from the new process;
 *   - stops it with SIGTERM: STOPPING=1, exit status 0;
 *   - with WATCHDOG_PID naming another process, celfw is ready but sends no
 *     pings (the variables were meant for someone else).
 * celfw's protocol side is libsystemd's sd_notify; this side is written from
 * sd_notify(3) and systemd.service(5), independent of it.
 *
 * Every wait is bounded; every child is killed and reaped.
 */
#define _GNU_SOURCE /* struct ucred, SO_PASSCRED */
#include <errno.h>
#include <poll.h>
#include <signal.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "testlib.h"

#define WATCHDOG_USEC 1000000 /* the unit says 10 s; the test cannot wait that long */

static const char *celfw_path;
static char sock_path[108];
static int sock_fd = -1;

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec / 1e9;
}

static bool open_socket(void)
{
    char dir[] = "/tmp/celscan-wd-XXXXXX";
    if (!mkdtemp(dir))
        return false;
    struct sockaddr_un a = {.sun_family = AF_UNIX};
    snprintf(sock_path, sizeof sock_path, "%s/notify", dir);
    snprintf(a.sun_path, sizeof a.sun_path, "%s", sock_path);
    int one = 1;
    sock_fd = socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    return sock_fd >= 0 && bind(sock_fd, (struct sockaddr *)&a, sizeof a) == 0 &&
           setsockopt(sock_fd, SOL_SOCKET, SO_PASSCRED, &one, sizeof one) == 0;
}

static void close_socket(void)
{
    if (sock_fd >= 0)
        close(sock_fd);
    unlink(sock_path);
    char *slash = strrchr(sock_path, '/');
    if (slash) {
        *slash = 0;
        rmdir(sock_path);
    }
}

/* Starts celfw on the null display; watchdog_pid 0 means "the child itself". */
static pid_t start(pid_t watchdog_pid)
{
    pid_t pid = fork();
    if (pid != 0)
        return pid;
    char v[32];
    setenv("NOTIFY_SOCKET", sock_path, 1);
    snprintf(v, sizeof v, "%d", WATCHDOG_USEC);
    setenv("WATCHDOG_USEC", v, 1);
    snprintf(v, sizeof v, "%ld", (long)(watchdog_pid ? watchdog_pid : getpid()));
    setenv("WATCHDOG_PID", v, 1);
    unsetenv("LD_PRELOAD"); /* the umockdev wrapper the Linux-board tests run under */
    struct rlimit no_core = {0, 0};
    setrlimit(RLIMIT_CORE, &no_core); /* the SIGABRT below would dump one */
    if (!freopen("/dev/null", "w", stderr) || !freopen("/dev/null", "r", stdin))
        _exit(126);
    execl(celfw_path, celfw_path, "--backend", "null", "--size", "96x48", "--fps", "60", "--input",
          "none", "--scene", "builtin:anim", "--log-interval", "0", (char *)NULL);
    _exit(127);
}

/*
 * Receives messages until one from pid contains want (a line such as
 * "READY=1") or the time is up. Counts WATCHDOG=1 pings from pid on the way
 * and the longest gap between them (from `since`). Returns whether want came.
 */
typedef struct {
    int pings, foreign;
    double last, max_gap;
} ping_log;

static bool receive(pid_t pid, const char *want, double timeout, ping_log *log)
{
    double end = now_s() + timeout;
    for (;;) {
        double left = end - now_s();
        if (left <= 0)
            return false;
        struct pollfd p = {sock_fd, POLLIN, 0};
        if (poll(&p, 1, (int)(left * 1000) + 1) <= 0)
            continue;
        char buf[512], ctl[CMSG_SPACE(sizeof(struct ucred))];
        struct iovec iov = {buf, sizeof buf - 1};
        struct msghdr m = {.msg_iov = &iov, .msg_iovlen = 1, .msg_control = ctl,
                           .msg_controllen = sizeof ctl};
        ssize_t n = recvmsg(sock_fd, &m, MSG_DONTWAIT);
        if (n < 0)
            continue;
        buf[n] = 0;
        struct cmsghdr *c = CMSG_FIRSTHDR(&m);
        struct ucred cred = {0};
        if (c && c->cmsg_level == SOL_SOCKET && c->cmsg_type == SCM_CREDENTIALS)
            memcpy(&cred, CMSG_DATA(c), sizeof cred);
        if (cred.pid != pid) { /* NotifyAccess=main: ignored, but counted */
            log->foreign++;
            continue;
        }
        double t = now_s();
        for (char *line = strtok(buf, "\n"); line; line = strtok(NULL, "\n")) {
            if (!strcmp(line, "WATCHDOG=1")) {
                if (t - log->last > log->max_gap)
                    log->max_gap = t - log->last;
                log->last = t;
                log->pings++;
            }
            if (want && !strcmp(line, want))
                return true;
        }
    }
}

/* Waits up to timeout seconds for pid to end; its wait status, or -1. */
static int reap(pid_t pid, double timeout)
{
    double end = now_s() + timeout;
    int st;
    do {
        if (waitpid(pid, &st, WNOHANG) == pid)
            return st;
        usleep(10000);
    } while (now_s() < end);
    kill(pid, SIGKILL);
    waitpid(pid, &st, 0);
    return -1;
}

/* READY=1, then pings at least once a period for 2 s; returns when the last one came. */
static double check_supervised(pid_t pid, const char *what)
{
    ping_log log = {0};
    CHECK(receive(pid, "READY=1", 10.0, &log), "%s: no READY=1 within 10 s", what);
    log = (ping_log){.last = now_s()};
    receive(pid, NULL, 2.0, &log);
    if (now_s() - log.last > log.max_gap) /* the gap still open counts too */
        log.max_gap = now_s() - log.last;
    double period = WATCHDOG_USEC / 1e6;
    CHECK(log.pings >= 4, "%s: %d WATCHDOG=1 pings in 2 s with a %.1f s period", what, log.pings,
          period);
    CHECK(log.max_gap < period, "%s: %.3f s between pings, the period is %.1f s", what, log.max_gap,
          period);
    CHECK(log.foreign == 0, "%s: %d messages from other processes", what, log.foreign);
    return log.last;
}

static void test_hang_and_restart(void)
{
    pid_t pid = start(0);
    double last_ping = check_supervised(pid, "first start");

    /* A hung renderer: the loop stops, so must the pings. The manager's
     * deadline is the last ping plus the period. */
    kill(pid, SIGSTOP);
    ping_log log = {.last = now_s()};
    receive(pid, NULL, 2.0 * WATCHDOG_USEC / 1e6, &log);
    CHECK(log.pings == 0, "%d pings from a stopped celfw", log.pings);
    CHECK(now_s() - last_ping > WATCHDOG_USEC / 1e6, "the watchdog deadline did not pass");

    /* Watchdog timeout: systemd sends WatchdogSignal (SIGABRT), then SIGCONT
     * so a stopped process receives it. */
    kill(pid, SIGABRT);
    kill(pid, SIGCONT);
    int st = reap(pid, 5.0);
    CHECK(st != -1 && WIFSIGNALED(st) && WTERMSIG(st) == SIGABRT,
          "celfw did not die of the watchdog's SIGABRT (wait status %d)", st);

    /* Restart=on-failure: a killed service is started again. */
    pid = start(0);
    check_supervised(pid, "restart");
    kill(pid, SIGTERM);
    log = (ping_log){.last = now_s()};
    CHECK(receive(pid, "STOPPING=1", 5.0, &log), "no STOPPING=1 after SIGTERM");
    st = reap(pid, 5.0);
    CHECK(st != -1 && WIFEXITED(st) && WEXITSTATUS(st) == 0, "SIGTERM: wait status %d, not exit 0", st);
}

static void test_watchdog_for_another_process(void)
{
    pid_t pid = start(getpid());
    ping_log log = {0};
    CHECK(receive(pid, "READY=1", 10.0, &log), "WATCHDOG_PID elsewhere: no READY=1");
    log = (ping_log){.last = now_s()};
    receive(pid, NULL, 1.0, &log);
    CHECK(log.pings == 0, "WATCHDOG_PID names another process, yet %d pings", log.pings);
    kill(pid, SIGTERM);
    reap(pid, 5.0);
}

int main(void)
{
    celfw_path = getenv("CELFW") ? getenv("CELFW") : "build/host/celfw";
    if (access(celfw_path, X_OK) != 0) {
        fprintf(stderr, "test_watchdog: %s not built (set CELFW)\n", celfw_path);
        return 2;
    }
    signal(SIGPIPE, SIG_IGN);
    if (!open_socket()) {
        fprintf(stderr, "test_watchdog: notify socket %s: %s\n", sock_path, strerror(errno));
        return 2;
    }
    test_hang_and_restart();
    test_watchdog_for_another_process();
    close_socket();
    return tl_summary("test_watchdog");
}
