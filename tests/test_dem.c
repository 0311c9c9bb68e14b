/* test_dem.c — digital elevation models: files written here read back as the surface they hold.
 * labels: unit
 *
 * Oracles:
 *   - A closed-form surface h(x, z) (sines and a tilt, metres) is written at the pixel centres
 *     x = (col + 1/2) cell - X/2, z = (row + 1/2) cell - Z/2 into each format by independent
 *     writers (a 16-bit PNG encoder written here from the PNG specification, stb_image_write for
 *     8-bit PNG, OpenEXR's C API for EXR, GDAL for GeoTIFF); reading back must give h within the
 *     format's quantisation: 16-bit PNG scale/2/65535, 8-bit PNG scale/2/255, EXR half 2^-11 |h|
 *     (half's rounding), float formats exactly, all plus the float rounding of a height
 *     (2^-24 |h|, from metres in double to float). The non-square grid (48 x 32) catches a
 *     transposition, the south-up and east-first GeoTIFFs a row or column flip.
 *   - GeoTIFF extents: projected (UTM, metres) = size x cell exactly; geographic degrees against
 *     the published lengths of a degree on WGS 84 (Wikipedia "Latitude", table of 1-degree
 *     lengths: at 0 deg 110 574 m of latitude and 111 320 m of longitude, at 45 deg 111 132 m and
 *     78 847 m, rounded to the metre), within 1 m; a band in feet comes back times 0.3048.
 *   - nodata: an isolated missing sample on a plane is the mean of its 8 neighbours, which on a
 *     plane is the plane's value (to float rounding); a large hole is filled within the range of
 *     the heights around it (the filling averages, so it cannot leave that range) and no sample
 *     stays non-finite; half a 1024 x 1024 grid missing (a coast) likewise; with
 *     terrain.heightmap_nodata=sea-level the missing samples are exactly 0 m.
 *   - Built without GDAL, a GeoTIFF is refused with one line saying how to enable it.
 *   - Bad files (truncated PNG, EXR, GeoTIFF; a text file; an RGB PNG; a two-channel EXR; a
 *     rotated geotransform; no CRS; a local CRS; sizes beyond the limit): ATMO_ERR_USAGE with one
 *     line naming the file and the reason.
 *   - Resampling: for the smooth surface sampled at cell size c, bilinear interpolation's error
 *     is at most (c^2/8)(max |h_xx| + max |h_zz|) (tensor-product linear interpolation), and
 *     both filters return the samples at the sample centres; halving c must divide the
 *     bilinear error by ~4 (measured order >= 1.8) and the bicubic (Keys) error by ~8 (order >=
 *     2.7, Keys 1981: third order), and bicubic must beat bilinear; bicubic's gradient against
 *     the surface's closed-form gradient falls by ~4 (order >= 1.8) and matches the central
 *     difference of the interpolated heights over +-0.1 mm within
 *     0.1 mm x (max |h_xx| + max |h_zz|).
 *   - The shipped real DEM (tests/data/jacksboro_fault_dem.tif, 403 x 344 samples of 3 arc-seconds)
 *     reads back with the size, height range and spot values its generator printed from the
 *     source, and its extent equals the closed-form lengths of its degrees on WGS 84 (1e-9).
 *   - The plan reads the scene's heightmap (terrain.heightmap_*) and refuses a bad one with the
 *     loader's error, before any device work. */
#include <math.h>
#include <openexr.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>
#include <stb_image_write.h>
#include "atmo/dem.h"
#include "atmo/plan.h"
#include "atmo/plan.h"
#include "testlib.h"
#ifdef ATMO_HAVE_GDAL
#include <gdal.h>
#include <ogr_srs_api.h>
#endif

#define PI 3.14159265358979323846
#define W 48
#define H 32
#define CELL 100.0 /* metres */

static char dir[256];

static void path_of(char *buf, size_t n, const char *name)
{
    snprintf(buf, n, "%s/%s", dir, name);
}

/* The closed-form surface, metres, at a point of the DEM frame, and its gradient. */
static double surface(double x, double z)
{
    return 400.0 + 300.0 * sin(2 * PI * x / 1700.0) * cos(2 * PI * z / 1300.0) + 0.01 * x -
           0.02 * z;
}

static void surface_gradient(double x, double z, double g[2])
{
    double kx = 2 * PI / 1700.0, kz = 2 * PI / 1300.0;
    g[0] = 300.0 * kx * cos(kx * x) * cos(kz * z) + 0.01;
    g[1] = -300.0 * kz * sin(kx * x) * sin(kz * z) - 0.02;
}

static double centre_x(int col, int width, double cell)
{
    return (col + 0.5) * cell - width * cell / 2;
}

/* ---- a 16-bit greyscale PNG, from the PNG specification (stored deflate blocks) ---------- */

static uint32_t crc_table[256];

static void crc_init(void)
{
    for (uint32_t n = 0; n < 256; n++) {
        uint32_t c = n;
        for (int k = 0; k < 8; k++)
            c = c & 1 ? 0xedb88320u ^ (c >> 1) : c >> 1;
        crc_table[n] = c;
    }
}

static uint32_t crc(const unsigned char *p, size_t n, uint32_t c)
{
    for (size_t i = 0; i < n; i++)
        c = crc_table[(c ^ p[i]) & 0xff] ^ (c >> 8);
    return c;
}

static void put32(unsigned char *p, uint32_t v)
{
    p[0] = (unsigned char)(v >> 24);
    p[1] = (unsigned char)(v >> 16);
    p[2] = (unsigned char)(v >> 8);
    p[3] = (unsigned char)v;
}

static void chunk(FILE *f, const char *type, const unsigned char *data, size_t n)
{
    unsigned char head[8];
    put32(head, (uint32_t)n);
    memcpy(head + 4, type, 4);
    fwrite(head, 1, 8, f);
    fwrite(data, 1, n, f);
    uint32_t c = crc(data, n, crc((const unsigned char *)type, 4, 0xffffffffu)) ^ 0xffffffffu;
    unsigned char tail[4];
    put32(tail, c);
    fwrite(tail, 1, 4, f);
}

/* values: w * h * channels 16-bit samples (channels 1: grey, 2: grey + alpha) */
static void write_png16(const char *path, int w, int h, int channels, const uint16_t *values)
{
    size_t row = 1 + (size_t)w * (size_t)channels * 2, raw_n = row * (size_t)h;
    unsigned char *raw = malloc(raw_n);
    for (int y = 0; y < h; y++) {
        raw[(size_t)y * row] = 0; /* filter: none */
        for (int i = 0; i < w * channels; i++) {
            uint16_t v = values[(size_t)y * (size_t)w * (size_t)channels + (size_t)i];
            raw[(size_t)y * row + 1 + 2 * (size_t)i] = (unsigned char)(v >> 8);
            raw[(size_t)y * row + 2 + 2 * (size_t)i] = (unsigned char)v;
        }
    }
    size_t blocks = raw_n / 65535 + 1, z_n = 2 + raw_n + 5 * blocks + 4;
    unsigned char *z = malloc(z_n), *q = z;
    *q++ = 0x78;
    *q++ = 0x01;
    uint32_t a = 1, b = 0;
    for (size_t off = 0; off < raw_n || off == 0; off += 65535) {
        size_t len = raw_n - off < 65535 ? raw_n - off : 65535;
        *q++ = off + len >= raw_n;
        *q++ = (unsigned char)len;
        *q++ = (unsigned char)(len >> 8);
        *q++ = (unsigned char)~len;
        *q++ = (unsigned char)(~len >> 8);
        memcpy(q, raw + off, len);
        q += len;
        for (size_t i = 0; i < len; i++) {
            a = (a + raw[off + i]) % 65521;
            b = (b + a) % 65521;
        }
        if (off + len >= raw_n)
            break;
    }
    put32(q, (b << 16) | a);
    q += 4;
    unsigned char ihdr[13];
    put32(ihdr, (uint32_t)w);
    put32(ihdr + 4, (uint32_t)h);
    ihdr[8] = 16;
    ihdr[9] = channels == 2 ? 4 : 0;
    ihdr[10] = ihdr[11] = ihdr[12] = 0;
    static const unsigned char sig[8] = {0x89, 'P', 'N', 'G', 0x0d, 0x0a, 0x1a, 0x0a};
    FILE *f = fopen(path, "wb");
    CHECK(f != NULL);
    if (f) {
        fwrite(sig, 1, 8, f);
        chunk(f, "IHDR", ihdr, 13);
        chunk(f, "IDAT", z, (size_t)(q - z));
        chunk(f, "IEND", NULL, 0);
        fclose(f);
    }
    free(z);
    free(raw);
}

/* ---- EXR through OpenEXR's C API ------------------------------------------------------ */

/* One or two channels ("Y", "Z") of heights; tiled with 16 x 16 tiles or scanlines. */
static int write_exr(const char *path, int w, int h, const float *heights, exr_pixel_type_t type,
                     int channels, int tiled)
{
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    exr_context_t ctxt = NULL;
    int part = -1;
    exr_result_t r = exr_start_write(&ctxt, path, EXR_WRITE_FILE_DIRECTLY, &init);
    if (r == EXR_ERR_SUCCESS)
        r = exr_add_part(ctxt, NULL, tiled ? EXR_STORAGE_TILED : EXR_STORAGE_SCANLINE, &part);
    if (r == EXR_ERR_SUCCESS)
        r = exr_initialize_required_attr_simple(ctxt, part, w, h, EXR_COMPRESSION_ZIP);
    if (r == EXR_ERR_SUCCESS && tiled)
        r = exr_set_tile_descriptor(ctxt, part, 16, 16, EXR_TILE_ONE_LEVEL, EXR_TILE_ROUND_DOWN);
    static const char *const names[2] = {"Y", "Z"};
    for (int c = 0; c < channels && r == EXR_ERR_SUCCESS; c++)
        r = exr_add_channel(ctxt, part, names[c], type, EXR_PERCEPTUALLY_LINEAR, 1, 1);
    if (r == EXR_ERR_SUCCESS)
        r = exr_write_header(ctxt);
    exr_encode_pipeline_t enc = EXR_ENCODE_PIPELINE_INITIALIZER;
    int started = 0, rows = 16;
    if (r == EXR_ERR_SUCCESS && !tiled)
        r = exr_get_scanlines_per_chunk(ctxt, part, &rows);
    int nx = tiled ? (w + 15) / 16 : 1, ny = (h + rows - 1) / rows;
    for (int ty = 0; r == EXR_ERR_SUCCESS && ty < ny; ty++)
        for (int tx = 0; r == EXR_ERR_SUCCESS && tx < nx; tx++) {
            exr_chunk_info_t ci;
            r = tiled ? exr_write_tile_chunk_info(ctxt, part, tx, ty, 0, 0, &ci)
                      : exr_write_scanline_chunk_info(ctxt, part, ty * rows, &ci);
            if (r != EXR_ERR_SUCCESS)
                break;
            r = started ? exr_encoding_update(ctxt, part, &ci, &enc)
                        : exr_encoding_initialize(ctxt, part, &ci, &enc);
            if (r != EXR_ERR_SUCCESS)
                break;
            for (int c = 0; c < enc.channel_count; c++) {
                enc.channels[c].encode_from_ptr =
                    (const uint8_t *)(heights + (size_t)(ty * rows) * (size_t)w +
                                      (size_t)(tx * 16));
                enc.channels[c].user_pixel_stride = sizeof(float);
                enc.channels[c].user_line_stride = w * (int32_t)sizeof(float);
                enc.channels[c].user_bytes_per_element = sizeof(float);
                enc.channels[c].user_data_type = EXR_PIXEL_FLOAT;
            }
            if (!started)
                r = exr_encoding_choose_default_routines(ctxt, part, &enc);
            started = 1;
            if (r == EXR_ERR_SUCCESS)
                r = exr_encoding_run(ctxt, part, &enc);
        }
    if (started)
        exr_encoding_destroy(ctxt, &enc);
    exr_result_t fin = ctxt ? exr_finish(&ctxt) : EXR_ERR_SUCCESS;
    CHECK(r == EXR_ERR_SUCCESS && fin == EXR_ERR_SUCCESS);
    if (r != EXR_ERR_SUCCESS)
        fprintf(stderr, "  writing %s: %s\n", path, exr_get_default_error_message(r));
    return r == EXR_ERR_SUCCESS && fin == EXR_ERR_SUCCESS;
}

/* ---- helpers ------------------------------------------------------------------------------ */

static void truncate_copy(const char *from, const char *to, double fraction)
{
    FILE *f = fopen(from, "rb");
    CHECK(f != NULL);
    if (!f)
        return;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *buf = malloc((size_t)n);
    CHECK(fread(buf, 1, (size_t)n, f) == (size_t)n);
    fclose(f);
    FILE *g = fopen(to, "wb");
    CHECK(g != NULL);
    if (g) {
        fwrite(buf, 1, (size_t)(n * fraction), g);
        fclose(g);
    }
    free(buf);
}

static atmo_dem_options options(double extent_m, double scale_m, double offset_m)
{
    atmo_dem_options o;
    memset(&o, 0, sizeof o);
    o.extent_m = extent_m;
    o.scale_m = scale_m;
    o.offset_m = offset_m;
    return o;
}

/* Loading fails with ATMO_ERR_USAGE and one line naming the file and `reason`. */
static void check_refused(const char *path, const atmo_dem_options *o, const char *reason)
{
    atmo_dem d;
    atmo_err e = {{0}};
    int rc = atmo_dem_load(path, o, &d, &e);
    const char *base = strrchr(path, '/') ? strrchr(path, '/') + 1 : path;
    int ok = rc == ATMO_ERR_USAGE && !strchr(e.msg, '\n') && strstr(e.msg, base) &&
             strstr(e.msg, reason) && d.heights_m == NULL;
    CHECK(ok);
    printf("refused %s: %s\n", base, e.msg);
    if (!ok)
        fprintf(stderr, "  %s -> %d: '%s' (wanted '%s')\n", base, rc, e.msg, reason);
}

/* max |loaded - surface| over the grid, and whether the grid is the expected one */
static double max_error(const atmo_dem *d, int w, int h, double cell)
{
    double worst = 0;
    CHECK(d->width == w && d->height == h);
    if (d->width != w || d->height != h)
        return INFINITY;
    for (int row = 0; row < h; row++)
        for (int col = 0; col < w; col++) {
            double want = surface(centre_x(col, w, cell), centre_x(row, h, cell));
            double err = fabs(d->heights_m[row * w + col] - want);
            if (!(err <= worst))
                worst = isnan(err) ? INFINITY : err;
        }
    return worst;
}

static const double float_rel = 1.0 / 16777216.0; /* 2^-24: metres in double to float */
static const double surface_max = 400.0 + 300.0 + 0.01 * 2400 + 0.02 * 1600; /* bound of |h| */

/* ---- PNG -------------------------------------------------------------------------------- */

static void test_png(void)
{
    char path[300];
    const double scale = 1000.0, offset = -50.0;
    uint16_t *v = malloc(sizeof *v * W * H * 2);
    for (int row = 0; row < H; row++)
        for (int col = 0; col < W; col++) {
            double h = surface(centre_x(col, W, CELL), centre_x(row, H, CELL));
            v[row * W + col] = (uint16_t)lround((h - offset) / scale * 65535.0);
        }
    path_of(path, sizeof path, "surface16.png");
    write_png16(path, W, H, 1, v);
    atmo_dem d;
    atmo_err e;
    atmo_dem_options o = options(W * CELL, scale, offset);
    CHECK(atmo_dem_load(path, &o, &d, &e) == ATMO_OK);
    if (d.heights_m) {
        double err = max_error(&d, W, H, CELL);
        double tol = scale / 2 / 65535 + surface_max * float_rel;
        printf("png 16-bit: max error %.3g m (bound %.3g m)\n", err, tol);
        CHECK(err <= tol);
        CHECK(d.extent_m[0] == W * CELL && d.extent_m[1] == H * CELL);
        CHECK(d.format == ATMO_DEM_PNG && strstr(d.format_name, "16-bit"));
        CHECK(d.nodata_filled == 0 && d.min_m <= d.max_m && d.min_m > 0);
    }
    atmo_dem_free(&d);
    atmo_dem_options no_extent = options(0, scale, offset);
    check_refused(path, &no_extent, "terrain.heightmap_file_extent_m");
    atmo_dem_options small = o;
    small.max_samples = W * H - 1;
    check_refused(path, &small, "48 x 32 samples, beyond the limit");

    /* 8-bit through stb_image_write */
    unsigned char *v8 = malloc(W * H);
    for (int i = 0; i < W * H; i++) {
        int row = i / W, col = i % W;
        double h = surface(centre_x(col, W, CELL), centre_x(row, H, CELL));
        v8[i] = (unsigned char)lround((h - offset) / scale * 255.0);
    }
    path_of(path, sizeof path, "surface8.png");
    CHECK(stbi_write_png(path, W, H, 1, v8, W) != 0);
    CHECK(atmo_dem_load(path, &o, &d, &e) == ATMO_OK);
    if (d.heights_m) {
        double err = max_error(&d, W, H, CELL), tol = scale / 2 / 255 + surface_max * float_rel;
        printf("png 8-bit: max error %.3g m (bound %.3g m)\n", err, tol);
        CHECK(err <= tol && strstr(d.format_name, "8-bit"));
    }
    atmo_dem_free(&d);

    /* colour: refused */
    unsigned char *rgb = calloc(W * H, 3);
    path_of(path, sizeof path, "colour.png");
    CHECK(stbi_write_png(path, W, H, 3, rgb, W * 3) != 0);
    check_refused(path, &o, "3 channels");
    free(rgb);

    /* truncated: refused */
    char cut[300];
    path_of(path, sizeof path, "surface16.png");
    path_of(cut, sizeof cut, "cut.png");
    truncate_copy(path, cut, 0.5);
    check_refused(cut, &o, "cut.png");

    /* grey + alpha: alpha 0 marks missing samples. A plane, with isolated holes (the mean of the
     * 8 neighbours of a plane is the plane) and a 6 x 6 hole. */
    const double plane0 = 200, plane_x = 0.05, plane_z = -0.03;
    int holes = 0;
    for (int row = 0; row < H; row++)
        for (int col = 0; col < W; col++) {
            double h = plane0 + plane_x * centre_x(col, W, CELL) + plane_z * centre_x(row, H, CELL);
            int isolated = row % 5 == 2 && col % 5 == 2 && col < 30;
            int big = row >= 10 && row < 16 && col >= 36 && col < 42;
            v[2 * (row * W + col)] = (uint16_t)lround((h - offset) / scale * 65535.0);
            v[2 * (row * W + col) + 1] = isolated || big ? 0 : 65535;
            holes += isolated || big;
        }
    path_of(path, sizeof path, "holes.png");
    write_png16(path, W, H, 2, v);
    CHECK(atmo_dem_load(path, &o, &d, &e) == ATMO_OK);
    if (d.heights_m) {
        CHECK(d.nodata_filled == (size_t)holes);
        double worst_isolated = 0, lo = INFINITY, hi = -INFINITY;
        int finite = 1;
        for (int row = 0; row < H; row++)
            for (int col = 0; col < W; col++) {
                float got = d.heights_m[row * W + col];
                double want =
                    plane0 + plane_x * centre_x(col, W, CELL) + plane_z * centre_x(row, H, CELL);
                finite &= isfinite(got) != 0;
                if (row % 5 == 2 && col % 5 == 2 && col < 30)
                    worst_isolated = fmax(worst_isolated, fabs(got - want));
                /* the ring around the big hole */
                if (row >= 9 && row < 17 && col >= 35 && col < 43 &&
                    !(row >= 10 && row < 16 && col >= 36 && col < 42)) {
                    lo = fmin(lo, got);
                    hi = fmax(hi, got);
                }
            }
        CHECK(finite);
        /* quantisation of the neighbours, averaged, plus float rounding */
        double tol = scale / 2 / 65535 + 300 * float_rel * 4;
        printf("nodata: %zu filled; isolated holes off the plane by %.3g m (bound %.3g m)\n",
               d.nodata_filled, worst_isolated, tol);
        CHECK(worst_isolated <= tol);
        for (int row = 10; row < 16; row++)
            for (int col = 36; col < 42; col++) {
                float got = d.heights_m[row * W + col];
                CHECK(got >= lo - 1e-3 && got <= hi + 1e-3);
            }
    }
    atmo_dem_free(&d);
    /* the same holes with terrain.heightmap_nodata=sea-level: exactly 0 m */
    atmo_dem_options sea = o;
    sea.nodata = ATMO_DEM_NODATA_SEA_LEVEL;
    CHECK(atmo_dem_load(path, &sea, &d, &e) == ATMO_OK);
    if (d.heights_m) {
        CHECK(d.nodata_filled == (size_t)holes);
        CHECK(d.heights_m[2 * W + 2] == 0 && d.heights_m[12 * W + 38] == 0 && d.min_m == 0);
    }
    atmo_dem_free(&d);
    free(v);
    free(v8);
}

/* A coast: the eastern half of a 1024 x 1024 grid is nodata. Filling from the neighbours is
 * linear in the grid (the time is printed, not asserted) and leaves every sample finite and
 * within the range of the known heights (a mean of known values cannot leave their range). */
static void test_large_hole(void)
{
    enum { N = 1024 };
    char path[300];
    uint16_t *v = malloc(sizeof *v * N * N * 2);
    for (int row = 0; row < N; row++)
        for (int col = 0; col < N; col++) {
            v[2 * (row * N + col)] = (uint16_t)(1000 + 30 * ((row * 7 + col * 3) % 101));
            v[2 * (row * N + col) + 1] = col < N / 2 ? 65535 : 0;
        }
    path_of(path, sizeof path, "coast.png");
    write_png16(path, N, N, 2, v);
    free(v);
    atmo_dem d;
    atmo_err e;
    atmo_dem_options o = options(N * 30.0, 65535, 0); /* heights = stored values, metres */
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    CHECK(atmo_dem_load(path, &o, &d, &e) == ATMO_OK);
    clock_gettime(CLOCK_MONOTONIC, &t1);
    if (d.heights_m) {
        CHECK(d.nodata_filled == (size_t)N * N / 2);
        CHECK(d.min_m >= 1000 && d.max_m <= 1000 + 30 * 100);
        int finite = 1;
        for (size_t i = 0; i < (size_t)N * N; i++)
            finite &= isfinite(d.heights_m[i]) != 0;
        CHECK(finite);
        printf("coast: %zu of %d samples filled from their neighbours in %.3f s (with reading)\n",
               d.nodata_filled, N * N,
               (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec));
    }
    atmo_dem_free(&d);
}

/* ---- EXR -------------------------------------------------------------------------------- */

static void test_exr(void)
{
    char path[300];
    float *h = malloc(sizeof *h * W * H);
    for (int row = 0; row < H; row++)
        for (int col = 0; col < W; col++)
            h[row * W + col] = (float)surface(centre_x(col, W, CELL), centre_x(row, H, CELL));
    atmo_dem_options o = options(W * CELL, 0, 0);
    atmo_dem d;
    atmo_err e;
    static const struct {
        const char *name;
        exr_pixel_type_t type;
        int tiled;
        double rel; /* the format's rounding of a height */
    } cases[] = {{"float.exr", EXR_PIXEL_FLOAT, 0, 0},
                 {"tiled.exr", EXR_PIXEL_FLOAT, 1, 0},
                 {"half.exr", EXR_PIXEL_HALF, 0, 1.0 / 2048}};
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        path_of(path, sizeof path, cases[k].name);
        if (!write_exr(path, W, H, h, cases[k].type, 1, cases[k].tiled))
            continue;
        CHECK(atmo_dem_load(path, &o, &d, &e) == ATMO_OK);
        if (!d.heights_m) {
            fprintf(stderr, "  %s: %s\n", cases[k].name, e.msg);
            continue;
        }
        double err = max_error(&d, W, H, CELL);
        double tol = surface_max * (cases[k].rel + float_rel);
        printf("exr %s: max error %.3g m (bound %.3g m)\n", cases[k].name, err, tol);
        CHECK(err <= tol);
        if (cases[k].type == EXR_PIXEL_FLOAT) /* float in, float out */
            CHECK(memcmp(d.heights_m, h, sizeof *h * W * H) == 0);
        CHECK(d.format == ATMO_DEM_EXR && d.extent_m[1] == H * CELL);
        atmo_dem_free(&d);
    }
    /* a non-finite sample is missing and filled */
    h[5 * W + 7] = INFINITY;
    path_of(path, sizeof path, "inf.exr");
    if (write_exr(path, W, H, h, EXR_PIXEL_FLOAT, 1, 0)) {
        CHECK(atmo_dem_load(path, &o, &d, &e) == ATMO_OK);
        CHECK(d.heights_m && d.nodata_filled == 1 && isfinite(d.heights_m[5 * W + 7]));
        atmo_dem_free(&d);
    }
    path_of(path, sizeof path, "two.exr");
    if (write_exr(path, W, H, h, EXR_PIXEL_FLOAT, 2, 0))
        check_refused(path, &o, "2 channels (Y, Z)");
    char cut[300];
    path_of(path, sizeof path, "float.exr");
    path_of(cut, sizeof cut, "cut.exr");
    truncate_copy(path, cut, 0.6);
    check_refused(cut, &o, "cut.exr");
    atmo_dem_options no_extent = options(0, 0, 0);
    check_refused(path, &no_extent, "terrain.heightmap_file_extent_m");
    free(h);
}

/* ---- GeoTIFF ---------------------------------------------------------------------------- */

#ifdef ATMO_HAVE_GDAL
/* EPSG code (0: none; -1: a local CRS), geotransform, heights row by row as stored. */
static void write_tiff(const char *path, int w, int h, int epsg, const double gt[6],
                       const float *heights, int has_nodata, double nodata, const char *unit)
{
    GDALAllRegister();
    GDALDriverH drv = GDALGetDriverByName("GTiff");
    CHECK(drv != NULL);
    GDALDatasetH ds = drv ? GDALCreate(drv, path, w, h, 1, GDT_Float32, NULL) : NULL;
    CHECK(ds != NULL);
    if (!ds)
        return;
    CHECK(GDALSetGeoTransform(ds, (double *)gt) == CE_None);
    if (epsg) {
        OGRSpatialReferenceH srs = OSRNewSpatialReference(NULL);
        if (epsg > 0) {
            CHECK(OSRImportFromEPSG(srs, epsg) == OGRERR_NONE);
        } else {
            CHECK(OSRSetLocalCS(srs, "site grid") == OGRERR_NONE);
            CHECK(OSRSetLinearUnits(srs, "metre", 1.0) == OGRERR_NONE);
        }
        CHECK(GDALSetSpatialRef(ds, srs) == CE_None);
        OSRDestroySpatialReference(srs);
    }
    GDALRasterBandH band = GDALGetRasterBand(ds, 1);
    if (heights)
        CHECK(GDALRasterIO(band, GF_Write, 0, 0, w, h, (void *)heights, w, h, GDT_Float32, 0, 0) ==
              CE_None);
    if (has_nodata)
        CHECK(GDALSetRasterNoDataValue(band, nodata) == CE_None);
    if (unit)
        CHECK(GDALSetRasterUnitType(band, unit) == CE_None);
    GDALClose(ds);
}

static void test_geotiff(void)
{
    char path[300];
    atmo_dem d;
    atmo_err e;
    atmo_dem_options o = options(0, 0, 0);
    float *h = malloc(sizeof *h * W * H), *flipped = malloc(sizeof *h * W * H);
    for (int row = 0; row < H; row++)
        for (int col = 0; col < W; col++) {
            h[row * W + col] = (float)surface(centre_x(col, W, CELL), centre_x(row, H, CELL));
            flipped[(H - 1 - row) * W + col] = h[row * W + col];
        }
    /* UTM zone 32N, north up */
    double gt[6] = {400000, CELL, 0, 5100000, 0, -CELL};
    path_of(path, sizeof path, "utm.tif");
    write_tiff(path, W, H, 32632, gt, h, 0, 0, NULL);
    CHECK(atmo_dem_load(path, &o, &d, &e) == ATMO_OK);
    if (d.heights_m) {
        double err = max_error(&d, W, H, CELL);
        printf("geotiff utm: max error %.3g m (float rounding), extent %.9g x %.9g m, %s\n", err,
               d.extent_m[0], d.extent_m[1], d.projection);
        CHECK(err <= surface_max * float_rel);
        CHECK(memcmp(d.heights_m, h, sizeof *h * W * H) == 0); /* float32 in, float32 out */
        CHECK(d.extent_m[0] == W * CELL && d.extent_m[1] == H * CELL);
        CHECK(strstr(d.projection, "32632") && !d.geographic && d.format == ATMO_DEM_GEOTIFF);
    } else {
        fprintf(stderr, "  utm.tif: %s\n", e.msg);
    }
    atmo_dem_free(&d);

    /* south up (rows stored south first): the same grid */
    double gt_south[6] = {400000, CELL, 0, 5100000 - H * CELL, 0, CELL};
    path_of(path, sizeof path, "south_up.tif");
    write_tiff(path, W, H, 32632, gt_south, flipped, 0, 0, NULL);
    CHECK(atmo_dem_load(path, &o, &d, &e) == ATMO_OK);
    if (d.heights_m)
        CHECK(memcmp(d.heights_m, h, sizeof *h * W * H) == 0);
    atmo_dem_free(&d);

    /* columns stored east first (negative cell width): the same grid */
    float *mirrored = malloc(sizeof *h * W * H);
    for (int row = 0; row < H; row++)
        for (int col = 0; col < W; col++)
            mirrored[row * W + (W - 1 - col)] = h[row * W + col];
    double gt_east[6] = {400000 + W * CELL, -CELL, 0, 5100000, 0, -CELL};
    path_of(path, sizeof path, "east_first.tif");
    write_tiff(path, W, H, 32632, gt_east, mirrored, 0, 0, NULL);
    CHECK(atmo_dem_load(path, &o, &d, &e) == ATMO_OK);
    if (d.heights_m)
        CHECK(memcmp(d.heights_m, h, sizeof *h * W * H) == 0);
    atmo_dem_free(&d);
    free(mirrored);

    /* nodata and a band in feet */
    float *holed = malloc(sizeof *h * W * H);
    memcpy(holed, h, sizeof *h * W * H);
    holed[3 * W + 4] = holed[20 * W + 30] = -9999;
    path_of(path, sizeof path, "nodata_ft.tif");
    write_tiff(path, W, H, 32632, gt, holed, 1, -9999, "ft");
    CHECK(atmo_dem_load(path, &o, &d, &e) == ATMO_OK);
    if (d.heights_m) {
        CHECK(d.nodata_filled == 2);
        CHECK_REL(d.heights_m[10 * W + 10], h[10 * W + 10] * 0.3048, 2 * float_rel);
        CHECK(d.min_m > 0); /* -9999 is not a height */
    }
    atmo_dem_free(&d);
    free(holed);

    /* geographic degrees against the published lengths of a degree on WGS 84 */
    static const struct {
        double lat, per_deg_lat, per_deg_lon;
    } published[] = {{0, 110574, 111320}, {45, 111132, 78847}};
    for (size_t k = 0; k < 2; k++) {
        double gt_geo[6] = {7, 1.0 / 36, 0, published[k].lat + 0.5, 0, -1.0 / 36};
        float *flat = calloc(36 * 36, sizeof *flat);
        path_of(path, sizeof path, "wgs84.tif");
        write_tiff(path, 36, 36, 4326, gt_geo, flat, 0, 0, NULL);
        CHECK(atmo_dem_load(path, &o, &d, &e) == ATMO_OK);
        if (d.heights_m) {
            printf("geotiff wgs84 at %g deg: 1 deg x 1 deg = %.3f x %.3f m (published %.0f x "
                   "%.0f)\n",
                   published[k].lat, d.extent_m[0], d.extent_m[1], published[k].per_deg_lon,
                   published[k].per_deg_lat);
            CHECK_ABS(d.extent_m[0], published[k].per_deg_lon, 1.0);
            CHECK_ABS(d.extent_m[1], published[k].per_deg_lat, 1.0);
            CHECK(d.geographic && fabs(d.centre_lat_deg - published[k].lat) < 1e-9);
        } else {
            fprintf(stderr, "  wgs84.tif: %s\n", e.msg);
        }
        atmo_dem_free(&d);
        free(flat);
    }

    /* refused: rotated, no CRS, a local CRS, truncated, too big */
    double gt_rot[6] = {400000, CELL, 5, 5100000, 0, -CELL};
    path_of(path, sizeof path, "rotated.tif");
    write_tiff(path, W, H, 32632, gt_rot, h, 0, 0, NULL);
    check_refused(path, &o, "rotated");
    path_of(path, sizeof path, "no_crs.tif");
    write_tiff(path, W, H, 0, gt, h, 0, 0, NULL);
    check_refused(path, &o, "no coordinate reference system");
    path_of(path, sizeof path, "local.tif");
    write_tiff(path, W, H, -1, gt, h, 0, 0, NULL);
    check_refused(path, &o, "local");
    char cut[300];
    path_of(path, sizeof path, "utm.tif");
    path_of(cut, sizeof cut, "cut.tif");
    truncate_copy(path, cut, 0.5);
    check_refused(cut, &o, "cut.tif");
    path_of(path, sizeof path, "wide.tif"); /* a sparse file: refused before its data are read */
    write_tiff(path, 40000, 2, 32632, gt, NULL, 0, 0, NULL);
    check_refused(path, &o, "40000 x 2 samples, beyond the limit of 32768 per side");
    free(h);
    free(flipped);
}

/* The shipped real DEM (tests/data/README.md): size, range and spot values as the tool that
 * wrote it printed them from matplotlib's file, and the extent of 403 x 344 cells of 1/1200
 * degree at the centre latitude by the closed forms with WGS 84's defining constants
 * (a = 6378137 m, 1/f = 298.257223563), computed here independently of dem_gdal.c. */
static void test_real_dem(void)
{
    const char *src = getenv("ATMO_SOURCE_DIR");
    char path[512];
    snprintf(path, sizeof path, "%s/tests/data/jacksboro_fault_dem.tif", src ? src : "..");
    atmo_dem d;
    atmo_err e;
    atmo_dem_options o = options(0, 0, 0);
    CHECK(atmo_dem_load(path, &o, &d, &e) == ATMO_OK);
    if (!d.heights_m) {
        fprintf(stderr, "  %s: %s\n", path, e.msg);
        return;
    }
    CHECK(d.width == 403 && d.height == 344 && d.min_m == 236 && d.max_m == 1076);
    CHECK(d.heights_m[0] == 483 && d.heights_m[172 * 403 + 201] == 583 &&
          d.heights_m[343 * 403 + 402] == 272 && d.heights_m[100 * 403 + 300] == 537);
    double lat = (36.73291666666667 + 36.44625) / 2 * PI / 180;
    double f = 1 / 298.257223563, e2 = f * (2 - f), w = 1 - e2 * sin(lat) * sin(lat);
    double ew = 6378137.0 / sqrt(w) * cos(lat) * PI / 180 * 403 / 1200.0;
    double ns = 6378137.0 * (1 - e2) / (w * sqrt(w)) * PI / 180 * 344 / 1200.0;
    printf("real DEM: %d x %d, %.3f x %.3f m (closed form %.3f x %.3f), %g .. %g m, %s\n",
           d.width, d.height, d.extent_m[0], d.extent_m[1], ew, ns, d.min_m, d.max_m,
           d.projection);
    CHECK_REL(d.extent_m[0], ew, 1e-9);
    CHECK_REL(d.extent_m[1], ns, 1e-9);
    CHECK(d.geographic && strstr(d.projection, "4326"));
    atmo_dem_free(&d);
}
#endif

#ifndef ATMO_HAVE_GDAL
/* Built without GDAL: a GeoTIFF is refused with one line that says how to enable it. */
static void test_without_gdal(void)
{
    const char *src = getenv("ATMO_SOURCE_DIR");
    char path[512];
    snprintf(path, sizeof path, "%s/tests/data/jacksboro_fault_dem.tif", src ? src : "..");
    atmo_dem_options o = options(0, 0, 0);
    check_refused(path, &o, "built without GDAL; install libgdal-dev and rebuild");
    printf("GeoTIFF reading: not in this build (no GDAL); its refusal tested\n");
}
#endif

/* ---- not a DEM, the plan --------------------------------------------------------------- */

static void test_not_a_dem(void)
{
    char path[300];
    path_of(path, sizeof path, "notes.txt");
    FILE *f = fopen(path, "w");
    CHECK(f != NULL);
    if (f) {
        fputs("these are not heights\n", f);
        fclose(f);
    }
    atmo_dem_options o = options(1000, 1000, 0);
    check_refused(path, &o, "notes.txt");
    path_of(path, sizeof path, "missing.png");
    check_refused(path, &o, "check the path");
}

static void test_plan(void)
{
    atmo_scene s;
    atmo_err e;
    atmo_plan p;
    char path[300], set[400];
    atmo_scene_defaults(&s);
    path_of(path, sizeof path, "surface16.png");
    snprintf(set, sizeof set, "terrain.heightmap_file=%s", path);
    CHECK(atmo_scene_assign(&s, set, "test", &e) == ATMO_OK);
    CHECK(atmo_scene_assign(&s, "terrain.heightmap_file_extent_m=4800", "test", &e) == ATMO_OK);
    CHECK(atmo_plan_make(&s, &p, &e) == ATMO_OK);
    CHECK(p.dem.width == W && p.dem.height == H && p.dem.extent_m[0] == 4800);
    atmo_plan_free(&p);
    CHECK(atmo_scene_assign(&s, "terrain.heightmap_file_extent_m=0", "test", &e) == ATMO_OK);
    int rc = atmo_plan_make(&s, &p, &e);
    CHECK(rc == ATMO_ERR_USAGE && strstr(e.msg, "terrain.heightmap_file_extent_m"));
    atmo_scene_defaults(&s); /* no file: no DEM */
    CHECK(atmo_plan_make(&s, &p, &e) == ATMO_OK && p.dem.width == 0 && !p.dem.heights_m);
    atmo_plan_free(&p);
}

/* ---- resampling ------------------------------------------------------------------------- */

/* A DEM of the surface at cell size `cell` over a fixed 6000 x 4000 m area. */
static void make_dem(atmo_dem *d, double cell)
{
    memset(d, 0, sizeof *d);
    d->width = (int)lround(6000 / cell);
    d->height = (int)lround(4000 / cell);
    d->extent_m[0] = 6000;
    d->extent_m[1] = 4000;
    d->heights_m = malloc(sizeof *d->heights_m * (size_t)d->width * (size_t)d->height);
    for (int row = 0; row < d->height; row++)
        for (int col = 0; col < d->width; col++)
            d->heights_m[row * d->width + col] =
                (float)surface(centre_x(col, d->width, cell), -centre_x(row, d->height, cell));
}

/* East on the right of a camera looking north: a DEM with a ridge along its eastern edge
 * (columns W/2 ..: 1000 m) and a plateau along its northern one (rows .. H/4: 500 m, row 0
 * north, column 0 west, dem.h's layout and GDAL's north-up one) is sampled where the renderer
 * samples it (atmo_dem_sample at world X, Z less the centre: plan_terrain.c's plan_dem,
 * `atmo terrain`); the camera whose forward points at the plateau (atmo_camera_basis, the
 * renderer's own) must have the ridge on its right (right . east > 0), as on a map. */
static void test_orientation(void)
{
    atmo_dem d;
    memset(&d, 0, sizeof d);
    d.width = d.height = 64;
    d.extent_m[0] = d.extent_m[1] = 6400.0;
    d.heights_m = malloc(sizeof *d.heights_m * 64 * 64);
    for (int row = 0; row < 64; row++)
        for (int col = 0; col < 64; col++)
            d.heights_m[row * 64 + col] = (float)((col >= 32 ? 1000.0 : 0.0) + (row < 16 ? 500.0 : 0.0));
    /* where the plateau and the ridge lie, from the interpolated heights at +-2500 m */
    double north = atmo_dem_sample(&d, -2500.0, 2500.0, ATMO_DEM_BILINEAR) -
                   atmo_dem_sample(&d, -2500.0, -2500.0, ATMO_DEM_BILINEAR);
    double east = atmo_dem_sample(&d, 2500.0, -2500.0, ATMO_DEM_BILINEAR) -
                  atmo_dem_sample(&d, -2500.0, -2500.0, ATMO_DEM_BILINEAR);
    double n_dir[3] = {0, 0, north > 0 ? 1.0 : -1.0}, e_dir[3] = {east > 0 ? 1.0 : -1.0, 0, 0};
    double yaw = n_dir[2] > 0 ? 0.0 : 180.0, fw[3], rt[3], up[3];
    atmo_camera_basis(0.0, yaw, fw, rt, up);
    double ahead = fw[0] * n_dir[0] + fw[2] * n_dir[2], side = rt[0] * e_dir[0] + rt[2] * e_dir[2];
    printf("orientation: north plateau toward world Z %+.0f, east ridge toward X %+.0f; a camera "
           "at yaw %.0f faces it (%.2f) with the ridge on its %s\n", n_dir[2], e_dir[0], yaw,
           ahead, side > 0 ? "right" : "LEFT");
    CHECK(fabs(north) > 400.0 && fabs(east) > 900.0);
    CHECK(ahead > 0.99 && side > 0.99);
    free(d.heights_m);
}

/* A low-discrepancy (golden-ratio) sequence over [-2500, 2500] x [-1500, 1500], inside the
 * outermost sample centres. */
static void test_point(int k, double *x, double *z)
{
    *x = -2500 + 5000 * fmod(0.5 + k * 0.6180339887498949, 1.0);
    *z = -1500 + 3000 * fmod(0.5 + k * 0.7548776662466927, 1.0);
}

/* max error of the height over the test points */
static double interpolation_error(const atmo_dem *d, int filter)
{
    double worst = 0, x, z;
    for (int k = 0; k < 4000; k++) {
        test_point(k, &x, &z);
        worst = fmax(worst, fabs(atmo_dem_sample(d, x, z, filter) - surface(x, z)));
    }
    return worst;
}

/* max error of bicubic's gradient against the surface's, and its largest difference from the
 * central difference of the interpolated heights over +-0.1 mm. The interpolant is a cubic in
 * each cell and C1 across cells, so that difference is at most delta/2 times the jump of its
 * second derivative at a cell edge (<= 2 max |h''|, 0.007/m for this surface) plus
 * delta^2/6 max |h'''| and the rounding of double heights over 2 delta (~1e-9): below
 * delta (max |h_xx| + max |h_zz|) ~ 1.1e-6. */
static double gradient_error(const atmo_dem *d, double *to_differences)
{
    double worst = 0, worst_fd = 0, x, z;
    for (int k = 0; k < 4000; k++) {
        test_point(k, &x, &z);
        double g[2], want[2], delta = 1e-4;
        atmo_dem_sample_gradient(d, x, z, ATMO_DEM_BICUBIC, g);
        surface_gradient(x, z, want);
        worst = fmax(worst, fmax(fabs(g[0] - want[0]), fabs(g[1] - want[1])));
        double fx = (atmo_dem_sample(d, x + delta, z, ATMO_DEM_BICUBIC) -
                     atmo_dem_sample(d, x - delta, z, ATMO_DEM_BICUBIC)) / (2 * delta);
        double fz = (atmo_dem_sample(d, x, z + delta, ATMO_DEM_BICUBIC) -
                     atmo_dem_sample(d, x, z - delta, ATMO_DEM_BICUBIC)) / (2 * delta);
        worst_fd = fmax(worst_fd, fmax(fabs(g[0] - fx), fabs(g[1] - fz)));
    }
    *to_differences = worst_fd;
    return worst;
}

static void test_resample(void)
{
    /* |h_xx| <= 300 (2 pi / 1700)^2, |h_zz| <= 300 (2 pi / 1300)^2 */
    const double hxx = 300 * pow(2 * PI / 1700, 2), hzz = 300 * pow(2 * PI / 1300, 2);
    double err_lin[2], err_cub[2], err_grad[2];
    for (int level = 0; level < 2; level++) {
        double cell = level == 0 ? 100 : 50;
        atmo_dem d;
        make_dem(&d, cell);
        err_lin[level] = interpolation_error(&d, ATMO_DEM_BILINEAR);
        err_cub[level] = interpolation_error(&d, ATMO_DEM_BICUBIC);
        double to_fd;
        err_grad[level] = gradient_error(&d, &to_fd);
        printf("bicubic gradient at %g m cells: max error %.3g (surface slope up to %.3g), "
               "%.2g from central differences\n",
               cell, err_grad[level], 300 * 2 * PI / 1300 + 0.02, to_fd);
        CHECK(to_fd <= 1e-4 * (hxx + hzz));
        double bound = cell * cell / 8 * (hxx + hzz) + surface_max * float_rel;
        printf("resample at %g m cells: bilinear %.4g m (bound %.4g m), bicubic %.4g m\n", cell,
               err_lin[level], bound, err_cub[level]);
        CHECK(err_lin[level] <= bound);
        CHECK(err_cub[level] < err_lin[level]);
        /* both interpolate: at the sample centres they return the samples */
        double at_centres = 0;
        for (int row = 0; row < d.height; row += 7)
            for (int col = 0; col < d.width; col += 5)
                for (int filter = 0; filter < 2; filter++)
                    at_centres = fmax(at_centres,
                                      fabs(atmo_dem_sample(&d, centre_x(col, d.width, cell),
                                                           -centre_x(row, d.height, cell), filter) -
                                           d.heights_m[row * d.width + col]));
        CHECK(at_centres <= surface_max * 1e-12);
        /* the grid form equals the point form, as float, with and without derivatives */
        atmo_dem_grid g = {17, 11, -2000, 1500, 230, -260, 0};
        float out[17 * 11], out3[3 * 17 * 11];
        atmo_err e;
        CHECK(atmo_dem_resample(&d, &g, ATMO_DEM_BICUBIC, out, &e) == ATMO_OK);
        g.derivatives = 1;
        CHECK(atmo_dem_resample(&d, &g, ATMO_DEM_BICUBIC, out3, &e) == ATMO_OK);
        int same = 1;
        for (int j = 0; j < g.height; j++)
            for (int i = 0; i < g.width; i++) {
                double grad[2];
                double h = atmo_dem_sample_gradient(&d, g.x0_m + i * g.dx_m, g.z0_m + j * g.dz_m,
                                                    ATMO_DEM_BICUBIC, grad);
                int k = j * g.width + i;
                same &= out[k] == (float)h && out3[3 * k] == (float)h &&
                        out3[3 * k + 1] == (float)grad[0] && out3[3 * k + 2] == (float)grad[1];
            }
        CHECK(same);
        /* far outside, the edge extends: far north-west, the first sample */
        CHECK(atmo_dem_sample(&d, -1e7, 1e7, ATMO_DEM_BILINEAR) == d.heights_m[0]);
        atmo_dem_free(&d);
    }
    double order_lin = log2(err_lin[0] / err_lin[1]), order_cub = log2(err_cub[0] / err_cub[1]);
    printf("resample: measured order bilinear %.2f (2 expected), bicubic %.2f (3 expected)\n",
           order_lin, order_cub);
    CHECK(order_lin >= 1.8 && order_lin <= 2.2);
    CHECK(order_cub >= 2.7);
    double order_grad = log2(err_grad[0] / err_grad[1]);
    printf("resample: bicubic gradient's measured order %.2f (2 expected)\n", order_grad);
    CHECK(order_grad >= 1.8);
    atmo_dem_grid bad = {0, 4, 0, 0, 1, 1, 0};
    atmo_err e;
    atmo_dem d;
    make_dem(&d, 100);
    CHECK(atmo_dem_resample(&d, &bad, ATMO_DEM_BILINEAR, NULL, &e) == ATMO_ERR_USAGE);
    atmo_dem_free(&d);
}

int main(void)
{
    crc_init();
    const char *tmp = getenv("TMPDIR");
    snprintf(dir, sizeof dir, "%s/atmo_test_dem.XXXXXX", tmp && tmp[0] ? tmp : "/tmp");
    if (!mkdtemp(dir)) {
        perror("mkdtemp");
        return 1;
    }
    test_png();
    test_large_hole();
    test_exr();
#ifdef ATMO_HAVE_GDAL
    test_geotiff();
    test_real_dem();
#else
    test_without_gdal();
#endif
    test_not_a_dem();
    test_plan();
    test_resample();
    test_orientation();
    char cmd[300];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    CHECK(system(cmd) == 0);
    return test_finish();
}
