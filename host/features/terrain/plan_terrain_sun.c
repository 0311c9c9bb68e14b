/* plan_terrain_sun.c — the terrain's sun-height map in the plan (atmo/plan_terrain.h;
 * kernels/terrain/terrain_sun.h, terrain_sun_map.h).
 *
 * The map's rows run along the sun's horizontal direction at the camera, a = (s - (s.n) n) /
 * |...| (n the camera's vertical, s the sun), and the bake needs tan(e0), e0 the sun's
 * elevation there, both from the float vectors the kernels hold. Lead: the bake starts
 * terrain.shadow_far_m beyond the map's sunward edge (at most 4 N texels), so every point of
 * the map sees at least as far toward the sun as the march does. The map is planned only for
 * 0 <= e0, and where the rows' vanishing point x_v = R cot(e0) (the point under the sun, where
 * they meet) lies beyond twice the bake's sunward end X, i.e. X tan(e0) <= R / 2 (e0 up to
 * about 88.6 degrees at the defaults): below the camera's horizon a sun ray's lowest point lies
 * sunward of the camera, possibly beyond the baked span; nearer the sub-solar point the rows
 * converge and the sun reaches the zenith of the baked texels (and shadows are short there:
 * the march is cheap). */
#include <math.h>
#include "atmo/plan_terrain.h"

/* the soft edge of the lookup, m: a few metres, below the bake's error band */
#define TERRAIN_SUN_SOFT_M 4.0
/* the rows' least spacing at the bake's sunward end, relative to the camera's (see above) */
#define TERRAIN_SUN_MIN_LATERAL 0.5
/* the lead's cap, in map sides */
#define TERRAIN_SUN_MAX_LEAD 4

int atmo_plan_terrain_sun_map(const atmo_scene *s, atmo_plan *p, atmo_err *e)
{
    atmo_gpu_terrain *t = &p->gpu.terrain;
    const float4 up = p->gpu.camera.local_up, sun = p->gpu.sun_direction;
    double n[3] = {up.x, up.y, up.z}, d[3] = {sun.x, sun.y, sun.z}, a[3];
    double sin_e = n[0] * d[0] + n[1] * d[1] + n[2] * d[2];
    for (int i = 0; i < 3; i++)
        a[i] = d[i] - sin_e * n[i];
    double cos_e = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    int size = s->terrain.sun_map_size;
    double extent = s->terrain.sun_map_extent_m, texel = extent / size;
    double lead = fmin(ceil(s->terrain.shadow_far_m / texel), TERRAIN_SUN_MAX_LEAD * size);
    double end = (size - 0.5 + lead) * texel - 0.5 * extent, R = p->gpu.atmosphere.bottom_radius;
    t->sun_map_size = 0;
    if (sin_e >= 0.0 && end * sin_e <= (1.0 - TERRAIN_SUN_MIN_LATERAL) * R * cos_e) {
        t->sun_map_size = size;
        t->sun_map_extent_m = (float)extent;
        t->sun_map_lead = (int)lead;
        t->sun_map_soft_m = (float)TERRAIN_SUN_SOFT_M;
        t->sun_map_axis.x = (float)(a[0] / cos_e);
        t->sun_map_axis.y = (float)(a[1] / cos_e);
        t->sun_map_axis.z = (float)(a[2] / cos_e);
        t->sun_map_axis.w = (float)(sin_e / cos_e);
    }
    size_t bytes = sizeof(float) * (size_t)t->sun_map_size * (size_t)t->sun_map_size;
    int rc = atmo_plan_add_buffer(p, "terrain_sun_map", "float", bytes, 1, NULL, e);
    if (!rc && t->sun_map_size > 0)
        rc = atmo_plan_add_pass(p, "terrain_sun_map_rows", t->sun_map_size, 1, 1, 0, e);
    return rc;
}
