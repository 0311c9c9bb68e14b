/* terrain_material.h — the terrain's procedural materials (no image assets).
 *
 * By altitude a above sea level, the cosine c = N . n of the
 * slope (N the surface normal, n the vertical) and a detail noise dn in [-1, 1] (two octaves of
 * value noise, periods 160 m and 40 m, each faded out where its period is below four pixel
 * footprints, t times pixel_angle, so far terrain neither aliases nor shimmers):
 *     flat  = smoothstep(0.70, 0.85, c)                        (steep faces are rock)
 *     low   = 1 - smoothstep(700, 1000, a + 150 dn)            (grass below ~700-1000 m)
 *     snow  = smoothstep(2500, 3100, a + 200 dn) smoothstep(0.55, 0.70, c)
 *     grass = (1 - snow) low flat,  rock = (1 - snow) (1 - flat + (1 - low) flat (1 - dn) / 2),
 *     dirt  = (1 - snow) (1 - low) flat (1 + dn) / 2,
 * which sum to 1 (the thesis' bands: presets.md); water where the height is at sea level or
 * below. The albedo is the weighted sum of the materials' albedos at the three render
 * wavelengths.
 *
 * Albedos at the render wavelengths (~680, 550, 440 nm): grass (0.09, 0.14, 0.04), dirt
 * (0.26, 0.20, 0.14), rock (0.30, 0.28, 0.26), snow (0.90, 0.92, 0.95), the water body (0.02,
 * 0.03, 0.04). */
#ifndef ATMO_TERRAIN_MATERIAL_H
#define ATMO_TERRAIN_MATERIAL_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "terrain/noise.h"
#include "terrain/terrain.h"
#include "atmo/gpu_types.h"
#endif

#define TERRAIN_DETAIL_PERIOD_M 160.0f

enum { TERRAIN_GRASS = 0, TERRAIN_DIRT, TERRAIN_ROCK, TERRAIN_SNOW, TERRAIN_WATER,
       TERRAIN_MATERIALS };

typedef struct terrain_surface_point {
    vec3 p;                          /* camera-relative position, m */
    vec3 normal, vertical;           /* unit */
    float altitude_m;                /* of the surface above sea level */
    float weight[TERRAIN_MATERIALS]; /* sum to 1 */
    vec3 albedo;
} terrain_surface_point;

ATMO_FN float terrain_smoothstep(float a, float b, float x)
{
    float t = clamp((x - a) / (b - a), 0.0f, 1.0f);
    return t * t * (3.0f - 2.0f * t);
}

/* Material albedos at the render wavelengths (~680, 550, 440 nm). */
ATMO_FN vec3 terrain_material_albedo(int k)
{
    switch (k) {
    case TERRAIN_GRASS: return v3(0.09f, 0.14f, 0.04f);
    case TERRAIN_DIRT: return v3(0.26f, 0.20f, 0.14f);
    case TERRAIN_ROCK: return v3(0.30f, 0.28f, 0.26f);
    case TERRAIN_SNOW: return v3(0.90f, 0.92f, 0.95f);
    default: return v3(0.02f, 0.03f, 0.04f); /* the water body */
    }
}

/* The detail noise at (u, v), filtered for a pixel footprint of `footprint` metres. */
ATMO_FN float terrain_detail(uint seed, float u, float v, float footprint)
{
    float sum = 0.0f, period = TERRAIN_DETAIL_PERIOD_M, amp = 0.7f;
    for (int i = 0; i < 2; i++) {
        float fade = terrain_smoothstep(2.0f, 4.0f, period / fmaxf(footprint, 1e-3f));
        sum += amp * fade * terrain_value_noise(u / period, v / period, seed + 0x3c6ef372u + (uint)i).v;
        period *= 0.25f;
        amp = 0.3f;
    }
    return sum;
}

/* The weights of grass, dirt, rock and snow at altitude a above sea level, slope cosine c and
 * detail noise dn (see the top of the file); water 0. */
ATMO_FN void terrain_material_weights(float a, float c, float dn, float w[TERRAIN_MATERIALS])
{
    float flat = terrain_smoothstep(0.70f, 0.85f, c);
    float low = 1.0f - terrain_smoothstep(700.0f, 1000.0f, a + 150.0f * dn);
    float snow = terrain_smoothstep(2500.0f, 3100.0f, a + 200.0f * dn) *
                 terrain_smoothstep(0.55f, 0.70f, c);
    float rest = 1.0f - snow;
    w[TERRAIN_GRASS] = rest * low * flat;
    w[TERRAIN_DIRT] = rest * (1.0f - low) * flat * 0.5f * (1.0f + dn);
    w[TERRAIN_ROCK] = rest * ((1.0f - flat) + (1.0f - low) * flat * 0.5f * (1.0f - dn));
    w[TERRAIN_SNOW] = snow;
    w[TERRAIN_WATER] = 0.0f;
}

/* The surface at the camera-relative point p on it, seen from `distance` metres: normal,
 * material weights and albedo (the path tracer's terrain_material). */
ATMO_FN terrain_surface_point terrain_material(ATMO_GLOBAL const atmo_gpu_scene *s,
                                               ATMO_GLOBAL const float *hm, vec3 p, float distance)
{
    terrain_surface_point m;
    terrain_site q = terrain_locate(s, p);
    terrain_height h = terrain_height_at(&s->terrain.field, hm, q.u, q.v);
    m.p = p;
    m.vertical = terrain_vertical(s, p);
    m.normal = terrain_normal(s, hm, p);
    m.altitude_m = fmaxf(h.h, s->terrain.sea_level_m);
    if (h.h <= s->terrain.sea_level_m) {
        for (int k = 0; k < TERRAIN_MATERIALS; k++)
            m.weight[k] = 0.0f;
        m.weight[TERRAIN_WATER] = 1.0f;
    } else {
        float dn = terrain_detail(s->terrain.field.seed, q.u, q.v, distance * s->terrain.pixel_angle);
        terrain_material_weights(h.h - s->terrain.sea_level_m, v3_dot(m.normal, m.vertical), dn,
                                 m.weight);
    }
    m.albedo = v3(0.0f, 0.0f, 0.0f);
    for (int k = 0; k < TERRAIN_MATERIALS; k++)
        m.albedo = v3_add(m.albedo, v3_scale(terrain_material_albedo(k), m.weight[k]));
    return m;
}

#endif
