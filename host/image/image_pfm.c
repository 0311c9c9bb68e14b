/* image_pfm.c — Portable Float Map: the linear values, exactly, with no metadata.
 *
 * Layout: "PF\n<width> <height>\n<scale>\n" then width*height RGB float32 triples, the BOTTOM
 * row first. The sign of the scale gives the byte order (negative: little-endian); |scale| is
 * an optional brightness factor that atmo always writes as 1. Bytes are assembled explicitly, so
 * the file is little-endian whatever the host. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/fileio.h"
#include "atmo/image.h"

int atmo_image_write_pfm(const char *path, const atmo_image *img, atmo_err *e)
{
    char tmp[ATMO_TMP_PATH_MAX];
    size_t row_bytes = (size_t)img->width * 12;
    unsigned char *row = malloc(row_bytes);
    if (!row)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory writing '%s'", path);
    FILE *f = atmo_atomic_open(path, tmp, e);
    if (!f) {
        free(row);
        return ATMO_ERR_RUNTIME;
    }
    fprintf(f, "PF\n%d %d\n-1.0\n", img->width, img->height);
    for (int y = img->height - 1; y >= 0; y--) {
        const float *src = img->rgb + (size_t)y * (size_t)img->width * 3;
        for (size_t i = 0; i < (size_t)img->width * 3; i++) {
            uint32_t u;
            memcpy(&u, &src[i], 4);
            for (int k = 0; k < 4; k++)
                row[4 * i + (size_t)k] = (unsigned char)(u >> (8 * k));
        }
        if (fwrite(row, 1, row_bytes, f) != row_bytes)
            break; /* ferror is set: the commit below reports it and removes the file */
    }
    free(row);
    return atmo_atomic_commit(f, tmp, path, e);
}

int atmo_image_read_pfm(const char *path, atmo_image *img, atmo_err *e)
{
    int rc = ATMO_ERR_RUNTIME;
    unsigned char *row = NULL;
    img->rgb = NULL;
    img->width = img->height = 0;
    img->layers = NULL; /* a PFM holds R, G, B only */
    img->layer_count = 0;
    FILE *f = fopen(path, "rb");
    if (!f)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "cannot open '%s'", path);
    int w, h;
    float scale;
    /* The header ends with exactly one whitespace character after the scale. */
    if (fscanf(f, "PF %d %d %f", &w, &h, &scale) != 3 || fgetc(f) == EOF || w <= 0 || h <= 0 ||
        scale == 0.0f) {
        atmo_fail(e, ATMO_ERR_RUNTIME, "'%s' is not a 3-channel PFM file", path);
        goto cleanup;
    }
    size_t row_bytes = (size_t)w * 12;
    row = malloc(row_bytes);
    img->rgb = malloc(row_bytes / 4 * sizeof(float) * (size_t)h);
    if (!row || !img->rgb) {
        atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory reading '%s'", path);
        goto cleanup;
    }
    int little = scale < 0.0f;
    for (int y = h - 1; y >= 0; y--) {
        if (fread(row, 1, row_bytes, f) != row_bytes) {
            atmo_fail(e, ATMO_ERR_RUNTIME, "'%s' ends early (truncated PFM)", path);
            goto cleanup;
        }
        float *dst = img->rgb + (size_t)y * (size_t)w * 3;
        for (size_t i = 0; i < (size_t)w * 3; i++) {
            uint32_t u = 0;
            for (int k = 0; k < 4; k++)
                u |= (uint32_t)row[4 * i + (size_t)(little ? k : 3 - k)] << (8 * k);
            memcpy(&dst[i], &u, 4);
        }
    }
    img->width = w;
    img->height = h;
    rc = ATMO_OK;
cleanup:
    if (rc != ATMO_OK) {
        free(img->rgb);
        img->rgb = NULL;
    }
    free(row);
    fclose(f);
    return rc;
}
