/* cloud_shell_feature.c — the cloud shell and the observer (kernels/cloud_shell/): a medium of
 * the methods with its own stepping, a sun occluder (the observer's body) and a surface (the
 * observer's), planned by atmo_plan_cloud (plan_cloud.c). */
#include "atmo/features.h"
#include "atmo/plan_cloud.h"

static int cloud_shell(const atmo_scene *s) { return s->cloud.enabled || s->observer.enabled; }

/* a medium (with its own stepping) and a visibility source, before the media's composition */
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
static const char *const cloud_march_fragments[] = {"kernels/cloud_shell/cloud_shell_march.h",
                                                    NULL};

static const atmo_feature rows[] = {
    {.name = "cloud", .order = ATMO_BAND_MEDIA + 10, .wanted = cloud_shell,
     .fragments = cloud_fragments, .defines = "-DATMO_CLOUD", .plan = atmo_plan_cloud,
     .slots = &cloud_slots},
    {.name = "cloud_march", .order = ATMO_BAND_STEPPING + 10, .wanted = cloud_shell,
     .fragments = cloud_march_fragments},
};
ATMO_FEATURE_SET(cloud_shell, rows);
