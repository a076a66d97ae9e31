/*
 * celc.c - the scene compiler: authoring formats in, cel streams out.
 *
 *   celc compile SCENE.json -o OUT.cels    scene JSON (DESIGN.md, docs/SCENE.md) to a stream
 *   celc import ...                        SVG to scene JSON or a stream (tools/celc_import.c)
 *   celc keygen -o NAME                    an Ed25519 key pair: NAME.key (0600), NAME.pub
 *   celc sign IN.cels -o OUT.cels --key NAME.key    every transaction in a signed envelope
 *
 * Signing (tools/cels_sign.c, docs/STREAM.md) wraps each transaction in an
 * envelope carrying the key id, a sequence number and an Ed25519 signature;
 * `compile --sign NAME.key` does it on the way out. The sequence is the
 * wall-clock time in microseconds (one more for each further transaction of
 * the same run): no counter file lives beside the key, so copies of a key on
 * two build machines cannot reuse a number, and a sign that remembers the
 * last sequence it applied refuses anything signed before it.
 *
 * compile loads the JSON with the same loader celsim uses (host-sim/
 * scene_json.c), so the scene is built and checked by the core's cs_scene_*
 * calls, "animate" tracks included, and a refusal names the JSON path of the
 * culprit. It then writes the whole store as one transaction after a stream
 * header (tools/cels_write.c, docs/STREAM.md). The decoder rebuilds the very
 * same store from it through the very same calls, so the board shows what
 * celsim shows for the JSON, bit for bit.
 *
 * The output appears only when it is complete: it is written to a temporary
 * file next to OUT and renamed over it, so a failed compile never leaves a
 * truncated stream for a board to pick up.
 *
 * Exit status: 0 written; 1 the scene was refused or a file could not be
 * read or written; 2 bad command line.
 */
#include <errno.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "celc_import.h"
#include "cels_sign.h"
#include "celc_publish.h"
#include "cels_write.h"
#include "celscan_private.h"
#include "cli.h"
#include "lottie/lt.h"
#include "scene_json.h"

enum { EXIT_FAIL = 1 };

static const char usage_text[] =
    "usage: celc compile SCENE.json -o OUT.cels [-v] [--sign NAME.key]\n"
    "       celc keygen -o NAME\n"
    "       celc sign IN.cels -o OUT.cels --key NAME.key\n"
    "       celc import DRAWING.svg -o OUT.json|OUT.cels [options]   (celc import --help)\n"
    "       celc text \"STRING\" -o OUT.json [options]                 (celc text --help)\n"
    "       celc publish FILE.cels|SCENE.json --broker mqtt[s]://HOST:PORT --topic T [--retain]\n"
    "                    [--credentials FILE]                        (celc publish --help)\n"
    "\n"
    "compile   turns authoring JSON (with its \"animate\" tracks) into a cel stream\n"
    "          (docs/STREAM.md): a stream header and one transaction that defines\n"
    "          the whole scene. -o - writes to standard output. Errors name the\n"
    "          JSON path, e.g. cels[2].regions[0].contours[1].points[4].\n"
    "  -v      print what was written (cels, regions, contours, functions, tracks, bytes)\n"
    "  --sign NAME.key  sign the transaction (as celc sign does)\n"
    "keygen    writes a new Ed25519 key pair: NAME.key (private, mode 0600) and NAME.pub\n"
    "          (give it to celfw --trust); never overwrites a key\n"
    "sign      wraps every transaction of a stream in a signed envelope; the sequence\n"
    "          number is the time in microseconds, one more per transaction\n"
    "import    turns an SVG drawing into scene JSON or straight into a stream: paths,\n"
    "          shapes, transforms, styles, gradients, strokes as regions, text\n"
    "text      sets a string in a font (FreeType) as scene JSON\n"
    "publish   sends a stream (a scene JSON compiled first) to an MQTT broker's topic, QoS 1\n"
    "\n"
    "exit status: 0 ok, 1 scene refused or file error, 2 usage error\n";

/* Writes all of `data` to `path` through a temporary file renamed into place. */
static int write_atomically(const char *path, const uint8_t *data, size_t len)
{
    if (strcmp(path, "-") == 0) {
        if (fwrite(data, 1, len, stdout) != len || fflush(stdout) != 0) {
            fprintf(stderr, "celc: cannot write to standard output: %s\n", strerror(errno));
            return EXIT_FAIL;
        }
        return 0;
    }
    size_t n = strlen(path);
    char *tmp = malloc(n + 16);
    if (tmp == NULL) {
        fprintf(stderr, "celc: out of memory\n");
        return EXIT_FAIL;
    }
    snprintf(tmp, n + 16, "%s.tmp.XXXXXX", path);
    int fd = mkstemp(tmp);
    if (fd < 0) {
        fprintf(stderr, "celc: %s: cannot create a file next to it: %s\n", path, strerror(errno));
        free(tmp);
        return EXIT_FAIL;
    }
    FILE *f = fdopen(fd, "wb");
    bool ok = f != NULL && fwrite(data, 1, len, f) == len;
    int saved = errno;
    if (f != NULL) {
        if (fclose(f) != 0 && ok) {
            ok = false;
            saved = errno;
        }
    } else {
        close(fd);
    }
    /* mkstemp makes the file 0600; a stream is no secret. */
    if (ok && chmod(tmp, 0644) != 0)
        saved = errno;
    if (ok && rename(tmp, path) != 0) {
        ok = false;
        saved = errno;
    }
    if (!ok) {
        fprintf(stderr, "celc: %s: cannot write: %s\n", path, strerror(saved));
        remove(tmp);
    }
    free(tmp);
    return ok ? 0 : EXIT_FAIL;
}

/* celc_publish.h: shared with celc publish --sign. */
int celc_sign_buffer(cels_buf *b, const char *key_path, const char *what)
{
    cels_secret_key k;
    char err[400];
    if (!cels_sign_init()) {
        fprintf(stderr, "celc: libsodium cannot start\n");
        return EXIT_FAIL;
    }
    if (cels_read_secret_key(key_path, &k, err, sizeof err) != 0) {
        fprintf(stderr, "celc: %s\n", err);
        return EXIT_FAIL;
    }
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    uint64_t seq = (uint64_t)ts.tv_sec * 1000000u + (uint64_t)ts.tv_nsec / 1000u;
    cels_buf out;
    cels_buf_init(&out);
    int rc = cels_sign_stream(b->data, b->len, &k, &seq, &out, err, sizeof err);
    memset(&k, 0, sizeof k);
    if (rc != 0 || out.oom) {
        fprintf(stderr, "celc: %s: %s\n", what, out.oom ? "out of memory" : err);
        cels_buf_free(&out);
        return EXIT_FAIL;
    }
    cels_buf_free(b);
    *b = out;
    return 0;
}

/* Loads and encodes the scene JSON at `in` into b; *scene_out gets the
 * store (the caller frees it and b), or NULL on failure. */
static int compile(const char *in, cels_buf *b, cs_scene **scene_out)
{
    cels_buf_init(b);
    *scene_out = NULL;
    /* The store is half a megabyte: heap, not stack. */
    cs_scene *scene = calloc(1, sizeof *scene);
    if (scene == NULL) {
        fprintf(stderr, "celc: out of memory for the scene store\n");
        return EXIT_FAIL;
    }
    char err[SCENE_JSON_ERRLEN];
    if (scene_json_load(in, scene, err, sizeof err) != 0) {
        fprintf(stderr, "celc: %s\n", err);
        free(scene);
        return EXIT_FAIL;
    }
    cels_stream_header(b);
    int rc = 0;
    if (cels_encode_scene(b, scene) != 0) {
        fprintf(stderr, "celc: out of memory encoding %s\n", in);
        rc = EXIT_FAIL;
    } else if (b->len - 2 * CS_WIRE_HEADER_SIZE - CS_WIRE_TRAILER_SIZE > CS_CFG_STREAM_MAX_TXN) {
        /* The stream header, then the transaction's header, body and trailer. */
        fprintf(stderr, "celc: %s: the scene's transaction body is %zu bytes, more than a decoder "
                        "accepts (%u)\n",
                in, b->len - 2 * CS_WIRE_HEADER_SIZE - CS_WIRE_TRAILER_SIZE,
                (unsigned)CS_CFG_STREAM_MAX_TXN);
        rc = EXIT_FAIL;
    }
    if (rc != 0) {
        cels_buf_free(b);
        free(scene);
        return rc;
    }
    *scene_out = scene;
    return 0;
}

int celc_compile_scene(const char *path, cels_buf *b)
{
    cs_scene *scene;
    int rc = compile(path, b, &scene);
    free(scene);
    return rc;
}

static int compile_main(int argc, char **argv)
{
    const char *in = NULL, *out = NULL, *key = NULL;
    bool verbose = false;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (strcmp(a, "-o") == 0 || strcmp(a, "--output") == 0) {
            if (i + 1 >= argc || argv[i + 1][0] == '\0')
                return cli_usage_error("%s needs a file name (see celc --help)", a);
            out = argv[++i];
        } else if (strncmp(a, "--output=", 9) == 0) {
            out = a + 9;
        } else if (strcmp(a, "--sign") == 0) {
            if (i + 1 >= argc || argv[i + 1][0] == '\0')
                return cli_usage_error("--sign needs a key file NAME.key (see celc --help)");
            key = argv[++i];
        } else if (strcmp(a, "-v") == 0 || strcmp(a, "--verbose") == 0) {
            verbose = true;
        } else if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
            fputs(usage_text, stdout);
            return 0;
        } else if (a[0] == '-' && a[1] != '\0') {
            return cli_usage_error("compile: unknown option '%s' (see celc --help)", a);
        } else if (in == NULL) {
            in = a;
        } else {
            return cli_usage_error("compile: unexpected argument '%s': one SCENE per run", a);
        }
    }
    if (in == NULL)
        return cli_usage_error("compile needs a SCENE.json (see celc --help)");
    if (out == NULL || out[0] == '\0')
        return cli_usage_error("compile needs -o OUT.cels (or -o - for standard output)");

    cels_buf b;
    cs_scene *scene = NULL;
    int rc = compile(in, &b, &scene);
    if (rc == 0 && key != NULL)
        rc = celc_sign_buffer(&b, key, in);
    if (rc == 0)
        rc = write_atomically(out, b.data, b.len);
    if (rc == 0 && verbose)
        fprintf(stderr,
                "celc: %s -> %s: %u cels, %u regions, %u contours, %u points, %u functions, "
                "%u tracks, %u keys; %zu bytes (stream %d.%d)\n",
                in, out, scene->cel_count, scene->region_count, scene->contour_count,
                scene->point_count, scene->func_count, scene->track_count, scene->key_count,
                b.len, CS_WIRE_MAJOR, CS_WIRE_MINOR);
    cels_buf_free(&b);
    free(scene);
    return rc;
}

static int keygen_main(int argc, char **argv)
{
    const char *name = NULL;
    for (int i = 1; i < argc; i++) {
        if ((strcmp(argv[i], "-o") == 0 || strcmp(argv[i], "--output") == 0) && i + 1 < argc)
            name = argv[++i];
        else
            return cli_usage_error("keygen: unexpected argument '%s' (celc keygen -o NAME)", argv[i]);
    }
    if (name == NULL || name[0] == '\0')
        return cli_usage_error("keygen needs -o NAME (writes NAME.key and NAME.pub)");
    char err[400];
    if (!cels_sign_init()) {
        fprintf(stderr, "celc: libsodium cannot start\n");
        return EXIT_FAIL;
    }
    if (cels_keygen(name, err, sizeof err) != 0) {
        fprintf(stderr, "celc: keygen: %s\n", err);
        return EXIT_FAIL;
    }
    fprintf(stderr, "celc: wrote %s.key (private, mode 0600: keep it) and %s.pub (for celfw --trust)\n",
            name, name);
    return 0;
}

/* Reads a whole file into b; 0, or EXIT_FAIL with the reason on stderr. */
static int read_whole(const char *path, cels_buf *b)
{
    FILE *f = fopen(path, "rb");
    if (f == NULL) {
        fprintf(stderr, "celc: %s: %s\n", path, strerror(errno));
        return EXIT_FAIL;
    }
    uint8_t chunk[65536];
    size_t got;
    while ((got = fread(chunk, 1, sizeof chunk, f)) > 0)
        cels_put_bytes(b, chunk, got);
    bool bad = ferror(f) != 0;
    fclose(f);
    if (bad || b->oom) {
        fprintf(stderr, "celc: %s: %s\n", path, bad ? "read error" : "out of memory");
        return EXIT_FAIL;
    }
    return 0;
}

static int sign_main(int argc, char **argv)
{
    const char *in = NULL, *out = NULL, *key = NULL;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if ((strcmp(a, "-o") == 0 || strcmp(a, "--output") == 0) && i + 1 < argc)
            out = argv[++i];
        else if (strcmp(a, "--key") == 0 && i + 1 < argc)
            key = argv[++i];
        else if (a[0] == '-' && a[1] != '\0')
            return cli_usage_error("sign: unknown option or missing value '%s' (see celc --help)", a);
        else if (in == NULL)
            in = a;
        else
            return cli_usage_error("sign: unexpected argument '%s': one stream per run", a);
    }
    if (in == NULL || out == NULL || out[0] == '\0' || key == NULL)
        return cli_usage_error("sign needs IN.cels, -o OUT.cels and --key NAME.key");
    cels_buf b;
    cels_buf_init(&b);
    int rc = read_whole(in, &b);
    if (rc == 0)
        rc = celc_sign_buffer(&b, key, in);
    if (rc == 0)
        rc = write_atomically(out, b.data, b.len);
    cels_buf_free(&b);
    return rc;
}

/* Whether `import`'s input (its first argument that is not an option or
 * an option's value) is a .json file: a Lottie animation, not an SVG. */
static bool lottie_input(int argc, char **argv)
{
    for (int i = 1; i < argc; i++) {
        if (argv[i][0] == '-') {
            if (strcmp(argv[i], "-q") != 0 && strcmp(argv[i], "--one-cel-per-shape") != 0)
                i++;
            continue;
        }
        size_t n = strlen(argv[i]);
        return n > 5 && strcmp(argv[i] + n - 5, ".json") == 0;
    }
    return false;
}

/* SVG import and text setting live in tools/celc_import.c (tools/svg/),
 * Lottie import in tools/lottie/ (an input file named *.json). */
static int import_main(int argc, char **argv)
{
    return lottie_input(argc, argv) ? lt_main(argc, argv) : celc_import_main(argc, argv);
}

int main(int argc, char **argv)
{
    /* MQTT delivery to a fleet of signs lives in tools/celc_publish.c. */
    static const cli_command commands[] = {
        {"compile", compile_main}, {"keygen", keygen_main},    {"sign", sign_main},
        {"import", import_main},   {"text", celc_text_main},  {"publish", celc_publish_main},
    };
    static const cli_program celc = {
        "celc", usage_text, "compile, keygen, sign, import, text or publish; see celc --help",
        commands, (int)(sizeof commands / sizeof commands[0])};
    return cli_main(&celc, argc, argv);
}
