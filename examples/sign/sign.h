/*
 * sign.h - the part of a sign's firmware that is the same on every board:
 * cel stream bytes in, frames out through the board's own line sink.
 *
 * An example of firmware built against an installed celscan (libcelscan.a,
 * celscan_private.h: the layouts of the structs it places): it holds the two scene stores, the stream decoder and the
 * render workspace in one struct the board places (statically: the core
 * never allocates), swaps in a committed scene between frames, and renders
 * each frame line by line, converting every line to RGB565 for the panel
 * and folding it into a CRC-32 of the frame (the `frame crc32` celsim
 * prints). It uses the core alone, so it runs on a microcontroller with no
 * C library as well as on a host.
 */
#ifndef SIGN_H
#define SIGN_H

#include <celscan_private.h>

/* The board's panel: receives line y as width RGB565 pixels, little-endian. */
typedef void (*sign_panel_write)(void *user, int y, const uint8_t *rgb565, int width);

typedef struct sign {
    cs_scene scenes[2];
    cs_stream stream;
    cs_workspace ws;
    cs_renderer r;
    float line[CS_CFG_MAX_WIDTH * 3];
    uint8_t px[CS_CFG_MAX_WIDTH * 2];
    int width, height;
    sign_panel_write write;
    void *user;
    uint32_t crc;          /* of the frame being rendered */
    uint32_t errors;       /* stream transactions or bytes dropped */
    cs_stream_error last;  /* the last of them */
} sign;

/* CS_ERR_ARG if the size is beyond the library's capacities or write is NULL. */
cs_status sign_init(sign *s, int width, int height, sign_panel_write write, void *user);

/* Bytes from the link, in any chunking. A commit is swapped in at once (the
 * caller feeds between frames); a dropped transaction is counted in errors. */
void sign_feed(sign *s, const uint8_t *data, size_t len);

/* The link closed: a transaction cut short is dropped and counted. */
void sign_end_of_input(sign *s);

/* Whether a scene has been committed. */
int sign_has_scene(const sign *s);

/* Renders the frame at `time` seconds to the panel; *crc is its CRC-32. */
cs_status sign_frame(sign *s, float time, uint32_t *crc);

#endif /* SIGN_H */
