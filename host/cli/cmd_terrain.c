/* cmd_terrain.c — `atmo terrain --at X,Z`: the terrain at a point of the planet, for users
 * placing cameras and objects and for the tests.
 *
 * Scene: the defaults, then --preset NAME or --scene FILE (default: the default preset), then
 * --set KEY=VALUE in order, as atmo render reads them (scene_options.h); terrain.enabled is
 * implied. (X, Z) are the planar coordinates of
 * the point's foot on the ground sphere (kernels/terrain/terrain.h: world x and z there, which
 * near the origin are the world coordinates of the point). For each --at it prints the height
 * of the height field above sea level (h, metres), the surface's altitude max(h, sea level),
 * the world position of the surface point, its unit normal (the sphere's tangent frame), the
 * land/sea coverage in [0, 1] and the material weights (terrain_material.h), all from the
 * kernels' own float functions compiled on the host (what a render sees, with the fBm
 * evaluated directly), plus the height from the double-precision reference
 * (host/terrain/terrain_ref.c). --json prints one JSON object per point, one per line, with at
 * least "height_m", "normal" and "coverage".
 *
 * With terrain.heightmap_file the terrain is the file's heights resampled into the heightmap
 * (features/terrain/plan_terrain.c: bicubic at the texel centres) and read back bilinearly, the
 * procedural fBm beyond the heightmap's square: the probe looks up the same texels with the
 * kernels' terrain_height_at as floats (the derivatives format differs in the normal's
 * interpolation, the half format by its rounding, 2^-11 of the height), the reference height
 * is the file's own bicubic interpolant in double (atmo_dem_sample) inside the square, plus with terrain.heightmap_detail the detail below
 * its cells (terrain_ref_detail), and the coverage is 1 on the file's land, 0 on its water. */
#include <cjson/cJSON.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/dem.h"
#include "atmo/plan.h"
#include "atmo/scene.h"
#include "atmo/terrain_ref.h"
#include "terrain/terrain_material.h"
#include "cli_flags.h"
#include "commands.h"
#include "scene_options.h"

#define TERRAIN_MAX_POINTS 256

static const char *const material_names[TERRAIN_MATERIALS] = {"grass", "dirt", "rock", "snow",
                                                              "water"};

static int parse_at(const char *v, double at[2], atmo_err *e)
{
    char *end;
    at[0] = strtod(v, &end);
    if (end == v || *end != ',')
        return atmo_fail(e, ATMO_ERR_USAGE, "--at needs X,Z in metres, got '%s'", v);
    const char *z = end + 1;
    at[1] = strtod(z, &end);
    if (end == z || *end || !isfinite(at[0]) || !isfinite(at[1]))
        return atmo_fail(e, ATMO_ERR_USAGE, "--at needs X,Z in metres, got '%s'", v);
    return ATMO_OK;
}

/* The flags' destinations (terrain_flags), holding the defaults before parsing. */
typedef struct terrain_args {
    scene_options so;
    double at[TERRAIN_MAX_POINTS][2];
    int n_at, json;
} terrain_args;

static int take_at(void *args, const cli_flag *f, const char *v, atmo_err *e)
{
    terrain_args *a = args;
    (void)f;
    if (a->n_at == TERRAIN_MAX_POINTS)
        return atmo_fail(e, ATMO_ERR_USAGE, "at most %d --at points", TERRAIN_MAX_POINTS);
    return parse_at(v, a->at[a->n_at++], e);
}

static const cli_flag terrain_flags[] = {
    {.type = CLI_STRING, .name = "--at", .metavar = "X,Z", .take = take_at,
     .def = "none: required",
     .help = "a point: planar coordinates in metres (repeatable, at least one)"},
    {.type = CLI_INCLUDE, .include = scene_source_flags, .offset = offsetof(terrain_args, so)},
    {.type = CLI_BOOL, .name = "--json", .offset = offsetof(terrain_args, json),
     .help = "one JSON object per point, one per line"},
    {.type = CLI_END},
};

static const cli_command terrain_cli = {
    .name = "terrain",
    .synopsis = "--at X,Z [--at X,Z ...] [--preset NAME | --scene FILE] [--set K=V ...]\n"
                "                    [--json]",
    .about = "Prints the terrain at planar coordinates (X, Z) in metres (the world x and z of\n"
             "the point's foot on the ground sphere): height above sea level, surface altitude (water\n"
             "at sea level), world position, unit normal, land/sea coverage and material weights.\n"
             "terrain.enabled is implied; terrain.* keys (atmo params) change the terrain, and with\n"
             "terrain.heightmap_file it is the file's heights as a render draws them.\n",
    .flags = terrain_flags,
    .scene_preset = &atmo_default_preset,
};

/* One point: the report as a cJSON object, or NULL with *e filled. */
static cJSON *probe(const atmo_plan *p, const atmo_scene *s, const double at[2], atmo_err *e)
{
    const atmo_gpu_scene *g = &p->gpu;
    double R = s->atmosphere.bottom_radius_m, rho2 = (at[0] * at[0] + at[1] * at[1]) / (R * R);
    if (rho2 >= 1.0) {
        atmo_fail(e, ATMO_ERR_USAGE,
                  "--at %g,%g lies outside the planet's disc of radius %g m; use |(X, Z)| < R",
                  at[0], at[1], R);
        return NULL;
    }
    const atmo_gpu_terrain_field *f = &g->terrain.field;
    const atmo_plan_buffer *base = atmo_plan_buffer_find((atmo_plan *)p, "terrain_base");
    const float *hm = p->dem.width > 0 && base ? (const float *)base->host_data : NULL;
    float gx, gy;
    int in_file = hm && terrain_in_heightmap(f, (float)at[0], (float)at[1], &gx, &gy);
    terrain_height h = terrain_height_at(f, in_file ? hm : NULL, (float)at[0], (float)at[1]);
    double ref_cov, ref = terrain_ref_height(f, at[0], at[1], NULL, &ref_cov);
    if (in_file)
        ref = atmo_dem_sample(&p->dem, at[0] - s->dem.center_m[0], at[1] - s->dem.center_m[1],
                              ATMO_DEM_BICUBIC) +
              terrain_ref_detail(f, at[0], at[1], NULL);
    double surface = fmax((double)h.h, s->terrain.sea_level_m);
    double n[3] = {at[0] / R, sqrt(1.0 - rho2), at[1] / R}, world[3], rel[3];
    for (int k = 0; k < 3; k++)
        world[k] = n[k] * (R + surface) - (k == 1 ? R : 0.0);
    double cam[3];
    atmo_plan_camera_world(p, s, cam);
    for (int k = 0; k < 3; k++)
        rel[k] = world[k] - cam[k];
    vec3 q = v3((float)rel[0], (float)rel[1], (float)rel[2]);
    terrain_surface_point m = terrain_material(g, in_file ? hm : NULL, q, 1.0f);
    float cu, cv;
    float coverage = in_file ? ((double)h.h > s->terrain.sea_level_m ? 1.0f : 0.0f)
                             : terrain_coverage(f, (float)at[0], (float)at[1], &cu, &cv);

    cJSON *o = cJSON_CreateObject(), *normal = cJSON_CreateArray();
    cJSON *pos = cJSON_CreateArray(), *mat = cJSON_CreateObject();
    if (!o || !normal || !pos || !mat) {
        cJSON_Delete(o), cJSON_Delete(normal), cJSON_Delete(pos), cJSON_Delete(mat);
        atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory");
        return NULL;
    }
    cJSON_AddNumberToObject(o, "x_m", at[0]);
    cJSON_AddNumberToObject(o, "z_m", at[1]);
    cJSON_AddNumberToObject(o, "height_m", h.h);
    cJSON_AddNumberToObject(o, "height_ref_m", ref);
    cJSON_AddNumberToObject(o, "surface_m", surface);
    cJSON_AddBoolToObject(o, "water", (double)h.h <= s->terrain.sea_level_m);
    for (int k = 0; k < 3; k++)
        cJSON_AddItemToArray(pos, cJSON_CreateNumber(world[k]));
    cJSON_AddItemToObject(o, "position_m", pos);
    cJSON_AddItemToArray(normal, cJSON_CreateNumber(m.normal.x));
    cJSON_AddItemToArray(normal, cJSON_CreateNumber(m.normal.y));
    cJSON_AddItemToArray(normal, cJSON_CreateNumber(m.normal.z));
    cJSON_AddItemToObject(o, "normal", normal);
    cJSON_AddNumberToObject(o, "coverage", coverage);
    for (int k = 0; k < TERRAIN_MATERIALS; k++)
        cJSON_AddNumberToObject(mat, material_names[k], m.weight[k]);
    cJSON_AddItemToObject(o, "materials", mat);
    return o;
}

static void print_text(const cJSON *o)
{
    const cJSON *n = cJSON_GetObjectItem(o, "normal"), *pos = cJSON_GetObjectItem(o, "position_m");
    printf("at (%g, %g) m: height %.3f m above sea level (double reference %.3f m), surface "
           "%.3f m%s\n",
           cJSON_GetObjectItem(o, "x_m")->valuedouble, cJSON_GetObjectItem(o, "z_m")->valuedouble,
           cJSON_GetObjectItem(o, "height_m")->valuedouble,
           cJSON_GetObjectItem(o, "height_ref_m")->valuedouble,
           cJSON_GetObjectItem(o, "surface_m")->valuedouble,
           cJSON_IsTrue(cJSON_GetObjectItem(o, "water")) ? " (water)" : "");
    printf("  position (%.3f, %.3f, %.3f) m, normal (%.6f, %.6f, %.6f), coverage %.4f\n",
           cJSON_GetArrayItem(pos, 0)->valuedouble, cJSON_GetArrayItem(pos, 1)->valuedouble,
           cJSON_GetArrayItem(pos, 2)->valuedouble, cJSON_GetArrayItem(n, 0)->valuedouble,
           cJSON_GetArrayItem(n, 1)->valuedouble, cJSON_GetArrayItem(n, 2)->valuedouble,
           cJSON_GetObjectItem(o, "coverage")->valuedouble);
    printf("  materials:");
    const cJSON *mat = cJSON_GetObjectItem(o, "materials");
    for (const cJSON *c = mat->child; c; c = c->next)
        printf(" %s %.3f", c->string, c->valuedouble);
    printf("\n");
}

/* The scene with terrain, planned for the host probe: no device or method needed. */
static int terrain_plan(const terrain_args *a, atmo_scene *scene, atmo_plan *plan, atmo_err *e)
{
    int rc = scene_options_scene(&a->so, NULL, scene, e);
    if (rc == ATMO_OK && a->n_at == 0)
        rc = atmo_fail(e, ATMO_ERR_USAGE, "atmo terrain needs --at X,Z (atmo terrain --help)");
    if (rc)
        return rc;
    scene->terrain.enabled = 1;
    /* the probe needs no device or method: plan with a method terrain works with */
    if (scene->atmosphere.method == ATMO_METHOD_REFERENCE)
        scene->atmosphere.method = ATMO_METHOD_SINGLE;
    if (!scene->dem.file[0]) /* the fBm directly; a file needs its heightmap */
        scene->terrain.heightmap_size = 0;
    scene->terrain.heightmap_format = ATMO_TERRAIN_FORMAT_FLOAT;
    return atmo_plan_make(scene, plan, e);
}

int cmd_terrain(int argc, char **argv)
{
    atmo_scene scene;
    atmo_err e = {{0}};
    atmo_plan plan;
    static terrain_args a;
    int rc;
    memset(&a, 0, sizeof a);
    scene_options_init(&a.so);
    if (!cli_parse(&terrain_cli, &a, argc, argv, NULL, NULL, &rc))
        return rc;
    if ((rc = terrain_plan(&a, &scene, &plan, &e)))
        return cli_fail(&terrain_cli, rc, &e);
    for (int i = 0; i < a.n_at && rc == ATMO_OK; i++) {
        cJSON *o = probe(&plan, &scene, a.at[i], &e);
        if (!o) {
            rc = ATMO_ERR_USAGE;
            break;
        }
        if (a.json) {
            char *text = cJSON_PrintUnformatted(o);
            if (text)
                printf("%s\n", text);
            free(text);
        } else {
            print_text(o);
        }
        cJSON_Delete(o);
    }
    atmo_plan_free(&plan);
    return rc ? cli_fail(&terrain_cli, rc, &e) : ATMO_OK;
}
