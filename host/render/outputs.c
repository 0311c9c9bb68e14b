/* outputs.c — the image files of a render from its mean image (atmo/outputs.h).
 *
 * PNG goes through atmo_post with the scene's post.* settings and the sun's white point
 * (colour.h); the linear formats take the values as they are. Every file carries the same
 * description: the quantity (spectral radiance at the three wavelengths, luminance, or the
 * spectral mode's luminance from N bands), its unit, the samples per pixel and whether the
 * render is partial. */
#include <stdio.h>
#include "atmo/colour.h"
#include "atmo/outputs.h"

void atmo_outputs_post(const atmo_scene *scene, atmo_post *post)
{
    double wp[3];
    atmo_solar_white_point(wp);
    post->exposure = (float)scene->post.exposure;
    post->tonemap = scene->post.tonemap;
    post->white_point = (float)scene->post.white_point;
    post->white_balance = scene->post.white_balance;
    for (int c = 0; c < 3; c++)
        post->white_balance_rgb[c] = (float)wp[c];
    post->transfer = scene->post.transfer;
}

int atmo_outputs_write(const atmo_scene *scene, const atmo_image *img, int samples_min,
                       int partial, int exr_compression, const char *const *outputs, int n,
                       atmo_err *e)
{
    int spectral = scene->render.spectral_bands > 0, rc = ATMO_OK;
    atmo_post post;
    atmo_outputs_post(scene, &post);
    int lum = spectral || scene->render.quantity == ATMO_QUANTITY_LUMINANCE;
    char spectral_quantity[96];
    snprintf(spectral_quantity, sizeof spectral_quantity,
             "luminance (linear sRGB from %d spectral bands, 360-830 nm; no channel wavelengths)",
             scene->render.spectral_bands);
    atmo_image_meta meta = {
        .quantity = spectral ? spectral_quantity : lum ? "luminance" : "spectral radiance",
        .unit = lum ? "cd m^-2" : "W m^-2 sr^-1 nm^-1",
        .wavelengths_nm = {spectral ? 0.0 : scene->render.wavelengths_nm[0],
                           spectral ? 0.0 : scene->render.wavelengths_nm[1],
                           spectral ? 0.0 : scene->render.wavelengths_nm[2]},
        .samples_per_pixel = samples_min,
        .partial = partial,
        .exr_compression = exr_compression,
        .software = "atmo " ATMO_VERSION};
    for (int i = 0; i < n && !rc; i++)
        rc = atmo_image_write(outputs[i], img, &post, &meta, e);
    return rc;
}
