/*
 * fw_host_ref.c - the host side of the firmware's bit-identity check.
 *
 * Builds one of the firmware's built-in scenes (firmware/scenes) with the
 * core compiled for the host, in the host's default configuration, renders
 * it line by line exactly as the firmware does, and prints the CRC-32 of
 * the frame in the panel pixel format (CS_PANEL_PIXFMT, rows top to bottom)
 * in the line format of the `celsim --crc` contract:
 *
 *   fw_host_ref --scene signage --size 480x272 --time 0.75 --aa 5 --crc
 *   frame crc32 1A2B3C4D
 *
 * --float-crc also prints `float crc32 X`, the CRC-32 of the linear-light
 * floats of every line (their bytes, little-endian), which the firmware
 * prints with fcrc=1: equal values mean bit-identical arithmetic, not just
 * equal pixels. --dump FILE also writes the raw frame (the same bytes the firmware dumps
 * over semihosting) for a pixel comparison.
 *
 * Besides the built-in scenes it renders
 *   --scene tracks   the animated stream test scene, built directly in C
 *                    (tests/fw_tracks_scene.c; the firmware gets it streamed)
 *   --cels FILE      the last scene a cel stream commits, decoded on the host
 *                    by tools/cels_read.c; each dropped transaction or skipped
 *                    run is printed as `stream error: byte N: ...`, the line
 *                    the firmware prints for the same bytes
 * so that streamed frames get the float CRC and byte comparison too (celsim
 * gives their `frame crc32` from the JSON, which is the contract).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cels_read.h"
#include "celscan_private.h"
#include "fw_scenes.h"
#include "fw_tracks_scene.h"

static int usage(void)
{
    fprintf(stderr, "usage: fw_host_ref --scene NAME|--cels FILE [--size WxH] [--time T] "
                    "[--aa none|N] [--crc] [--float-crc] [--dump FILE]\n"
                    "       fw_host_ref --list\n");
    return 2;
}

int main(int argc, char **argv)
{
    const char *scene_name = NULL, *dump = NULL, *cels = NULL;
    int width = 480, height = 272, subscan = 5, want_crc = 0, want_float_crc = 0;
    float t = 0.0f;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        const char *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (!strcmp(a, "--list")) {
            for (int k = 0; k < FW_SCENE_COUNT; k++)
                printf("%s\n", fw_scenes[k].name);
            printf("tracks\n");
            return 0;
        } else if (!strcmp(a, "--crc")) {
            want_crc = 1;
        } else if (!strcmp(a, "--float-crc")) {
            want_float_crc = 1;
        } else if (!v) {
            return usage();
        } else if (!strcmp(a, "--scene")) {
            scene_name = v;
            i++;
        } else if (!strcmp(a, "--cels")) {
            cels = v;
            i++;
        } else if (!strcmp(a, "--size")) {
            if (sscanf(v, "%dx%d", &width, &height) != 2)
                return usage();
            i++;
        } else if (!strcmp(a, "--time")) {
            char *end;
            t = strtof(v, &end);
            if (*end)
                return usage();
            i++;
        } else if (!strcmp(a, "--aa")) {
            subscan = strcmp(v, "none") ? atoi(v) : 0;
            i++;
        } else if (!strcmp(a, "--dump")) {
            dump = v;
            i++;
        } else {
            return usage();
        }
    }
    int si = scene_name ? fw_scene_find(scene_name) : -1;
    bool tracks = scene_name && !strcmp(scene_name, "tracks");
    if (!cels && si < 0 && !tracks) {
        fprintf(stderr, "fw_host_ref: unknown scene '%s' (try --list)\n",
                scene_name ? scene_name : "");
        return 2;
    }

    cs_scene *scene = calloc(1, sizeof *scene), *other = calloc(1, sizeof *other);
    cs_workspace *ws = calloc(1, sizeof *ws);
    float *line = calloc((size_t)width * 3, sizeof *line);
    uint8_t *px = calloc((size_t)width, 2);
    if (!scene || !other || !ws || !line || !px) {
        fprintf(stderr, "fw_host_ref: out of memory\n");
        return 1;
    }
    cs_error err;
    cs_status st = CS_OK;
    const cs_scene *shown = scene;
    if (cels) {
        /* The name prefixes each message: the firmware's line format. */
        FILE *f = fopen(cels, "rb");
        static uint8_t data[1 << 20];
        size_t len = f ? fread(data, 1, sizeof data, f) : 0;
        if (!f || len == sizeof data) {
            fprintf(stderr, "fw_host_ref: %s: unreadable or larger than 1 MiB\n", cels);
            return 1;
        }
        fclose(f);
        shown = cels_decode_buffer(data, len, "stream error", scene, other, stdout, NULL);
        if (!shown) {
            fprintf(stderr, "fw_host_ref: %s: nothing committed\n", cels);
            return 1;
        }
    } else if (tracks) {
        st = fw_tracks_scene(scene, &err);
    } else {
        st = fw_scenes[si].build(scene, t, &err);
    }
    if (st != CS_OK) {
        fprintf(stderr, "fw_host_ref: scene %s: %s\n", scene_name, cs_status_str(st));
        return 1;
    }
    cs_render_opts o = cs_render_defaults(width, height);
    o.aa = subscan ? CS_AA_SUBSCAN : CS_AA_NONE;
    o.subscanlines = subscan ? subscan : 1;
    o.time = t;
    cs_renderer r;
    st = cs_frame_begin(&r, ws, shown, &o, &err);
    if (st != CS_OK) {
        fprintf(stderr, "fw_host_ref: frame: %s (cel %d region %d contour %d)\n",
                cs_status_str(st), err.cel, err.region, err.contour);
        return 1;
    }
    FILE *out = dump ? fopen(dump, "wb") : NULL;
    if (dump && !out) {
        perror(dump);
        return 1;
    }
    size_t bpp = cs_pixfmt_bytes_per_pixel(CS_PANEL_PIXFMT);
    uint32_t crc = 0, float_crc = 0;
    for (int y = 0; y < height; y++) {
        st = cs_render_line(&r, y, line);
        if (st != CS_OK) {
            fprintf(stderr, "fw_host_ref: line %d: %s\n", y, cs_status_str(st));
            return 1;
        }
        /* The floats' bytes, little-endian as on the target (x86, Arm LE). */
        float_crc = cs_crc32(float_crc, line, (size_t)width * 3 * sizeof *line);
        cs_pixfmt_convert(CS_PANEL_PIXFMT, line, width, px);
        crc = cs_crc32(crc, px, (size_t)width * bpp);
        if (out && fwrite(px, bpp, (size_t)width, out) != (size_t)width) {
            perror(dump);
            return 1;
        }
    }
    if (r.sticky.status != CS_OK)
        fprintf(stderr, "fw_host_ref: warning: %s\n", cs_status_str(r.sticky.status));
    if (out && fclose(out) != 0) {
        perror(dump);
        return 1;
    }
    if (want_crc)
        printf("frame crc32 %08X\n", crc);
    if (want_float_crc)
        printf("float crc32 %08X\n", float_crc);
    free(px);
    free(line);
    free(ws);
    free(other);
    free(scene);
    return 0;
}
