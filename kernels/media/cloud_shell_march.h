/* cloud_shell_march.h — the cloud shell's own stepping along a view ray (cloud_shell.h's
 * intervals, optical-depth steps and octaves; see the top of cloud_shell.h): the shell's
 * media_interval in the plan's composition (media.h). It asks the sun's occluders
 * (visibility_sun_occluders), so it comes after the visibility composition (visibility.h),
 * while the shell's coefficients (cloud_shell.h) come before the media's. */
#ifndef ATMO_CLOUD_SHELL_MARCH_H
#define ATMO_CLOUD_SHELL_MARCH_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "atmosphere/atmosphere.h"
#include "common/geometry.h"
#include "common/phase.h"
#include "media/ray.h"
#include "media/cloud_shell.h"
#include "media/visibility.h"
#include "atmo/gpu_types.h"
#endif

/* The sun's transmittance through the atmosphere to the point at distance t along the ray (no
 * shadows), and in *chord its path length through the shell. */
ATMO_FN vec3 cloud_air_sun_transmittance(ATMO_GLOBAL const atmo_gpu_scene *s,
                                         ATMO_GLOBAL const float4 *transmittance_lut, const medium_ray *m,
                                         float t, float *chord)
{
    ATMO_GLOBAL const atmo_gpu_atmosphere *a = &s->atmosphere;
    medium_point q = medium_ray_at(m, t, a->bottom_radius);
    *chord = cloud_shell_chord(a->bottom_radius, cloud_shell_base(s), cloud_shell_top(s), q.h,
                               q.r, q.mu_s);
    return atmosphere_transmittance_to_top(a, transmittance_lut, s->transmittance_width,
                                           s->transmittance_height, q.r, q.mu_s);
}

/* One interval [t0, t1] inside the shell: steps equal in optical depth (channel y), octaves of
 * multiple scattering, the air's extinction (at the interval's middle) on top. Adds the light
 * to *L with the running view transmittance *T, and multiplies *shell_t by the shell's own
 * transmittance over the interval. */
ATMO_FN void cloud_shell_interval(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                  const medium_ray *m, float t0, float t1, float jitter, vec3 *L,
                                  vec3 *T, vec3 *shell_t)
{
    ATMO_GLOBAL const atmo_gpu_atmosphere *a = &s->atmosphere;
    vec3 E = v3_from4(a->solar_irradiance);
    vec3 sigma = v3_from4(s->cloud.extinction), albedo = v3_from4(s->cloud.albedo);
    vec3 sigma_v = v3_add(sigma, atmosphere_extinction(
                                     a, geometry_altitude_at(m->r, m->mu, 0.5f * (t0 + t1),
                                                             a->bottom_radius)));
    float len = fminf(t1 - t0, CLOUD_TAU_CUT / sigma.y);
    int n = s->cloud.steps;
    float dt = len / (float)n;
    vec3 p0 = cloud_phase(s, cloud_phase_table, m->nu);
    vec3 k_src = v3_mul(v3_mul(sigma, albedo), E);
    float chord0, chord1;
    vec3 sun0 = cloud_air_sun_transmittance(s, transmittance_lut, m, t0, &chord0);
    for (int j = 0; j < n; j++) {
        float ta = t0 + (float)j * dt;
        vec3 sun1 = cloud_air_sun_transmittance(s, transmittance_lut, m, ta + dt, &chord1);
        /* the occluders' shadows are sharp: asked at a jittered point of the step */
        medium_point q = medium_ray_at(m, ta + jitter * dt, a->bottom_radius);
        vec3 sun_t = v3_scale(sun0, visibility_sun_occluders(s, ATMO_LUT_ARGS, &q));
        float sa = 1.0f, sb = 1.0f, sc = 1.0f;
        for (int i = 0; i < ATMO_CLOUD_OCTAVES; i++) {
            vec3 p = i == 0 ? p0
                            : v3(phase_henyey_greenstein(m->nu, s->cloud.g.x * sc),
                                 phase_henyey_greenstein(m->nu, s->cloud.g.y * sc),
                                 phase_henyey_greenstein(m->nu, s->cloud.g.z * sc));
            vec3 sig_sun = v3_scale(sigma, sa);
            vec3 source = v3_scale(v3_mul(v3_mul(k_src, p), sun_t), sb);
            vec3 x0 = v3_scale(sig_sun, chord0);
            vec3 w = cloud_exp_mean3(x0, v3_add(v3_scale(sig_sun, chord1), v3_scale(sigma_v, dt)),
                                     dt);
            *L = v3_add(*L, v3_mul(v3_mul(*T, source), w));
            sa *= CLOUD_OCTAVE_A;
            sb *= CLOUD_OCTAVE_B;
            sc *= CLOUD_OCTAVE_C;
        }
        *T = v3_mul(*T, v3_exp(v3_scale(sigma_v, -dt)));
        chord0 = chord1;
        sun0 = sun1;
    }
    /* what lies beyond the optical-depth cut */
    *T = v3_mul(*T, v3_exp(v3_scale(sigma_v, -(t1 - t0 - len))));
    *shell_t = v3_mul(*shell_t, v3_exp(v3_scale(sigma, -(t1 - t0))));
}

/* media_interval's part [t0, t1] of the shell (use_ms and ground unused: the octaves stand
 * for the shell's multiple scattering, the air's is not added inside it). */
ATMO_FN void cloud_shell_media_interval(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                        const medium_ray *m, float t0, float t1, float jitter,
                                        int use_ms, int ground, vec3 *L, vec3 *T, vec3 *medium_t)
{
    cloud_shell_interval(s, ATMO_LUT_ARGS, m, t0, t1, jitter, L, T, medium_t);
}

#endif
