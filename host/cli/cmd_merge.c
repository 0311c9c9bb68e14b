/* cmd_merge.c — `atmo merge PART... --output FILE...`: the parts of a split render
 * (`atmo render --part I/N`, atmo/part.h) joined into the files the single render writes.
 *
 * Order: the outputs' formats and paths are checked (output_paths.h), every part is read, the
 * merge checks them (same scene hash and size, parts 1..N each once, every part complete in its
 * bands and empty elsewhere: atmo_part_merge), the scene stored in the parts is loaded and
 * validated; only then is anything written. An output that exists is refused unless --force.
 * Any failure is one line naming the file or the part, exit status 2, and no output. The pixels
 * are each copied from the part that rendered them and the mean is atmo_session_read's, so
 * with parts rendered on one device the files equal a single-process render's bit for bit
 * (atmo_outputs_write_denoised, host/render/outputs.c, writes both). Parts from different
 * devices merge with a warning: each pixel is then its own device's.
 *
 * Denoising (the parts' output.denoise, or --denoise's quality in its place) runs once, on the
 * merged image, guided as `atmo render` guides it: the merge renders the albedo and normal
 * guides of the whole image itself (atmo_render_guides on the device --device selects) rather
 * than reading them from the parts.
 * The guides draw no random number and depend on the scene alone, which the parts carry, so the
 * parts stay the sums they are (8 more floats a pixel would nearly double them) and, on the
 * parts' device, the guides and so the denoised files are the single render's bit for bit. A
 * guide device other than the parts' is a warning: the guides are then that device's. The
 * heightmap the scene names must be the one the parts read (their input hash), else the merge
 * stops with a usage error before the device work. --report writes what was merged and how it
 * was denoised. */
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cjson/cJSON.h>
#include "atmo/cl_runtime.h"
#include "atmo/fileio.h"
#include "atmo/image.h"
#include "atmo/outputs.h"
#include "atmo/part.h"
#include "atmo/render.h"
#include "atmo/scene.h"
#include "cli_flags.h"
#include "commands.h"
#include "output_paths.h"
#include "overwrite.h"
#include "run_report.h"

#define MERGE_MAX_PARTS 4096
#define MERGE_MAX_OUTPUTS 8

/* The flags' destinations (merge_flags) and the parts, given as arguments. */
typedef struct merge_args {
    const char *outputs[MERGE_MAX_OUTPUTS];
    int n_out, quiet, force;
    const char *report, *device, *denoise;
    const char *parts[MERGE_MAX_PARTS];
} merge_args;

#define MERGE_FLAG(member) offsetof(merge_args, member)

/* --denoise Q: checked as the scene key output.denoise checks it, applied to the parts' scene */
static int take_denoise(void *args, const cli_flag *f, const char *v, atmo_err *e)
{
    merge_args *a = args;
    atmo_scene probe;
    atmo_scene_defaults(&probe);
    int rc = atmo_scene_set(&probe, "output.denoise", v, f->name, e);
    if (!rc)
        a->denoise = v;
    return rc;
}

static const cli_flag merge_flags[] = {
    {.type = CLI_PATH, .name = "--output", .alias = "-o", .offset = MERGE_FLAG(outputs),
     .repeat = MERGE_MAX_OUTPUTS, .count_offset = MERGE_FLAG(n_out), .def = "none: required",
     .help = "image to write, format from the extension (repeatable)"},
    {.type = CLI_BOOL, .name = "--force", .offset = MERGE_FLAG(force),
     .help = "overwrite outputs that exist (without it an existing file is an\nerror)"},
    {.type = CLI_BOOL, .name = "--quiet", .alias = "-q", .offset = MERGE_FLAG(quiet),
     .help = "no summary line"},
    {.type = CLI_PATH, .name = "--report", .offset = MERGE_FLAG(report), .def = "none",
     .help = "JSON report: the parts, the image, how it was denoised"},
    {.type = CLI_STRING, .name = "--denoise", .metavar = "Q", .take = take_denoise,
     .def = "the parts' scene's output.denoise",
     .help = "denoise the merged image: auto, off, fast, balanced or high, as\n"
             "atmo render --denoise (parts are never denoised themselves)"},
    {.type = CLI_STRING, .name = "--device", .metavar = "N|NAME", .offset = MERGE_FLAG(device),
     .def = "$ATMO_DEVICE, else the first GPU, else the first device",
     .help = "OpenCL device of the denoiser's guides (atmo devices); the parts'\n"
             "device gives the single render's files bit for bit"},
    {.type = CLI_END},
};

static const cli_command merge_cli = {
    .name = "merge",
    .synopsis = "PART.exr... --output FILE [--output FILE ...] [--report FILE] [--denoise Q]\n"
                "            [--device N|NAME] [--force] [--quiet]",
    .about = "Joins the N parts of a split render (atmo render --part I/N --output PART.exr) into the\n"
             "images the single render writes (.png .hdr .exr .pfm, format from the extension), bit for\n"
             "bit when the parts were rendered on one device. Refused with exit status 2 and no output:\n"
             "a file that is not a part, parts of different scenes, a part given twice, a missing part,\n"
             "an incomplete (interrupted) part, an output that exists (without --force). Outputs that\n"
             "the scene's output.denoise (or --denoise) denoises are denoised once, after the merge,\n"
             "with the albedo and normal guides that atmo render uses, rendered here on --device.\n",
    .flags = merge_flags,
    .max_positional = MERGE_MAX_PARTS,
};

/* The denoiser's guides of the merged image into *res (atmo_render_guides on `device`): the
 * scene's heightmap must be the parts' (their input hash); another device than the parts' is
 * a warning. */
static int merge_guides(const atmo_scene *scene, const atmo_part *part, const char *path,
                        const char *device, atmo_render_result *res, atmo_err *e)
{
    atmo_plan plan;
    atmo_render_settings rs;
    atmo_render_settings_default(&rs);
    rs.device = device;
    int rc = atmo_plan_make_cached(scene, 1, 1, &plan, e);
    if (rc)
        return rc;
    unsigned long long input =
        atmo_part_input_hash(plan.dem.width, plan.dem.height, plan.dem.heights_m);
    if (input != part->input_hash)
        rc = atmo_fail(e, ATMO_ERR_USAGE,
                       "'%s': the heightmap '%s' is not the one the parts were rendered with "
                       "(input hash %016llx, the parts' %016llx); the denoiser's guides need "
                       "it: restore that file",
                       path, scene->dem.file[0] ? scene->dem.file : "(none)", input,
                       part->input_hash);
    if (!rc)
        rc = atmo_render_guides(&plan, &rs, res, e);
    atmo_plan_free(&plan);
    char here[sizeof part->device];
    if (!rc)
        snprintf(here, sizeof here, "%s / %s / %s", res->platform_name, res->device_name,
                 res->driver_version);
    if (!rc && strcmp(here, part->device) != 0)
        fprintf(stderr, "atmo merge: warning: the denoiser's guides are rendered on %s, '%s' on "
                        "%s; the denoised image is not one device's bit for bit (--device "
                        "selects the guides' device)\n",
                here, path, part->device);
    return rc;
}

/* The merge's report: the parts, the image, the guides' device and how it was denoised. */
static int merge_report(const char *path, const atmo_scene *scene, const char *const *parts,
                        int n, const char *const *outputs, int n_out, const atmo_part *merged,
                        const atmo_render_result *guides, const atmo_outputs_denoise *denoised,
                        atmo_err *e)
{
    cJSON *root = run_report_new(scene);
    if (!root)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory writing the report '%s'", path);
    cJSON *m = cJSON_AddObjectToObject(root, "merge");
    cJSON_AddNumberToObject(m, "width", merged->width);
    cJSON_AddNumberToObject(m, "height", merged->height);
    cJSON_AddNumberToObject(m, "samples", scene->image.samples);
    cJSON *list = cJSON_AddArrayToObject(m, "parts");
    for (int i = 0; i < n; i++)
        cJSON_AddItemToArray(list, cJSON_CreateString(parts[i]));
    if (guides->guides) {
        cJSON *dev = cJSON_AddObjectToObject(m, "guide_device");
        cJSON_AddStringToObject(dev, "platform", guides->platform_name);
        cJSON_AddStringToObject(dev, "name", guides->device_name);
        cJSON_AddStringToObject(dev, "driver_version", guides->driver_version);
        cJSON_AddNumberToObject(m, "guide_session_seconds",
                                guides->seconds_device + guides->seconds_build +
                                    guides->seconds_precompute);
    }
    cJSON *dn = atmo_outputs_denoise_json(scene, denoised);
    if (dn)
        cJSON_AddItemToObject(m, "denoise", dn);
    return run_report_write(root, outputs, n_out, path, e);
}

static int merge_parts(const merge_args *a, int n, atmo_err *e)
{
    const char *const *paths = a->parts, *const *outputs = a->outputs;
    int n_out = a->n_out;
    atmo_part *parts = calloc((size_t)n, sizeof *parts), merged = {0};
    atmo_render_result guide_res = {0};
    atmo_outputs_denoise denoised = {0};
    float *rgb = NULL;
    int rc = ATMO_OK;
    if (!parts)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory for %d parts", n);
    for (int i = 0; i < n && !rc; i++)
        rc = atmo_part_read(paths[i], &parts[i], e);
    atmo_scene scene;
    atmo_scene_defaults(&scene);
    if (!rc)
        rc = atmo_scene_load_json_text(&scene, parts[0].scene_json, strlen(parts[0].scene_json),
                                       paths[0], e);
    if (!rc && a->denoise)
        rc = atmo_scene_set(&scene, "output.denoise", a->denoise, "--denoise", e);
    if (!rc)
        rc = atmo_scene_validate(&scene, e);
    if (!rc && (scene.image.width != parts[0].width || scene.image.height != parts[0].height))
        rc = atmo_fail(e, ATMO_ERR_USAGE,
                       "'%s' holds a %dx%d image but its scene is %dx%d; render that part again",
                       paths[0], parts[0].width, parts[0].height, scene.image.width,
                       scene.image.height);
    char denoise_warning[1200] = ""; /* output.denoise of the parts' scene, once, after */
    if (!rc)
        rc = atmo_outputs_denoise_prepare(&scene, outputs, n_out, denoise_warning,
                                          sizeof denoise_warning, e);
    if (denoise_warning[0])
        fprintf(stderr, "atmo merge: %s\n", denoise_warning);
    if (!rc)
        rc = atmo_part_merge(parts, paths, n, scene.image.samples, &merged, e);
    if (!rc && !(rgb = malloc(sizeof(float) * 3 * (size_t)merged.width * merged.height)))
        rc = atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory for a %dx%d image", merged.width,
                       merged.height);
    if (!rc) {
        for (int i = 1; i < n; i++)
            if (strcmp(parts[i].device, parts[0].device) != 0) {
                fprintf(stderr, "atmo merge: warning: '%s' was rendered on %s, '%s' on %s; the "
                                "image is not one device's bit for bit\n",
                        paths[i], parts[i].device, paths[0], parts[0].device);
                break;
            }
        atmo_part_mean(&merged, rgb);
    }
    if (!rc && atmo_outputs_want_guides(&scene, outputs, n_out))
        rc = merge_guides(&scene, &parts[0], paths[0], a->device, &guide_res, e);
    if (!rc) {
        atmo_image img = {.width = merged.width, .height = merged.height, .rgb = rgb};
        atmo_outputs_guides guides;
        float *no_block;
        atmo_outputs_guides_from_passes(&guide_res, &guides, &no_block);
        rc = atmo_outputs_write_denoised(&scene, &img, &guides, scene.image.samples, 0,
                                         ATMO_EXR_DEFAULT, outputs, n_out, &denoised, e);
        denoised.guide_seconds = guide_res.seconds_guides;
    }
    if (!rc && a->report)
        rc = merge_report(a->report, &scene, paths, n, outputs, n_out, &merged, &guide_res,
                          &denoised, e);
    if (!rc && !a->quiet)
        fprintf(stderr, "atmo merge: wrote %d image%s (%dx%d, %d sample%s/pixel) from %d part%s%s\n",
                n_out, n_out == 1 ? "" : "s", merged.width, merged.height, scene.image.samples,
                scene.image.samples == 1 ? "" : "s", n, n == 1 ? "" : "s",
                !denoised.applied ? ""
                : denoised.guided ? ", denoised with albedo and normal guides"
                                  : ", denoised (colour alone)");
    free(rgb);
    atmo_render_result_free(&guide_res);
    atmo_part_free(&merged);
    for (int i = 0; i < n; i++)
        atmo_part_free(&parts[i]);
    free(parts);
    return rc;
}

/* The outputs: formats, paths, none of them a part, none existing without --force. */
static int merge_check_outputs(merge_args *a, int n, output_paths *files, atmo_err *e)
{
    int rc = ATMO_OK;
    if (n == 0)
        return atmo_fail(e, ATMO_ERR_USAGE, "no parts given (atmo merge PART.exr... --output FILE)");
    if (a->n_out == 0)
        return atmo_fail(e, ATMO_ERR_USAGE, "no --output given; name the image(s) to write");
    for (int i = 0; i < a->n_out && !rc; i++) {
        if (atmo_image_format_from_path(a->outputs[i]) < 0)
            rc = atmo_fail(e, ATMO_ERR_USAGE,
                           "--output '%s': unknown image format (use .png, .hdr, .exr or .pfm)",
                           a->outputs[i]);
        else
            rc = output_paths_add(files, "--output", a->outputs[i], e);
    }
    int images = files->count;
    if (!rc && a->report)
        rc = output_paths_add(files, "--report", a->report, e);
    /* an output that is one of the parts would overwrite what is being read */
    for (int i = 0; i < n && !rc; i++) {
        char *real = realpath(a->parts[i], NULL);
        for (int k = 0; real && k < files->count && !rc; k++)
            if (strcmp(real, files->file[k]) == 0)
                rc = atmo_fail(e, ATMO_ERR_USAGE,
                               "%s '%s' is the part '%s'; write it elsewhere",
                               files->option[k], files->path[k], a->parts[i]);
        free(real);
    }
    for (int i = 0; i < files->count && !rc; i++)
        rc = overwrite_check(files->option[i], files->path[i], a->force, e);
    if (!rc && a->device)
        rc = atmo_cl_check_selector(a->device, e);
    a->n_out = images;
    for (int i = 0; i < images; i++)
        a->outputs[i] = files->path[i];
    return rc;
}

int cmd_merge(int argc, char **argv)
{
    atmo_err e = {{0}};
    static merge_args a;
    output_paths files = {0};
    int n = 0, rc;
    memset(&a, 0, sizeof a);
    if (!cli_parse(&merge_cli, &a, argc, argv, a.parts, &n, &rc))
        return rc;
    if (!(rc = merge_check_outputs(&a, n, &files, &e)))
        rc = merge_parts(&a, n, &e);
    if (rc)
        cli_fail(&merge_cli, rc, &e);
    output_paths_free(&files);
    return rc;
}
