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
    char channels[96];
    if (meta->rec709)
        snprintf(channels, sizeof channels, "linear Rec.709 RGB (sRGB primaries, D65 white)");
    else
        snprintf(channels, sizeof channels, "R %g nm, G %g nm, B %g nm", w[0], w[1], w[2]);
    snprintf(buf, (size_t)size, "%s [%s]; %s; %d samples per pixel%s",
             meta->quantity ? meta->quantity : "linear value", meta->unit ? meta->unit : "1",
             channels, meta->samples_per_pixel,
             meta->partial ? "; partial render (interrupted before all samples)" : "");
}

void atmo_image_free(atmo_image *img)
{
    free(img->rgb);
    img->rgb = NULL;
    img->width = img->height = 0;
}

/* Count the values of n floats that may not reach a file (NaN always, +-Inf unless
 * keep_infinity); if there are any, *clean becomes a malloc'ed copy with those values set to 0
 * (NULL when there are none). */
static long sanitize(const float *v, size_t n, int keep_infinity, float **clean, atmo_err *e)
{
    long bad = 0;
    *clean = NULL;
    for (size_t i = 0; i < n; i++)
        bad += keep_infinity ? isnan(v[i]) != 0 : !isfinite(v[i]);
    if (bad == 0)
        return 0;
    *clean = malloc(n * sizeof(float));
    if (!*clean) {
        atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory copying %zu image values", n);
        return -1;
    }
    for (size_t i = 0; i < n; i++) {
        int ok = keep_infinity ? !isnan(v[i]) : isfinite(v[i]);
        (*clean)[i] = ok ? v[i] : 0.0f;
    }
    return bad;
}

static int check_layers(const atmo_image *img, const char *path, atmo_err *e)
{
    if (img->layer_count < 0 || (img->layer_count > 0 && !img->layers))
        return atmo_fail(e, ATMO_ERR_USAGE, "image for '%s' has %d layers and no layer list",
                         path, img->layer_count);
    for (int l = 0; l < img->layer_count; l++) {
        const atmo_image_layer *layer = &img->layers[l];
        if (!layer->name || !layer->name[0] || layer->channels < 1 || layer->channels > 4 ||
            !layer->data)
            return atmo_fail(e, ATMO_ERR_USAGE,
                             "layer %d of the image for '%s' needs a name, 1-4 channels and data",
                             l, path);
        for (int c = 0; c < layer->channels; c++)
            if (!layer->channel_names[c] || !layer->channel_names[c][0])
                return atmo_fail(e, ATMO_ERR_USAGE,
                                 "layer '%s' of the image for '%s' has no name for channel %d",
                                 layer->name, path, c);
    }
    return ATMO_OK;
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

    int rc = check_layers(img, path, e);
    if (rc)
        return rc;
    size_t pixels = (size_t)img->width * (size_t)img->height;
    float *clean;
    long bad = sanitize(img->rgb, pixels * 3, 0, &clean, e);
    if (bad < 0)
        return ATMO_ERR_RUNTIME;
    atmo_image safe = *img;
    safe.rgb = clean ? clean : img->rgb;
    atmo_image_layer *layers = NULL;
    float **layer_clean = NULL;
    safe.layers = NULL;
    safe.layer_count = 0;
    if (format == ATMO_IMAGE_EXR && img->layer_count > 0) {
        layers = malloc((size_t)img->layer_count * sizeof *layers);
        layer_clean = calloc((size_t)img->layer_count, sizeof *layer_clean);
        if (!layers || !layer_clean) {
            rc = atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory for the layers of '%s'", path);
            goto cleanup;
        }
        for (int l = 0; l < img->layer_count; l++) {
            layers[l] = img->layers[l];
            long b = sanitize(layers[l].data, pixels * (size_t)layers[l].channels,
                              layers[l].keep_infinity, &layer_clean[l], e);
            if (b < 0) {
                rc = ATMO_ERR_RUNTIME;
                goto cleanup;
            }
            bad += b;
            if (layer_clean[l])
                layers[l].data = layer_clean[l];
        }
        safe.layers = layers;
        safe.layer_count = img->layer_count;
    }

    switch (format) {
    case ATMO_IMAGE_PNG: rc = atmo_image_write_png(path, &safe, post, meta, e); break;
    case ATMO_IMAGE_HDR: rc = atmo_image_write_hdr(path, &safe, meta, e); break;
    case ATMO_IMAGE_EXR: rc = atmo_image_write_exr(path, &safe, meta, e); break;
    default: rc = atmo_image_write_pfm(path, &safe, e); break;
    }
    if (rc == ATMO_OK && bad > 0)
        rc = atmo_fail(e, ATMO_ERR_RUNTIME,
                       "%ld non-finite values (NaN/Inf) in the image were written as 0 to '%s': "
                       "a renderer bug, please report it with the scene",
                       bad, path);
cleanup:
    for (int l = 0; layer_clean && l < safe.layer_count; l++)
        free(layer_clean[l]);
    free(layer_clean);
    free(layers);
    free(clean);
    return rc;
}
