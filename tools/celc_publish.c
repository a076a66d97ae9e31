/*
 * celc_publish.c - celc publish: a cel stream to a topic of an MQTT broker.
 *
 *   celc publish FILE.cels|SCENE.json --broker mqtt[s]://HOST:PORT --topic T
 *                [--retain] [--credentials FILE] [--client-id ID] [--timeout S]
 *
 * A JSON scene is compiled first (celc_compile_scene, the bytes `celc
 * compile` writes); a .cels file goes as it is, one message. The message is
 * QoS 1, and the command waits for the broker's PUBACK: it speaks MQTT 5, in
 * which the PUBACK carries a reason, so a publish the broker's ACL refuses
 * fails here ("not authorized") instead of vanishing as it would under
 * 3.1.1. --retain makes it the topic's current content, what a sign gets on
 * (re)connect.
 *
 * Credentials never go on the command line: --credentials names a file of
 * `name = value` lines (username, password, ca, cert, key) which, holding a
 * password, must not be readable by group or others. mqtts verifies the
 * broker's certificate against `ca` (or the system's CAs) and its host name.
 *
 * --sign KEY is reserved for signed streams (the key helper of issue 23):
 * until that is wired, publish a stream signed by `celc sign`.
 *
 * Exit status: 0 the broker acknowledged; 1 compile, connection, refusal or
 * time-out; 2 bad command line.
 */
#include <ctype.h>
#include <errno.h>
#include <mosquitto.h>
#include <mqtt_protocol.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "celc_publish.h"
#include "cels_write.h"
#include "cli_num.h"

enum { EXIT_FAIL = 1, EXIT_USAGE = 2 };

typedef struct creds {
    char username[128], password[256], ca[256], cert[256], key[256];
} creds;

typedef struct pub_state {
    int connack;   /* -1 until CONNACK */
    int mid;       /* our message */
    int puback;    /* -1 until its PUBACK: the MQTT 5 reason */
    bool lost;
} pub_state;

static const char usage_text[] =
    "usage: celc publish FILE.cels|SCENE.json --broker mqtt[s]://HOST:PORT --topic TOPIC\n"
    "                    [--retain] [--credentials FILE] [--client-id ID] [--timeout SECONDS]\n"
    "\n"
    "Sends the stream (a scene JSON is compiled first) as one QoS 1 message and waits\n"
    "for the broker to acknowledge it (MQTT 5: a refusal by the ACL is an error).\n"
    "  --retain            keep it as the topic's current content (what signs get on connect)\n"
    "  --credentials FILE  'name = value' lines: username, password, ca, cert, key\n"
    "                      (mode 0600 when it holds a password)\n"
    "  --client-id ID      default celc-PID\n"
    "  --timeout SECONDS   for the connection and the acknowledgement (default 10)\n";

static int usage(const char *what, const char *arg)
{
    fprintf(stderr, "celc publish: %s%s%s (see celc publish --help)\n", what, arg ? ": " : "",
            arg ? arg : "");
    return EXIT_USAGE;
}

static char *trim(char *s)
{
    while (isspace((unsigned char)*s))
        s++;
    char *e = s + strlen(s);
    while (e > s && isspace((unsigned char)e[-1]))
        *--e = 0;
    return s;
}

static bool read_creds(const char *path, creds *c)
{
    FILE *f = fopen(path, "r");
    if (!f) {
        fprintf(stderr, "celc publish: credentials %s: %s\n", path, strerror(errno));
        return false;
    }
    struct stat st;
    bool ok = fstat(fileno(f), &st) == 0;
    char line[600];
    int no = 0;
    while (ok && fgets(line, sizeof line, f)) {
        no++;
        char *s = trim(line);
        if (!*s || *s == '#')
            continue;
        char *eq = strchr(s, '=');
        if (!eq) {
            fprintf(stderr, "celc publish: credentials %s:%d: expected 'name = value'\n", path, no);
            ok = false;
            break;
        }
        *eq = 0;
        const char *name = trim(s), *value = trim(eq + 1);
        struct {
            const char *name;
            char *dst;
            size_t cap;
        } fields[] = {{"username", c->username, sizeof c->username},
                      {"password", c->password, sizeof c->password},
                      {"ca", c->ca, sizeof c->ca},
                      {"cert", c->cert, sizeof c->cert},
                      {"key", c->key, sizeof c->key}};
        size_t k = 0;
        while (k < sizeof fields / sizeof fields[0] && strcmp(fields[k].name, name))
            k++;
        if (k == sizeof fields / sizeof fields[0] || strlen(value) >= fields[k].cap) {
            fprintf(stderr, "celc publish: credentials %s:%d: %s '%s' (username, password, ca, "
                            "cert, key)\n",
                    path, no, k == sizeof fields / sizeof fields[0] ? "unknown name" : "too long",
                    name);
            ok = false;
            break;
        }
        memcpy(fields[k].dst, value, strlen(value) + 1);
    }
    fclose(f);
    if (ok && c->password[0] && (st.st_mode & 077) != 0) {
        fprintf(stderr, "celc publish: credentials %s: mode %04o lets others read the password; "
                        "chmod 600 it\n",
                path, (unsigned)(st.st_mode & 07777));
        ok = false;
    }
    return ok;
}

/* mqtt[s]://HOST:PORT, HOST may be [V6]. */
static bool parse_broker(const char *url, bool *tls, char *host, size_t hn, int *port)
{
    *tls = !strncmp(url, "mqtts://", 8);
    if (!*tls && strncmp(url, "mqtt://", 7))
        return false;
    const char *p = url + (*tls ? 8 : 7), *colon;
    if (*p == '[') {
        const char *close = strchr(p, ']');
        if (!close || close[1] != ':')
            return false;
        snprintf(host, hn, "%.*s", (int)(close - p - 1), p + 1);
        colon = close + 1;
    } else {
        colon = strrchr(p, ':');
        if (!colon)
            return false;
        snprintf(host, hn, "%.*s", (int)(colon - p), p);
    }
    long v;
    if (!host[0] || !cli_int(colon + 1, 10, '\0', 1, 65535, &v))
        return false;
    *port = (int)v;
    return true;
}

static void on_connect(struct mosquitto *m, void *user, int rc, int flags,
                       const mosquitto_property *props)
{
    (void)m;
    (void)flags;
    (void)props;
    ((pub_state *)user)->connack = rc;
}

static void on_publish(struct mosquitto *m, void *user, int mid, int reason,
                       const mosquitto_property *props)
{
    (void)m;
    (void)props;
    pub_state *s = user;
    if (mid == s->mid)
        s->puback = reason;
}

static void on_disconnect(struct mosquitto *m, void *user, int rc, const mosquitto_property *props)
{
    (void)m;
    (void)rc;
    (void)props;
    ((pub_state *)user)->lost = true;
}

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

/* Runs the client's loop until *flag leaves -1 or the deadline passes. */
static bool wait_for(struct mosquitto *m, pub_state *s, const int *flag, double deadline)
{
    while (*flag == -1 && !s->lost && now_s() < deadline)
        if (mosquitto_loop(m, 100, 1) != MOSQ_ERR_SUCCESS)
            break;
    return *flag != -1;
}

static int publish(const char *file, const uint8_t *data, size_t len, const char *broker,
                   const char *topic, bool retain, const creds *c, const char *client_id,
                   double timeout)
{
    bool tls;
    char host[256];
    int port;
    if (!parse_broker(broker, &tls, host, sizeof host, &port))
        return usage("--broker expects mqtt[s]://HOST:PORT", broker);
    mosquitto_lib_init();
    char id[64];
    if (!client_id)
        snprintf(id, sizeof id, "celc-%ld", (long)getpid());
    pub_state s = {-1, -1, -1, false};
    struct mosquitto *m = mosquitto_new(client_id ? client_id : id, true, &s);
    int rc = m ? MOSQ_ERR_SUCCESS : MOSQ_ERR_NOMEM;
    if (rc == MOSQ_ERR_SUCCESS)
        rc = mosquitto_int_option(m, MOSQ_OPT_PROTOCOL_VERSION, MQTT_PROTOCOL_V5);
    if (rc == MOSQ_ERR_SUCCESS && (c->username[0] || c->password[0]))
        rc = mosquitto_username_pw_set(m, c->username[0] ? c->username : NULL,
                                       c->password[0] ? c->password : NULL);
    if (rc == MOSQ_ERR_SUCCESS && tls) {
        if (!c->ca[0])
            mosquitto_int_option(m, MOSQ_OPT_TLS_USE_OS_CERTS, 1);
        rc = mosquitto_tls_set(m, c->ca[0] ? c->ca : NULL, c->ca[0] ? NULL : "/etc/ssl/certs",
                               c->cert[0] ? c->cert : NULL, c->key[0] ? c->key : NULL, NULL);
        if (rc == MOSQ_ERR_SUCCESS)
            rc = mosquitto_tls_opts_set(m, 1, NULL, NULL); /* verify the broker */
    }
    const char *stage = "setting up";
    if (rc == MOSQ_ERR_SUCCESS) {
        mosquitto_connect_v5_callback_set(m, on_connect);
        mosquitto_publish_v5_callback_set(m, on_publish);
        mosquitto_disconnect_v5_callback_set(m, on_disconnect);
        stage = "connecting";
        rc = mosquitto_connect(m, host, port, 10);
    }
    int status = EXIT_FAIL;
    double deadline = now_s() + timeout;
    if (rc != MOSQ_ERR_SUCCESS) {
        fprintf(stderr, "celc publish: %s to %s: %s\n", stage, broker,
                rc == MOSQ_ERR_ERRNO ? strerror(errno) : mosquitto_strerror(rc));
    } else if (!wait_for(m, &s, &s.connack, deadline) || s.connack != 0) {
        fprintf(stderr, "celc publish: %s refused the connection: %s\n", broker,
                s.connack > 0 ? mosquitto_reason_string(s.connack)
                              : s.lost ? "connection closed" : "no answer in time");
    } else if ((rc = mosquitto_publish(m, &s.mid, topic, (int)len, data, 1, retain)) !=
               MOSQ_ERR_SUCCESS) {
        fprintf(stderr, "celc publish: %s: %s\n", topic, mosquitto_strerror(rc));
    } else if (!wait_for(m, &s, &s.puback, deadline)) {
        fprintf(stderr, "celc publish: %s on %s: no acknowledgement in %g s\n", file, topic,
                timeout);
    } else if (s.puback >= 0x80) {
        fprintf(stderr, "celc publish: %s refused %s on %s: %s\n", broker, file, topic,
                mosquitto_reason_string(s.puback));
    } else {
        printf("published %s (%zu bytes) to %s on %s%s\n", file, len, topic, broker,
               retain ? ", retained" : "");
        status = 0;
    }
    if (m) {
        mosquitto_disconnect(m);
        mosquitto_destroy(m);
    }
    mosquitto_lib_cleanup();
    return status;
}

static bool read_file(const char *path, uint8_t **data, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        fprintf(stderr, "celc publish: %s: %s\n", path, strerror(errno));
        return false;
    }
    size_t cap = 1 << 16, n = 0;
    uint8_t *buf = malloc(cap);
    size_t got;
    while (buf && (got = fread(buf + n, 1, cap - n, f)) > 0) {
        n += got;
        if (n == cap) {
            uint8_t *bigger = cap <= ((size_t)256 << 20) ? realloc(buf, cap * 2) : NULL;
            if (!bigger) {
                free(buf);
                buf = NULL;
                break;
            }
            buf = bigger;
            cap *= 2;
        }
    }
    bool ok = buf && !ferror(f);
    fclose(f);
    if (!ok) {
        fprintf(stderr, "celc publish: %s: %s\n", path, buf ? "read error" : "too big");
        free(buf);
        return false;
    }
    *data = buf;
    *len = n;
    return true;
}

int celc_publish_main(int argc, char **argv)
{
    const char *in = NULL, *broker = NULL, *topic = NULL, *cred = NULL, *client_id = NULL;
    bool retain = false;
    double timeout = 10.0;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        bool valued = !strcmp(a, "--broker") || !strcmp(a, "--topic") ||
                      !strcmp(a, "--credentials") || !strcmp(a, "--client-id") ||
                      !strcmp(a, "--timeout") || !strcmp(a, "--sign");
        if (valued && i + 1 >= argc)
            return usage("needs a value", a);
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            fputs(usage_text, stdout);
            return 0;
        } else if (!strcmp(a, "--broker")) {
            broker = argv[++i];
        } else if (!strcmp(a, "--topic")) {
            topic = argv[++i];
        } else if (!strcmp(a, "--credentials")) {
            cred = argv[++i];
        } else if (!strcmp(a, "--client-id")) {
            client_id = argv[++i];
        } else if (!strcmp(a, "--timeout")) {
            if (!cli_real(argv[++i], '\0', 0.1, 3600.0, &timeout))
                return usage("--timeout expects seconds 0.1..3600", argv[i]);
        } else if (!strcmp(a, "--sign")) {
            return usage("--sign is not wired yet: sign the stream with celc sign, then publish "
                         "the signed .cels",
                         NULL);
        } else if (!strcmp(a, "--retain")) {
            retain = true;
        } else if (a[0] == '-' && a[1]) {
            return usage("unknown option", a);
        } else if (!in) {
            in = a;
        } else {
            return usage("one FILE per run, unexpected", a);
        }
    }
    if (!in || !broker || !topic || !topic[0])
        return usage("needs FILE, --broker and --topic", NULL);
    if (strpbrk(topic, "+#"))
        return usage("a topic to publish to has no wildcards", topic);
    creds c;
    memset(&c, 0, sizeof c);
    if (cred && !read_creds(cred, &c))
        return EXIT_FAIL;
    uint8_t *data = NULL;
    size_t len = 0, n = strlen(in);
    if (n > 5 && !strcmp(in + n - 5, ".json")) {
        cels_buf b;
        if (celc_compile_scene(in, &b) != 0)
            return EXIT_FAIL;
        data = b.data; /* the buffer is handed over whole */
        len = b.len;
    } else if (!read_file(in, &data, &len)) {
        return EXIT_FAIL;
    }
    int rc = publish(in, data, len, broker, topic, retain, &c, client_id, timeout);
    memset(&c, 0, sizeof c);
    free(data);
    return rc;
}
