/* outputs.c — the image files of a render from its mean image (atmo/outputs.h).
 *
 * PNG goes through atmo_post with the scene's post.* settings and the sun's white point
 * (colour.h); the linear formats take the values as they are. Every file carries the same
 * description: the quantity (spectral radiance at the three wavelengths, luminance, or the
 * spectral mode's luminance from N bands), its unit, whether R, G, B are linear Rec.709 colour
 * (both luminance modes) or samples at wavelengths (radiance), the samples per pixel and
 * whether the render is partial. With output.blender the EXR files also carry the World
 * settings of atmo_outputs_blender_world (docs/guide/blender.md derives them). */
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
    const double *w = scene->render.wavelengths_nm;
    char lum_quantity[160];
    if (spectral)
        snprintf(lum_quantity, sizeof lum_quantity,
                 "luminance (linear sRGB from %d spectral bands, 360-830 nm; no channel "
                 "wavelengths)",
                 scene->render.spectral_bands);
    else
        snprintf(lum_quantity, sizeof lum_quantity,
                 "luminance (linear sRGB from spectral radiance at %g, %g and %g nm, Bruneton "
                 "2016 section 14.3)",
                 w[0], w[1], w[2]);
    atmo_image_meta meta = {
        .quantity = lum ? lum_quantity : "spectral radiance",
        .unit = lum ? "cd m^-2" : "W m^-2 sr^-1 nm^-1",
        .wavelengths_nm = {lum ? 0.0 : w[0], lum ? 0.0 : w[1], lum ? 0.0 : w[2]},
        .rec709 = lum,
        .samples_per_pixel = samples_min,
        .partial = partial,
        .exr_compression = exr_compression,
        .software = "atmo " ATMO_VERSION};
    double strength, colour[3];
    char strength_text[32], colour_text[64];
    const char *blender[4] = {"blenderWorldStrength", strength_text, "blenderWhiteBalance",
                              colour_text};
    if (atmo_outputs_blender_world(scene, &strength, colour)) {
        snprintf(strength_text, sizeof strength_text, "%.6g", strength);
        snprintf(colour_text, sizeof colour_text, "%.6g %.6g %.6g", colour[0], colour[1],
                 colour[2]);
        meta.attributes = blender;
        meta.attribute_count = 2;
    }
    for (int i = 0; i < n && !rc; i++)
        rc = atmo_image_write(outputs[i], img, &post, &meta, e);
    return rc;
}

int atmo_outputs_blender_world(const atmo_scene *scene, double *strength, double colour[3])
{
    if (!scene->output.blender)
        return 0;
    double wp[3] = {1.0, 1.0, 1.0};
    if (scene->post.white_balance)
        atmo_solar_white_point(wp);
    *strength = scene->post.exposure;
    for (int c = 0; c < 3; c++)
        colour[c] = 1.0 / wp[c];
    return 1;
}
