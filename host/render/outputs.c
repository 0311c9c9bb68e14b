/* outputs.c — the image files of a render from its mean image (atmo/outputs.h).
 *
 * PNG goes through atmo_post with the scene's post.* settings and the sun's white point
 * (colour.h); the linear formats take the values as they are. Every file carries the same
 * description: the quantity (spectral radiance at the three wavelengths, luminance, or the
 * spectral mode's luminance from N bands), its unit, whether R, G, B are linear Rec.709 colour
 * (both luminance modes) or samples at wavelengths (radiance), the samples per pixel and
 * whether the render is partial. With output.blender the EXR files also carry the World
 * settings of atmo_outputs_blender_world (docs/guide/blender.md derives them). Denoising
 * (output.denoise) runs once per write, on the linear mean image, and the outputs that ask for
 * it get the denoised image (outputs.h). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/clock.h"
#include "atmo/colour.h"
#include "atmo/denoise.h"
#include "atmo/gpu_path.h"
#include "atmo/guides.h"
#include "atmo/outputs.h"

/* the path tracer's depth of a sample that hits nothing (kernels/render/path.h) */
#define OUTPUTS_NO_HIT_DEPTH_M 1e10f
/* the denoising layers of an EXR beside the image's own */
#define OUTPUTS_DENOISE_LAYERS 4
#define OUTPUTS_MAX_LAYERS 32

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

/* Whether the scene's image carries Monte Carlo noise that the filter is for: every path-traced
 * image, and a preview with anything beyond the air (terrain, procedural or a heightmap file,
 * which implies it; the cloud layer or shell, objects, the observer). The preview of the air
 * alone is smooth (its jittered segments leave about 1 % of noise), so the filter would cost
 * seconds beside a render of a fraction of one and gain nothing (docs/guide/denoise.md). */
static int scene_noisy(const atmo_scene *scene)
{
    return scene->path.mode == ATMO_RENDER_PATH || scene->terrain.enabled || scene->dem.file[0] ||
           scene->clouds.enabled || scene->cloud.enabled || scene->objects.count > 0 ||
           scene->observer.enabled;
}

/* Whether output `path` gets the denoised image under output.denoise. auto: the PNGs of a
 * noisy scene (scene_noisy): the image to look at, where the filter lowers the error against
 * the converged image (the default render's by 1.5x, its guide pass a quarter of the render's
 * time), while the linear files stay the rendered data a measurement works from
 * (docs/guide/denoise.md). */
static int output_denoised(const atmo_scene *scene, const char *path)
{
    if (scene->output.denoise == ATMO_OUTPUT_DENOISE_AUTO)
        return atmo_image_format_from_path(path) == ATMO_IMAGE_PNG && scene_noisy(scene);
    return scene->output.denoise != ATMO_OUTPUT_DENOISE_OFF;
}

int atmo_outputs_any_denoised(const atmo_scene *scene, const char *const *outputs, int n)
{
    int any = 0;
    for (int i = 0; i < n; i++)
        any |= output_denoised(scene, outputs[i]);
    return any;
}

/* ATMO_DENOISE_* of output.denoise (auto: high, OIDN's own default quality) */
static int denoise_quality(const atmo_scene *scene)
{
    switch (scene->output.denoise) {
    case ATMO_OUTPUT_DENOISE_FAST: return ATMO_DENOISE_FAST;
    case ATMO_OUTPUT_DENOISE_BALANCED: return ATMO_DENOISE_BALANCED;
    default: return ATMO_DENOISE_HIGH;
    }
}

int atmo_outputs_denoise_prepare(const atmo_scene *scene, const char *const *outputs, int n,
                                 char *warning, int warning_size, atmo_err *e)
{
    warning[0] = 0;
    if (!atmo_outputs_any_denoised(scene, outputs, n))
        return ATMO_OK;
    atmo_err le = {{0}};
    int rc = atmo_denoise_load(&le);
    if (rc == ATMO_ERR_USAGE && scene->output.denoise == ATMO_OUTPUT_DENOISE_AUTO) {
        snprintf(warning, (size_t)warning_size,
                 "warning: not denoising (output.denoise=auto): %s; or --denoise off", le.msg);
        return ATMO_OK;
    }
    if (rc)
        return atmo_fail(e, rc, "output.denoise=%s: %s",
                         scene->output.denoise == ATMO_OUTPUT_DENOISE_AUTO
                             ? "auto"
                             : atmo_denoise_quality_name(denoise_quality(scene)),
                         le.msg);
    return ATMO_OK;
}

cJSON *atmo_outputs_denoise_json(const atmo_scene *scene, const atmo_outputs_denoise *info)
{
    static const char *const settings[] = {"auto", "off", "fast", "balanced", "high"};
    cJSON *d = cJSON_CreateObject();
    if (!d)
        return NULL;
    cJSON_AddStringToObject(d, "setting", settings[scene->output.denoise]);
    cJSON_AddBoolToObject(d, "applied", info->applied);
    if (info->applied) {
        char version[32];
        snprintf(version, sizeof version, "%d.%d.%d", info->version / 10000,
                 info->version / 100 % 100, info->version % 100);
        cJSON_AddStringToObject(d, "library", "Intel Open Image Denoise");
        cJSON_AddStringToObject(d, "library_version", version);
        cJSON_AddStringToObject(d, "library_file", atmo_denoise_library_path());
        cJSON_AddStringToObject(d, "filter", "RT, hdr");
        cJSON_AddStringToObject(d, "quality", atmo_denoise_quality_name(info->quality));
        cJSON_AddStringToObject(d, "guides", info->guided ? "albedo, normal" : "none");
        cJSON_AddBoolToObject(d, "clean_aux", info->clean_aux);
        cJSON_AddBoolToObject(d, "sun_disc_kept_out", info->sun_disc_kept);
        cJSON_AddNumberToObject(d, "seconds", info->seconds);
        if (info->guided)
            cJSON_AddNumberToObject(d, "guide_pass_seconds", info->guide_seconds);
    }
    return d;
}

int atmo_outputs_guides_from_passes(const atmo_render_result *r, atmo_outputs_guides *g,
                                    float **block)
{
    memset(g, 0, sizeof *g);
    *block = NULL;
    if (r->guides) {
        size_t pixels = (size_t)r->width * r->height;
        g->albedo = r->guides;
        g->normal = r->guides + 3 * pixels;
        g->depth = r->guides + 6 * pixels;
        g->disc = r->guides + 7 * pixels;
        g->clean = 1;
        return 1;
    }
    if (r->pass_planes < ATMO_PATH_PASS_PLANES || !r->passes)
        return 0;
    size_t pixels = (size_t)r->width * r->height;
    float *data = malloc(sizeof(float) * 7 * pixels);
    if (!data)
        return -1;
    *block = data;
    float *albedo = data, *normal = data + 3 * pixels, *depth = data + 6 * pixels;
    const float *np = r->passes + 4 * pixels * ATMO_PATH_LIGHT_PASSES;
    const float *ap = r->passes + 4 * pixels * (ATMO_PATH_LIGHT_PASSES + 1);
    for (size_t i = 0; i < pixels; i++) {
        float escaped = np[4 * i + 3] / OUTPUTS_NO_HIT_DEPTH_M;
        escaped = escaped < 0.0f ? 0.0f : escaped > 1.0f ? 1.0f : escaped;
        for (int c = 0; c < 3; c++) {
            float a = ap[4 * i + c] + escaped;
            albedo[3 * i + c] = a < 0.0f ? 0.0f : a > 1.0f ? 1.0f : a;
            normal[3 * i + c] = np[4 * i + c];
        }
        depth[i] = np[4 * i + 3];
    }
    g->albedo = albedo;
    g->normal = normal;
    g->depth = depth;
    g->clean = 0;
    return 1;
}

/* img's layers and the denoising layers (the noisy image, the guides) into layers[]; returns
 * their count. */
static int denoise_layers(const atmo_image *img, const float *noisy,
                          const atmo_outputs_guides *guides, atmo_image_layer *layers)
{
    int n = 0;
    for (int i = 0; i < img->layer_count && n < OUTPUTS_MAX_LAYERS - OUTPUTS_DENOISE_LAYERS; i++)
        layers[n++] = img->layers[i];
    layers[n++] = (atmo_image_layer){"Noisy Image", 3, {"R", "G", "B", NULL}, noisy, 0};
    if (guides && guides->albedo) {
        layers[n++] = (atmo_image_layer){"Denoising Albedo", 3, {"R", "G", "B", NULL},
                                         guides->albedo, 0};
        layers[n++] = (atmo_image_layer){"Denoising Normal", 3, {"X", "Y", "Z", NULL},
                                         guides->normal, 0};
    }
    if (guides && guides->depth)
        layers[n++] = (atmo_image_layer){"Denoising Depth", 1, {"Z", NULL, NULL, NULL},
                                         guides->depth, 0};
    return n;
}

int atmo_outputs_want_guides(const atmo_scene *scene, const char *const *outputs, int n)
{
    return atmo_outputs_any_denoised(scene, outputs, n) && atmo_denoise_version() > 0 &&
           atmo_guides_apply(scene);
}

/* The brightest value of each channel over the pixels whose guide rays miss the sun's disc. */
static void brightest_without_disc(const float *rgb, const float *disc, size_t pixels,
                                   float top[3])
{
    top[0] = top[1] = top[2] = 0.0f;
    for (size_t i = 0; i < pixels; i++)
        for (int c = 0; c < 3 && disc[i] == 0.0f; c++)
            top[c] = rgb[3 * i + c] > top[c] ? rgb[3 * i + c] : top[c];
}

int atmo_outputs_denoise_rgb(const float *rgb, int width, int height,
                             const atmo_outputs_guides *guides, int quality, float *out,
                             atmo_err *e)
{
    size_t pixels = (size_t)width * height;
    /* noisy guides are written as layers but kept from the filter: guides whose edges carry
     * the image's own sampling noise make OIDN keep that noise (docs/guide/denoise.md) */
    int guided = guides && guides->albedo && guides->normal && guides->clean;
    const float *disc = guides ? guides->disc : NULL;
    float *base = disc ? malloc(sizeof(float) * 3 * pixels) : NULL;
    if (disc && !base)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory for the denoiser's input");
    float top[3];
    if (disc) { /* the disc's pixels enter clamped; what lies above is added back after */
        brightest_without_disc(rgb, disc, pixels, top);
        for (size_t i = 0; i < 3 * pixels; i++)
            base[i] = disc[i / 3] > 0.0f && rgb[i] > top[i % 3] ? top[i % 3] : rgb[i];
    }
    atmo_denoise_input in = {width, height, disc ? base : rgb,
                             guided ? guides->albedo : NULL, guided ? guides->normal : NULL,
                             guided, quality};
    int rc = atmo_denoise_run(&in, out, e);
    for (size_t i = 0; !rc && disc && i < 3 * pixels; i++)
        out[i] += rgb[i] - base[i];
    free(base);
    return rc;
}

/* The denoised image of img into *out (malloc'd), and what was done into *info. */
static int denoise_image(const atmo_scene *scene, const atmo_image *img,
                         const atmo_outputs_guides *guides, float **out,
                         atmo_outputs_denoise *info, atmo_err *e)
{
    size_t floats = 3 * (size_t)img->width * img->height;
    int guided = guides && guides->albedo && guides->normal && guides->clean;
    if (!(*out = malloc(sizeof(float) * floats)))
        return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory for the denoised image");
    double t0 = atmo_now_seconds();
    int rc = atmo_outputs_denoise_rgb(img->rgb, img->width, img->height, guides,
                                      denoise_quality(scene), *out, e);
    *info = (atmo_outputs_denoise){!rc, denoise_quality(scene), guided, guided,
                                   atmo_denoise_version(), atmo_now_seconds() - t0,
                                   !rc && guides && guides->disc, 0.0};
    return rc;
}

int atmo_outputs_write_denoised(const atmo_scene *scene, const atmo_image *img,
                                const atmo_outputs_guides *guides, int samples_min, int partial,
                                int exr_compression, const char *const *outputs, int n,
                                atmo_outputs_denoise *info, atmo_err *e)
{
    int spectral = scene->render.spectral_bands > 0, rc = ATMO_OK;
    atmo_outputs_denoise done = {0};
    float *denoised = NULL;
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
    char denoise_note[128];
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
    /* name-value pairs: the Blender World settings (output.blender), then the denoising note */
    const char *attributes[6] = {"blenderWorldStrength", strength_text, "blenderWhiteBalance",
                                 colour_text};
    int n_attributes = 0;
    if (atmo_outputs_blender_world(scene, &strength, colour)) {
        snprintf(strength_text, sizeof strength_text, "%.6g", strength);
        snprintf(colour_text, sizeof colour_text, "%.6g %.6g %.6g", colour[0], colour[1],
                 colour[2]);
        n_attributes = 2;
    }
    meta.attributes = attributes;
    meta.attribute_count = n_attributes;
    if (atmo_outputs_any_denoised(scene, outputs, n)) {
        atmo_err le = {{0}};
        int load = atmo_denoise_load(&le);
        /* auto without the library: the outputs as rendered */
        int skip = load == ATMO_ERR_USAGE && scene->output.denoise == ATMO_OUTPUT_DENOISE_AUTO;
        if (load && !skip)
            rc = atmo_fail(e, load, "output.denoise: %s", le.msg);
        else if (!load)
            rc = denoise_image(scene, img, guides, &denoised, &done, e);
    }
    attributes[2 * n_attributes] = "denoise";
    attributes[2 * n_attributes + 1] = denoise_note;
    if (done.applied)
        snprintf(denoise_note, sizeof denoise_note,
                 "Intel Open Image Denoise %d.%d.%d, RT filter, quality %s, %s", done.version / 10000,
                 done.version / 100 % 100, done.version % 100, atmo_denoise_quality_name(done.quality),
                 done.guided ? "albedo and normal guides (clean)" : "no guides");
    for (int i = 0; i < n && !rc; i++) {
        atmo_image out = *img;
        atmo_image_layer layers[OUTPUTS_MAX_LAYERS];
        atmo_image_meta m = meta;
        if (denoised && output_denoised(scene, outputs[i])) {
            out.rgb = denoised;
            out.layer_count = denoise_layers(img, img->rgb, guides, layers);
            out.layers = layers;
            m.attribute_count = n_attributes + 1;
        }
        rc = atmo_image_write(outputs[i], &out, &post, &m, e);
    }
    free(denoised);
    if (info)
        *info = done;
    return rc;
}

int atmo_outputs_write(const atmo_scene *scene, const atmo_image *img, int samples_min,
                       int partial, int exr_compression, const char *const *outputs, int n,
                       atmo_err *e)
{
    return atmo_outputs_write_denoised(scene, img, NULL, samples_min, partial, exr_compression,
                                       outputs, n, NULL, e);
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
