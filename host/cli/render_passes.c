/* render_passes.c — the path tracer's render passes (kernels/render/path.cl's planes) as the
 * EXR layers a compositor reads, named as Blender's compositor names its passes where it has
 * one:
 *   Env.R/G/B      the sky and the sun's disc seen directly (Blender: Environment)
 *   Emit.R/G/B     the objects' emission (Blender: Emission)
 *   Volume.R/G/B   the air's in-scattered light in front of surfaces (Blender's Volume Direct +
 *                  Indirect together); with path.air = medium, the light of the air's
 *                  scatterings past the camera ray (those on a camera ray that meets no
 *                  surface are the sky seen directly: Env)
 *   Sun.R/G/B      sunlight reflected by surfaces, every bounce
 *   Sky.R/G/B      skylight reflected by surfaces, every bounce (Sun + Sky = Blender's Diffuse
 *                  Direct + Indirect: atmo splits them by light instead of by bounce)
 *   Clouds.R/G/B   light scattered by the cloud layer's volume (path.clouds = volume): the sun
 *                  at its scattering events and the sky reached from them, every bounce
 *   Depth.Z        distance to the primary hit in metres along the ray (1e10 where the ray
 *                  escapes, Blender's background depth), averaged over the pixel's samples
 *   Normal.X/Y/Z   the primary hit's unit normal facing the camera, world axes, averaged
 *   DiffCol.R/G/B  the primary hit's albedo (Blender: Diffuse Color), averaged
 *   Samples.N      samples per pixel
 *   Error.R/G/B    the standard error of each pixel's mean (atmo/session.h)
 * The six light passes sum to the beauty image R, G, B (to float rounding). */
#include <stdlib.h>
#include "render_passes.h"

int render_pass_layers(const atmo_render_result *r, atmo_image_layer *layers, float **block)
{
    static const char *const light_names[ATMO_PATH_LIGHT_PASSES] = {"Env", "Emit", "Volume",
                                                                    "Sun", "Sky", "Clouds"};
    *block = NULL;
    if (r->pass_planes == 0)
        return 0;
    size_t pixels = (size_t)r->width * r->height;
    /* 3 channels for each light pass, Normal, DiffCol, Error; 1 for Depth and Samples */
    size_t floats = pixels * (3 * (ATMO_PATH_LIGHT_PASSES + 3) + 2);
    float *data = malloc(floats * sizeof(float));
    if (!data)
        return -1;
    *block = data;
    int n = 0;
    float *next = data;
    for (int k = 0; k < ATMO_PATH_PASS_PLANES; k++) {
        const float *plane = r->passes + 4 * pixels * (size_t)k;
        int is_normal = k == ATMO_PATH_LIGHT_PASSES, is_albedo = k == ATMO_PATH_LIGHT_PASSES + 1;
        atmo_image_layer l = {is_normal ? "Normal" : is_albedo ? "DiffCol" : light_names[k], 3,
                              {"R", "G", "B", NULL}, next, 0};
        if (is_normal)
            l.channel_names[0] = "X", l.channel_names[1] = "Y", l.channel_names[2] = "Z";
        for (size_t i = 0; i < pixels; i++)
            for (int c = 0; c < 3; c++)
                next[3 * i + c] = plane[4 * i + c];
        next += 3 * pixels;
        layers[n++] = l;
        if (is_normal) { /* the depth rides in the normal plane's w */
            atmo_image_layer d = {"Depth", 1, {"Z", NULL, NULL, NULL}, next, 0};
            for (size_t i = 0; i < pixels; i++)
                next[i] = plane[4 * i + 3];
            next += pixels;
            layers[n++] = d;
        }
    }
    atmo_image_layer ns = {"Samples", 1, {"N", NULL, NULL, NULL}, next, 0};
    for (size_t i = 0; i < pixels; i++)
        next[i] = (float)r->samples[i];
    next += pixels;
    layers[n++] = ns;
    atmo_image_layer err = {"Error", 3, {"R", "G", "B", NULL}, next, 0};
    for (size_t i = 0; i < 3 * pixels; i++)
        next[i] = r->se[i];
    layers[n++] = err;
    return n;
}
