/* cmd_render.c — `atmo render`: scene -> plan -> device -> images and a run report.
 *
 * Scene assembly, in this order: the defaults; --preset NAME (default: atmo_default_preset) or
 * --scene FILE; then --set KEY=VALUE and the shorthands (--width, --height, --samples, --seed,
 * --time, --camera) in command-line order. Every output's format and path is checked before
 * anything runs (output_paths.h: directory, name, limits, no two outputs in one file), so a bad
 * argument never costs a render.
 *
 * Interrupts: the first SIGINT or SIGTERM sets the render's cancel token; the precompute or the
 * render stops after the launch in flight. Samples already rendered are written, marked
 * partial (report "interrupted", file metadata), and the exit status is 3; stopped before any
 * sample (in the precompute, or in a spectral render's triplets), nothing is written and the
 * exit status is 4. A signal while the files are written lets the writing finish (the image is
 * whole). A second signal removes the temporary file being written and ends the process by
 * that signal at once. Exit statuses: 0 done, 1 runtime error, 2 usage, 3 interrupted with a
 * partial image written, 4 interrupted with nothing written. */
#include <cjson/cJSON.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "atmo/clock.h"
#include "atmo/colour.h"
#include "atmo/fileio.h"
#include "atmo/flare.h"
#include "atmo/image.h"
#include "atmo/part.h"
#include "atmo/plan.h"
#include "atmo/render.h"
#include "atmo/scene.h"
#include "atmo/spectral_render.h"
#include "commands.h"
#include "frames.h"
#include "output_paths.h"
#include "render_passes.h"
#include "scene_options.h"
#include "atmo/outputs.h"

#define RENDER_MAX_OUTPUTS 8

static const char render_usage[] =
    "usage: atmo render [--preset NAME | --scene FILE] [--set KEY=VALUE ...] [options]\n"
    "\n"
    "Renders a scene and writes one image per --output (format from the extension):\n"
    "  .png  8-bit sRGB after white balance, exposure and tone mapping (post.*)\n"
    "  .hdr  Radiance RGBE, linear     .exr  OpenEXR 32-bit float, linear\n"
    "  .pfm  portable float map, linear\n"
    "Linear outputs hold spectral radiance (W m^-2 sr^-1 nm^-1) at render.wavelengths_nm, or\n"
    "luminance (cd/m^2) with --set render.quantity=luminance. With --set render.spectral_bands=N\n"
    "(N >= 15) the scene is rendered at N wavelengths over 360-830 nm, three at a time, and\n"
    "combined through the CIE 1931 colour matching functions into linear sRGB (cd/m^2).\n"
    "\n"
    "scene:\n"
    "  --preset NAME          a built-in scene (atmo presets; default %s)\n"
    "  --scene FILE           a JSON scene file (atmo params lists every key)\n"
    "  --set KEY=VALUE        override one parameter, e.g. --set sun.zenith_deg=60 (repeatable)\n"
    "  --width N, --height N, --samples N, --seed N, --camera perspective|panorama\n"
    "                         shorthands for image.width, image.height, image.samples,\n"
    "                         image.seed and camera.kind\n"
    "  --time SECONDS         shorthand for clouds.time_s: the clouds move with the wind\n"
    "                         (frames of an animation: --time 0, 1, 2, ... -o NAME.0001.png ...)\n"
    "  --save-scene FILE      write the fully resolved scene as JSON (rendering it reproduces\n"
    "                         the image bit for bit); without --output nothing is rendered\n"
    "output:\n"
    "  --output FILE          image to write (repeatable; default atmo.png)\n"
    "  --report FILE          JSON run report: settings, device, samples, stage timings\n"
    "  --exr-compression C    EXR codec, all lossless: piz (default: smallest), none (fastest,\n"
    "                         2x the size), zip, zips, rle\n"
    "progressive (path mode, render.mode=path, and every other render):\n"
    "  --noise P              stop each tile once its relative standard error is at most P\n"
    "                         (e.g. 1%% or 0.01; checked at 16, 32, 64, ... samples); the\n"
    "                         image.samples are the most any tile gets\n"
    "  --time-limit S         no new launch after S seconds; the image has what was rendered\n"
    "device:\n"
    "  --device N|NAME        OpenCL device by index or name part (or ATMO_DEVICE; atmo devices)\n"
    "  --tile-size N          tile edge in pixels (default 64)\n"
    "  --launch-budget-ms MS  time per kernel launch to aim for (default 100)\n"
    "  --dump-kernels DIR     write the assembled OpenCL source to DIR\n"
    "  --no-kernel-cache      always compile the kernels (cache: ATMO_CACHE_DIR or ~/.cache/atmo)\n"
    "  --no-lut-cache         always precompute LUTs and Mie tables, and store none (LUTs that\n"
    "                         take over 20 ms and Mie tables are cached)\n"
    "  --quiet                no progress output\n"
    "split and animate (README: Rendering on a cluster):\n"
    "  --part I/N             render part I of N of the image (its rows in bands of 8, band b\n"
    "                         in part b mod N + 1) into one --output FILE.exr of raw sums;\n"
    "                         atmo merge joins the N parts into the image of a single render\n"
    "  --frames A..B          render frames A to B; each output NAME.EXT becomes NAME.0001.EXT\n"
    "                         ...; with --part I/N, part I renders frames A+I-1, A+I-1+N, ...\n"
    "  --animate KEY=V0..V1   move a float key linearly from V0 (frame A) to V1 (frame B)\n"
    "  --scene-end FILE       move every float and vector key in which the end scene differs\n"
    "                         from the start: the --preset (none with --scene), FILE, then\n"
    "                         the same --set options\n"
    "\n"
    "Ctrl-C (SIGINT) or SIGTERM stops the precompute or the render after the launch in flight:\n"
    "the samples finished so far are written, marked partial, with exit status 3; stopped\n"
    "before any sample, nothing is written and the exit status is 4. A second signal stops at\n"
    "once and removes the file being written. Exit statuses: 0 done, 1 runtime error, 2 usage\n"
    "or input error (nothing is rendered), 3 interrupted with a partial image, 4 interrupted\n"
    "with nothing written.\n";

/* What the signal handler uses: a handler takes no user data, so this file holds the one token
 * that the render it starts is given (atmo_render_settings.cancel), and the temporary names of
 * the outputs (atmo_tmp_path), computed before the handler is installed. */
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

/* SIGINT and SIGTERM to on_signal (install) or back to what they were. */
static void handle_signals(int install, struct sigaction old[2])
{
    static const int sigs[2] = {SIGINT, SIGTERM};
    struct sigaction sa = {0};
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    for (int i = 0; i < 2; i++)
        sigaction(sigs[i], install ? &sa : &old[i], install ? &old[i] : NULL);
}

static int write_report(const char *path, const atmo_scene *s, const atmo_render_result *r,
                          const atmo_render_settings *rs, const char *const *outputs, int n_out,
                          double seconds_write, const atmo_image_layer *layers, int n_layers,
                          const atmo_flare_info *flare, atmo_err *e)
{
    cJSON *root = cJSON_CreateObject();
    char *scene_text = atmo_scene_to_json(s);
    cJSON *scene = scene_text ? cJSON_Parse(scene_text) : NULL;
    free(scene_text);
    cJSON_AddStringToObject(root, "software", "atmo " ATMO_VERSION);
    cJSON_AddItemToObject(root, "scene", scene ? scene : cJSON_CreateNull());
    cJSON *dev = cJSON_AddObjectToObject(root, "device");
    cJSON_AddStringToObject(dev, "platform", r->platform_name);
    cJSON_AddStringToObject(dev, "name", r->device_name);
    cJSON_AddStringToObject(dev, "driver_version", r->driver_version);
    cJSON *ren = cJSON_AddObjectToObject(root, "render");
    cJSON_AddNumberToObject(ren, "width", r->width);
    cJSON_AddNumberToObject(ren, "height", r->height);
    cJSON_AddNumberToObject(ren, "samples_requested", r->samples_requested);
    cJSON_AddNumberToObject(ren, "samples_min", r->samples_min);
    cJSON_AddNumberToObject(ren, "samples_max", r->samples_max);
    cJSON_AddBoolToObject(ren, "interrupted", r->interrupted);
    cJSON_AddNumberToObject(ren, "nonfinite_samples_dropped", r->nonfinite);
    cJSON_AddNumberToObject(ren, "launches", r->launches);
    cJSON_AddNumberToObject(ren, "noise_target", rs->noise_target);
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
    cJSON_AddNumberToObject(t, "write", seconds_write);
    cJSON *passes = cJSON_AddArrayToObject(ren, "passes"); /* the EXR layers' channels */
    for (int i = 0; i < n_layers; i++)
        for (int c = 0; c < layers[i].channels; c++) {
            char name[64];
            snprintf(name, sizeof name, "%s.%s", layers[i].name, layers[i].channel_names[c]);
            cJSON_AddItemToArray(passes, cJSON_CreateString(name));
        }
    if (s->post.flare) { /* what the lens flare measured and added */
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
    cJSON *outs = cJSON_AddArrayToObject(root, "outputs");
    for (int i = 0; i < n_out; i++)
        cJSON_AddItemToArray(outs, cJSON_CreateString(outputs[i]));
    char *text = cJSON_Print(root);
    cJSON_Delete(root);
    if (!text)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory writing the report");
    size_t len = strlen(text);
    char *with_newline = malloc(len + 2);
    int rc = ATMO_ERR_RUNTIME;
    if (with_newline) {
        memcpy(with_newline, text, len);
        memcpy(with_newline + len, "\n", 2);
        rc = atmo_write_text_file(path, with_newline, e);
    }
    free(with_newline);
    free(text);
    return rc;
}

static int parse_int_arg(const char *opt, const char *v, int lo, int hi, int *out, atmo_err *e)
{
    double x = 0.0;
    if (!v || !atmo_parse_decimal(v, &x) || x != floor(x) || x < lo || x > hi)
        return atmo_fail(e, ATMO_ERR_USAGE, "%s needs a whole number in [%d, %d] written as "
                         "decimal digits, got '%s'", opt, lo, hi, v ? v : "");
    *out = (int)x;
    return ATMO_OK;
}

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

/* Render one scene (a frame) and write its files: the images, or with part_file the part's raw
 * sums (outputs[0]); then the report. Returns the exit status; errors are printed. */
static int render_frame(const atmo_scene *scene_in, atmo_render_settings *rs_in, int lut_cache,
                        int quiet, int part_file, int exr_compression,
                        const char *const *outputs, int n_out, const char *report)
{
    atmo_err e = {{0}};
    atmo_scene scene = *scene_in;
    atmo_render_settings rs = *rs_in;
    atmo_render_result res = {0};
    atmo_part part = {0};
    int rc = ATMO_OK;
    /* spectral mode plans each triplet of bands itself */
    int spectral = scene.render.spectral_bands > 0;
    atmo_plan plan;
    if (!spectral && (rc = atmo_plan_make_cached(&scene, lut_cache, lut_cache, &plan, &e)))
        goto runtime_error;

    /* the handler stays until the files are written: a signal then lets the writing finish */
    atmo_cancel_clear(&render_cancel);
    signals_seen = 0;
    pending_count = 0;
    for (int i = 0; i < n_out; i++)
        atmo_tmp_path(outputs[i], pending_tmp[pending_count++]);
    if (report)
        atmo_tmp_path(report, pending_tmp[pending_count++]);
    rs.cancel = &render_cancel;
    struct sigaction old[2];
    handle_signals(1, old);
    char *scene_json = part_file ? atmo_scene_to_json(&scene) : NULL;
    if (part_file && !scene_json)
        rc = atmo_fail(&e, ATMO_ERR_RUNTIME, "out of memory for the scene's text");
    else if (part_file && !(rc = atmo_part_alloc(&part, plan.width, plan.height, rs.part,
                                                 rs.parts, scene_json, &e)))
        rc = atmo_render_part(&plan, &rs, &res, &part, &e);
    else if (!part_file)
        rc = spectral ? atmo_spectral_render(&scene, lut_cache, &rs, &res, &e)
                      : atmo_render(&plan, &rs, &res, &e);
    free(scene_json);
    if (!spectral)
        atmo_plan_free(&plan);
    if (rc == ATMO_ERR_RUNTIME || rc == ATMO_ERR_USAGE) {
        handle_signals(0, old);
        goto runtime_error;
    }
    if (rc == ATMO_OK && res.interrupted && res.samples_max == 0) {
        atmo_fail(&e, ATMO_INTERRUPTED_EMPTY, "interrupted before the first sample");
        rc = ATMO_INTERRUPTED_EMPTY;
    }
    if (rc) { /* interrupted before any result */
        fprintf(stderr, "atmo render: %s; no image written (exit status %d)\n", e.msg, rc);
        handle_signals(0, old);
        atmo_render_result_free(&res);
        atmo_part_free(&part);
        return rc;
    }
    if (res.interrupted)
        fprintf(stderr, "atmo render: interrupted; writing %d to %d of %d samples per pixel "
                        "(exit status %d)\n",
                res.samples_min, res.samples_max, res.samples_requested,
                ATMO_INTERRUPTED_PARTIAL);
    if (res.nonfinite)
        fprintf(stderr, "atmo render: warning: %u non-finite samples were dropped (a bug; please "
                        "report it with the scene)\n", res.nonfinite);

    /* post: the lens flare, on the linear image every output gets */
    atmo_flare_info flare = {0};
    if (!part_file && scene.post.flare && scene.camera.kind == ATMO_CAMERA_PERSPECTIVE) {
        atmo_flare_camera fc = {.width = res.width, .height = res.height,
                                .tan_half_fov = tan(0.5 * scene.camera.fov_deg * M_PI / 180.0),
                                .sun_radius_rad = scene.sun.angular_radius_deg * M_PI / 180.0};
        atmo_camera_basis(scene.camera.pitch_deg, scene.camera.yaw_deg, fc.forward, fc.right,
                          fc.up);
        atmo_sun_direction(scene.sun.zenith_deg, scene.sun.azimuth_deg, fc.sun);
        atmo_flare_apply(res.rgb, &fc, scene.post.flare_strength, &flare);
    }

    /* outputs: the images with the render passes as EXR layers, or the part's raw sums */
    double tw = atmo_now_seconds();
    atmo_image img = {.width = res.width, .height = res.height, .rgb = res.rgb};
    atmo_image_layer layers[RENDER_PASS_LAYERS];
    float *layer_data = NULL;
    img.layer_count = part_file ? 0 : render_pass_layers(&res, layers, &layer_data);
    img.layers = layers;
    if (img.layer_count < 0)
        rc = atmo_fail(&e, ATMO_ERR_RUNTIME, "out of memory for the render passes");
    else
        rc = part_file ? atmo_part_write(outputs[0], &part, &e)
                       : atmo_outputs_write(&scene, &img, res.samples_min, res.interrupted,
                                            exr_compression, outputs, n_out, &e);
    double seconds_write = atmo_now_seconds() - tw;
    if (!rc && report)
        rc = write_report(report, &scene, &res, &rs, outputs, n_out, seconds_write, img.layers,
                          img.layer_count > 0 ? img.layer_count : 0, &flare, &e);
    free(layer_data);
    handle_signals(0, old);
    if (rc)
        goto runtime_error;
    if (!quiet)
        fprintf(stderr, "atmo render: wrote %d image%s (%dx%d, %d samples/pixel%s) in %.2fs: "
                        "%.2fs device, %.2fs build%s, %.2fs precompute%s, %.2fs render, %.2fs "
                        "read-back, %.2fs write on %s\n",
                n_out, n_out > 1 ? "s" : "", res.width, res.height, res.samples_min,
                spectral ? ", spectral mode" : "",
                res.seconds_device + res.seconds_build + res.seconds_precompute +
                    res.seconds_render + res.seconds_read + seconds_write,
                res.seconds_device, res.seconds_build, res.kernel_cache_hit ? " (cached)" : "",
                res.seconds_precompute, res.lut_cache_hit ? " (cached)" : "", res.seconds_render,
                res.seconds_read, seconds_write, res.device_name);
    rc = res.interrupted ? ATMO_INTERRUPTED_PARTIAL : ATMO_OK;
    atmo_render_result_free(&res);
    atmo_part_free(&part);
    return rc;
runtime_error:
    atmo_render_result_free(&res);
    atmo_part_free(&part);
    fprintf(stderr, "atmo render: %s\n", e.msg);
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

int cmd_render(int argc, char **argv)
{
    atmo_err e = {{0}};
    atmo_scene scene;
    atmo_render_settings rs;
    const char *report = NULL, *save_scene = NULL;
    const char *part_text = NULL, *frames_text = NULL, *scene_end = NULL;
    const char *animate[FRAMES_MAX_KEYS];
    int n_animate = 0;
    const char *outputs[RENDER_MAX_OUTPUTS];
    scene_options so;
    int n_out = 0, quiet = 0, lut_cache = 1, rc = ATMO_OK;
    int exr_compression = ATMO_EXR_DEFAULT;
    output_paths files = {0};
    atmo_render_settings_default(&rs);
    scene_options_init(&so, "render", 1);

    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        const char *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            printf(render_usage, atmo_default_preset);
            return ATMO_OK;
        }
        int taken = scene_options_take(&so, argc, argv, &i);
        if (taken < 0)
            return ATMO_ERR_USAGE;
        if (taken)
            continue;
        if (strcmp(a, "--quiet") == 0 || strcmp(a, "-q") == 0) {
            quiet = 1;
            continue;
        }
        if (strcmp(a, "--no-kernel-cache") == 0) {
            rs.use_kernel_cache = 0;
            continue;
        }
        if (strcmp(a, "--no-lut-cache") == 0) {
            lut_cache = 0;
            continue;
        }
        static const char *const with_value[] = {
            "--output", "-o", "--report", "--save-scene",
            "--noise", "--time-limit", "--device", "--dump-kernels", "--tile-size", "--launch-budget-ms",
            "--part", "--frames", "--animate", "--scene-end",
            "--exr-compression", NULL};
        int known = 0;
        for (int k = 0; with_value[k]; k++)
            known |= strcmp(a, with_value[k]) == 0;
        if (!known) {
            fprintf(stderr, "atmo render: %s '%s' (atmo render --help)\n",
                    a[0] == '-' ? "unknown option" : "unexpected argument", a);
            return ATMO_ERR_USAGE;
        }
        if (!v) {
            fprintf(stderr, "atmo render: %s needs a value (atmo render --help)\n", a);
            return ATMO_ERR_USAGE;
        }
        i++;
        if (strcmp(a, "--output") == 0 || strcmp(a, "-o") == 0) {
            if (n_out == RENDER_MAX_OUTPUTS) {
                fprintf(stderr, "atmo render: more than %d --output options\n", RENDER_MAX_OUTPUTS);
                return ATMO_ERR_USAGE;
            }
            outputs[n_out++] = v;
        } else if (strcmp(a, "--report") == 0)
            report = v;
        else if (strcmp(a, "--save-scene") == 0)
            save_scene = v;
        else if (strcmp(a, "--device") == 0)
            rs.device = v;
        else if (strcmp(a, "--dump-kernels") == 0)
            rs.dump_dir = v;
        else if (strcmp(a, "--exr-compression") == 0) {
            if ((exr_compression = atmo_exr_compression_from_name(v)) < 0) {
                rc = atmo_fail(&e, ATMO_ERR_USAGE, "--exr-compression '%s': use piz, none, zip, "
                               "zips or rle", v);
                goto usage_error;
            }
        }
        else if (strcmp(a, "--tile-size") == 0) {
            if ((rc = parse_int_arg(a, v, 8, 4096, &rs.tile_size, &e)))
                goto usage_error;
        } else if (strcmp(a, "--launch-budget-ms") == 0) {
            char *end;
            rs.launch_budget_ms = strtod(v, &end);
            if (*v == 0 || *end != 0 || !(rs.launch_budget_ms >= 1.0 && rs.launch_budget_ms <= 1e5)) {
                rc = atmo_fail(&e, ATMO_ERR_USAGE,
                               "--launch-budget-ms needs milliseconds in [1, 100000], got '%s'", v);
                goto usage_error;
            }
        } else if (strcmp(a, "--noise") == 0) {
            if ((rc = parse_noise(v, &rs.noise_target, &e)))
                goto usage_error;
        } else if (strcmp(a, "--time-limit") == 0) {
            char *end;
            rs.time_limit_s = strtod(v, &end);
            if (*v == 0 || *end != 0 || !(rs.time_limit_s > 0.0 && rs.time_limit_s <= 1e7)) {
                rc = atmo_fail(&e, ATMO_ERR_USAGE,
                               "--time-limit needs seconds in (0, 1e7], got '%s'", v);
                goto usage_error;
            }
        } else if (strcmp(a, "--part") == 0)
            part_text = v;
        else if (strcmp(a, "--frames") == 0)
            frames_text = v;
        else if (strcmp(a, "--scene-end") == 0)
            scene_end = v;
        else if (strcmp(a, "--animate") == 0) {
            if (n_animate == FRAMES_MAX_KEYS) {
                fprintf(stderr, "atmo render: more than %d --animate options\n", FRAMES_MAX_KEYS);
                return ATMO_ERR_USAGE;
            }
            animate[n_animate++] = v;
        }
    }

    /* scene */
    if ((rc = scene_options_scene(&so, NULL, &scene, &e)))
        goto usage_error;

    /* animation: the frames' scenes, each checked before any work */
    frames_animation anim = {0};
    if (frames_text && (rc = frames_parse_range(frames_text, &anim.first, &anim.last, &e)))
        goto usage_error;
    if (!frames_text && (n_animate || scene_end)) {
        rc = atmo_fail(&e, ATMO_ERR_USAGE, "--animate and --scene-end need --frames A..B");
        goto usage_error;
    }
    for (int i = 0; i < n_animate && !rc; i++)
        rc = frames_add_animate(&anim, animate[i], &e);
    if (!rc && scene_end) {
        atmo_scene end; /* the start's base (defaults or the preset), then FILE, then the --set */
        if (!(rc = scene_options_scene(&so, scene_end, &end, &e)))
            rc = frames_add_scene_end(&anim, &scene, &end, scene_end, &e);
    }
    for (int f = anim.first; frames_text && f <= anim.last && !rc; f++) {
        atmo_scene frame;
        rc = frames_scene(&anim, &scene, f, &frame, &e);
    }
    if (rc)
        goto usage_error;

    /* parts: one EXR of raw sums per part of one image, or whole frames per part */
    if (part_text && ((rc = parse_part(part_text, &rs.part, &rs.parts, &e)) ||
                      (rc = check_part(&scene, rs.parts, frames_text != NULL, outputs, n_out, &e))))
        goto usage_error;
    int part_file = part_text && !frames_text;
    int frame_first = frames_text ? anim.first : 0, frame_last = frames_text ? anim.last : 0;
    int frame_step = 1;
    if (frames_text && part_text) { /* part I of N: frames A + I - 1, A + I - 1 + N, ... */
        frame_first += rs.part - 1;
        frame_step = rs.parts;
        rs.part = rs.parts = 0;
    }

    /* outputs: formats and paths, before any work; the same file twice is one output */
    if (n_out == 0 && !save_scene)
        outputs[n_out++] = "atmo.png";
    for (int i = 0; i < n_out; i++) {
        if (atmo_image_format_from_path(outputs[i]) < 0) {
            rc = atmo_fail(&e, ATMO_ERR_USAGE,
                           "--output '%s': unknown image format (use .png, .hdr, .exr or .pfm)",
                           outputs[i]);
            goto usage_error;
        }
        if ((rc = output_paths_add(&files, "--output", outputs[i], &e)))
            goto usage_error;
    }
    n_out = files.count;
    for (int i = 0; i < n_out; i++)
        outputs[i] = files.path[i];
    if ((report && (rc = output_paths_add(&files, "--report", report, &e))) ||
        (save_scene && (rc = output_paths_add(&files, "--save-scene", save_scene, &e))) ||
        (rc = output_paths_check_input(&files, "--scene", so.scene_file, &e)) ||
        (rc = output_paths_check_input(&files, "--scene-end", scene_end, &e)) ||
        (rc = output_paths_check_input(&files, "terrain.heightmap_file", scene.dem.file, &e)))
        goto usage_error;
    /* numbered names: the longest (the last frame's) is checked like the others */
    if (frames_text && (rc = check_frame_paths(outputs, n_out, report, anim.last, &e)))
        goto usage_error;
    if (save_scene && (rc = atmo_scene_save_json(&scene, save_scene, &e)))
        goto runtime_error;
    if (n_out > 0 && frame_first > frame_last && !quiet)
        fprintf(stderr, "atmo render: part %d/%d of frames %d..%d has no frame to render\n",
                frame_first - anim.first + 1, frame_step, anim.first, anim.last);
    if (n_out == 0 || frame_first > frame_last) {
        output_paths_free(&files);
        return ATMO_OK;
    }

    rs.progress = quiet ? 0 : (isatty(STDERR_FILENO) ? 2 : 1);
    for (int f = frame_first; f <= frame_last && !rc; f += frame_step) {
        char names[RENDER_MAX_OUTPUTS][ATMO_TMP_PATH_MAX], report_name[ATMO_TMP_PATH_MAX];
        const char *frame_outputs[RENDER_MAX_OUTPUTS];
        atmo_scene frame = scene;
        for (int i = 0; i < n_out; i++) {
            frame_outputs[i] = outputs[i];
            if (frames_text) {
                frames_path(outputs[i], f, names[i], sizeof names[i]);
                frame_outputs[i] = names[i];
            }
        }
        if (frames_text && report)
            frames_path(report, f, report_name, sizeof report_name);
        if (frames_text && (rc = frames_scene(&anim, &scene, f, &frame, &e)))
            goto runtime_error;
        rc = render_frame(&frame, &rs, lut_cache, quiet, part_file, exr_compression,
                          frame_outputs, n_out,
                          frames_text ? (report ? report_name : NULL) : report);
    }
    output_paths_free(&files);
    return rc;

usage_error:
    output_paths_free(&files);
    fprintf(stderr, "atmo render: %s\n", e.msg);
    return rc;
runtime_error:
    output_paths_free(&files);
    fprintf(stderr, "atmo render: %s\n", e.msg);
    return rc;
}
