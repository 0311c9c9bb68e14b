/* path_feature.c — the path tracer (kernels/render/path*.h, its stages): its kernel
 * path_render over whichever method was assembled, the sea's BSDF, the air as its volume
 * medium (path.air = medium), and its camera pattern in the denoiser's guides; planned by
 * plan_path.c. */
#include "atmo/features.h"
#include "atmo/gpu_enums.h"
#include "atmo/plan_path.h"

static int path_mode(const atmo_scene *s) { return s->path.mode == ATMO_RENDER_PATH; }
/* path.air = medium: the path tracer scatters in the air itself */
static int path_air(const atmo_scene *s)
{
    return path_mode(s) && s->path.air == ATMO_PATH_AIR_MEDIUM;
}

/* the air as a volume medium of the path tracer's walk (render/volume_stage.h): no fragment of
 * its own, the walk's composition takes it in */
static const atmo_slots path_air_slots = {.volume_air = 1};
/* the sea's BSDF, over the water's optics (a path vertex is the sea where the terrain's hit
 * says so, render/path_hit.h's SURFACES_WATER) */
static const char *const path_water_fragments[] = {"kernels/terrain/water.h",
                                                   "kernels/render/bsdf_water.h", NULL};
static const char *const path_fragments[] = {
    "kernels/render/path_camera.h",  "kernels/render/bsdf.h",  "kernels/render/light_sun.h",
    "kernels/render/light_sky.h",    "kernels/render/volume_stage.h", "kernels/render/path.h",
    "kernels/render/path.cl",        NULL};
/* the path tracer's pattern, pixel filter and media in the guides */
static const atmo_slots path_slots = {.pixel_ray = "path_camera_pixel_ray",
                                      .media_shown = "path_media_shown",
                                      .guides_grid = ATMO_GUIDES_PATH_GRID};

static const atmo_feature rows[] = {
    {.name = "path_air", .order = ATMO_BAND_MEDIA + 60, .wanted = path_air,
     .plan = atmo_plan_path_air, .slots = &path_air_slots},
    {.name = "path_water", .order = ATMO_BAND_PATH + 10, .wanted = path_mode,
     .fragments = path_water_fragments},
    {.name = "path", .order = ATMO_BAND_PATH + 20, .wanted = path_mode,
     .fragments = path_fragments, .defines = "-DATMO_PATH", .plan = atmo_plan_path,
     .slots = &path_slots},
};
ATMO_FEATURE_SET(path, rows);
