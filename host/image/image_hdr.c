/* image_hdr.c — Radiance RGBE (.hdr) of the linear values.
 *
 * Each pixel is four bytes (r, g, b, e): with the largest channel v = m 2^k, m in [0.5, 1)
 * (frexp), the channels are stored as round(c 2^(8-k)) and the shared exponent as k + 128; a
 * reader gets back byte * 2^(e-136) (G. Ward, "Real pixels", Graphics Gems II, 1991). atmo
 * rounds to nearest where Ward's code truncates, because the common decoders (stb_image, Ward's
 * and Walter's rgbe.c) decode without a half-unit offset: rounding then bounds the error of every
 * channel by half a unit of the largest, 2^(k-9) <= 2^-8 v, where truncation would allow 2^-7 v.
 * Negative values (which RGBE cannot hold) are stored as 0.
 *
 * File: "#?RADIANCE", comment lines describing the data (quantity, unit, wavelengths, samples,
 * partial render; for RGB colour, meta->rec709, the header's PRIMARIES= line with Rec.709's
 * primaries and D65 white instead of the wavelengths), "FORMAT=32-bit_rle_rgbe", a blank line, "-Y <height> +X <width>" (rows top to
 * bottom), then flat (uncompressed) scanlines. Flat scanlines cannot be mistaken for run-length
 * ones: those begin with bytes 2, 2 and a third byte below 128, while a stored pixel has its
 * largest channel at 128 or above (or is all zero). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include "atmo/fileio.h"
#include "atmo/image.h"

static void rgbe_encode(const float *rgb, unsigned char out[4])
{
    float c[3];
    for (int i = 0; i < 3; i++)
        c[i] = rgb[i] > 0.0f ? rgb[i] : 0.0f;
    float v = fmaxf(c[0], fmaxf(c[1], c[2]));
    int k;
    frexpf(v, &k);
    /* Below 2^-128 nothing survives the shared exponent; zero (and denormal-small) pixels too. */
    if (v == 0.0f || k < -127) {
        out[0] = out[1] = out[2] = out[3] = 0;
        return;
    }
    /* Rounding can carry the largest channel to 256: then use the next exponent. */
    if (lrintf(ldexpf(v, 8 - k)) > 255)
        k++;
    if (k > 127) { /* beyond 2^127: saturate (float's range ends at 2^128) */
        out[0] = out[1] = out[2] = 255;
        out[3] = 255;
        return;
    }
    for (int i = 0; i < 3; i++)
        out[i] = (unsigned char)lrintf(ldexpf(c[i], 8 - k));
    out[3] = (unsigned char)(k + 128);
}

int atmo_image_write_hdr(const char *path, const atmo_image *img, const atmo_image_meta *meta,
                         atmo_err *e)
{
    char tmp[ATMO_TMP_PATH_MAX];
    size_t row_bytes = (size_t)img->width * 4;
    unsigned char *row = malloc(row_bytes);
    if (!row)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory writing '%s'", path);
    FILE *f = atmo_atomic_open(path, tmp, e);
    if (!f) {
        free(row);
        return ATMO_ERR_RUNTIME;
    }
    fputs("#?RADIANCE\n", f);
    if (meta) {
        const double *w = meta->wavelengths_nm;
        fprintf(f, "# software: %s\n", meta->software ? meta->software : "atmo");
        fprintf(f, "# quantity: %s\n", meta->quantity ? meta->quantity : "linear value");
        fprintf(f, "# unit: %s\n", meta->unit ? meta->unit : "1");
        if (meta->rec709) /* Radiance's PRIMARIES= line: x y of R, G, B and white */
            fputs("PRIMARIES=0.640 0.330 0.300 0.600 0.150 0.060 0.3127 0.3290\n", f);
        else
            fprintf(f, "# wavelengths: R %g nm, G %g nm, B %g nm\n", w[0], w[1], w[2]);
        fprintf(f, "# samples per pixel: %d\n", meta->samples_per_pixel);
        if (meta->partial)
            fputs("# partial render: interrupted before all samples were taken\n", f);
    }
    fprintf(f, "FORMAT=32-bit_rle_rgbe\n\n-Y %d +X %d\n", img->height, img->width);
    for (int y = 0; y < img->height; y++) {
        const float *src = img->rgb + (size_t)y * (size_t)img->width * 3;
        for (int x = 0; x < img->width; x++)
            rgbe_encode(src + 3 * x, row + 4 * x);
        if (fwrite(row, 1, row_bytes, f) != row_bytes)
            break; /* ferror is set: the commit below reports it and removes the file */
    }
    free(row);
    return atmo_atomic_commit(f, tmp, path, e);
}
