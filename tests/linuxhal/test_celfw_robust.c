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

#include "celfw_child.h"
#include "fake_gud.h"
#include "gud_wire.h"
#include "lx_test.h"

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
    g_object_unref(tb);
    return lx_test_report("test_celfw_robust");
}
