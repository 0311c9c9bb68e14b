/* cmd_dem.c — `atmo dem info FILE`: what atmo reads from a digital elevation model (atmo/dem.h):
 * format, size in samples, extent and cell size in metres, lowest and highest height, the
 * coordinate reference system and how the extent was found, and how many nodata samples were
 * filled. PNG and EXR heightmaps take their extent (and PNG its scale and offset) from the
 * terrain.heightmap_* keys, given with --set as for `atmo render`. --json prints one object
 * (for tools and tests). Errors are the loader's one line, exit 2. */
#include <cjson/cJSON.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>
#include "atmo/dem.h"
#include "atmo/scene.h"
#include "cli_flags.h"
#include "commands.h"

typedef struct dem_args {
    atmo_scene scene; /* the terrain.heightmap_* keys of --set */
    int json;
} dem_args;

static int take_set(void *args, const cli_flag *f, const char *v, atmo_err *e)
{
    (void)f;
    return atmo_scene_assign(&((dem_args *)args)->scene, v, "--set", e);
}

static const cli_flag dem_flags[] = {
    {.type = CLI_STRING, .name = "--set", .metavar = "KEY=VALUE", .take = take_set, .def = "none",
     .help = "PNG/EXR: terrain.heightmap_file_extent_m (east-west size, m);\n"
             "PNG: terrain.heightmap_scale_m, terrain.heightmap_offset_m;\n"
             "terrain.heightmap_nodata (neighbours or sea-level) (repeatable)"},
    {.type = CLI_BOOL, .name = "--json", .offset = offsetof(dem_args, json),
     .help = "print one JSON object"},
    {.type = CLI_END},
};

static const cli_command dem_cli = {
    .name = "dem",
    .synopsis = "info FILE [--set terrain.heightmap_KEY=VALUE]... [--json]",
    .about = "Read a digital elevation model as `atmo render --set terrain.heightmap_file=FILE`\n"
             "would, and print its format, size, extent in metres, height range and projection.\n"
             "Formats: GeoTIFF (through GDAL), 16-bit greyscale PNG, one-channel EXR.\n",
    .flags = dem_flags,
    .max_positional = 2,
};

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
    printf("extent      %.6g x %.6g m (cells %.6g x %.6g m; x east, z north)\n", d->extent_m[0],
           d->extent_m[1], d->extent_m[0] / d->width, d->extent_m[1] / d->height);
    printf("height      %.6g .. %.6g m\n", d->min_m, d->max_m);
    printf("projection  %s\n", d->projection);
    printf("nodata      %zu samples, %s\n", d->nodata_filled,
           o->nodata == ATMO_DEM_NODATA_SEA_LEVEL ? "set to sea level (0 m)"
                                                  : "filled from their neighbours");
}

int cmd_dem(int argc, char **argv)
{
    const char *words[2] = {NULL, NULL};
    static dem_args a;
    int n = 0, rc;
    atmo_err e;
    memset(&a, 0, sizeof a);
    atmo_scene_defaults(&a.scene);
    if (!cli_parse(&dem_cli, &a, argc, argv, words, &n, &rc)) {
        if (rc == ATMO_OK)
            printf("\nGeoTIFF in this build: %s\n",
                   atmo_dem_have_gdal() ? "yes, through GDAL" : "no: needs libgdal-dev");
        return rc;
    }
    if (n < 1 || strcmp(words[0], "info") != 0) {
        fprintf(stderr, "atmo dem: expected 'info FILE'; run 'atmo dem --help'\n");
        return ATMO_ERR_USAGE;
    }
    if (n < 2) {
        fprintf(stderr, "atmo dem info: name the file: atmo dem info FILE\n");
        return ATMO_ERR_USAGE;
    }
    const char *path = words[1];
    atmo_dem_options o;
    atmo_dem d;
    atmo_dem_options_from_scene(&a.scene, &o);
    if ((rc = atmo_dem_load(path, &o, &d, &e))) {
        fprintf(stderr, "atmo dem: %s\n", e.msg);
        return rc;
    }
    if (a.json)
        rc = print_json(path, &d, &o);
    else
        print_text(path, &d, &o);
    atmo_dem_free(&d);
    return rc;
}
