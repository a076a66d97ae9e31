/*
 * celsim.c - the host simulator: render a scene the way a board would.
 *
 *   celsim render SCENE [-o OUT.png] [--size WxH] [--time T] [--aa none|N|exact]
 *                 [--encoding srgb|linear] [--repeat N [--time-step S]] [--blend linear|srgb] [--crc]
 *                 [--threads N] [--core auto|baseline|x86-64-v3]
 *
 * SCENE is authoring JSON (.json, with its "animate" tracks) or a cel stream
 * (.cels, decoded by the core's stream decoder as a board would: every
 * committed transaction is applied in order, damage is reported on stderr
 * with its byte offset, and the last good commit is what renders). --time
 * samples the tracks of either at that instant.
 *
 * The scene is loaded into a cs_scene, and each frame goes through the same
 * path as on a board: the core renders lines, frame_drive converts them to the
 * display's pixel format and sends them to a HAL display, here the in-memory
 * simulator (hal/sim). With --threads N > 1 the lines are rendered in bands
 * on N - 1 worker threads and this one (which shows the lines in order
 * between its bands) from one prepared frame (bands.h), with the same
 * bytes. The PNG is written from what the simulated display received, so
 * the picture is what the glass would show.
 *
 * Exit status: 0 success; 1 the scene or a file could not be read, loaded or
 * written, or the frame could not be rendered, or a stream committed nothing
 * valid; 2 bad command line; 3 the frame was rendered and written but the
 * core ran out of capacity, so parts of it are missing. A stream with damage
 * after a good commit renders that commit and exits 0 (DESIGN.md): the
 * damage is on stderr.
 */
#include <errno.h>
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cels_read.h"
#include "celscan_private.h"
#include "cli.h"
#include "cli_num.h"
#include "clock.h"
#include "core_variant.h"
#include "display.h"
#include "frame_drive.h"
#include "png_out.h"
#include "scene_json.h"
#include "sim/display_sim.h"

enum { EXIT_LOAD = 1, EXIT_USAGE = 2, EXIT_DEGRADED = 3 };

/* The default vertical anti-aliasing, cs_render_defaults' (16 sub-scanlines). */
#define DEFAULT_SUBSCANLINES 16
#define MAX_REPEAT 1000000

static const char usage_text[] =
    "usage: celsim render SCENE [-o OUT.png] [options]\n"
    "\n"
    "Renders one frame of SCENE (scene JSON .json, or a cel stream .cels) with the\n"
    "celscan core through the simulated display, and writes it as a PNG. A damaged\n"
    "stream is reported on stderr with the byte offset of each fault; the last good\n"
    "commit is rendered.\n"
    "\n"
    "options:\n"
    "  -o, --output FILE       PNG to write (may be omitted with --crc or --repeat)\n"
    "  --size WxH              output size in pixels (default: the canvas size, rounded)\n"
    "  --viewport X,Y,W,H      render only that window of the output (one board of a video\n"
    "                          wall whose size is --size, which may then exceed the line\n"
    "                          maximum): the image is WxH, bit for bit that part of the whole\n"
    "  --time SECONDS          scene time for animation (default 0)\n"
    "  --aa none|N|exact       vertical anti-aliasing: one sample per pixel, N\n"
    "                          sub-scanlines (1..64), or exact area (default 16)\n"
    "  --encoding srgb|linear  8-bit sRGB PNG (default), or 16-bit linear-light PNG\n"
    "  --repeat N              render N times; print the median render time as\n"
    "                          'X.XXX ms/frame' (rendering only, not loading or writing)\n"
    "  --time-step S           with --repeat: N frames S seconds apart from --time; print\n"
    "                          each frame's damage (the window that can differ from the\n"
    "                          frame before, cs_frame_damage: what a board redraws) and\n"
    "                          the pixels that leaves to render per frame\n"
    "  --blend linear|srgb     compositing space: linear light, or sRGB-encoded as SVG renderers\n"
    "                          blend (default: what the scene asks, \"canvas\": {\"blend\": ...})\n"
    "  --crc                   print 'frame crc32 XXXXXXXX' of the frame in the panel\n"
    "                          pixel format (RGB565, little-endian, rows top to bottom)\n"
    "  --threads N             render bands of lines on N threads, 1..64 (default: the\n"
    "                          cores this process may use); the bytes are the same\n"
    "  --core auto|baseline|x86-64-v3\n"
    "                          the build of the core to render with (default: the fastest\n"
    "                          this CPU runs, or $CELSCAN_CORE); the bytes are the same\n"
    "  -h, --help              show this help\n"
    "\n"
    "exit status: 0 ok, 1 load/render/write error (or a stream with no valid commit),\n"
    "             2 usage error, 3 image written but the renderer ran out of capacity\n";

typedef struct options {
    const char *scene;
    const char *out;
    int width, height; /* 0: canvas size */
    int view[4];       /* --viewport X, Y, W, H; W = 0: none */
    float time;
    cs_aa_mode aa;
    int subscanlines;
    bool linear;
    int repeat;        /* 0: not timing */
    double time_step;  /* --time-step: the repeats are frames this many seconds apart */
    cs_blend blend;    /* CS_BLEND_SCENE unless --blend says */
    bool crc;
    int threads;       /* 1: the lines on the calling thread, as a board renders them */
} options;

/* ------------------------------------------------------- command line */

/* The value of an option given as "--opt value" or "--opt=value". */
static const char *option_value(int argc, char **argv, int *i, const char *arg, const char *name)
{
    size_t n = strlen(name);
    if (arg[n] == '=')
        return arg + n + 1;
    if (*i + 1 >= argc)
        return NULL;
    return argv[++*i];
}

/* Matches "--name" and "--name=..." exactly. */
static bool is_option(const char *arg, const char *name)
{
    size_t n = strlen(name);
    return strncmp(arg, name, n) == 0 && (arg[n] == '\0' || arg[n] == '=');
}

static int parse_render_args(int argc, char **argv, options *o)
{
    *o = (options){.aa = CS_AA_SUBSCAN, .subscanlines = DEFAULT_SUBSCANLINES,
                   .blend = CS_BLEND_SCENE, .threads = bands_cores()};
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        const char *v;
        static const char *const valued[] = {"-o",       "--output",   "--size",    "--time",
                                             "--aa",     "--encoding", "--repeat",  "--blend",
                                             "--viewport", "--threads", "--time-step", "--core"};
        const char *name = NULL;
        for (size_t k = 0; k < sizeof valued / sizeof valued[0]; k++)
            if (is_option(a, valued[k]))
                name = valued[k];
        if (name != NULL) {
            v = option_value(argc, argv, &i, a, name);
            if (v == NULL)
                return cli_usage_error("%s needs a value (see celsim --help)", name);
        } else {
            v = NULL;
        }

        if (name && (strcmp(name, "-o") == 0 || strcmp(name, "--output") == 0)) {
            if (v[0] == '\0')
                return cli_usage_error("%s expects a file name", name);
            o->out = v;
        } else if (name && strcmp(name, "--size") == 0) {
            if (!cli_size(v, 1000000, 1000000, &o->width, &o->height))
                return cli_usage_error("--size expects WxH, got '%s'", v);
            if (o->width > CS_CFG_MAX_WALL || o->height > CS_CFG_MAX_WALL)
                return cli_usage_error("--size %s is beyond the configured maximum %dx%d", v,
                                   CS_CFG_MAX_WALL, CS_CFG_MAX_WALL);
        } else if (name && strcmp(name, "--viewport") == 0) {
            if (!cli_viewport(v, &o->view[0], &o->view[1], &o->view[2], &o->view[3]))
                return cli_usage_error("--viewport expects X,Y,W,H (whole pixels, W and H at "
                                   "least 1), got '%s'", v);
        } else if (name && strcmp(name, "--time") == 0) {
            double t;
            if (!cli_real(v, '\0', -1e9, 1e9, &t))
                return cli_usage_error("--time expects seconds (a number), got '%s'", v);
            o->time = (float)t;
        } else if (name && strcmp(name, "--time-step") == 0) {
            if (!cli_real(v, '\0', 1e-6, 1e6, &o->time_step))
                return cli_usage_error("--time-step expects seconds between frames (a positive "
                                   "number), got '%s'", v);
        } else if (name && strcmp(name, "--aa") == 0) {
            if (!cli_aa(v, &o->aa, &o->subscanlines)) {
                return cli_usage_error("--aa expects none, exact or a number of sub-scanlines "
                                   "1..%d, got '%s'",
                                   CS_CFG_MAX_SUBSCANLINES, v);
            }
        } else if (name && strcmp(name, "--encoding") == 0) {
            if (strcmp(v, "srgb") == 0)
                o->linear = false;
            else if (strcmp(v, "linear") == 0)
                o->linear = true;
            else
                return cli_usage_error("--encoding expects srgb or linear, got '%s'", v);
        } else if (name && strcmp(name, "--repeat") == 0) {
            long n;
            if (!cli_int(v, 10, '\0', 1, MAX_REPEAT, &n))
                return cli_usage_error("--repeat expects a count 1..%d, got '%s'", MAX_REPEAT, v);
            o->repeat = (int)n;
        } else if (name && strcmp(name, "--blend") == 0) {
            if (strcmp(v, "linear") == 0)
                o->blend = CS_BLEND_LINEAR;
            else if (strcmp(v, "srgb") == 0)
                o->blend = CS_BLEND_SRGB;
            else
                return cli_usage_error("--blend expects linear or srgb, got '%s'", v);
        } else if (name && strcmp(name, "--threads") == 0) {
            long n;
            if (!cli_int(v, 10, '\0', 1, BANDS_MAX_THREADS, &n))
                return cli_usage_error("--threads expects a count 1..%d, got '%s'", BANDS_MAX_THREADS, v);
            o->threads = (int)n;
        } else if (name && strcmp(name, "--core") == 0) {
            const char *why = core_variant_select(v);
            if (why != NULL)
                return cli_usage_error("--core %s: %s", v, why);
        } else if (strcmp(a, "--crc") == 0) {
            o->crc = true;
        } else if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
            fputs(usage_text, stdout);
            exit(0);
        } else if (a[0] == '-' && a[1] != '\0') {
            return cli_usage_error("unknown option '%s' (see celsim --help)", a);
        } else if (o->scene == NULL) {
            o->scene = a;
        } else {
            return cli_usage_error("unexpected argument '%s': one SCENE per run", a);
        }
    }
    if (o->scene == NULL)
        return cli_usage_error("render needs a SCENE file (see celsim --help)");
    if (o->time_step > 0 && o->repeat == 0)
        return cli_usage_error("--time-step needs --repeat N (the number of frames)");
    if (o->out == NULL && !o->crc && o->repeat == 0)
        return cli_usage_error("render needs -o OUT.png (or --crc or --repeat)");
    /* A line is at most CS_CFG_MAX_WIDTH pixels; only a viewport's whole may be wider. */
    if (o->view[2] == 0 && (o->width > CS_CFG_MAX_WIDTH || o->height > CS_CFG_MAX_HEIGHT))
        return cli_usage_error("--size %dx%d is beyond the configured maximum %dx%d (a wider wall "
                           "needs --viewport)", o->width, o->height, CS_CFG_MAX_WIDTH,
                           CS_CFG_MAX_HEIGHT);
    if (o->view[2] > 0 && (o->view[2] > CS_CFG_MAX_WIDTH || o->view[3] > CS_CFG_MAX_HEIGHT))
        return cli_usage_error("--viewport %dx%d is beyond the configured maximum %dx%d",
                           o->view[2], o->view[3], CS_CFG_MAX_WIDTH, CS_CFG_MAX_HEIGHT);
    return 0;
}

/* -------------------------------------------------------------- loading */

typedef int (*scene_loader)(const char *path, cs_scene *out, char *errbuf, size_t errlen);

/*
 * A cel stream through the core's decoder (tools/cels_read.c), in two stores
 * of its own. Every fault is printed at once, one line each, naming the byte
 * offset; the load fails only when no transaction committed.
 */
static int load_cels_stream(const char *path, cs_scene *out, char *errbuf, size_t errlen)
{
    FILE *probe = fopen(path, "rb");
    if (probe == NULL) {
        snprintf(errbuf, errlen, "%s: cannot open: %s", path, strerror(errno));
        return -1;
    }
    fclose(probe);
    cs_scene *a = calloc(1, sizeof *a), *b = calloc(1, sizeof *b);
    if (a == NULL || b == NULL) {
        free(a);
        free(b);
        snprintf(errbuf, errlen, "%s: out of memory for the decoder's scene stores", path);
        return -1;
    }
    char *log = NULL;
    size_t loglen = 0;
    FILE *errf = open_memstream(&log, &loglen);
    cels_read_stats st;
    const cs_scene *got = cels_read_file(path, a, b, errf ? errf : stderr, &st);
    if (errf)
        fclose(errf);
    /* Prefix each reported line, so that it reads as celsim's. */
    for (char *line = log; line && *line;) {
        char *nl = strchr(line, '\n');
        size_t n = nl ? (size_t)(nl - line) : strlen(line);
        fprintf(stderr, "celsim: %.*s\n", (int)n, line);
        line += n + (nl ? 1 : 0);
    }
    free(log);
    int rc = 0;
    if (got) {
        cs_scene_copy(out, got);
        if (st.errors)
            fprintf(stderr, "celsim: %s: rendering commit %u, the last good one (%u error%s above)\n",
                    path, st.commits, st.errors, st.errors == 1 ? "" : "s");
    } else {
        if (st.errors || st.commits)
            snprintf(errbuf, errlen, "%s: no valid scene was committed (%u error%s)", path,
                     st.errors, st.errors == 1 ? "" : "s");
        else
            snprintf(errbuf, errlen, "%s: no valid scene was committed (the stream is empty)",
                     path);
        rc = -1;
    }
    free(a);
    free(b);
    return rc;
}

/* SCENE formats by file extension; the stream decoder plugs in here. */
static const struct {
    const char *ext;
    scene_loader load;
} scene_loaders[] = {
    {".json", scene_json_load},
    {".cels", load_cels_stream},
};

static int load_scene(const char *path, cs_scene *scene)
{
    size_t n = strlen(path);
    for (size_t k = 0; k < sizeof scene_loaders / sizeof scene_loaders[0]; k++) {
        size_t e = strlen(scene_loaders[k].ext);
        if (n > e && strcmp(path + n - e, scene_loaders[k].ext) == 0) {
            char err[SCENE_JSON_ERRLEN];
            if (scene_loaders[k].load(path, scene, err, sizeof err) != 0) {
                fprintf(stderr, "celsim: %s\n", err);
                return EXIT_LOAD;
            }
            return 0;
        }
    }
    fprintf(stderr, "celsim: %s: unknown scene format (expected a .json or .cels file)\n", path);
    return EXIT_LOAD;
}

/* ------------------------------------------------------------ rendering */

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

static void report_core_error(const char *what, const cs_error *e)
{
    char msg[512];
    scene_json_describe_error(e, msg, sizeof msg);
    fprintf(stderr, "celsim: %s: %s\n", what, msg);
}

typedef struct sim_state {
    cs_scene *scene;
    cs_workspace *ws;
    uint8_t *image;
    uint8_t *bytes;
    uint8_t *panel;
    double *times;
    bands *pool;          /* --threads > 1 */
    uint8_t *frame_bytes; /* the pool's lines: display bytes and panel pixels */
    uint8_t *frame_panel;
} sim_state;

static void free_state(sim_state *s)
{
    free(s->scene);
    free(s->ws);
    free(s->image);
    free(s->bytes);
    free(s->panel);
    free(s->times);
    bands_free(s->pool);
    free(s->frame_bytes);
    free(s->frame_panel);
}

static int render(const options *o, sim_state *s)
{
    int status = load_scene(o->scene, s->scene);
    if (status != 0)
        return status;

    cs_render_opts ro = {
        .width = o->width,
        .height = o->height,
        .aa = o->aa,
        .subscanlines = o->aa == CS_AA_SUBSCAN ? o->subscanlines : 1,
        .time = o->time,
        .blend = o->blend,
    };
    if (ro.width == 0) {
        /* The canvas size, rounded; at least one pixel. */
        double w = floor((double)s->scene->canvas_w + 0.5);
        double h = floor((double)s->scene->canvas_h + 0.5);
        if (w > CS_CFG_MAX_WIDTH || h > CS_CFG_MAX_HEIGHT) {
            fprintf(stderr,
                    "celsim: %s: canvas %gx%g is beyond the configured maximum %dx%d; "
                    "use --size\n",
                    o->scene, w, h, CS_CFG_MAX_WIDTH, CS_CFG_MAX_HEIGHT);
            return EXIT_LOAD;
        }
        ro.width = w < 1.0 ? 1 : (int)w;
        ro.height = h < 1.0 ? 1 : (int)h;
    }

    /* The image is the viewport's, when there is one: the wall's window. */
    int ow = ro.width, oh = ro.height;
    if (o->view[2] > 0) {
        if (o->view[0] > ro.width - o->view[2] || o->view[1] > ro.height - o->view[3]) {
            fprintf(stderr, "celsim: --viewport %d,%d,%d,%d does not fit in the %dx%d output\n",
                    o->view[0], o->view[1], o->view[2], o->view[3], ro.width, ro.height);
            return EXIT_USAGE;
        }
        ro.view_x = o->view[0];
        ro.view_y = o->view[1];
        ro.view_w = ow = o->view[2];
        ro.view_h = oh = o->view[3];
    }

    cs_pixfmt fmt = o->linear ? CS_PIX_RGB16_LINEAR : CS_PIX_RGB888_SRGB;
    sim_display dev;
    size_t image_bytes = sim_display_image_bytes(ow, oh, fmt);
    size_t line_bytes = image_bytes / (size_t)oh;
    s->image = malloc(image_bytes);
    s->bytes = malloc(line_bytes);
    if (o->crc)
        s->panel = malloc((size_t)ow * cs_pixfmt_bytes_per_pixel(CS_PANEL_PIXFMT));
    int runs = o->repeat > 0 ? o->repeat : 1;
    s->times = malloc((size_t)runs * sizeof *s->times);
    if (!s->image || !s->bytes || (o->crc && !s->panel) || !s->times) {
        fprintf(stderr, "celsim: out of memory for a %dx%d frame\n", ow, oh);
        return EXIT_LOAD;
    }
    if (sim_display_init(&dev, ow, oh, fmt, s->image, image_bytes) != HAL_OK) {
        fprintf(stderr, "celsim: cannot set up a %dx%d display: %s\n", ow, oh, dev.d.err);
        return EXIT_LOAD;
    }

    size_t panel_line = (size_t)ow * cs_pixfmt_bytes_per_pixel(CS_PANEL_PIXFMT);
    if (o->threads > 1) {
        s->pool = bands_new(o->threads - 1); /* and this thread */
        s->frame_bytes = malloc(image_bytes);
        if (o->crc)
            s->frame_panel = malloc(panel_line * (size_t)oh);
        if (!s->pool || !s->frame_bytes || (o->crc && !s->frame_panel)) {
            fprintf(stderr, "celsim: out of memory or threads for --threads %d\n", o->threads);
            return EXIT_LOAD;
        }
    }
    frame_drive d = {.dev = &dev.d, .bytes = s->bytes, .panel = NULL, .pool = s->pool,
                     .frame_bytes = s->frame_bytes, .frame_panel = s->frame_panel};
    cs_renderer r;
    int rc = FRAME_DRIVE_OK;
    uint32_t crc = 0;
    cs_damage damage;
    cs_damage_reset(&damage);
    double damaged = 0;
    for (int k = 0; k < runs; k++) {
        /* Hash only the first frame: every run renders the same bytes, and the
         * median of the timings shrugs off the one slower run. */
        d.panel = k == 0 ? s->panel : NULL;
        if (o->time_step > 0) {
            ro.time = (float)((double)o->time + o->time_step * k);
            cs_rect w;
            if (cs_frame_damage(&damage, s->scene, &ro, &w) == CS_OK) {
                long px = w.x0 < w.x1 ? (long)(w.x1 - w.x0) * (w.y1 - w.y0) : 0;
                printf("frame %d time %.6g damage %d,%d..%d,%d %ld pixels\n", k, (double)ro.time,
                       w.x0, w.y0, w.x1, w.y1, px);
                damaged += (double)px;
            }
        }
        uint64_t t0 = hal_now(&hal_clock_monotonic);
        rc = frame_drive_render(&d, &r, s->ws, s->scene, &ro);
        uint64_t t1 = hal_now(&hal_clock_monotonic);
        s->times[k] = (double)(t1 - t0) * 1e-6;
        if (k == 0)
            crc = d.crc;
        if (rc < 0)
            break;
    }

    if (rc == FRAME_DRIVE_CORE) {
        report_core_error(o->scene, &d.err);
        return EXIT_LOAD;
    }
    if (rc == FRAME_DRIVE_HAL) {
        if (d.hal_y >= 0)
            fprintf(stderr, "celsim: simulated display refused line %d: %s\n", d.hal_y, dev.d.err);
        else
            fprintf(stderr, "celsim: simulated display refused the frame: %s\n", dev.d.err);
        return EXIT_LOAD;
    }
    if (rc == FRAME_DRIVE_DEGRADED) {
        char what[512];
        scene_json_describe_error(&d.err, what, sizeof what);
        fprintf(stderr, "celsim: %s: frame degraded, parts are missing: %s\n", o->scene, what);
        status = EXIT_DEGRADED;
    }

    if (o->crc)
        printf("frame crc32 %08X\n", (unsigned)crc);
    if (o->repeat > 0)
        printf("%.3f ms/frame\n", median(s->times, runs));
    if (o->time_step > 0)
        printf("damage: %.0f pixels rendered per frame on average (%.1f %% of %dx%d)\n",
               damaged / runs, 100.0 * damaged / runs / ((double)ro.width * ro.height), ro.width,
               ro.height);

    if (o->out != NULL) {
        char err[1024];
        if (png_write_rgb(o->out, ow, oh, fmt, s->image, line_bytes, err,
                          sizeof err) != 0) {
            fprintf(stderr, "celsim: %s\n", err);
            return EXIT_LOAD;
        }
    }
    return status;
}

/* celsim render ...: argv[0] is "render". */
static int render_main(int argc, char **argv)
{
    options o;
    int status = parse_render_args(argc, argv, &o);
    if (status != 0)
        return status;

    /* The scene store and workspace are megabytes: heap, not stack. */
    sim_state s = {0};
    s.scene = calloc(1, sizeof *s.scene);
    s.ws = calloc(1, sizeof *s.ws);
    if (s.scene == NULL || s.ws == NULL) {
        fprintf(stderr, "celsim: out of memory for the scene store and workspace\n");
        free_state(&s);
        return EXIT_LOAD;
    }
    status = render(&o, &s);
    free_state(&s);
    if (fflush(stdout) != 0) {
        fprintf(stderr, "celsim: cannot write to standard output: %s\n", strerror(errno));
        return EXIT_LOAD;
    }
    return status;
}

int main(int argc, char **argv)
{
    static const cli_command commands[] = {{"render", render_main}};
    static const cli_program celsim = {"celsim", usage_text, "see celsim --help", commands, 1};
    return cli_main(&celsim, argc, argv);
}
