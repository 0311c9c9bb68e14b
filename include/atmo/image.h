/* image.h — writing rendered images: PNG for viewing, HDR / EXR / PFM with linear values.
 *
 * An atmo_image holds linear floats, 3 per pixel (R, G, B), row 0 at the top. What the three
 * channels are (spectral radiance at three wavelengths, or luminance-based colour) is said by
 * atmo_image_meta and written into the files that can carry it:
 *   .png  8-bit, display-encoded through atmo_post (white balance, exposure, tone map, transfer
 *         curve; kernels/post/tonemap.h); the description goes into tEXt chunks.
 *   .hdr  Radiance RGBE of the linear values (shared 8-bit exponent: relative precision 2^-8 of
 *         the pixel's largest channel); the description goes into header comment lines.
 *   .exr  OpenEXR, scanline, ZIP, 32-bit float R, G, B: the linear values exactly; the
 *         description goes into string attributes.
 *   .pfm  Portable float map, little-endian float32, bottom row first: exact, no metadata.
 * Files are written atomically (include/atmo/fileio.h): complete, or absent.
 *
 * Non-finite values never reach a file: they are written as 0, counted, and atmo_image_write
 * then returns ATMO_ERR_RUNTIME saying how many there were (the render guarantees none, so this
 * is a safety net). Negative values cannot be stored in RGBE or displayed and become 0 there. */
#ifndef ATMO_IMAGE_H
#define ATMO_IMAGE_H
#include "atmo/status.h"

typedef struct atmo_image {
    int width, height;
    float *rgb; /* linear RGB, 3 floats per pixel, row-major, row 0 = top */
} atmo_image;

typedef struct atmo_post {
    float exposure;             /* multiplies the (white-balanced) linear value before tone mapping */
    int tonemap;                /* ATMO_TONEMAP_* of include/atmo/scene.h */
    float white_point;          /* exposed value that maps to white: reinhard-white, lottes */
    int white_balance;          /* 0/1: divide each channel by white_balance_rgb */
    float white_balance_rgb[3]; /* the sun's colour in linear sRGB, mean 1; thesis default
                                   (1.08241, 0.96756, 0.95003); filled by the caller */
    int transfer;               /* ATMO_TRANSFER_SRGB or ATMO_TRANSFER_GAMMA22 */
} atmo_post;

typedef struct atmo_image_meta {
    const char *quantity;     /* "spectral radiance" or "luminance" */
    const char *unit;         /* "W m^-2 sr^-1 nm^-1" or "cd m^-2" */
    double wavelengths_nm[3]; /* what R, G, B hold */
    int samples_per_pixel;
    int partial;              /* 1 if the render was interrupted: the files say so */
    const char *software;     /* "atmo 0.1.0" */
} atmo_image_meta;

enum { ATMO_IMAGE_PNG, ATMO_IMAGE_HDR, ATMO_IMAGE_EXR, ATMO_IMAGE_PFM };

/* ATMO_IMAGE_* from the extension of path (case-insensitive), -1 if it is none of
 * .png .hdr .exr .pfm. */
int atmo_image_format_from_path(const char *path);

/* Write img to path in the format its extension names. post is needed for PNG only (may be
 * NULL otherwise); meta may be NULL (no description). Returns ATMO_OK, ATMO_ERR_USAGE (unknown
 * extension, empty image, PNG without post) or ATMO_ERR_RUNTIME (I/O failure, non-finite values
 * found and replaced by 0). */
int atmo_image_write(const char *path, const atmo_image *img, const atmo_post *post,
                     const atmo_image_meta *meta, atmo_err *e);

/* One pixel through the display pipeline: linear -> display-encoded values in [0, 1] (what a
 * PNG stores, divided by 255). */
void atmo_post_pixel(const atmo_post *post, const float in[3], float out_display[3]);

/* The whole image through atmo_post_pixel, rounded to 8 bits: out holds 3 bytes per pixel. */
void atmo_post_to_rgb8(const atmo_post *post, const atmo_image *img, unsigned char *out);

/* Per-format writers behind atmo_image_write. They expect a non-empty image with finite
 * values (atmo_image_write guarantees both) and write atomically. */
int atmo_image_write_png(const char *path, const atmo_image *img, const atmo_post *post,
                         const atmo_image_meta *meta, atmo_err *e);
int atmo_image_write_hdr(const char *path, const atmo_image *img, const atmo_image_meta *meta,
                         atmo_err *e);
int atmo_image_write_exr(const char *path, const atmo_image *img, const atmo_image_meta *meta,
                         atmo_err *e);
int atmo_image_write_pfm(const char *path, const atmo_image *img, atmo_err *e);

/* Read a 3-channel PFM ("PF", either byte order) into img (rows top first, as atmo_image);
 * img->rgb is malloc'ed and released with atmo_image_free. For tests and tools. */
int atmo_image_read_pfm(const char *path, atmo_image *img, atmo_err *e);
void atmo_image_free(atmo_image *img);

/* EXR files of named float layers (host/image/image_exr_layers.c): one full-resolution 32-bit
 * float channel per layer (width x height values, row 0 = top), ZIP-compressed (lossless: every
 * bit reads back), and string attributes. The raw sums of a split render's parts use them. */
typedef struct atmo_image_layer {
    const char *name;  /* EXR channel name, e.g. "S1.R" */
    const float *data; /* width x height floats */
} atmo_image_layer;

typedef struct atmo_image_attr {
    const char *name, *value;
} atmo_image_attr;

int atmo_image_write_exr_layers(const char *path, int width, int height,
                                const atmo_image_layer *layers, int count,
                                const atmo_image_attr *attrs, int attr_count, atmo_err *e);

/* What atmo_image_read_exr_layers returns: every channel as floats, every string attribute. */
typedef struct atmo_exr_layers {
    int width, height;
    int count;
    char **name;
    float **data;
    int attr_count;
    char **attr_name, **attr_value;
} atmo_exr_layers;

/* Read a single-part scanline EXR; a file that is none is a usage error naming it. */
int atmo_image_read_exr_layers(const char *path, atmo_exr_layers *f, atmo_err *e);
void atmo_exr_layers_free(atmo_exr_layers *f);
/* The layer or the string attribute of that name, NULL if the file has none. */
const float *atmo_exr_layer(const atmo_exr_layers *f, const char *name);
const char *atmo_exr_attr(const atmo_exr_layers *f, const char *name);

/* "R 680 nm, G 550 nm, B 440 nm; 64 samples per pixel" style description shared by the
 * writers: quantity, unit, wavelengths, samples, and "partial render" when meta->partial. */
void atmo_image_describe(const atmo_image_meta *meta, char *buf, int size);

#endif
