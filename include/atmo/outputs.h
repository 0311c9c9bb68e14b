/* outputs.h — the image files of a render from its mean image (host/render/outputs.c), shared
 * by `atmo render`, `atmo merge` and the viewer's saves, so that the same scene and samples
 * give the same files, bit for bit, whichever of them wrote them.
 *
 * Denoising (scene key output.denoise, atmo/denoise.h): the mean image goes through Intel Open
 * Image Denoise's "RT" filter, linear and HDR, before any post-processing, once per write for
 * every output that asks for it:
 *   auto      the PNG outputs of a path-traced scene or of a preview with more than the air
 *             (terrain, clouds, a cloud shell, objects, the observer), at quality high,
 *             where the library is installed (without it the images stay as rendered, and
 *             atmo_outputs_denoise_prepare says so in one line);
 *   off       none;
 *   fast, balanced, high  every output, at that quality; missing library: a usage error.
 * A denoised EXR holds the denoised image as R, G, B and, as layers named as Blender names its
 * denoising data, the noisy image ("Noisy Image.R/G/B") and the guides where the render has
 * them ("Denoising Albedo.R/G/B", "Denoising Normal.X/Y/Z", "Denoising Depth.Z"), so a
 * compositor can redo it. The filter uses the guides only when they are noise-free
 * (atmo_outputs_guides.clean): the guide pass's (atmo/guides.h), as clean auxiliary images
 * (OIDN's cleanAux); the path tracer's passes carry the image's own sampling noise on their
 * edges and are written as layers only. The sun's disc is kept out of the filter where the
 * guides say where it is (the pixels with disc > 0 enter it clamped to the brightest pixel
 * without the disc, and the rest is added back after), so the filter does not spread it. */
#ifndef ATMO_OUTPUTS_H
#define ATMO_OUTPUTS_H
#include <cjson/cJSON.h>
#include "atmo/image.h"
#include "atmo/render.h"
#include "atmo/scene.h"
#include "atmo/status.h"

/* The display pipeline of `scene` for PNG: its post.* settings and the sun's white point
 * (atmo_solar_white_point). */
void atmo_outputs_post(const atmo_scene *scene, atmo_post *post);

/* The denoiser's guides, 3 floats per pixel (depth: 1), row 0 = top (atmo/denoise.h says what
 * OIDN expects of them). */
typedef struct atmo_outputs_guides {
    const float *albedo;
    const float *normal;
    const float *depth; /* written as a layer only; may be NULL */
    const float *disc;  /* share of each pixel's guide rays that see the sun's disc; may be
                           NULL */
    int clean;          /* 1: free of noise: the filter uses them (cleanAux); 0: they are
                           written as EXR layers only (noisy guides made the denoised image
                           worse, docs/denoise.md) */
} atmo_outputs_guides;

/* What the denoising of one write did, for the run report. */
typedef struct atmo_outputs_denoise {
    int applied;        /* 1 when at least one output holds the denoised image */
    int quality;        /* ATMO_DENOISE_* (when applied) */
    int guided;         /* 1: albedo and normal guides */
    int clean_aux;
    int version;        /* OIDN's, major * 10000 + minor * 100 + patch (0: not loaded) */
    double seconds;     /* the filter, device creation included */
    int sun_disc_kept;  /* 1: the sun's disc was kept out of the filter (guides' disc) */
    double guide_seconds; /* the guide pass (set by the caller that rendered it) */
} atmo_outputs_denoise;

/* The run report's "denoise" object: the setting, whether it was applied, and how (quality,
 * guides, the library's version and file, seconds). NULL when out of memory. */
cJSON *atmo_outputs_denoise_json(const atmo_scene *scene, const atmo_outputs_denoise *info);

/* Before a render: with output.denoise = auto and a PNG among outputs[0..n-1] that it
 * denoises, load the library;
 * when it is not installed, write one warning line into warning (else warning = ""): the
 * writes then leave the images as rendered. With an explicit quality, load it: ATMO_ERR_USAGE
 * with how to install it when it is missing. A library that is found but fails:
 * ATMO_ERR_RUNTIME. */
int atmo_outputs_denoise_prepare(const atmo_scene *scene, const char *const *outputs, int n,
                                 char *warning, int warning_size, atmo_err *e);

/* The guides of a result: the guide pass's (r->guides, atmo/guides.h; clean) where the render
 * made one, else those of a path-mode result with render passes (the primary hit's albedo,
 * normal and depth averaged over the pixel's samples; not clean), in OIDN's conventions: a
 * sample that escapes (to the sky, or scattered in a volume cloud before any surface) counts as
 * albedo 1 and normal 0; its share of the pixel is the mean depth over 1e10 m (the passes'
 * no-hit depth). The passes' guides live in *block (malloc'd; the caller frees it; NULL for
 * the guide pass's, which stay r's). Returns 0 and no guides for a result with neither, 1 with
 * guides, -1 when out of memory. */
int atmo_outputs_guides_from_passes(const atmo_render_result *r, atmo_outputs_guides *g,
                                    float **block);

/* Whether output.denoise denoises some of outputs[0..n-1] (the library aside). */
int atmo_outputs_any_denoised(const atmo_scene *scene, const char *const *outputs, int n);

/* Whether a render of `scene` to outputs[0..n-1] wants the guide pass: some output is denoised,
 * the library is loaded (after atmo_outputs_denoise_prepare) and atmo_guides_apply(scene). */
int atmo_outputs_want_guides(const atmo_scene *scene, const char *const *outputs, int n);

/* Denoise the W x H x 3 linear image rgb into out (quality ATMO_DENOISE_*, guides may be NULL)
 * as the writes do: guided only by clean guides, the sun's disc kept out of the filter. */
int atmo_outputs_denoise_rgb(const float *rgb, int width, int height,
                             const atmo_outputs_guides *guides, int quality, float *out,
                             atmo_err *e);

/* Write img (the mean image of `scene`) to each of outputs[0..n-1]: denoised as
 * output.denoise says (guides may be NULL: the colour alone), post-processing and the files'
 * description from the scene (post.*, render.quantity, wavelengths or spectral bands),
 * samples_min samples per pixel, marked partial when `partial`; EXR files with the codec
 * exr_compression (ATMO_EXR_*). info (may be NULL) receives what the denoising did. */
int atmo_outputs_write_denoised(const atmo_scene *scene, const atmo_image *img,
                                const atmo_outputs_guides *guides, int samples_min, int partial,
                                int exr_compression, const char *const *outputs, int n,
                                atmo_outputs_denoise *info, atmo_err *e);

/* atmo_outputs_write_denoised without guides or report. */
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
