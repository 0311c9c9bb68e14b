/* plan_objects.c — the scene's objects in the plan (atmo/plan_objects.h).
 *
 * Objects become atmo_gpu_object rows (include/atmo/gpu_path.h) placed camera-relative in the
 * world's axes, the subtraction of the camera's position done in double: a sphere's centre
 * c - p_cam and radius, a box's corners min - p_cam and min + size - p_cam. An object with
 * on_terrain has its anchor's y (the centre's, the min's) above the terrain: y + Y_s, Y_s the
 * world Y of the terrain's surface over world (x, z) = terrain_at_m (or the sphere's centre, the
 * box's base centre) as the renderer draws it, procedural or a DEM
 * (atmo_plan_terrain_surface_y, host/features/terrain/plan_terrain.c). The rows are a host
 * table the plan owns, copied into the buffer `objects` before the passes. */
#include <stdlib.h>
#include "atmo/plan_objects.h"
#include "atmo/plan_terrain.h"

static float4 rel4(const double v[3], const double cam[3], double w)
{
    float4 r = {(float)(v[0] - cam[0]), (float)(v[1] - cam[1]), (float)(v[2] - cam[2]), (float)w};
    return r;
}

static float4 col4(const double v[3])
{
    float4 r = {(float)v[0], (float)v[1], (float)v[2], 0.0f};
    return r;
}

int atmo_plan_objects(const atmo_scene *s, atmo_plan *p, atmo_err *e)
{
    int n = s->objects.count;
    atmo_gpu_object *rows = calloc((size_t)n, sizeof *rows);
    if (!rows)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory for %d objects", n);
    int rc = atmo_plan_own(p, rows, e);
    if (rc)
        return rc;
    const double *cam = s->camera.position_m;
    for (int i = 0; i < n; i++) {
        atmo_object o = s->objects.list[i];
        atmo_gpu_object *g = &rows[i];
        g->kind = o.type;
        if (o.on_terrain) {
            /* the scene's checks allow it only with the terrain, planned before */
            int sphere = o.type == ATMO_OBJECT_SPHERE;
            double x = o.has_terrain_at ? o.terrain_at_m[0]
                                        : sphere ? o.center_m[0] : o.min_m[0] + 0.5 * o.size_m[0];
            double z = o.has_terrain_at ? o.terrain_at_m[1]
                                        : sphere ? o.center_m[2] : o.min_m[2] + 0.5 * o.size_m[2];
            double y = atmo_plan_terrain_surface_y(p, s->atmosphere.bottom_radius_m, x, z);
            *(sphere ? &o.center_m[1] : &o.min_m[1]) += y;
        }
        if (o.type == ATMO_OBJECT_SPHERE) {
            g->a = rel4(o.center_m, cam, o.radius_m);
        } else {
            double hi[3] = {o.min_m[0] + o.size_m[0], o.min_m[1] + o.size_m[1],
                            o.min_m[2] + o.size_m[2]};
            g->a = rel4(o.min_m, cam, 0.0);
            g->b = rel4(hi, cam, 0.0);
        }
        g->albedo = col4(o.albedo);
        g->emission = col4(o.emission);
    }
    p->gpu.path.object_count = n;
    return atmo_plan_add_buffer(p, "objects", "atmo_gpu_object", (size_t)n * sizeof *rows, 0,
                                rows, e);
}

