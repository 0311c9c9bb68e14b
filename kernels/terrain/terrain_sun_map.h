/* terrain_sun_map.h — the bake of the sun-height map (terrain_sun.h: its frame and lookup):
 * one row of texels along the sun, from the sunward end toward the camera's side.
 *
 * Texel k of row j lies on the radial line through the gnomonic point (x_k, y_k), x_k =
 * (k + 1/2) t - E/2 (t = E / N the texel), y_k = eta_j (1 - x_k tan(e0) / R); the row runs
 * k = N - 1 + lead down to 0 and stores k < N. Its ground is the terrain's surface there,
 * h_k = max(h(u, v), sea level) with (u, v) the foot of that line (terrain.h's placement).
 *
 * Recurrence. A straight sun ray keeps r cos(e) constant along itself (r cos(e) is its
 * distance from the planet's centre; e the sun's elevation at the ray's point), so the ray
 * that leaves texel k at radius r passes over texel k + 1 (the same row: rows follow the
 * projected sun lines) at r c_k / c_{k+1}, c = cos(e) at the texel's radial line,
 * sin(e_k) = s.w_k / |w_k|, w_k = R n + x_k a + y_k b. It clears the terrain from there on iff
 * r c_k / c_{k+1} >= R + S_{k+1}, so, with S an altitude,
 *     S_k = max(h_k, S_{k+1} + (R + S_{k+1}) (c_{k+1} - c_k) / c_k),
 *     c_{k+1} - c_k = (sin e_k - sin e_{k+1}) (sin e_k + sin e_{k+1}) / (c_k + c_{k+1})
 * (the product form keeps the small difference exact in float; the drop per texel is about
 * t tan(e): the sun's elevation with the planet's curvature, e growing sunward by t / R per
 * texel, the tangent plane's drop x^2 / 2R). S_{N-1+lead} = h_{N-1+lead}: no terrain beyond
 * the bake's end. The recurrence is exact on the sampled heights; between samples the height
 * field can rise by at most L t / 2 over them (L the slope bound), so S is low by at most
 * that (tests/test_terrain_sun_map.c states the band). Float: the drop's relative error is
 * about 1e-3 per texel, a millimetre in S.
 *
 * Parameters: gpu_terrain.h (sun_map_*), the height field (terrain.h). */
#ifndef ATMO_TERRAIN_SUN_MAP_H
#define ATMO_TERRAIN_SUN_MAP_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "terrain/terrain.h"
#include "terrain/terrain_sun.h"
#include "atmo/gpu_types.h"
#endif

/* Texel k's radial line of row j: the unit vector w / |w| from the planet's centre (*up) and
 * the sine of the sun's elevation there (the return value). */
ATMO_FN float terrain_sun_map_line(ATMO_GLOBAL const atmo_gpu_scene *s, int k, int j, vec3 *up)
{
    vec3 n, a, b;
    terrain_sun_frame(s, &n, &a, &b);
    float R = s->atmosphere.bottom_radius, texel = terrain_sun_texel_m(s);
    float half_e = 0.5f * s->terrain.sun_map_extent_m;
    float x = ((float)k + 0.5f) * texel - half_e;
    float y = (((float)j + 0.5f) * texel - half_e) * terrain_sun_lateral(s, x);
    vec3 w = v3_add(v3_scale(n, R), v3_add(v3_scale(a, x), v3_scale(b, y)));
    *up = v3_scale(w, 1.0f / v3_length(w));
    return v3_dot(v3_from4(s->sun_direction), *up);
}

/* The terrain's surface altitude under texel k of row j (k may pass N - 1: the lead). The
 * camera-relative ground point R up - r_c n is formed as R (up - n) - h_c n, without the
 * planet's radius cancelling in float. */
ATMO_FN float terrain_sun_map_ground(ATMO_GLOBAL const atmo_gpu_scene *s,
                                     ATMO_GLOBAL const float *hm, int k, int j)
{
    vec3 up, n = v3_from4(s->camera.local_up);
    terrain_sun_map_line(s, k, j, &up);
    float R = s->atmosphere.bottom_radius;
    vec3 p = v3_sub(v3_scale(v3_sub(up, n), R), v3_scale(n, s->terrain.camera.w));
    terrain_site q = terrain_locate(s, p);
    return terrain_surface(s, hm, q);
}

/* Row j of the map: S for k = N - 1 + lead down to 0, texels k < N written to map[j N + k]. */
ATMO_FN void terrain_sun_map_row(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_GLOBAL const float *hm,
                                 int j, ATMO_GLOBAL float *map)
{
    int n = s->terrain.sun_map_size, last = n - 1 + s->terrain.sun_map_lead;
    float R = s->atmosphere.bottom_radius, S = 0.0f, sin_prev = 0.0f, cos_prev = 1.0f;
    vec3 up;
    for (int k = last; k >= 0; k--) {
        float sin_e = terrain_sun_map_line(s, k, j, &up);
        float cos_e = atmo_safe_sqrt(1.0f - sin_e * sin_e);
        float h = terrain_sun_map_ground(s, hm, k, j);
        if (k == last) {
            S = h;
        } else {
            float dc = (sin_e - sin_prev) * (sin_e + sin_prev) / (cos_e + cos_prev);
            S = fmaxf(h, S + (R + S) * dc / cos_e);
        }
        sin_prev = sin_e, cos_prev = cos_e;
        if (k < n)
            map[j * n + k] = S;
    }
}

#endif
