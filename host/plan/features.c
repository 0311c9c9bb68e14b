/* features.c — the feature registry (atmo/features.h): one row per feature, in the order their
 * fragments are assembled. */
#include <stdio.h>
#include <string.h>
#include "atmo/features.h"
#include "atmo/gpu_enums.h"
#include "atmo/plan_cloud.h"
#include "atmo/plan_clouds.h"
#include "atmo/plan_fast.h"
#include "atmo/plan_lut.h"
#include "atmo/plan_march.h"
#include "atmo/plan_path.h"
#include "atmo/plan_reference.h"
#include "atmo/plan_terrain.h"

static int always(const atmo_scene *s) { return s != NULL; }
static int ms_methods(const atmo_scene *s)
{
    return s->atmosphere.method == ATMO_METHOD_MARCH || s->atmosphere.method == ATMO_METHOD_FAST;
}
static int cloud_shell(const atmo_scene *s) { return s->cloud.enabled || s->observer.enabled; }
/* path.clouds = volume: the path tracer scatters in the layer, the methods see only the air */
static int cloud_volume(const atmo_scene *s) { return atmo_plan_clouds_volume(s); }
static int has_clouds(const atmo_scene *s) { return s->clouds.enabled; }
/* the layer as a medium of the methods (media.h, visibility.h, the marcher) */
static int cloud_layer(const atmo_scene *s) { return s->clouds.enabled && !cloud_volume(s); }
static int cloud_grid(const atmo_scene *s)
{
    return (cloud_layer(s) && s->atmosphere.method == ATMO_METHOD_REFERENCE) || cloud_volume(s);
}
/* the layer as a medium of the reference's walk */
static int cloud_tracked(const atmo_scene *s)
{
    return cloud_layer(s) && s->atmosphere.method == ATMO_METHOD_REFERENCE;
}
/* the sun shadow map of the methods' light march; the reference ratio-tracks the sun instead */
static int cloud_shadow_map(const atmo_scene *s)
{
    return cloud_layer(s) && s->clouds.shadow_map && s->atmosphere.method != ATMO_METHOD_REFERENCE;
}
static int has_objects(const atmo_scene *s) { return s->objects.count > 0; }
static int path_mode(const atmo_scene *s) { return s->path.mode == ATMO_RENDER_PATH; }
/* path.air = medium: the path tracer scatters in the air itself */
static int path_air(const atmo_scene *s)
{
    return path_mode(s) && s->path.air == ATMO_PATH_AIR_MEDIUM;
}
static int objects_preview(const atmo_scene *s) { return has_objects(s) && !path_mode(s); }
/* a heightmap file is drawn as terrain, so it implies terrain.enabled */
static int has_terrain(const atmo_scene *s) { return s->terrain.enabled || s->dem.file[0]; }
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
static int is_single(const atmo_scene *s) { return s->atmosphere.method == ATMO_METHOD_SINGLE; }
static int is_march(const atmo_scene *s) { return s->atmosphere.method == ATMO_METHOD_MARCH; }
static int is_fast(const atmo_scene *s) { return s->atmosphere.method == ATMO_METHOD_FAST; }
static int is_lut(const atmo_scene *s) { return s->atmosphere.method == ATMO_METHOD_LUT; }
static int is_reference(const atmo_scene *s)
{
    return s->atmosphere.method == ATMO_METHOD_REFERENCE;
}

/* The transmittance LUT, which every method gets first. */
static int plan_atmosphere(const atmo_scene *s, atmo_plan *p, atmo_err *e)
{
    (void)s;
    int w = p->gpu.transmittance_width, h = p->gpu.transmittance_height;
    int rc = atmo_plan_add_buffer(p, "transmittance_lut", "float4",
                                  sizeof(float4) * (size_t)w * (size_t)h, 0, NULL, e);
    return rc ? rc : atmo_plan_add_pass(p, "transmittance_lut", w, h, 1, 0, e);
}

/* The headers every kernel is compiled with: the shared GPU structs (each feature's in its own
 * header, before the scene struct that holds them), math, the deterministic quadrature's walk
 * (the atmosphere's transmittance integral walks it), the atmosphere, the camera, the
 * camera-relative ray that the media and the integrator take, the hit record that the
 * surfaces' slots fill (render/path_hit.h), the media's contract and the air, the planet as
 * the first occluder of the sun, and the free-flight and ratio-tracking steps of the Monte
 * Carlo walks. */
static const char *const atmosphere_fragments[] = {
    "kernels/common/compat.h",        "include/atmo/gpu_enums.h",
    "include/atmo/gpu_atmosphere.h",  "include/atmo/gpu_ms_lut.h",
    "include/atmo/gpu_sky_view.h",    "include/atmo/gpu_lut.h",
    "include/atmo/gpu_reference.h",   "include/atmo/gpu_cloud.h",
    "include/atmo/gpu_clouds.h",      "include/atmo/gpu_path.h",
    "include/atmo/gpu_terrain.h",
    "include/atmo/gpu_types.h",       "kernels/common/rng.h",
    "kernels/common/geometry.h",      "kernels/common/frame.h",
    "kernels/common/phase.h",         "kernels/media/quadrature_walk.h",
    "kernels/atmosphere/atmosphere.h", "kernels/common/camera.h",
    "kernels/atmosphere/sky_method.h", "kernels/media/ray.h",
    "kernels/render/path_hit.h",      "kernels/media/tracking.h",
    "kernels/media/majorant_walk.h",
    "kernels/media/media.h",          "kernels/media/planet.h",
    "kernels/atmosphere/transmittance.cl", NULL};
static const atmo_slots atmosphere_slots = {.sun_occluder = "planet_sun_visibility",
                                            .surface_occluder = 1};
static const atmo_gpu_field atmosphere_params[] = {ATMO_GPU_FIELD(atmosphere),
                                                   ATMO_GPU_FIELD(transmittance_width),
                                                   ATMO_GPU_FIELD(transmittance_height),
                                                   {0, 0}};
static const char *const atmosphere_sources[] = {
    "kernels/common/compat.h",       "include/atmo/gpu_enums.h",
    "include/atmo/gpu_atmosphere.h", "include/atmo/gpu_types.h",
    "kernels/common/geometry.h",     "kernels/media/quadrature_walk.h",
    "kernels/atmosphere/atmosphere.h", "kernels/atmosphere/transmittance.cl", NULL};

/* The sun's visibility over the composed occluders and media; the one medium integrator over
 * the composed media, visibility and intervals. */
static const char *const visibility_fragments[] = {"kernels/media/visibility.h",
                                                   "kernels/media/medium_air.h",
                                                   "kernels/media/media_walk.h", NULL};
static const char *const medium_fragments[] = {"kernels/media/medium.h", NULL};
#define MEDIUM_SOURCES                                                                             \
    "kernels/media/ray.h", "kernels/media/tracking.h", "kernels/media/media.h",                    \
        "kernels/media/quadrature_walk.h", "kernels/media/visibility.h",                           \
        "kernels/cloud_shell/observer.h", "kernels/media/medium.h"

/* Psi_ms: its lookups (the source of march and fast) before the media's composition, its
 * passes (which march with the integrator) after the integrator. */
static const char *const ms_lut_fragments[] = {"kernels/atmosphere/ms_lut_source.h", NULL};
static const char *const ms_lut_pass_fragments[] = {"kernels/atmosphere/ms_lut.h",
                                                    "kernels/atmosphere/ms_lut.cl", NULL};
static const atmo_slots ms_lut_slots = {.ms_source = "ms_lut_ms_source",
                                        .ms_ground_irradiance = "ms_lut_ms_ground_irradiance"};
static const atmo_gpu_field ms_lut_params[] = {ATMO_GPU_FIELD(atmosphere), ATMO_GPU_FIELD(ms),
                                               {0, 0}};
static const char *const ms_lut_sources[] = {
    "kernels/common/compat.h",        "include/atmo/gpu_enums.h",
    "include/atmo/gpu_atmosphere.h",  "include/atmo/gpu_ms_lut.h",
    "include/atmo/gpu_types.h",       "kernels/common/geometry.h",
    "kernels/common/phase.h",         "kernels/atmosphere/atmosphere.h",
    "kernels/atmosphere/sky_method.h", MEDIUM_SOURCES,
    "kernels/atmosphere/ms_lut_source.h", "kernels/atmosphere/ms_lut.h",
    "kernels/atmosphere/ms_lut.cl",   NULL};

/* method lut: its tables' lookups (and the integrator's source) before the media's composition,
 * the method and its passes after the integrator */
static const char *const lut_fragments[] = {"kernels/atmosphere/lut_scattering.h",
                                            "kernels/atmosphere/lut_source.h", NULL};
static const char *const lut_pass_fragments[] = {"kernels/atmosphere/method_lut.h",
                                                 "kernels/atmosphere/lut_precompute.cl", NULL};
static const atmo_slots lut_slots = {.ms_source = "lut_ms_source",
                                     .ms_ground_irradiance = "lut_ms_ground_irradiance"};
static const atmo_gpu_field lut_params[] = {ATMO_GPU_FIELD(atmosphere), ATMO_GPU_FIELD(lut),
                                            {0, 0}};
static const char *const lut_sources[] = {
    "kernels/common/compat.h",           "include/atmo/gpu_enums.h",
    "include/atmo/gpu_atmosphere.h",     "include/atmo/gpu_lut.h",
    "include/atmo/gpu_types.h",          "kernels/common/rng.h",
    "kernels/common/geometry.h",         "kernels/common/phase.h",
    "kernels/atmosphere/atmosphere.h",   "kernels/atmosphere/sky_method.h",
    MEDIUM_SOURCES,                       "kernels/atmosphere/lut_scattering.h",
    "kernels/atmosphere/lut_source.h",
    "kernels/atmosphere/method_lut.h",   "kernels/atmosphere/lut_precompute.cl",
    NULL};

static const char *const needs_transmittance[] = {"atmosphere", NULL};
static const char *const cloud_fragments[] = {"kernels/cloud_shell/observer.h",
                                              "kernels/media/phase_table.h",
                                              "kernels/cloud_shell/cloud_shell.h",
                                              "kernels/cloud_shell/cloud_shell_walk.h",
                                              "kernels/cloud_shell/observer_surface.h", NULL};
static const atmo_slots cloud_slots = {.component = "CLOUD",
                                       .media_add = "cloud_shell_media_add",
                                       .media_phase = "cloud_shell_media_phase",
                                       .media_sun = "cloud_shell_media_sun",
                                       .media_intervals = "cloud_shell_intervals",
                                       .media_interval = "cloud_shell_interval",
                                       .sun_occluder = "observer_sun_visibility",
                                       .surface_occluder = 1,
                                       .surface_hit = "observer_surface_hit",
                                       .surface_radiance = "observer_surface_radiance",
                                       .majorant_state = "cloud_shell_majorant",
                                       .majorant_begin = "cloud_shell_majorant_begin",
                                       .majorant_segment = "cloud_shell_majorant_segment",
                                       .sun_exact = 1,
                                       .media_direction = "cloud_shell_media_direction",
                                       .roulette_gain = "cloud_shell_roulette_gain",
                                       .guide_depth = "cloud_shell_guide_depth"};
/* the shell's own stepping, after the visibility it asks */
static const char *const cloud_march_fragments[] = {"kernels/cloud_shell/cloud_shell_march.h", NULL};
static const char *const clouds_fragments[] = {"kernels/clouds/cloud_noise.h",
                                               "kernels/media/phase_table.h",
                                               "kernels/clouds/cloud_layer.h", NULL};
/* the layer in the denoiser's guides, in every mode */
static const atmo_slots clouds_guides_slots = {.guide_block = "clouds_guide_block"};
/* the grid and the layer's majorant over it, the layer in the one walk (cloud_track.h: the
 * slots below) */
static const char *const clouds_majorant_fragments[] = {"kernels/clouds/cloud_majorant.h",
                                                        "kernels/clouds/cloud_majorant.cl",
                                                        "kernels/clouds/cloud_track.h", NULL};
static const char *const clouds_shadow_map_fragments[] = {
    "kernels/clouds/cloud_majorant.h", "kernels/clouds/cloud_shadow_map.h",
    "kernels/clouds/cloud_shadow_map.cl", NULL};
/* the layer as a medium of the methods, over its shadow map when there is one */
static const char *const clouds_medium_fragments[] = {"kernels/clouds/cloud_layer_medium.h", NULL};
static const atmo_slots clouds_slots = {.component = "CLOUDS",
                                        .media_add = "clouds_media_add",
                                        .media_phase = "clouds_media_phase",
                                        .media_sun = "clouds_media_sun",
                                        .media_sun_surface = "clouds_media_sun_surface",
                                        .media_intervals = "clouds_media_intervals",
                                        .media_interval = "clouds_media_interval"};
/* the layer as the path tracer's volume medium in the one walk, over its majorant grid: the
 * volume stage's free flights and shadow rays, the shadows it casts on the air's samples of
 * every method */
static const atmo_slots clouds_path_volume_slots = {.volume_at = "clouds_volume_at",
                                                    .media_phase = "clouds_volume_phase",
                                                    .majorant_state = "clouds_track",
                                                    .majorant_begin = "clouds_track_begin",
                                                    .majorant_segment = "clouds_track_segment",
                                                    .media_direction = "clouds_media_direction",
                                                    .roulette_gain = "clouds_roulette_gain"};
/* the layer as a medium of the reference's walk: its majorant, its scattering's sampling */
static const atmo_slots clouds_tracked_slots = {.majorant_state = "clouds_track",
                                                .majorant_begin = "clouds_track_begin",
                                                .majorant_segment = "clouds_track_segment",
                                                .walk_component = "CLOUDS",
                                                .media_direction = "clouds_media_direction",
                                                .roulette_gain = "clouds_roulette_gain"};
static const char *const clouds_march_fragments[] = {"kernels/clouds/cloud_march.h", NULL};
/* The terrain: the height field, the tracer and shadows, the surface's light, and the
 * heightmap pass, which reads only the field (the camera's placement stays out of the key). */
static const char *const terrain_fragments[] = {"kernels/terrain/noise.h",
                                                "kernels/terrain/terrain_detail.h",
                                                "kernels/terrain/terrain_half.h",
                                                "kernels/terrain/terrain.h",
                                                "kernels/terrain/terrain_sun.h",
                                                "kernels/terrain/terrain_shafts.h",
                                                "kernels/terrain/water.h",
                                                "kernels/terrain/terrain_material.h",
                                                "kernels/terrain/heightmap.cl", NULL};
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
/* the terrain's stage of the preview's camera rays: methods fast and lut read whole rays from
 * tables that know no terrain, so it finds the hit first and asks the method's integrator for
 * the air in front of it; every method gets the water's mirror ray from it */
static const char *const terrain_stage_fragments[] = {"kernels/terrain/terrain_stage.h", NULL};
static const atmo_slots terrain_stage_slots = {.camera_stage = "terrain_stage_trace_tables"};
static const atmo_slots terrain_water_stage_slots = {.camera_stage = "terrain_stage_trace"};
static const char *const single_fragments[] = {"kernels/atmosphere/method_single.h", NULL};
static const char *const march_fragments[] = {"kernels/atmosphere/method_march.h", NULL};
static const char *const fast_fragments[] = {"kernels/atmosphere/method_fast.h",
                                             "kernels/atmosphere/fast_luts.cl", NULL};
static const char *const reference_fragments[] = {"kernels/atmosphere/method_reference.h", NULL};
static const char *const render_fragments[] = {"kernels/atmosphere/sky_cosines.h",
                                               "kernels/render/sky.cl", NULL};
static const char *const objects_fragments[] = {"kernels/render/objects.h", NULL};
/* the preview's objects: sun occluders (of the air and of the terrain's surface) and surfaces
 * lit by the sun and the sky */
static const char *const objects_preview_fragments[] = {"kernels/render/objects_light.h", NULL};
/* the preview's camera rays that see an object: the air in front and the object's light */
static const char *const objects_stage_fragments[] = {"kernels/render/objects_stage.h", NULL};
static const atmo_slots objects_stage_slots = {.camera_stage = "objects_stage_trace"};
static const atmo_slots objects_preview_slots = {.sun_occluder = "objects_sun_visibility",
                                                 .surface_occluder = 1,
                                                 .surface_hit = "objects_surface_hit",
                                                 .surface_radiance = "objects_light_radiance"};
/* the air as a volume medium of the path tracer's walk (render/volume_stage.h) */
static const atmo_slots path_air_slots = {.volume_air = 1};
/* the sea's BSDF, over the water's optics (a path vertex is the sea where the terrain's hit
 * says so, render/path_hit.h's SURFACES_WATER) */
static const char *const path_water_fragments[] = {"kernels/terrain/water.h",
                                                   "kernels/render/bsdf_water.h", NULL};
static const char *const path_fragments[] = {
    "kernels/render/path_camera.h",  "kernels/render/bsdf.h",  "kernels/render/light_sun.h",
    "kernels/render/light_sky.h",    "kernels/render/volume_stage.h", "kernels/render/path.h",
    "kernels/render/path.cl",        NULL};
/* the surfaces of the path tracer and the guides: the features' surfaces (composed after
 * them), the queries over the ground sphere and the composition */
static const char *const terrain_path_fragments[] = {"kernels/terrain/terrain_path.h", NULL};
static const atmo_slots terrain_path_slots = {.path_hit = "terrain_path_hit",
                                              .path_occluded = "terrain_path_occluded",
                                              .path_replaces_ground = 1};
static const char *const objects_path_fragments[] = {"kernels/render/objects_path.h", NULL};
static const atmo_slots objects_path_slots = {.path_hit = "objects_path_hit",
                                              .path_occluded = "objects_path_occluded"};
static const char *const surfaces_fragments[] = {"kernels/render/surfaces.h", NULL};
/* the path tracer's pattern, pixel filter and media in the guides */
static const atmo_slots path_slots = {.pixel_ray = "path_camera_pixel_ray",
                                      .media_shown = "path_media_shown",
                                      .guides_grid = ATMO_GUIDES_PATH_GRID};
/* the denoiser's guides, noise-free, in every mode: the first surface of fixed rays per pixel */
static const char *const guides_fragments[] = {"kernels/render/guides.cl", NULL};

const atmo_feature atmo_features[] = {
    {"atmosphere", -1, always, atmosphere_fragments, "", atmosphere_params, atmosphere_sources,
     NULL, plan_atmosphere, 0, &atmosphere_slots, 0},
    /* a medium (with its own stepping) and a visibility source, before the media's composition */
    {"cloud", -1, cloud_shell, cloud_fragments, "-DATMO_CLOUD", NULL, NULL, NULL,
     atmo_plan_cloud, 0, &cloud_slots, 0},
    /* the fBm cloud layer: its density, optics and light march */
    {"clouds", -1, has_clouds, clouds_fragments, "-DATMO_CLOUDS", NULL, NULL, NULL,
     atmo_plan_clouds, 0, &clouds_guides_slots, 0},
    /* the layer's majorant grid for the reference's walk and the volume stage's; it follows the
     * view (never cached) */
    {"clouds_majorant", -1, cloud_grid, clouds_majorant_fragments, "", NULL, NULL, NULL,
     atmo_plan_clouds_majorant, 0, NULL, 0},
    /* the layer as the path tracer's volume medium (render/volume_stage.h): no method sees it */
    {"clouds_path_volume", -1, cloud_volume, NULL, "", NULL, NULL, NULL, NULL, 0,
     &clouds_path_volume_slots, 0},
    {"clouds_tracked", -1, cloud_tracked, NULL, "", NULL, NULL, NULL, NULL, 0,
     &clouds_tracked_slots, 0},
    /* the layer's sun shadow map for the visibility source and the marcher (over the majorant
     * grid's frame); it follows the view (never cached) */
    {"clouds_shadow_map", -1, cloud_shadow_map, clouds_shadow_map_fragments,
     "-DATMO_CLOUDS_SHADOW_MAP", NULL, NULL, NULL, atmo_plan_clouds_shadow_map, 0, NULL, 0},
    /* the layer as a medium of the methods (with its own stepping, clouds_march) */
    {"clouds_medium", -1, cloud_layer, clouds_medium_fragments, "", NULL, NULL, NULL, NULL, 0,
     &clouds_slots, 0},
    /* an opaque surface and a visibility source */
    {"terrain", -1, has_terrain, terrain_fragments, "-DATMO_TERRAIN", terrain_params,
     terrain_sources, NULL, atmo_plan_terrain, 0, NULL, 0},
    /* the sun-height map over the terrain, baked per camera and sun: it follows the view and
     * is cached under a key that covers them */
    {"terrain_sun_map", -1, terrain_sun_map, terrain_sun_map_fragments,
     "-DATMO_TERRAIN_SUN_MAP", terrain_sun_map_params, terrain_sun_map_sources, needs_heightmap,
     atmo_plan_terrain_sun_map, 0, NULL, 0},
    /* the scene's spheres and boxes: sun occluders and the preview's surfaces (visibility.h),
     * the path tracer's surfaces; after the terrain, whose height field places the objects
     * with on_terrain */
    {"objects", -1, has_objects, objects_fragments, "-DATMO_OBJECTS", NULL, NULL, NULL,
     atmo_plan_objects, 0, NULL, 0},
    /* Psi_ms, shared by march and fast: the multiple-scattering source of the integrator */
    {"ms_lut", -1, ms_methods, ms_lut_fragments, "", ms_lut_params, ms_lut_sources,
     needs_transmittance, atmo_plan_ms_lut, 0, &ms_lut_slots, 0},
    /* the density of orders >= 2: the integrator's source for aerial perspective */
    {"lut", ATMO_METHOD_LUT, is_lut, lut_fragments, "", lut_params, lut_sources,
     needs_transmittance, atmo_plan_lut, 0, &lut_slots, 0},
    /* the air as the path tracer's volume medium (path.air = medium): no fragment of its own,
     * the walk's composition takes it in */
    {"path_air", -1, path_air, NULL, "", NULL, NULL, NULL, atmo_plan_path_air, 0,
     &path_air_slots, 0},
    /* the generated composition: media, then the sun's occluders (the objects' and the
     * terrain's are asked in the order of their rows below, after the observer's) */
    {"compose_media", -1, always, NULL, "", NULL, NULL, NULL, NULL, 0, NULL, ATMO_COMPOSE_MEDIA},
    {"compose_sun", -1, always, NULL, "", NULL, NULL, NULL, NULL, 0, NULL, ATMO_COMPOSE_SUN},
    {"visibility", -1, always, visibility_fragments, "", NULL, NULL, NULL, NULL, 0, NULL, 0},
    {"objects_preview", -1, objects_preview, objects_preview_fragments, "-DATMO_OBJECTS_PREVIEW",
     NULL, NULL, NULL, NULL, 0, &objects_preview_slots, 0},
    {"terrain_light", -1, has_terrain, terrain_light_fragments, "", NULL, NULL, NULL, NULL, 0,
     NULL, 0},
    {"terrain_shadow", -1, terrain_air_shadows, NULL, "", NULL, NULL, NULL, NULL, 0,
     &terrain_shadow_slots, 0},
    {"terrain_surface", -1, terrain_surface, NULL, "", NULL, NULL, NULL, NULL, 0,
     &terrain_surface_slots, 0},
    {"compose_surfaces", -1, always, NULL, "", NULL, NULL, NULL, NULL, 0, NULL,
     ATMO_COMPOSE_SURFACES},
    {"cloud_march", -1, cloud_shell, cloud_march_fragments, "", NULL, NULL, NULL, NULL, 0, NULL,
     0},
    {"clouds_march", -1, cloud_layer, clouds_march_fragments, "", NULL, NULL, NULL, NULL, 0,
     NULL, 0},
    {"compose_intervals", -1, always, NULL, "", NULL, NULL, NULL, NULL, 0, NULL,
     ATMO_COMPOSE_INTERVALS},
    /* the medium integrator of single, march, fast and lut; the media of the reference */
    {"medium", -1, always, medium_fragments, "", NULL, NULL, NULL, NULL, 0, NULL, 0},
    {"ms_lut_passes", -1, ms_methods, ms_lut_pass_fragments, "", NULL, NULL, NULL, NULL, 0, NULL,
     0},
    {"lut_passes", -1, is_lut, lut_pass_fragments, "", NULL, NULL, NULL, NULL, 0, NULL, 0},
    {"single", ATMO_METHOD_SINGLE, is_single, single_fragments, "", NULL, NULL, NULL, NULL, 0,
     NULL, 0},
    {"march", ATMO_METHOD_MARCH, is_march, march_fragments, "", NULL, NULL, NULL, NULL, 0, NULL,
     0},
    /* the sky-view LUT follows the view: never cached, so no key */
    {"fast", ATMO_METHOD_FAST, is_fast, fast_fragments, "", NULL, NULL, NULL, atmo_plan_fast, 1,
     NULL, 0},
    {"reference", ATMO_METHOD_REFERENCE, is_reference, reference_fragments, "", NULL, NULL, NULL,
     atmo_plan_reference, 0, NULL, 0},
    /* the stages of the preview's camera rays, asked in this order, and their composition */
    {"objects_stage", -1, objects_preview, objects_stage_fragments, "", NULL, NULL, NULL, NULL, 0,
     &objects_stage_slots, 0},
    {"terrain_stage", -1, terrain_stage, terrain_stage_fragments, "-DATMO_TERRAIN_STAGE", NULL,
     NULL, NULL, NULL, 0, &terrain_stage_slots, 0},
    {"terrain_water_stage", -1, terrain_water_stage, terrain_stage_fragments,
     "-DATMO_TERRAIN_STAGE", NULL, NULL, NULL, NULL, 0, &terrain_water_stage_slots, 0},
    {"compose_camera", -1, always, NULL, "", NULL, NULL, NULL, NULL, 0, NULL, ATMO_COMPOSE_CAMERA},
    /* the kernels that render with whichever method was assembled */
    {"render", -1, always, render_fragments, "", NULL, NULL, NULL, NULL, 0, NULL, 0},
    /* the surfaces of the path tracer and of the guides (every mode) */
    {"terrain_path", -1, has_terrain, terrain_path_fragments, "", NULL, NULL, NULL, NULL, 0,
     &terrain_path_slots, 0},
    {"objects_path", -1, has_objects, objects_path_fragments, "", NULL, NULL, NULL, NULL, 0,
     &objects_path_slots, 0},
    {"compose_path_surfaces", -1, always, NULL, "", NULL, NULL, NULL, NULL, 0, NULL,
     ATMO_COMPOSE_PATH_SURFACES},
    {"surfaces", -1, always, surfaces_fragments, "", NULL, NULL, NULL, NULL, 0, NULL, 0},
    /* the sea's BSDF in the path tracer (over terrain/water.h) */
    {"path_water", -1, path_mode, path_water_fragments, "", NULL, NULL, NULL, NULL, 0, NULL, 0},
    /* the path tracer's stages and its kernel path_render, over whichever method was assembled */
    {"path", -1, path_mode, path_fragments, "-DATMO_PATH", NULL, NULL, NULL, atmo_plan_path, 0,
     &path_slots, 0},
    {"compose_guides", -1, always, NULL, "", NULL, NULL, NULL, NULL, 0, NULL, ATMO_COMPOSE_GUIDES},
    {"guides", -1, always, guides_fragments, "", NULL, NULL, NULL, NULL, 0, NULL, 0},
};
const int atmo_feature_count = (int)(sizeof atmo_features / sizeof atmo_features[0]);

const atmo_feature *atmo_feature_find(const char *name)
{
    for (int i = 0; i < atmo_feature_count; i++)
        if (strcmp(atmo_features[i].name, name) == 0)
            return &atmo_features[i];
    return NULL;
}

const atmo_feature *atmo_feature_method(int method)
{
    for (int i = 0; i < atmo_feature_count; i++)
        if (atmo_features[i].method == method && method >= 0)
            return &atmo_features[i];
    return NULL;
}

const char *atmo_plan_available_methods(void)
{
    static char list[128];
    list[0] = 0;
    for (int m = 0; m <= ATMO_METHOD_REFERENCE; m++)
        if (atmo_feature_method(m))
            snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", list[0] ? ", " : "",
                     atmo_feature_method(m)->name);
    return list;
}
