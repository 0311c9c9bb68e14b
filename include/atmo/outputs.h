/* outputs.h — the image files of a render from its mean image (host/render/outputs.c), shared
 * by `atmo render`, `atmo merge` and the viewer's saves, so that the same scene and samples
 * give the same files, bit for bit, whichever of them wrote them. */
#ifndef ATMO_OUTPUTS_H
#define ATMO_OUTPUTS_H
#include "atmo/image.h"
#include "atmo/scene.h"
#include "atmo/status.h"

/* The display pipeline of `scene` for PNG: its post.* settings and the sun's white point
 * (atmo_solar_white_point). */
void atmo_outputs_post(const atmo_scene *scene, atmo_post *post);

/* Write img (the mean image of `scene`) to each of outputs[0..n-1]: post-processing and the
 * files' description from the scene (post.*, render.quantity, wavelengths or spectral bands),
 * samples_min samples per pixel, marked partial when `partial`; EXR files with the codec
 * exr_compression (ATMO_EXR_*). */
int atmo_outputs_write(const atmo_scene *scene, const atmo_image *img, int samples_min,
                       int partial, int exr_compression, const char *const *outputs, int n,
                       atmo_err *e);

/* Blender's World settings that show `scene`'s linear outputs as its PNG shows them, for scenes
 * with output.blender (0 for others): the Background strength, which is post.exposure (the
 * factor the PNG applies before its tone map), and the colour the texture is multiplied by for
 * the white balance (1 / the sun's colour with post.white_balance, else 1, 1, 1). Every EXR of
 * such a scene carries them as the attributes "blenderWorldStrength" and
 * "blenderWhiteBalance". */
int atmo_outputs_blender_world(const atmo_scene *scene, double *strength, double colour[3]);

#endif
