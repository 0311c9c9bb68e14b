/* image_exr.c — OpenEXR of the linear values: 32-bit float R, G, B and the image's extra
 * layers, scanlines, lossless compression, chunks compressed in parallel.
 *
 * Written with OpenEXR's C Core API (OpenEXR 3.1): one scanline part, data and display windows
 * (0, 0)-(width-1, height-1), increasing y (row 0 at the top, as atmo_image). Each layer's
 * channels are "<layer>.<channel>" (atmo_image_layer), after R, G, B. The description goes into
 * string attributes: "quantity", "unit", "samplesPerPixel", "software", "renderStatus"
 * ("complete" or "partial"), the standard "comments" with the whole one-line description, and
 * the meta's own attributes. What R, G, B are: in radiance mode spectral samples, not primaries,
 * so "wavelengths" names them and there is no "chromaticities"; RGB colour (meta->rec709) gets
 * the standard "chromaticities" attribute with the Rec.709 primaries and D65 white point
 * (ITU-R BT.709-6, Table 1, items 1.3 and 1.4: the values OpenEXR's own default stands for),
 * and "colorInteropID" = "lin_rec709_scene" (the Color Interop Forum's ID, which Blender reads
 * to pick an EXR's colour space), instead of "wavelengths".
 *
 * Compression (meta->exr_compression): the codecs that are lossless for 32-bit floats, none,
 * rle, zips (1 row per chunk), zip (16 rows) and piz (32 rows; wavelet + Huffman). On a
 * 2048x1024 `fast` sky panorama (R, G, B) they wrote 25.2, 25.2, 14.3, 13.6 and 11.7 MB; piz is
 * the smallest and also the quickest of the three that compress (zips and zip take 1.4 and 1.7
 * times its time), so it is the default; none writes 2.1 times the bytes in a tenth of the
 * time (the choice for speed: --exr-compression none); rle finds no runs in float noise.
 * docs/notes/speed_io.md has the measurements.
 *
 * Threads: the C API leaves threading to the caller. Every chunk is compressed by its own run
 * of the library's encode pipeline, one pipeline per thread, the threads (one per online
 * processor) taking the next chunk from a shared counter; the pipeline's last stage keeps the
 * compressed bytes instead of writing them, and this thread then writes the chunks in file
 * order. The file's bytes are the same whichever thread compressed which chunk.
 *
 * The library writes to the temporary path of fileio.h; on success the file is renamed over the
 * target, on any error it is removed. Library messages are collected into the atmo_err instead of
 * being printed. */
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <openexr.h>
#include "atmo/fileio.h"
#include "atmo/image.h"

/* The codec ATMO_EXR_DEFAULT stands for. */
#define EXR_DEFAULT_CODEC ATMO_EXR_PIZ

static const struct {
    const char *name;
    exr_compression_t codec;
} codecs[] = {
    [ATMO_EXR_NONE] = {"none", EXR_COMPRESSION_NONE}, [ATMO_EXR_RLE] = {"rle", EXR_COMPRESSION_RLE},
    [ATMO_EXR_ZIPS] = {"zips", EXR_COMPRESSION_ZIPS}, [ATMO_EXR_ZIP] = {"zip", EXR_COMPRESSION_ZIP},
    [ATMO_EXR_PIZ] = {"piz", EXR_COMPRESSION_PIZ},
};

int atmo_exr_compression_from_name(const char *name)
{
    if (name && strcmp(name, "default") == 0)
        return ATMO_EXR_DEFAULT;
    for (int c = ATMO_EXR_NONE; c <= ATMO_EXR_PIZ; c++)
        if (name && strcmp(name, codecs[c].name) == 0)
            return c;
    return -1;
}

const char *atmo_exr_compression_name(int compression)
{
    int c = compression >= ATMO_EXR_NONE && compression <= ATMO_EXR_PIZ ? compression
                                                                          : EXR_DEFAULT_CODEC;
    return codecs[c].name;
}

/* Extra layers one file can carry (each up to 4 channels). */
#define EXR_MAX_LAYERS 32

/* The first message the library reported, for the error line. */
typedef struct {
    char msg[256];
} exr_log;

static void exr_on_error(exr_const_context_t ctxt, exr_result_t code, const char *msg)
{
    void *user = NULL;
    exr_get_user_data(ctxt, &user);
    exr_log *log = user;
    if (log && log->msg[0] == '\0')
        snprintf(log->msg, sizeof log->msg, "%s", msg ? msg : exr_get_default_error_message(code));
}

static exr_result_t exr_attributes(exr_context_t ctxt, const atmo_image_meta *meta)
{
    char text[512];
    exr_result_t r = EXR_ERR_SUCCESS;
    if (!meta)
        return r;
    const double *w = meta->wavelengths_nm;
    /* ITU-R BT.709: red, green, blue primaries and the D65 white point (CIE 1931 xy) */
    static const exr_attr_chromaticities_t rec709 = {0.64f, 0.33f, 0.30f, 0.60f,
                                                     0.15f, 0.06f, 0.3127f, 0.3290f};
    if (meta->quantity && r == EXR_ERR_SUCCESS)
        r = exr_attr_set_string(ctxt, 0, "quantity", meta->quantity);
    if (meta->unit && r == EXR_ERR_SUCCESS)
        r = exr_attr_set_string(ctxt, 0, "unit", meta->unit);
    snprintf(text, sizeof text, "R %g nm, G %g nm, B %g nm", w[0], w[1], w[2]);
    if (r == EXR_ERR_SUCCESS && meta->rec709)
        r = exr_attr_set_chromaticities(ctxt, 0, "chromaticities", &rec709);
    if (r == EXR_ERR_SUCCESS && meta->rec709)
        r = exr_attr_set_string(ctxt, 0, "colorInteropID", "lin_rec709_scene");
    if (r == EXR_ERR_SUCCESS && !meta->rec709)
        r = exr_attr_set_string(ctxt, 0, "wavelengths", text);
    snprintf(text, sizeof text, "%d", meta->samples_per_pixel);
    if (r == EXR_ERR_SUCCESS)
        r = exr_attr_set_string(ctxt, 0, "samplesPerPixel", text);
    if (r == EXR_ERR_SUCCESS)
        r = exr_attr_set_string(ctxt, 0, "software", meta->software ? meta->software : "atmo");
    if (r == EXR_ERR_SUCCESS)
        r = exr_attr_set_string(ctxt, 0, "renderStatus", meta->partial ? "partial" : "complete");
    atmo_image_describe(meta, text, sizeof text);
    if (r == EXR_ERR_SUCCESS)
        r = exr_attr_set_string(ctxt, 0, "comments", text);
    for (int a = 0; a < meta->attribute_count && r == EXR_ERR_SUCCESS; a++)
        r = exr_attr_set_string(ctxt, 0, meta->attributes[2 * a], meta->attributes[2 * a + 1]);
    return r;
}

/* Where channel `name` lives: the first float of row 0 and the floats per pixel. */
typedef struct {
    char name[64];
    const float *base;
    int stride;
} exr_source;

/* R, G, B, then each layer's channels; returns how many (at most max). */
static int exr_sources(const atmo_image *img, exr_source *src, int max)
{
    static const char *const rgb[3] = {"R", "G", "B"};
    int n = 0;
    for (int c = 0; c < 3 && n < max; c++, n++) {
        snprintf(src[n].name, sizeof src[n].name, "%s", rgb[c]);
        src[n].base = img->rgb + c;
        src[n].stride = 3;
    }
    for (int l = 0; l < img->layer_count; l++) {
        const atmo_image_layer *layer = &img->layers[l];
        for (int c = 0; c < layer->channels && n < max; c++, n++) {
            snprintf(src[n].name, sizeof src[n].name, "%s.%s", layer->name,
                     layer->channel_names[c]);
            src[n].base = layer->data + c;
            src[n].stride = layer->channels;
        }
    }
    return n;
}

static const exr_source *exr_find(const exr_source *src, int n, const char *name)
{
    for (int i = 0; i < n; i++)
        if (strcmp(src[i].name, name) == 0)
            return &src[i];
    return NULL;
}

/* Threads that compress chunks (the writing thread is one of them). */
#define EXR_MAX_THREADS 16

/* One compressed chunk, as the writing thread stores it in the file. */
typedef struct {
    void *data;
    size_t bytes;
} exr_chunk_out;

/* What the encoding threads share: the chunks to compress, which one is next, the results. */
typedef struct {
    exr_const_context_t ctxt;
    const atmo_image *img;
    const exr_source *src;
    int n_src, chunks;
    const exr_chunk_info_t *info; /* per chunk */
    exr_chunk_out *out;           /* per chunk */
    pthread_mutex_t lock;
    int next;                     /* the first chunk no thread has taken */
    exr_result_t r;               /* the first failure, under lock */
} exr_job;

/* The pipeline's last stage: keep the compressed bytes for the writing thread. */
static exr_result_t keep_chunk(exr_encode_pipeline_t *pipe)
{
    exr_chunk_out *o = pipe->encoding_user_data;
    o->data = malloc(pipe->compressed_bytes ? pipe->compressed_bytes : 1);
    if (!o->data)
        return EXR_ERR_OUT_OF_MEMORY;
    memcpy(o->data, pipe->compressed_buffer, pipe->compressed_bytes);
    o->bytes = pipe->compressed_bytes;
    return EXR_ERR_SUCCESS;
}

/* The chunks are written by one thread in file order after all are compressed: a thread
 * never waits for another's chunk. */
static exr_result_t never_wait(exr_encode_pipeline_t *pipe)
{
    (void)pipe;
    return EXR_ERR_SUCCESS;
}

/* Point the pipeline's channels at chunk rows of the image and its layers. */
static exr_result_t point_channels(const exr_job *job, exr_encode_pipeline_t *pipe, int y)
{
    for (int c = 0; c < pipe->channel_count; c++) {
        exr_coding_channel_info_t *ch = &pipe->channels[c];
        /* The library sorts the channels by name: find each one's source. */
        const exr_source *from = exr_find(job->src, job->n_src, ch->channel_name);
        if (!from)
            return EXR_ERR_INVALID_ARGUMENT;
        size_t row_floats = (size_t)job->img->width * (size_t)from->stride;
        ch->encode_from_ptr = (const uint8_t *)(from->base + (size_t)y * row_floats);
        ch->user_pixel_stride = from->stride * (int32_t)sizeof(float);
        ch->user_line_stride = (int32_t)(row_floats * sizeof(float));
        ch->user_bytes_per_element = sizeof(float);
        ch->user_data_type = EXR_PIXEL_FLOAT;
    }
    return EXR_ERR_SUCCESS;
}

/* An encoding thread: takes the next chunk until none is left or one failed. */
static void *encode_chunks(void *arg)
{
    exr_job *job = arg;
    exr_encode_pipeline_t pipe = EXR_ENCODE_PIPELINE_INITIALIZER;
    int initialized = 0;
    exr_result_t r = EXR_ERR_SUCCESS;
    for (;;) {
        pthread_mutex_lock(&job->lock);
        int k = job->r == EXR_ERR_SUCCESS && job->next < job->chunks ? job->next++ : -1;
        pthread_mutex_unlock(&job->lock);
        if (k < 0)
            break;
        const exr_chunk_info_t *chunk = &job->info[k];
        r = initialized ? exr_encoding_update(job->ctxt, 0, chunk, &pipe)
                        : exr_encoding_initialize(job->ctxt, 0, chunk, &pipe);
        if (r == EXR_ERR_SUCCESS)
            r = point_channels(job, &pipe, chunk->start_y);
        if (r == EXR_ERR_SUCCESS && !initialized) {
            r = exr_encoding_choose_default_routines(job->ctxt, 0, &pipe);
            initialized = r == EXR_ERR_SUCCESS;
            pipe.write_fn = keep_chunk;
            pipe.yield_until_ready_fn = never_wait;
        }
        pipe.encoding_user_data = &job->out[k];
        if (r == EXR_ERR_SUCCESS)
            r = exr_encoding_run(job->ctxt, 0, &pipe);
        if (r != EXR_ERR_SUCCESS)
            break;
    }
    if (initialized) {
        exr_result_t d = exr_encoding_destroy(job->ctxt, &pipe);
        r = r == EXR_ERR_SUCCESS ? d : r;
    }
    pthread_mutex_lock(&job->lock);
    if (job->r == EXR_ERR_SUCCESS)
        job->r = r;
    pthread_mutex_unlock(&job->lock);
    return NULL;
}

/* The number of threads to compress on: the online processors, at most EXR_MAX_THREADS. */
static int encode_threads(void)
{
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n < 1 ? 1 : n > EXR_MAX_THREADS ? EXR_MAX_THREADS : (int)n;
}

/* Compress every chunk of rows on all processors, then write them in file order (the chunk
 * table wants increasing y); the channels point into the interleaved floats of the image and
 * its layers. */
static exr_result_t exr_pixels(exr_context_t ctxt, const atmo_image *img, const exr_source *src,
                               int n_src)
{
    int rows_per_chunk = 0;
    exr_result_t r = exr_get_scanlines_per_chunk(ctxt, 0, &rows_per_chunk);
    if (r != EXR_ERR_SUCCESS)
        return r;
    exr_job job = {ctxt, img, src, n_src, (img->height + rows_per_chunk - 1) / rows_per_chunk,
                   NULL, NULL, PTHREAD_MUTEX_INITIALIZER, 0, EXR_ERR_SUCCESS};
    exr_chunk_info_t *info = calloc((size_t)job.chunks, sizeof *info);
    job.out = calloc((size_t)job.chunks, sizeof *job.out);
    job.info = info;
    if (!info || !job.out)
        r = EXR_ERR_OUT_OF_MEMORY;
    /* The library hands out chunk descriptions in file order only, as each is written: the
     * others follow from the first (all channels are 32-bit floats, no subsampling), and each
     * is checked against the library's own before its chunk is written. */
    if (r == EXR_ERR_SUCCESS)
        r = exr_write_scanline_chunk_info(ctxt, 0, 0, &info[0]);
    for (int k = 1; r == EXR_ERR_SUCCESS && k < job.chunks; k++) {
        info[k] = info[0];
        info[k].idx = k;
        info[k].start_y = info[0].start_y + k * rows_per_chunk;
        info[k].height = img->height - k * rows_per_chunk < rows_per_chunk
                             ? img->height - k * rows_per_chunk
                             : rows_per_chunk;
        info[k].unpacked_size = (uint64_t)info[k].width * (uint64_t)info[k].height *
                                (uint64_t)n_src * sizeof(float);
    }
    if (r == EXR_ERR_SUCCESS) {
        pthread_t threads[EXR_MAX_THREADS];
        int helpers = encode_threads() - 1, started = 0;
        helpers = helpers < job.chunks - 1 ? helpers : job.chunks - 1;
        while (started < helpers && pthread_create(&threads[started], NULL, encode_chunks,
                                                   &job) == 0)
            started++;
        encode_chunks(&job); /* this thread too, and alone if none could start */
        for (int t = 0; t < started; t++)
            pthread_join(threads[t], NULL);
        r = job.r;
    }
    for (int k = 0; r == EXR_ERR_SUCCESS && k < job.chunks; k++) {
        exr_chunk_info_t check;
        r = exr_write_scanline_chunk_info(ctxt, 0, info[k].start_y, &check);
        if (r == EXR_ERR_SUCCESS && (check.idx != k || check.height != info[k].height ||
                                     check.unpacked_size != info[k].unpacked_size))
            r = EXR_ERR_INVALID_ARGUMENT;
        if (r == EXR_ERR_SUCCESS)
            r = exr_write_scanline_chunk(ctxt, 0, info[k].start_y, job.out[k].data,
                                         job.out[k].bytes);
    }
    for (int k = 0; job.out && k < job.chunks; k++)
        free(job.out[k].data);
    free(job.out);
    free(info);
    pthread_mutex_destroy(&job.lock);
    return r;
}

int atmo_image_write_exr(const char *path, const atmo_image *img, const atmo_image_meta *meta,
                         atmo_err *e)
{
    if (img->layer_count > EXR_MAX_LAYERS)
        return atmo_fail(e, ATMO_ERR_USAGE, "cannot write '%s': %d layers, at most %d", path,
                         img->layer_count, EXR_MAX_LAYERS);
    char tmp[ATMO_TMP_PATH_MAX];
    exr_log log = {""};
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = exr_on_error;
    init.user_data = &log;
    exr_context_t ctxt = NULL;
    int part = -1;
    atmo_tmp_path(path, tmp);

    exr_result_t r = exr_start_write(&ctxt, tmp, EXR_WRITE_FILE_DIRECTLY, &init);
    if (r == EXR_ERR_SUCCESS)
        r = exr_add_part(ctxt, NULL, EXR_STORAGE_SCANLINE, &part);
    int compression = meta ? meta->exr_compression : ATMO_EXR_DEFAULT;
    compression = atmo_exr_compression_from_name(atmo_exr_compression_name(compression));
    if (r == EXR_ERR_SUCCESS)
        r = exr_initialize_required_attr_simple(ctxt, part, img->width, img->height,
                                                codecs[compression].codec);
    exr_source src[3 + 4 * EXR_MAX_LAYERS];
    int n_src = exr_sources(img, src, (int)(sizeof src / sizeof src[0]));
    for (int c = 0; c < n_src && r == EXR_ERR_SUCCESS; c++) {
        /* Colour is perceptual (lossy codecs may weigh it so); passes like depth are not. */
        exr_perceptual_treatment_t treatment =
            c < 3 ? EXR_PERCEPTUALLY_LOGARITHMIC : EXR_PERCEPTUALLY_LINEAR;
        r = exr_add_channel(ctxt, part, src[c].name, EXR_PIXEL_FLOAT, treatment, 1, 1);
    }
    if (r == EXR_ERR_SUCCESS)
        r = exr_attributes(ctxt, meta);
    if (r == EXR_ERR_SUCCESS)
        r = exr_write_header(ctxt);
    if (r == EXR_ERR_SUCCESS)
        r = exr_pixels(ctxt, img, src, n_src);
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
