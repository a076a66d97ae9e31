/*
 * celc_publish.h - celc publish (tools/celc_publish.c), and the compile step
 * it shares with celc compile (tools/celc.c).
 */
#ifndef CELC_PUBLISH_H
#define CELC_PUBLISH_H

#include "cels_write.h"

/* celc publish FILE.cels|SCENE.json --broker mqtt[s]://HOST:PORT --topic T [--retain] ... */
int celc_publish_main(int argc, char **argv);

/*
 * The stream `celc compile` writes for the scene JSON at `path`, into b
 * (initialised here; the caller frees it with cels_buf_free). Returns 0, or
 * 1 with the reason on stderr (refused scene, out of memory, too big).
 */
int celc_compile_scene(const char *path, cels_buf *b);

#endif /* CELC_PUBLISH_H */
