/* image_png.c — 8-bit PNG for viewing, through the display pipeline of atmo_post (post.c).
 *
 * stb_image_write (Debian's libstb) encodes the pixels into memory; atmo then inserts tEXt
 * chunks right after IHDR (PNG 1.2, section 4.2.3.1: "Software", and "Description" naming what
 * the tone-mapped values came from) and writes the whole buffer atomically. A PNG chunk is
 * length (4 bytes, big-endian), type, data, and the CRC-32 of type and data (ISO 3309
 * polynomial, reflected 0xEDB88320, initial and final XOR 0xFFFFFFFF). */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <stb_image_write.h>
#include "atmo/fileio.h"
#include "atmo/image.h"

/* The encoded PNG, collected from stb's callback (which it calls once with the whole file). */
typedef struct {
    unsigned char *data;
    size_t size;
    int failed;
} png_buffer;

static void png_collect(void *context, void *data, int size)
{
    png_buffer *b = context;
    unsigned char *grown = realloc(b->data, b->size + (size_t)size);
    if (!grown) {
        b->failed = 1;
        return;
    }
    memcpy(grown + b->size, data, (size_t)size);
    b->data = grown;
    b->size += (size_t)size;
}

static uint32_t png_crc(const unsigned char *p, size_t n, uint32_t crc)
{
    for (size_t i = 0; i < n; i++) {
        crc ^= p[i];
        for (int k = 0; k < 8; k++)
            crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
    }
    return crc;
}

static void png_put_u32(FILE *f, uint32_t v)
{
    unsigned char b[4] = {(unsigned char)(v >> 24), (unsigned char)(v >> 16),
                          (unsigned char)(v >> 8), (unsigned char)v};
    fwrite(b, 1, 4, f);
}

/* One tEXt chunk: keyword (Latin-1, 1-79 bytes), a zero byte, the text. */
static void png_write_text(FILE *f, const char *keyword, const char *text)
{
    size_t nk = strlen(keyword), nt = strlen(text);
    png_put_u32(f, (uint32_t)(nk + 1 + nt));
    uint32_t crc = png_crc((const unsigned char *)"tEXt", 4, 0xFFFFFFFFu);
    crc = png_crc((const unsigned char *)keyword, nk + 1, crc); /* with its zero byte */
    crc = png_crc((const unsigned char *)text, nt, crc);
    fwrite("tEXt", 1, 4, f);
    fwrite(keyword, 1, nk + 1, f);
    fwrite(text, 1, nt, f);
    png_put_u32(f, crc ^ 0xFFFFFFFFu);
}

int atmo_image_write_png_rgb8(const char *path, int width, int height, const unsigned char *rgb,
                              const char *software, const char *description, atmo_err *e)
{
    /* Signature (8 bytes) and the IHDR chunk (4 + 4 + 13 + 4 bytes) come first. */
    const size_t header_bytes = 8 + 25;
    int rc = ATMO_ERR_RUNTIME;
    png_buffer png = {NULL, 0, 0};
    if (!stbi_write_png_to_func(png_collect, &png, width, height, 3, rgb, width * 3) ||
        png.failed || png.size < header_bytes || memcmp(png.data + 12, "IHDR", 4) != 0) {
        atmo_fail(e, ATMO_ERR_RUNTIME, "PNG encoding of '%s' failed (out of memory?)", path);
        goto cleanup;
    }
    char tmp[ATMO_TMP_PATH_MAX];
    FILE *f = atmo_atomic_open(path, tmp, e);
    if (!f)
        goto cleanup;
    fwrite(png.data, 1, header_bytes, f);
    if (software)
        png_write_text(f, "Software", software);
    if (description)
        png_write_text(f, "Description", description);
    fwrite(png.data + header_bytes, 1, png.size - header_bytes, f);
    rc = atmo_atomic_commit(f, tmp, path, e);
cleanup:
    free(png.data);
    return rc;
}

int atmo_image_write_png(const char *path, const atmo_image *img, const atmo_post *post,
                         const atmo_image_meta *meta, atmo_err *e)
{
    unsigned char *pixels = malloc((size_t)img->width * (size_t)img->height * 3);
    if (!pixels)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory writing '%s'", path);
    atmo_post_to_rgb8(post, img, pixels);
    char description[512], text[640];
    if (meta) {
        atmo_image_describe(meta, description, sizeof description);
        snprintf(text, sizeof text, "display-encoded (tone mapped, exposure %g) %s",
                 (double)post->exposure, description);
    }
    int rc = atmo_image_write_png_rgb8(path, img->width, img->height, pixels,
                                       meta ? (meta->software ? meta->software : "atmo") : NULL,
                                       meta ? text : NULL, e);
    free(pixels);
    return rc;
}
