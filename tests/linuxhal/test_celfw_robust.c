/*
 * test_celfw_robust.c - the real celfw against what a kiosk sign meets in
 * months of service: a USB display that reports nonsense, streams that
 * commit scenes which cannot render, scenes too heavy for the frame budget,
 * and long uptimes.
 *
 * celfw runs as a child process under the umockdev preload (celfw_child.h),
 * so its libusb finds the emulated GUD displays this process serves.
 */
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cels_write.h"
#include "celfw_child.h"
#include "fake_gud.h"
#include "gud_wire.h"
#include "lx_test.h"
#include "scene_json.h"

/*
 * A display reporting a 0-wide mode used to kill celfw with SIGFPE. At
 * start, with nothing to show, celfw must exit 4 with a message; a display
 * that turns hostile after a replug must leave celfw running, the display
 * reported down and retried, until it comes back whole.
 */
static void test_hostile_usb(UMockdevTestbed *tb)
{
    fake_gud_opts o;
    fake_gud_opts_default(&o);
    o.pid = 0x7201;
    o.width = 0;
    o.any_size = true;
    fake_gud *dev = fake_gud_add(tb, 40, 2, &o);
    child c;
    spawn(&c, (const char *[]){"--backend", "usb", "--usb-device", "1d50:7201", "--frames", "5", NULL}, false);
    int rc = wait_exit(&c, 10.0);
    CHECK(rc == 4 && strstr(c.log, "celfw: error usb: USB device 1d50:7201") && strstr(c.log, "mode 0x180 has no pixels"),
          "0-wide display at start: exit %d (want 4), log: %s", rc, c.log);
    fake_gud_unplug(dev);
    fake_gud_free(dev);

    fake_gud_opts_default(&o);
    o.pid = 0x7202;
    dev = fake_gud_add(tb, 41, 2, &o);
    spawn(&c,
          (const char *[]){"--backend", "usb", "--usb-device", "1d50:7202", "--scene", "builtin:anim", "--fps",
                           "50", "--usb-reconnect-ms", "20", "--log-interval", "0.1", NULL},
          false);
    char line[1024];
    CHECK(wait_line(&c, "celfw: start", 10.0, line, sizeof line), "started: %s", c.log);
    fake_gud_unplug(dev);
    CHECK(wait_line(&c, "display lost", 10.0, line, sizeof line), "celfw notices the unplug");
    fake_gud_opts bad = o;
    bad.width = 0;
    bad.any_size = true;
    fake_gud_set_opts(dev, &bad);
    fake_gud_replug(dev, 3);
    CHECK(wait_line(&c, "display not back yet", 10.0, line, sizeof line) &&
              strstr(line, "no 320x180 mode; the device offers 0x180"),
          "the 0-wide display is refused: %s", line);
    g_usleep(200000);
    CHECK(kill(c.pid, 0) == 0, "celfw still running beside a 0-wide display");
    fake_gud_unplug(dev);
    fake_gud_set_opts(dev, &o);
    fake_gud_replug(dev, 4);
    CHECK(wait_line(&c, "display connected", 10.0, line, sizeof line) && strstr(line, "address 4"),
          "celfw reconnects once the display is whole: %s", line);
    kill(c.pid, SIGTERM);
    rc = wait_exit(&c, 10.0);
    const char *ex = strstr(c.log, "celfw: exit");
    CHECK(rc == 0 && ex && field(ex, "dropped") > 0, "clean exit: rc %d, %s", rc, ex ? ex : c.log);
    fake_gud_unplug(dev);
    fake_gud_free(dev);
}

/* Reads the port from celfw's start line ("input=tcp:127.0.0.1:PORT"). */
static int start_port(child *c, char *line, size_t len)
{
    if (!wait_line(c, "celfw: start", 10.0, line, len))
        return -1;
    const char *tcp = strstr(line, "input=tcp:127.0.0.1:");
    return tcp ? atoi(tcp + strlen("input=tcp:127.0.0.1:")) : -1;
}

/*
 * A stream that commits a scene which cannot render at the display's size
 * (scenes/demo.json with its canvas made 1e-6: valid, but scaled to 320x180
 * beyond the coordinate limit) is refused at its commit with one line, the
 * panel keeps the scene before it, and no frame fails.
 */
static void test_unrenderable(UMockdevTestbed *tb)
{
    static cs_scene demo, tiny;
    char err[SCENE_JSON_ERRLEN];
    int rc = scene_json_load("scenes/demo.json", &demo, err, sizeof err);
    CHECK(rc == 0, "scenes/demo.json: %s", err);
    if (rc != 0)
        return;
    cs_scene_copy(&tiny, &demo);
    cs_scene_set_canvas(&tiny, 1e-6f, 1e-6f);
    cels_buf b;
    cels_buf_init(&b);
    cels_stream_header(&b);
    cels_encode_scene(&b, &demo);
    size_t second = b.len;
    cels_encode_scene(&b, &tiny);

    fake_gud_opts o;
    fake_gud_opts_default(&o);
    o.pid = 0x7203;
    fake_gud *dev = fake_gud_add(tb, 42, 2, &o);
    child c;
    spawn(&c,
          (const char *[]){"--backend", "usb", "--usb-device", "1d50:7203", "--scene", "builtin:bars", "--fps",
                           "50", "--input", "tcp:127.0.0.1:0", "--log-interval", "0.1", NULL},
          false);
    char line[1024] = "";
    int port = start_port(&c, line, sizeof line);
    int fd = port > 0 ? tcp_connect(port) : -1;
    CHECK(fd >= 0 && send_all(fd, b.data, b.len), "send demo, then its 1e-6 canvas");
    char want[200];
    snprintf(want, sizeof want, "stream error at byte %zu: coordinate magnitude beyond the limit", b.len);
    CHECK(wait_line(&c, "commit refused", 10.0, line, sizeof line) && strstr(line, want) &&
              strstr(line, "the scene (canvas 1e-06x1e-06) cannot render at 320x180") && strstr(line, "scene kept"),
          "the refusal says why and where (want \"%s\"): %s", want, line);
    snprintf(want, sizeof want, "(transaction at byte %zu dropped)", second);
    CHECK(strstr(line, want) != NULL, "and names the transaction %s: %s", want, line);
    unsigned long long before = 0;
    for (int i = 0; i < 50; i++) {
        if (!wait_line(&c, "celfw: status", 5.0, line, sizeof line))
            break;
        if (!before)
            before = field(line, "frames");
        else if (field(line, "frames") >= before + 10)
            break;
    }
    if (fd >= 0)
        close(fd);
    kill(c.pid, SIGTERM);
    rc = wait_exit(&c, 10.0);
    const char *ex = strstr(c.log, "celfw: exit");
    CHECK(rc == 0 && ex && field(ex, "commits") == 1 && field(ex, "stream_errors") == 1 && field(ex, "errors") == 0 &&
              !strstr(c.log, "render failed") && !strstr(c.log, "event render:"),
          "one commit, one refusal, no failed frame: rc %d, %s", rc, c.log);
    const char *at = ex ? strstr(ex, "anim_t=") : NULL;
    float t = at ? strtof(at + 7, NULL) : -1.0f;
    int bad = compare_panel_scene(dev, &demo, t, 320, 180);
    CHECK(bad == 0, "the panel still shows the demo at t=%g (%d pixels differ)", (double)t, bad);
    cels_buf_free(&b);
    fake_gud_unplug(dev);
    fake_gud_free(dev);
}

int main(void)
{
    UMockdevTestbed *tb = umockdev_testbed_new();
    if (!umockdev_in_mock_environment()) {
        fprintf(stderr, "test_celfw_robust: run under umockdev-wrapper (LD_PRELOAD=libumockdev-preload.so)\n");
        return 2;
    }
    if (access(celfw_child_path(), X_OK) != 0) {
        fprintf(stderr, "test_celfw_robust: %s not built (set CELFW)\n", celfw_child_path());
        return 2;
    }
    char *root = umockdev_testbed_get_root_dir(tb);
    char path[600];
    snprintf(path, sizeof path, "%s/dev/bus/usb", root);
    g_mkdir_with_parents(path, 0755);
    g_free(root);

    test_hostile_usb(tb);
    test_unrenderable(tb);
    g_object_unref(tb);
    return lx_test_report("test_celfw_robust");
}
