/* lut_scattering.h — method "lut": how the 4-D scattering function and the 2-D ground irradiance
 * are laid out in plain float4 buffers, and how they are read back with interpolation written
 * here (no OpenCL images, DESIGN.md). Compiles on the host through compat.h, so the tests call
 * these very functions.
 *
 * The scattered radiance seen from radius r along view cosine mu, with sun cosine mu_s and
 * view-sun cosine nu, is a function of four numbers (spherical symmetry; Bruneton & Neyret 2008).
 * Each gets a texel position p in [0, n - 1] (texel centres at the ends of the range, so the
 * extreme values are stored exactly), following Bruneton 2017 ("Precomputed Atmospheric
 * Scattering: a New Implementation", section "Single scattering / precomputation"):
 *   r:    x_r = rho / H,  rho = sqrt(r^2 - R^2),  H = sqrt(R_top^2 - R^2) (Bruneton's map, more
 *         accurate between texels than one linear in the altitude: docs/notes/lut_method.md).
 *   mu:   split in two halves so that no lookup interpolates between a ray that hits the ground
 *         and one that does not (the radiance jumps there):
 *           sky rays    (texels n/2 .. n-1): x = (d - d_min) / (d_max - d_min), d = distance to
 *                       the top, d_min = R_top - r (straight up), d_max = rho + H (horizon);
 *                       p = n/2 + x (n/2 - 1), so the horizon sits on the last texel;
 *           ground rays (texels 0 .. n/2-1): x = (d - d_min) / (d_max - d_min), d = distance to
 *                       the ground, d_min = r - R (straight down), d_max = rho (horizon);
 *                       p = (n/2 - 1)(1 - x), so the horizon sits on texel 0.
 *         Distances rather than angles put texels where the radiance changes, near the horizon.
 *   mu_s: d = distance from the ground to the top along mu_s, a = (d - d_min)/(d_max - d_min)
 *         with d_min = R_top - R, d_max = H; x = max(1 - a/A, 0) / (1 + a) with
 *         A = -2 mu_s_min R / (d_max - d_min) (Bruneton 2017, the mu_s part of its
 *         GetScatteringTextureUvwzFromRMuMuSNu).
 *         mu_s_min = -0.5 (sun zenith 120 deg), beyond twilight: a camera anywhere in the
 *         atmosphere sees no sunlit air once the sun is lower than about 114 deg, so the clamped
 *         edge texel is already dark. x = 1 is the sun at the zenith.
 *   nu:   x = (nu + 1) / 2. A texel's nu is clamped to what its mu and mu_s allow,
 *         mu mu_s -+ sqrt((1 - mu^2)(1 - mu_s^2)).
 * Layout of one 4-D table (Bruneton packs nu with mu_s the same way): 3-D buffer of width
 * n_nu * n_mu_s (x = i_nu * n_mu_s + i_mu_s), height n_mu, depth n_r, i.e. element
 *     ((i_r n_mu + i_mu) n_nu + i_nu) n_mu_s + i_mu_s.
 * dims[] = {n_nu, n_mu_s, n_mu, n_r} (atmo_gpu_lut.dims). Lookups interpolate linearly
 * in all four positions (16 texels). The ground irradiance table shares the r and mu_s axes:
 * element i_r n_mu_s + i_mu_s, bilinear lookups.
 *
 * Directions for the integrals over the sphere (scattering density, irradiance): at a point with
 * the sun in the x-z plane of the local frame (z up, sun = (sqrt(1 - mu_s^2), 0, mu_s)), the
 * incoming radiance is symmetric in the azimuth phi -> -phi, so a grid of n_theta zenith rings
 * times n_theta azimuths over phi in [0, pi] covers the sphere with its mirror image
 * (midpoint rule: theta_j = (j + 1/2) pi / n, phi_k = (k + 1/2) pi / n,
 * d omega = sin theta_j (pi / n)^2 for each half). No ring lies on the horizon (n even). */
#ifndef ATMO_LUT_SCATTERING_H
#define ATMO_LUT_SCATTERING_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "atmosphere/atmosphere.h"
#include "common/geometry.h"
#include "atmo/gpu_types.h"
#endif

#define LUT_MU_S_MIN (-0.5f)

/* Where the method's tables sit in its buffers (named by the plan, plan_lut.c), in
 * float4 elements (method_lut.h), with N = LUT_TEXELS (one 4-D table), I = n_r n_mu_s (one
 * irradiance table), G = lut.rings^2 (the sphere grid):
 *   scattering_rayleigh: [0, N) single Rayleigh S_R   [N, 2N) orders 2..N summed (phase
 *      included)
 *   scattering_mie: [0, N) single Mie S_M   [N, N + I) indirect ground irradiance, orders
 *      1..N-1   [N + I, 2N + I) the density J of orders 2..N summed (radiance per metre, phase
 *      included), for aerial perspective (method_lut.h's sky_trace over a segment)
 *   scattering_scratch: [0, N) delta scattering (order n)  [N, 2N) density J_n
 *      [2N, 2N + I G) sphere grid   [2N + I G, 2N + I G + I) delta irradiance (order n - 1)
 *      [2N + I G + I, 2N + I G + I + G) the grid's directions (xyz) and solid angles (w), so
 *      the density pass reads them instead of evaluating four trigonometric functions each
 * The knobs are in s->lut (atmo_gpu_lut): dims, steps (segments per texel ray), rings (of the
 * sphere grid) and orders (for reports; the plan lists the passes). */
#define LUT_TEXELS(dims) ((dims)[0] * (dims)[1] * (dims)[2] * (dims)[3])
#define LUT_IRRADIANCE_TEXELS(dims) ((dims)[1] * (dims)[3])
#define LUT_DELTA_IRRADIANCE(dims, G) (2 * LUT_TEXELS(dims) + LUT_IRRADIANCE_TEXELS(dims) * (G))
#define LUT_DIRECTIONS(dims, G) (LUT_DELTA_IRRADIANCE(dims, G) + LUT_IRRADIANCE_TEXELS(dims))
#define LUT_DENSITY_SUM(dims) (LUT_TEXELS(dims) + LUT_IRRADIANCE_TEXELS(dims))

ATMO_FN float lut_h(ATMO_GLOBAL const atmo_gpu_atmosphere *a)
{
    return sqrtf((a->top_radius - a->bottom_radius) * (a->top_radius + a->bottom_radius));
}

ATMO_FN float lut_rho(ATMO_GLOBAL const atmo_gpu_atmosphere *a, float r)
{
    return atmo_safe_sqrt((r - a->bottom_radius) * (r + a->bottom_radius));
}

/* ---- forward maps: value -> texel position in [0, n - 1] ---- */

ATMO_FN float lut_r_position(ATMO_GLOBAL const atmo_gpu_atmosphere *a, float r, int n)
{
    return clamp(lut_rho(a, r) / lut_h(a), 0.0f, 1.0f) * (float)(n - 1);
}

ATMO_FN float lut_mu_position(ATMO_GLOBAL const atmo_gpu_atmosphere *a, float r, float mu,
                              int ground, int n)
{
    float rho = lut_rho(a, r), n_half = (float)(n / 2 - 1);
    if (ground) {
        float d = geometry_distance_to_bottom(r, mu, a->bottom_radius);
        float d_min = r - a->bottom_radius, d_max = rho;
        float x = d_max > d_min ? clamp((d - d_min) / (d_max - d_min), 0.0f, 1.0f) : 0.0f;
        return n_half * (1.0f - x);
    }
    float d = geometry_distance_to_top(r, mu, a->top_radius);
    float d_min = a->top_radius - r, d_max = rho + lut_h(a);
    float x = d_max > d_min ? clamp((d - d_min) / (d_max - d_min), 0.0f, 1.0f) : 0.0f;
    return (float)(n / 2) + n_half * x;
}

ATMO_FN float lut_mu_s_a_max(ATMO_GLOBAL const atmo_gpu_atmosphere *a)
{
    float d_min = a->top_radius - a->bottom_radius, d_max = lut_h(a);
    return -2.0f * LUT_MU_S_MIN * a->bottom_radius / (d_max - d_min);
}

ATMO_FN float lut_mu_s_position(ATMO_GLOBAL const atmo_gpu_atmosphere *a, float mu_s, int n)
{
    float d_min = a->top_radius - a->bottom_radius, d_max = lut_h(a);
    float d = geometry_distance_to_top(a->bottom_radius, atmo_clamp_cos(mu_s), a->top_radius);
    float aa = (d - d_min) / (d_max - d_min), A = lut_mu_s_a_max(a);
    return clamp(fmaxf(1.0f - aa / A, 0.0f) / (1.0f + aa), 0.0f, 1.0f) * (float)(n - 1);
}

ATMO_FN float lut_nu_position(float nu, int n)
{
    return clamp(0.5f * (nu + 1.0f), 0.0f, 1.0f) * (float)(n - 1);
}

/* ---- inverse maps: texel position -> value (texel centres at whole positions) ---- */

ATMO_FN float lut_r_at(ATMO_GLOBAL const atmo_gpu_atmosphere *a, float p, int n)
{
    float rho = lut_h(a) * p / (float)(n - 1);
    return sqrtf(rho * rho + atmo_sq(a->bottom_radius));
}

/* View cosine at position p of the mu axis at radius r; *ground tells which half p is in. */
ATMO_FN float lut_mu_at(ATMO_GLOBAL const atmo_gpu_atmosphere *a, float r, float p, int n,
                        int *ground)
{
    float rho = lut_rho(a, r), H = lut_h(a), n_half = (float)(n / 2 - 1);
    if (p < (float)(n / 2) - 0.5f) {
        *ground = 1;
        float x = 1.0f - p / n_half;
        float d_min = r - a->bottom_radius, d_max = rho;
        float d = d_min + x * (d_max - d_min);
        /* law of cosines in (centre, point, ground point): R^2 = r^2 + d^2 + 2 r d mu */
        return d <= 0.0f ? -1.0f : atmo_clamp_cos(-(rho * rho + d * d) / (2.0f * r * d));
    }
    *ground = 0;
    float x = (p - (float)(n / 2)) / n_half;
    float d_min = a->top_radius - r, d_max = rho + H;
    float d = d_min + x * (d_max - d_min);
    return d <= 0.0f ? 1.0f : atmo_clamp_cos((H * H - rho * rho - d * d) / (2.0f * r * d));
}

ATMO_FN float lut_mu_s_at(ATMO_GLOBAL const atmo_gpu_atmosphere *a, float p, int n)
{
    float x = p / (float)(n - 1);
    float d_min = a->top_radius - a->bottom_radius, H = lut_h(a), A = lut_mu_s_a_max(a);
    float aa = (A - x * A) / (1.0f + x * A);
    float d = d_min + fminf(aa, A) * (H - d_min);
    return d <= 0.0f ? 1.0f
                     : atmo_clamp_cos((H * H - d * d) / (2.0f * a->bottom_radius * d));
}

ATMO_FN float lut_nu_at(float p, int n, float mu, float mu_s)
{
    float nu = -1.0f + 2.0f * p / (float)(n - 1);
    float s = atmo_safe_sqrt((1.0f - mu * mu) * (1.0f - mu_s * mu_s));
    return clamp(nu, mu * mu_s - s, mu * mu_s + s);
}

/* The (r, mu, mu_s, nu) of texel (x, y, z) of a 4-D table (x = i_nu n_mu_s + i_mu_s). */
ATMO_FN void lut_scattering_texel(ATMO_GLOBAL const atmo_gpu_atmosphere *a,
                                  ATMO_GLOBAL const int *dims, int x, int y, int z, float *r,
                                  float *mu, float *mu_s, float *nu, int *ground)
{
    *r = lut_r_at(a, (float)z, dims[3]);
    *mu = lut_mu_at(a, *r, (float)y, dims[2], ground);
    *mu_s = lut_mu_s_at(a, (float)(x % dims[1]), dims[1]);
    *nu = lut_nu_at((float)(x / dims[1]), dims[0], *mu, *mu_s);
}

/* ---- interpolation ---- */

/* Lower texel of the interval holding position p, within texels lo..hi; *f = weight of the
 * upper one. */
ATMO_FN int lut_cell(float p, int lo, int hi, float *f)
{
    int i = (int)floorf(p);
    i = i < lo ? lo : (i > hi - 1 ? hi - 1 : i);
    *f = clamp(p - (float)i, 0.0f, 1.0f);
    return i;
}

/* Quadrilinear lookup of a 4-D table at the given texel positions; p_mu stays in its half. */
ATMO_FN vec3 lut_scattering_fetch(ATMO_GLOBAL const float4 *t, ATMO_GLOBAL const int *dims,
                                  float p_nu, float p_mu_s, float p_mu, float p_r)
{
    int n_nu = dims[0], n_mu_s = dims[1], n_mu = dims[2], n_r = dims[3];
    float f_nu, f_mu_s, f_mu, f_r;
    int i_nu = lut_cell(p_nu, 0, n_nu - 1, &f_nu);
    int i_mu_s = lut_cell(p_mu_s, 0, n_mu_s - 1, &f_mu_s);
    int upper = p_mu >= (float)(n_mu / 2);
    int i_mu = lut_cell(p_mu, upper ? n_mu / 2 : 0, upper ? n_mu - 1 : n_mu / 2 - 1, &f_mu);
    int i_r = lut_cell(p_r, 0, n_r - 1, &f_r);
    vec3 sum = v3(0.0f, 0.0f, 0.0f);
    for (int k = 0; k < 16; k++) {
        int b_nu = k & 1, b_mu_s = (k >> 1) & 1, b_mu = (k >> 2) & 1, b_r = k >> 3;
        float w = (b_nu ? f_nu : 1.0f - f_nu) * (b_mu_s ? f_mu_s : 1.0f - f_mu_s) *
                  (b_mu ? f_mu : 1.0f - f_mu) * (b_r ? f_r : 1.0f - f_r);
        int idx = (((i_r + b_r) * n_mu + i_mu + b_mu) * n_nu + i_nu + b_nu) * n_mu_s + i_mu_s +
                  b_mu_s;
        sum = v3_add(sum, v3_scale(v3_from4(t[idx]), w));
    }
    return sum;
}

/* A 4-D table at (r, mu, mu_s, nu); `ground` must say whether the ray hits the ground. */
ATMO_FN vec3 lut_scattering_lookup(ATMO_GLOBAL const atmo_gpu_atmosphere *a,
                                   ATMO_GLOBAL const float4 *t, ATMO_GLOBAL const int *dims,
                                   float r, float mu, float mu_s, float nu, int ground)
{
    return lut_scattering_fetch(t, dims, lut_nu_position(nu, dims[0]),
                                lut_mu_s_position(a, mu_s, dims[1]),
                                lut_mu_position(a, r, mu, ground, dims[2]),
                                lut_r_position(a, r, dims[3]));
}

/* Bilinear lookup of an irradiance table (r, mu_s axes of the 4-D table). */
ATMO_FN vec3 lut_irradiance_lookup(ATMO_GLOBAL const atmo_gpu_atmosphere *a,
                                   ATMO_GLOBAL const float4 *t, ATMO_GLOBAL const int *dims,
                                   float r, float mu_s)
{
    int n_mu_s = dims[1], n_r = dims[3];
    float f_mu_s, f_r;
    int i = lut_cell(lut_mu_s_position(a, mu_s, n_mu_s), 0, n_mu_s - 1, &f_mu_s);
    int j = lut_cell(lut_r_position(a, r, n_r), 0, n_r - 1, &f_r);
    vec3 lo = v3_add(v3_scale(v3_from4(t[j * n_mu_s + i]), 1.0f - f_mu_s),
                     v3_scale(v3_from4(t[j * n_mu_s + i + 1]), f_mu_s));
    vec3 hi = v3_add(v3_scale(v3_from4(t[(j + 1) * n_mu_s + i]), 1.0f - f_mu_s),
                     v3_scale(v3_from4(t[(j + 1) * n_mu_s + i + 1]), f_mu_s));
    return v3_add(v3_scale(lo, 1.0f - f_r), v3_scale(hi, f_r));
}

/* ---- helpers shared by the precompute kernels and sky_radiance ---- */

/* Optical depth from r along mu to the top of the atmosphere, from the transmittance LUT. */
ATMO_FN vec3 lut_tau_to_top(ATMO_GLOBAL const atmo_gpu_scene *s,
                              ATMO_GLOBAL const float4 *transmittance, float r, float mu)
{
    int w = s->transmittance_width, h = s->transmittance_height;
    float x, y;
    atmosphere_transmittance_position(&s->atmosphere, r, mu, w, h, &x, &y);
    return atmosphere_lut_bilinear_at(transmittance, w, h, x, y);
}

/* Transmittance from r along mu to the point at distance d, radius r_d, view cosine mu_d there
 * (Bruneton 2017, GetTransmittance): the difference of two optical depths to the top, taken
 * before the exponential (the LUT stores tau) and kept >= 0: tau(r, mu) - tau(r_d, mu_d) for
 * a ray that does not hit the ground, and for one that does, the same for the reversed, upward
 * ray, tau(r_d, -mu_d) - tau(r, -mu). */
ATMO_FN vec3 lut_transmittance_between(ATMO_GLOBAL const atmo_gpu_scene *s,
                                       ATMO_GLOBAL const float4 *transmittance, float r, float mu,
                                       float r_d, float mu_d, int ground)
{
    vec3 tau = ground ? v3_sub(lut_tau_to_top(s, transmittance, r_d, -mu_d),
                               lut_tau_to_top(s, transmittance, r, -mu))
                      : v3_sub(lut_tau_to_top(s, transmittance, r, mu),
                               lut_tau_to_top(s, transmittance, r_d, mu_d));
    return v3_exp(v3(-fmaxf(tau.x, 0.0f), -fmaxf(tau.y, 0.0f), -fmaxf(tau.z, 0.0f)));
}

/* Transmittance from r along a ground-hitting mu to the ground at distance d. */
ATMO_FN vec3 lut_transmittance_to_ground(ATMO_GLOBAL const atmo_gpu_scene *s,
                                         ATMO_GLOBAL const float4 *transmittance, float r,
                                         float mu, float d)
{
    float R = s->atmosphere.bottom_radius;
    return lut_transmittance_between(s, transmittance, r, mu, R,
                                     atmo_clamp_cos((r * mu + d) / R), 1);
}

/* Direction k (k = ring * n + azimuth) of the sphere grid with n rings, in the local frame (z up,
 * sun in the x-z plane, azimuth phi in [0, pi]), and its solid angle (one half of the mirror
 * pair phi, -phi). */
ATMO_FN vec3 lut_grid_direction(int k, int n, float *domega)
{
    float step = ATMO_PI / (float)n;
    float theta = ((float)(k / n) + 0.5f) * step, phi = ((float)(k % n) + 0.5f) * step;
    *domega = sinf(theta) * step * step;
    return v3(sinf(theta) * cosf(phi), sinf(theta) * sinf(phi), cosf(theta));
}

/* The sun's direction in that frame. */
ATMO_FN vec3 lut_grid_sun(float mu_s)
{
    return v3(atmo_safe_sqrt(1.0f - mu_s * mu_s), 0.0f, mu_s);
}

#endif
