/* water.h — the sea's optics: Fresnel reflectance of a smooth air-water interface and the sun
 * glint of a wind-roughened sea.
 *
 * Fresnel (Born and Wolf, Principles of Optics, sec. 1.5.2), unpolarised light from air onto a
 * dielectric of relative index eta at incidence cosine c:
 *     c_t = sqrt(1 - (1 - c^2) / eta^2),
 *     r_s = (c - eta c_t) / (c + eta c_t),  r_p = (eta c - c_t) / (eta c + c_t),
 *     F = (r_s^2 + r_p^2) / 2;
 * WATER_INDEX = 1.333 (fresh water at 550 nm; the sea's 1.34 changes F by < 2 %).
 *
 * Glint (Cox and Munk 1954): facet slopes are Gaussian with mean square slope
 * sigma^2 = 0.003 + 0.00512 W (W the wind speed in m/s; WATER_WIND_M_S = 5 gives 0.0286), and
 * the radiance reflected from the sun of irradiance E (normal incidence) is
 *     L = E F(h . s) p(tan beta) / (4 cos(theta_v) cos^4 beta),
 *     p = exp(-tan^2 beta / sigma^2) / (pi sigma^2),
 * with h the half vector of view and sun, beta its angle to the vertical n, theta_v the view's
 * angle to n, times the facets' masking and shadowing G. The slope density p is Beckmann's
 * facet distribution D = p / cos^4 beta with roughness alpha = sigma (Walter et al. 2007, eq.
 * 25), so L / E = F D G / (4 cos theta_v) is the microfacet BRDF F D G / (4 cos theta_v
 * cos theta_s) times cos theta_s, and G is Smith's height-correlated form for it (Heitz 2014,
 * "Understanding the masking-shadowing function", eqs. 72 and 99):
 *     G = 1 / (1 + Lambda(theta_v) + Lambda(theta_s)),
 *     Lambda(theta) = (erf(a) - 1) / 2 + exp(-a^2) / (2 a sqrt(pi)),  a = 1 / (alpha tan theta).
 * G is 1 to < 1e-3 for view and sun within 70 degrees of the vertical (a > 2.2) and keeps the
 * glint's directional albedo below 1 at grazing views, where without it the 1 / cos theta_v
 * factor lets it exceed 1 (2.3 at cos theta_v = 0.01). */
#ifndef ATMO_TERRAIN_WATER_H
#define ATMO_TERRAIN_WATER_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#endif

#define WATER_INDEX 1.333f
#define WATER_WIND_M_S 5.0f

ATMO_FN float water_fresnel(float c, float eta)
{
    c = clamp(c, 0.0f, 1.0f);
    float st2 = (1.0f - c * c) / (eta * eta);
    if (st2 >= 1.0f)
        return 1.0f;
    float ct = sqrtf(1.0f - st2);
    float rs = (c - eta * ct) / (c + eta * ct), rp = (eta * c - ct) / (eta * c + ct);
    return 0.5f * (rs * rs + rp * rp);
}

/* Smith's Lambda of the Beckmann facets of mean square slope sigma2 for a direction of cosine
 * c to the vertical (see the top of the file). */
ATMO_FN float water_smith_lambda(float c, float sigma2)
{
    float s2 = fmaxf(1.0f - c * c, 0.0f);
    if (s2 <= 0.0f)
        return 0.0f;
    float a = c / sqrtf(sigma2 * s2);
    if (a > 9.0f) /* erfc(9) ~ 4e-37: Lambda is 0 in float */
        return 0.0f;
    return 0.5f * (erff(a) - 1.0f) + expf(-a * a) / (2.0f * a * sqrtf(ATMO_PI));
}

/* The glint's bidirectional factor L / E for the unit vertical n, the unit vector v toward the
 * viewer and s toward the sun. */
ATMO_FN float water_glint(vec3 n, vec3 v, vec3 s)
{
    float cv = v3_dot(n, v), cs = v3_dot(n, s);
    if (cv <= 0.0f || cs <= 0.0f)
        return 0.0f;
    vec3 h = v3_normalize(v3_add(v, s));
    float cb = v3_dot(h, n);
    float sigma2 = 0.003f + 0.00512f * WATER_WIND_M_S;
    float tan2 = (1.0f - cb * cb) / (cb * cb);
    float p = expf(-tan2 / sigma2) / (ATMO_PI * sigma2);
    float g = 1.0f / (1.0f + water_smith_lambda(cv, sigma2) + water_smith_lambda(cs, sigma2));
    return water_fresnel(v3_dot(h, s), WATER_INDEX) * p * g / (4.0f * cv * cb * cb * cb * cb);
}

#endif
