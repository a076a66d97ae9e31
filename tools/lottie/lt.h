/*
 * lt.h - the Lottie importer: a Lottie (Bodymovin JSON) animation as a
 * celscan scene with tracks, cel groups and easing (docs/LOTTIE.md).
 *
 * lt_import turns the file's text into scene JSON (docs/SCENE.md), which
 * the scene loader turns into a store and `celc` into a cel stream; what it
 * cannot map it names in one warning per feature, and it refuses hostile
 * input (deep nesting, cycles, huge counts, NaN) with an error, in bounded
 * time and memory. Host code: libc, libm, cJSON and the SVG importer's
 * geometry.
 */
#ifndef LT_H
#define LT_H

#include <cjson/cJSON.h>
#include <stdbool.h>
#include <stddef.h>

typedef struct lt_warnings {
    int n;
    char **text;
} lt_warnings;

void lt_warnings_free(lt_warnings *w);

typedef struct lt_opts {
    double tolerance; /* stroke outline tolerance in canvas units; 0: 0.01 px at 1024 px */
    double max_work;  /* sampled floats allowed (0: LT_MAX_WORK); a fuzzer sets less */
    int max_frames;   /* frames sampled at most (0: LT_MAX_FRAMES) */
} lt_opts;

/* Whether a parsed JSON document is a Lottie file ("v", "fr", "ip", "op", "layers"). */
bool lt_is_lottie(const cJSON *root);

/*
 * The scene JSON of a Lottie document, or NULL with a message in err.
 * Warnings (may be NULL) receive one line per unsupported feature.
 * Scene time t is Lottie frame ip + t * fr, as a player shows it.
 */
cJSON *lt_import(const cJSON *root, const lt_opts *opts, lt_warnings *warnings, char *err,
                 size_t errlen);

/* `celc import anim.json -o out.json|out.cels [-q] [--tolerance T]`: exit status 0, 1, 2. */
int lt_main(int argc, char **argv);

#endif /* LT_H */
