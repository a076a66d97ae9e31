/*
 * cels_write.c - host-side cel stream writer (see cels_write.h).
 *
 * The framing helpers leave placeholders for lengths and CRCs and patch them
 * when a record or transaction closes, so callers write fields in order and
 * never count bytes. The scene encoder walks the store cel by cel, which is
 * the order the decoder rebuilds it in; region and contour indices in tracks
 * are renumbered to that order, so even a store whose regions are not in
 * stack order (after cs_scene_move_cel) round-trips to the same picture.
 * For a store built only by appending (the JSON loader) the decoded store is
 * identical, byte for byte, in its used part: paint functions, CSG programs
 * and contour operands included (class 5 records, format 1.1).
 */
#include "cels_write.h"
#include "celscan_private.h"

#include <stdlib.h>
#include <string.h>

void cels_buf_init(cels_buf *b)
{
    memset(b, 0, sizeof *b);
}

void cels_buf_free(cels_buf *b)
{
    free(b->data);
    cels_buf_init(b);
}

static bool reserve(cels_buf *b, size_t n)
{
    if (b->oom)
        return false;
    if (b->len + n <= b->cap)
        return true;
    size_t cap = b->cap ? b->cap : 256;
    while (cap < b->len + n)
        cap *= 2;
    uint8_t *p = realloc(b->data, cap);
    if (!p) {
        b->oom = true;
        return false;
    }
    b->data = p;
    b->cap = cap;
    return true;
}

void cels_put_bytes(cels_buf *b, const void *p, size_t n)
{
    if (n && reserve(b, n)) {
        memcpy(b->data + b->len, p, n);
        b->len += n;
    }
}

void cels_put_u8(cels_buf *b, uint8_t v)
{
    cels_put_bytes(b, &v, 1);
}

void cels_put_u16(cels_buf *b, uint16_t v)
{
    uint8_t p[2] = {(uint8_t)v, (uint8_t)(v >> 8)};
    cels_put_bytes(b, p, 2);
}

static void set_u32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)v;
    p[1] = (uint8_t)(v >> 8);
    p[2] = (uint8_t)(v >> 16);
    p[3] = (uint8_t)(v >> 24);
}

void cels_put_u32(cels_buf *b, uint32_t v)
{
    uint8_t p[4];
    set_u32(p, v);
    cels_put_bytes(b, p, 4);
}

void cels_put_f32(cels_buf *b, float v)
{
    uint32_t u;
    memcpy(&u, &v, 4);
    cels_put_u32(b, u);
}

void cels_put_f32s(cels_buf *b, const float *v, size_t n)
{
    for (size_t i = 0; i < n; i++)
        cels_put_f32(b, v[i]);
}

static void header(cels_buf *b, const char *magic, uint32_t word)
{
    uint8_t h[CS_WIRE_HEADER_SIZE];
    memcpy(h, magic, 4);
    h[4] = CS_WIRE_MAJOR;
    h[5] = CS_WIRE_MINOR;
    h[6] = h[7] = 0;
    set_u32(h + 8, word);
    set_u32(h + 12, cs_crc32(0, h, 12));
    cels_put_bytes(b, h, sizeof h);
}

void cels_stream_header(cels_buf *b)
{
    header(b, CS_WIRE_STREAM_MAGIC, 0);
}

void cels_txn_begin(cels_buf *b)
{
    b->txn_start = b->len;
    header(b, CS_WIRE_TXN_MAGIC, 0);
}

void cels_envelope_begin(cels_buf *b)
{
    b->txn_start = b->len;
    header(b, CS_WIRE_SIGNED_MAGIC, 0);
}

void cels_txn_end(cels_buf *b)
{
    if (b->oom || b->txn_start + CS_WIRE_HEADER_SIZE > b->len)
        return;
    uint8_t *h = b->data + b->txn_start;
    size_t body = b->len - b->txn_start - CS_WIRE_HEADER_SIZE;
    set_u32(h + 8, (uint32_t)body);
    set_u32(h + 12, cs_crc32(0, h, 12));
    cels_put_u32(b, cs_crc32(0, b->data + b->txn_start, b->len - b->txn_start));
}

void cels_rec_begin(cels_buf *b, uint16_t type)
{
    b->rec_start = b->len;
    cels_put_u16(b, type);
    cels_put_u32(b, 0);
}

void cels_rec_end(cels_buf *b)
{
    if (b->oom || b->rec_start + CS_WIRE_RECORD_HEADER_SIZE > b->len)
        return;
    set_u32(b->data + b->rec_start + 2,
            (uint32_t)(b->len - b->rec_start - CS_WIRE_RECORD_HEADER_SIZE));
}

void cels_rec_commit(cels_buf *b)
{
    cels_rec_begin(b, CS_REC_COMMIT);
    cels_rec_end(b);
}

static void put_paint(cels_buf *b, const cs_paint *p)
{
    cels_put_f32s(b, p->pigment, 3);
    cels_put_f32s(b, p->medium, 3);
    cels_put_f32(b, p->beta);
}

/* REGION_FUNC for field `field` of the region just written. */
static void put_func(cels_buf *b, int field, const cs_paint_func *f)
{
    cels_rec_begin(b, CS_REC_REGION_FUNC);
    cels_put_u32(b, (uint32_t)field);
    cels_put_u32(b, f->kind);
    cels_put_u32(b, f->spread);
    cels_put_u32(b, f->map_cols);
    cels_put_u32(b, f->stop_count);
    cels_put_f32s(b, f->geom, 6);
    for (int i = 0; i < f->stop_count; i++) {
        cels_put_f32(b, f->stops[i].offset);
        cels_put_f32s(b, f->stops[i].value, 3);
    }
    cels_rec_end(b);
}

/* REGION_CSG: tokens as the API writes them (operand n, operator -k). */
static void put_csg(cels_buf *b, const cs_region *r)
{
    cels_rec_begin(b, CS_REC_REGION_CSG);
    cels_put_u32(b, r->csg_len);
    for (int i = 0; i < r->csg_len; i++) {
        uint8_t t = r->csg[i];
        int32_t tok = (t & 0x80u) ? -(int32_t)(t & 0x7Fu) : (int32_t)t;
        cels_put_u32(b, (uint32_t)tok);
    }
    cels_rec_end(b);
}

static bool is_default(const float *v, float x)
{
    return v[0] == x && v[1] == x && v[2] == x;
}

int cels_encode_scene(cels_buf *b, const cs_scene *sc)
{
    uint32_t *region_new = calloc(sc->region_count + 1u, sizeof *region_new);
    uint32_t *contour_new = calloc(sc->contour_count + 1u, sizeof *contour_new);
    uint32_t *track_order = calloc(sc->track_count + 1u, sizeof *track_order);
    if (!region_new || !contour_new || !track_order) {
        free(region_new);
        free(contour_new);
        free(track_order);
        return -1;
    }
    cels_txn_begin(b);
    cels_rec_begin(b, CS_REC_SCENE);
    cels_put_f32(b, sc->canvas_w);
    cels_put_f32(b, sc->canvas_h);
    cels_rec_end(b);
    /* Before the cels: a cel without its own front light keeps a copy of
     * the stack front light as it was when the cel was added. */
    if (!is_default(sc->stack_front, 1.0f) || !is_default(sc->stack_back, 0.0f)) {
        cels_rec_begin(b, CS_REC_LIGHTS);
        cels_put_f32s(b, sc->stack_front, 3);
        cels_put_f32s(b, sc->stack_back, 3);
        cels_rec_end(b);
    }
    if (sc->has_background) {
        cels_rec_begin(b, CS_REC_BACKGROUND);
        cels_put_f32s(b, sc->background, 3);
        cels_rec_end(b);
    }
    if (sc->blend != CS_BLEND_LINEAR) {
        cels_rec_begin(b, CS_REC_BLEND);
        cels_put_u32(b, sc->blend);
        cels_rec_end(b);
    }
    if (sc->epoch_ns) {
        cels_rec_begin(b, CS_REC_EPOCH);
        cels_put_u32(b, (uint32_t)sc->epoch_ns);
        cels_put_u32(b, (uint32_t)(sc->epoch_ns >> 32));
        cels_rec_end(b);
    }
    uint32_t next_region = 0, next_contour = 0;
    for (uint32_t ci = 0; ci < sc->cel_count; ci++) {
        const cs_cel *c = &sc->cels[ci];
        cels_rec_begin(b, CS_REC_CEL);
        cels_put_u32(b, c->has_front ? CS_WIRE_CEL_HAS_FRONT : 0u);
        cels_put_f32s(b, &c->transform.a, 6);
        cels_put_f32s(b, c->front, 3);
        cels_put_f32s(b, c->back, 3);
        cels_rec_end(b);
        for (uint32_t ri = c->first_region; ri < c->first_region + c->region_count; ri++) {
            const cs_region *r = &sc->regions[ri];
            region_new[ri] = next_region++;
            cels_rec_begin(b, CS_REC_REGION);
            cels_put_u32(b, r->fill_rule);
            put_paint(b, &r->paint);
            cels_rec_end(b);
            /* Functions in field order and CSG, before the contours: the
             * order the JSON loader makes its calls in, so the function
             * slots come out numbered the same. */
            for (int f = 0; f < 3; f++)
                if (r->func[f])
                    put_func(b, f, &sc->funcs[r->func[f] - 1u]);
            if (r->csg_len)
                put_csg(b, r);
            for (uint32_t k = r->first_contour; k < r->first_contour + r->contour_count; k++) {
                const cs_contour *ct = &sc->contours[k];
                const cs_point *pts = &sc->points[ct->first_point];
                const float *iv = &sc->intervals[ct->first_point];
                bool uniform = true;
                for (uint32_t i = 0; i < ct->point_count; i++)
                    uniform = uniform && iv[i] == 1.0f;
                contour_new[k] = next_contour++;
                cels_rec_begin(b, CS_REC_CONTOUR);
                cels_put_u32(b, ct->degree);
                cels_put_u32(b, ct->point_count);
                cels_put_u32(b, uniform ? 0u : CS_WIRE_CONTOUR_INTERVALS);
                for (uint32_t i = 0; i < ct->point_count; i++) {
                    cels_put_f32(b, pts[i].x);
                    cels_put_f32(b, pts[i].y);
                    cels_put_f32(b, pts[i].w);
                }
                if (!uniform)
                    cels_put_f32s(b, iv, ct->point_count);
                cels_rec_end(b);
                if (ct->operand) {
                    cels_rec_begin(b, CS_REC_CONTOUR_OPERAND);
                    cels_put_u32(b, ct->operand);
                    cels_rec_end(b);
                }
            }
        }
    }
    /* Groups once every cel exists: a parent may stand behind its child. */
    for (uint32_t ci = 0; ci < sc->cel_count; ci++)
        if (sc->cels[ci].parent != CS_NO_PARENT) {
            cels_rec_begin(b, CS_REC_CEL_PARENT);
            cels_put_u32(b, ci);
            cels_put_u32(b, sc->cels[ci].parent);
            cels_rec_end(b);
        }
    /* Tracks in the order their keys lie in the pools, i.e. the order they
     * were added: the decoder then lays the pools out the same way. */
    for (uint32_t i = 0; i < sc->track_count; i++)
        track_order[i] = i;
    for (uint32_t i = 1; i < sc->track_count; i++)
        for (uint32_t j = i; j > 0 && sc->tracks[track_order[j - 1]].first_key >
                                          sc->tracks[track_order[j]].first_key;
             j--) {
            uint32_t t = track_order[j];
            track_order[j] = track_order[j - 1];
            track_order[j - 1] = t;
        }
    for (uint32_t i = 0; i < sc->track_count; i++) {
        const cs_track *t = &sc->tracks[track_order[i]];
        if (t->key_count == 0)
            continue; /* a track without keys animates nothing */
        uint32_t target = t->target;
        if (t->kind == CS_TRACK_PAINT)
            target = region_new[target];
        else if (t->kind == CS_TRACK_POINTS)
            target = contour_new[target];
        cels_rec_begin(b, CS_REC_TRACK);
        cels_put_u32(b, t->kind);
        cels_put_u32(b, target);
        cels_put_u32(b, t->ease);
        cels_put_u32(b, t->key_count);
        for (uint32_t k = 0; k < t->key_count; k++) {
            cels_put_f32(b, sc->key_times[t->first_key + k]);
            cels_put_f32s(b, &sc->key_values[t->first_value + k * t->width], t->width);
        }
        cels_rec_end(b);
    }
    cels_rec_commit(b);
    cels_txn_end(b);
    free(region_new);
    free(contour_new);
    free(track_order);
    return b->oom ? -1 : 0;
}

int cels_write_scene(const cs_scene *scene, FILE *out)
{
    cels_buf b;
    cels_buf_init(&b);
    cels_stream_header(&b);
    int rc = cels_encode_scene(&b, scene);
    if (rc == 0 && fwrite(b.data, 1, b.len, out) != b.len)
        rc = -1;
    cels_buf_free(&b);
    return rc;
}
