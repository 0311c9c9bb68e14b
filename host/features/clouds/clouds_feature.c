/* clouds_feature.c — the fBm cloud layer (kernels/clouds/): a medium of the methods with its
 * own stepping and light march, the reference's and the path tracer's volume medium over its
 * majorant grid, its sun shadow map, and its part of the denoiser's guides; planned by
 * plan_clouds.c. */
#include "atmo/features.h"
#include "atmo/plan_clouds.h"

static int has_clouds(const atmo_scene *s) { return s->clouds.enabled; }
/* path.clouds = volume: the path tracer scatters in the layer, the methods see only the air */
static int cloud_volume(const atmo_scene *s) { return atmo_plan_clouds_volume(s); }
/* the layer as a medium of the methods (media.h, visibility.h, the marcher) */
static int cloud_layer(const atmo_scene *s) { return s->clouds.enabled && !cloud_volume(s); }
static int is_reference(const atmo_scene *s)
{
    return s->atmosphere.method == ATMO_METHOD_REFERENCE;
}
static int cloud_grid(const atmo_scene *s)
{
    return (cloud_layer(s) && is_reference(s)) || cloud_volume(s);
}
/* the layer as a medium of the reference's walk */
static int cloud_tracked(const atmo_scene *s) { return cloud_layer(s) && is_reference(s); }
/* the sun shadow map of the methods' light march; the reference ratio-tracks the sun instead */
static int cloud_shadow_map(const atmo_scene *s)
{
    return cloud_layer(s) && s->clouds.shadow_map && !is_reference(s);
}

/* the layer's density, optics and light march */
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
/* the layer's own stepping of the methods, after the visibility it asks */
static const char *const clouds_march_fragments[] = {"kernels/clouds/cloud_march.h", NULL};

static const atmo_feature rows[] = {
    {.name = "clouds", .order = ATMO_BAND_MEDIA + 20, .wanted = has_clouds,
     .fragments = clouds_fragments, .defines = "-DATMO_CLOUDS", .plan = atmo_plan_clouds,
     .slots = &clouds_guides_slots},
    /* the majorant grid of the reference's walk and the volume stage's; it follows the view
     * (never cached) */
    {.name = "clouds_majorant", .order = ATMO_BAND_MEDIA + 21, .wanted = cloud_grid,
     .fragments = clouds_majorant_fragments, .plan = atmo_plan_clouds_majorant},
    /* the path tracer's volume medium (render/volume_stage.h): no method sees it */
    {.name = "clouds_path_volume", .order = ATMO_BAND_MEDIA + 22, .wanted = cloud_volume,
     .slots = &clouds_path_volume_slots},
    {.name = "clouds_tracked", .order = ATMO_BAND_MEDIA + 23, .wanted = cloud_tracked,
     .slots = &clouds_tracked_slots},
    /* the sun shadow map for the visibility source and the marcher (over the majorant grid's
     * frame); it follows the view (never cached) */
    {.name = "clouds_shadow_map", .order = ATMO_BAND_MEDIA + 24, .wanted = cloud_shadow_map,
     .fragments = clouds_shadow_map_fragments, .defines = "-DATMO_CLOUDS_SHADOW_MAP",
     .plan = atmo_plan_clouds_shadow_map},
    /* a medium of the methods (with its own stepping, clouds_march) */
    {.name = "clouds_medium", .order = ATMO_BAND_MEDIA + 25, .wanted = cloud_layer,
     .fragments = clouds_medium_fragments, .slots = &clouds_slots},
    {.name = "clouds_march", .order = ATMO_BAND_STEPPING + 20, .wanted = cloud_layer,
     .fragments = clouds_march_fragments},
};
ATMO_FEATURE_SET(clouds, rows);
