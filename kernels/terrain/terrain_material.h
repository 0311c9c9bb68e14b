/* terrain_material.h — the terrain's procedural materials (no image assets).
 *
 * Detail noise. D(x, y) is two octaves of value noise, periods 160 m and 40 m, each faded out
 * where its period is below four pixel footprints (t times pixel_angle), so far terrain neither
 * aliases nor shimmers. Evaluated in the plane (u, v) alone it stretches on steep faces: a metre
 * along the fall line of a slope s moves (u, v) by 1 / sqrt(1 + s^2) m, so the noise varies
 * that much slower there than along the strike. The detail dn is therefore triplanar (Geiss,
 * "Generating complex procedural terrains using the GPU", GPU Gems 3, ch. 1, 2007): in the
 * frame (u, a, v) of the height field (a the altitude, metres: the planar coordinates of
 * terrain.h, so camera-relative float precision as the rest of the terrain) the surface's
 * normal is N ~ (-h_u, 1, -h_v), and the three axis projections blend by |N_k|^4,
 *     dn = w_u D(v, a) + w_a D(u, v) + w_v D(u, a),
 *     (w_u, w_a, w_v) = (h_u^4, 1, h_v^4) / (1 + h_u^4 + h_v^4),
 * (the normalisation of N cancels), weights that sum to 1 and keep dn in [-1, 1]. On flat
 * ground w_a = 1 exactly and dn = D(u, v); on a vertical face the projection along the face's
 * normal dominates, whose coordinates move a metre per metre along both the fall line and the
 * strike (tests/test_terrain_triplanar.c measures the variance per metre of each).
 *
 * Materials. By altitude a above sea level, the cosine c = N . n of the slope (N the surface
 * normal, n the vertical) and the detail noise dn in [-1, 1]:
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

/* D: the detail noise in one plane at (x, y) metres, filtered for a pixel footprint of
 * `footprint` metres. */
ATMO_FN float terrain_material_noise_plane(uint seed, float x, float y, float footprint)
{
    float sum = 0.0f, period = TERRAIN_DETAIL_PERIOD_M, amp = 0.7f;
    for (int i = 0; i < 2; i++) {
        float fade = terrain_smoothstep(2.0f, 4.0f, period / fmaxf(footprint, 1e-3f));
        sum += amp * fade * terrain_value_noise(x / period, y / period, seed + 0x3c6ef372u + (uint)i).v;
        period *= 0.25f;
        amp = 0.3f;
    }
    return sum;
}

/* The triplanar weights (w_u, w_a, w_v) for the height field's gradient (h_u, h_v) (see the
 * top of the file); slopes beyond 1e4 (89.994 degrees) count as 1e4, so the fourth powers stay
 * finite. */
ATMO_FN void terrain_triplanar_weights(float hu, float hv, float w[3])
{
    float a = fminf(hu * hu, 1e8f), b = fminf(hv * hv, 1e8f);
    a *= a, b *= b;
    float s = 1.0f + a + b;
    w[0] = a / s, w[1] = 1.0f / s, w[2] = b / s;
}

/* dn: the triplanar detail noise at planar (u, v) and altitude a (metres) of a surface with
 * gradient (h_u, h_v) (see the top of the file); projections of weight 0 are not evaluated. */
ATMO_FN float terrain_material_noise(uint seed, float u, float v, float a, float hu, float hv,
                                     float footprint)
{
    float w[3], dn = 0.0f;
    terrain_triplanar_weights(hu, hv, w);
    if (w[0] > 0.0f)
        dn += w[0] * terrain_material_noise_plane(seed, v, a, footprint);
    if (w[1] > 0.0f)
        dn += w[1] * terrain_material_noise_plane(seed, u, v, footprint);
    if (w[2] > 0.0f)
        dn += w[2] * terrain_material_noise_plane(seed, u, a, footprint);
    return dn;
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
        float dn = terrain_material_noise(s->terrain.field.seed, q.u, q.v, h.h, h.du, h.dv,
                                          distance * s->terrain.pixel_angle);
        terrain_material_weights(h.h - s->terrain.sea_level_m, v3_dot(m.normal, m.vertical), dn,
                                 m.weight);
    }
    m.albedo = v3(0.0f, 0.0f, 0.0f);
    for (int k = 0; k < TERRAIN_MATERIALS; k++)
        m.albedo = v3_add(m.albedo, v3_scale(terrain_material_albedo(k), m.weight[k]));
    return m;
}

#endif
