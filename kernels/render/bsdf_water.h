/* bsdf_water.h — the sea's BSDF in the path tracer: the preview's water (terrain_shade.h,
 * water.h) as lobes a path can sample and a sun it can estimate.
 *
 * The preview's sea sends back, for the view direction v (cosine c_v = n . v to the vertical n)
 *     L = F(c_v) L(r) + E T_sun V glint(v, s) + (1 - F(c_v)) a_w / pi (E T_sun V mu_s + E_sky),
 * with r = 2 (n . v) n - v the mirror direction: the sky reflected by the mean surface with the
 * Fresnel reflectance F (Born and Wolf 1.5.2), the sun reflected by the wind's facets
 * (Cox and Munk 1954, water_glint) and a dark water body of albedo a_w lit through the surface.
 * As a BSDF:
 *     f(v, w) = F(c_v) delta(w - r) / cos + (1 - F(c_v)) a_w / pi      (all light but the sun)
 *     f(v, s) cos_s = glint(v, s) + (1 - F(c_v)) a_w / pi cos_s          (the sun's disc)
 * The path samples the first line: the mirror with probability P_m = F / (F + (1 - F) abar)
 * (abar the mean of a_w's channels, so both lobes carry about the same throughput), weight
 * F / P_m and no MIS (a delta lobe: the sky's sampling never finds r); else the body's cosine
 * lobe, weight (1 - F) a_w / (1 - P_m), density (1 - P_m) cos / pi, against which the sky's
 * next-event estimate is weighed (path.h). The sun comes from next-event estimation only, the
 * glint's and the body's, and the mirror ray does not count the disc: the glint is the sun's
 * reflection from the rough sea, of which a mirror's disc would count part twice (as in the
 * preview). The glint needs no BSDF-sampled partner: its lobe (rms slope sigma = 0.17 rad) is
 * 36 times wider than the disc (0.0047 rad), so the disc's samples see a smooth integrand.
 * With path.sun_nee = false nothing estimates the glint; the mirror ray then counts the disc
 * (the smooth-sea limit), as every continuation does without the sun's NEE. */
#ifndef ATMO_RENDER_BSDF_WATER_H
#define ATMO_RENDER_BSDF_WATER_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "terrain/water.h"
#endif

/* P_m: the probability of the mirror lobe for Fresnel reflectance f and body albedo a. */
ATMO_FN float bsdf_water_mirror_probability(float f, vec3 a)
{
    float body = (1.0f - f) * (a.x + a.y + a.z) * (1.0f / 3.0f);
    return f + body > 0.0f ? f / (f + body) : 1.0f;
}

/* The mirror direction of the unit direction d (pointing at the surface) about the unit n. */
ATMO_FN vec3 bsdf_water_mirror(vec3 d, vec3 n)
{
    return v3_normalize(v3_sub(d, v3_scale(n, 2.0f * v3_dot(d, n))));
}

/* f cos toward the sun direction w for the view v (unit, away from the surface), the vertical
 * n, Fresnel reflectance f of the view and body albedo a, per unit normal-incidence irradiance:
 * the glint plus the body. */
ATMO_FN vec3 bsdf_water_sun(vec3 n, vec3 v, vec3 w, float f, vec3 a)
{
    float c = v3_dot(n, w);
    if (c <= 0.0f)
        return v3(0.0f, 0.0f, 0.0f);
    float g = water_glint(n, v, w);
    return v3_add(v3(g, g, g), v3_scale(a, (1.0f - f) * c / ATMO_PI));
}

#endif
