/* cmd_render.c — `atmo render`: scene -> plan -> device -> images and a run report.
 *
 * Scene assembly, in this order: the defaults; --preset NAME (default: atmo_default_preset) or
 * --scene FILE; then --set KEY=VALUE and the shorthands (--width, --height, --samples, --seed,
 * --time, --camera) in command-line order. Every output's format and path is checked before
 * anything runs (output_paths.h: directory, name, limits, no two outputs in one file; an
 * existing file only with --force, overwrite.h), so a bad argument never costs a render. The
 * flags are one table (cli_flags.h), from which --help is generated with every default. With
 * atmosphere.method = auto (the default) the plan picks the method (atmo_plan_auto_method);
 * unless --quiet, the cost line before the work names it and says why, and the run report
 * records it (render.method, render.method_auto).
 *
 * Interrupts: the first SIGINT, SIGTERM or SIGHUP (the terminal closed) sets the render's cancel
 * token; the precompute or the render stops after the launch in flight. Samples already rendered are written, marked
 * partial (report "interrupted", file metadata), and the exit status is 3; stopped before any
 * sample (in the precompute, or in a spectral render's triplets), nothing is written and the
 * exit status is 4. A signal while the files are written lets the writing finish (the image is
 * whole). A second signal removes the temporary file being written and ends the process by
 * that signal at once (exit status 128 + its number: 130 SIGINT, 143 SIGTERM, 129 SIGHUP).
 * Exit statuses: 0 done, 1 runtime error, 2 usage, 3 interrupted with a partial image written,
 * 4 interrupted with nothing written. */
#include <cjson/cJSON.h>
#include <stddef.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "atmo/cl_runtime.h"
#include "atmo/clock.h"
#include "atmo/colour.h"
#include "atmo/fileio.h"
#include "atmo/flare.h"
#include "atmo/image.h"
#include "atmo/part.h"
#include "atmo/plan.h"
#include "atmo/plan_terrain.h"
#include "atmo/render.h"
#include "atmo/scene.h"
#include "atmo/spectral_render.h"
#include "cli_flags.h"
#include "commands.h"
#include "frames.h"
#include "output_paths.h"
#include "render_passes.h"
#include "run_report.h"
#include "overwrite.h"
#include "scene_options.h"
#include "atmo/outputs.h"

#define RENDER_MAX_OUTPUTS 8

/* The flags' destinations (render_flags), holding the defaults before parsing. */
typedef struct render_args {
    scene_options so;
    atmo_render_settings rs;
    const char *outputs[RENDER_MAX_OUTPUTS];
    int n_out;
    const char *report, *save_scene, *part_text, *frames_text, *scene_end;
    const char *animate[FRAMES_MAX_KEYS];
    int n_animate;
    int quiet, force, no_kernel_cache, no_lut_cache, exr_codec;
    int first, step; /* the frames this process renders: first, first + step, ... */
} render_args;

static const char *const render_exr_codecs[] = {"piz", "none", "zip", "zips", "rle", NULL};

/* --noise: "1%" or a fraction "0.01", in (0, 1]. */
static int parse_noise(const char *v, double *out, atmo_err *e)
{
    char *end;
    double x = strtod(v, &end);
    if (end != v && *end == '%' && end[1] == 0)
        x /= 100.0;
    else if (end == v || *end != 0)
        x = -1.0;
    if (!(x > 0.0 && x <= 1.0))
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "--noise needs a relative standard error such as 1%% or 0.01 (above 0, "
                         "at most 100%%), got '%s'",
                         v);
    *out = x;
    return ATMO_OK;
}

static int take_noise(void *args, const cli_flag *f, const char *v, atmo_err *e)
{
    (void)f;
    return parse_noise(v, &((render_args *)args)->rs.noise_target, e);
}

#define RENDER_FLAG(member) offsetof(render_args, member)

static const cli_flag render_flags[] = {
    {.type = CLI_SECTION, .help = "scene:"},
    {.type = CLI_INCLUDE, .include = scene_option_flags, .offset = RENDER_FLAG(so)},
    {.type = CLI_PATH, .name = "--save-scene", .offset = RENDER_FLAG(save_scene), .def = "none",
     .help = "write the fully resolved scene as JSON (rendering it reproduces\n"
             "the image bit for bit); without --output nothing is rendered"},
    {.type = CLI_SECTION, .help = "output:"},
    {.type = CLI_PATH, .name = "--output", .alias = "-o", .offset = RENDER_FLAG(outputs),
     .repeat = RENDER_MAX_OUTPUTS, .count_offset = RENDER_FLAG(n_out), .def = "atmo.png",
     .help = "image to write, format from the extension (repeatable)"},
    {.type = CLI_BOOL, .name = "--force", .offset = RENDER_FLAG(force),
     .help = "overwrite outputs that exist (without it an existing file is an\nerror)"},
    {.type = CLI_PATH, .name = "--report", .offset = RENDER_FLAG(report), .def = "none",
     .help = "JSON run report: settings, device, samples, stage timings"},
    {.type = CLI_ENUM, .name = "--exr-compression", .offset = RENDER_FLAG(exr_codec),
     .choices = render_exr_codecs,
     .help = "EXR codec, all lossless: piz is the smallest, none the fastest\n(2x the size)"},
    {.type = CLI_SECTION, .help = "progressive (every render, path mode included):"},
    {.type = CLI_STRING, .name = "--noise", .metavar = "P", .take = take_noise, .def = "off",
     .help = "stop each tile once its relative standard error is at most P\n"
             "(e.g. 1% or 0.01; checked at 16, 32, 64, ... samples); the\n"
             "image.samples are the most any tile gets"},
    {.type = CLI_FLOAT, .name = "--time-limit", .metavar = "S", .min = 0.0, .max = 1e7,
     .open_min = 1, .offset = RENDER_FLAG(rs.time_limit_s), .def = "none",
     .help = "no new launch after S seconds; the image has what was rendered"},
    {.type = CLI_SECTION, .help = "device:"},
    {.type = CLI_STRING, .name = "--device", .metavar = "N|NAME", .offset = RENDER_FLAG(rs.device),
     .def = "$ATMO_DEVICE, else the first GPU, else the first device",
     .help = "OpenCL device by index or name part (atmo devices)"},
    {.type = CLI_INT, .name = "--tile-size", .min = 8, .max = 4096,
     .offset = RENDER_FLAG(rs.tile_size), .help = "tile edge in pixels"},
    {.type = CLI_FLOAT, .name = "--launch-budget-ms", .metavar = "MS", .min = 1.0, .max = 1e5,
     .offset = RENDER_FLAG(rs.launch_budget_ms), .help = "time per kernel launch to aim for"},
    {.type = CLI_PATH, .name = "--dump-kernels", .metavar = "DIR", .offset = RENDER_FLAG(rs.dump_dir),
     .def = "none", .help = "write the assembled OpenCL source to DIR"},
    {.type = CLI_BOOL, .name = "--no-kernel-cache", .offset = RENDER_FLAG(no_kernel_cache),
     .help = "always compile the kernels (cache: ATMO_CACHE_DIR or ~/.cache/atmo)"},
    {.type = CLI_BOOL, .name = "--no-lut-cache", .offset = RENDER_FLAG(no_lut_cache),
     .help = "always precompute LUTs and Mie tables, and store none (LUTs that\n"
             "take over 20 ms and Mie tables are cached)"},
    {.type = CLI_BOOL, .name = "--quiet", .alias = "-q", .offset = RENDER_FLAG(quiet),
     .help = "no progress output"},
    {.type = CLI_SECTION, .help = "split and animate (docs: rendering on a cluster):"},
    {.type = CLI_STRING, .name = "--part", .metavar = "I/N", .offset = RENDER_FLAG(part_text),
     .def = "the whole image",
     .help = "render part I of N of the image (its rows in bands of 8, band b\n"
             "in part b mod N + 1) into one --output FILE.exr of raw sums;\n"
             "atmo merge joins the N parts into the image of a single render"},
    {.type = CLI_STRING, .name = "--frames", .metavar = "A..B", .offset = RENDER_FLAG(frames_text),
     .def = "one image, not numbered",
     .help = "render frames A to B; each output NAME.EXT becomes NAME.0001.EXT\n"
             "...; with --part I/N, part I renders frames A+I-1, A+I-1+N, ..."},
    {.type = CLI_STRING, .name = "--animate", .metavar = "KEY=V0..V1", .offset = RENDER_FLAG(animate),
     .repeat = FRAMES_MAX_KEYS, .count_offset = RENDER_FLAG(n_animate), .def = "none",
     .help = "move a float key linearly from V0 (frame A) to V1 (frame B)"},
    {.type = CLI_PATH, .name = "--scene-end", .offset = RENDER_FLAG(scene_end), .def = "none",
     .help = "move every float and vector key in which the end scene differs\n"
             "from the start: the --preset (none with --scene), FILE, then\n"
             "the same --set options"},
    {.type = CLI_END},
};

static const cli_command render_cli = {
    .name = "render",
    .synopsis = "[--preset NAME | --scene FILE] [--set KEY=VALUE ...] [options]",
    .about =
        "Renders a scene and writes one image per --output (format from the extension):\n"
        "  .png  8-bit sRGB after white balance, exposure and tone mapping (post.*)\n"
        "  .hdr  Radiance RGBE, linear     .exr  OpenEXR 32-bit float, linear\n"
        "  .pfm  portable float map, linear\n"
        "Linear outputs hold spectral radiance (W m^-2 sr^-1 nm^-1) at render.wavelengths_nm, or\n"
        "luminance (cd/m^2) with --set render.quantity=luminance. With --set render.spectral_bands=N\n"
        "(N >= 15) the scene is rendered at N wavelengths over 360-830 nm, three at a time, and\n"
        "combined through the CIE 1931 colour matching functions into linear sRGB (cd/m^2).\n"
        "For Blender (a World environment texture) use --blender: linear Rec.709 RGB (cd/m^2)\n"
        "with the EXR chromaticities, panoramas in Blender's world orientation, and the World\n"
        "strength that matches the PNG's exposure, printed and stored in the EXR\n"
        "(docs/guide/blender.md).\n"
        "An output that exists is not replaced unless --force is given.\n",
    .flags = render_flags,
    .scene_preset = &atmo_default_preset,
    .epilogue =
        "Ctrl-C (SIGINT), SIGTERM or SIGHUP stops the precompute or the render after the launch in\n"
        "flight: the samples finished so far are written, marked partial, with exit status 3;\n"
        "stopped before any sample, nothing is written and the exit status is 4. A second signal\n"
        "stops at once and removes the file being written; the process ends by that signal (the\n"
        "shell shows 128 + its number: 130 for SIGINT, 143 SIGTERM, 129 SIGHUP).\n"
        "Exit statuses: 0 done, 1 runtime error, 2 usage or input error (nothing is rendered),\n"
        "3 interrupted with a partial image, 4 interrupted with nothing written.\n",
};
/* What the signal handler uses: a handler takes no user data, so this file holds the one token
 * that the render it starts is given (atmo_render_settings.cancel), and the temporary names of
 * the outputs (atmo_tmp_path), computed before the handler is installed. */
#define HANDLED_SIGNALS 3
static atmo_cancel render_cancel;
static volatile sig_atomic_t signals_seen;
static char pending_tmp[OUTPUT_PATHS_MAX][ATMO_TMP_PATH_MAX];
static int pending_count;

/* Async-signal-safe: a store, unlink(2), signal(2) and raise(3). */
static void on_signal(int sig)
{
    if (signals_seen++ == 0) {
        atmo_cancel_request(&render_cancel);
        return;
    }
    for (int i = 0; i < pending_count; i++)
        unlink(pending_tmp[i]);
    signal(sig, SIG_DFL);
    raise(sig);
}

/* SIGINT, SIGTERM and SIGHUP to on_signal (install) or back to what they were. */
static void handle_signals(int install, struct sigaction old[HANDLED_SIGNALS])
{
    static const int sigs[HANDLED_SIGNALS] = {SIGINT, SIGTERM, SIGHUP};
    struct sigaction sa = {0};
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    for (int i = 0; i < HANDLED_SIGNALS; i++)
        sigaction(sigs[i], install ? &sa : &old[i], install ? &old[i] : NULL);
}

/* The report's render passes (the EXR layers' channels) and what the lens flare measured and
 * added. */
static void report_passes_and_flare(cJSON *ren, const atmo_scene *s,
                                    const atmo_image_layer *layers, int n_layers,
                                    const atmo_flare_info *flare)
{
    cJSON *passes = cJSON_AddArrayToObject(ren, "passes");
    for (int i = 0; i < n_layers; i++)
        for (int c = 0; c < layers[i].channels; c++) {
            char name[64];
            snprintf(name, sizeof name, "%s.%s", layers[i].name, layers[i].channel_names[c]);
            cJSON_AddItemToArray(passes, cJSON_CreateString(name));
        }
    if (!s->post.flare)
        return;
    cJSON *fl = cJSON_AddObjectToObject(ren, "flare");
    cJSON_AddNumberToObject(fl, "sun_x_px", flare->sun_x);
    cJSON_AddNumberToObject(fl, "sun_y_px", flare->sun_y);
    cJSON *irr = cJSON_AddArrayToObject(fl, "sun_irradiance");
    cJSON *add = cJSON_AddArrayToObject(fl, "added_irradiance");
    for (int c = 0; c < 3; c++) {
        cJSON_AddItemToArray(irr, cJSON_CreateNumber(flare->irradiance[c]));
        cJSON_AddItemToArray(add, cJSON_CreateNumber(flare->added[c]));
    }
}

/* The name of the method the scene renders with; *why (NULL unless atmosphere.method = auto)
 * the plan's reason for its choice. */
static const char *method_name(const atmo_scene *s, const char **why)
{
    int m = s->atmosphere.method;
    *why = NULL;
    if (m == ATMO_METHOD_AUTO)
        m = atmo_plan_auto_method(s, why);
    return atmo_param_find("atmosphere.method")->names[m];
}

static int write_report(const char *path, const atmo_scene *s, const atmo_render_result *r,
                          const atmo_render_settings *rs, const char *const *outputs, int n_out,
                          double seconds_write, const atmo_image_layer *layers, int n_layers,
                          const atmo_flare_info *flare, const atmo_outputs_denoise *denoised,
                          atmo_err *e)
{
    cJSON *root = run_report_new(s);
    if (!root)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory writing the report '%s'", path);
    cJSON *dev = cJSON_AddObjectToObject(root, "device");
    cJSON_AddStringToObject(dev, "platform", r->platform_name);
    cJSON_AddStringToObject(dev, "name", r->device_name);
    cJSON_AddStringToObject(dev, "driver_version", r->driver_version);
    cJSON *ren = cJSON_AddObjectToObject(root, "render");
    cJSON_AddNumberToObject(ren, "width", r->width);
    cJSON_AddNumberToObject(ren, "height", r->height);
    const char *why;
    cJSON_AddStringToObject(ren, "method", method_name(s, &why));
    if (why)
        cJSON_AddStringToObject(ren, "method_auto", why);
    cJSON_AddNumberToObject(ren, "samples_requested", r->samples_requested);
    cJSON_AddNumberToObject(ren, "samples_min", r->samples_min);
    cJSON_AddNumberToObject(ren, "samples_max", r->samples_max);
    cJSON_AddBoolToObject(ren, "interrupted", r->interrupted);
    cJSON_AddNumberToObject(ren, "nonfinite_samples_dropped", r->nonfinite);
    cJSON_AddNumberToObject(ren, "launches", r->launches);
    cJSON_AddNumberToObject(ren, "noise_target", rs->noise_target);
    if (r->noise_tiles > 0) { /* the relative standard error each tile reached */
        cJSON *tiles = cJSON_AddArrayToObject(ren, "tiles_noise");
        for (int i = 0; i < r->noise_tiles; i++) {
            cJSON *t = cJSON_CreateObject();
            static const char *const keys[5] = {"x", "y", "w", "h", "samples"};
            for (int k = 0; k < 5; k++)
                cJSON_AddNumberToObject(t, keys[k], r->tile_rect[5 * i + k]);
            cJSON_AddNumberToObject(t, "noise", r->tile_noise[i]);
            cJSON_AddItemToArray(tiles, t);
        }
    }
    cJSON_AddNumberToObject(ren, "time_limit_s", rs->time_limit_s);
    cJSON_AddNumberToObject(ren, "tile_size", rs->tile_size);
    cJSON_AddNumberToObject(ren, "launch_budget_ms", rs->launch_budget_ms);
    cJSON_AddBoolToObject(ren, "kernel_cache_hit", r->kernel_cache_hit);
    cJSON_AddBoolToObject(ren, "lut_cache_hit", r->lut_cache_hit);
    cJSON_AddStringToObject(ren, "mode", s->render.spectral_bands ? "spectral" : "3-wavelength");
    cJSON_AddNumberToObject(ren, "spectral_bands", s->render.spectral_bands);
    cJSON_AddStringToObject(ren, "quantity",
                            s->render.spectral_bands ? "luminance, linear sRGB from the spectral "
                                                       "bands through the CIE 1931 CMFs (cd m^-2)"
                            : s->render.quantity == ATMO_QUANTITY_LUMINANCE
                                ? "luminance (cd m^-2)"
                                : "spectral radiance (W m^-2 sr^-1 nm^-1)");
    cJSON *t = cJSON_AddObjectToObject(root, "seconds");
    cJSON_AddNumberToObject(t, "device_init", r->seconds_device);
    cJSON_AddNumberToObject(t, "kernel_build", r->seconds_build);
    cJSON_AddNumberToObject(t, "precompute", r->seconds_precompute);
    cJSON_AddNumberToObject(t, "render", r->seconds_render);
    cJSON_AddNumberToObject(t, "read_back", r->seconds_read);
    cJSON_AddNumberToObject(t, "guides", r->seconds_guides);
    cJSON_AddNumberToObject(t, "write", seconds_write);
    report_passes_and_flare(ren, s, layers, n_layers, flare);
    cJSON *dn = atmo_outputs_denoise_json(s, denoised);
    if (dn)
        cJSON_AddItemToObject(ren, "denoise", dn);
    return run_report_write(root, outputs, n_out, path, e);
}

/* A camera under the terrain's surface (or the sea's) sees the ground from inside: one warning,
 * before the build and the precompute, with the camera's height and the surface's there, both
 * world Y in metres; the surface from the renderer's own heights (atmo_plan_terrain_surface_y:
 * a DEM's heightmap texels as the kernels read them, the procedural field in double). */
static void warn_camera_under_terrain(const atmo_plan *p, const atmo_scene *s)
{
    if (!atmo_plan_buffer_find((atmo_plan *)p, "heightmap"))
        return;
    double cam[3];
    atmo_plan_camera_world(p, s, cam);
    double ground = atmo_plan_terrain_surface_y(p, s->atmosphere.bottom_radius_m, cam[0], cam[2]);
    if (!(cam[1] < ground))
        return;
    int sea = atmo_plan_terrain_height(p, cam[0], cam[2]) <= (double)p->gpu.terrain.sea_level_m;
    fprintf(stderr,
            "atmo render: warning: the camera is under the %s: at x = %.1f, z = %.1f m its height "
            "is %.1f m and the %s's surface is at %.1f m; raise camera.position_m's y above it, "
            "or set camera.on_terrain=below to give y above the surface\n",
            sea ? "sea" : "terrain", cam[0], cam[2], cam[1], sea ? "sea" : "terrain", ground);
}

/* warn_camera_under_terrain for a spectral render, which plans each triplet of bands itself:
 * the terrain of a plan of its first triplet. */
static void warn_camera_under_terrain_spectral(const atmo_scene *scene, int lut_cache)
{
    atmo_scene first = *scene;
    atmo_plan plan;
    atmo_err e = {{0}};
    first.render.spectral_bands = 0;
    if (atmo_plan_make_cached(&first, lut_cache, lut_cache, &plan, &e))
        return; /* the render's own plan reports the error */
    warn_camera_under_terrain(&plan, scene);
    atmo_plan_free(&plan);
}

/* Render one scene (a frame) to res (or part): plan it, then install the signal handler (*old
 * gets the handlers it replaced, *installed 1), then render. The handler stays until the files
 * are written: a signal then lets the writing finish. Returns the status; an error leaves its
 * message in e. */
static int render_run(const render_args *a, const atmo_scene *scene, atmo_render_settings *rs,
                      int part_file, atmo_render_result *res, atmo_part *part,
                      struct sigaction old[HANDLED_SIGNALS], int *installed, atmo_err *e)
{
    int rc, lut_cache = !a->no_lut_cache;
    /* spectral mode plans each triplet of bands itself */
    int spectral = scene->render.spectral_bands > 0;
    atmo_plan plan;
    if (!spectral && (rc = atmo_plan_make_cached(scene, lut_cache, lut_cache, &plan, e)))
        return rc;
    if (spectral)
        warn_camera_under_terrain_spectral(scene, lut_cache);
    else
        warn_camera_under_terrain(&plan, scene);
    handle_signals(1, old);
    *installed = 1;
    char *scene_json = part_file ? atmo_scene_to_json(scene) : NULL;
    if (part_file && !scene_json)
        rc = atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory for the scene's text");
    else if (part_file && !(rc = atmo_part_alloc(part, plan.width, plan.height, rs->part,
                                                 rs->parts, scene_json, e)))
        rc = atmo_render_part(&plan, rs, res, part, e);
    else if (!part_file)
        rc = spectral ? atmo_spectral_render(scene, lut_cache, rs, res, e)
                      : atmo_render(&plan, rs, res, e);
    free(scene_json);
    if (!spectral)
        atmo_plan_free(&plan);
    if (rc == ATMO_OK && res->interrupted && res->samples_max == 0)
        rc = atmo_fail(e, ATMO_INTERRUPTED_EMPTY, "interrupted before the first sample");
    return rc;
}

/* post: the lens flare, on the linear image every output gets */
static void render_flare(const atmo_scene *scene, atmo_render_result *res, atmo_flare_info *flare)
{
    atmo_flare_camera fc = {.width = res->width, .height = res->height,
                            .tan_half_fov = tan(0.5 * scene->camera.fov_deg * M_PI / 180.0),
                            .sun_radius_rad = scene->sun.angular_radius_deg * M_PI / 180.0};
    atmo_camera_basis(scene->camera.pitch_deg, scene->camera.yaw_deg, fc.forward, fc.right,
                      fc.up);
    atmo_sun_direction(scene->sun.zenith_deg, scene->sun.azimuth_deg, fc.sun);
    atmo_flare_apply(res->rgb, &fc, scene->post.flare_strength, flare);
}

/* outputs: the images with the render passes as EXR layers, or the part's raw sums; then the
 * report. *seconds_write gets the images' time. */
static int render_write(const render_args *a, const atmo_scene *scene,
                        const atmo_render_settings *rs, const atmo_render_result *res,
                        const atmo_part *part, const atmo_flare_info *flare,
                        const char *const *outputs, int n_out, const char *report,
                        double *seconds_write, atmo_err *e)
{
    int rc, part_file = part->width > 0;
    double tw = atmo_now_seconds();
    atmo_image img = {.width = res->width, .height = res->height, .rgb = res->rgb};
    atmo_image_layer layers[RENDER_PASS_LAYERS];
    float *layer_data = NULL, *guide_data = NULL;
    atmo_outputs_guides guides;
    atmo_outputs_denoise denoised = {0};
    img.layer_count = part_file ? 0 : render_pass_layers(res, layers, &layer_data);
    img.layers = layers;
    int exr = atmo_exr_compression_from_name(render_exr_codecs[a->exr_codec]);
    if (img.layer_count < 0 || atmo_outputs_guides_from_passes(res, &guides, &guide_data) < 0)
        rc = atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory for the render passes");
    else
        rc = part_file ? atmo_part_write(outputs[0], part, e)
                       : atmo_outputs_write_denoised(scene, &img, &guides, res->samples_min,
                                                     res->interrupted, exr, outputs, n_out,
                                                     &denoised, e);
    denoised.guide_seconds = res->seconds_guides;
    *seconds_write = atmo_now_seconds() - tw;
    if (!rc && report)
        rc = write_report(report, scene, res, rs, outputs, n_out, *seconds_write, img.layers,
                          img.layer_count > 0 ? img.layer_count : 0, flare, &denoised, e);
    free(guide_data);
    free(layer_data);
    return rc;
}

/* "wrote 1 image (16x8, 1 sample/pixel) in 0.42s: ..." */
static void render_summary(const atmo_render_result *res, int n_out, int spectral,
                           double seconds_write)
{
    fprintf(stderr, "atmo render: wrote %d image%s (%dx%d, %d sample%s/pixel%s) in %.2fs: "
                    "%.2fs device, %.2fs build%s, %.2fs precompute%s, %.2fs render, %.2fs "
                    "read-back, %.2fs denoiser's guides, %.2fs write on %s\n",
            n_out, n_out == 1 ? "" : "s", res->width, res->height, res->samples_min,
            res->samples_min == 1 ? "" : "s", spectral ? ", spectral mode" : "",
            res->seconds_device + res->seconds_build + res->seconds_precompute +
                res->seconds_render + res->seconds_read + res->seconds_guides + seconds_write,
            res->seconds_device, res->seconds_build, res->kernel_cache_hit ? " (cached)" : "",
            res->seconds_precompute, res->lut_cache_hit ? " (cached)" : "", res->seconds_render,
            res->seconds_read, res->seconds_guides, seconds_write, res->device_name);
}

/* Render one scene (a frame) and write its files: the images, or with part_file the part's raw
 * sums (outputs[0]); then the report. Returns the exit status; errors are printed. */
static int render_frame(const render_args *a, const atmo_scene *scene, int part_file,
                        const char *const *outputs, int n_out, const char *report)
{
    atmo_err e = {{0}};
    atmo_render_settings rs = a->rs;
    atmo_render_result res = {0};
    atmo_part part = {0};
    atmo_flare_info flare = {0};
    double seconds_write = 0.0;

    atmo_cancel_clear(&render_cancel);
    signals_seen = 0;
    pending_count = 0;
    for (int i = 0; i < n_out; i++)
        atmo_tmp_path(outputs[i], pending_tmp[pending_count++]);
    if (report)
        atmo_tmp_path(report, pending_tmp[pending_count++]);
    rs.cancel = &render_cancel;
    rs.guides = !part_file && atmo_outputs_want_guides(scene, outputs, n_out);
    struct sigaction old[HANDLED_SIGNALS];
    int installed = 0;
    int rc = render_run(a, scene, &rs, part_file, &res, &part, old, &installed, &e);
    if (rc == ATMO_INTERRUPTED_EMPTY) /* interrupted before any result */
        fprintf(stderr, "atmo render: %s; no image written (exit status %d)\n", e.msg, rc);
    if (!rc && res.interrupted)
        fprintf(stderr, "atmo render: interrupted; writing %d to %d of %d samples per pixel "
                        "(exit status %d)\n",
                res.samples_min, res.samples_max, res.samples_requested,
                ATMO_INTERRUPTED_PARTIAL);
    if (!rc && res.nonfinite)
        fprintf(stderr, "atmo render: warning: %u non-finite sample%s dropped (a bug; "
                        "please report it with the scene)\n",
                res.nonfinite, res.nonfinite == 1 ? " was" : "s were");
    if (!rc && !part_file && scene->post.flare && scene->camera.kind == ATMO_CAMERA_PERSPECTIVE)
        render_flare(scene, &res, &flare);
    if (!rc)
        rc = render_write(a, scene, &rs, &res, &part, &flare, outputs, n_out, report,
                          &seconds_write, &e);
    if (installed)
        handle_signals(0, old);
    if (rc && rc != ATMO_INTERRUPTED_EMPTY)
        fprintf(stderr, "atmo render: %s\n", e.msg);
    double strength, colour[3];
    if (!rc && !a->quiet && !part_file &&
        atmo_outputs_blender_world(scene, &strength, colour))
        fprintf(stderr, "atmo render: in Blender, World > Background Strength %.6g with the "
                        "texture multiplied by (%.4f, %.4f, %.4f) shows these files as the PNG "
                        "before its tone map (docs/guide/blender.md)\n",
                strength, colour[0], colour[1], colour[2]);
    if (!rc && !a->quiet)
        render_summary(&res, n_out, scene->render.spectral_bands > 0, seconds_write);
    if (!rc && res.interrupted)
        rc = ATMO_INTERRUPTED_PARTIAL;
    atmo_render_result_free(&res);
    atmo_part_free(&part);
    return rc;
}

/* "I/N" with 1 <= I <= N <= 4096. */
static int parse_part(const char *text, int *part, int *parts, atmo_err *e)
{
    char tail;
    if (sscanf(text, "%d/%d%c", part, parts, &tail) != 2 || *parts < 1 || *parts > 4096 ||
        *part < 1 || *part > *parts)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "--part needs I/N with 1 <= I <= N <= 4096 (e.g. 2/4), got '%s'", text);
    return ATMO_OK;
}

/* A part of one image is one EXR of raw sums of a 3-wavelength render, in one of its bands. */
static int check_part(const atmo_scene *s, int parts, int frames, const char *const *outputs,
                      int n_out, atmo_err *e)
{
    if (frames)
        return ATMO_OK;
    int bands = (s->image.height + ATMO_PART_BAND_ROWS - 1) / ATMO_PART_BAND_ROWS;
    if (parts > bands)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "--part: %d parts of a %d-row image, which has only %d bands of %d rows "
                         "(one per part at least); use at most %d parts",
                         parts, s->image.height, bands, ATMO_PART_BAND_ROWS, bands);
    if (s->render.spectral_bands > 0)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "--part: the spectral mode (render.spectral_bands) cannot be split; "
                         "render it whole");
    if (s->post.flare || s->path.passes)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "--part: a split render keeps no %s (atmo merge could not write it); "
                         "render it whole, or set %s=false",
                         s->post.flare ? "lens flare" : "render passes",
                         s->post.flare ? "post.flare" : "path.passes");
    if (n_out != 1 || atmo_image_format_from_path(outputs[0]) != ATMO_IMAGE_EXR)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "--part writes the part's sums to one --output FILE.exr (got %d "
                         "output%s%s%s); atmo merge writes the images",
                         n_out, n_out == 1 ? " '" : "s", n_out == 1 ? outputs[0] : "",
                         n_out == 1 ? "'" : "");
    return ATMO_OK;
}

/* The numbered names of the last frame (the longest) can be written. */
static int check_frame_paths(const char *const *outputs, int n_out, const char *report,
                             int frame, atmo_err *e)
{
    output_paths last = {0};
    char names[RENDER_MAX_OUTPUTS + 1][ATMO_TMP_PATH_MAX];
    int rc = ATMO_OK;
    for (int i = 0; i <= n_out && !rc; i++) {
        const char *path = i < n_out ? outputs[i] : report;
        if (!path)
            continue;
        if (!frames_path(path, frame, names[i], sizeof names[i]))
            rc = atmo_fail(e, ATMO_ERR_USAGE, "'%s': the name of frame %d is too long", path,
                           frame);
        else
            rc = output_paths_add(&last, i < n_out ? "--output" : "--report", names[i], e);
    }
    output_paths_free(&last);
    return rc;
}


/* animation: the frames' scenes, each checked before any work */
static int render_animation(const render_args *a, const atmo_scene *scene, frames_animation *anim,
                            atmo_err *e)
{
    int rc = ATMO_OK;
    if (a->frames_text && (rc = frames_parse_range(a->frames_text, &anim->first, &anim->last, e)))
        return rc;
    if (!a->frames_text && (a->n_animate || a->scene_end))
        return atmo_fail(e, ATMO_ERR_USAGE, "--animate and --scene-end need --frames A..B");
    for (int i = 0; i < a->n_animate && !rc; i++)
        rc = frames_add_animate(anim, a->animate[i], e);
    if (!rc && a->scene_end) {
        atmo_scene end; /* the start's base (defaults or the preset), then FILE, then the --set */
        if (!(rc = scene_options_scene(&a->so, a->scene_end, &end, e)))
            rc = frames_add_scene_end(anim, scene, &end, a->scene_end, e);
    }
    for (int f = anim->first; a->frames_text && f <= anim->last && !rc; f++) {
        atmo_scene frame;
        rc = frames_scene(anim, scene, f, &frame, e);
    }
    return rc;
}

/* Every file this render writes may be written: no existing file without --force (each frame's
 * numbered names with --frames). */
static int render_check_overwrite(const render_args *a, const frames_animation *anim,
                                  atmo_err *e)
{
    int rc = ATMO_OK;
    for (int f = a->first; f <= anim->last && !rc; f += a->step)
        for (int i = 0; i <= a->n_out + 1 && !rc; i++) {
            const char *path = i < a->n_out ? a->outputs[i] : i == a->n_out ? a->report
                                                                             : a->save_scene;
            const char *option = i < a->n_out ? "--output" : i == a->n_out ? "--report"
                                                                           : "--save-scene";
            char name[ATMO_TMP_PATH_MAX];
            if (!path)
                continue;
            if (a->frames_text && path != a->save_scene &&
                frames_path(path, f, name, sizeof name))
                path = name;
            rc = overwrite_check(option, path, a->force, e);
        }
    return rc;
}

/* outputs: formats and paths, before any work; the same file twice is one output */
static int render_outputs(render_args *a, const atmo_scene *scene, const frames_animation *anim,
                          output_paths *files, atmo_err *e)
{
    int rc;
    if (a->n_out == 0 && !a->save_scene)
        a->outputs[a->n_out++] = "atmo.png";
    for (int i = 0; i < a->n_out; i++) {
        if (atmo_image_format_from_path(a->outputs[i]) < 0)
            return atmo_fail(e, ATMO_ERR_USAGE,
                             "--output '%s': unknown image format (use .png, .hdr, .exr or .pfm)",
                             a->outputs[i]);
        if ((rc = output_paths_add(files, "--output", a->outputs[i], e)))
            return rc;
    }
    a->n_out = files->count;
    for (int i = 0; i < a->n_out; i++)
        a->outputs[i] = files->path[i];
    if ((a->report && (rc = output_paths_add(files, "--report", a->report, e))) ||
        (a->save_scene && (rc = output_paths_add(files, "--save-scene", a->save_scene, e))) ||
        (rc = output_paths_check_input(files, "--scene", a->so.scene_file, e)) ||
        (rc = output_paths_check_input(files, "--scene-end", a->scene_end, e)) ||
        (rc = output_paths_check_input(files, "terrain.heightmap_file", scene->dem.file, e)))
        return rc;
    /* numbered names: the longest (the last frame's) is checked like the others */
    if (a->frames_text && (rc = check_frame_paths(a->outputs, a->n_out, a->report, anim->last, e)))
        return rc;
    return render_check_overwrite(a, anim, e);
}

/* Render frames first, first + step, ... to the last (one image without --frames). */
static int render_frames(const render_args *a, const atmo_scene *scene,
                         const frames_animation *anim)
{
    int rc = ATMO_OK, part_file = a->part_text && !a->frames_text;
    for (int f = a->first; f <= anim->last && !rc; f += a->step) {
        char names[RENDER_MAX_OUTPUTS][ATMO_TMP_PATH_MAX], report_name[ATMO_TMP_PATH_MAX];
        const char *frame_outputs[RENDER_MAX_OUTPUTS];
        atmo_scene frame = *scene;
        atmo_err e = {{0}};
        for (int i = 0; i < a->n_out; i++) {
            frame_outputs[i] = a->outputs[i];
            if (a->frames_text) {
                frames_path(a->outputs[i], f, names[i], sizeof names[i]);
                frame_outputs[i] = names[i];
            }
        }
        if (a->frames_text && a->report)
            frames_path(a->report, f, report_name, sizeof report_name);
        if (a->frames_text && (rc = frames_scene(anim, scene, f, &frame, &e)))
            return cli_fail(&render_cli, rc, &e);
        rc = render_frame(a, &frame, part_file, frame_outputs, a->n_out,
                          a->frames_text ? (a->report ? report_name : NULL) : a->report);
    }
    return rc;
}

/* "atmo render: 640x360 at 16 samples/pixel (3.7 M samples), method fast, 1 image": what the
 * render will cost in samples, before any work. Its time follows once the first pass over the
 * image is timed: the session prints "about N s" then (host/render/session.c), and the
 * progress line's ETA refines it. */
static void render_cost_line(const render_args *a, const atmo_scene *s, const frames_animation *anim)
{
    const char *why;
    const char *method = method_name(s, &why);
    int frames = a->frames_text ? (anim->last - a->first) / a->step + 1 : 1;
    int triplets = s->render.spectral_bands > 0 ? (s->render.spectral_bands + 2) / 3 : 1;
    double samples = (double)s->image.width * s->image.height * s->image.samples * triplets;
    if (a->part_text && !a->frames_text)
        samples /= a->rs.parts;
    fprintf(stderr, "atmo render: %dx%d at %s%d sample%s/pixel%s (%.3g M samples%s), method %s%s%s%s%s; "
                    "%d frame%s%s\n",
            s->image.width, s->image.height, a->rs.noise_target > 0.0 ? "at most " : "",
            s->image.samples, s->image.samples == 1 ? "" : "s",
            triplets > 1 ? " per triplet of bands" : "", 1e-6 * samples * frames,
            a->part_text && !a->frames_text ? " in this part" : "",
            method, why ? " (auto: " : "", why ? why : "", why ? ")" : "",
            s->path.mode != ATMO_RENDER_PATH ? ""
            : s->path.air == ATMO_PATH_AIR_MEDIUM
                ? ", path traced with the air as the paths' medium (path.air=medium: the "
                  "method's sky goes unused)"
                : ", path traced",
            frames,
            frames == 1 ? "" : "s",
            s->image.samples > 1 ? "; the time follows the first pass over the image" : "");
}

/* The scene, the animation, the parts and the outputs, all checked before any work. */
static int render_prepare(render_args *a, atmo_scene *scene, frames_animation *anim,
                          output_paths *files, atmo_err *e)
{
    int rc;
    if ((rc = scene_options_scene(&a->so, NULL, scene, e)) ||
        (rc = render_animation(a, scene, anim, e)))
        return rc;
    /* parts: one EXR of raw sums per part of one image, or whole frames per part */
    if (a->part_text &&
        ((rc = parse_part(a->part_text, &a->rs.part, &a->rs.parts, e)) ||
         (rc = check_part(scene, a->rs.parts, a->frames_text != NULL, a->outputs, a->n_out, e))))
        return rc;
    if (a->part_text && !a->frames_text && (a->rs.noise_target > 0.0 || a->rs.time_limit_s > 0.0))
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "--part renders every pixel to image.samples (atmo merge needs the same "
                         "count in all parts), so %s cannot stop it early; leave it out, or "
                         "render the image whole",
                         a->rs.noise_target > 0.0 ? "--noise" : "--time-limit");
    a->first = anim->first;
    a->step = 1;
    if (a->frames_text && a->part_text) { /* part I of N: frames A + I - 1, A + I - 1 + N, ... */
        a->first += a->rs.part - 1;
        a->step = a->rs.parts;
        a->rs.part = a->rs.parts = 0;
    }
    if ((rc = render_outputs(a, scene, anim, files, e)))
        return rc;
    return a->n_out > 0 ? atmo_cl_check_selector(a->rs.device, e) : ATMO_OK;
}

int cmd_render(int argc, char **argv)
{
    atmo_err e = {{0}};
    atmo_scene scene;
    render_args a = {0};
    frames_animation anim = {0};
    output_paths files = {0};
    int rc;
    atmo_render_settings_default(&a.rs);
    scene_options_init(&a.so);
    if (!cli_parse(&render_cli, &a, argc, argv, NULL, NULL, &rc))
        return rc;
    a.rs.use_kernel_cache = !a.no_kernel_cache;
    if ((rc = render_prepare(&a, &scene, &anim, &files, &e))) {
        output_paths_free(&files);
        return cli_fail(&render_cli, rc, &e);
    }
    if (a.save_scene && (rc = atmo_scene_save_json(&scene, a.save_scene, &e))) {
        output_paths_free(&files);
        return cli_fail(&render_cli, rc, &e);
    }
    /* denoising: a missing library is a usage error when asked for, a warning for auto */
    char denoise_warning[1200] = "";
    if (a.n_out > 0 && !(a.part_text && !a.frames_text) &&
        (rc = atmo_outputs_denoise_prepare(&scene, a.outputs, a.n_out, denoise_warning,
                                           sizeof denoise_warning, &e))) {
        output_paths_free(&files);
        return cli_fail(&render_cli, rc, &e);
    }
    if (denoise_warning[0])
        fprintf(stderr, "atmo render: %s\n", denoise_warning);
    if (a.n_out > 0 && a.first > anim.last && !a.quiet)
        fprintf(stderr, "atmo render: part %d/%d of frames %d..%d has no frame to render\n",
                a.first - anim.first + 1, a.step, anim.first, anim.last);
    a.rs.progress = a.quiet ? 0 : (isatty(STDERR_FILENO) ? 2 : 1);
    if (a.n_out > 0 && a.first <= anim.last && !a.quiet)
        render_cost_line(&a, &scene, &anim);
    if (a.n_out > 0)
        rc = render_frames(&a, &scene, &anim);
    output_paths_free(&files);
    return rc;
}
