/* SPDX-License-Identifier: MIT */
/*
 * np_image.h - images: OpenEXR (FLOAT channels, through the OpenEXRCore C
 * API) for data, PNG (8-bit RGB, libpng) for looking at, and the hash that
 * guards golden images (SHA-256 of the image as a binary PPM, so that
 * `sha256sum` of a file written by np_image_write_ppm gives the same digest).
 */
#ifndef NP_IMAGE_H
#define NP_IMAGE_H

#include <stddef.h>
#include <stdint.h>

enum { NP_IMAGE_MAX_CHANNELS = 8, NP_IMAGE_NAME = 32, NP_IMAGE_MAX_TEXT = 8 };

/*
 * What an image file says about itself besides its pixels: text pairs
 * (PNG tEXt chunks; EXR string attributes), keys of 1..79 printable
 * characters, values of printable Latin-1; and for EXR, whether to write the
 * chromaticities attribute with Rec. 709 primaries and the D65 white point
 * (the primaries and white of sRGB, so a viewer reads linear sRGB).
 */
typedef struct np_image_meta {
    unsigned n_text;
    const char *key[NP_IMAGE_MAX_TEXT];
    const char *value[NP_IMAGE_MAX_TEXT];
    int rec709;
} np_image_meta;

/* Add key = value to m (ignored beyond NP_IMAGE_MAX_TEXT pairs). */
void np_image_meta_add(np_image_meta *m, const char *key, const char *value);

/*
 * Write a scanline OpenEXR file with nch FLOAT channels named names[c]
 * (ZIP compression). Channel c's pixels are planes + c * w * h, row-major,
 * row 0 at the top. Written to a temporary name and renamed into place.
 * 0, or -1 with a message in err.
 */
int np_image_write_exr(const char *path, unsigned w, unsigned h, unsigned nch,
                       const char *const *names, const float *planes, char *err, size_t errlen);
/* The same with meta's attributes in the header (meta may be NULL). */
int np_image_write_exr_meta(const char *path, unsigned w, unsigned h, unsigned nch, const char *const *names,
                            const float *planes, const np_image_meta *meta, char *err, size_t errlen);

/*
 * Read a scanline OpenEXR file of FLOAT channels (data window at 0, 0) into
 * planes (malloc'd: *planes, nch * w * h; free() it), the channels in the
 * file's (alphabetical) order with their names. 0, or -1 with err.
 */
int np_image_read_exr(const char *path, unsigned *w, unsigned *h, unsigned *nch,
                      char names[NP_IMAGE_MAX_CHANNELS][NP_IMAGE_NAME], float **planes, char *err,
                      size_t errlen);

/* Write an 8-bit RGB PNG (rgb: w * h * 3 bytes, row 0 at the top). 0, or -1 with err. */
int np_image_write_png(const char *path, unsigned w, unsigned h, const uint8_t *rgb, char *err,
                       size_t errlen);
/* The same with meta's text pairs as tEXt chunks before the pixels (meta may be NULL). */
int np_image_write_png_meta(const char *path, unsigned w, unsigned h, const uint8_t *rgb, const np_image_meta *meta,
                            char *err, size_t errlen);

/* Write a binary PPM (P6, maxval 255). 0, or -1 with err. */
int np_image_write_ppm(const char *path, unsigned w, unsigned h, const uint8_t *rgb, char *err,
                       size_t errlen);

/* SHA-256 (FIPS 180-4). */
typedef struct np_sha256 {
    uint32_t h[8];
    uint64_t len;
    uint8_t buf[64];
    unsigned fill;
} np_sha256;

void np_sha256_init(np_sha256 *s);
void np_sha256_update(np_sha256 *s, const void *data, size_t n);
void np_sha256_final(np_sha256 *s, uint8_t out[32]);

/* SHA-256 of "P6\n<w> <h>\n255\n" followed by the rgb bytes, as 64 hex digits. */
void np_image_hash(unsigned w, unsigned h, const uint8_t *rgb, char hex[65]);

#endif /* NP_IMAGE_H */
