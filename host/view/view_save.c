/* view_save.c — what P and --screenshot-after write: the image through atmo_image_write (the
 * formats, metadata and atomic writes of `atmo render`, through atmo_outputs_write_denoised: a
 * PNG with the scene's post-processing, denoised as output.denoise says with the view's guides)
 * and, for P, the scene beside it through atmo_scene_save_json. */
#include <stdio.h>
#include <string.h>
#include "atmo/outputs.h"
#include "view_save.h"

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

int view_save_image(const char *path, const atmo_image *img,
                    const atmo_outputs_guides *guides, const atmo_scene *rendered,
                    int samples_min, int partial, atmo_err *e)
{
    const char *outputs[1] = {path};
    return atmo_outputs_write_denoised(rendered, img, guides, samples_min, partial,
                                       ATMO_EXR_DEFAULT, outputs, 1, NULL, e);
}
