/* cmd_merge.c — `atmo merge PART... --output FILE...`: the parts of a split render
 * (`atmo render --part I/N`, atmo/part.h) joined into the files the single render writes.
 *
 * Order: the outputs' formats and paths are checked (output_paths.h), every part is read, the
 * merge checks them (same scene hash and size, parts 1..N each once, every part complete in its
 * bands and empty elsewhere: atmo_part_merge), the scene stored in the parts is loaded and
 * validated; only then is anything written. An output that exists is refused unless --force.
 * Any failure is one line naming the file or the part, exit status 2, and no output. The pixels are each copied from the part that rendered
 * them and the mean is atmo_session_read's, so with parts rendered on one device the files
 * equal a single-process render's bit for bit (atmo_outputs_write, host/render/outputs.c, writes both). Parts from
 * different devices merge with a warning: each pixel is then its own device's. */
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/image.h"
#include "atmo/part.h"
#include "atmo/scene.h"
#include "cli_flags.h"
#include "commands.h"
#include "output_paths.h"
#include "overwrite.h"
#include "atmo/outputs.h"

#define MERGE_MAX_PARTS 4096
#define MERGE_MAX_OUTPUTS 8

/* The flags' destinations (merge_flags) and the parts, given as arguments. */
typedef struct merge_args {
    const char *outputs[MERGE_MAX_OUTPUTS];
    int n_out, quiet, force;
    const char *parts[MERGE_MAX_PARTS];
} merge_args;

#define MERGE_FLAG(member) offsetof(merge_args, member)

static const cli_flag merge_flags[] = {
    {.type = CLI_PATH, .name = "--output", .alias = "-o", .offset = MERGE_FLAG(outputs),
     .repeat = MERGE_MAX_OUTPUTS, .count_offset = MERGE_FLAG(n_out), .def = "none: required",
     .help = "image to write, format from the extension (repeatable)"},
    {.type = CLI_BOOL, .name = "--force", .offset = MERGE_FLAG(force),
     .help = "overwrite outputs that exist (without it an existing file is an\nerror)"},
    {.type = CLI_BOOL, .name = "--quiet", .alias = "-q", .offset = MERGE_FLAG(quiet),
     .help = "no summary line"},
    {.type = CLI_END},
};

static const cli_command merge_cli = {
    .name = "merge",
    .synopsis = "PART.exr... --output FILE [--output FILE ...] [--force] [--quiet]",
    .about = "Joins the N parts of a split render (atmo render --part I/N --output PART.exr) into the\n"
             "images the single render writes (.png .hdr .exr .pfm, format from the extension), bit for\n"
             "bit when the parts were rendered on one device. Refused with exit status 2 and no output:\n"
             "a file that is not a part, parts of different scenes, a part given twice, a missing part,\n"
             "an incomplete (interrupted) part, an output that exists (without --force).\n",
    .flags = merge_flags,
    .max_positional = MERGE_MAX_PARTS,
};

static int merge_parts(const char *const *paths, int n, const char *const *outputs, int n_out,
                       int quiet, atmo_err *e)
{
    atmo_part *parts = calloc((size_t)n, sizeof *parts), merged = {0};
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
        atmo_image img = {.width = merged.width, .height = merged.height, .rgb = rgb};
        rc = atmo_outputs_write(&scene, &img, scene.image.samples, 0, ATMO_EXR_DEFAULT, outputs,
                                  n_out, e);
    }
    if (!rc && !quiet)
        fprintf(stderr, "atmo merge: wrote %d image%s (%dx%d, %d sample%s/pixel) from %d part%s\n",
                n_out, n_out == 1 ? "" : "s", merged.width, merged.height, scene.image.samples,
                scene.image.samples == 1 ? "" : "s", n, n == 1 ? "" : "s");
    free(rgb);
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
    /* an output that is one of the parts would overwrite what is being read */
    for (int i = 0; i < n && !rc; i++) {
        char *real = realpath(a->parts[i], NULL);
        for (int k = 0; real && k < files->count && !rc; k++)
            if (strcmp(real, files->file[k]) == 0)
                rc = atmo_fail(e, ATMO_ERR_USAGE,
                               "--output '%s' is the part '%s'; write the image elsewhere",
                               files->path[k], a->parts[i]);
        free(real);
    }
    for (int i = 0; i < files->count && !rc; i++)
        rc = overwrite_check("--output", files->path[i], a->force, e);
    a->n_out = files->count;
    for (int i = 0; i < files->count; i++)
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
        rc = merge_parts(a.parts, n, a.outputs, a.n_out, a.quiet, &e);
    if (rc)
        cli_fail(&merge_cli, rc, &e);
    output_paths_free(&files);
    return rc;
}
