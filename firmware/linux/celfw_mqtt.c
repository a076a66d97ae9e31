/*
 * celfw_mqtt.c - the MQTT fleet input (see celfw_mqtt.h).
 *
 * Two threads meet here. A network thread of this file runs libmosquitto
 * (mosquitto_loop, and every connect and reconnect, blocking there and
 * never in celfw's frame loop) and so its callbacks: they copy each message
 * and each event note into a small queue under a mutex and write to an
 * eventfd. celfw's thread polls that eventfd with its other descriptors,
 * takes the queue whole and feeds the messages to the input sink; it alone
 * touches the decoder and the display. The queue is bounded
 * (CELFW_MQTT_QUEUE messages, MAX_QUEUED bytes): a broker that sends faster
 * than celfw takes loses the oldest messages, which are counted and
 * reported, never memory without end. The sign speaks MQTT 5 and tells the
 * broker the largest packet it takes (MAX_MESSAGE and a little), so the
 * broker drops bigger messages for it rather than sending them
 * (libmosquitto would hold a whole packet in memory first).
 *
 * The thread is ours, not mosquitto_loop_start's: that loop gives up for
 * good on errors it deems fatal (a TLS failure while the broker restarts
 * was one, in this test's runs), and a sign must never stop trying. Here
 * every failure waits 1, 2, ... 10 s and tries again. mosquitto_threaded_set
 * tells libmosquitto that celfw's thread publishes (status) concurrently:
 * it queues and wakes the network thread, which does all socket I/O.
 *
 * Retained content comes again with every reconnect. A message whose bytes
 * are those last delivered on its topic (same BLAKE2b-128 digest, from
 * libsodium) is not fed twice: re-applying it would restart its animation and, for a signed
 * stream, be refused as a replay. Not a CRC-32: a cel stream carries the
 * CRC of each transaction after it, so CRC-32 over a whole message is the
 * same for every stream of one length (CRC's residue; measured: the demo
 * and the demo with another background, both 11,112 bytes, gave 6A8781E5).
 * The digest is also what the status reports as the content shown. The own topic is subscribed after the
 * group topics, so at start its retained content is the one that stays.
 *
 * Credentials are read here, from files named in the config file: the
 * password file and the TLS key must not be readable by group or others.
 */
#define _GNU_SOURCE
#include <cjson/cJSON.h>
#include <errno.h>
#include <fcntl.h>
#include <mosquitto.h>
#include <mqtt_protocol.h>
#include <stdarg.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/eventfd.h>
#include <sodium.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "celfw_mqtt.h"
#include "cli_num.h"

#define CELFW_MQTT_QUEUE 16
#define MAX_NOTES 16
#define MAX_MESSAGE (32u << 20) /* a scene transaction is at most 16 MiB (CS_CFG_STREAM_MAX_TXN) */
#define MAX_QUEUED (64u << 20)  /* bytes waiting for celfw's thread, all messages together */
#define KEEPALIVE_S 10
#define STATUS_MIN_NS 250000000ull /* events closer than this share one status message */
#define DIGEST_BYTES 16              /* BLAKE2b-128: names a content, 32 hex digits */

typedef struct digest {
    uint8_t b[DIGEST_BYTES];
} digest;

static digest digest_of(const uint8_t *p, size_t n)
{
    digest d;
    crypto_generichash(d.b, sizeof d.b, p, n, NULL, 0);
    return d;
}

static void digest_hex(const digest *d, char out[2 * DIGEST_BYTES + 1])
{
    sodium_bin2hex(out, 2 * DIGEST_BYTES + 1, d->b, sizeof d->b);
}

typedef struct mqtt_msg {
    int topic;          /* index into topics, -1 if none matched */
    uint8_t *data;
    size_t len;
} mqtt_msg;

struct celfw_mqtt {
    struct mosquitto *mosq;
    mosquitto_property *props; /* CONNECT: the largest packet this sign takes */
    int efd;
    pthread_t thread;
    bool thread_started;
    pthread_mutex_t lock;
    pthread_cond_t wakeup;   /* ends the network thread's back-off wait early (stop) */
    bool stop;
    /* Shared with the loop thread, under lock. */
    mqtt_msg q[CELFW_MQTT_QUEUE];
    unsigned q_head, q_count;
    size_t q_bytes;
    uint64_t q_dropped;
    char notes[MAX_NOTES][240];
    unsigned n_head, n_count;
    bool connected, announce;
    bool told;                 /* network thread only: this outage was logged */
    /* celfw's thread only. */
    char host[256];
    int port;
    bool tls;
    char topics[CELFW_MQTT_MAX_TOPICS + 1][256]; /* the groups, then the own topic */
    int topic_count;
    char status_topic[300];
    char id[65];
    char desc[600];
    bool have_last[CELFW_MQTT_MAX_TOPICS + 1];
    digest last[CELFW_MQTT_MAX_TOPICS + 1];
    /* What was fed last, and what of it a commit applied. */
    int fed_topic;
    digest fed;
    int applied_topic;
    digest applied;
    celfw_report rep;
    char last_error[240];
    bool dirty;
    uint64_t last_status_ns, status_every_ns;
};

static uint64_t now_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint64_t)ts.tv_sec * 1000000000ull + (uint64_t)ts.tv_nsec;
}

static void wake(celfw_mqtt *m)
{
    uint64_t one = 1;
    ssize_t r = write(m->efd, &one, sizeof one);
    (void)r; /* a full counter still wakes the poll */
}

/* Loop thread: queue a line for celfw's log. */
static void queue_note(celfw_mqtt *m, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void queue_note(celfw_mqtt *m, const char *fmt, ...)
{
    va_list ap;
    pthread_mutex_lock(&m->lock);
    if (m->n_count < MAX_NOTES) {
        char *slot = m->notes[(m->n_head + m->n_count++) % MAX_NOTES];
        va_start(ap, fmt);
        vsnprintf(slot, sizeof m->notes[0], fmt, ap);
        va_end(ap);
    }
    pthread_mutex_unlock(&m->lock);
    wake(m);
}

static void on_connect(struct mosquitto *mosq, void *user, int rc)
{
    celfw_mqtt *m = user;
    if (rc != 0) {
        if (!m->told)
            queue_note(m, "mqtt %s:%d refused the connection: %s; retrying every 1..10 s",
                       m->host, m->port, mosquitto_reason_string(rc)); /* MQTT 5 reason */
        m->told = true;
        return;
    }
    char *subs[CELFW_MQTT_MAX_TOPICS + 1];
    for (int i = 0; i < m->topic_count; i++)
        subs[i] = m->topics[i];
    int s = mosquitto_subscribe_multiple(mosq, NULL, m->topic_count, subs, 1, 0, NULL);
    pthread_mutex_lock(&m->lock);
    m->connected = true;
    m->announce = true; /* celfw's thread publishes the status */
    pthread_mutex_unlock(&m->lock);
    queue_note(m, "mqtt connected to %s:%d as %s%s", m->host, m->port, m->id,
               s == MOSQ_ERR_SUCCESS ? "" : "; subscribing failed");
}

static void on_disconnect(struct mosquitto *mosq, void *user, int rc)
{
    (void)mosq;
    (void)rc; /* the network thread says why, once */
    celfw_mqtt *m = user;
    pthread_mutex_lock(&m->lock);
    m->connected = false;
    pthread_mutex_unlock(&m->lock);
}

static void on_subscribe(struct mosquitto *mosq, void *user, int mid, int n, const int *granted)
{
    (void)mosq;
    (void)mid;
    celfw_mqtt *m = user;
    for (int i = 0; i < n && i < m->topic_count; i++) {
        if (granted[i] > 1)
            queue_note(m, "mqtt subscription to %s refused by the broker", m->topics[i]);
    }
}

static void on_message(struct mosquitto *mosq, void *user, const struct mosquitto_message *msg)
{
    (void)mosq;
    celfw_mqtt *m = user;
    if (msg->payloadlen <= 0)
        return; /* an empty retained message clears a topic's content: nothing to feed */
    if ((size_t)msg->payloadlen > MAX_MESSAGE) {
        queue_note(m, "mqtt message on %s dropped: %d bytes, more than %u", msg->topic,
                   msg->payloadlen, MAX_MESSAGE);
        return;
    }
    int topic = -1;
    for (int i = 0; i < m->topic_count && topic < 0; i++) {
        bool match = false;
        if (mosquitto_topic_matches_sub(m->topics[i], msg->topic, &match) == MOSQ_ERR_SUCCESS &&
            match)
            topic = i;
    }
    uint8_t *copy = malloc((size_t)msg->payloadlen);
    if (!copy) {
        queue_note(m, "mqtt message on %s dropped: out of memory", msg->topic);
        return;
    }
    memcpy(copy, msg->payload, (size_t)msg->payloadlen);
    pthread_mutex_lock(&m->lock);
    while (m->q_count == CELFW_MQTT_QUEUE ||
           (m->q_count > 0 && m->q_bytes + (size_t)msg->payloadlen > MAX_QUEUED)) {
        /* celfw is behind: the oldest goes */
        m->q_bytes -= m->q[m->q_head].len;
        free(m->q[m->q_head].data);
        m->q_head = (m->q_head + 1) % CELFW_MQTT_QUEUE;
        m->q_count--;
        m->q_dropped++;
    }
    m->q[(m->q_head + m->q_count++) % CELFW_MQTT_QUEUE] =
        (mqtt_msg){topic, copy, (size_t)msg->payloadlen};
    m->q_bytes += (size_t)msg->payloadlen;
    pthread_mutex_unlock(&m->lock);
    wake(m);
}

/* Network thread: waits `seconds` unless told to stop; returns whether to go on. */
static bool backoff(celfw_mqtt *m, unsigned seconds)
{
    struct timespec until;
    clock_gettime(CLOCK_REALTIME, &until);
    until.tv_sec += (time_t)seconds;
    pthread_mutex_lock(&m->lock);
    while (!m->stop && pthread_cond_timedwait(&m->wakeup, &m->lock, &until) == 0)
        ;
    bool go = !m->stop;
    pthread_mutex_unlock(&m->lock);
    return go;
}

static bool stopping(celfw_mqtt *m)
{
    pthread_mutex_lock(&m->lock);
    bool s = m->stop;
    pthread_mutex_unlock(&m->lock);
    return s;
}

/*
 * The network thread: connect (blocking, here), run the client's loop
 * while the connection lasts, and after any failure wait 1, 2, ... 10 s
 * and reconnect. A failure is logged once per outage, not per attempt.
 */
static void *net_thread(void *arg)
{
    celfw_mqtt *m = arg;
    unsigned delay = 0;
    bool up = false, tried = false;
    while (!stopping(m)) {
        if (!up) {
            int rc = tried ? mosquitto_reconnect(m->mosq) /* the same properties */
                           : mosquitto_connect_bind_v5(m->mosq, m->host, m->port, KEEPALIVE_S,
                                                       NULL, m->props);
            tried = true;
            if (rc != MOSQ_ERR_SUCCESS) {
                delay = delay < 10 ? delay + 1 : 10;
                if (!m->told)
                    queue_note(m, "mqtt %s:%d: %s; retrying every 1..10 s, picture kept", m->host,
                               m->port, rc == MOSQ_ERR_ERRNO ? strerror(errno)
                                                             : mosquitto_strerror(rc));
                m->told = true;
                if (!backoff(m, delay))
                    break;
                continue;
            }
            up = true;
        }
        pthread_mutex_lock(&m->lock);
        bool was = m->connected;
        pthread_mutex_unlock(&m->lock);
        int rc = mosquitto_loop(m->mosq, 1000, 1);
        pthread_mutex_lock(&m->lock);
        bool connected = m->connected;
        pthread_mutex_unlock(&m->lock);
        if (connected) { /* CONNACK accepted: the next outage starts from 1 s */
            delay = 0;
            m->told = false;
        }
        if (rc != MOSQ_ERR_SUCCESS) {
            up = false;
            pthread_mutex_lock(&m->lock);
            m->connected = false;
            pthread_mutex_unlock(&m->lock);
            const char *why = rc == MOSQ_ERR_ERRNO ? strerror(errno) : mosquitto_strerror(rc);
            if (was && !stopping(m)) {
                queue_note(m, "mqtt connection to %s:%d lost (%s); picture kept, reconnecting",
                           m->host, m->port, why);
            } else if (!was && !m->told && !stopping(m)) {
                /* e.g. a TLS listener that wants a client certificate closes here */
                queue_note(m, "mqtt %s:%d closed the connection before accepting it (%s); "
                           "retrying every 1..10 s, picture kept", m->host, m->port, why);
                m->told = true;
            }
            delay = delay < 10 ? delay + 1 : 10;
            if (!backoff(m, delay))
                break;
        }
    }
    if (up) { /* a clean goodbye: what celfw queued last (its offline status), then DISCONNECT */
        mosquitto_disconnect(m->mosq);
        for (int i = 0; i < 10 && mosquitto_want_write(m->mosq); i++)
            if (mosquitto_loop(m->mosq, 100, 1) != MOSQ_ERR_SUCCESS)
                break;
    }
    return NULL;
}

bool celfw_mqtt_spec(const char *spec)
{
    return !strncmp(spec, "mqtt://", 7) || !strncmp(spec, "mqtts://", 8);
}

/* "HOST:PORT[/TOPIC]" or "[V6]:PORT[/TOPIC]". */
static bool parse_spec(celfw_mqtt *m, const char *rest, char *topic, size_t topic_len)
{
    const char *slash = strchr(rest, '/');
    const char *end = slash ? slash : rest + strlen(rest);
    const char *colon;
    if (*rest == '[') {
        const char *close = memchr(rest, ']', (size_t)(end - rest));
        if (!close || close[1] != ':')
            return false;
        snprintf(m->host, sizeof m->host, "%.*s", (int)(close - rest - 1), rest + 1);
        colon = close + 1;
    } else {
        colon = memchr(rest, ':', (size_t)(end - rest));
        if (!colon)
            return false;
        snprintf(m->host, sizeof m->host, "%.*s", (int)(colon - rest), rest);
    }
    char port[16];
    long p;
    if (!m->host[0] || end - colon - 1 <= 0 || end - colon - 1 >= (long)sizeof port)
        return false;
    snprintf(port, sizeof port, "%.*s", (int)(end - colon - 1), colon + 1);
    if (!cli_int(port, 10, '\0', 1, 65535, &p))
        return false;
    m->port = (int)p;
    snprintf(topic, topic_len, "%s", slash && slash[1] ? slash + 1 : "");
    return true;
}

/* A secret file's mode: regular, not readable by group or others. */
static bool secret_mode_ok(const char *what, const char *path, const struct stat *st, char *err,
                           size_t errlen)
{
    if (!S_ISREG(st->st_mode) || (st->st_mode & 077) != 0) {
        snprintf(err, errlen, "%s %s: mode %04o lets others read it; chmod 600 it", what, path,
                 (unsigned)(st->st_mode & 07777));
        return false;
    }
    return true;
}

/* The key is opened by libmosquitto (OpenSSL): its mode is checked by path. */
static bool secret_file_ok(const char *what, const char *path, char *err, size_t errlen)
{
    struct stat st;
    if (stat(path, &st) != 0) {
        snprintf(err, errlen, "%s %s: %s", what, path, strerror(errno));
        return false;
    }
    return secret_mode_ok(what, path, &st, err, errlen);
}

/* The password file's first line; its mode is checked on the file read. */
static bool read_password(const char *path, char *out, size_t n, char *err, size_t errlen)
{
    FILE *f = fopen(path, "r");
    struct stat st;
    if (!f || fstat(fileno(f), &st) != 0) {
        snprintf(err, errlen, "mqtt-password-file %s: %s", path, strerror(errno));
        if (f)
            fclose(f);
        return false;
    }
    bool ok = secret_mode_ok("mqtt-password-file", path, &st, err, errlen);
    if (ok && !fgets(out, (int)n, f)) {
        snprintf(err, errlen, "mqtt-password-file %s: empty", path);
        ok = false;
    }
    fclose(f);
    out[ok ? strcspn(out, "\r\n") : 0] = 0;
    return ok;
}

static char *status_json(celfw_mqtt *m, bool online)
{
    cJSON *o = cJSON_CreateObject();
    if (!o)
        return NULL;
    cJSON_AddStringToObject(o, "id", m->id);
    cJSON_AddBoolToObject(o, "online", online);
    if (online) {
        cJSON_AddNumberToObject(o, "commits", (double)m->rep.commits);
        cJSON_AddNumberToObject(o, "stream_errors", (double)m->rep.stream_errors);
        if (m->applied_topic >= 0) {
            char hex[2 * DIGEST_BYTES + 1];
            digest_hex(&m->applied, hex);
            cJSON_AddStringToObject(o, "content", hex);
            cJSON_AddStringToObject(o, "topic", m->topics[m->applied_topic]);
        } else {
            cJSON_AddNullToObject(o, "content");
            cJSON_AddNullToObject(o, "topic");
        }
        if (m->rep.seq)
            cJSON_AddNumberToObject(o, "seq", (double)m->rep.seq);
        else
            cJSON_AddNullToObject(o, "seq");
        if (m->rep.fps >= 0)
            cJSON_AddNumberToObject(o, "fps", (double)(long)(m->rep.fps * 10.0 + 0.5) / 10.0);
        if (m->last_error[0])
            cJSON_AddStringToObject(o, "last_error", m->last_error);
        else
            cJSON_AddNullToObject(o, "last_error");
        if (m->q_dropped)
            cJSON_AddNumberToObject(o, "mqtt_dropped", (double)m->q_dropped);
    }
    char *s = cJSON_PrintUnformatted(o);
    cJSON_Delete(o);
    return s;
}

static void publish_status(celfw_mqtt *m)
{
    char *s = status_json(m, true);
    if (!s)
        return;
    /* QoS 1, retained: the fleet view shows the latest of every sign */
    if (mosquitto_publish(m->mosq, NULL, m->status_topic, (int)strlen(s), s, 1, true) ==
        MOSQ_ERR_SUCCESS) {
        m->dirty = false;
        m->last_status_ns = now_ns();
    }
    cJSON_free(s);
}

int celfw_mqtt_open(celfw_mqtt **out, const char *spec, const celfw_mqtt_config *cfg, char *err,
                    size_t errlen)
{
    *out = NULL;
    if (!cfg->sign_id[0]) {
        snprintf(err, errlen, "input %s: needs sign-id (the client id and status topic)", spec);
        return -1;
    }
    celfw_mqtt *m = calloc(1, sizeof *m);
    if (!m) {
        snprintf(err, errlen, "input %s: out of memory", spec);
        return -1;
    }
    m->efd = -1;
    m->fed_topic = m->applied_topic = -1;
    m->rep.fps = -1.0;
    m->tls = !strncmp(spec, "mqtts://", 8);
    char own[256];
    if (!parse_spec(m, spec + (m->tls ? 8 : 7), own, sizeof own)) {
        snprintf(err, errlen, "input '%s': expected mqtt[s]://HOST:PORT[/TOPIC]", spec);
        free(m);
        return -1;
    }
    snprintf(m->id, sizeof m->id, "%s", cfg->sign_id);
    for (int i = 0; i < cfg->topic_count; i++)
        snprintf(m->topics[m->topic_count++], sizeof m->topics[0], "%s", cfg->topics[i]);
    if (own[0])
        snprintf(m->topics[m->topic_count++], sizeof m->topics[0], "%s", own);
    else
        snprintf(m->topics[m->topic_count++], sizeof m->topics[0], "signs/%s", m->id);
    snprintf(m->status_topic, sizeof m->status_topic, "signs/%s/status", m->id);
    m->status_every_ns = (uint64_t)((cfg->status_interval > 0 ? cfg->status_interval : 5.0) * 1e9);
    int len = snprintf(m->desc, sizeof m->desc, "%s://%s:%d topics=", m->tls ? "mqtts" : "mqtt",
                       m->host, m->port);
    for (int i = 0; i < m->topic_count && len > 0 && (size_t)len < sizeof m->desc; i++)
        len += snprintf(m->desc + len, sizeof m->desc - (size_t)len, "%s%s", i ? "," : "",
                        m->topics[i]);

    char password[256] = "";
    if (cfg->password_file[0] && !read_password(cfg->password_file, password, sizeof password, err,
                                                errlen)) {
        free(m);
        return -1;
    }
    if (cfg->key_file[0] && !secret_file_ok("mqtt-key", cfg->key_file, err, errlen)) {
        free(m);
        return -1;
    }
    if ((cfg->cert_file[0] != 0) != (cfg->key_file[0] != 0)) {
        snprintf(err, errlen, "mqtt-cert and mqtt-key go together");
        free(m);
        return -1;
    }
    if (sodium_init() < 0) {
        snprintf(err, errlen, "input %s: libsodium would not start", spec);
        free(m);
        return -1;
    }
    pthread_mutex_init(&m->lock, NULL);
    pthread_cond_init(&m->wakeup, NULL);
    mosquitto_lib_init();
    m->efd = eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC);
    /* A clean session: what a sign missed while away is the retained content. */
    m->mosq = mosquitto_new(m->id, true, m);
    int rc = m->efd < 0 || !m->mosq ? MOSQ_ERR_NOMEM : MOSQ_ERR_SUCCESS;
    if (rc == MOSQ_ERR_SUCCESS)
        rc = mosquitto_int_option(m->mosq, MOSQ_OPT_PROTOCOL_VERSION, MQTT_PROTOCOL_V5);
    if (rc == MOSQ_ERR_SUCCESS) /* the payload, and room for the topic and headers */
        rc = mosquitto_property_add_int32(&m->props, MQTT_PROP_MAXIMUM_PACKET_SIZE,
                                          MAX_MESSAGE + 65536u);
    char *will = rc == MOSQ_ERR_SUCCESS ? status_json(m, false) : NULL;
    if (rc == MOSQ_ERR_SUCCESS)
        rc = will ? mosquitto_will_set(m->mosq, m->status_topic, (int)strlen(will), will, 1, true)
                  : MOSQ_ERR_NOMEM;
    cJSON_free(will);
    if (rc == MOSQ_ERR_SUCCESS && (cfg->username[0] || password[0]))
        rc = mosquitto_username_pw_set(m->mosq, cfg->username[0] ? cfg->username : NULL,
                                       password[0] ? password : NULL);
    memset(password, 0, sizeof password);
    if (rc == MOSQ_ERR_SUCCESS && m->tls) {
        if (!cfg->ca_file[0])
            mosquitto_int_option(m->mosq, MOSQ_OPT_TLS_USE_OS_CERTS, 1);
        rc = mosquitto_tls_set(m->mosq, cfg->ca_file[0] ? cfg->ca_file : NULL,
                               cfg->ca_file[0] ? NULL : "/etc/ssl/certs",
                               cfg->cert_file[0] ? cfg->cert_file : NULL,
                               cfg->key_file[0] ? cfg->key_file : NULL, NULL);
        if (rc == MOSQ_ERR_SUCCESS) /* SSL_VERIFY_PEER; the host name is checked too */
            rc = mosquitto_tls_opts_set(m->mosq, 1, NULL, NULL);
    }
    if (rc != MOSQ_ERR_SUCCESS) {
        snprintf(err, errlen, "input %s: %s", spec, mosquitto_strerror(rc));
        celfw_mqtt_close(m);
        return -1;
    }
    mosquitto_connect_callback_set(m->mosq, on_connect);
    mosquitto_disconnect_callback_set(m->mosq, on_disconnect);
    mosquitto_subscribe_callback_set(m->mosq, on_subscribe);
    mosquitto_message_callback_set(m->mosq, on_message);
    mosquitto_threaded_set(m->mosq, true);
    /* A broker that is not up yet is not an error: the thread keeps trying. */
    if (pthread_create(&m->thread, NULL, net_thread, m) != 0) {
        snprintf(err, errlen, "input %s: cannot start the MQTT thread", spec);
        celfw_mqtt_close(m);
        return -1;
    }
    m->thread_started = true;
    *out = m;
    return 0;
}

int celfw_mqtt_pollfds(celfw_mqtt *m, struct pollfd *pfd, int max)
{
    if (max < 1)
        return 0;
    pfd[0] = (struct pollfd){m->efd, POLLIN, 0};
    return 1;
}

void celfw_mqtt_service(celfw_mqtt *m, const celfw_input_sink *sink)
{
    uint64_t count;
    ssize_t r = read(m->efd, &count, sizeof count);
    (void)r; /* EAGAIN: nothing new, the queue says the same */
    mqtt_msg msgs[CELFW_MQTT_QUEUE];
    char notes[MAX_NOTES][240];
    unsigned nm = 0, nn = 0;
    bool announce;
    pthread_mutex_lock(&m->lock);
    for (; m->q_count; m->q_count--, m->q_head = (m->q_head + 1) % CELFW_MQTT_QUEUE)
        msgs[nm++] = m->q[m->q_head];
    m->q_bytes = 0;
    for (; m->n_count; m->n_count--, m->n_head = (m->n_head + 1) % MAX_NOTES)
        memcpy(notes[nn++], m->notes[m->n_head], sizeof notes[0]);
    announce = m->announce;
    m->announce = false;
    pthread_mutex_unlock(&m->lock);
    for (unsigned i = 0; i < nn; i++)
        if (sink->note)
            sink->note(sink->user, notes[i]);
    if (announce)
        publish_status(m);
    for (unsigned i = 0; i < nm; i++) {
        mqtt_msg *g = &msgs[i];
        digest d = digest_of(g->data, g->len);
        char hex[2 * DIGEST_BYTES + 1], what[400];
        digest_hex(&d, hex);
        int t = g->topic;
        const char *name = t >= 0 ? m->topics[t] : "?";
        if (t >= 0 && m->have_last[t] && !memcmp(&m->last[t], &d, sizeof d)) {
            snprintf(what, sizeof what, "mqtt %s: %zu bytes, content %s as before, not fed again",
                     name, g->len, hex);
            if (sink->note)
                sink->note(sink->user, what);
        } else {
            if (t >= 0) {
                m->have_last[t] = true;
                m->last[t] = d;
            }
            snprintf(what, sizeof what, "mqtt message on %s: %zu bytes, content %s", name,
                     g->len, hex);
            if (sink->note)
                sink->note(sink->user, what);
            m->fed_topic = t;
            m->fed = d;
            /* One message, one byte sequence: what TCP does for one client. */
            sink->bytes(sink->user, g->data, g->len);
            if (sink->reset)
                sink->reset(sink->user, "end of mqtt message");
            m->fed_topic = -1;
        }
        free(g->data);
    }
}

void celfw_mqtt_report(celfw_mqtt *m, const celfw_report *r)
{
    if (r->commits > m->rep.commits && m->fed_topic >= 0) {
        m->applied_topic = m->fed_topic;
        m->applied = m->fed;
    }
    if (r->commits != m->rep.commits || r->stream_errors != m->rep.stream_errors)
        m->dirty = true;
    if (r->last_error)
        snprintf(m->last_error, sizeof m->last_error, "%s", r->last_error);
    double fps = r->fps >= 0 ? r->fps : m->rep.fps;
    m->rep = *r;
    m->rep.fps = fps;
}

void celfw_mqtt_tick(celfw_mqtt *m)
{
    uint64_t now = now_ns();
    bool connected;
    pthread_mutex_lock(&m->lock);
    connected = m->connected;
    pthread_mutex_unlock(&m->lock);
    if (!connected)
        return; /* the next connection announces itself */
    if ((m->dirty && now - m->last_status_ns >= STATUS_MIN_NS) ||
        now - m->last_status_ns >= m->status_every_ns)
        publish_status(m);
}

const char *celfw_mqtt_describe(const celfw_mqtt *m)
{
    return m->desc;
}

void celfw_mqtt_close(celfw_mqtt *m)
{
    if (!m)
        return;
    if (m->mosq) {
        bool connected;
        pthread_mutex_lock(&m->lock);
        connected = m->connected;
        pthread_mutex_unlock(&m->lock);
        if (connected) {
            /* A clean goodbye: the will only fires on a broken connection. */
            char *s = status_json(m, false);
            if (s) /* the network thread sends it before it disconnects */
                mosquitto_publish(m->mosq, NULL, m->status_topic, (int)strlen(s), s, 1, true);
            cJSON_free(s);
        }
        pthread_mutex_lock(&m->lock);
        m->stop = true;
        pthread_cond_signal(&m->wakeup);
        pthread_mutex_unlock(&m->lock);
        if (m->thread_started) {
            /* Done within a loop timeout (1 s) and the goodbye, unless it is
             * stuck in a connect (a name lookup, an unanswered SYN): then celfw
             * exits without it rather than hang, and leaves the client alone. */
            struct timespec until;
            clock_gettime(CLOCK_REALTIME, &until);
            until.tv_sec += 3;
            if (pthread_timedjoin_np(m->thread, NULL, &until) != 0)
                return;
        }
        mosquitto_destroy(m->mosq);
        mosquitto_property_free_all(&m->props);
        mosquitto_lib_cleanup();
    }
    for (unsigned i = 0; i < m->q_count; i++)
        free(m->q[(m->q_head + i) % CELFW_MQTT_QUEUE].data);
    if (m->efd >= 0)
        close(m->efd);
    pthread_cond_destroy(&m->wakeup);
    pthread_mutex_destroy(&m->lock);
    free(m);
}
