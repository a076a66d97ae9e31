/*
 * cs_wire.h - constants of the cel stream wire format (docs/STREAM.md).
 *
 * Shared by the core's decoder (cs_stream.c) and host encoders
 * (tools/cels_write.c), so the two can only disagree about what a record
 * means, never about its number. Everything on the wire is little-endian;
 * floats are IEEE-754 binary32.
 */
#ifndef CS_WIRE_H
#define CS_WIRE_H

/* Format version written by this code; decoders accept any minor of their major. */
#define CS_WIRE_MAJOR 1
#define CS_WIRE_MINOR 4

/* 16-byte headers: magic(4) major(1) minor(1) flags(2) word(4) crc32(4). */
#define CS_WIRE_HEADER_SIZE 16
#define CS_WIRE_STREAM_MAGIC "CELS" /* word: reserved, 0 */
#define CS_WIRE_TXN_MAGIC "CSTX"    /* word: body length in bytes */
#define CS_WIRE_TRAILER_SIZE 4      /* CRC-32 of header and body */
/* A signed envelope is framed as a transaction: its body is the signature
 * block (key id, sequence, signature) and then one whole inner transaction.
 * The core only unwraps it; verifying is the Linux board's job (celfw). */
#define CS_WIRE_SIGNED_MAGIC "CSSG"  /* word: body length in bytes */
#define CS_WIRE_SIG_KEYID_SIZE 8
#define CS_WIRE_SIG_SIZE 64         /* Ed25519 */
#define CS_WIRE_SIG_BLOCK_SIZE (CS_WIRE_SIG_KEYID_SIZE + 8 + CS_WIRE_SIG_SIZE) /* + u64 sequence */
/* The smallest envelope body: the block and an inner transaction with no body. */
#define CS_WIRE_SIGNED_MIN_BODY (CS_WIRE_SIG_BLOCK_SIZE + CS_WIRE_HEADER_SIZE + CS_WIRE_TRAILER_SIZE)

/* Record header: type u16 (class << 8 | subtype), payload length u32. */
#define CS_WIRE_RECORD_HEADER_SIZE 6
#define CS_WIRE_CLASS_COUNT 7 /* classes 0..6 known to version 1.4 (1.1-1.3: 0..5, 1.0: 0..4) */

/* Class 0: control */
#define CS_REC_PAD 0x0000u    /* any payload, ignored */
#define CS_REC_COMMIT 0x0001u /* empty; the last record of every transaction */
/* Class 1: scene-wide values */
#define CS_REC_SCENE 0x0100u         /* f32 canvas w, h: start a new scene (first record) */
#define CS_REC_CANVAS 0x0101u        /* f32 canvas w, h */
#define CS_REC_LIGHTS 0x0102u        /* f32 front[3], back[3]: stack lights */
#define CS_REC_BACKGROUND 0x0103u    /* f32 rgb[3], linear */
#define CS_REC_NO_BACKGROUND 0x0104u /* empty */
#define CS_REC_BLEND 0x0105u         /* u32 blend: 0 linear light, 1 sRGB (since 1.2) */
#define CS_REC_EPOCH 0x0106u         /* u32 lo, hi: ns since 1970 UTC of animation time 0 (since 1.3) */
/* Class 2: structure */
#define CS_REC_CEL 0x0200u        /* u32 flags, f32 transform[6], front[3], back[3] */
#define CS_REC_REGION 0x0201u     /* u32 fill rule, f32 pigment[3], medium[3], beta */
#define CS_REC_CONTOUR 0x0202u    /* u32 degree, count, flags; f32 (x,y,w)*count [, interval*count] */
#define CS_REC_CEL_REMOVE 0x0203u /* u32 cel */
#define CS_REC_CEL_MOVE 0x0204u   /* u32 from, to */
/* Class 3: values of existing items */
#define CS_REC_CEL_TRANSFORM 0x0300u  /* u32 cel, f32 transform[6] */
#define CS_REC_CEL_LIGHTS 0x0301u     /* u32 cel, flags, f32 front[3], back[3] */
#define CS_REC_REGION_PAINT 0x0302u   /* u32 region, fill rule, f32 pigment[3], medium[3], beta */
#define CS_REC_CONTOUR_POINTS 0x0303u /* u32 contour, count, flags; floats as CONTOUR */
/* Class 4: animation */
#define CS_REC_TRACK 0x0400u        /* u32 kind, target, ease, keys; f32 (time, value*width)*keys */
#define CS_REC_TRACK_REMOVE 0x0401u /* u32 kind, target */
/* Class 5 (1.1): what a region is made of beyond its constant paint. A new
 * class, not new subtypes of class 2, so that a 1.0 decoder refuses these
 * transactions instead of skipping the records and showing another picture. */
#define CS_REC_REGION_FUNC 0x0500u      /* u32 field, kind, spread, map_cols, stops; f32 geom[6];
                                           f32 (offset, value[3])*stops: last region */
#define CS_REC_REGION_CSG 0x0501u       /* u32 len; i32 token*len: last region */
#define CS_REC_CONTOUR_OPERAND 0x0502u  /* u32 operand: last contour */
/* Class 6 (1.4): cel groups; a new class for the same reason as class 5. */
#define CS_REC_CEL_PARENT 0x0600u       /* u32 cel, parent (0xFFFFFFFF: none) */

/* Flag bits; every other bit is reserved and must be 0. */
#define CS_WIRE_CEL_HAS_FRONT 1u       /* CEL, CEL_LIGHTS: front light given (else the stack's) */
#define CS_WIRE_CONTOUR_INTERVALS 1u   /* CONTOUR, CONTOUR_POINTS: knot intervals follow */

#endif /* CS_WIRE_H */
