/* view_save.c — what P and --screenshot-after write: the image through atmo_image_write (the
 * formats, metadata and atomic writes of `atmo render`; a PNG through atmo_post with the
 * scene's exposure, tone mapper, white balance and transfer curve, the sun's white point of
 * atmo_solar_white_point) and, for P, the scene beside it through atmo_scene_save_json. */
#include <stdio.h>
#include <string.h>
#include "atmo/colour.h"
#include "view_save.h"

void view_save_post(const atmo_scene *s, atmo_post *post)
{
    double wp[3];
    atmo_solar_white_point(wp);
    post->exposure = (float)s->post.exposure;
    post->tonemap = s->post.tonemap;
    post->white_point = (float)s->post.white_point;
    post->white_balance = s->post.white_balance;
    for (int c = 0; c < 3; c++)
        post->white_balance_rgb[c] = (float)wp[c];
    post->transfer = s->post.transfer;
}

int view_save_names(const char *base, int n, char image[VIEW_PATH_MAX],
                    char scene[VIEW_PATH_MAX], atmo_err *e)
{
    const char *slash = strrchr(base, '/');
    const char *dot = strrchr(base, '.');
    if (!dot || (slash && dot < slash))
        return atmo_fail(e, ATMO_ERR_USAGE, "--save '%s' needs an image extension", base);
    int stem = (int)(dot - base);
    int a = snprintf(image, VIEW_PATH_MAX, "%.*s-%03d%s", stem, base, n, dot);
    int b = snprintf(scene, VIEW_PATH_MAX, "%.*s-%03d.json", stem, base, n);
    if (a < 0 || a >= VIEW_PATH_MAX || b < 0 || b >= VIEW_PATH_MAX)
        return atmo_fail(e, ATMO_ERR_USAGE, "--save '%s' is too long", base);
    return ATMO_OK;
}

int view_save_image(const char *path, const atmo_image *img, const atmo_scene *rendered,
                    int samples_min, int partial, atmo_err *e)
{
    atmo_post post;
    view_save_post(rendered, &post);
    int lum = rendered->render.quantity == ATMO_QUANTITY_LUMINANCE;
    atmo_image_meta meta = {
        .quantity = lum ? "luminance" : "spectral radiance",
        .unit = lum ? "cd m^-2" : "W m^-2 sr^-1 nm^-1",
        .wavelengths_nm = {rendered->render.wavelengths_nm[0],
                           rendered->render.wavelengths_nm[1],
                           rendered->render.wavelengths_nm[2]},
        .samples_per_pixel = samples_min,
        .partial = partial,
        .software = "atmo " ATMO_VERSION};
    return atmo_image_write(path, img, &post, &meta, e);
}
