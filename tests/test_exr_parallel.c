/* test_exr_parallel — the EXR writer's chunks, compressed on every processor and written in
 * order, decode to exactly the input floats in each lossless compression.
 * labels: unit
 *
 * Oracle: OpenEXR's own decoder (atmo_exr_read runs the library's decode pipeline on every
 * chunk) must return every float bit for bit, since each offered codec is lossless for 32-bit
 * floats; the file's compression attribute, read with the library's exr_get_compression, must
 * be the one asked for. The image is 67 x 131 pixels, so every codec's chunking (1, 16 or 32
 * rows) ends in a partial chunk and PIZ has 5 chunks, with R, G, B and two layers (Depth.Z with
 * +Inf kept, Normal.X/Y/Z): the bit patterns come from a hash (every sign, exponent and
 * mantissa, denormals included; NaN and Inf patterns mapped to finite ones), a smooth ramp
 * (which the codecs do compress, so their predictors and Huffman tables run) and zeros. Also
 * checked: writing the same image twice gives the same bytes (the chunk order does not depend
 * on which thread finished first), a one-row image (one chunk, fewer chunks than threads)
 * decodes exactly, and the names round-trip (atmo_exr_compression_from_name). */
#include <math.h>
#include <openexr.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "atmo/image.h"
#include "testlib.h"

#define W 67
#define H 131

static char dir[512];

static const char *in_dir(const char *name)
{
    static char path[1100];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    return path;
}

static uint32_t hash(uint32_t x)
{
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

/* Region 0: hashed bit patterns (finite); 1: a smooth ramp; 2: zeros. */
static float value(int i, int c, int w)
{
    int y = i / w, region = y % 3;
    if (region == 2)
        return 0.0f;
    if (region == 1)
        return 0.01f * (float)(i % w) + 0.1f * (float)c + 1e-4f * (float)y;
    uint32_t bits = hash((uint32_t)(i * 7 + c));
    if (((bits >> 23) & 0xffu) == 0xffu) /* an Inf or NaN pattern: make the exponent finite */
        bits &= ~(1u << 30);
    float f;
    memcpy(&f, &bits, sizeof f);
    return f;
}

static void fill(float *v, int n, int channels, int w, int seed)
{
    for (int i = 0; i < n; i++)
        for (int c = 0; c < channels; c++)
            v[channels * i + c] = value(i, c + seed, w);
}

static int compression_of(const char *path, exr_compression_t *out)
{
    exr_context_t c = NULL;
    exr_result_t r = exr_start_read(&c, path, NULL);
    if (r == EXR_ERR_SUCCESS)
        r = exr_get_compression(c, 0, out);
    if (c)
        exr_finish(&c);
    return r == EXR_ERR_SUCCESS;
}

static int same_bits(const float *a, int a_stride, const float *b, int n)
{
    for (int i = 0; i < n; i++)
        if (memcmp(&a[(size_t)i * a_stride], &b[i], sizeof(float)) != 0)
            return 0;
    return 1;
}

/* Write w x h pixels with the codec, read them back, compare every channel's bits. */
static int round_trip(int codec, int w, int h, const char *name)
{
    int n = w * h;
    float *rgb = malloc(sizeof(float) * 3 * (size_t)n), *depth = malloc(sizeof(float) * (size_t)n);
    float *normal = malloc(sizeof(float) * 3 * (size_t)n);
    fill(rgb, n, 3, w, 0);
    fill(depth, n, 1, w, 3);
    fill(normal, n, 3, w, 4);
    for (int i = 0; i < n; i += 11)
        depth[i] = INFINITY;
    atmo_image_layer layers[2] = {
        {.name = "Depth", .channels = 1, .channel_names = {"Z"}, .data = depth,
         .keep_infinity = 1},
        {.name = "Normal", .channels = 3, .channel_names = {"X", "Y", "Z"}, .data = normal},
    };
    atmo_image img = {.width = w, .height = h, .rgb = rgb, .layers = layers, .layer_count = 2};
    atmo_image_meta meta = {.quantity = "spectral radiance", .unit = "W m^-2 sr^-1 nm^-1",
                            .wavelengths_nm = {680, 550, 440}, .samples_per_pixel = 1,
                            .software = "atmo test", .exr_compression = codec};
    atmo_err e = {""};
    int ok = atmo_image_write(in_dir(name), &img, NULL, &meta, &e) == ATMO_OK;
    if (!ok)
        fprintf(stderr, "%s: %s\n", name, e.msg);
    atmo_exr_file f;
    ok = ok && atmo_exr_read(in_dir(name), &f, &e) == ATMO_OK;
    if (ok) {
        static const char *const rgb_names[3] = {"R", "G", "B"}, *const xyz[3] = {"X", "Y", "Z"};
        ok = f.width == w && f.height == h && f.channel_count == 7;
        for (int c = 0; ok && c < 3; c++) {
            char layer_name[32];
            snprintf(layer_name, sizeof layer_name, "Normal.%s", xyz[c]);
            const float *got = atmo_exr_channel_data(&f, rgb_names[c]);
            const float *got_n = atmo_exr_channel_data(&f, layer_name);
            ok = got && got_n && same_bits(rgb + c, 3, got, n) && same_bits(normal + c, 3, got_n, n);
        }
        const float *z = atmo_exr_channel_data(&f, "Depth.Z");
        ok = ok && z && same_bits(depth, 1, z, n);
        atmo_exr_file_free(&f);
    }
    exr_compression_t stored = EXR_COMPRESSION_LAST_TYPE;
    static const exr_compression_t want[] = {
        [ATMO_EXR_DEFAULT] = EXR_COMPRESSION_PIZ, [ATMO_EXR_NONE] = EXR_COMPRESSION_NONE,
        [ATMO_EXR_RLE] = EXR_COMPRESSION_RLE,     [ATMO_EXR_ZIPS] = EXR_COMPRESSION_ZIPS,
        [ATMO_EXR_ZIP] = EXR_COMPRESSION_ZIP,     [ATMO_EXR_PIZ] = EXR_COMPRESSION_PIZ};
    int default_codec = atmo_exr_compression_from_name(atmo_exr_compression_name(ATMO_EXR_DEFAULT));
    exr_compression_t expected = codec == ATMO_EXR_DEFAULT ? want[default_codec] : want[codec];
    ok = ok && compression_of(in_dir(name), &stored) && stored == expected;
    free(normal);
    free(depth);
    free(rgb);
    return ok;
}

static int same_file(const char *a, const char *b)
{
    char cmd[2400];
    snprintf(cmd, sizeof cmd, "cmp -s '%s' '%s'", a, b);
    return system(cmd) == 0;
}

int main(void)
{
    snprintf(dir, sizeof dir, "/tmp/atmo-test-exr-%d", (int)getpid());
    char cmd[600];
    snprintf(cmd, sizeof cmd, "mkdir -p '%s'", dir);
    if (system(cmd) != 0)
        return 1;
    for (int codec = ATMO_EXR_DEFAULT; codec <= ATMO_EXR_PIZ; codec++) {
        const char *name = atmo_exr_compression_name(codec);
        char file[64], again[64], row[64];
        snprintf(file, sizeof file, "%d-%s.exr", codec, name);
        snprintf(again, sizeof again, "%d-%s-again.exr", codec, name);
        snprintf(row, sizeof row, "%d-%s-row.exr", codec, name);
        int exact = round_trip(codec, W, H, file);
        int repeat = round_trip(codec, W, H, again);
        int identical = same_file(in_dir(file), in_dir(again));
        int one_row = round_trip(codec, W, 1, row);
        CHECK(exact && repeat && identical && one_row);
        CHECK(codec == ATMO_EXR_DEFAULT || atmo_exr_compression_from_name(name) == codec);
        printf("%-7s (%s): %dx%d with 2 layers %s, rewritten %s, one row %s\n",
               codec == ATMO_EXR_DEFAULT ? "default" : name, name, W, H,
               exact ? "bit-exact" : "DIFFERENT", identical ? "byte-identical" : "DIFFERENT",
               one_row ? "bit-exact" : "DIFFERENT");
    }
    CHECK(atmo_exr_compression_from_name("default") == ATMO_EXR_DEFAULT);
    CHECK(atmo_exr_compression_from_name("dwaa") == -1 && atmo_exr_compression_from_name(NULL) == -1);
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    CHECK(system(cmd) == 0);
    return test_finish();
}
