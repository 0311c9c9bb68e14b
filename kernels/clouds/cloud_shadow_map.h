/* cloud_shadow_map.h — the fBm cloud layer's sun shadow map (-DATMO_CLOUDS_SHADOW_MAP, scene key
 * clouds.shadow_map): a 3-D grid of the density integral D toward the sun over the region
 * around the camera, precomputed once per view by its pass (cloud_shadow_map.cl), so that the
 * marcher (cloud_march.h) and the visibility of the terrain and the air (visibility.h) look D
 * up instead of marching toward the sun at every sample.
 *
 * Frame: the majorant grid's (cloud_majorant.h's clouds_grid_frame_make): the tangent frame at
 * the camera's foot F, ax and az horizontal, ay up, the planet centre at -r_c ay from the
 * camera (r_c the camera's radius). A point v from the centre has the gnomonic coordinates
 *     X = R (v . ax) / (v . ay),   Z = R (v . az) / (v . ay)
 * (its direction from the centre projected onto the plane tangent at F) and its altitude h, so
 * the third axis follows the curved layer at full vertical resolution everywhere. Nodes:
 *     X_i = -E + i 2E / (n - 1),  Z_k = -E + k 2E / (n - 1),  i, k = 0 .. n - 1,
 *     h_j = bottom + j (top - bottom) / (L - 1),  j = 0 .. L - 1,
 * E = min(max_distance_m, CLOUDS_GRID_EXTENT_MAX R) (the majorant grid's), n =
 * clouds.shadow_map_size, L = clouds.shadow_map_levels; node (i, j, k) at map[(j n + k) n + i].
 * The node's point: with rho^2 = (X^2 + Z^2) / R^2 and s = sqrt(1 + rho^2), its direction from
 * the centre is (X ax + R ay + Z az) / (R s), and its camera-relative position
 *     p = (R + h) (X ax + Z az) / (R s) + ay ((R + h) (1/s - 1) + h - h_c),
 *     1/s - 1 = -rho^2 / (s (1 + s))
 * (h_c = r_c - R the camera's altitude), written so nothing cancels at planet scale.
 *
 * A node holds D = int d dt from its point toward the sun over the whole chord through the layer
 * (cloud_layer.h's clouds_sun_density_steps with clouds.shadow_map_steps steps growing as
 * (i/n)^2, sampled at their midpoints, not stopped when opaque): the light march cuts its chord
 * to light_distance_m to bound its cost per sample, which the map pays once per node, and the
 * Monte Carlo reference's ratio tracking (method_reference.h) does not cut, so the map's
 * shadows converge to the reference's with its steps and resolution.
 *
 * Lookup (clouds_shadow_map_density): a point in the layer takes the trilinear interpolation of
 * the 8 nodes around (X, Z, h); a point below the layer takes the map at the point where its ray
 * toward the sun enters the layer's bottom (the density is zero below it, so D is the same),
 * one whose ray misses the layer gets 0; a point above the layer or horizontally outside the
 * map falls back to the light march. T_sun = exp(-extinction D) then, as for the light march.
 * Units: metres; D in metres of unit density. */
#ifndef ATMO_CLOUDS_CLOUD_SHADOW_MAP_H
#define ATMO_CLOUDS_CLOUD_SHADOW_MAP_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "common/geometry.h"
#include "media/ray.h"
#include "clouds/cloud_layer.h"
#include "clouds/cloud_majorant.h"
#include "atmo/gpu_types.h"
#endif

/* The map's horizontal half-extent E (m). */
ATMO_FN float clouds_shadow_map_extent(ATMO_GLOBAL const atmo_gpu_scene *s)
{
    return fminf(s->clouds.max_distance_m, CLOUDS_GRID_EXTENT_MAX * s->atmosphere.bottom_radius);
}

/* The medium point of node (i, j, k) (mu, the view cosine, is not used and set to 1). */
ATMO_FN medium_point clouds_shadow_map_node_point(ATMO_GLOBAL const atmo_gpu_scene *s,
                                                  const clouds_grid_frame *f, int i, int j, int k)
{
    ATMO_GLOBAL const atmo_gpu_clouds *c = &s->clouds;
    float R = s->atmosphere.bottom_radius, E = clouds_shadow_map_extent(s);
    int n = c->shadow_map_size, L = c->shadow_map_levels;
    float X = -E + 2.0f * E * (float)i / (float)(n - 1);
    float Z = -E + 2.0f * E * (float)k / (float)(n - 1);
    float h = c->bottom_m + (c->top_m - c->bottom_m) * (float)j / (float)(L - 1);
    float rho2 = (X * X + Z * Z) / (R * R), sq = sqrtf(1.0f + rho2);
    float r = R + h, h_c = s->camera.local_up.w - R;
    vec3 horizontal = v3_add(v3_scale(f->ax, X), v3_scale(f->az, Z));
    medium_point q;
    q.p = v3_add(v3_scale(horizontal, r / (R * sq)),
                 v3_scale(f->ay, -r * rho2 / (sq * (1.0f + sq)) + h - h_c));
    q.r = r;
    q.h = h;
    q.mu = 1.0f;
    vec3 dir = v3_scale(v3_add(horizontal, v3_scale(f->ay, R)), 1.0f / (R * sq));
    q.mu_s = atmo_clamp_cos(v3_dot(dir, v3_from4(s->sun_direction)));
    return q;
}

/* The value of node (i, j, k): D over the whole chord toward the sun (see the top). */
ATMO_FN float clouds_shadow_map_node(ATMO_GLOBAL const atmo_gpu_scene *s,
                                     const clouds_grid_frame *f, int i, int j, int k)
{
    medium_point q = clouds_shadow_map_node_point(s, f, i, j, k);
    return clouds_sun_density_steps(s, &q, 0.5f, s->clouds.shadow_map_steps, INFINITY,
                                    INFINITY);
}

/* The map's cell (i, j, k) around the camera-relative point p of altitude h in [bottom, top]
 * (node (i, j, k) its low corner) and p's fractions in it along X, h, Z; 0 where p lies
 * horizontally outside the map. */
ATMO_FN int clouds_shadow_map_cell(ATMO_GLOBAL const atmo_gpu_scene *s, const clouds_grid_frame *f,
                                   vec3 p, float h, int *i, int *j, int *k, vec3 *frac)
{
    ATMO_GLOBAL const atmo_gpu_clouds *c = &s->clouds;
    float R = s->atmosphere.bottom_radius, E = clouds_shadow_map_extent(s);
    int n = c->shadow_map_size, L = c->shadow_map_levels;
    float vy = v3_dot(p, f->ay) + s->camera.local_up.w;
    float spacing = 2.0f * E / (float)(n - 1);
    float u = (R * v3_dot(p, f->ax) / vy + E) / spacing;
    float w = (R * v3_dot(p, f->az) / vy + E) / spacing;
    float v = clamp((h - c->bottom_m) / (c->top_m - c->bottom_m) * (float)(L - 1), 0.0f,
                    (float)(L - 1));
    if (!(vy > 0.0f && u >= 0.0f && u <= (float)(n - 1) && w >= 0.0f && w <= (float)(n - 1)))
        return 0;
    *i = (int)u, *k = (int)w, *j = (int)v; /* the last nodes interpolate from the cell below */
    *i = *i < n - 2 ? *i : n - 2, *k = *k < n - 2 ? *k : n - 2, *j = *j < L - 2 ? *j : L - 2;
    *frac = v3(u - (float)*i, v - (float)*j, w - (float)*k);
    return 1;
}

/* The trilinear interpolation of the map at the camera-relative point p of altitude h in
 * [bottom, top]; -1 where p lies horizontally outside the map. */
ATMO_FN float clouds_shadow_map_lookup(ATMO_GLOBAL const atmo_gpu_scene *s,
                                       ATMO_GLOBAL const float *map, const clouds_grid_frame *f,
                                       vec3 p, float h)
{
    int n = s->clouds.shadow_map_size, i, j, k;
    vec3 t;
    if (!clouds_shadow_map_cell(s, f, p, h, &i, &j, &k, &t))
        return -1.0f;
    ATMO_GLOBAL const float *m0 = map + ((size_t)j * (size_t)n + (size_t)k) * (size_t)n + (size_t)i;
    ATMO_GLOBAL const float *m1 = m0 + (size_t)n * (size_t)n;
    float a0 = m0[0] + t.x * (m0[1] - m0[0]), b0 = m0[n] + t.x * (m0[n + 1] - m0[n]);
    float a1 = m1[0] + t.x * (m1[1] - m1[0]), b1 = m1[n] + t.x * (m1[n + 1] - m1[n]);
    float d0 = a0 + t.z * (b0 - a0), d1 = a1 + t.z * (b1 - a1);
    return d0 + t.y * (d1 - d0);
}

/* The density integral D toward the sun from q: the map's where it covers q, else the light
 * march (see the top). */
ATMO_FN float clouds_shadow_map_density(ATMO_GLOBAL const atmo_gpu_scene *s,
                                        ATMO_GLOBAL const float *map, const medium_point *q)
{
    ATMO_GLOBAL const atmo_gpu_clouds *c = &s->clouds;
    clouds_grid_frame f = clouds_grid_frame_make(s);
    float D = -1.0f;
    if (q->h >= c->bottom_m && q->h <= c->top_m) {
        D = clouds_shadow_map_lookup(s, map, &f, q->p, q->h);
    } else if (q->h < c->bottom_m) {
        float lo[2], hi[2];
        if (geometry_shell_parts(s->atmosphere.bottom_radius, c->bottom_m, c->top_m, q->r, q->mu_s,
                               0.0f, INFINITY, lo, hi) == 0)
            return 0.0f;
        vec3 entry = v3_add(q->p, v3_scale(v3_from4(s->sun_direction), lo[0]));
        D = clouds_shadow_map_lookup(s, map, &f, entry, c->bottom_m);
    }
    return D >= 0.0f ? D : clouds_sun_density(s, q, clouds_point_jitter(q->p, c->seed));
}

#endif
