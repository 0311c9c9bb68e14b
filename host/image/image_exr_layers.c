/* image_exr_layers.c — OpenEXR files of named float layers and string attributes, written and
 * read back exactly (atmo/image.h: atmo_image_write_exr_layers, atmo_image_read_exr_layers).
 *
 * A layer is one 32-bit float channel of width x height values, row 0 at the top, under any
 * EXR channel name ("S1.R", "N"); the file is one scanline part with ZIP compression, which is
 * lossless, so every float (and every bit of it: the raw sums of a split render, atmo/part.h)
 * reads back unchanged. String attributes carry what the layers mean (the resolved scene, its
 * hash). The reader takes any scanline or tiled single-part EXR whose channels are FLOAT (HALF
 * and UINT are converted to float by the library's decoder) and keeps every string attribute.
 *
 * Written to the temporary path of fileio.h and renamed on success, removed on any error; the
 * library's messages go into the atmo_err. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <openexr.h>
#include "atmo/fileio.h"
#include "atmo/image.h"

typedef struct {
    char msg[256];
} layers_log;

static void on_exr_error(exr_const_context_t ctxt, exr_result_t code, const char *msg)
{
    void *user = NULL;
    exr_get_user_data(ctxt, &user);
    layers_log *log = user;
    if (log && log->msg[0] == '\0')
        snprintf(log->msg, sizeof log->msg, "%s", msg ? msg : exr_get_default_error_message(code));
}

/* Encode every chunk of rows, each channel from its layer (the library sorts channels by name). */
static exr_result_t encode_layers(exr_context_t ctxt, int width, int height,
                                  const atmo_image_layer *layers, int count)
{
    int rows_per_chunk = 0;
    exr_result_t r = exr_get_scanlines_per_chunk(ctxt, 0, &rows_per_chunk);
    exr_encode_pipeline_t encoder = EXR_ENCODE_PIPELINE_INITIALIZER;
    int initialized = 0;
    for (int y = 0; r == EXR_ERR_SUCCESS && y < height; y += rows_per_chunk) {
        exr_chunk_info_t chunk;
        r = exr_write_scanline_chunk_info(ctxt, 0, y, &chunk);
        if (r != EXR_ERR_SUCCESS)
            break;
        r = initialized ? exr_encoding_update(ctxt, 0, &chunk, &encoder)
                        : exr_encoding_initialize(ctxt, 0, &chunk, &encoder);
        if (r != EXR_ERR_SUCCESS)
            break;
        for (int c = 0; c < encoder.channel_count; c++) {
            exr_coding_channel_info_t *ch = &encoder.channels[c];
            const float *data = NULL;
            for (int k = 0; k < count && !data; k++)
                if (strcmp(layers[k].name, ch->channel_name) == 0)
                    data = layers[k].data;
            ch->encode_from_ptr = (const uint8_t *)(data + (size_t)y * (size_t)width);
            ch->user_pixel_stride = (int32_t)sizeof(float);
            ch->user_line_stride = width * (int32_t)sizeof(float);
            ch->user_bytes_per_element = sizeof(float);
            ch->user_data_type = EXR_PIXEL_FLOAT;
        }
        if (!initialized) {
            r = exr_encoding_choose_default_routines(ctxt, 0, &encoder);
            if (r != EXR_ERR_SUCCESS)
                break;
            initialized = 1;
        }
        r = exr_encoding_run(ctxt, 0, &encoder);
    }
    if (initialized) {
        exr_result_t d = exr_encoding_destroy(ctxt, &encoder);
        if (r == EXR_ERR_SUCCESS)
            r = d;
    }
    return r;
}

int atmo_image_write_exr_layers(const char *path, int width, int height,
                                const atmo_image_layer *layers, int count,
                                const atmo_image_attr *attrs, int attr_count, atmo_err *e)
{
    if (width < 1 || height < 1 || count < 1)
        return atmo_fail(e, ATMO_ERR_USAGE, "cannot write '%s': an EXR needs pixels and a layer",
                         path);
    for (int k = 0; k < count; k++)
        for (int j = 0; j < k; j++)
            if (strcmp(layers[j].name, layers[k].name) == 0)
                return atmo_fail(e, ATMO_ERR_USAGE, "cannot write '%s': two layers named '%s'",
                                 path, layers[k].name);
    char tmp[ATMO_TMP_PATH_MAX];
    layers_log log = {""};
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = on_exr_error;
    init.user_data = &log;
    exr_context_t ctxt = NULL;
    int part = -1;
    atmo_tmp_path(path, tmp);
    exr_result_t r = exr_start_write(&ctxt, tmp, EXR_WRITE_FILE_DIRECTLY, &init);
    if (r == EXR_ERR_SUCCESS)
        r = exr_add_part(ctxt, NULL, EXR_STORAGE_SCANLINE, &part);
    if (r == EXR_ERR_SUCCESS)
        r = exr_initialize_required_attr_simple(ctxt, part, width, height, EXR_COMPRESSION_ZIP);
    for (int k = 0; k < count && r == EXR_ERR_SUCCESS; k++)
        r = exr_add_channel(ctxt, part, layers[k].name, EXR_PIXEL_FLOAT, EXR_PERCEPTUALLY_LINEAR,
                            1, 1);
    for (int k = 0; k < attr_count && r == EXR_ERR_SUCCESS; k++)
        r = exr_attr_set_string(ctxt, part, attrs[k].name, attrs[k].value);
    if (r == EXR_ERR_SUCCESS)
        r = exr_write_header(ctxt);
    if (r == EXR_ERR_SUCCESS)
        r = encode_layers(ctxt, width, height, layers, count);
    exr_result_t fin = ctxt ? exr_finish(&ctxt) : EXR_ERR_SUCCESS;
    if (r == EXR_ERR_SUCCESS)
        r = fin;
    if (r != EXR_ERR_SUCCESS) {
        atmo_atomic_abort(NULL, tmp);
        return atmo_fail(e, ATMO_ERR_RUNTIME,
                         "cannot write '%s': OpenEXR: %s (check the directory exists and is "
                         "writable)",
                         path, log.msg[0] ? log.msg : exr_get_default_error_message(r));
    }
    return atmo_atomic_commit(NULL, tmp, path, e);
}

void atmo_exr_layers_free(atmo_exr_layers *f)
{
    for (int k = 0; k < f->count; k++) {
        free(f->name[k]);
        free(f->data[k]);
    }
    for (int k = 0; k < f->attr_count; k++) {
        free(f->attr_name[k]);
        free(f->attr_value[k]);
    }
    free(f->name);
    free(f->data);
    free(f->attr_name);
    free(f->attr_value);
    memset(f, 0, sizeof *f);
}

static char *copy_text(const char *s, int length)
{
    char *c = malloc((size_t)length + 1);
    if (c) {
        memcpy(c, s, (size_t)length);
        c[length] = 0;
    }
    return c;
}

/* Every string attribute of part 0, copied. */
static int read_attributes(exr_const_context_t ctxt, atmo_exr_layers *f)
{
    int32_t n = 0;
    if (exr_get_attribute_count(ctxt, 0, &n) != EXR_ERR_SUCCESS)
        return 0;
    f->attr_name = calloc((size_t)n + 1, sizeof *f->attr_name);
    f->attr_value = calloc((size_t)n + 1, sizeof *f->attr_value);
    if (!f->attr_name || !f->attr_value)
        return 0;
    for (int32_t i = 0; i < n; i++) {
        const exr_attribute_t *a = NULL;
        if (exr_get_attribute_by_index(ctxt, 0, EXR_ATTR_LIST_FILE_ORDER, i, &a) !=
            EXR_ERR_SUCCESS)
            return 0;
        if (a->type != EXR_ATTR_STRING)
            continue;
        int k = f->attr_count;
        f->attr_name[k] = copy_text(a->name, (int)strlen(a->name));
        f->attr_value[k] = copy_text(a->string->str, a->string->length);
        f->attr_count++;
        if (!f->attr_name[k] || !f->attr_value[k])
            return 0;
    }
    return 1;
}

/* Decode every chunk of part 0 into the layers (planar floats, row 0 = the data window's top). */
static exr_result_t decode_layers(exr_const_context_t ctxt, atmo_exr_layers *f, int min_y)
{
    int32_t chunks = 0;
    exr_result_t r = exr_get_chunk_count(ctxt, 0, &chunks);
    exr_storage_t storage;
    if (r == EXR_ERR_SUCCESS)
        r = exr_get_storage(ctxt, 0, &storage);
    if (r == EXR_ERR_SUCCESS && storage != EXR_STORAGE_SCANLINE)
        return EXR_ERR_FEATURE_NOT_IMPLEMENTED;
    int rows_per_chunk = 0;
    if (r == EXR_ERR_SUCCESS)
        r = exr_get_scanlines_per_chunk(ctxt, 0, &rows_per_chunk);
    exr_decode_pipeline_t decoder = EXR_DECODE_PIPELINE_INITIALIZER;
    int initialized = 0;
    for (int32_t c = 0; r == EXR_ERR_SUCCESS && c < chunks; c++) {
        exr_chunk_info_t chunk;
        r = exr_read_scanline_chunk_info(ctxt, 0, min_y + c * rows_per_chunk, &chunk);
        if (r != EXR_ERR_SUCCESS)
            break;
        r = initialized ? exr_decoding_update(ctxt, 0, &chunk, &decoder)
                        : exr_decoding_initialize(ctxt, 0, &chunk, &decoder);
        if (r != EXR_ERR_SUCCESS)
            break;
        for (int k = 0; k < decoder.channel_count; k++) {
            exr_coding_channel_info_t *ch = &decoder.channels[k];
            float *data = NULL;
            for (int j = 0; j < f->count && !data; j++)
                if (strcmp(f->name[j], ch->channel_name) == 0)
                    data = f->data[j];
            ch->decode_to_ptr =
                (uint8_t *)(data + (size_t)(chunk.start_y - min_y) * (size_t)f->width);
            ch->user_pixel_stride = (int32_t)sizeof(float);
            ch->user_line_stride = f->width * (int32_t)sizeof(float);
            ch->user_bytes_per_element = sizeof(float);
            ch->user_data_type = EXR_PIXEL_FLOAT;
        }
        if (!initialized) {
            r = exr_decoding_choose_default_routines(ctxt, 0, &decoder);
            if (r != EXR_ERR_SUCCESS)
                break;
            initialized = 1;
        }
        r = exr_decoding_run(ctxt, 0, &decoder);
    }
    if (initialized) {
        exr_result_t d = exr_decoding_destroy(ctxt, &decoder);
        if (r == EXR_ERR_SUCCESS)
            r = d;
    }
    return r;
}

int atmo_image_read_exr_layers(const char *path, atmo_exr_layers *f, atmo_err *e)
{
    layers_log log = {""};
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = on_exr_error;
    init.user_data = &log;
    exr_context_t ctxt = NULL;
    exr_attr_box2i_t box;
    const exr_attr_chlist_t *channels = NULL;
    int rc = ATMO_OK;
    memset(f, 0, sizeof *f);
    exr_result_t r = exr_start_read(&ctxt, path, &init);
    if (r == EXR_ERR_SUCCESS)
        r = exr_get_data_window(ctxt, 0, &box);
    if (r == EXR_ERR_SUCCESS)
        r = exr_get_channels(ctxt, 0, &channels);
    if (r != EXR_ERR_SUCCESS)
        goto library_error;
    f->width = box.max.x - box.min.x + 1;
    f->height = box.max.y - box.min.y + 1;
    size_t pixels = (size_t)f->width * (size_t)f->height;
    f->name = calloc((size_t)channels->num_channels + 1, sizeof *f->name);
    f->data = calloc((size_t)channels->num_channels + 1, sizeof *f->data);
    if (!f->name || !f->data)
        goto out_of_memory;
    for (int k = 0; k < channels->num_channels; k++) {
        const exr_attr_chlist_entry_t *ch = &channels->entries[k];
        if (ch->x_sampling != 1 || ch->y_sampling != 1) {
            rc = atmo_fail(e, ATMO_ERR_USAGE,
                           "'%s': channel '%s' is subsampled; atmo reads full-resolution layers",
                           path, ch->name.str);
            goto cleanup;
        }
        f->name[k] = copy_text(ch->name.str, ch->name.length);
        f->data[k] = calloc(pixels, sizeof(float));
        f->count++;
        if (!f->name[k] || !f->data[k])
            goto out_of_memory;
    }
    if (!read_attributes(ctxt, f))
        goto out_of_memory;
    r = decode_layers(ctxt, f, box.min.y);
    if (r == EXR_ERR_FEATURE_NOT_IMPLEMENTED) {
        rc = atmo_fail(e, ATMO_ERR_USAGE, "'%s' is a tiled EXR; atmo reads scanline EXR files",
                       path);
        goto cleanup;
    }
    if (r != EXR_ERR_SUCCESS)
        goto library_error;
    goto cleanup;
out_of_memory:
    rc = atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory reading '%s'", path);
    goto cleanup;
library_error:
    rc = atmo_fail(e, ATMO_ERR_USAGE, "cannot read '%s': OpenEXR: %s (is it an EXR file?)", path,
                   log.msg[0] ? log.msg : exr_get_default_error_message(r));
cleanup:
    if (ctxt)
        exr_finish(&ctxt);
    if (rc)
        atmo_exr_layers_free(f);
    return rc;
}

const float *atmo_exr_layer(const atmo_exr_layers *f, const char *name)
{
    for (int k = 0; k < f->count; k++)
        if (strcmp(f->name[k], name) == 0)
            return f->data[k];
    return NULL;
}

const char *atmo_exr_attr(const atmo_exr_layers *f, const char *name)
{
    for (int k = 0; k < f->attr_count; k++)
        if (strcmp(f->attr_name[k], name) == 0)
            return f->attr_value[k];
    return NULL;
}
