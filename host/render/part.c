/* part.c — the parts of a split render (atmo/part.h): part files and their merge.
 *
 * The merge's checks, in order, each a usage error that names a file or a part: every file
 * reads as a part (the layers and attributes of part.h) whose stored hash is its scene text's;
 * all have the first file's scene hash, input hash (atmoInputHash: the heightmap's heights as
 * the render read them, since the scene names the file, not its contents), image size, N and
 * band rows; no part index appears
 * twice; none of 1..N is missing; each part has the requested samples in every pixel. Only
 * then are the rows copied, each to its place in the image (atmo_part_of_row).
 *
 * A part's pixels carry a checksum (atmoDataChecksum): FNV-1a 64 over the bytes of its planes
 * as stored, R, G, B (the mean), S1.R, S1.G, S1.B, S2.R, S2.G, S2.B and Samples.N in this
 * order, each plane's pixels in row order. One changed byte always changes it (each FNV step
 * is a bijection of the state for a fixed byte), so a flipped bit that the EXR codec decodes
 * without complaint is refused by the merge instead of becoming a wrong pixel. A file that
 * cannot be decoded (cut short, damaged chunks) is a usage error naming it. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/image.h"
#include "atmo/part.h"
#include "atmo/session.h"
#include "atmo/tiles.h"

static const char *const rgb_names[4] = {"R", "G", "B", NULL};
static const char *const count_names[4] = {"N", NULL, NULL, NULL};

unsigned long long atmo_part_scene_hash(const char *scene_json)
{
    unsigned long long h = 1469598103934665603ull;
    for (const unsigned char *c = (const unsigned char *)scene_json; *c; c++)
        h = (h ^ *c) * 1099511628211ull;
    return h;
}

/* FNV-1a 64 of n floats taken every stride from data + offset, continuing from h. */
static unsigned long long plane_hash(unsigned long long h, const float *data, size_t n,
                                     int stride, int offset)
{
    for (size_t i = 0; i < n; i++) {
        const unsigned char *b = (const unsigned char *)&data[i * (size_t)stride + (size_t)offset];
        for (size_t k = 0; k < sizeof(float); k++)
            h = (h ^ b[k]) * 1099511628211ull;
    }
    return h;
}

/* The checksum of the header's order over the mean (interleaved RGB), the sums and the counts. */
static unsigned long long data_checksum(const atmo_part *p, const float *mean, const float *count)
{
    size_t n = (size_t)p->width * (size_t)p->rows;
    unsigned long long h = 1469598103934665603ull;
    for (int c = 0; c < 3; c++)
        h = plane_hash(h, mean, n, 3, c);
    for (int c = 0; c < 3; c++)
        h = plane_hash(h, p->s1, n, 3, c);
    for (int c = 0; c < 3; c++)
        h = plane_hash(h, p->s2, n, 3, c);
    return plane_hash(h, count, n, 1, 0);
}

unsigned long long atmo_part_input_hash(int width, int height, const float *heights_m)
{
    if (!heights_m)
        return 0;
    float size[2] = {(float)width, (float)height};
    unsigned long long h = plane_hash(1469598103934665603ull, size, 2, 1, 0);
    return plane_hash(h, heights_m, (size_t)width * (size_t)height, 1, 0);
}

int atmo_part_row_count(int height, int part, int parts)
{
    int n = 0;
    for (int y = 0; y < height; y++)
        n += atmo_part_of_row(y, parts) == part;
    return n;
}

int atmo_part_alloc(atmo_part *p, int width, int height, int part, int parts,
                    const char *scene_json, atmo_err *e)
{
    memset(p, 0, sizeof *p);
    p->width = width;
    p->height = height;
    p->part = part;
    p->parts = parts;
    p->band_rows = ATMO_PART_BAND_ROWS;
    p->rows = atmo_part_row_count(height, part, parts);
    size_t pixels = (size_t)width * (size_t)p->rows;
    p->s1 = calloc(pixels * 3 + 1, sizeof(float));
    p->s2 = calloc(pixels * 3 + 1, sizeof(float));
    p->samples = calloc(pixels + 1, sizeof(int));
    p->scene_json = malloc(strlen(scene_json) + 1);
    if (!p->s1 || !p->s2 || !p->samples || !p->scene_json) {
        atmo_part_free(p);
        return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory for the sums of a %dx%d image", width,
                         height);
    }
    strcpy(p->scene_json, scene_json);
    p->scene_hash = atmo_part_scene_hash(scene_json);
    return ATMO_OK;
}

void atmo_part_pack(atmo_part *p, const float *s1, const float *s2, const int *samples)
{
    size_t w = (size_t)p->width, k = 0;
    for (int y = 0; y < p->height; y++) {
        if (atmo_part_of_row(y, p->parts) != p->part)
            continue;
        memcpy(p->s1 + 3 * w * k, s1 + 3 * w * (size_t)y, sizeof(float) * 3 * w);
        memcpy(p->s2 + 3 * w * k, s2 + 3 * w * (size_t)y, sizeof(float) * 3 * w);
        memcpy(p->samples + w * k, samples + w * (size_t)y, sizeof(int) * w);
        k++;
    }
}

void atmo_part_free(atmo_part *p)
{
    free(p->scene_json);
    free(p->samples);
    free(p->s2);
    free(p->s1);
    memset(p, 0, sizeof *p);
}

int atmo_part_write(const char *path, const atmo_part *p, atmo_err *e)
{
    size_t pixels = (size_t)p->width * (size_t)p->rows;
    float *mean = malloc(pixels * 3 * sizeof(float));
    float *count = malloc(pixels * sizeof(float));
    if (!mean || !count) {
        free(count);
        free(mean);
        return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory writing '%s'", path);
    }
    atmo_part_mean(p, mean);
    for (size_t i = 0; i < pixels; i++)
        count[i] = (float)p->samples[i];
    atmo_image_layer layers[3] = {
        {.name = "S1", .channels = 3, .data = p->s1},
        {.name = "S2", .channels = 3, .data = p->s2},
        {.name = "Samples", .channels = 1, .data = count}};
    for (int c = 0; c < 4; c++) {
        layers[0].channel_names[c] = layers[1].channel_names[c] = rgb_names[c];
        layers[2].channel_names[c] = count_names[c];
    }
    char part[32], rows[16], hash[24], size[32], sum[24], input[24];
    snprintf(input, sizeof input, "%016llx", p->input_hash);
    snprintf(sum, sizeof sum, "%016llx", data_checksum(p, mean, count));
    snprintf(part, sizeof part, "%d/%d", p->part, p->parts);
    snprintf(size, sizeof size, "%dx%d", p->width, p->height);
    snprintf(rows, sizeof rows, "%d", p->band_rows);
    snprintf(hash, sizeof hash, "%016llx", p->scene_hash);
    const char *const attributes[] = {"atmoPart",      part,          "atmoBandRows", rows,
                                      "atmoImageSize", size,         "atmoSceneHash", hash,          "atmoScene",    p->scene_json,
                                      "atmoDevice",    p->device,      "atmoDataChecksum", sum,
                                      "atmoInputHash", input};
    atmo_image_meta meta = {
        .quantity = "a part of a split render: its mean in R, G, B; the sums of the samples and "
                    "of their squares in S1, S2; the samples per pixel in Samples.N (atmo merge)",
        .software = "atmo " ATMO_VERSION,
        .attributes = attributes,
        .attribute_count = (int)(sizeof attributes / sizeof attributes[0] / 2)};
    atmo_image img = {.width = p->width, .height = p->rows, .rgb = mean, .layers = layers,
                      .layer_count = 3};
    int rc = atmo_image_write(path, &img, NULL, &meta, e);
    free(count);
    free(mean);
    return rc;
}

/* "I/N" with 1 <= I <= N, nothing else. */
static int parse_part(const char *text, int *part, int *parts)
{
    char tail;
    return text && sscanf(text, "%d/%d%c", part, parts, &tail) == 2 && *parts >= 1 &&
           *part >= 1 && *part <= *parts;
}

int atmo_part_read(const char *path, atmo_part *p, atmo_err *e)
{
    atmo_exr_file f;
    memset(p, 0, sizeof *p);
    int rc = atmo_exr_read(path, &f, e);
    if (rc) {
        atmo_exr_file_free(&f);
        return rc;
    }
    const char *part = atmo_exr_attribute_value(&f, "atmoPart");
    const char *rows = atmo_exr_attribute_value(&f, "atmoBandRows");
    const char *hash = atmo_exr_attribute_value(&f, "atmoSceneHash");
    const char *scene = atmo_exr_attribute_value(&f, "atmoScene");
    const char *device = atmo_exr_attribute_value(&f, "atmoDevice");
    const char *size = atmo_exr_attribute_value(&f, "atmoImageSize");
    const char *sum = atmo_exr_attribute_value(&f, "atmoDataChecksum");
    const char *input = atmo_exr_attribute_value(&f, "atmoInputHash");
    static const char *const plane_names[10] = {"S1.R", "S1.G", "S1.B", "S2.R", "S2.G",
                                                "S2.B", "Samples.N", "R", "G", "B"};
    const float *planes[10];
    float *mean = NULL, *count = NULL;
    unsigned long long stored_sum = 0;
    unsigned long long input_hash = 0;
    int complete = part && rows && hash && scene && device && size && sum && input;
    for (int k = 0; k < 10; k++)
        complete = complete && (planes[k] = atmo_exr_channel_data(&f, plane_names[k])) != NULL;
    int i_part = 0, n_parts = 0, band_rows = 0, width = 0, height = 0;
    unsigned long long stored = 0;
    char tail;
    if (!complete || !parse_part(part, &i_part, &n_parts) ||
        sscanf(rows, "%d%c", &band_rows, &tail) != 1 || band_rows < 1 ||
        sscanf(hash, "%16llx%c", &stored, &tail) != 1 ||
        sscanf(sum, "%16llx%c", &stored_sum, &tail) != 1 ||
        sscanf(input, "%16llx%c", &input_hash, &tail) != 1 ||
        sscanf(size, "%dx%d%c", &width, &height, &tail) != 2 || width < 1 || height < 1) {
        rc = atmo_fail(e, ATMO_ERR_USAGE,
                       "'%s' is not a part of a split render (it lacks the S1, S2, Samples "
                       "layers or the atmoPart, atmoScene, atmoDataChecksum, atmoInputHash attributes); make "
                       "parts with this atmo's render --part I/N --output FILE.exr",
                       path);
        goto cleanup;
    }
    if (band_rows != ATMO_PART_BAND_ROWS) {
        rc = atmo_fail(e, ATMO_ERR_USAGE,
                       "'%s' cuts the image into bands of %d rows; this atmo's parts have %d "
                       "(render the parts with one atmo version)",
                       path, band_rows, ATMO_PART_BAND_ROWS);
        goto cleanup;
    }
    if ((rc = atmo_part_alloc(p, width, height, i_part, n_parts, scene, e)))
        goto cleanup;
    if (f.width != width || f.height != p->rows) {
        rc = atmo_fail(e, ATMO_ERR_USAGE,
                       "'%s' is damaged: part %d/%d of a %dx%d image has %d rows of %d pixels, "
                       "but the file holds %dx%d; render that part again",
                       path, i_part, n_parts, width, height, p->rows, width, f.width, f.height);
        goto cleanup;
    }
    if (p->scene_hash != stored) {
        rc = atmo_fail(e, ATMO_ERR_USAGE,
                       "'%s' is damaged: its scene does not hash to its atmoSceneHash %s; render "
                       "that part again",
                       path, hash);
        goto cleanup;
    }
    snprintf(p->device, sizeof p->device, "%s", device);
    p->input_hash = input_hash;
    size_t pixels = (size_t)f.width * (size_t)f.height;
    mean = malloc(pixels * 3 * sizeof(float) + 1);
    count = malloc(pixels * sizeof(float) + 1);
    if (!mean || !count) {
        rc = atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory reading '%s'", path);
        goto cleanup;
    }
    for (size_t i = 0; i < pixels; i++) {
        for (int c = 0; c < 3; c++) {
            p->s1[3 * i + c] = planes[c][i];
            p->s2[3 * i + c] = planes[3 + c][i];
            mean[3 * i + c] = planes[7 + c][i];
        }
        count[i] = planes[6][i];
        p->samples[i] = (int)planes[6][i];
    }
    if (data_checksum(p, mean, count) != stored_sum)
        rc = atmo_fail(e, ATMO_ERR_USAGE,
                       "'%s' (part %d/%d) is damaged: its pixels do not match their checksum "
                       "atmoDataChecksum %s; render that part again",
                       path, i_part, n_parts, sum);
cleanup:
    free(count);
    free(mean);
    if (rc)
        atmo_part_free(p);
    atmo_exr_file_free(&f);
    return rc;
}

/* Every pixel of the part has `samples` samples. */
static int check_complete(const atmo_part *p, const char *path, int samples, atmo_err *e)
{
    size_t n = (size_t)p->width * (size_t)p->rows;
    int lo = n ? p->samples[0] : samples, hi = lo;
    for (size_t i = 1; i < n; i++) {
        lo = p->samples[i] < lo ? p->samples[i] : lo;
        hi = p->samples[i] > hi ? p->samples[i] : hi;
    }
    if (lo == samples && hi == samples)
        return ATMO_OK;
    if (lo == hi)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "'%s' (part %d/%d) is incomplete: %d samples in every pixel, its "
                         "scene %d (an interrupted render); render that part again",
                         path, p->part, p->parts, lo, samples);
    return atmo_fail(e, ATMO_ERR_USAGE,
                     "'%s' (part %d/%d) is incomplete: %d to %d samples per pixel, its scene %d "
                     "in every pixel (an interrupted render); render that part again",
                     path, p->part, p->parts, lo, hi, samples);
}

int atmo_part_merge(const atmo_part *parts, const char *const *paths, int n, int samples,
                    atmo_part *out, atmo_err *e)
{
    memset(out, 0, sizeof *out);
    if (n < 1)
        return atmo_fail(e, ATMO_ERR_USAGE, "no parts to merge");
    const atmo_part *a = &parts[0];
    int *seen = calloc((size_t)a->parts + 1, sizeof *seen);
    if (!seen)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory for %d parts", a->parts);
    int rc = ATMO_OK;
    for (int k = 0; k < n && !rc; k++) {
        const atmo_part *p = &parts[k];
        if (p->scene_hash != a->scene_hash)
            rc = atmo_fail(e, ATMO_ERR_USAGE,
                           "'%s' is a part of another scene (hash %016llx, '%s' has %016llx); "
                           "merge only the parts of one render",
                           paths[k], p->scene_hash, paths[0], a->scene_hash);
        else if (p->input_hash != a->input_hash)
            rc = atmo_fail(e, ATMO_ERR_USAGE,
                           "'%s' was rendered from other input data than '%s' (the heightmap's "
                           "heights hash to %016llx and %016llx) under the same scene; merge only "
                           "the parts of one render",
                           paths[k], paths[0], p->input_hash, a->input_hash);
        else if (p->width != a->width || p->height != a->height || p->parts != a->parts ||
                 p->band_rows != a->band_rows)
            rc = atmo_fail(e, ATMO_ERR_USAGE,
                           "'%s' is part %d/%d of a %dx%d image in bands of %d rows, '%s' part "
                           "%d/%d of %dx%d in bands of %d; merge only the parts of one render",
                           paths[k], p->part, p->parts, p->width, p->height, p->band_rows,
                           paths[0], a->part, a->parts, a->width, a->height, a->band_rows);
        else if (seen[p->part])
            rc = atmo_fail(e, ATMO_ERR_USAGE,
                           "'%s' is part %d/%d again (so is '%s'); give each part once",
                           paths[k], p->part, p->parts, paths[seen[p->part] - 1]);
        else
            seen[p->part] = k + 1;
    }
    for (int i = 1; i <= a->parts && !rc; i++)
        if (!seen[i])
            rc = atmo_fail(e, ATMO_ERR_USAGE,
                           "part %d/%d is missing (%d of %d parts given); render it with "
                           "--part %d/%d and merge all of them",
                           i, a->parts, n, a->parts, i, a->parts);
    for (int k = 0; k < n && !rc; k++)
        rc = check_complete(&parts[k], paths[k], samples, e);
    if (!rc && (rc = atmo_part_alloc(out, a->width, a->height, 1, 1, a->scene_json, e)) == ATMO_OK) {
        snprintf(out->device, sizeof out->device, "%s", a->device);
        size_t w = (size_t)a->width;
        int *next = calloc((size_t)a->parts + 1, sizeof *next); /* packed row per part */
        if (!next)
            rc = atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory for %d parts", a->parts);
        for (int y = 0; next && y < a->height; y++) {
            int i = atmo_part_of_row(y, a->parts);
            const atmo_part *p = &parts[seen[i] - 1];
            size_t k = (size_t)next[i]++;
            memcpy(out->s1 + 3 * w * (size_t)y, p->s1 + 3 * w * k, sizeof(float) * 3 * w);
            memcpy(out->s2 + 3 * w * (size_t)y, p->s2 + 3 * w * k, sizeof(float) * 3 * w);
            memcpy(out->samples + w * (size_t)y, p->samples + w * k, sizeof(int) * w);
        }
        free(next);
        if (rc)
            atmo_part_free(out);
    }
    free(seen);
    return rc;
}

void atmo_part_mean(const atmo_part *p, float *rgb)
{
    size_t pixels = (size_t)p->width * (size_t)p->rows;
    for (size_t i = 0; i < pixels; i++)
        for (int c = 0; c < 3; c++)
            rgb[3 * i + c] = atmo_session_mean(p->s1[3 * i + c], p->samples[i]);
}
