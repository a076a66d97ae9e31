/*
 * lt_main.c - `celc import ANIM.json -o OUT.json|OUT.cels`: the Lottie
 * importer on the command line.
 *
 * The Lottie file becomes scene JSON (lt_import); to write a cel stream the
 * JSON goes through the scene loader and the stream writer, as `celc
 * compile` does, so the two outputs are the same scene. Warnings (one per
 * unsupported feature) go to stderr unless -q.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../../host-sim/scene_json.h"
#include "../cels_write.h"
#include "../cli_num.h"
#include "celscan_private.h"
#include "lt.h"

static int usage(void)
{
    fprintf(stderr, "usage: celc import ANIM.json -o OUT.json|OUT.cels [--tolerance T] [-q]\n"
                    "  a Lottie (Bodymovin JSON) animation as a scene with tracks (docs/LOTTIE.md)\n"
                    "  --tolerance T  stroke outline tolerance in canvas units (default 0.01 px\n"
                    "                 at 1024 px on the longer side)\n"
                    "  -q             no warnings\n");
    return 2;
}

static char *read_file(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    size_t cap = 1 << 16, n = 0;
    char *buf = malloc(cap + 1);
    while (buf) {
        size_t got = fread(buf + n, 1, cap - n, f);
        n += got;
        if (n < cap)
            break;
        if (cap >= (size_t)64 << 20) { /* 64 MiB: not an animation file */
            free(buf);
            buf = NULL;
            break;
        }
        cap *= 2;
        char *nb = realloc(buf, cap + 1);
        if (!nb)
            free(buf);
        buf = nb;
    }
    fclose(f);
    if (buf) {
        buf[n] = '\0';
        *len = n;
    }
    return buf;
}

static bool has_suffix(const char *s, const char *suf)
{
    size_t n = strlen(s), m = strlen(suf);
    return n >= m && strcmp(s + n - m, suf) == 0;
}

int lt_main(int argc, char **argv)
{
    const char *in = NULL, *out = NULL;
    bool quiet = false;
    lt_opts opts = {0};
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "-o") && i + 1 < argc) {
            out = argv[++i];
        } else if (!strcmp(argv[i], "-q")) {
            quiet = true;
        } else if (!strcmp(argv[i], "--tolerance") && i + 1 < argc) {
            if (!cli_real(argv[++i], '\0', 0.0, 1e6, &opts.tolerance)) {
                fprintf(stderr, "celc import: --tolerance '%s': expected a number in 0..1e6\n",
                        argv[i]);
                return 2;
            }
        } else if (argv[i][0] == '-' || in) {
            return usage();
        } else {
            in = argv[i];
        }
    }
    if (!in || !out || (!has_suffix(out, ".json") && !has_suffix(out, ".cels")))
        return usage();
    size_t len = 0;
    char *text = read_file(in, &len);
    if (!text) {
        fprintf(stderr, "celc import: cannot read %s (or larger than 64 MiB)\n", in);
        return 1;
    }
    cJSON *root = cJSON_ParseWithLength(text, len);
    free(text);
    if (!root) {
        fprintf(stderr, "celc import: %s: not valid JSON (or nested too deeply)\n", in);
        return 1;
    }
    lt_warnings w = {0, NULL};
    char err[512];
    cJSON *scene = lt_import(root, &opts, &w, err, sizeof err);
    cJSON_Delete(root);
    if (!quiet)
        for (int i = 0; i < w.n; i++)
            fprintf(stderr, "celc import: %s: warning: %s\n", in, w.text[i]);
    lt_warnings_free(&w);
    if (!scene) {
        fprintf(stderr, "celc import: %s: %s\n", in, err);
        return 1;
    }
    int rc = 1;
    if (has_suffix(out, ".json")) {
        char *js = cJSON_PrintUnformatted(scene);
        FILE *f = js ? fopen(out, "w") : NULL;
        if (f && fputs(js, f) >= 0 && fputc('\n', f) != EOF && fclose(f) == 0)
            rc = 0;
        else
            fprintf(stderr, "celc import: cannot write %s\n", out);
        free(js);
    } else {
        cs_scene *sc = malloc(sizeof *sc);
        char lerr[SCENE_JSON_ERRLEN];
        if (!sc) {
            fprintf(stderr, "celc import: out of memory\n");
        } else if (scene_json_load_tree(scene, in, sc, lerr, sizeof lerr) != 0) {
            fprintf(stderr, "celc import: the scene does not fit the store: %s\n", lerr);
        } else {
            FILE *f = fopen(out, "wb");
            if (f && cels_write_scene(sc, f) == 0 && fclose(f) == 0)
                rc = 0;
            else
                fprintf(stderr, "celc import: cannot write %s\n", out);
        }
        free(sc);
    }
    cJSON_Delete(scene);
    return rc;
}
