/* cmd_merge.c — `atmo merge PART... --output FILE...`: the parts of a split render
 * (`atmo render --part I/N`, atmo/part.h) joined into the files the single render writes.
 *
 * Order: the outputs' formats and paths are checked (output_paths.h), every part is read, the
 * merge checks them (same scene hash and size, parts 1..N each once, every part complete in its
 * bands and empty elsewhere: atmo_part_merge), the scene stored in the parts is loaded and
 * validated; only then is anything written. Any failure is one line naming the file or the
 * part, exit status 2, and no output. The pixels are each copied from the part that rendered
 * them and the mean is atmo_session_read's, so with parts rendered on one device the files
 * equal a single-process render's bit for bit (atmo_outputs_write, host/render/outputs.c, writes both). Parts from
 * different devices merge with a warning: each pixel is then its own device's. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/image.h"
#include "atmo/part.h"
#include "atmo/scene.h"
#include "commands.h"
#include "output_paths.h"
#include "atmo/outputs.h"

#define MERGE_MAX_PARTS 4096
#define MERGE_MAX_OUTPUTS 8

static const char merge_usage[] =
    "usage: atmo merge PART.exr... --output FILE [--output FILE ...] [--quiet]\n"
    "\n"
    "Joins the N parts of a split render (atmo render --part I/N --output PART.exr) into the\n"
    "images the single render writes (.png .hdr .exr .pfm, format from the extension), bit for\n"
    "bit when the parts were rendered on one device. Refused with exit status 2 and no output:\n"
    "a file that is not a part, parts of different scenes, a part given twice, a missing part,\n"
    "an incomplete (interrupted) part.\n";

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
        fprintf(stderr, "atmo merge: wrote %d image%s (%dx%d, %d samples/pixel) from %d parts\n",
                n_out, n_out > 1 ? "s" : "", merged.width, merged.height, scene.image.samples, n);
    free(rgb);
    atmo_part_free(&merged);
    for (int i = 0; i < n; i++)
        atmo_part_free(&parts[i]);
    free(parts);
    return rc;
}

int cmd_merge(int argc, char **argv)
{
    atmo_err e = {{0}};
    const char **paths = calloc((size_t)argc, sizeof *paths);
    const char *outputs[MERGE_MAX_OUTPUTS];
    output_paths files = {0};
    int n = 0, n_out = 0, quiet = 0, rc = ATMO_OK;
    if (!paths) {
        fprintf(stderr, "atmo merge: out of memory\n");
        return ATMO_ERR_RUNTIME;
    }
    for (int i = 1; i < argc && !rc; i++) {
        const char *a = argv[i];
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            printf("%s", merge_usage);
            free(paths);
            return ATMO_OK;
        }
        if (strcmp(a, "--quiet") == 0 || strcmp(a, "-q") == 0)
            quiet = 1;
        else if (strcmp(a, "--output") == 0 || strcmp(a, "-o") == 0) {
            if (i + 1 == argc)
                rc = atmo_fail(&e, ATMO_ERR_USAGE, "%s needs a file name (atmo merge --help)", a);
            else if (n_out == MERGE_MAX_OUTPUTS)
                rc = atmo_fail(&e, ATMO_ERR_USAGE, "more than %d --output options",
                               MERGE_MAX_OUTPUTS);
            else
                outputs[n_out++] = argv[++i];
        } else if (a[0] == '-' && a[1] != 0)
            rc = atmo_fail(&e, ATMO_ERR_USAGE, "unknown option '%s' (atmo merge --help)", a);
        else if (n == MERGE_MAX_PARTS)
            rc = atmo_fail(&e, ATMO_ERR_USAGE, "more than %d parts", MERGE_MAX_PARTS);
        else
            paths[n++] = a;
    }
    if (!rc && n == 0)
        rc = atmo_fail(&e, ATMO_ERR_USAGE, "no parts given (atmo merge PART.exr... --output FILE)");
    if (!rc && n_out == 0)
        rc = atmo_fail(&e, ATMO_ERR_USAGE, "no --output given; name the image(s) to write");
    for (int i = 0; i < n_out && !rc; i++) {
        if (atmo_image_format_from_path(outputs[i]) < 0)
            rc = atmo_fail(&e, ATMO_ERR_USAGE,
                           "--output '%s': unknown image format (use .png, .hdr, .exr or .pfm)",
                           outputs[i]);
        else
            rc = output_paths_add(&files, "--output", outputs[i], &e);
    }
    /* an output that is one of the parts would overwrite what is being read */
    for (int i = 0; i < n && !rc; i++) {
        char *real = realpath(paths[i], NULL);
        for (int k = 0; real && k < files.count && !rc; k++)
            if (strcmp(real, files.file[k]) == 0)
                rc = atmo_fail(&e, ATMO_ERR_USAGE,
                               "--output '%s' is the part '%s'; write the image elsewhere",
                               files.path[k], paths[i]);
        free(real);
    }
    if (!rc) {
        for (int i = 0; i < files.count; i++)
            outputs[i] = files.path[i];
        rc = merge_parts(paths, n, outputs, files.count, quiet, &e);
    }
    if (rc)
        fprintf(stderr, "atmo merge: %s\n", e.msg);
    output_paths_free(&files);
    free(paths);
    return rc;
}
