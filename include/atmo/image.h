/* image.h — writing rendered images: PNG for viewing, HDR / EXR / PFM with linear values.
 *
 * An atmo_image holds linear floats, 3 per pixel (R, G, B), row 0 at the top. What the three
 * channels are (spectral radiance at three wavelengths, or luminance-based colour) is said by
 * atmo_image_meta and written into the files that can carry it:
 *   .png  8-bit, display-encoded through atmo_post (white balance, exposure, tone map, transfer
 *         curve; kernels/post/tonemap.h); the description goes into tEXt chunks.
 *   .hdr  Radiance RGBE of the linear values (shared 8-bit exponent: relative precision 2^-8 of
 *         the pixel's largest channel); the description goes into header comment lines.
 *   .exr  OpenEXR, scanline, 32-bit float R, G, B: the linear values exactly, plus the image's
 *         extra layers (below), in a lossless compression (meta's exr_compression; chunks
 *         compressed on every processor); the description goes into string attributes, and
 *         RGB colour (meta->rec709) into the standard chromaticities attribute.
 *   .pfm  Portable float map, little-endian float32, bottom row first: exact, no metadata.
 * Files are written atomically (include/atmo/fileio.h): complete, or absent.
 *
 * Non-finite values never reach a file: they are written as 0, counted, and atmo_image_write
 * then returns ATMO_ERR_RUNTIME saying how many there were (the render guarantees none, so this
 * is a safety net). Negative values cannot be stored in RGBE or displayed and become 0 there. */
#ifndef ATMO_IMAGE_H
#define ATMO_IMAGE_H
#include "atmo/status.h"

/* An extra layer of float channels written beside R, G, B into EXR files (the other formats
 * hold R, G, B only and ignore it): `channels` values per pixel, interleaved, row-major, row 0 =
 * top, stored as the channels "<name>.<channel_names[c]>" (layer "Depth" with channel "Z" is
 * "Depth.Z", layer "Normal" with "X", "Y", "Z" is "Normal.X" ...: the names Blender's compositor
 * reads as passes). Values are stored exactly. NaN never reaches a file (written as 0 and
 * counted, as in R, G, B); +-Inf is kept where keep_infinity is set (a depth of +Inf for rays
 * that hit nothing) and counted as non-finite otherwise. */
typedef struct atmo_image_layer {
    const char *name;
    int channels;                 /* 1 .. 4 */
    const char *channel_names[4];
    const float *data;            /* width * height * channels floats */
    int keep_infinity;
} atmo_image_layer;

typedef struct atmo_image {
    int width, height;
    float *rgb; /* linear RGB, 3 floats per pixel, row-major, row 0 = top */
    const atmo_image_layer *layers; /* extra layers for EXR (may be NULL) */
    int layer_count;
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
    double wavelengths_nm[3]; /* what R, G, B hold (rec709 = 0) */
    int rec709;               /* 1: R, G, B are linear Rec.709 (sRGB primaries, D65 white), not
                                 samples at wavelengths: EXR gets the standard "chromaticities"
                                 attribute and "colorInteropID" lin_rec709_scene instead of
                                 "wavelengths" */
    int samples_per_pixel;
    int partial;              /* 1 if the render was interrupted: the files say so */
    const char *software;     /* "atmo 0.1.0" */
    /* Further string attributes for the formats that carry them (EXR): attribute_count pairs
     * name, value in attributes[2 k], attributes[2 k + 1] (may be NULL). */
    const char *const *attributes;
    int attribute_count;
    int exr_compression;      /* ATMO_EXR_* (lossless codecs); 0 = ATMO_EXR_DEFAULT */
} atmo_image_meta;

/* EXR compression, all lossless for 32-bit floats. ATMO_EXR_DEFAULT is the one chosen by
 * measurement (image_exr.c's header has the numbers). */
enum { ATMO_EXR_DEFAULT, ATMO_EXR_NONE, ATMO_EXR_RLE, ATMO_EXR_ZIPS, ATMO_EXR_ZIP, ATMO_EXR_PIZ };
/* ATMO_EXR_* of "none", "rle", "zips", "zip", "piz" or "default"; -1 for another name. */
int atmo_exr_compression_from_name(const char *name);
/* The name of an ATMO_EXR_* ("default" resolved to the codec it stands for). */
const char *atmo_exr_compression_name(int compression);

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
/* 8-bit RGB pixels (3 bytes each, row 0 = top) as a PNG, with tEXt chunks "Software" and
 * "Description" where those are not NULL (the viewer's window capture writes through it). */
int atmo_image_write_png_rgb8(const char *path, int width, int height, const unsigned char *rgb,
                              const char *software, const char *description, atmo_err *e);
int atmo_image_write_hdr(const char *path, const atmo_image *img, const atmo_image_meta *meta,
                         atmo_err *e);
int atmo_image_write_exr(const char *path, const atmo_image *img, const atmo_image_meta *meta,
                         atmo_err *e);
int atmo_image_write_pfm(const char *path, const atmo_image *img, atmo_err *e);

/* An EXR file read back whole: every channel as a float plane (HALF and UINT channels
 * converted), and its string attributes. For merging partial renders, tools and tests. */
typedef struct atmo_exr_channel {
    char name[64];
    float *data; /* width * height floats, row 0 = top */
} atmo_exr_channel;

typedef struct atmo_exr_attribute {
    char name[64];
    char *value;
} atmo_exr_attribute;

typedef struct atmo_exr_file {
    int width, height;
    int channel_count, attribute_count;
    atmo_exr_channel *channels;
    atmo_exr_attribute *attributes; /* the string-typed attributes only */
} atmo_exr_file;

/* Read the first part of a scanline or tiled EXR file into f (released with
 * atmo_exr_file_free, also after a failure). ATMO_ERR_USAGE for a file that is missing or not
 * an EXR image, ATMO_ERR_RUNTIME for a decoding failure. */
int atmo_exr_read(const char *path, atmo_exr_file *f, atmo_err *e);
/* The channel or string attribute of that name, NULL if the file has none. */
const float *atmo_exr_channel_data(const atmo_exr_file *f, const char *name);
const char *atmo_exr_attribute_value(const atmo_exr_file *f, const char *name);
void atmo_exr_file_free(atmo_exr_file *f);

/* Read a 3-channel PFM ("PF", either byte order) into img (rows top first, as atmo_image);
 * img->rgb is malloc'ed and released with atmo_image_free. For tests and tools. */
int atmo_image_read_pfm(const char *path, atmo_image *img, atmo_err *e);
void atmo_image_free(atmo_image *img);

/* "R 680 nm, G 550 nm, B 440 nm; 64 samples per pixel" style description shared by the
 * writers: quantity, unit, wavelengths (or "linear Rec.709 RGB" for meta->rec709), samples, and
 * "partial render" when meta->partial. */
void atmo_image_describe(const atmo_image_meta *meta, char *buf, int size);

#endif
