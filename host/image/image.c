/* image.c — choosing the output format by extension, and the checks every format shares.
 *
 * atmo_image_write validates the image, replaces non-finite values by 0 in a copy (counting
 * them), dispatches to the writer of the extension (image_png.c, image_hdr.c, image_exr.c,
 * image_pfm.c) and then reports the non-finite count as a runtime error: the file is still
 * written, with zeros, so a long render is not lost to one bad pixel, but the run fails loudly. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include "atmo/image.h"

int atmo_image_format_from_path(const char *path)
{
    static const struct { const char *ext; int format; } formats[] = {
        {".png", ATMO_IMAGE_PNG}, {".hdr", ATMO_IMAGE_HDR},
        {".exr", ATMO_IMAGE_EXR}, {".pfm", ATMO_IMAGE_PFM},
    };
    const char *dot = path ? strrchr(path, '.') : NULL;
    if (!dot)
        return -1;
    for (size_t i = 0; i < sizeof formats / sizeof formats[0]; i++)
        if (strcasecmp(dot, formats[i].ext) == 0)
            return formats[i].format;
    return -1;
}

void atmo_image_describe(const atmo_image_meta *meta, char *buf, int size)
{
    const double *w = meta->wavelengths_nm;
    snprintf(buf, (size_t)size, "%s [%s]; R %g nm, G %g nm, B %g nm; %d samples per pixel%s",
             meta->quantity ? meta->quantity : "linear value", meta->unit ? meta->unit : "1",
             w[0], w[1], w[2], meta->samples_per_pixel,
             meta->partial ? "; partial render (interrupted before all samples)" : "");
}

void atmo_image_free(atmo_image *img)
{
    free(img->rgb);
    img->rgb = NULL;
    img->width = img->height = 0;
}

/* Count the non-finite values of img; if there are any, *clean becomes a malloc'ed copy of
 * the pixels with those values set to 0 (NULL when there are none). */
static long image_sanitize(const atmo_image *img, float **clean, atmo_err *e)
{
    size_t n = (size_t)img->width * (size_t)img->height * 3;
    long bad = 0;
    *clean = NULL;
    for (size_t i = 0; i < n; i++)
        bad += !isfinite(img->rgb[i]);
    if (bad == 0)
        return 0;
    *clean = malloc(n * sizeof(float));
    if (!*clean) {
        atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory copying a %dx%d image", img->width,
                  img->height);
        return -1;
    }
    for (size_t i = 0; i < n; i++)
        (*clean)[i] = isfinite(img->rgb[i]) ? img->rgb[i] : 0.0f;
    return bad;
}

int atmo_image_write(const char *path, const atmo_image *img, const atmo_post *post,
                     const atmo_image_meta *meta, atmo_err *e)
{
    int format = atmo_image_format_from_path(path);
    if (format < 0)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "unknown image format for '%s': use a .png, .hdr, .exr or .pfm name",
                         path ? path : "(null)");
    if (!img || !img->rgb || img->width <= 0 || img->height <= 0)
        return atmo_fail(e, ATMO_ERR_USAGE, "cannot write '%s': the image is empty", path);
    if (format == ATMO_IMAGE_PNG && !post)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "cannot write '%s': PNG output needs the post-processing settings", path);

    float *clean;
    long bad = image_sanitize(img, &clean, e);
    if (bad < 0)
        return ATMO_ERR_RUNTIME;
    atmo_image safe = {img->width, img->height, clean ? clean : img->rgb};

    int rc;
    switch (format) {
    case ATMO_IMAGE_PNG: rc = atmo_image_write_png(path, &safe, post, meta, e); break;
    case ATMO_IMAGE_HDR: rc = atmo_image_write_hdr(path, &safe, meta, e); break;
    case ATMO_IMAGE_EXR: rc = atmo_image_write_exr(path, &safe, meta, e); break;
    default: rc = atmo_image_write_pfm(path, &safe, e); break;
    }
    free(clean);
    if (rc == ATMO_OK && bad > 0)
        rc = atmo_fail(e, ATMO_ERR_RUNTIME,
                       "%ld non-finite values (NaN/Inf) in the image were written as 0 to '%s': "
                       "a renderer bug, please report it with the scene",
                       bad, path);
    return rc;
}
