/* SPDX-License-Identifier: MIT */
/* Image files (np_image.h): OpenEXR through OpenEXRCore, PNG through libpng. */
#include "np_image.h"
#include "np_outfile.h"

#include <errno.h>
#include <openexr.h>
#include <png.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* --- OpenEXR --- */

static int exr_fail(char *err, size_t errlen, const char *path, const char *what, exr_result_t rc)
{
    snprintf(err, errlen, "%s: %s: %s", path, what, exr_get_default_error_message(rc));
    return -1;
}

/*
 * The EXR is assembled in memory (the library writes the chunk offset table
 * last, at an earlier offset, so it needs random access) and then written in
 * one pass through np_outfile: atomic for a regular file, streamed to a FIFO
 * or device, through a symbolic link to its target.
 */
typedef struct exr_mem exr_mem;
static int exr_encode_mem(const char *path, exr_mem *mem, unsigned w, unsigned h, unsigned nch,
                          const char *const *names, const float *planes, const np_image_meta *meta, char *err,
                          size_t errlen);

struct exr_mem {
    uint8_t *buf;
    size_t len, cap;
    int oom;
};

static int64_t exr_mem_write(exr_const_context_t ctxt, void *userdata, const void *buffer, uint64_t sz,
                             uint64_t offset, exr_stream_error_func_ptr_t error_cb)
{
    exr_mem *m = userdata;
    if (offset > SIZE_MAX - sz) {
        m->oom = 1;
        return error_cb(ctxt, EXR_ERR_OUT_OF_MEMORY, "image too large"), -1;
    }
    size_t end = (size_t)(offset + sz);
    if (end > m->cap) {
        size_t cap = m->cap ? m->cap : (size_t)1 << 16;
        while (cap < end)
            cap *= 2;
        uint8_t *nb = realloc(m->buf, cap);
        if (!nb) {
            m->oom = 1;
            return error_cb(ctxt, EXR_ERR_OUT_OF_MEMORY, "out of memory"), -1;
        }
        memset(nb + m->cap, 0, cap - m->cap);
        m->buf = nb;
        m->cap = cap;
    }
    memcpy(m->buf + offset, buffer, (size_t)sz);
    if (end > m->len)
        m->len = end;
    return (int64_t)sz;
}

/* The library's own messages would precede ours on stderr; exr_fail says it once, naming the file. */
static void exr_quiet(exr_const_context_t ctxt, exr_result_t code, const char *msg)
{
    (void)ctxt;
    (void)code;
    (void)msg;
}

void np_image_meta_add(np_image_meta *m, const char *key, const char *value)
{
    if (m->n_text < NP_IMAGE_MAX_TEXT) {
        m->key[m->n_text] = key;
        m->value[m->n_text] = value;
        m->n_text++;
    }
}

int np_image_write_exr(const char *path, unsigned w, unsigned h, unsigned nch,
                       const char *const *names, const float *planes, char *err, size_t errlen)
{
    return np_image_write_exr_meta(path, w, h, nch, names, planes, NULL, err, errlen);
}

int np_image_write_exr_meta(const char *path, unsigned w, unsigned h, unsigned nch, const char *const *names,
                            const float *planes, const np_image_meta *meta, char *err, size_t errlen)
{
    exr_mem mem = { NULL, 0, 0, 0 };
    int ret = exr_encode_mem(path, &mem, w, h, nch, names, planes, meta, err, errlen);
    if (ret == 0) {
        np_outfile o;
        if (np_outfile_open(&o, path, "wb") != 0) {
            snprintf(err, errlen, "%s", o.err);
            ret = -1;
        } else {
            fwrite(mem.buf, 1, mem.len, o.f);
            if (np_outfile_close(&o, 1) != 0) {
                snprintf(err, errlen, "%s", o.err);
                ret = -1;
            }
        }
    }
    free(mem.buf);
    return ret;
}

/* Rec. 709 primaries and D65 white (ITU-R BT.709-6 table 1; the primaries of sRGB). */
static const exr_attr_chromaticities_t rec709_d65 = { 0.64f, 0.33f, 0.30f, 0.60f, 0.15f, 0.06f, 0.3127f, 0.3290f };

static int exr_encode_mem(const char *path, exr_mem *mem, unsigned w, unsigned h, unsigned nch,
                          const char *const *names, const float *planes, const np_image_meta *meta, char *err,
                          size_t errlen)
{
    exr_context_t ctx = NULL;
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.user_data = mem;
    init.write_fn = exr_mem_write;
    init.error_handler_fn = exr_quiet;
    exr_result_t rc;
    int part = 0;
    if (nch < 1 || nch > NP_IMAGE_MAX_CHANNELS || w < 1 || h < 1) {
        snprintf(err, errlen, "%s: bad image shape", path);
        return -1;
    }
    rc = exr_start_write(&ctx, path, EXR_WRITE_FILE_DIRECTLY, &init);
    if (rc != EXR_ERR_SUCCESS)
        return exr_fail(err, errlen, path, "cannot start writing", rc);
    rc = exr_add_part(ctx, "image", EXR_STORAGE_SCANLINE, &part);
    if (rc == EXR_ERR_SUCCESS)
        rc = exr_initialize_required_attr_simple(ctx, part, (int32_t)w, (int32_t)h, EXR_COMPRESSION_ZIP);
    for (unsigned c = 0; c < nch && rc == EXR_ERR_SUCCESS; c++)
        rc = exr_add_channel(ctx, part, names[c], EXR_PIXEL_FLOAT, EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1);
    if (meta && meta->rec709 && rc == EXR_ERR_SUCCESS)
        rc = exr_attr_set_chromaticities(ctx, part, "chromaticities", &rec709_d65);
    for (unsigned t = 0; meta && t < meta->n_text && rc == EXR_ERR_SUCCESS; t++)
        rc = exr_attr_set_string(ctx, part, meta->key[t], meta->value[t]);
    if (rc == EXR_ERR_SUCCESS)
        rc = exr_write_header(ctx);
    if (rc != EXR_ERR_SUCCESS) {
        exr_finish(&ctx);
        return exr_fail(err, errlen, path, "cannot write the header", rc);
    }
    int32_t lpc = 1;
    rc = exr_get_scanlines_per_chunk(ctx, part, &lpc);
    exr_encode_pipeline_t enc = EXR_ENCODE_PIPELINE_INITIALIZER;
    int first = 1;
    for (unsigned y = 0; rc == EXR_ERR_SUCCESS && y < h; y += (unsigned)lpc) {
        exr_chunk_info_t ci;
        rc = exr_write_scanline_chunk_info(ctx, part, (int)y, &ci);
        if (rc != EXR_ERR_SUCCESS)
            break;
        rc = first ? exr_encoding_initialize(ctx, part, &ci, &enc) : exr_encoding_update(ctx, part, &ci, &enc);
        if (rc != EXR_ERR_SUCCESS)
            break;
        /* The library sorts channels by name: map each by its name, never by index. */
        for (int c = 0; c < enc.channel_count; c++) {
            exr_coding_channel_info_t *ch = &enc.channels[c];
            unsigned k = 0;
            while (k < nch && strcmp(names[k], ch->channel_name) != 0)
                k++;
            const float *plane = planes + (size_t)k * w * h;
            ch->encode_from_ptr = (const uint8_t *)(plane + (size_t)ci.start_y * w);
            ch->user_pixel_stride = (int32_t)sizeof(float);
            ch->user_line_stride = (int32_t)(sizeof(float) * w);
            ch->user_bytes_per_element = (int16_t)sizeof(float);
            ch->user_data_type = EXR_PIXEL_FLOAT;
        }
        if (first)
            rc = exr_encoding_choose_default_routines(ctx, part, &enc);
        first = 0;
        if (rc == EXR_ERR_SUCCESS)
            rc = exr_encoding_run(ctx, part, &enc);
    }
    if (!first)
        exr_encoding_destroy(ctx, &enc);
    exr_result_t fin = exr_finish(&ctx);
    if (rc != EXR_ERR_SUCCESS)
        return exr_fail(err, errlen, path, "cannot write the pixels", rc);
    if (fin != EXR_ERR_SUCCESS)
        return exr_fail(err, errlen, path, "cannot finish the file", fin);
    return 0;
}

int np_image_read_exr(const char *path, unsigned *w, unsigned *h, unsigned *nch,
                      char names[NP_IMAGE_MAX_CHANNELS][NP_IMAGE_NAME], float **planes, char *err,
                      size_t errlen)
{
    exr_context_t ctx = NULL;
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    exr_result_t rc = exr_start_read(&ctx, path, &init);
    *planes = NULL;
    if (rc != EXR_ERR_SUCCESS)
        return exr_fail(err, errlen, path, "cannot read", rc);
    exr_attr_box2i_t dw;
    const exr_attr_chlist_t *cl = NULL;
    exr_storage_t st;
    rc = exr_get_storage(ctx, 0, &st);
    if (rc == EXR_ERR_SUCCESS)
        rc = exr_get_data_window(ctx, 0, &dw);
    if (rc == EXR_ERR_SUCCESS)
        rc = exr_get_channels(ctx, 0, &cl);
    if (rc != EXR_ERR_SUCCESS) {
        exr_finish(&ctx);
        return exr_fail(err, errlen, path, "bad header", rc);
    }
    if (st != EXR_STORAGE_SCANLINE || dw.min.x != 0 || dw.min.y != 0 || cl->num_channels < 1 ||
        cl->num_channels > NP_IMAGE_MAX_CHANNELS) {
        exr_finish(&ctx);
        snprintf(err, errlen, "%s: not a scanline image with 1..%d channels at (0, 0)", path, NP_IMAGE_MAX_CHANNELS);
        return -1;
    }
    *w = (unsigned)(dw.max.x + 1);
    *h = (unsigned)(dw.max.y + 1);
    *nch = (unsigned)cl->num_channels;
    for (int c = 0; c < cl->num_channels; c++) {
        snprintf(names[c], NP_IMAGE_NAME, "%s", cl->entries[c].name.str);
        if (cl->entries[c].pixel_type != EXR_PIXEL_FLOAT) {
            exr_finish(&ctx);
            snprintf(err, errlen, "%s: channel %s is not FLOAT", path, names[c]);
            return -1;
        }
    }
    float *pl = malloc(sizeof(float) * (size_t)*nch * *w * *h);
    if (!pl) {
        exr_finish(&ctx);
        snprintf(err, errlen, "%s: out of memory", path);
        return -1;
    }
    int32_t lpc = 1;
    rc = exr_get_scanlines_per_chunk(ctx, 0, &lpc);
    exr_decode_pipeline_t dec = EXR_DECODE_PIPELINE_INITIALIZER;
    int first = 1;
    for (unsigned y = 0; rc == EXR_ERR_SUCCESS && y < *h; y += (unsigned)lpc) {
        exr_chunk_info_t ci;
        rc = exr_read_scanline_chunk_info(ctx, 0, (int)y, &ci);
        if (rc != EXR_ERR_SUCCESS)
            break;
        rc = first ? exr_decoding_initialize(ctx, 0, &ci, &dec) : exr_decoding_update(ctx, 0, &ci, &dec);
        if (rc != EXR_ERR_SUCCESS)
            break;
        /* Planar buffers, mapped by name; the last chunk is partial (ci.height). */
        for (int c = 0; c < dec.channel_count; c++) {
            exr_coding_channel_info_t *ch = &dec.channels[c];
            unsigned k = 0;
            while (k < *nch && strcmp(names[k], ch->channel_name) != 0)
                k++;
            ch->decode_to_ptr = (uint8_t *)(pl + (size_t)k * *w * *h + (size_t)ci.start_y * *w);
            ch->user_pixel_stride = (int32_t)sizeof(float);
            ch->user_line_stride = (int32_t)(sizeof(float) * *w);
            ch->user_bytes_per_element = (int16_t)sizeof(float);
            ch->user_data_type = EXR_PIXEL_FLOAT;
        }
        if (first)
            rc = exr_decoding_choose_default_routines(ctx, 0, &dec);
        first = 0;
        if (rc == EXR_ERR_SUCCESS)
            rc = exr_decoding_run(ctx, 0, &dec);
    }
    if (!first)
        exr_decoding_destroy(ctx, &dec);
    exr_finish(&ctx);
    if (rc != EXR_ERR_SUCCESS) {
        free(pl);
        return exr_fail(err, errlen, path, "cannot read the pixels", rc);
    }
    *planes = pl;
    return 0;
}

/* --- PNG --- */

typedef struct png_err_ctx {
    char *err;
    size_t errlen;
    const char *path;
} png_err_ctx;

static void png_error_fn(png_structp png, png_const_charp msg)
{
    png_err_ctx *e = png_get_error_ptr(png);
    snprintf(e->err, e->errlen, "%s: libpng: %s", e->path, msg);
    png_longjmp(png, 1);
}

static void png_warn_fn(png_structp png, png_const_charp msg)
{
    (void)png;
    (void)msg;
}

/* Write to path through np_outfile (atomic for a regular file, streamed to a FIFO or device). */
int np_image_write_png(const char *path, unsigned w, unsigned h, const uint8_t *rgb, char *err,
                       size_t errlen)
{
    return np_image_write_png_meta(path, w, h, rgb, NULL, err, errlen);
}

int np_image_write_png_meta(const char *path, unsigned w, unsigned h, const uint8_t *rgb, const np_image_meta *meta,
                            char *err, size_t errlen)
{
    np_outfile o;
    if (np_outfile_open(&o, path, "wb") != 0) {
        snprintf(err, errlen, "%s", o.err);
        return -1;
    }
    png_err_ctx ec = { err, errlen, path };
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &ec, png_error_fn, png_warn_fn);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    if (!png || !info) {
        png_destroy_write_struct(&png, NULL);
        np_outfile_close(&o, 0);
        snprintf(err, errlen, "%s: out of memory", path);
        return -1;
    }
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        np_outfile_close(&o, 0);
        return -1;
    }
    png_init_io(png, o.f);
    png_set_IHDR(png, info, w, h, 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
                 PNG_FILTER_TYPE_DEFAULT);
    png_text text[NP_IMAGE_MAX_TEXT];
    unsigned nt = meta ? meta->n_text : 0;
    for (unsigned t = 0; t < nt; t++) {
        memset(&text[t], 0, sizeof text[t]);
        text[t].compression = PNG_TEXT_COMPRESSION_NONE;
        text[t].key = (png_charp)(uintptr_t)meta->key[t]; /* libpng copies; it does not write through them */
        text[t].text = (png_charp)(uintptr_t)meta->value[t];
        text[t].text_length = strlen(meta->value[t]);
    }
    if (nt)
        png_set_text(png, info, text, (int)nt);
    png_write_info(png, info);
    for (unsigned y = 0; y < h; y++)
        png_write_row(png, rgb + (size_t)y * w * 3u);
    png_write_end(png, info);
    png_destroy_write_struct(&png, &info);
    if (np_outfile_close(&o, 1) != 0) {
        snprintf(err, errlen, "%s", o.err);
        return -1;
    }
    return 0;
}

int np_image_write_ppm(const char *path, unsigned w, unsigned h, const uint8_t *rgb, char *err,
                       size_t errlen)
{
    np_outfile o;
    if (np_outfile_open(&o, path, "wb") != 0) {
        snprintf(err, errlen, "%s", o.err);
        return -1;
    }
    fprintf(o.f, "P6\n%u %u\n255\n", w, h);
    fwrite(rgb, 1, (size_t)w * h * 3u, o.f);
    if (np_outfile_close(&o, 1) != 0) {
        snprintf(err, errlen, "%s", o.err);
        return -1;
    }
    return 0;
}

/* --- SHA-256 (FIPS 180-4) --- */

static const uint32_t sha_k[64] = {
    0x428a2f98, 0x71374491, 0xb5c0fbcf, 0xe9b5dba5, 0x3956c25b, 0x59f111f1, 0x923f82a4, 0xab1c5ed5,
    0xd807aa98, 0x12835b01, 0x243185be, 0x550c7dc3, 0x72be5d74, 0x80deb1fe, 0x9bdc06a7, 0xc19bf174,
    0xe49b69c1, 0xefbe4786, 0x0fc19dc6, 0x240ca1cc, 0x2de92c6f, 0x4a7484aa, 0x5cb0a9dc, 0x76f988da,
    0x983e5152, 0xa831c66d, 0xb00327c8, 0xbf597fc7, 0xc6e00bf3, 0xd5a79147, 0x06ca6351, 0x14292967,
    0x27b70a85, 0x2e1b2138, 0x4d2c6dfc, 0x53380d13, 0x650a7354, 0x766a0abb, 0x81c2c92e, 0x92722c85,
    0xa2bfe8a1, 0xa81a664b, 0xc24b8b70, 0xc76c51a3, 0xd192e819, 0xd6990624, 0xf40e3585, 0x106aa070,
    0x19a4c116, 0x1e376c08, 0x2748774c, 0x34b0bcb5, 0x391c0cb3, 0x4ed8aa4a, 0x5b9cca4f, 0x682e6ff3,
    0x748f82ee, 0x78a5636f, 0x84c87814, 0x8cc70208, 0x90befffa, 0xa4506ceb, 0xbef9a3f7, 0xc67178f2,
};

static uint32_t ror(uint32_t x, unsigned n) { return (x >> n) | (x << (32u - n)); }

static void sha_block(np_sha256 *s, const uint8_t *p)
{
    uint32_t w[64];
    for (unsigned i = 0; i < 16; i++)
        w[i] = (uint32_t)p[4 * i] << 24 | (uint32_t)p[4 * i + 1] << 16 | (uint32_t)p[4 * i + 2] << 8 |
               (uint32_t)p[4 * i + 3];
    for (unsigned i = 16; i < 64; i++) {
        uint32_t s0 = ror(w[i - 15], 7) ^ ror(w[i - 15], 18) ^ (w[i - 15] >> 3);
        uint32_t s1 = ror(w[i - 2], 17) ^ ror(w[i - 2], 19) ^ (w[i - 2] >> 10);
        w[i] = w[i - 16] + s0 + w[i - 7] + s1;
    }
    uint32_t a = s->h[0], b = s->h[1], c = s->h[2], d = s->h[3], e = s->h[4], f = s->h[5], g = s->h[6],
             h = s->h[7];
    for (unsigned i = 0; i < 64; i++) {
        uint32_t t1 = h + (ror(e, 6) ^ ror(e, 11) ^ ror(e, 25)) + ((e & f) ^ (~e & g)) + sha_k[i] + w[i];
        uint32_t t2 = (ror(a, 2) ^ ror(a, 13) ^ ror(a, 22)) + ((a & b) ^ (a & c) ^ (b & c));
        h = g, g = f, f = e, e = d + t1, d = c, c = b, b = a, a = t1 + t2;
    }
    s->h[0] += a, s->h[1] += b, s->h[2] += c, s->h[3] += d;
    s->h[4] += e, s->h[5] += f, s->h[6] += g, s->h[7] += h;
}

void np_sha256_init(np_sha256 *s)
{
    static const uint32_t iv[8] = { 0x6a09e667, 0xbb67ae85, 0x3c6ef372, 0xa54ff53a,
                                    0x510e527f, 0x9b05688c, 0x1f83d9ab, 0x5be0cd19 };
    memcpy(s->h, iv, sizeof iv);
    s->len = 0;
    s->fill = 0;
}

void np_sha256_update(np_sha256 *s, const void *data, size_t n)
{
    const uint8_t *p = data;
    s->len += n;
    while (n > 0) {
        size_t take = 64u - s->fill < n ? 64u - s->fill : n;
        memcpy(s->buf + s->fill, p, take);
        s->fill += (unsigned)take;
        p += take;
        n -= take;
        if (s->fill == 64) {
            sha_block(s, s->buf);
            s->fill = 0;
        }
    }
}

void np_sha256_final(np_sha256 *s, uint8_t out[32])
{
    uint64_t bits = s->len * 8u;
    uint8_t pad = 0x80, zero = 0, len[8];
    np_sha256_update(s, &pad, 1);
    while (s->fill != 56)
        np_sha256_update(s, &zero, 1);
    for (unsigned i = 0; i < 8; i++)
        len[i] = (uint8_t)(bits >> (56u - 8u * i));
    np_sha256_update(s, len, 8);
    for (unsigned i = 0; i < 8; i++) {
        out[4 * i] = (uint8_t)(s->h[i] >> 24);
        out[4 * i + 1] = (uint8_t)(s->h[i] >> 16);
        out[4 * i + 2] = (uint8_t)(s->h[i] >> 8);
        out[4 * i + 3] = (uint8_t)s->h[i];
    }
}

void np_image_hash(unsigned w, unsigned h, const uint8_t *rgb, char hex[65])
{
    np_sha256 s;
    char head[64];
    uint8_t d[32];
    int n = snprintf(head, sizeof head, "P6\n%u %u\n255\n", w, h);
    np_sha256_init(&s);
    np_sha256_update(&s, head, (size_t)n);
    np_sha256_update(&s, rgb, (size_t)w * h * 3u);
    np_sha256_final(&s, d);
    for (unsigned i = 0; i < 32; i++)
        snprintf(hex + 2 * i, 3, "%02x", d[i]);
}
