/* atmosphere.h — the atmosphere model in the kernels: densities, extinction, and the
 * transmittance LUT (its parametrisation and its bilinear lookup).
 *
 * Model (include/atmo/atmosphere.h; defaults Bruneton 2017):
 *   sigma_t(h) = beta_R e^{-h/H_R} + beta_M,t e^{-h/H_M} + beta_O tent(h)      [1/m]
 *   sigma_s(h) = beta_R e^{-h/H_R} (Rayleigh) and beta_M,s e^{-h/H_M} (Mie)
 *
 * Transmittance LUT (Bruneton 2017, "Transmittance" section): texel (u, v) holds the optical depth
 * tau(r, mu) from radius r to the top of the atmosphere along mu, for rays that do not hit the
 * ground; lookups interpolate tau and return exp(-tau). Interpolating tau rather than T (which
 * Bruneton stores) matters near the horizon: T is strongly convex there, so linear interpolation
 * of T overestimates it by up to 1 % at 256 x 64, while tau is nearly linear in the texel
 * coordinates (tests/test_transmittance.c measures both bounds). With H = sqrt(top^2 - bottom^2)
 * and rho = sqrt(r^2 - bottom^2):
 *     x_r  = rho / H,
 *     x_mu = (d - d_min) / (d_max - d_min),   d = distance to top, d_min = top - r, d_max = rho + H
 * so the horizon ray maps to x_mu = 1 for every r and the samples crowd where T changes fastest.
 * Texel centres sit at x = 0 and x = 1 exactly: u = 0.5/n + x (1 - 1/n). The lookup interpolates
 * bilinearly in a plain float4 buffer (row = r, column = mu), as DESIGN.md requires. */
#ifndef ATMO_ATMOSPHERE_KERNEL_H
#define ATMO_ATMOSPHERE_KERNEL_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "common/geometry.h"
#include "media/quadrature_walk.h"
#include "atmo/gpu_types.h"
#endif

ATMO_FN float atmosphere_ozone_tent(ATMO_GLOBAL const atmo_gpu_atmosphere *a, float h)
{
    if (h <= a->ozone_bottom || h >= a->ozone_top)
        return 0.0f;
    if (h < a->ozone_peak)
        return (h - a->ozone_bottom) / (a->ozone_peak - a->ozone_bottom);
    return (a->ozone_top - h) / (a->ozone_top - a->ozone_peak);
}

/* Extinction coefficient (1/m) at altitude h from the relative densities rayleigh =
 * e^{-h / H_R} and mie = e^{-h / H_M} there (callers that also need the scattering coefficients
 * compute the exponentials once). */
ATMO_FN vec3 atmosphere_extinction_at(ATMO_GLOBAL const atmo_gpu_atmosphere *a, float h,
                                      float rayleigh, float mie)
{
    float ozone = atmosphere_ozone_tent(a, h);
    return v3_add(v3_add(v3_scale(v3_from4(a->rayleigh_scattering), rayleigh),
                         v3_scale(v3_from4(a->mie_extinction), mie)),
                  v3_scale(v3_from4(a->ozone_absorption), ozone));
}

/* Extinction coefficient (1/m) at altitude h (m above the ground). */
ATMO_FN vec3 atmosphere_extinction(ATMO_GLOBAL const atmo_gpu_atmosphere *a, float h)
{
    return atmosphere_extinction_at(a, h, expf(-h / a->rayleigh_scale_height),
                                    expf(-h / a->mie_scale_height));
}

ATMO_FN float atmosphere_texcoord_from_unit(float x, int n)
{
    return 0.5f / (float)n + x * (1.0f - 1.0f / (float)n);
}

ATMO_FN float atmosphere_unit_from_texcoord(float u, int n)
{
    return (u - 0.5f / (float)n) / (1.0f - 1.0f / (float)n);
}

/* (r, mu) -> texel position (x, y) in [0, width - 1] x [0, height - 1] (texel centres at whole
 * positions: x = u width - 1/2 of the (u, v) below), for rays that do not hit the ground. The
 * lookups take positions directly, which spares the four divisions of the round trip through
 * (u, v). */
ATMO_FN void atmosphere_transmittance_position(ATMO_GLOBAL const atmo_gpu_atmosphere *a,
                                               float r, float mu, int width, int height,
                                               float *x, float *y)
{
    float H = sqrtf((a->top_radius - a->bottom_radius) * (a->top_radius + a->bottom_radius));
    float rho = atmo_safe_sqrt((r - a->bottom_radius) * (r + a->bottom_radius));
    float d = geometry_distance_to_top(r, mu, a->top_radius);
    float d_min = a->top_radius - r;
    float d_max = rho + H;
    float x_mu = d_max > d_min ? clamp((d - d_min) / (d_max - d_min), 0.0f, 1.0f) : 0.0f;
    *x = (1.0f - sqrtf(1.0f - x_mu)) * (float)(width - 1);
    *y = clamp(rho / H, 0.0f, 1.0f) * (float)(height - 1);
}

/* (r, mu) -> (u, v) in [0, 1]^2, for rays that do not hit the ground. */
ATMO_FN void atmosphere_transmittance_uv(ATMO_GLOBAL const atmo_gpu_atmosphere *a, float r,
                                         float mu, int width, int height, float *u, float *v)
{
    float x, y;
    atmosphere_transmittance_position(a, r, mu, width, height, &x, &y);
    *u = (x + 0.5f) / (float)width;
    *v = (y + 0.5f) / (float)height;
}

/* (u, v) -> (r, mu): the inverse, used to place the LUT's texels. */
ATMO_FN void atmosphere_transmittance_r_mu(ATMO_GLOBAL const atmo_gpu_atmosphere *a, float u,
                                           float v, int width, int height, float *r, float *mu)
{
    float H = sqrtf((a->top_radius - a->bottom_radius) * (a->top_radius + a->bottom_radius));
    float x_mu = 1.0f - atmo_sq(1.0f - atmosphere_unit_from_texcoord(u, width));
    float x_r = atmosphere_unit_from_texcoord(v, height);
    float rho = H * x_r;
    *r = sqrtf(rho * rho + atmo_sq(a->bottom_radius));
    float d_min = a->top_radius - *r;
    float d_max = rho + H;
    float d = d_min + x_mu * (d_max - d_min);
    /* law of cosines in the triangle (centre, point, exit point); d = 0 only at the top looking up */
    *mu = d == 0.0f ? 1.0f : atmo_clamp_cos((H * H - rho * rho - d * d) / (2.0f * *r * d));
}

/* Bilinear fetch from a float4 LUT of width x height at the texel position (x, y) (texel
 * centres at whole positions; clamped at the edges). */
ATMO_FN vec3 atmosphere_lut_bilinear_at(ATMO_GLOBAL const float4 *lut, int width, int height,
                                        float x, float y)
{
    x = clamp(x, 0.0f, (float)(width - 1));
    y = clamp(y, 0.0f, (float)(height - 1));
    int x0 = (int)x, y0 = (int)y;
    int x1 = x0 + 1 < width ? x0 + 1 : x0;
    int y1 = y0 + 1 < height ? y0 + 1 : y0;
    float fx = x - (float)x0, fy = y - (float)y0;
    vec3 t00 = v3_from4(lut[y0 * width + x0]), t10 = v3_from4(lut[y0 * width + x1]);
    vec3 t01 = v3_from4(lut[y1 * width + x0]), t11 = v3_from4(lut[y1 * width + x1]);
    vec3 top = v3_add(v3_scale(t00, 1.0f - fx), v3_scale(t10, fx));
    vec3 bottom = v3_add(v3_scale(t01, 1.0f - fx), v3_scale(t11, fx));
    return v3_add(v3_scale(top, 1.0f - fy), v3_scale(bottom, fy));
}

/* The same at (u, v) in [0, 1]^2 (texel centres at (i + 0.5) / n). */
ATMO_FN vec3 atmosphere_lut_bilinear(ATMO_GLOBAL const float4 *lut, int width, int height,
                                     float u, float v)
{
    return atmosphere_lut_bilinear_at(lut, width, height, u * (float)width - 0.5f,
                                      v * (float)height - 0.5f);
}

/* Transmittance from radius r to the top of the atmosphere along mu (a ray that does not hit the
 * ground), from the LUT of optical depths. */
ATMO_FN vec3 atmosphere_transmittance_to_top(ATMO_GLOBAL const atmo_gpu_atmosphere *a,
                                             ATMO_GLOBAL const float4 *lut, int width,
                                             int height, float r, float mu)
{
    float x, y;
    atmosphere_transmittance_position(a, r, mu, width, height, &x, &y);
    return v3_exp(v3_scale(atmosphere_lut_bilinear_at(lut, width, height, x, y), -1.0f));
}

/* Transmittance to the sun from radius r with sun cosine mu_s: zero when the planet hides the
 * sun's centre (a point sun, like the host reference; the disc's penumbra is left out). */
ATMO_FN vec3 atmosphere_sun_transmittance(ATMO_GLOBAL const atmo_gpu_atmosphere *a,
                                          ATMO_GLOBAL const float4 *lut, int width, int height,
                                          float r, float mu_s)
{
    if (geometry_ray_hits_ground(r, mu_s, a->bottom_radius))
        return v3(0.0f, 0.0f, 0.0f);
    return atmosphere_transmittance_to_top(a, lut, width, height, r, mu_s);
}

/* The discriminant / 4 of |x + t v| = top for a camera above the atmosphere, written
 * top^2 - b^2 = (top - b)(top + b) with b = r sqrt((1 - mu)(1 + mu)) the ray's closest distance
 * to the planet centre, not (top - r)(top + r) + (r mu)^2: far from the planet (r = 1e8 m) the
 * two terms of the latter are ~1e16 m^2, and their float rounding (~4e9 m^2) would move the
 * entry of rays near the limb by ~300 m, which rays grazing the top of the atmosphere see as
 * a change of brightness; b carries ~3 float roundings, ~1 m (tests/test_space_views.c;
 * measured choices: docs/notes/space_views.md). */
ATMO_FN float atmosphere_top_discriminant(ATMO_GLOBAL const atmo_gpu_atmosphere *a, float r,
                                            float mu)
{
    float b = r * atmo_safe_sqrt((1.0f - mu) * (1.0f + mu));
    return (a->top_radius - b) * (a->top_radius + b);
}

/* A camera above the atmosphere sees it from where its ray enters: moves (r, mu, mu_s) there
 * and returns 1, or returns 0 if the ray misses the atmosphere (nothing changed). With t0 the
 * distance to the entry, r' = top, r' mu' = r mu + t0 = -sqrt(discriminant) exactly, and
 * mu_s' = (r mu_s + t0 nu) / top. Rays from inside are left as they are.
 * The discriminant comes from atmosphere_top_discriminant. */
ATMO_FN int atmosphere_enter(ATMO_GLOBAL const atmo_gpu_atmosphere *a, float *r, float *mu,
                             float *mu_s, float nu)
{
    if (*r <= a->top_radius)
        return 1;
    float disc = atmosphere_top_discriminant(a, *r, *mu);
    if (*mu >= 0.0f || disc < 0.0f)
        return 0;
    float t0 = -*r * *mu - sqrtf(disc);
    *mu_s = atmo_clamp_cos((*r * *mu_s + t0 * nu) / a->top_radius);
    *mu = -sqrtf(disc) / a->top_radius;
    *r = a->top_radius;
    return 1;
}

/* Distance from radius r along mu to where the ray enters the atmosphere: 0 from inside, the
 * t0 of atmosphere_enter from above (meaningful where that returns 1). A segment [0, d] of a
 * ray from above keeps d - t0 of its length once atmosphere_enter has moved its start. */
ATMO_FN float atmosphere_entry_distance(ATMO_GLOBAL const atmo_gpu_atmosphere *a, float r,
                                        float mu)
{
    if (r <= a->top_radius)
        return 0.0f;
    return fmaxf(-r * mu - atmo_safe_sqrt(atmosphere_top_discriminant(a, r, mu)), 0.0f);
}

/* The length of a ray from radius r inside the atmosphere along mu to where it leaves it:
 * to the ground where `ground` (the ray meets the ground: geometry_ray_hits_ground, or a
 * quadrature's choice of direction), else to the top (m). */
ATMO_FN float atmosphere_ray_length(ATMO_GLOBAL const atmo_gpu_atmosphere *a, float r, float mu,
                                    int ground)
{
    return ground ? geometry_distance_to_bottom(r, mu, a->bottom_radius)
                  : geometry_distance_to_top(r, mu, a->top_radius);
}

/* Radiance of the sun disc outside the atmosphere: E over its solid angle 2 pi (1 - cos alpha)
 * (cos_alpha = the scene's sun_direction.w). */
ATMO_FN vec3 atmosphere_sun_disc_radiance(ATMO_GLOBAL const atmo_gpu_atmosphere *a,
                                          float cos_alpha)
{
    return v3_scale(v3_from4(a->solar_irradiance), 1.0f / (2.0f * ATMO_PI * (1.0f - cos_alpha)));
}

/* Optical depth from radius r to the top along mu by the midpoint rule with n segments, the
 * quadrature walk's equal ones (quadrature_walk.h; used to fill the LUT; the integrand is
 * smooth, so the error falls as 1/n^2). */
ATMO_FN vec3 atmosphere_optical_depth_to_top(ATMO_GLOBAL const atmo_gpu_atmosphere *a, float r,
                                             float mu, int n)
{
    float d = geometry_distance_to_top(r, mu, a->top_radius);
    quadrature_walk q = quadrature_begin_equal(d, n);
    vec3 tau = v3(0.0f, 0.0f, 0.0f);
    while (quadrature_next(&q) != QUADRATURE_END) {
        float h = geometry_altitude_at(r, mu, q.t, a->bottom_radius);
        tau = v3_add(tau, atmosphere_extinction(a, h));
    }
    return v3_scale(tau, q.step);
}

#endif
