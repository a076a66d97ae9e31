/*
 * cs_stream.c - the cel stream decoder: bytes in, whole scenes out.
 *
 * The board's front door, so it assumes every byte may be hostile. The
 * format is in docs/STREAM.md; in short: 16-byte headers that carry their
 * own CRC, transactions of length-prefixed records, a CRC-32 trailer over
 * each transaction, a COMMIT record last.
 *
 * How it stays safe with fixed memory and any chunking:
 *   - One byte at a time through a state machine (this struct is all of its
 *     state; there is no recursion and no buffer that input can size).
 *   - The last 16 bytes always sit in a small ring. A header is recognised
 *     where the ring holds a magic and the CRC of the 12 bytes before its
 *     CRC field matches, in any state: that is how the decoder finds the
 *     first transaction, resynchronises after garbage, and notices that a
 *     transaction was cut short because a sender restarted (a new header
 *     inside a body drops the old transaction instead of eating the new
 *     one). A header's length field is trusted only once its CRC matched.
 *   - Records are read and applied to the back scene store as they stream
 *     in, each by its type's row in one table (cs_stream_apply.c), through
 *     the same cs_scene_* calls the JSON loader uses, so a stream and its
 *     JSON give identical stores. Bulk data (control points, keys) is read
 *     straight into the free end of the store's arrays, or in place for a
 *     same-size point update, and then checked and adopted by those calls,
 *     so no record size needs a buffer.
 *     A patch transaction first copies the front scene into the back store.
 *   - Nothing of a transaction becomes visible until its CRC trailer has
 *     matched and every record was accepted; then feeding pauses with
 *     CS_STREAM_COMMIT and the caller swaps the two stores between frames.
 *     Otherwise the back store is scratch and the transaction is reported
 *     once, with its start offset and the offset of the fault. A record
 *     error inside a transaction whose CRC then fails is reported as the
 *     CRC error: the bytes were damaged, not badly encoded.
 */
#include "cs_stream_internal.h"

/* CEL has the largest fixed part (cs__rec_kinds). */
_Static_assert(sizeof(((cs_stream *)0)->buf) >= 52, "buf holds the largest fixed part");
/* A CSG program is kept in buf after its 4-byte length, one byte a token. */
_Static_assert(sizeof(((cs_stream *)0)->buf) >= 4 + CS_CFG_MAX_CSG, "buf holds a CSG program");
_Static_assert(CS_CFG_MAX_OPERANDS <= 127, "CSG operands fit the token byte");

static void set_error(cs_stream_error *e, cs_status st, uint64_t offset, uint64_t at,
                      const char *what, const cs_error *where)
{
    e->status = st;
    e->offset = offset;
    e->at = at;
    e->what = what;
    if (where) {
        e->where.status = where->status;
        e->where.cel = where->cel;
        e->where.region = where->region;
        e->where.contour = where->contour;
        e->where.item = where->item;
    } else {
        cs__error(&e->where, st, -1, -1, -1, -1);
    }
}

static void copy_error(cs_stream_error *dst, const cs_stream_error *src)
{
    set_error(dst, src->status, src->offset, src->at, src->what, &src->where);
}

/* Queues an error for the caller. At most two arise from one byte. */
static void emit(cs_stream *s, cs_status st, uint64_t offset, uint64_t at, const char *what,
                 const cs_error *where)
{
    uint8_t slot = s->queued < 2 ? s->queued++ : 1;
    set_error(&s->queue[slot], st, offset, at, what, where);
}

/* Marks the current transaction as failed (the first failure is kept). */
static void fail(cs_stream *s, cs_status st, const char *what, const cs_error *where)
{
    if (!s->txn_failed) {
        s->txn_failed = true;
        set_error(&s->txn_err, st, s->txn_offset, s->rec_offset, what, where);
    }
    s->parse = P_DEAD;
}

cs_status cs_stream_init(cs_stream *s, cs_scene *front, bool front_valid, cs_scene *back)
{
    if (!s || !front || !back || front == back)
        return CS_ERR_ARG;
    s->front = front;
    s->back = back;
    s->has_scene = front_valid;
    s->offset = s->txn_offset = s->rec_offset = s->garbage_offset = s->skipped = 0;
    s->skip_left = s->env_end = 0;
    s->commits = s->dropped = 0;
    s->body_len = s->body_pos = s->crc = s->trailer = 0;
    s->rec_len = s->rec_pos = s->fixed_len = s->fill = s->word = 0;
    s->float_count = s->float_index = s->base = s->count = s->width = s->slot = 0;
    s->key_time = 0.0f;
    s->rec_kind = 0;
    s->state = ST_HUNT;
    s->parse = P_HDR;
    s->mode = M_NONE;
    s->rec_flags = 0;
    s->win_pos = s->win_count = s->queued = 0;
    s->commit_ready = s->in_garbage = s->seen_commit = s->txn_failed = false;
    for (int i = 0; i < 16; i++)
        s->win[i] = 0;
    set_error(&s->last, CS_OK, 0, 0, "ok", 0);
    set_error(&s->txn_err, CS_OK, 0, 0, "ok", 0);
    return CS_OK;
}

static void to_hunt(cs_stream *s)
{
    s->state = ST_HUNT;
    s->win_count = 0;
    s->in_garbage = false;
}

/* Stream or transaction header in the ring? Copies it out in order. */
static int ring_header(const cs_stream *s, uint8_t *hdr)
{
    if (s->win_count < CS_WIRE_HEADER_SIZE || s->win[s->win_pos] != 'C')
        return H_NONE;
    for (int i = 0; i < CS_WIRE_HEADER_SIZE; i++)
        hdr[i] = s->win[(s->win_pos + i) & 15];
    int kind = H_NONE;
    if (hdr[1] == CS_WIRE_TXN_MAGIC[1] && hdr[2] == CS_WIRE_TXN_MAGIC[2] &&
        hdr[3] == CS_WIRE_TXN_MAGIC[3])
        kind = H_TXN;
    else if (hdr[1] == CS_WIRE_SIGNED_MAGIC[1] && hdr[2] == CS_WIRE_SIGNED_MAGIC[2] &&
             hdr[3] == CS_WIRE_SIGNED_MAGIC[3])
        kind = H_SIGNED;
    else if (hdr[1] == CS_WIRE_STREAM_MAGIC[1] && hdr[2] == CS_WIRE_STREAM_MAGIC[2] &&
             hdr[3] == CS_WIRE_STREAM_MAGIC[3])
        kind = H_STREAM;
    if (kind == H_NONE || cs_crc32(0, hdr, 12) != cs__rd_u32(hdr + 12))
        return H_NONE;
    return kind;
}

static void end_body(cs_stream *s, uint64_t at);

/*
 * A signed envelope (docs/STREAM.md): the core does not verify signatures
 * (a board that must, verifies before its decoder; an MCU is fed by a trusted
 * host), it unwraps. The signature block is skipped, the inner transaction
 * that follows is found by its own header and decoded as any other, and the
 * envelope's trailer after it is skipped; so a signed stream gives the very
 * scene its unsigned original gives.
 */
static void start_envelope(cs_stream *s, const uint8_t *hdr, uint64_t at)
{
    uint32_t len = cs__rd_u32(hdr + 8);
    s->win_count = 0;
    s->in_garbage = false;
    s->skip_left = (uint64_t)len + CS_WIRE_TRAILER_SIZE;
    s->state = ST_SKIP;
    s->env_end = at + CS_WIRE_HEADER_SIZE + len;
    if (hdr[4] != CS_WIRE_MAJOR || len < CS_WIRE_SIGNED_MIN_BODY) {
        bool version = hdr[4] != CS_WIRE_MAJOR;
        emit(s, version ? CS_ERR_STREAM_VERSION : CS_ERR_STREAM_RECORD, at, at + (version ? 4 : 8),
             version ? "signed envelope of an unsupported major version: skipped"
                     : "signed envelope too short for a signature and a transaction: skipped",
             0);
        s->dropped++;
        return;
    }
    s->skip_left = CS_WIRE_SIG_BLOCK_SIZE;
}

/* A frame (or a skipped stretch) ended: hunt again, or skip the trailer of
 * the envelope it filled. */
static void frame_done(cs_stream *s)
{
    to_hunt(s);
    if (s->env_end != 0 && s->offset == s->env_end) {
        s->skip_left = CS_WIRE_TRAILER_SIZE;
        s->state = ST_SKIP;
    } else if (s->offset > s->env_end) {
        s->env_end = 0;
    }
}

static void start_txn(cs_stream *s, const uint8_t *hdr, uint64_t at)
{
    uint32_t len = cs__rd_u32(hdr + 8);
    s->txn_offset = at;
    s->win_count = 0;
    s->in_garbage = false;
    if (hdr[4] != CS_WIRE_MAJOR || len > CS_CFG_STREAM_MAX_TXN) {
        bool version = hdr[4] != CS_WIRE_MAJOR;
        emit(s, version ? CS_ERR_STREAM_VERSION : CS_ERR_STREAM_TOO_BIG, at, at + (version ? 4 : 8),
             version ? "transaction of an unsupported major version: skipped"
                     : "transaction longer than this decoder accepts: skipped",
             0);
        s->dropped++;
        /* The header's CRC matched, so its length can be skipped over; a
         * header met on the way still starts a new transaction. */
        s->skip_left = (uint64_t)len + CS_WIRE_TRAILER_SIZE;
        s->state = ST_SKIP;
        return;
    }
    s->crc = cs_crc32(0, hdr, CS_WIRE_HEADER_SIZE);
    s->body_len = len;
    s->body_pos = 0;
    s->trailer = 0;
    s->fill = 0;
    s->word = 0;
    s->parse = P_HDR;
    s->mode = M_NONE;
    s->seen_commit = s->txn_failed = false;
    s->rec_offset = at + CS_WIRE_HEADER_SIZE;
    s->state = ST_BODY;
    if (len == 0) /* no body: straight to the trailer (and "no COMMIT") */
        end_body(s, at + CS_WIRE_HEADER_SIZE);
}

/* --------------------------------------------------------------- records */

/* Prepares the back store for the first record that changes it. */
static bool prepare(cs_stream *s, uint32_t type)
{
    if (type == CS_REC_SCENE) {
        if (s->mode != M_NONE) {
            fail(s, CS_ERR_STREAM_RECORD, "SCENE must be the first record of its transaction", 0);
            return false;
        }
        s->mode = M_FULL; /* cs_scene_init runs when its fields are in */
        return true;
    }
    if (s->mode == M_NONE) {
        if (!s->has_scene) {
            fail(s, CS_ERR_STATE, "a patch needs a committed scene; the stream must start with SCENE",
                 0);
            return false;
        }
        cs_scene_copy(s->back, s->front);
        s->mode = M_PATCH;
    }
    return true;
}

/* Applies a record whose fields are all in (fixed part and floats) by its
 * row's function (cs_stream_apply.c). */
static void finish_record(cs_stream *s)
{
    cs_error where;
    cs__error(&where, CS_OK, -1, -1, -1, -1);
    const cs__rec_kind *k = &cs__rec_kinds[s->rec_kind];
    cs_status st = k->apply ? k->apply(s, &where) : CS_OK;
    if (st != CS_OK) {
        where.status = st;
        fail(s, st, cs_status_str(st), &where);
        return;
    }
    s->parse = P_HDR;
    s->fill = 0;
}

/* Error location of the last region, for faults found before its call. */
static void last_region_where(const cs_scene *sc, cs_error *where, cs_status st)
{
    int32_t cel = (int32_t)sc->cel_count - 1;
    int32_t region = cel >= 0 ? (int32_t)sc->cels[cel].region_count - 1 : -1;
    cs__error(where, st, cel, region, -1, -1);
}

/*
 * REGION_FUNC: the function is read straight into the slot that
 * cs_scene_set_region_func will use (the field's own slot if the region
 * already has one, else the next free one), so no record buffer is needed;
 * the call then checks it in place. Faults that would make the read unsafe
 * or that the call reports anyway are caught here, before any float.
 */
static bool begin_func(cs_stream *s)
{
    cs_scene *sc = s->back;
    const uint8_t *b = s->buf;
    uint32_t field = cs__rd_u32(b), kind = cs__rd_u32(b + 4), spread = cs__rd_u32(b + 8);
    uint32_t cols = cs__rd_u32(b + 12), stops = cs__rd_u32(b + 16);
    cs_error where;
    last_region_where(sc, &where, CS_ERR_FUNC);
    if (field > CS_FIELD_BETA) {
        fail(s, CS_ERR_FUNC, "paint function field is not pigment (0), medium (1) or beta (2)",
             &where);
        return false;
    }
    if (stops < 1 || stops > CS_CFG_MAX_STOPS) {
        fail(s, CS_ERR_FUNC, "paint function stop count is 0 or beyond the decoder's limit", &where);
        return false;
    }
    const cs_cel *c = sc->cel_count ? &sc->cels[sc->cel_count - 1] : 0;
    if (!c || c->region_count == 0 || c->first_region + c->region_count != sc->region_count) {
        where.status = CS_ERR_STATE;
        fail(s, CS_ERR_STATE, "a paint function needs a region of the last cel to belong to",
             &where);
        return false;
    }
    const cs_region *r = &sc->regions[sc->region_count - 1];
    uint32_t slot = r->func[field] ? r->func[field] - 1u : sc->func_count;
    if (slot >= CS_CFG_MAX_FUNCS) {
        where.status = CS_ERR_CAP_FUNCS;
        fail(s, CS_ERR_CAP_FUNCS, cs_status_str(CS_ERR_CAP_FUNCS), &where);
        return false;
    }
    cs_paint_func *f = &sc->funcs[slot];
    /* Values beyond a byte become ones the check refuses, never wrap to valid ones. */
    f->kind = (uint8_t)(kind <= 0xFFu ? kind : 0u);
    f->spread = (uint8_t)(spread <= 0xFFu ? spread : 0xFFu);
    f->map_cols = (uint8_t)(cols <= 0xFFu ? cols : 0u);
    f->stop_count = (uint8_t)stops;
    cs__rd_f32s(b + 20, f->geom, 6);
    s->base = slot;
    s->count = stops;
    return true;
}

/* CONTOUR (points into the free end of the store) or CONTOUR_POINTS (in
 * place): checks the counts and flags, and says where the floats go. */
static bool begin_points(cs_stream *s, bool in_place, uint64_t *floats)
{
    cs_scene *sc = s->back;
    const uint8_t *b = s->buf;
    uint32_t count = cs__rd_u32(b + 4), flags = cs__rd_u32(b + 8);
    if (flags & ~CS_WIRE_CONTOUR_INTERVALS) {
        fail(s, CS_ERR_STREAM_RECORD, "reserved flag bits set", 0);
        return false;
    }
    s->rec_flags = (uint8_t)flags;
    if (!in_place) {
        /* Points are read into the free end of the store. */
        if (count > UINT16_MAX || count > CS_CFG_MAX_POINTS - sc->point_count) {
            cs_error where;
            cs__error(&where, CS_ERR_CAP_POINTS, (int32_t)sc->cel_count - 1, -1, -1, -1);
            fail(s, CS_ERR_CAP_POINTS, cs_status_str(CS_ERR_CAP_POINTS), &where);
            return false;
        }
        s->base = sc->point_count;
    } else {
        /* Points are read in place: the count must be the contour's. */
        uint32_t contour = cs__rd_u32(b);
        if (contour >= sc->contour_count) {
            fail(s, CS_ERR_INDEX, "no such contour", 0);
            return false;
        }
        if (count != sc->contours[contour].point_count) {
            fail(s, CS_ERR_COUNT, cs_status_str(CS_ERR_COUNT), 0);
            return false;
        }
        s->base = sc->contours[contour].first_point;
    }
    s->count = count;
    *floats = (uint64_t)count * ((flags & CS_WIRE_CONTOUR_INTERVALS) ? 4u : 3u);
    return true;
}

/* TRACK: opens the track, checks its keys fit, and counts their floats. */
static bool begin_track(cs_stream *s, uint64_t *floats)
{
    cs_scene *sc = s->back;
    const uint8_t *b = s->buf;
    uint32_t kind = cs__rd_u32(b), target = cs__rd_u32(b + 4), ease = cs__rd_u32(b + 8);
    uint32_t keys = cs__rd_u32(b + 12);
    if (kind >= CS_TRACK_KIND_COUNT_ || ease >= CS_EASE_COUNT_) {
        fail(s, CS_ERR_TRACK, cs_status_str(CS_ERR_TRACK), 0);
        return false;
    }
    if (keys == 0) {
        fail(s, CS_ERR_STREAM_RECORD, "a track needs at least one key", 0);
        return false;
    }
    cs_error where;
    cs_status st = cs_scene_add_track(sc, (cs_track_kind)kind, target, (cs_ease)ease, &where);
    if (st != CS_OK) {
        fail(s, st, cs_status_str(st), &where);
        return false;
    }
    s->width = sc->tracks[sc->open_track].width;
    /* Key values are read into the free end of the pool, one key at a time. */
    if (keys > CS_CFG_MAX_KEYS - sc->key_count ||
        (uint64_t)keys * s->width > CS_CFG_MAX_KEY_VALUES - sc->value_count) {
        fail(s, CS_ERR_CAP_KEYS, cs_status_str(CS_ERR_CAP_KEYS), 0);
        return false;
    }
    s->slot = 0;
    *floats = (uint64_t)keys * (1u + s->width);
    return true;
}

/*
 * The fixed part is in: checks it, works out how many floats follow and
 * where they go, and checks the record length against that.
 */
static void begin_floats(cs_stream *s)
{
    cs_scene *sc = s->back;
    const uint8_t *b = s->buf;
    uint64_t floats = 0;
    uint8_t layout = cs__rec_kinds[s->rec_kind].layout;
    s->rec_flags = 0;
    switch (layout) {
    case L_FLAGS_AT0:
    case L_FLAGS_AT4: {
        uint32_t flags = cs__rd_u32(layout == L_FLAGS_AT0 ? b : b + 4);
        if (flags & ~CS_WIRE_CEL_HAS_FRONT) {
            fail(s, CS_ERR_STREAM_RECORD, "reserved flag bits set", 0);
            return;
        }
        s->rec_flags = (uint8_t)flags;
        break;
    }
    case L_POINTS_NEW:
    case L_POINTS_AT:
        if (!begin_points(s, layout == L_POINTS_AT, &floats))
            return;
        break;
    case L_KEYS:
        if (!begin_track(s, &floats))
            return;
        break;
    case L_STOPS:
        if (!begin_func(s))
            return;
        floats = 4u * (uint64_t)s->count;
        break;
    case L_TOKENS:
        s->count = cs__rd_u32(b);
        if (s->count < 1 || s->count > CS_CFG_MAX_CSG) {
            cs_error where;
            last_region_where(sc, &where, CS_ERR_CSG);
            fail(s, CS_ERR_CSG, "CSG program length is 0 or beyond the decoder's limit", &where);
            return;
        }
        floats = s->count;
        break;
    default:
        break;
    }
    if ((uint64_t)s->fixed_len + 4u * floats != s->rec_len) {
        fail(s, CS_ERR_STREAM_RECORD, "record length does not match its fields and counts", 0);
        return;
    }
    s->float_count = (uint32_t)floats;
    s->float_index = 0;
    s->fill = 0;
    if (floats == 0)
        finish_record(s);
    else
        s->parse = P_FLOATS;
}

/* Stores the next word of a record's counted part where it belongs. */
static void put_word(cs_stream *s, uint32_t w)
{
    cs_scene *sc = s->back;
    uint32_t i = s->float_index;
    float v = cs__word_f32(w);
    switch (cs__rec_kinds[s->rec_kind].layout) {
    case L_POINTS_NEW:
    case L_POINTS_AT:
        if (i < 3u * s->count) {
            cs_point *p = &sc->points[s->base + i / 3u];
            if (i % 3u == 0)
                p->x = v;
            else if (i % 3u == 1)
                p->y = v;
            else
                p->w = v;
        } else {
            sc->intervals[s->base + (i - 3u * s->count)] = v;
        }
        break;
    case L_KEYS:
        if (s->slot == 0) {
            s->key_time = v;
        } else {
            sc->key_values[sc->value_count + s->slot - 1u] = v;
        }
        if (s->slot++ == s->width) {
            cs_error where;
            s->slot = 0;
            cs_status st = cs_scene_add_key(sc, s->key_time, &sc->key_values[sc->value_count],
                                            &where);
            if (st != CS_OK)
                fail(s, st, cs_status_str(st), &where);
        }
        break;
    case L_STOPS: {
        cs_stop *stop = &sc->funcs[s->base].stops[i / 4u];
        if (i % 4u == 0)
            stop->offset = v;
        else
            stop->value[i % 4u - 1u] = v;
        break;
    }
    case L_TOKENS: {
        /* Operand n as n, operator k (-k on the wire, an i32) as 0x80|k, as
         * the store keeps them; anything else as 0xFF, which the check
         * refuses with this token's index. */
        int32_t t = (int32_t)w;
        uint8_t code = 0xFFu;
        if (t >= 0 && t <= CS_CFG_MAX_OPERANDS)
            code = (uint8_t)t;
        else if (t < 0 && t >= -4)
            code = (uint8_t)(0x80u | (uint32_t)-t);
        s->buf[4 + i] = code;
        break;
    }
    default:
        break;
    }
}

/* A record header is in: decide how its payload is read. */
static void begin_record(cs_stream *s)
{
    uint32_t type = (uint32_t)s->buf[0] | (uint32_t)s->buf[1] << 8;
    uint32_t len = cs__rd_u32(s->buf + 2);
    s->rec_len = len;
    s->rec_pos = 0;
    s->fill = 0;
    if (s->seen_commit) {
        fail(s, CS_ERR_STREAM_RECORD, "a record follows the COMMIT record", 0);
        return;
    }
    if (len > s->body_len - s->body_pos) {
        fail(s, CS_ERR_STREAM_RECORD, "record longer than the rest of its transaction", 0);
        return;
    }
    if ((type >> 8) >= CS_WIRE_CLASS_COUNT) {
        fail(s, CS_ERR_STREAM_RECORD, "record of an unknown class", 0);
        return;
    }
    int kind = cs__rec_kind_find(type);
    if (kind < 0) {
        /* PAD, or a newer type of a known class: skippable by definition. */
        s->parse = len ? P_SKIP : P_HDR;
        return;
    }
    s->rec_kind = (uint8_t)kind;
    if (!prepare(s, type))
        return;
    uint32_t fixed = cs__rec_kinds[kind].fixed;
    if (fixed > len) {
        fail(s, CS_ERR_STREAM_RECORD, "record shorter than its fields", 0);
        return;
    }
    s->fixed_len = fixed;
    if (fixed == 0)
        begin_floats(s);
    else
        s->parse = P_FIXED;
}

static void parse_byte(cs_stream *s, uint8_t b, uint64_t at)
{
    switch (s->parse) {
    case P_HDR:
        if (s->fill == 0)
            s->rec_offset = at;
        s->buf[s->fill++] = b;
        if (s->fill == CS_WIRE_RECORD_HEADER_SIZE)
            begin_record(s);
        break;
    case P_FIXED:
        s->buf[s->fill++] = b;
        if (s->fill == s->fixed_len)
            begin_floats(s);
        break;
    case P_FLOATS:
        s->word |= (uint32_t)b << (8u * s->fill);
        if (++s->fill == 4) {
            uint32_t w = s->word;
            s->word = 0;
            s->fill = 0;
            put_word(s, w);
            if (s->parse == P_FLOATS && ++s->float_index == s->float_count)
                finish_record(s);
        }
        break;
    case P_SKIP:
        if (++s->rec_pos == s->rec_len) {
            s->parse = P_HDR;
            s->fill = 0;
        }
        break;
    default:
        break;
    }
}

/* ------------------------------------------------------------ transactions */

static void end_body(cs_stream *s, uint64_t at)
{
    if (s->parse != P_DEAD) {
        if (s->parse != P_HDR || s->fill != 0) {
            fail(s, CS_ERR_STREAM_RECORD, "transaction ends inside a record", 0);
        } else if (!s->seen_commit) {
            s->rec_offset = at;
            fail(s, CS_ERR_STREAM_RECORD, "transaction has no COMMIT record", 0);
        }
    }
    s->state = ST_TRAILER;
    s->fill = 0;
    s->trailer = 0;
}

static void end_txn(cs_stream *s, uint64_t trailer_at)
{
    if (s->trailer != s->crc) {
        emit(s, CS_ERR_STREAM_CRC, s->txn_offset, trailer_at,
             "CRC mismatch: transaction damaged, dropped", 0);
        s->dropped++;
    } else if (s->txn_failed) {
        emit(s, s->txn_err.status, s->txn_err.offset, s->txn_err.at, s->txn_err.what,
             &s->txn_err.where);
        s->dropped++;
    } else {
        s->commit_ready = true;
        s->commits++;
    }
    frame_done(s);
}

static void step(cs_stream *s, uint8_t b)
{
    uint64_t at = s->offset++;
    s->win[s->win_pos] = b;
    s->win_pos = (uint8_t)((s->win_pos + 1) & 15);
    if (s->win_count < CS_WIRE_HEADER_SIZE)
        s->win_count++;
    uint8_t hdr[CS_WIRE_HEADER_SIZE];
    int h = ring_header(s, hdr);
    uint64_t hdr_at = at + 1 - CS_WIRE_HEADER_SIZE;
    /* Inside an envelope being skipped (a refused one, its signature block),
     * the inner transaction's header is part of what is skipped. */
    if (h == H_TXN && !(s->state == ST_SKIP && hdr_at < s->env_end)) {
        if (s->state == ST_BODY || s->state == ST_TRAILER) {
            emit(s, CS_ERR_STREAM_TRUNCATED, s->txn_offset, hdr_at,
                 "transaction cut short by the next transaction header", 0);
            s->dropped++;
        }
        start_txn(s, hdr, hdr_at);
        return;
    }
    if (h == H_SIGNED) {
        if (s->state == ST_BODY || s->state == ST_TRAILER) {
            emit(s, CS_ERR_STREAM_TRUNCATED, s->txn_offset, hdr_at,
                 "transaction cut short by the next signed envelope", 0);
            s->dropped++;
        }
        start_envelope(s, hdr, hdr_at);
        return;
    }
    if (h == H_STREAM && s->state == ST_HUNT) {
        if (hdr[4] != CS_WIRE_MAJOR)
            emit(s, CS_ERR_STREAM_VERSION, hdr_at, hdr_at + 4,
                 "stream of an unsupported major version", 0);
        to_hunt(s);
        return;
    }
    switch (s->state) {
    case ST_HUNT:
        /* The oldest byte of a full ring can no longer start a header. */
        if (s->win_count == CS_WIRE_HEADER_SIZE) {
            if (!s->in_garbage) {
                s->in_garbage = true;
                s->garbage_offset = hdr_at;
                emit(s, CS_ERR_STREAM_SYNC, hdr_at, hdr_at,
                     "bytes outside any transaction: skipping to the next header", 0);
            }
            s->skipped++;
        }
        break;
    case ST_BODY:
        s->crc = cs_crc32(s->crc, &b, 1);
        s->body_pos++;
        parse_byte(s, b, at);
        if (s->body_pos == s->body_len)
            end_body(s, at + 1);
        break;
    case ST_TRAILER:
        s->trailer |= (uint32_t)b << (8u * s->fill);
        if (++s->fill == CS_WIRE_TRAILER_SIZE)
            end_txn(s, at + 1 - CS_WIRE_TRAILER_SIZE);
        break;
    default: /* ST_SKIP */
        if (--s->skip_left == 0)
            frame_done(s);
        break;
    }
}

static cs_stream_event pop(cs_stream *s)
{
    copy_error(&s->last, &s->queue[0]);
    if (s->queued > 1)
        copy_error(&s->queue[0], &s->queue[1]);
    s->queued--;
    return CS_STREAM_ERROR;
}

cs_stream_event cs_stream_feed(cs_stream *s, const uint8_t *data, size_t len, size_t *used)
{
    size_t i = 0;
    cs_stream_event ev = CS_STREAM_MORE;
    if (!s) {
        if (used)
            *used = 0;
        return CS_STREAM_MORE;
    }
    if (!data)
        len = 0;
    if (s->queued) {
        ev = pop(s);
    } else if (s->commit_ready) {
        ev = CS_STREAM_COMMIT;
    } else {
        while (i < len) {
            step(s, data[i++]);
            if (s->queued) {
                ev = pop(s);
                break;
            }
            if (s->commit_ready) {
                ev = CS_STREAM_COMMIT;
                break;
            }
        }
    }
    if (used)
        *used = i;
    return ev;
}

cs_stream_event cs_stream_finish(cs_stream *s)
{
    if (!s)
        return CS_STREAM_MORE;
    if (!s->queued && !s->commit_ready) {
        if (s->state == ST_BODY || s->state == ST_TRAILER) {
            emit(s, CS_ERR_STREAM_TRUNCATED, s->txn_offset, s->offset,
                 "input ended inside a transaction", 0);
            s->dropped++;
        } else if (s->state == ST_HUNT && s->win_count > 0) {
            s->skipped += s->win_count;
            if (!s->in_garbage)
                emit(s, CS_ERR_STREAM_SYNC, s->offset - s->win_count, s->offset - s->win_count,
                     "input ended with bytes that are no transaction", 0);
        }
        to_hunt(s);
    }
    size_t used;
    return cs_stream_feed(s, 0, 0, &used);
}

cs_stream_event cs_stream_gap(cs_stream *s)
{
    if (!s)
        return CS_STREAM_MORE;
    if (!s->queued && !s->commit_ready) {
        if (s->state == ST_BODY || s->state == ST_TRAILER) {
            emit(s, CS_ERR_STREAM_GAP, s->txn_offset, s->offset,
                 "bytes lost on the link inside a transaction", 0);
            s->dropped++;
        }
        /* A skipped stretch's length and an envelope's end count bytes
         * that may be among the lost ones: trust neither. */
        s->env_end = 0;
        to_hunt(s);
    }
    size_t used;
    return cs_stream_feed(s, 0, 0, &used);
}

cs_status cs_stream_swap(cs_stream *s)
{
    if (!s || !s->commit_ready)
        return CS_ERR_STATE;
    cs_scene *t = s->front;
    s->front = s->back;
    s->back = t;
    s->has_scene = true;
    s->commit_ready = false;
    return CS_OK;
}

cs_status cs_stream_refuse(cs_stream *s, cs_status status, const char *what, const cs_error *where)
{
    if (!s || !s->commit_ready)
        return CS_ERR_STATE;
    s->commit_ready = false;
    s->commits--;
    s->dropped++;
    s->last.status = status;
    s->last.offset = s->txn_offset;
    s->last.at = s->offset;
    s->last.what = what ? what : "refused";
    if (where)
        s->last.where = *where;
    else
        cs__error(&s->last.where, CS_OK, -1, -1, -1, -1);
    return CS_OK;
}

bool cs_stream_busy(const cs_stream *s)
{
    return s && (s->state == ST_BODY || s->state == ST_TRAILER || s->commit_ready);
}

const cs_scene *cs_stream_scene(const cs_stream *s)
{
    return s && s->has_scene ? s->front : 0;
}

const cs_stream_error *cs_stream_last_error(const cs_stream *s)
{
    return s ? &s->last : 0;
}
