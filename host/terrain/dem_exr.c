/* dem_exr.c — an OpenEXR heightmap: one channel of heights in metres, through OpenEXR's C API.
 *
 * The first part of the file is read, scanline or tiled (the full-resolution level of a tiled
 * part); it must hold exactly one channel, sampled at every pixel (x and y sampling 1), of any
 * pixel type (half, float or uint; the library converts each to float: half's 11-bit mantissa
 * gives heights to 1 part in 2048, float's to 1 in 2^24). The grid is the data window, its first
 * row north. Non-finite samples count as missing (dem.c fills them). The extent comes from
 * terrain.heightmap_file_extent_m: EXR carries no georeference. Library messages are collected into
 * the one-line error instead of being printed. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <openexr.h>
#include "dem_read.h"

typedef struct {
    char msg[256];
} exr_log;

static void on_error(exr_const_context_t ctxt, exr_result_t code, const char *msg)
{
    void *user = NULL;
    exr_get_user_data(ctxt, &user);
    exr_log *log = user;
    if (log && log->msg[0] == '\0')
        snprintf(log->msg, sizeof log->msg, "%s", msg ? msg : exr_get_default_error_message(code));
}

/* Decode the chunk into the grid at pixel (x, y) of the data window. */
static exr_result_t decode_chunk(exr_context_t ctxt, const exr_chunk_info_t *chunk, int x, int y,
                                 float *grid, int width, exr_decode_pipeline_t *decoder,
                                 int *initialized)
{
    exr_result_t r = *initialized ? exr_decoding_update(ctxt, 0, chunk, decoder)
                                  : exr_decoding_initialize(ctxt, 0, chunk, decoder);
    if (r != EXR_ERR_SUCCESS)
        return r;
    *initialized = 1;
    exr_coding_channel_info_t *ch = &decoder->channels[0];
    ch->decode_to_ptr = (uint8_t *)(grid + (size_t)y * (size_t)width + (size_t)x);
    ch->user_pixel_stride = (int32_t)sizeof(float);
    ch->user_line_stride = width * (int32_t)sizeof(float);
    ch->user_bytes_per_element = sizeof(float);
    ch->user_data_type = EXR_PIXEL_FLOAT;
    r = exr_decoding_choose_default_routines(ctxt, 0, decoder);
    if (r == EXR_ERR_SUCCESS)
        r = exr_decoding_run(ctxt, 0, decoder);
    return r;
}

static exr_result_t read_scanlines(exr_context_t ctxt, int y0, float *grid, int width, int height,
                                   exr_decode_pipeline_t *decoder, int *initialized)
{
    int rows = 0;
    exr_result_t r = exr_get_scanlines_per_chunk(ctxt, 0, &rows);
    for (int y = 0; r == EXR_ERR_SUCCESS && y < height; y += rows) {
        exr_chunk_info_t chunk;
        r = exr_read_scanline_chunk_info(ctxt, 0, y0 + y, &chunk);
        if (r == EXR_ERR_SUCCESS)
            r = decode_chunk(ctxt, &chunk, 0, chunk.start_y - y0, grid, width, decoder,
                             initialized);
    }
    return r;
}

static exr_result_t read_tiles(exr_context_t ctxt, float *grid, int width, int height,
                               exr_decode_pipeline_t *decoder, int *initialized)
{
    int32_t tw = 0, th = 0;
    exr_result_t r = exr_get_tile_sizes(ctxt, 0, 0, 0, &tw, &th);
    if (r == EXR_ERR_SUCCESS && (tw < 1 || th < 1))
        r = EXR_ERR_BAD_CHUNK_LEADER;
    for (int ty = 0; r == EXR_ERR_SUCCESS && ty * th < height; ty++)
        for (int tx = 0; r == EXR_ERR_SUCCESS && tx * tw < width; tx++) {
            exr_chunk_info_t chunk;
            r = exr_read_tile_chunk_info(ctxt, 0, tx, ty, 0, 0, &chunk);
            if (r == EXR_ERR_SUCCESS)
                r = decode_chunk(ctxt, &chunk, tx * tw, ty * th, grid, width, decoder,
                                 initialized);
        }
    return r;
}

int dem_read_exr(const char *path, const atmo_dem_options *o, atmo_dem *dem, atmo_err *e)
{
    int rc = ATMO_OK;
    exr_log log = {""};
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = on_error;
    init.user_data = &log;
    exr_context_t ctxt = NULL;
    exr_decode_pipeline_t decoder = EXR_DECODE_PIPELINE_INITIALIZER;
    int initialized = 0;
    float *grid = NULL;
    const char *what = "header";

    exr_result_t r = exr_start_read(&ctxt, path, &init);
    exr_storage_t storage = EXR_STORAGE_SCANLINE;
    const exr_attr_chlist_t *channels = NULL;
    exr_attr_box2i_t window;
    if (r == EXR_ERR_SUCCESS)
        r = exr_get_storage(ctxt, 0, &storage);
    if (r == EXR_ERR_SUCCESS)
        r = exr_get_channels(ctxt, 0, &channels);
    if (r == EXR_ERR_SUCCESS)
        r = exr_get_data_window(ctxt, 0, &window);
    if (r != EXR_ERR_SUCCESS)
        goto library_error;
    if (storage != EXR_STORAGE_SCANLINE && storage != EXR_STORAGE_TILED) {
        rc = atmo_fail(e, ATMO_ERR_USAGE,
                       "%s: a deep EXR; a heightmap is a flat image of one channel", path);
        goto cleanup;
    }
    if (channels->num_channels != 1) {
        char names[160] = "";
        size_t used = 0;
        for (int c = 0; c < channels->num_channels && used < sizeof names; c++)
            used += (size_t)snprintf(names + used, sizeof names - used, "%s%s", c ? ", " : "",
                                     channels->entries[c].name.str);
        rc = atmo_fail(e, ATMO_ERR_USAGE,
                       "%s: an EXR with %d channels (%s); a heightmap holds one channel of "
                       "heights in metres",
                       path, channels->num_channels, names);
        goto cleanup;
    }
    const exr_attr_chlist_entry_t *ch = &channels->entries[0];
    if (ch->x_sampling != 1 || ch->y_sampling != 1) {
        rc = atmo_fail(e, ATMO_ERR_USAGE,
                       "%s: channel %s is subsampled (%d x %d); store one height per pixel", path,
                       ch->name.str, ch->x_sampling, ch->y_sampling);
        goto cleanup;
    }
    long width = (long)window.max.x - window.min.x + 1;
    long height = (long)window.max.y - window.min.y + 1;
    rc = dem_check_size(path, "EXR", width, height, o, e);
    if (rc)
        goto cleanup;
    grid = malloc((size_t)width * (size_t)height * sizeof *grid);
    if (!grid) {
        rc = atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory reading %s (%ld x %ld)", path, width,
                       height);
        goto cleanup;
    }
    what = "pixels";
    r = storage == EXR_STORAGE_TILED
            ? read_tiles(ctxt, grid, (int)width, (int)height, &decoder, &initialized)
            : read_scanlines(ctxt, window.min.y, grid, (int)width, (int)height, &decoder,
                             &initialized);
    if (r != EXR_ERR_SUCCESS)
        goto library_error;
    dem->heights_m = grid;
    grid = NULL;
    dem->width = (int)width;
    dem->height = (int)height;
    dem->format = ATMO_DEM_EXR;
    snprintf(dem->format_name, sizeof dem->format_name, "EXR %s",
             ch->pixel_type == EXR_PIXEL_HALF    ? "half"
             : ch->pixel_type == EXR_PIXEL_FLOAT ? "float"
                                                 : "uint");
    rc = dem_extent_from_options(path, "EXR", o, dem, e);
    goto cleanup;
library_error:
    rc = atmo_fail(e, ATMO_ERR_USAGE, "%s: the EXR's %s cannot be read: %s; is the file complete?",
                   path, what, log.msg[0] ? log.msg : exr_get_default_error_message(r));
cleanup:
    if (initialized)
        exr_decoding_destroy(ctxt, &decoder);
    if (ctxt)
        exr_finish(&ctxt);
    free(grid);
    return rc;
}
