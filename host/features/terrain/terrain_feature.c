/* terrain_feature.c — the procedural (or DEM) terrain (kernels/terrain/): its height field and
 * heightmap pass, its sun-height map, its surface and light in the preview, its shadows in the
 * air (light shafts), its stage of the preview's camera rays and its surface in the path
 * tracer and the guides; planned by plan_terrain.c and plan_terrain_sun.c. */
#include "atmo/features.h"
#include "atmo/plan_terrain.h"

/* a heightmap file is drawn as terrain, so it implies terrain.enabled */
static int has_terrain(const atmo_scene *s) { return s->terrain.enabled || s->dem.file[0]; }
static int path_mode(const atmo_scene *s) { return s->path.mode == ATMO_RENDER_PATH; }
static int terrain_surface(const atmo_scene *s) { return has_terrain(s) && !path_mode(s); }
/* the terrain as an occluder of the sun at points of the media (light shafts) */
static int terrain_air_shadows(const atmo_scene *s)
{
    return has_terrain(s) && s->terrain.air_shadows;
}
/* the sun-height map of the view rays' sun queries; the path tracer marches */
static int terrain_sun_map(const atmo_scene *s)
{
    return terrain_air_shadows(s) && !path_mode(s) &&
           s->terrain.sun_visibility == ATMO_TERRAIN_SUN_BY_MAP;
}
static int terrain_stage(const atmo_scene *s)
{
    return has_terrain(s) && (s->atmosphere.method == ATMO_METHOD_FAST ||
                              s->atmosphere.method == ATMO_METHOD_LUT);
}
/* the methods whose sky_trace integrates the terrain itself get the stage for the water's
 * mirror ray alone */
static int terrain_water_stage(const atmo_scene *s)
{
    return has_terrain(s) && (s->atmosphere.method == ATMO_METHOD_SINGLE ||
                              s->atmosphere.method == ATMO_METHOD_MARCH);
}

/* The height field, the tracer and shadows, the surface's light, and the heightmap pass, which
 * reads only the field (the camera's placement stays out of the key). */
static const char *const terrain_fragments[] = {"kernels/terrain/noise.h",
                                                "kernels/terrain/terrain_detail.h",
                                                "kernels/terrain/terrain_half.h",
                                                "kernels/terrain/terrain.h",
                                                "kernels/terrain/terrain_sun.h",
                                                "kernels/terrain/terrain_shafts.h",
                                                "kernels/terrain/water.h",
                                                "kernels/terrain/terrain_material.h",
                                                "kernels/terrain/heightmap.cl", NULL};
static const atmo_gpu_field terrain_params[] = {ATMO_GPU_FIELD(terrain.field), {0, 0}};
static const char *const terrain_sources[] = {
    "kernels/common/compat.h",   "include/atmo/gpu_enums.h",   "include/atmo/gpu_terrain.h",
    "include/atmo/gpu_types.h",  "kernels/terrain/noise.h",    "kernels/terrain/heightmap.cl",
    NULL};
/* the bake of the sun-height map (the lookup, terrain_sun.h, is the terrain's own: its
 * shadow queries ask it and march where it has no answer); it follows the view */
static const char *const terrain_sun_map_fragments[] = {"kernels/terrain/terrain_sun_map.h",
                                                        "kernels/terrain/terrain_sun_map.cl",
                                                        NULL};
/* its key: the height field and the heightmap's (through needs), the camera's placement and
 * vertical, the sun, the sea, the map's own fields, the planet's radius */
static const atmo_gpu_field terrain_sun_map_params[] = {
    ATMO_GPU_FIELD(terrain.field),          ATMO_GPU_FIELD(terrain.camera),
    ATMO_GPU_FIELD(terrain.sea_level_m),    ATMO_GPU_FIELD(terrain.sun_map_size),
    ATMO_GPU_FIELD(terrain.sun_map_extent_m), ATMO_GPU_FIELD(terrain.sun_map_lead),
    ATMO_GPU_FIELD(terrain.sun_map_axis),   ATMO_GPU_FIELD(camera.local_up),
    ATMO_GPU_FIELD(sun_direction),          ATMO_GPU_FIELD(atmosphere.bottom_radius),
    {0, 0}};
static const char *const terrain_sun_map_sources[] = {
    "kernels/common/compat.h",           "include/atmo/gpu_enums.h",
    "include/atmo/gpu_terrain.h",        "include/atmo/gpu_types.h",
    "kernels/common/geometry.h",         "kernels/terrain/noise.h",
    "kernels/terrain/terrain_detail.h",  "kernels/terrain/terrain_half.h",
    "kernels/terrain/terrain.h",         "kernels/terrain/terrain_sun.h",
    "kernels/terrain/terrain_sun_map.h", "kernels/terrain/terrain_sun_map.cl",
    NULL};
static const char *const needs_heightmap[] = {"terrain", NULL};
/* the terrain's light, which takes the method's sky irradiance from the media's composition;
 * its shadows in the media, after the objects' (their order is that of the samples its
 * shortcuts remember), unless terrain.air_shadows is off; and its surface, which the path
 * tracer traces itself */
static const char *const terrain_light_fragments[] = {"kernels/terrain/terrain_shade.h", NULL};
static const atmo_slots terrain_shadow_slots = {.ray_occluder = "terrain_shafts_sun_visibility",
                                                .ray_state = "terrain_shafts",
                                                .ray_begin = "terrain_shafts_begin"};
static const atmo_slots terrain_surface_slots = {.surface_hit = "terrain_surface_hit",
                                                 .surface_radiance = "terrain_radiance"};
/* the terrain's stage of the preview's camera rays: methods fast and lut read whole rays from
 * tables that know no terrain, so it finds the hit first and asks the method's integrator for
 * the air in front of it; every method gets the water's mirror ray from it */
static const char *const terrain_stage_fragments[] = {"kernels/terrain/terrain_stage.h", NULL};
static const atmo_slots terrain_stage_slots = {.camera_stage = "terrain_stage_trace_tables"};
static const atmo_slots terrain_water_stage_slots = {.camera_stage = "terrain_stage_trace"};
/* its surface in the path tracer and the guides, in place of the ground sphere */
static const char *const terrain_path_fragments[] = {"kernels/terrain/terrain_path.h", NULL};
static const atmo_slots terrain_path_slots = {.path_hit = "terrain_path_hit",
                                              .path_occluded = "terrain_path_occluded",
                                              .path_replaces_ground = 1,
                                              .cone_start = "terrain_path_cone_start"};

static const atmo_feature rows[] = {
    /* an opaque surface and a visibility source */
    {.name = "terrain", .order = ATMO_BAND_MEDIA + 30, .wanted = has_terrain,
     .fragments = terrain_fragments, .defines = "-DATMO_TERRAIN", .params = terrain_params,
     .sources = terrain_sources, .plan = atmo_plan_terrain},
    /* the sun-height map over the terrain, baked per camera and sun: it follows the view and
     * is cached under a key that covers them */
    {.name = "terrain_sun_map", .order = ATMO_BAND_MEDIA + 31, .wanted = terrain_sun_map,
     .fragments = terrain_sun_map_fragments, .defines = "-DATMO_TERRAIN_SUN_MAP",
     .params = terrain_sun_map_params, .sources = terrain_sun_map_sources,
     .needs = needs_heightmap, .plan = atmo_plan_terrain_sun_map},
    {.name = "terrain_light", .order = ATMO_BAND_LIGHT + 20, .wanted = has_terrain,
     .fragments = terrain_light_fragments},
    {.name = "terrain_shadow", .order = ATMO_BAND_LIGHT + 21, .wanted = terrain_air_shadows,
     .slots = &terrain_shadow_slots},
    {.name = "terrain_surface", .order = ATMO_BAND_LIGHT + 22, .wanted = terrain_surface,
     .slots = &terrain_surface_slots},
    /* after the objects' stage */
    {.name = "terrain_stage", .order = ATMO_BAND_CAMERA + 20, .wanted = terrain_stage,
     .fragments = terrain_stage_fragments, .defines = "-DATMO_TERRAIN_STAGE",
     .slots = &terrain_stage_slots},
    {.name = "terrain_water_stage", .order = ATMO_BAND_CAMERA + 21,
     .wanted = terrain_water_stage, .fragments = terrain_stage_fragments,
     .defines = "-DATMO_TERRAIN_STAGE", .slots = &terrain_water_stage_slots},
    {.name = "terrain_path", .order = ATMO_BAND_PATH_SURFACES + 10, .wanted = has_terrain,
     .fragments = terrain_path_fragments, .slots = &terrain_path_slots},
};
ATMO_FEATURE_SET(terrain, rows);
