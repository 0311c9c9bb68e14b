/* light_sky.h — sampling the sky at a surface point, for next-event estimation combined with
 * the BSDF's sampling by multiple importance sampling.
 *
 * The density is a mixture that follows where the sky's light is: a share LIGHT_SKY_CONE_WEIGHT
 * uniform over the cone of half-angle LIGHT_SKY_CONE_RAD around the sun, where the aerosols'
 * forward peak makes the sky brightest, and the rest uniform over the sphere (every direction
 * possible, so the estimator stays unbiased wherever the sky is lit):
 *     p(w) = c [s . w >= cos theta_c] / (2 pi (1 - cos theta_c)) + (1 - c) / (4 pi).
 * The uniform test sky (path.sky = uniform) is the same in every direction: p(w) = 1 / (4 pi). A sample is drawn
 * from three numbers: u0 picks the component, (u1, u2) the direction in it (light_sun.h's cone
 * sampling; the sphere by z = 1 - 2 u1, phi = 2 pi u2).
 * The estimators are combined by the power heuristic with beta = 2 (Veach 1997, sec. 9.2.4):
 * for n_l light samples of density p_l and n_b BSDF samples of density p_b at the same vertex,
 *     w_l = (n_l p_l)^2 / ((n_l p_l)^2 + (n_b p_b)^2),  w_b = (n_b p_b)^2 / (same),
 * which sum to 1 for every direction, so the sum of the weighted estimators is unbiased. */
#ifndef ATMO_RENDER_LIGHT_SKY_H
#define ATMO_RENDER_LIGHT_SKY_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "render/light_sun.h"
#include "atmo/gpu_types.h"
#endif

#define LIGHT_SKY_CONE_WEIGHT 0.5f
#define LIGHT_SKY_CONE_RAD 0.35f

ATMO_FN float light_sky_cone_weight(ATMO_GLOBAL const atmo_gpu_scene *s)
{
    return s->path.sky == ATMO_PATH_SKY_UNIFORM ? 0.0f : LIGHT_SKY_CONE_WEIGHT;
}

ATMO_FN vec3 light_sky_sample(ATMO_GLOBAL const atmo_gpu_scene *s, float u0, float u1, float u2)
{
    if (u0 < light_sky_cone_weight(s))
        return light_sun_sample(v3_from4(s->sun_direction), cosf(LIGHT_SKY_CONE_RAD), u1, u2);
    float z = 1.0f - 2.0f * u1, rr = sqrtf(fmaxf(1.0f - z * z, 0.0f));
    float phi = 2.0f * ATMO_PI * u2;
    return v3(rr * cosf(phi), z, rr * sinf(phi));
}

ATMO_FN float light_sky_pdf(ATMO_GLOBAL const atmo_gpu_scene *s, vec3 w)
{
    float c = light_sky_cone_weight(s);
    float cone = c > 0.0f ? light_sun_pdf(v3_from4(s->sun_direction), cosf(LIGHT_SKY_CONE_RAD), w)
                          : 0.0f;
    return c * cone + (1.0f - c) * (1.0f / (4.0f * ATMO_PI));
}

/* The power heuristic's weight of a strategy with n_a samples of density p_a against one with
 * n_b of density p_b. */
ATMO_FN float light_sky_power(float n_a, float p_a, float n_b, float p_b)
{
    float a = n_a * p_a, b = n_b * p_b;
    return a * a / (a * a + b * b);
}

#endif
