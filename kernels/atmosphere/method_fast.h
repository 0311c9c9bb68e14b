/* method_fast.h — atmosphere method "fast": per-frame LUTs in the spirit of Hillaire 2020
 * (sec. 5.3, the sky-view LUT), over the march of ms_lut.h.
 *
 * The camera's radius r_c and sun cosine mu_s,c are fixed for a frame, so the sky seen from
 * the camera is a function of two angles only: the view zenith angle theta and the azimuth phi
 * from the sun (the sky is symmetric about the sun's vertical plane, so phi in [0, pi]). The
 * sky-view LUT (buffer sky_view_lut, s->sky_view.width = W columns of phi, s->sky_view.height
 * = 2 n rows) holds the march of ms_lut.h (single scattering + sigma_s Psi_ms, the lit ground,
 * no sun disc) with s->sky_view.steps segments (growing from the camera, kernels/media/medium.h,
 * so they resolve the aerosols' steep density near the ground) at their midpoints, in three
 * planes (fast_luts.cl): the view-sun cosine nu is constant along a straight ray, so the phase
 * functions factor out of single scattering, and the LUT holds its Rayleigh and Mie integrals
 * without them, multiplied by p_R(nu) and p_M(nu) of each pixel's own ray at lookup; the third
 * plane holds the rest (multiple scattering, the ground). The aerosol peak around the sun,
 * narrower than a LUT column, then comes from the exact phase function instead of the
 * interpolation of texels (measured choices: docs/notes/fast_method.md). A texel's march is of
 * the air alone (medium_integrate_air: no opaque surface ends it, the occluders' shadows on its
 * samples stay): a texel's ray is one 3-D ray from the camera, on one side of the sun's vertical
 * plane, and a terrain or object it met would lend its light to the sky rows next to it on both
 * sides; the rays that meet a surface are the render's (terrain_stage.h, sky.cl) and never read
 * the LUT. Each plane has two halves
 * of n rows:
 *   rows 0 .. n-1 : rays that leave the atmosphere, x = 1 - sqrt(1 - theta / theta_h)
 *   rows n .. 2n-1: rays that hit the ground,       x = sqrt((theta - theta_h) / (pi - theta_h))
 * with theta_h = acos(-sqrt(r_c^2 - R^2) / r_c) the zenith angle of the horizon, texel centres
 * at x = 0 and 1 and columns at phi = pi i / (W - 1). Both mappings put most rows next to the
 * horizon, where the sky changes fastest (Hillaire's non-linear latitude mapping), and a lookup
 * interpolates within one half only, so the step between sky and ground at the horizon is not
 * smeared over a texel (the horizon band of a single mapping). Lookups are bilinear, written here
 * (DESIGN.md: LUTs in plain buffers).
 *
 * sky_trace: rays from the camera's (r_c, mu_s,c) read the LUT; any other ray (a camera above
 * the atmosphere or the air of path.clouds = volume, where the plan builds no sky-view LUT:
 * host/features/atmosphere/plan_fast.c; or a probe from elsewhere) and every
 * segment ending at a surface fall back to the march with one random offset per sample, like
 * method "march". The view transmittance of a whole ray comes from the transmittance LUT: to
 * the top, or for a ray that hits the ground at distance d the ratio T(R, -mu_g) / T(r, -mu)
 * of the reversed rays (mu_g = (r mu + d) / R; Bruneton 2017, GetTransmittance). The sun disc
 * is added apart from the LUT: E T(r, mu) / Omega_sun when the ray sees the sun's disc and not
 * the ground.
 * The sky-view LUT's inputs (r_c, mu_s,c) are those sky.cl computes for every pixel. */
#ifndef ATMO_METHOD_FAST_H
#define ATMO_METHOD_FAST_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "common/rng.h"
#include "atmosphere/sky_method.h"
#include "atmosphere/ms_lut.h"
#include "media/medium.h"
#endif

/* The camera's sun cosine, computed as sky.cl computes it. */
ATMO_FN float fast_camera_mu_s(ATMO_GLOBAL const atmo_gpu_scene *s)
{
    vec3 up = v3_from4(s->camera.local_up), sun = v3_from4(s->sun_direction);
    return v3_dot(up, sun);
}

/* arccos(x) for x in [-1, 1] from arcsin's odd series in a reduced argument: arccos(x) =
 * pi/2 - arcsin(x) for |x| <= 1/2, and 2 arcsin(sqrt((1 - |x|) / 2)) (mirrored by
 * pi - arccos(|x|) for x < 0) beyond, with arcsin(s) = s + s z P(z), z = s^2 <= 1/4, P the
 * degree-4 minimax polynomial of Moshier's Cephes library (single precision: within ~1 ulp).
 * One sqrt and five multiply-adds instead of the library's acosf (Sleef on PoCL), a quarter of
 * fast's render kernel on a panorama; measured within 3.0e-7 rad of acos in double
 * (tests/test_kernel_math.c; acosf: 2.1e-7). The LUT's texels are placed with the same function. */
ATMO_FN float fast_acos(float x)
{
    float a = fminf(fabsf(x), 1.0f);
    int far = a > 0.5f;
    float z = far ? 0.5f * (1.0f - a) : a * a;
    float s = far ? sqrtf(z) : a;
    float p = 4.2163199048e-2f;
    p = p * z + 2.4181311049e-2f;
    p = p * z + 4.5470025998e-2f;
    p = p * z + 7.4953002686e-2f;
    p = p * z + 1.6666752422e-1f;
    float q = s + s * z * p; /* arcsin(s) */
    if (far)
        return x < 0.0f ? ATMO_PI - 2.0f * q : 2.0f * q;
    return x < 0.0f ? 0.5f * ATMO_PI + q : 0.5f * ATMO_PI - q;
}

ATMO_FN float fast_horizon_zenith(ATMO_GLOBAL const atmo_gpu_atmosphere *a, float r)
{
    float rho = atmo_safe_sqrt((r - a->bottom_radius) * (r + a->bottom_radius));
    return fast_acos(atmo_clamp_cos(-rho / r));
}

/* Texel (i, j) of the sky-view LUT -> (mu, cos phi) of its ray. The rows at x = 1 of the sky
 * half and x = 0 of the ground half sit a hair (1e-4 rad) off the horizon on their own side. */
ATMO_FN void fast_sky_view_ray(ATMO_GLOBAL const atmo_gpu_scene *s, int i, int j, int width,
                               int height, float *mu, float *cos_phi)
{
    int n = height / 2;
    float theta_h = fast_horizon_zenith(&s->atmosphere, s->camera.local_up.w);
    float theta;
    if (j < n) {
        float x = (float)j / (float)(n - 1);
        theta = fminf(theta_h * (1.0f - atmo_sq(1.0f - x)), theta_h - 1e-4f);
    } else {
        float x = (float)(j - n) / (float)(n - 1);
        theta = fmaxf(theta_h + (ATMO_PI - theta_h) * x * x, theta_h + 1e-4f);
    }
    *mu = cosf(theta);
    *cos_phi = cosf(ATMO_PI * (float)i / (float)(width - 1));
}

/* Bilinear lookup of the sky-view LUT for a ray (mu, nu) from the camera: its three planes
 * interpolated at one place, single scattering's with the phase functions of the ray's nu. */
ATMO_FN vec3 fast_sky_view_lookup(ATMO_GLOBAL const atmo_gpu_scene *s,
                                  ATMO_GLOBAL const float4 *lut, float mu, float mu_s, float nu,
                                  int hits_ground)
{
    int width = s->sky_view.width, n = s->sky_view.height / 2, plane = 2 * n * width;
    float theta_h = fast_horizon_zenith(&s->atmosphere, s->camera.local_up.w);
    float theta = fast_acos(mu);
    float x = hits_ground
                  ? atmo_safe_sqrt((theta - theta_h) / (ATMO_PI - theta_h))
                  : 1.0f - atmo_safe_sqrt(1.0f - theta / theta_h);
    float y = clamp(x, 0.0f, 1.0f) * (float)(n - 1);
    float denom = atmo_safe_sqrt((1.0f - mu * mu) * (1.0f - mu_s * mu_s));
    float cos_phi = denom > 1e-6f ? atmo_clamp_cos((nu - mu * mu_s) / denom) : 1.0f;
    float c = clamp(fast_acos(cos_phi) / ATMO_PI, 0.0f, 1.0f) * (float)(width - 1);
    int x0 = (int)c, y0 = (int)y;
    int x1 = x0 + 1 < width ? x0 + 1 : x0;
    int y1 = y0 + 1 < n ? y0 + 1 : y0;
    float fx = c - (float)x0, fy = y - (float)y0;
    int row0 = hits_ground ? n : 0;
    int i00 = (row0 + y0) * width + x0, i10 = (row0 + y0) * width + x1;
    int i01 = (row0 + y1) * width + x0, i11 = (row0 + y1) * width + x1;
    float w00 = (1.0f - fx) * (1.0f - fy), w10 = fx * (1.0f - fy);
    float w01 = (1.0f - fx) * fy, w11 = fx * fy;
    float weight[3] = {phase_rayleigh(nu), media_mie_phase(&s->atmosphere, nu), 1.0f};
    vec3 sum = v3(0.0f, 0.0f, 0.0f);
    for (int k = 0; k < 3; k++) {
        ATMO_GLOBAL const float4 *p = lut + k * plane;
        vec3 top = v3_add(v3_scale(v3_from4(p[i00]), w00), v3_scale(v3_from4(p[i10]), w10));
        vec3 bottom = v3_add(v3_scale(v3_from4(p[i01]), w01), v3_scale(v3_from4(p[i11]), w11));
        vec3 part = v3_add(top, bottom);
        sum = v3_add(sum, v3_scale(part, weight[k]));
    }
    return sum;
}

/* The method's ray (sky_method.h): the camera's rays over their whole length from the LUT,
 * any other ray and every segment by the march (march_trace). */
ATMO_FN void sky_trace(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS, const medium_ray *m,
                       float t_max, rng_stream *g, vec3 *sky, vec3 *sun, vec3 *view_t)
{
    ATMO_GLOBAL const atmo_gpu_atmosphere *a = &s->atmosphere;
    float r_c = s->camera.local_up.w;
    int from_camera = s->sky_view.width > 0 && fabsf(m->r - r_c) <= 1e-6f * r_c &&
                      fabsf(m->mu_s - fast_camera_mu_s(s)) <= 1e-6f;
    if (!from_camera || t_max < INFINITY) {
        march_trace(s, ATMO_LUT_ARGS, m, t_max, rng_next(g), sky, sun, view_t);
        return;
    }
    int hits_ground = geometry_ray_hits_ground(m->r, m->mu, a->bottom_radius);
    *sky = fast_sky_view_lookup(s, sky_view_lut, m->mu, m->mu_s, m->nu, hits_ground);
    *sun = v3(0.0f, 0.0f, 0.0f);
    int tw = s->transmittance_width, th = s->transmittance_height;
    if (hits_ground) {
        float d = geometry_distance_to_bottom(m->r, m->mu, a->bottom_radius);
        float mu_g = atmo_clamp_cos((m->r * m->mu + d) / a->bottom_radius);
        vec3 up_g = atmosphere_transmittance_to_top(a, transmittance_lut, tw, th,
                                                    a->bottom_radius, -mu_g);
        vec3 up_c = atmosphere_transmittance_to_top(a, transmittance_lut, tw, th, m->r, -m->mu);
        *view_t = v3(fminf(up_g.x / up_c.x, 1.0f), fminf(up_g.y / up_c.y, 1.0f),
                     fminf(up_g.z / up_c.z, 1.0f));
        return;
    }
    *view_t = atmosphere_transmittance_to_top(a, transmittance_lut, tw, th, m->r, m->mu);
    if (m->nu >= s->sun_direction.w)
        *sun = v3_mul(atmosphere_sun_disc_radiance(a, s->sun_direction.w), *view_t);
}

#endif
