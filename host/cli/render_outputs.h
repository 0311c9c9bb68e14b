/* render_outputs.h — the image files of a render (render_outputs.c), shared by `atmo render`
 * and `atmo merge` so that a merged render's files are the single render's, bit for bit. */
#ifndef ATMO_RENDER_OUTPUTS_H
#define ATMO_RENDER_OUTPUTS_H
#include "atmo/image.h"
#include "atmo/scene.h"
#include "atmo/status.h"

/* Write img (the mean image of `scene`) to each of outputs[0..n-1]: post-processing and the
 * files' description from the scene (post.*, render.quantity, wavelengths or spectral bands),
 * samples_min samples per pixel, marked partial when `partial`; EXR files with the codec
 * exr_compression (ATMO_EXR_*). */
int render_outputs_write(const atmo_scene *scene, const atmo_image *img, int samples_min,
                         int partial, int exr_compression, const char *const *outputs, int n,
                         atmo_err *e);

#endif
