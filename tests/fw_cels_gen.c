/*
 * fw_cels_gen.c - cel streams for the firmware's stream tests.
 *
 *   fw_cels_gen SCENE.json OUT.cels     the scene JSON, as celsim loads it
 *   fw_cels_gen --tracks OUT.cels       the animated C scene (fw_tracks_scene.c)
 *
 * Writes a stream header and one transaction that defines the whole scene:
 * the JSON goes through scene_json_load, the loader celsim uses, and then
 * cels_write_scene, the encoder `celc compile` will use, so the firmware
 * decodes the very store celsim renders. A stand-in until celc lands; the
 * qemu test then calls celc instead (tools/fw_qemu_test.sh, FW_CELC).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cels_write.h"
#include "celscan.h"
#include "fw_tracks_scene.h"
#include "scene_json.h"

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: fw_cels_gen SCENE.json|--tracks OUT.cels\n");
        return 2;
    }
    cs_scene *scene = calloc(1, sizeof *scene);
    if (!scene) {
        fprintf(stderr, "fw_cels_gen: out of memory\n");
        return 1;
    }
    if (strcmp(argv[1], "--tracks") == 0) {
        cs_error err;
        cs_status st = fw_tracks_scene(scene, &err);
        if (st != CS_OK) {
            fprintf(stderr, "fw_cels_gen: tracks scene: %s (cel %d region %d contour %d)\n",
                    cs_status_str(st), err.cel, err.region, err.contour);
            return 1;
        }
    } else {
        char msg[SCENE_JSON_ERRLEN];
        if (scene_json_load(argv[1], scene, msg, sizeof msg) != 0) {
            fprintf(stderr, "fw_cels_gen: %s\n", msg);
            return 1;
        }
        if (scene->func_count) {
            /* Version 1.0 of the stream has no record for paint functions. */
            fprintf(stderr, "fw_cels_gen: %s: paint functions cannot be streamed yet\n",
                    argv[1]);
            return 1;
        }
        for (uint32_t r = 0; r < scene->region_count; r++)
            if (scene->regions[r].csg_len) {
                fprintf(stderr, "fw_cels_gen: %s: CSG cannot be streamed yet\n", argv[1]);
                return 1;
            }
    }
    FILE *out = fopen(argv[2], "wb");
    if (!out || cels_write_scene(scene, out) != 0 || fclose(out) != 0) {
        perror(argv[2]);
        return 1;
    }
    free(scene);
    return 0;
}
