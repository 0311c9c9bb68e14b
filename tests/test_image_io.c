/* test_image_io.c — image writers: every format read back by an independent reader.
 * labels: unit
 *
 * Oracles (the readers are other people's code, except the trivial PFM one):
 *   - PFM: the format stores float32 bits, so the round trip through atmo_image_read_pfm must be
 *     bit-exact; the raw bytes are also checked against the format's definition (header text,
 *     little-endian, bottom row first).
 *   - HDR: stb_image's stbi_loadf decodes byte * 2^(e - 136). The writer rounds each channel to
 *     the nearest unit 2^(k-8) of the shared exponent, whose largest channel byte is >= 128, so
 *     every channel is off by at most half a unit <= 2^-8 times the decoded largest channel of
 *     its pixel; that bound (no slack: encoding and decoding are exact in float) is the
 *     tolerance. Negative values must come back as 0.
 *   - EXR: OpenEXR's own C Core API decoder must return the float values bit-exactly (PIZ is
 *     lossless) and the string attributes as written; `exrheader`, when installed, must accept
 *     the file. Extra layers ("Depth.Z", "Normal.X/Y/Z") come back bit-exactly through
 *     atmo_exr_read, whose R, G, B must equal the independent decoder's; RGB colour carries the
 *     standard chromaticities (ITU-R BT.709, D65) and no wavelengths, spectral samples the
 *     reverse; +Inf survives in a
 *     layer that keeps it, NaN is counted and written as 0; a non-EXR file is a usage error.
 *   - PNG: stb_image's stbi_load must return exactly floor(255 d + 1/2) of atmo_post_pixel's
 *     display value d for every channel; the tEXt chunks must carry valid CRCs (the test's CRC is
 *     itself checked against the published CRC of the empty IEND chunk, 0xAE426082).
 *   - Failure paths: an unwritable target (missing directory; a directory in the way, where the
 *     temporary file is created but the rename fails) returns ATMO_ERR_RUNTIME and leaves neither
 *     the file nor a temporary file; NaN and Inf are reported (ATMO_ERR_RUNTIME, message names
 *     the count) and written as 0. */
#include <dirent.h>
#include <math.h>
#include <openexr.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include <stb_image.h>
#include "atmo/image.h"
#include "atmo/scene.h"
#include "testlib.h"

#define W 7
#define H 5

static char dir[256];

static const char *in_dir(const char *name)
{
    static char path[512];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    return path;
}

/* Values over many decades, a zero pixel, a negative value, and a sky-like gradient. */
static void fill(float *rgb)
{
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            float *p = rgb + 3 * (y * W + x);
            float s = powf(10.0f, (float)(x + W * y) / 5.0f - 4.0f);
            p[0] = s * 1.3f;
            p[1] = s * (0.2f + 0.1f * (float)x);
            p[2] = s / (1.0f + (float)y);
        }
    rgb[3 * 2] = rgb[3 * 2 + 1] = rgb[3 * 2 + 2] = 0.0f;
    rgb[3 * 4 + 1] = -0.5f;
}

static const atmo_image_meta meta = {.quantity = "spectral radiance",
                                     .unit = "W m^-2 sr^-1 nm^-1",
                                     .wavelengths_nm = {680, 550, 440},
                                     .samples_per_pixel = 64,
                                     .partial = 1,
                                     .software = "atmo test"};

static size_t read_all(const char *path, unsigned char **data)
{
    FILE *f = fopen(path, "rb");
    *data = NULL;
    if (!f)
        return 0;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    *data = malloc((size_t)n + 1);
    size_t got = fread(*data, 1, (size_t)n, f);
    (*data)[got] = 0;
    fclose(f);
    return got;
}

static int tmp_files_left(void)
{
    int n = 0;
    DIR *d = opendir(dir);
    struct dirent *ent;
    while (d && (ent = readdir(d)))
        n += strstr(ent->d_name, ".tmp.") != NULL;
    if (d)
        closedir(d);
    return n;
}

static void test_format_names(void)
{
    CHECK(atmo_image_format_from_path("a.png") == ATMO_IMAGE_PNG);
    CHECK(atmo_image_format_from_path("out/A.PNG") == ATMO_IMAGE_PNG);
    CHECK(atmo_image_format_from_path("sky.Hdr") == ATMO_IMAGE_HDR);
    CHECK(atmo_image_format_from_path("x.exr") == ATMO_IMAGE_EXR);
    CHECK(atmo_image_format_from_path("x.y.pfm") == ATMO_IMAGE_PFM);
    CHECK(atmo_image_format_from_path("x.jpg") == -1);
    CHECK(atmo_image_format_from_path("png") == -1);
    CHECK(atmo_image_format_from_path("dir.png/x") == -1);
    atmo_err e = {""};
    float px[3] = {1, 1, 1};
    atmo_image one = {.width = 1, .height = 1, .rgb = px};
    CHECK(atmo_image_write(in_dir("x.jpg"), &one, NULL, NULL, &e) == ATMO_ERR_USAGE);
    CHECK(strstr(e.msg, ".png") != NULL);
    CHECK(atmo_image_write(in_dir("x.png"), &one, NULL, NULL, &e) == ATMO_ERR_USAGE);
    atmo_image empty = {.width = 0, .height = 3, .rgb = px};
    CHECK(atmo_image_write(in_dir("x.pfm"), &empty, NULL, NULL, &e) == ATMO_ERR_USAGE);
    CHECK(access(in_dir("x.png"), F_OK) != 0 && access(in_dir("x.pfm"), F_OK) != 0);
}

static void test_pfm(void)
{
    float rgb[W * H * 3];
    fill(rgb);
    atmo_image img = {.width = W, .height = H, .rgb = rgb};
    atmo_err e = {""};
    CHECK(atmo_image_write(in_dir("a.pfm"), &img, NULL, &meta, &e) == ATMO_OK);
    atmo_image back;
    CHECK(atmo_image_read_pfm(in_dir("a.pfm"), &back, &e) == ATMO_OK);
    CHECK(back.width == W && back.height == H);
    if (back.rgb)
        CHECK(memcmp(back.rgb, rgb, sizeof rgb) == 0);
    atmo_image_free(&back);

    unsigned char *raw;
    size_t n = read_all(in_dir("a.pfm"), &raw);
    const char *header = "PF\n7 5\n-1.0\n";
    size_t hl = strlen(header);
    CHECK(n == hl + sizeof rgb);
    if (n == hl + sizeof rgb) {
        CHECK(memcmp(raw, header, hl) == 0);
        /* First value in the file: R of the bottom-left pixel, little-endian. */
        uint32_t want, got = 0;
        memcpy(&want, &rgb[3 * (H - 1) * W], 4);
        for (int k = 0; k < 4; k++)
            got |= (uint32_t)raw[hl + (size_t)k] << (8 * k);
        CHECK(got == want);
    }
    free(raw);
}

static void test_hdr(void)
{
    float rgb[W * H * 3];
    fill(rgb);
    atmo_image img = {.width = W, .height = H, .rgb = rgb};
    atmo_err e = {""};
    CHECK(atmo_image_write(in_dir("a.hdr"), &img, NULL, &meta, &e) == ATMO_OK);
    int w = 0, h = 0, n = 0;
    float *back = stbi_loadf(in_dir("a.hdr"), &w, &h, &n, 3);
    CHECK(back != NULL && w == W && h == H);
    if (!back)
        return;
    int bad = 0;
    for (int i = 0; i < W * H; i++) {
        const float *b = back + 3 * i;
        double vmax = fmax(b[0], fmax(b[1], b[2]));
        for (int c = 0; c < 3; c++) {
            double want = fmax(rgb[3 * i + c], 0.0);
            bad += !CHECK_ABS(b[c], want, ldexp(vmax, -8));
        }
        /* The tolerance is relative: the decoded maximum must be the true one to 2^-8. */
        double tmax = fmax(rgb[3 * i], fmax(rgb[3 * i + 1], rgb[3 * i + 2]));
        bad += !CHECK_ABS(vmax, tmax, ldexp(tmax, -8));
    }
    CHECK(bad == 0);
    CHECK(back[3 * 2] == 0.0f && back[3 * 4 + 1] == 0.0f);
    stbi_image_free(back);

    unsigned char *raw;
    read_all(in_dir("a.hdr"), &raw);
    CHECK(raw && strncmp((char *)raw, "#?RADIANCE\n", 11) == 0);
    CHECK(raw && strstr((char *)raw, "# quantity: spectral radiance\n") != NULL);
    CHECK(raw && strstr((char *)raw, "# unit: W m^-2 sr^-1 nm^-1\n") != NULL);
    CHECK(raw && strstr((char *)raw, "R 680 nm, G 550 nm, B 440 nm") != NULL);
    CHECK(raw && strstr((char *)raw, "# partial render") != NULL);
    CHECK(raw && strstr((char *)raw, "FORMAT=32-bit_rle_rgbe\n\n-Y 5 +X 7\n") != NULL);
    free(raw);
}

/* Decode every chunk of part 0 into interleaved RGB floats with OpenEXR's own reader. */
static int read_exr(const char *path, float *rgb, char *quantity, char *wavelengths)
{
    exr_context_t c = NULL;
    exr_decode_pipeline_t d = EXR_DECODE_PIPELINE_INITIALIZER;
    int initialized = 0, rows = 0;
    exr_attr_box2i_t dw;
    exr_result_t r = exr_start_read(&c, path, NULL);
    if (r == EXR_ERR_SUCCESS)
        r = exr_get_data_window(c, 0, &dw);
    if (r == EXR_ERR_SUCCESS &&
        (dw.min.x != 0 || dw.min.y != 0 || dw.max.x != W - 1 || dw.max.y != H - 1))
        r = EXR_ERR_INVALID_ATTR;
    if (r == EXR_ERR_SUCCESS)
        r = exr_get_scanlines_per_chunk(c, 0, &rows);
    for (int y = 0; r == EXR_ERR_SUCCESS && y < H; y += rows) {
        exr_chunk_info_t ci;
        r = exr_read_scanline_chunk_info(c, 0, y, &ci);
        if (r == EXR_ERR_SUCCESS)
            r = initialized ? exr_decoding_update(c, 0, &ci, &d)
                            : exr_decoding_initialize(c, 0, &ci, &d);
        if (r != EXR_ERR_SUCCESS)
            break;
        for (int k = 0; k < d.channel_count; k++) {
            exr_coding_channel_info_t *ch = &d.channels[k];
            int off = strcmp(ch->channel_name, "R") == 0 ? 0 : strcmp(ch->channel_name, "G") == 0 ? 1 : 2;
            ch->decode_to_ptr = (uint8_t *)(rgb + 3 * (size_t)(ci.start_y * W) + off);
            ch->user_pixel_stride = 12;
            ch->user_line_stride = 12 * W;
            ch->user_bytes_per_element = 4;
            ch->user_data_type = EXR_PIXEL_FLOAT;
        }
        if (!initialized) {
            r = exr_decoding_choose_default_routines(c, 0, &d);
            initialized = r == EXR_ERR_SUCCESS;
        }
        if (r == EXR_ERR_SUCCESS)
            r = exr_decoding_run(c, 0, &d);
    }
    if (initialized)
        exr_decoding_destroy(c, &d);
    const char *s;
    int32_t len;
    if (r == EXR_ERR_SUCCESS && exr_attr_get_string(c, 0, "quantity", &len, &s) == EXR_ERR_SUCCESS)
        snprintf(quantity, 64, "%.*s", (int)len, s);
    if (r == EXR_ERR_SUCCESS &&
        exr_attr_get_string(c, 0, "wavelengths", &len, &s) == EXR_ERR_SUCCESS)
        snprintf(wavelengths, 64, "%.*s", (int)len, s);
    if (c)
        exr_finish(&c);
    return r == EXR_ERR_SUCCESS;
}

static void test_exr(void)
{
    float rgb[W * H * 3], back[W * H * 3];
    fill(rgb);
    memset(back, 0xff, sizeof back);
    atmo_image img = {.width = W, .height = H, .rgb = rgb};
    atmo_err e = {""};
    CHECK(atmo_image_write(in_dir("a.exr"), &img, NULL, &meta, &e) == ATMO_OK);
    char quantity[64] = "", wavelengths[64] = "";
    CHECK(read_exr(in_dir("a.exr"), back, quantity, wavelengths));
    CHECK(memcmp(back, rgb, sizeof rgb) == 0);
    CHECK(strcmp(quantity, "spectral radiance") == 0);
    CHECK(strcmp(wavelengths, "R 680 nm, G 550 nm, B 440 nm") == 0);
    if (system("command -v exrheader >/dev/null 2>&1") == 0) {
        char cmd[1100];
        snprintf(cmd, sizeof cmd, "exrheader '%s' > '%s/exrheader.txt' 2>&1", in_dir("a.exr"), dir);
        CHECK(system(cmd) == 0);
        unsigned char *txt;
        read_all(in_dir("exrheader.txt"), &txt);
        CHECK(txt && strstr((char *)txt, "piz") && strstr((char *)txt, "32-bit floating-point"));
        CHECK(txt && strstr((char *)txt, "renderStatus") && strstr((char *)txt, "partial"));
        free(txt);
    }
}

/* What R, G, B are: RGB colour (meta.rec709) gets OpenEXR's standard chromaticities attribute
 * with ITU-R BT.709's primaries and D65 white (x, y; the file stores them as float, so they are
 * compared with the floats of the published decimals) and no wavelengths; spectral samples get
 * wavelengths and no chromaticities. Read with OpenEXR's own C API. */
static void test_exr_chromaticities(void)
{
    static const float bt709[8] = {0.64f, 0.33f, 0.30f, 0.60f, 0.15f, 0.06f, 0.3127f, 0.3290f};
    float rgb[W * H * 3];
    fill(rgb);
    atmo_image img = {.width = W, .height = H, .rgb = rgb};
    atmo_image_meta colour = meta;
    colour.quantity = "luminance";
    colour.unit = "cd m^-2";
    colour.rec709 = 1;
    atmo_err e = {""};
    CHECK(atmo_image_write(in_dir("rgb.exr"), &img, NULL, &colour, &e) == ATMO_OK);
    char paths[2][512]; /* in_dir's buffer is static */
    snprintf(paths[0], sizeof paths[0], "%s", in_dir("a.exr"));
    snprintf(paths[1], sizeof paths[1], "%s", in_dir("rgb.exr"));
    for (int k = 0; k < 2; k++) {
        exr_context_t c = NULL;
        exr_attr_chromaticities_t ch;
        const char *s;
        int32_t len;
        CHECK(exr_start_read(&c, paths[k], NULL) == EXR_ERR_SUCCESS);
        int has_chroma = exr_attr_get_chromaticities(c, 0, "chromaticities", &ch) ==
                         EXR_ERR_SUCCESS;
        int has_wl = exr_attr_get_string(c, 0, "wavelengths", &len, &s) == EXR_ERR_SUCCESS;
        int has_id = exr_attr_get_string(c, 0, "colorInteropID", &len, &s) == EXR_ERR_SUCCESS &&
                     len == 16 && strncmp(s, "lin_rec709_scene", 16) == 0;
        CHECK(has_chroma == k && has_id == k && has_wl == !k);
        if (has_chroma) {
            const float got[8] = {ch.red_x,  ch.red_y,  ch.green_x, ch.green_y,
                                  ch.blue_x, ch.blue_y, ch.white_x, ch.white_y};
            CHECK(memcmp(got, bt709, sizeof got) == 0);
        }
        if (c)
            exr_finish(&c);
    }
}

static void test_exr_layers(void)
{
    float rgb[W * H * 3], depth[W * H], normal[W * H * 3], back[W * H * 3];
    fill(rgb);
    for (int i = 0; i < W * H; i++) {
        depth[i] = i % 5 == 0 ? INFINITY : 1.5f * (float)i + 0.25f;
        for (int c = 0; c < 3; c++)
            normal[3 * i + c] = (float)(c - 1) * 0.5f + (float)i * 1e-3f;
    }
    atmo_image_layer layers[2] = {
        {.name = "Depth", .channels = 1, .channel_names = {"Z"}, .data = depth,
         .keep_infinity = 1},
        {.name = "Normal", .channels = 3, .channel_names = {"X", "Y", "Z"}, .data = normal},
    };
    static const char *const attributes[] = {"atmoScene", "{\"seed\": 7}"};
    atmo_image_meta m = meta;
    m.attributes = attributes;
    m.attribute_count = 1;
    atmo_image img = {.width = W, .height = H, .rgb = rgb, .layers = layers, .layer_count = 2};
    atmo_err e = {""};
    CHECK(atmo_image_write(in_dir("layers.exr"), &img, NULL, &m, &e) == ATMO_OK);
    char quantity[64] = "", wavelengths[64] = "";
    CHECK(read_exr(in_dir("layers.exr"), back, quantity, wavelengths));
    atmo_exr_file f;
    CHECK(atmo_exr_read(in_dir("layers.exr"), &f, &e) == ATMO_OK);
    CHECK(f.width == W && f.height == H && f.channel_count == 7);
    const float *r = atmo_exr_channel_data(&f, "R"), *z = atmo_exr_channel_data(&f, "Depth.Z");
    const float *ny = atmo_exr_channel_data(&f, "Normal.Y");
    CHECK(r && z && ny && !atmo_exr_channel_data(&f, "Depth.X"));
    int bad = 0;
    for (int i = 0; r && z && ny && i < W * H; i++) {
        bad += memcmp(&r[i], &back[3 * i], sizeof(float)) != 0;
        bad += memcmp(&r[i], &rgb[3 * i], sizeof(float)) != 0;
        bad += memcmp(&z[i], &depth[i], sizeof(float)) != 0;
        bad += memcmp(&ny[i], &normal[3 * i + 1], sizeof(float)) != 0;
    }
    CHECK(bad == 0);
    const char *scene = atmo_exr_attribute_value(&f, "atmoScene");
    CHECK(scene && strcmp(scene, "{\"seed\": 7}") == 0);
    CHECK(atmo_exr_attribute_value(&f, "renderStatus") &&
          strcmp(atmo_exr_attribute_value(&f, "renderStatus"), "partial") == 0);
    atmo_exr_file_free(&f);

    normal[4] = NAN;
    depth[3] = NAN;
    CHECK(atmo_image_write(in_dir("nan.exr"), &img, NULL, &m, &e) == ATMO_ERR_RUNTIME);
    CHECK(strstr(e.msg, "2 non-finite") != NULL);
    CHECK(atmo_exr_read(in_dir("nan.exr"), &f, &e) == ATMO_OK);
    CHECK(f.channel_count == 7 && atmo_exr_channel_data(&f, "Normal.Y")[1] == 0.0f &&
          atmo_exr_channel_data(&f, "Depth.Z")[3] == 0.0f &&
          isinf(atmo_exr_channel_data(&f, "Depth.Z")[0]));
    atmo_exr_file_free(&f);

    CHECK(atmo_image_write(in_dir("x.png"), &img, NULL, NULL, &e) == ATMO_ERR_USAGE);
    atmo_image_write_pfm(in_dir("not.exr"), &img, &e);
    CHECK(atmo_exr_read(in_dir("not.exr"), &f, &e) == ATMO_ERR_USAGE);
    CHECK(atmo_exr_read(in_dir("missing.exr"), &f, &e) == ATMO_ERR_USAGE);
}

static uint32_t crc32_png(const unsigned char *p, size_t n)
{
    uint32_t crc = 0xFFFFFFFFu;
    for (size_t i = 0; i < n; i++) {
        crc ^= p[i];
        for (int k = 0; k < 8; k++)
            crc = (crc & 1u) ? (crc >> 1) ^ 0xEDB88320u : crc >> 1;
    }
    return crc ^ 0xFFFFFFFFu;
}

static uint32_t be32(const unsigned char *p)
{
    return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}

static void test_png(void)
{
    float rgb[W * H * 3];
    fill(rgb);
    atmo_image img = {.width = W, .height = H, .rgb = rgb};
    atmo_post post = {.exposure = 3.0f,
                      .tonemap = ATMO_TONEMAP_ACES,
                      .white_point = 4.0f,
                      .white_balance = 1,
                      .white_balance_rgb = {1.08241f, 0.96756f, 0.95003f},
                      .transfer = ATMO_TRANSFER_SRGB};
    atmo_err e = {""};
    CHECK(atmo_image_write(in_dir("a.png"), &img, &post, &meta, &e) == ATMO_OK);
    int w = 0, h = 0, n = 0;
    unsigned char *back = stbi_load(in_dir("a.png"), &w, &h, &n, 3);
    CHECK(back != NULL && w == W && h == H && n == 3);
    if (!back)
        return;
    int mismatches = 0, distinct = 0;
    for (int i = 0; i < W * H; i++) {
        float d[3];
        atmo_post_pixel(&post, rgb + 3 * i, d);
        for (int c = 0; c < 3; c++) {
            int want = (int)floorf(255.0f * d[c] + 0.5f);
            mismatches += back[3 * i + c] != want;
            distinct += back[3 * i + c] != back[0];
        }
    }
    CHECK(mismatches == 0);
    CHECK(distinct > 0);
    stbi_image_free(back);

    /* Chunk structure and CRCs; the CRC routine first against the published IEND CRC. */
    CHECK(crc32_png((const unsigned char *)"IEND", 4) == 0xAE426082u);
    unsigned char *raw;
    size_t size = read_all(in_dir("a.png"), &raw);
    int chunks = 0, crc_bad = 0, found_text = 0;
    size_t p = 8;
    while (raw && p + 12 <= size) {
        uint32_t len = be32(raw + p);
        if (p + 12 + len > size)
            break;
        crc_bad += crc32_png(raw + p + 4, 4 + len) != be32(raw + p + 8 + len);
        if (memcmp(raw + p + 4, "tEXt", 4) == 0 && len > 12 &&
            memcmp(raw + p + 8, "Description", 12) == 0)
            found_text = strstr((const char *)raw + p + 20, "spectral radiance") != NULL;
        chunks++;
        p += 12 + len;
    }
    CHECK(p == size && chunks >= 5 && crc_bad == 0 && found_text);
    free(raw);
}

static void test_unwritable(void)
{
    float rgb[W * H * 3];
    fill(rgb);
    atmo_image img = {.width = W, .height = H, .rgb = rgb};
    atmo_post post = {1.0f, ATMO_TONEMAP_REINHARD, 4.0f, 0, {1, 1, 1}, ATMO_TRANSFER_SRGB};
    static const char *const names[] = {"missing/a.png", "missing/a.hdr", "missing/a.exr",
                                        "missing/a.pfm", "d.png",         "d.hdr",
                                        "d.exr",         "d.pfm"};
    for (int i = 0; i < 8; i++) {
        char path[512];
        snprintf(path, sizeof path, "%s", in_dir(names[i]));
        if (i >= 4)
            mkdir(path, 0700); /* a directory where the file should go: rename fails */
        atmo_err e = {""};
        int rc = atmo_image_write(path, &img, &post, &meta, &e);
        CHECK(rc == ATMO_ERR_RUNTIME);
        CHECK(strstr(e.msg, path) != NULL);
        struct stat st;
        CHECK(i < 4 ? stat(path, &st) != 0 : (stat(path, &st) == 0 && S_ISDIR(st.st_mode)));
        if (i >= 4)
            rmdir(path);
    }
    CHECK(tmp_files_left() == 0);
}

static void test_nonfinite(void)
{
    float rgb[W * H * 3];
    fill(rgb);
    rgb[5] = NAN;
    rgb[9] = INFINITY;
    rgb[3 * (W * H - 1)] = -INFINITY;
    atmo_image img = {.width = W, .height = H, .rgb = rgb};
    atmo_err e = {""};

    CHECK(atmo_image_write(in_dir("nan.pfm"), &img, NULL, &meta, &e) == ATMO_ERR_RUNTIME);
    CHECK(strstr(e.msg, "3 non-finite") != NULL);
    atmo_image back;
    CHECK(atmo_image_read_pfm(in_dir("nan.pfm"), &back, &e) == ATMO_OK);
    if (back.rgb) {
        int nonfinite = 0, changed = 0;
        for (int i = 0; i < W * H * 3; i++) {
            nonfinite += !isfinite(back.rgb[i]);
            changed += isfinite(rgb[i]) && back.rgb[i] != rgb[i];
        }
        CHECK(nonfinite == 0 && changed == 0);
        CHECK(back.rgb[5] == 0.0f && back.rgb[9] == 0.0f && back.rgb[3 * (W * H - 1)] == 0.0f);
    }
    atmo_image_free(&back);

    e.msg[0] = 0;
    CHECK(atmo_image_write(in_dir("nan.exr"), &img, NULL, &meta, &e) == ATMO_ERR_RUNTIME);
    CHECK(strstr(e.msg, "non-finite") != NULL);
    float exr[W * H * 3];
    char q[64], wl[64];
    CHECK(read_exr(in_dir("nan.exr"), exr, q, wl));
    CHECK(exr[5] == 0.0f && exr[9] == 0.0f && exr[3 * (W * H - 1)] == 0.0f);

    e.msg[0] = 0;
    CHECK(atmo_image_write(in_dir("nan.hdr"), &img, NULL, &meta, &e) == ATMO_ERR_RUNTIME);
    int w, h, n;
    float *hdr = stbi_loadf(in_dir("nan.hdr"), &w, &h, &n, 3);
    int nonfinite = 0;
    for (int i = 0; hdr && i < W * H * 3; i++)
        nonfinite += !isfinite(hdr[i]);
    CHECK(hdr && nonfinite == 0 && hdr[5] == 0.0f);
    stbi_image_free(hdr);
    /* The input itself is left untouched. */
    CHECK(isnan(rgb[5]));
}

static void remove_dir(void)
{
    DIR *d = opendir(dir);
    struct dirent *ent;
    while (d && (ent = readdir(d)))
        if (ent->d_name[0] != '.')
            remove(in_dir(ent->d_name));
    if (d)
        closedir(d);
    rmdir(dir);
}

int main(void)
{
    snprintf(dir, sizeof dir, "test_image_io.XXXXXX");
    if (!mkdtemp(dir)) {
        perror("mkdtemp");
        return 1;
    }
    test_format_names();
    test_pfm();
    test_hdr();
    test_exr();
    test_exr_chromaticities();
    test_exr_layers();
    test_png();
    test_unwritable();
    test_nonfinite();
    remove_dir();
    return test_finish();
}
