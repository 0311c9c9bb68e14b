/* image_exr_read.c — reading an EXR file back whole: every channel as a float plane, and the
 * string attributes.
 *
 * For what atmo itself wrote (partial renders to merge, tests) and for tools: the first part of
 * a scanline file, any compression, channels of type FLOAT, HALF or UINT converted to float by
 * the library's decoder, each channel at full resolution (x and y sampling 1). The data window
 * may start anywhere; row 0 of a plane is its top row. Tiled and deep files, and subsampled
 * channels, are refused with a one-line error: nothing atmo writes has them.
 *
 * Written with OpenEXR's C Core API; the library's first error message goes into the atmo_err. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <openexr.h>
#include "atmo/image.h"

typedef struct {
    char msg[256];
} read_log;

static void on_error(exr_const_context_t ctxt, exr_result_t code, const char *msg)
{
    void *user = NULL;
    exr_get_user_data(ctxt, &user);
    read_log *log = user;
    if (log && log->msg[0] == '\0')
        snprintf(log->msg, sizeof log->msg, "%s", msg ? msg : exr_get_default_error_message(code));
}

static atmo_exr_channel *find_channel(atmo_exr_file *f, const char *name)
{
    for (int i = 0; i < f->channel_count; i++)
        if (strcmp(f->channels[i].name, name) == 0)
            return &f->channels[i];
    return NULL;
}

/* Allocate one plane per channel of the file's channel list. */
static int alloc_channels(exr_context_t c, atmo_exr_file *f, const char *path, atmo_err *e)
{
    const exr_attr_chlist_t *list = NULL;
    if (exr_get_channels(c, 0, &list) != EXR_ERR_SUCCESS || !list || list->num_channels < 1)
        return atmo_fail(e, ATMO_ERR_USAGE, "'%s' has no channels: not an image atmo can read",
                         path);
    f->channels = calloc((size_t)list->num_channels, sizeof *f->channels);
    if (!f->channels)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory reading '%s'", path);
    size_t plane = (size_t)f->width * (size_t)f->height;
    for (int i = 0; i < list->num_channels; i++) {
        const exr_attr_chlist_entry_t *ch = &list->entries[i];
        if (ch->x_sampling != 1 || ch->y_sampling != 1)
            return atmo_fail(e, ATMO_ERR_USAGE,
                             "'%s': channel '%s' is subsampled; only full-resolution channels "
                             "can be read", path, ch->name.str);
        atmo_exr_channel *out = &f->channels[f->channel_count++];
        snprintf(out->name, sizeof out->name, "%.*s", (int)ch->name.length, ch->name.str);
        out->data = malloc(plane * sizeof(float));
        if (!out->data)
            return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory reading '%s'", path);
    }
    return ATMO_OK;
}

static exr_result_t decode_pixels(exr_context_t c, atmo_exr_file *f, int min_y)
{
    int rows = 0, initialized = 0;
    exr_decode_pipeline_t d = EXR_DECODE_PIPELINE_INITIALIZER;
    exr_result_t r = exr_get_scanlines_per_chunk(c, 0, &rows);
    for (int y = 0; r == EXR_ERR_SUCCESS && y < f->height; y += rows) {
        exr_chunk_info_t ci;
        r = exr_read_scanline_chunk_info(c, 0, min_y + y, &ci);
        if (r == EXR_ERR_SUCCESS)
            r = initialized ? exr_decoding_update(c, 0, &ci, &d)
                            : exr_decoding_initialize(c, 0, &ci, &d);
        if (r != EXR_ERR_SUCCESS)
            break;
        for (int k = 0; k < d.channel_count; k++) {
            exr_coding_channel_info_t *ch = &d.channels[k];
            atmo_exr_channel *to = find_channel(f, ch->channel_name);
            if (!to) {
                r = EXR_ERR_INVALID_ARGUMENT;
                break;
            }
            size_t row0 = (size_t)(ci.start_y - min_y);
            ch->decode_to_ptr = (uint8_t *)(to->data + row0 * (size_t)f->width);
            ch->user_pixel_stride = (int32_t)sizeof(float);
            ch->user_line_stride = f->width * (int32_t)sizeof(float);
            ch->user_bytes_per_element = sizeof(float);
            ch->user_data_type = EXR_PIXEL_FLOAT;
        }
        if (r == EXR_ERR_SUCCESS && !initialized) {
            r = exr_decoding_choose_default_routines(c, 0, &d);
            initialized = r == EXR_ERR_SUCCESS;
        }
        if (r == EXR_ERR_SUCCESS)
            r = exr_decoding_run(c, 0, &d);
    }
    if (initialized) {
        exr_result_t z = exr_decoding_destroy(c, &d);
        if (r == EXR_ERR_SUCCESS)
            r = z;
    }
    return r;
}

static int read_attributes(exr_context_t c, atmo_exr_file *f, const char *path, atmo_err *e)
{
    int32_t n = 0;
    if (exr_get_attribute_count(c, 0, &n) != EXR_ERR_SUCCESS || n <= 0)
        return ATMO_OK;
    f->attributes = calloc((size_t)n, sizeof *f->attributes);
    if (!f->attributes)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory reading '%s'", path);
    for (int32_t i = 0; i < n; i++) {
        const exr_attribute_t *a = NULL;
        if (exr_get_attribute_by_index(c, 0, EXR_ATTR_LIST_FILE_ORDER, i, &a) != EXR_ERR_SUCCESS ||
            !a || a->type != EXR_ATTR_STRING || !a->string)
            continue;
        atmo_exr_attribute *out = &f->attributes[f->attribute_count];
        snprintf(out->name, sizeof out->name, "%s", a->name);
        out->value = malloc((size_t)a->string->length + 1);
        if (!out->value)
            return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory reading '%s'", path);
        memcpy(out->value, a->string->str, (size_t)a->string->length);
        out->value[a->string->length] = '\0';
        f->attribute_count++;
    }
    return ATMO_OK;
}

int atmo_exr_read(const char *path, atmo_exr_file *f, atmo_err *e)
{
    memset(f, 0, sizeof *f);
    read_log log = {""};
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = on_error;
    init.user_data = &log;
    exr_context_t c = NULL;
    exr_storage_t storage;
    exr_attr_box2i_t dw;
    int rc = ATMO_OK;
    if (exr_start_read(&c, path, &init) != EXR_ERR_SUCCESS) {
        rc = atmo_fail(e, ATMO_ERR_USAGE, "cannot read '%s' as OpenEXR: %s (is it an .exr file?)",
                       path, log.msg[0] ? log.msg : "unreadable");
        goto cleanup;
    }
    if (exr_get_storage(c, 0, &storage) != EXR_ERR_SUCCESS || storage != EXR_STORAGE_SCANLINE) {
        rc = atmo_fail(e, ATMO_ERR_USAGE,
                       "'%s' is a tiled or deep EXR file; only scanline files can be read", path);
        goto cleanup;
    }
    if (exr_get_data_window(c, 0, &dw) != EXR_ERR_SUCCESS) {
        rc = atmo_fail(e, ATMO_ERR_USAGE, "'%s' has no data window", path);
        goto cleanup;
    }
    int64_t w = (int64_t)dw.max.x - dw.min.x + 1, h = (int64_t)dw.max.y - dw.min.y + 1;
    if (w < 1 || h < 1 || w * h > (int64_t)1 << 30) {
        rc = atmo_fail(e, ATMO_ERR_USAGE, "'%s' has a %lldx%lld data window: not readable", path,
                       (long long)w, (long long)h);
        goto cleanup;
    }
    f->width = (int)w;
    f->height = (int)h;
    rc = alloc_channels(c, f, path, e);
    if (!rc && decode_pixels(c, f, dw.min.y) != EXR_ERR_SUCCESS)
        rc = atmo_fail(e, ATMO_ERR_USAGE,
                       "'%s' is damaged or cut short: OpenEXR cannot decode its pixels (%s)",
                       path, log.msg[0] ? log.msg : "damaged pixel data");
    if (!rc)
        rc = read_attributes(c, f, path, e);
cleanup:
    if (c)
        exr_finish(&c);
    if (rc)
        atmo_exr_file_free(f);
    return rc;
}

const float *atmo_exr_channel_data(const atmo_exr_file *f, const char *name)
{
    for (int i = 0; i < f->channel_count; i++)
        if (strcmp(f->channels[i].name, name) == 0)
            return f->channels[i].data;
    return NULL;
}

const char *atmo_exr_attribute_value(const atmo_exr_file *f, const char *name)
{
    for (int i = 0; i < f->attribute_count; i++)
        if (strcmp(f->attributes[i].name, name) == 0)
            return f->attributes[i].value;
    return NULL;
}

void atmo_exr_file_free(atmo_exr_file *f)
{
    for (int i = 0; i < f->channel_count; i++)
        free(f->channels[i].data);
    for (int i = 0; i < f->attribute_count; i++)
        free(f->attributes[i].value);
    free(f->channels);
    free(f->attributes);
    memset(f, 0, sizeof *f);
}
