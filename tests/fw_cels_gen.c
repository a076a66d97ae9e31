/*
 * fw_cels_gen.c - the cel stream of the firmware test's animated C scene.
 *
 *   fw_cels_gen --tracks OUT.cels
 *
 * The qemu test sends scene JSON compiled by `celc compile`; this writes the
 * one scene that exists only in C (tests/fw_tracks_scene.c, every keyframe
 * track kind on the 480x272 board's capacities) through the same encoder,
 * a stream header and one transaction that defines the whole scene.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cels_write.h"
#include "celscan_private.h"
#include "fw_tracks_scene.h"

int main(int argc, char **argv)
{
    if (argc != 3 || strcmp(argv[1], "--tracks") != 0) {
        fprintf(stderr, "usage: fw_cels_gen --tracks OUT.cels\n");
        return 2;
    }
    cs_scene *scene = calloc(1, sizeof *scene);
    if (!scene) {
        fprintf(stderr, "fw_cels_gen: out of memory\n");
        return 1;
    }
    cs_error err;
    cs_status st = fw_tracks_scene(scene, &err);
    if (st != CS_OK) {
        fprintf(stderr, "fw_cels_gen: tracks scene: %s (cel %d region %d contour %d)\n",
                cs_status_str(st), err.cel, err.region, err.contour);
        return 1;
    }
    FILE *out = fopen(argv[2], "wb");
    if (!out || cels_write_scene(scene, out) != 0 || fclose(out) != 0) {
        perror(argv[2]);
        return 1;
    }
    free(scene);
    return 0;
}
