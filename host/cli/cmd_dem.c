/* cmd_dem.c — `atmo dem info FILE`: what atmo reads from a digital elevation model (atmo/dem.h):
 * format, size in samples, extent and cell size in metres, lowest and highest height, the
 * coordinate reference system and how the extent was found, and how many nodata samples were
 * filled. PNG and EXR heightmaps take their extent (and PNG its scale and offset) from the
 * terrain.heightmap_* keys, given with --set as for `atmo render`. --json prints one object
 * (for tools and tests). Errors are the loader's one line, exit 2. */
#include <cjson/cJSON.h>
#include <stdio.h>
#include <string.h>
#include "atmo/dem.h"
#include "atmo/scene.h"
#include "commands.h"

static void print_usage(FILE *f)
{
    fprintf(f,
            "usage: atmo dem info FILE [--set terrain.heightmap_KEY=VALUE]... [--json]\n\n"
            "Read a digital elevation model as `atmo render --set terrain.heightmap_file=FILE`\n"
            "would, and print its format, size, extent in metres, height range and projection.\n"
            "Formats: GeoTIFF (%s), 16-bit greyscale PNG, one-channel EXR.\n\n"
            "  --set KEY=VALUE  PNG/EXR: terrain.heightmap_file_extent_m (east-west size, m);\n"
            "                   PNG: terrain.heightmap_scale_m, terrain.heightmap_offset_m;\n"
            "                   terrain.heightmap_nodata (neighbours or sea-level)\n"
            "  --json           print one JSON object\n"
            "  --help           this text\n",
            atmo_dem_have_gdal() ? "through GDAL" : "not in this build: needs libgdal-dev");
}

static const char *fill_name(const atmo_dem_options *o)
{
    return o->nodata == ATMO_DEM_NODATA_SEA_LEVEL ? "sea-level" : "neighbours";
}

static int print_json(const char *path, const atmo_dem *d, const atmo_dem_options *opt)
{
    int rc = ATMO_ERR_RUNTIME;
    char *text = NULL;
    cJSON *o = cJSON_CreateObject();
    double extent[2] = {d->extent_m[0], d->extent_m[1]};
    double cell[2] = {d->extent_m[0] / d->width, d->extent_m[1] / d->height};
    if (!o || !cJSON_AddStringToObject(o, "file", path) ||
        !cJSON_AddStringToObject(o, "format", d->format_name) ||
        !cJSON_AddNumberToObject(o, "width", d->width) ||
        !cJSON_AddNumberToObject(o, "height", d->height) ||
        !cJSON_AddItemToObject(o, "extent_m", cJSON_CreateDoubleArray(extent, 2)) ||
        !cJSON_AddItemToObject(o, "cell_m", cJSON_CreateDoubleArray(cell, 2)) ||
        !cJSON_AddNumberToObject(o, "min_m", d->min_m) ||
        !cJSON_AddNumberToObject(o, "max_m", d->max_m) ||
        !cJSON_AddStringToObject(o, "projection", d->projection) ||
        !cJSON_AddBoolToObject(o, "geographic", d->geographic) ||
        (d->geographic && !cJSON_AddNumberToObject(o, "centre_lat_deg", d->centre_lat_deg)) ||
        !cJSON_AddNumberToObject(o, "nodata_filled", (double)d->nodata_filled) ||
        !cJSON_AddStringToObject(o, "nodata_fill", fill_name(opt)))
        goto cleanup;
    text = cJSON_Print(o);
    if (!text)
        goto cleanup;
    puts(text);
    rc = ATMO_OK;
cleanup:
    if (rc)
        fprintf(stderr, "atmo dem: out of memory\n");
    cJSON_free(text);
    cJSON_Delete(o);
    return rc;
}

static void print_text(const char *path, const atmo_dem *d, const atmo_dem_options *o)
{
    printf("file        %s\n", path);
    printf("format      %s\n", d->format_name);
    printf("size        %d x %d samples\n", d->width, d->height);
    printf("extent      %.6g x %.6g m (cells %.6g x %.6g m; x east, z south)\n", d->extent_m[0],
           d->extent_m[1], d->extent_m[0] / d->width, d->extent_m[1] / d->height);
    printf("height      %.6g .. %.6g m\n", d->min_m, d->max_m);
    printf("projection  %s\n", d->projection);
    printf("nodata      %zu samples, %s\n", d->nodata_filled,
           o->nodata == ATMO_DEM_NODATA_SEA_LEVEL ? "set to sea level (0 m)"
                                                  : "filled from their neighbours");
}

int cmd_dem(int argc, char **argv)
{
    const char *path = NULL;
    int json = 0, rc;
    atmo_scene s;
    atmo_err e;
    atmo_scene_defaults(&s);
    if (argc >= 2 && (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0)) {
        print_usage(stdout);
        return ATMO_OK;
    }
    if (argc < 2 || strcmp(argv[1], "info") != 0) {
        fprintf(stderr, "atmo dem: expected 'info FILE'; run 'atmo dem --help'\n");
        return ATMO_ERR_USAGE;
    }
    for (int i = 2; i < argc; i++) {
        if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
            print_usage(stdout);
            return ATMO_OK;
        } else if (strcmp(argv[i], "--json") == 0) {
            json = 1;
        } else if (strcmp(argv[i], "--set") == 0) {
            if (i + 1 >= argc) {
                fprintf(stderr, "atmo dem: --set needs KEY=VALUE\n");
                return ATMO_ERR_USAGE;
            }
            if ((rc = atmo_scene_assign(&s, argv[++i], "--set", &e))) {
                fprintf(stderr, "atmo dem: %s\n", e.msg);
                return rc;
            }
        } else if (argv[i][0] == '-' || path) {
            fprintf(stderr, "atmo dem: unexpected argument '%s'; run 'atmo dem --help'\n",
                    argv[i]);
            return ATMO_ERR_USAGE;
        } else {
            path = argv[i];
        }
    }
    if (!path) {
        fprintf(stderr, "atmo dem info: name the file: atmo dem info FILE\n");
        return ATMO_ERR_USAGE;
    }
    atmo_dem_options o;
    atmo_dem d;
    atmo_dem_options_from_scene(&s, &o);
    if ((rc = atmo_dem_load(path, &o, &d, &e))) {
        fprintf(stderr, "atmo dem: %s\n", e.msg);
        return rc;
    }
    if (json)
        rc = print_json(path, &d, &o);
    else
        print_text(path, &d, &o);
    atmo_dem_free(&d);
    return rc;
}
