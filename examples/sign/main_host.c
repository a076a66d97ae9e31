/*
 * main_host.c - the sign's main loop on a host: a .cels file in, one frame's CRC out.
 *
 *   sign STREAM.cels WxH SECONDS     prints "frame crc32 XXXXXXXX", as
 *                                    `celsim render STREAM --size WxH --time SECONDS --crc`
 *
 * The file stands in for the board's link and the CRC for its panel. A
 * damaged stream is reported with the byte offset of each fault; exit
 * status 1 if nothing valid was committed or the frame failed, 2 on usage.
 */
#include <stdio.h>
#include <stdlib.h>

#include "sign.h"

static sign board; /* large: the scene stores at the host library's capacities */

static void panel_write(void *user, int y, const uint8_t *rgb565, int width)
{
    (void)user, (void)y, (void)rgb565, (void)width; /* a real panel would show the line */
}

int main(int argc, char **argv)
{
    int w, h;
    char tail;
    if (argc != 4 || sscanf(argv[2], "%dx%d%c", &w, &h, &tail) != 2) {
        fprintf(stderr, "usage: sign STREAM.cels WxH SECONDS\n");
        return 2;
    }
    char *end;
    float t = strtof(argv[3], &end);
    if (*end || end == argv[3]) {
        fprintf(stderr, "sign: time '%s' is not a number\n", argv[3]);
        return 2;
    }
    if (sign_init(&board, w, h, panel_write, NULL) != CS_OK) {
        fprintf(stderr, "sign: size %dx%d is beyond this library's %dx%d\n", w, h, CS_CFG_MAX_WIDTH,
                CS_CFG_MAX_HEIGHT);
        return 2;
    }
    FILE *f = fopen(argv[1], "rb");
    if (!f) {
        perror(argv[1]);
        return 1;
    }
    uint8_t chunk[4096];
    size_t n;
    while ((n = fread(chunk, 1, sizeof chunk, f)) > 0)
        sign_feed(&board, chunk, n);
    if (ferror(f))
        fprintf(stderr, "sign: %s: read error; decoding what arrived\n", argv[1]);
    fclose(f);
    sign_end_of_input(&board);
    if (board.errors > 0)
        fprintf(stderr, "sign: %s: %u dropped; the last at byte %llu: %s (%s)\n", argv[1],
                (unsigned)board.errors, (unsigned long long)board.last.at, board.last.what,
                cs_status_str(board.last.status));
    if (!sign_has_scene(&board)) {
        fprintf(stderr, "sign: %s: no valid scene committed\n", argv[1]);
        return 1;
    }
    uint32_t crc;
    cs_status st = sign_frame(&board, t, &crc);
    if (st != CS_OK) {
        fprintf(stderr, "sign: frame: %s\n", cs_status_str(st));
        return 1;
    }
    printf("frame crc32 %08X\n", (unsigned)crc);
    return 0;
}
