/* render_passes.h — the path tracer's render passes as EXR layers (render_passes.c). */
#ifndef ATMO_CLI_RENDER_PASSES_H
#define ATMO_CLI_RENDER_PASSES_H
#include "atmo/image.h"
#include "atmo/render.h"
#include "atmo/gpu_path.h"

/* the light passes, then Normal, Depth, DiffCol, Samples and Error */
#define RENDER_PASS_LAYERS (ATMO_PATH_LIGHT_PASSES + 5)

/* The layers of a result with passes, into layers[RENDER_PASS_LAYERS]; their data lives in
 * *block (malloc'd; the caller frees it). Returns the number of layers, 0 for a result without
 * passes, -1 when out of memory. */
int render_pass_layers(const atmo_render_result *r, atmo_image_layer *layers, float **block);

#endif
