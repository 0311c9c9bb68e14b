/* dem_png.c — a greyscale PNG heightmap (16-bit, or 8-bit) through stb_image.
 *
 * A sample's height is offset_m + scale_m * v / vmax, with v the stored value and vmax 65535
 * for 16-bit and 255 for 8-bit files (stb_image widens 8-bit values to 16 bits as v * 257, so
 * v16 / 65535 = v8 / 255 exactly and one formula serves both). The quantisation error of a
 * height is then at most scale_m / 2 / vmax. A grey+alpha PNG marks samples with alpha 0 as
 * missing (filled by dem.c). Colour PNGs are refused: a heightmap is one channel, and mixing
 * R, G, B into grey would invent heights. The extent comes from terrain.heightmap_file_extent_m. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <stb_image.h>
#include "dem_read.h"

int dem_read_png(const char *path, const atmo_dem_options *o, atmo_dem *dem, atmo_err *e)
{
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
