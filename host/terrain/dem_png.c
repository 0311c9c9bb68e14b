/* dem_png.c — a greyscale PNG heightmap (16-bit, or 8-bit) through stb_image.
 *
 * A sample's height is offset_m + scale_m * v / vmax, with v the stored value and vmax 65535
 * for 16-bit and 255 for 8-bit files (stb_image widens 8-bit values to 16 bits as v * 257, so
 * v16 / 65535 = v8 / 255 exactly and one formula serves both). The quantisation error of a
 * height is then at most scale_m / 2 / vmax. A grey+alpha PNG marks samples with alpha 0 as
 * missing (filled by dem.c). Colour PNGs are refused: a heightmap is one channel, and mixing
 * R, G, B into grey would invent heights. The extent comes from terrain.heightmap_file_extent_m.
 *
 * stb_image does not check the chunks' CRCs, so every chunk is checked here first (PNG
 * specification, ISO/IEC 15948 section 5.3: CRC-32 of ISO 3309, polynomial 0xEDB88320
 * reflected, over the chunk's type and data), up to IEND: a damaged file is refused naming the
 * chunk and its offset, instead of giving wrong heights. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <stb_image.h>
#include "atmo/fileio.h"
#include "dem_read.h"

static unsigned long crc32_update(unsigned long crc, const unsigned char *b, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        crc ^= b[i];
        for (int k = 0; k < 8; k++)
            crc = crc & 1 ? (crc >> 1) ^ 0xEDB88320ul : crc >> 1;
    }
    return crc;
}

static unsigned long be32(const unsigned char *b)
{
    return (unsigned long)b[0] << 24 | (unsigned long)b[1] << 16 | (unsigned long)b[2] << 8 | b[3];
}

/* Every chunk's CRC, from the signature to IEND. */
static int check_crcs(const char *path, atmo_err *e)
{
    const char *why = NULL;
    FILE *f = atmo_open_regular(path, &why);
    unsigned char head[8], *data = NULL;
    int rc = ATMO_OK;
    long at = 8;
    if (!f)
        return atmo_fail(e, ATMO_ERR_USAGE, "%s: cannot open it (%s)", path, why);
    if (fread(head, 1, 8, f) != 8)
        rc = atmo_fail(e, ATMO_ERR_USAGE, "%s: cut short inside the PNG signature", path);
    for (int chunk = 1; !rc; chunk++, at = ftell(f)) {
        unsigned char crc[4];
        if (fread(head, 1, 8, f) != 8) {
            rc = atmo_fail(e, ATMO_ERR_USAGE, "%s: cut short at byte %ld, before IEND (chunk %d "
                           "is missing); is the file complete?", path, at, chunk);
            break;
        }
        unsigned long len = be32(head);
        unsigned char *grown = len < 0x7fffffff ? realloc(data, len + 1) : NULL;
        if (!grown) {
            rc = atmo_fail(e, ATMO_ERR_USAGE, "%s: chunk %d at byte %ld claims %lu bytes; the "
                           "file is damaged", path, chunk, at, len);
            break;
        }
        data = grown;
        if (fread(data, 1, len, f) != len || fread(crc, 1, 4, f) != 4) {
            rc = atmo_fail(e, ATMO_ERR_USAGE, "%s: cut short inside chunk %d (%.4s) at byte %ld; "
                           "is the file complete?", path, chunk, (const char *)head + 4, at);
            break;
        }
        unsigned long want = crc32_update(crc32_update(0xFFFFFFFFul, head + 4, 4), data, len) ^
                             0xFFFFFFFFul;
        if (want != be32(crc)) {
            rc = atmo_fail(e, ATMO_ERR_USAGE, "%s: chunk %d (%.4s) at byte %ld fails its CRC-32 "
                           "(stored %08lx, computed %08lx); the file is damaged", path, chunk,
                           (const char *)head + 4, at, be32(crc), want);
            break;
        }
        if (memcmp(head + 4, "IEND", 4) == 0)
            break;
    }
    free(data);
    fclose(f);
    return rc;
}

int dem_read_png(const char *path, const atmo_dem_options *o, atmo_dem *dem, atmo_err *e)
{
    int crc_rc = check_crcs(path, e);
    if (crc_rc)
        return crc_rc;
    int w = 0, h = 0, comp = 0;
    if (!stbi_info(path, &w, &h, &comp))
        return atmo_fail(e, ATMO_ERR_USAGE, "%s: not a readable PNG (%s); is the file complete?",
                         path, stbi_failure_reason());
    int sixteen = stbi_is_16_bit(path);
    const char *format = sixteen ? "16-bit PNG" : "8-bit PNG";
    int rc = dem_check_size(path, format, w, h, o, e);
    if (rc)
        return rc;
    if (comp != 1 && comp != 2)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "%s: a %s with %d channels; a heightmap is one grey channel (save it as "
                         "16-bit greyscale)",
                         path, comp >= 3 ? "colour PNG" : "PNG", comp);
    unsigned short *data = stbi_load_16(path, &w, &h, &comp, 0);
    if (!data)
        return atmo_fail(e, ATMO_ERR_USAGE, "%s: the PNG's data cannot be decoded (%s); is the "
                         "file complete?", path, stbi_failure_reason());
    size_t n = (size_t)w * (size_t)h;
    dem->heights_m = malloc(n * sizeof *dem->heights_m);
    if (!dem->heights_m) {
        stbi_image_free(data);
        return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory reading %s (%d x %d)", path, w, h);
    }
    for (size_t i = 0; i < n; i++) {
        double v = data[i * (size_t)comp] / 65535.0;
        int missing = comp == 2 && data[i * 2 + 1] == 0;
        dem->heights_m[i] = missing ? NAN : (float)(o->offset_m + o->scale_m * v);
    }
    stbi_image_free(data);
    dem->width = w;
    dem->height = h;
    dem->format = ATMO_DEM_PNG;
    snprintf(dem->format_name, sizeof dem->format_name, "%s%s", format,
             comp == 2 ? " grey+alpha" : "");
    return dem_extent_from_options(path, format, o, dem, e);
}
