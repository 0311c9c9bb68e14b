/* terrain_sun.h — the terrain's shadow on the sun from the sun-height map: whether a point of
 * a view ray sees the sun over the terrain, as one bilinear lookup instead of a march.
 *
 * The map (baked by terrain_sun_map.cl, row by row: terrain_sun_map.h) lies on the gnomonic
 * (tangent) plane of the ground sphere (radius R) at the foot of the camera, with unit up n
 * (the camera's vertical), x along the sun's horizontal direction a at the camera and y along
 * b = n x a. A camera-relative point p projects from the planet's centre onto it at
 *     x = R (a.p) / (r_c + n.p),   y = R (b.p) / (r_c + n.p)
 * (r_c the camera's distance to the centre). The projection maps straight lines to straight
 * lines, so every sun ray, a straight line parallel to the sun direction s, projects to a line
 * through the vanishing point x_v = R cot(e0) on the x axis (e0 the sun's elevation at the
 * camera). The map's rows follow these lines: row coordinate eta = y / (1 - x tan(e0) / R),
 * the lateral offset at x = 0 of the sun line through (x, y); along a row x. The map covers
 * x, eta in [-E/2, E/2] (E = sun_map_extent_m) on an N x N grid (N = sun_map_size), texel
 * centres at (i + 1/2) E / N - E / 2.
 *
 * Each texel holds S, the lowest altitude (above the ground sphere) at which a point on its
 * radial line sees the sun's centre over the terrain (and the sea) between it and the bake's
 * sunward end (the map's edge plus sun_map_lead texels). A point at altitude z sees the sun
 * where z >= S: the lookup returns clamp((z - S) / w + 1/2, 0, 1) with w = sun_map_soft_m, a
 * soft edge of a few metres so neighbouring samples of a view ray do not alias on the texel
 * grid. The error of S (the height field between the bake's samples, the bilinear
 * interpolation across rows) is bounded by the slope bound L times a texel:
 * tests/test_terrain_sun_map.c. The map returns -1 (the caller marches instead) where it has
 * no answer: outside the square, or without a map (sun_map_size 0: terrain.sun_visibility =
 * exact, the path tracer, a sun below the camera's horizon, where a ray's lowest point lies
 * sunward of the camera and may pass beyond the baked span, or a sun so high that the rows'
 * vanishing point, under the sun, comes near the baked span: plan_terrain_sun.c).
 *
 * Parameters (gpu_terrain.h): sun_map_size N (terrain.sun_map_size, 2 to 4096, default 1024),
 * sun_map_extent_m E (terrain.sun_map_extent_m, default 80000 m), sun_map_lead (texels,
 * the plan's: terrain.shadow_far_m over the texel, at most 4 N), sun_map_soft_m (4 m),
 * sun_map_axis (a; w = tan e0). */
#ifndef ATMO_TERRAIN_SUN_H
#define ATMO_TERRAIN_SUN_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "terrain/terrain.h"
#include "atmo/gpu_types.h"
#endif

/* The map's frame: the camera's unit vertical n, the rows' direction a and the lateral b. */
ATMO_FN void terrain_sun_frame(ATMO_GLOBAL const atmo_gpu_scene *s, vec3 *n, vec3 *a, vec3 *b)
{
    *n = v3_from4(s->camera.local_up);
    *a = v3_from4(s->terrain.sun_map_axis);
    *b = v3_cross(*n, *a);
}

/* The side of one texel, m. */
ATMO_FN float terrain_sun_texel_m(ATMO_GLOBAL const atmo_gpu_scene *s)
{
    return s->terrain.sun_map_extent_m / (float)s->terrain.sun_map_size;
}

/* The factor y / eta of the sun line at gnomonic x: 1 - x tan(e0) / R. */
ATMO_FN float terrain_sun_lateral(ATMO_GLOBAL const atmo_gpu_scene *s, float x)
{
    return 1.0f - x * s->terrain.sun_map_axis.w / s->atmosphere.bottom_radius;
}

/* The stored sun height at grid coordinates (gx, gy) (texel centres at integers, gx along the
 * sun), bilinear; inside [0, N - 1]^2. */
ATMO_FN float terrain_sun_height(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_GLOBAL const float *map,
                                 float gx, float gy)
{
    int n = s->terrain.sun_map_size;
    float x0 = fminf(floorf(gx), (float)(n - 2)), y0 = fminf(floorf(gy), (float)(n - 2));
    float fx = gx - x0, fy = gy - y0;
    int i = (int)x0, j = (int)y0;
    float a = map[j * n + i], b = map[j * n + i + 1];
    float c = map[(j + 1) * n + i], d = map[(j + 1) * n + i + 1];
    return mix(mix(a, b, fx), mix(c, d, fx), fy);
}

/* The map's grid coordinates of the camera-relative point p: 1 inside the map, else 0. */
ATMO_FN int terrain_sun_grid(ATMO_GLOBAL const atmo_gpu_scene *s, vec3 p, float *gx, float *gy)
{
    vec3 n, a, b;
    terrain_sun_frame(s, &n, &a, &b);
    float R = s->atmosphere.bottom_radius, depth = s->camera.local_up.w + v3_dot(n, p);
    if (!(depth > 0.0f))
        return 0;
    float x = R * v3_dot(a, p) / depth, y = R * v3_dot(b, p) / depth;
    float lateral = terrain_sun_lateral(s, x);
    if (!(lateral > 0.0f))
        return 0;
    float texel = terrain_sun_texel_m(s), half_e = 0.5f * s->terrain.sun_map_extent_m;
    float last = (float)(s->terrain.sun_map_size - 1);
    *gx = (x + half_e) / texel - 0.5f;
    *gy = (y / lateral + half_e) / texel - 0.5f;
    return *gx >= 0.0f && *gy >= 0.0f && *gx <= last && *gy <= last;
}

/* The visible fraction of the sun's centre from the camera-relative point p over the map (see
 * the top of the file), or -1 where the map has no answer. */
ATMO_FN float terrain_sun_map_visibility(ATMO_GLOBAL const atmo_gpu_scene *s,
                                         ATMO_GLOBAL const float *map, vec3 p)
{
    float gx, gy;
    if (!map || s->terrain.sun_map_size < 2 || !terrain_sun_grid(s, p, &gx, &gy))
        return -1.0f;
    float S = terrain_sun_height(s, map, gx, gy), z = terrain_locate(s, p).alt;
    return clamp((z - S) / s->terrain.sun_map_soft_m + 0.5f, 0.0f, 1.0f);
}

#endif
