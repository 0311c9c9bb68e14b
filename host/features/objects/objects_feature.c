/* objects_feature.c — the scene's spheres and boxes (kernels/render/objects*.h): sun occluders
 * and surfaces of the preview, a stage of its camera rays, surfaces of the path tracer and the
 * guides; planned by plan_objects.c. */
#include "atmo/features.h"
#include "atmo/plan_objects.h"

static int has_objects(const atmo_scene *s) { return s->objects.count > 0; }
static int objects_preview(const atmo_scene *s)
{
    return has_objects(s) && s->path.mode != ATMO_RENDER_PATH;
}

static const char *const objects_fragments[] = {"kernels/render/objects.h", NULL};
/* the preview's objects: sun occluders (of the air and of the terrain's surface) and surfaces
 * lit by the sun and the sky */
static const char *const objects_preview_fragments[] = {"kernels/render/objects_light.h", NULL};
static const atmo_slots objects_preview_slots = {.sun_occluder = "objects_sun_visibility",
                                                 .surface_occluder = 1,
                                                 .surface_hit = "objects_surface_hit",
                                                 .surface_radiance = "objects_light_radiance"};
/* the preview's camera rays that see an object: the air in front and the object's light */
static const char *const objects_stage_fragments[] = {"kernels/render/objects_stage.h", NULL};
static const atmo_slots objects_stage_slots = {.camera_stage = "objects_stage_trace"};
/* their surfaces in the path tracer and the guides */
static const char *const objects_path_fragments[] = {"kernels/render/objects_path.h", NULL};
static const atmo_slots objects_path_slots = {.path_hit = "objects_path_hit",
                                              .path_occluded = "objects_path_occluded"};

static const atmo_feature rows[] = {
    /* after the terrain, whose height field places the objects with on_terrain */
    {.name = "objects", .order = ATMO_BAND_MEDIA + 40, .wanted = has_objects,
     .fragments = objects_fragments, .defines = "-DATMO_OBJECTS", .plan = atmo_plan_objects},
    /* their sun occluders before the terrain's */
    {.name = "objects_preview", .order = ATMO_BAND_LIGHT + 10, .wanted = objects_preview,
     .fragments = objects_preview_fragments, .defines = "-DATMO_OBJECTS_PREVIEW",
     .slots = &objects_preview_slots},
    /* their stage before the terrain's */
    {.name = "objects_stage", .order = ATMO_BAND_CAMERA + 10, .wanted = objects_preview,
     .fragments = objects_stage_fragments, .slots = &objects_stage_slots},
    {.name = "objects_path", .order = ATMO_BAND_PATH_SURFACES + 20, .wanted = has_objects,
     .fragments = objects_path_fragments, .slots = &objects_path_slots},
};
ATMO_FEATURE_SET(objects, rows);
