/* cloud_shell_march.h — the cloud shell's own stepping along a view ray (cloud_shell.h's
 * intervals, optical-depth steps and octaves; see the top of cloud_shell.h): the shell's
 * media_interval in the plan's composition (media.h). It asks the sun's occluders
 * (visibility_sun_occluders) and adds the air's light in its part (medium_air_source), so it
 * comes after the visibility and medium_air.h, while the shell's coefficients (cloud_shell.h)
 * come before the media's composition. */
#ifndef ATMO_CLOUD_SHELL_MARCH_H
#define ATMO_CLOUD_SHELL_MARCH_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "atmosphere/atmosphere.h"
#include "common/geometry.h"
#include "common/phase.h"
#include "media/ray.h"
#include "cloud_shell/cloud_shell.h"
#include "media/visibility.h"
#include "media/medium_air.h"
#include "media/quadrature_walk.h"
#include "atmo/gpu_types.h"
#endif

/* The sun's path length through the shell from the point at distance t along the ray. */
ATMO_FN float cloud_shell_chord_at(ATMO_GLOBAL const atmo_gpu_scene *s, const medium_ray *m,
                                   float t)
{
    float R = s->atmosphere.bottom_radius;
    medium_point q = medium_ray_at(m, t, R);
    return cloud_shell_chord(R, cloud_shell_base(s), cloud_shell_top(s), q.h, q.r, q.mu_s);
}

/* One step of length dt of an interval, coefficients taken at its sample point t: the cloud's
 * octaves (their phases in phase[]) and the air's light (its single scattering
 * and, with use_ms, the method's multiple-scattering source: medium_air_source), each
 * attenuated toward the sun by the shell's chord (linear in t from chord0 to chord1) and
 * toward the viewer by the cloud and the air at the sample. Adds the light to *L with the
 * running view transmittance *T, which it advances over the step. */
ATMO_FN void cloud_shell_step(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                              const medium_ray *m, const vec3 *phase, float t, float dt,
                              float chord0, float chord1, int use_ms, int ground, vec3 *L,
                              vec3 *T)
{
    ATMO_GLOBAL const atmo_gpu_atmosphere *a = &s->atmosphere;
    vec3 sigma = v3_from4(s->cloud.extinction);
    medium_point q = medium_ray_at(m, t, a->bottom_radius);
    vec3 sigma_v = v3_add(sigma, atmosphere_extinction(a, q.h));
    /* the occluders' shadows are sharp: asked at the jittered point */
    vec3 sun_e = v3_scale(v3_mul(v3_from4(a->solar_irradiance),
                                 atmosphere_transmittance_to_top(a, transmittance_lut,
                                                                 s->transmittance_width,
                                                                 s->transmittance_height, q.r,
                                                                 q.mu_s)),
                          visibility_sun_occluders(s, ATMO_LUT_ARGS, &q));
    vec3 k_src = v3_mul(v3_mul(sigma, v3_from4(s->cloud.albedo)), sun_e);
    vec3 air = medium_air_source(s, ATMO_LUT_ARGS, &q, m->nu, sun_e, use_ms, ground);
    float sa = 1.0f, sb = 1.0f;
    for (int i = 0; i < ATMO_CLOUD_OCTAVES; i++) {
        vec3 source = v3_scale(v3_mul(k_src, phase[i]), sb);
        if (i == 0)
            source = v3_add(source, air);
        vec3 sig_sun = v3_scale(sigma, sa);
        vec3 w = cloud_exp_mean3(v3_scale(sig_sun, chord0),
                                 v3_add(v3_scale(sig_sun, chord1), v3_scale(sigma_v, dt)), dt);
        *L = v3_add(*L, v3_mul(v3_mul(*T, source), w));
        sa *= CLOUD_OCTAVE_A;
        sb *= CLOUD_OCTAVE_B;
    }
    *T = v3_mul(*T, v3_exp(v3_scale(sigma_v, -dt)));
}

/* One interval [t0, t1] inside the shell, walked up to the cut in sized quadrature pieces
 * (quadrature_walk.h). Its steps end at the cloud's break points, equal in optical depth
 * (channel y) up to the cut, and at the air grid's (grid_d, grid_n: those of medium_integrate's
 * quadrature walk, quadrature_grid_next), so the air inside the shell is resolved at least as
 * finely as the grid resolves it outside: a shell of negligible depth leaves the sky as the air
 * alone makes it. Adds the light to *L with the running view transmittance *T, and multiplies
 * *shell_t by the shell's own transmittance over the interval. */
ATMO_FN void cloud_shell_interval(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                  const medium_ray *m, float t0, float t1, float jitter,
                                  int use_ms, int ground, float grid_d, int grid_n, vec3 *L,
                                  vec3 *T, vec3 *shell_t)
{
    vec3 sigma = v3_from4(s->cloud.extinction), phase[ATMO_CLOUD_OCTAVES];
    float sc = 1.0f; /* the octaves' phases: nu is constant along the ray */
    for (int i = 0; i < ATMO_CLOUD_OCTAVES; i++) {
        phase[i] = i == 0 ? cloud_phase(s, cloud_phase_table, m->nu)
                          : v3(phase_henyey_greenstein(m->nu, s->cloud.g.x * sc),
                               phase_henyey_greenstein(m->nu, s->cloud.g.y * sc),
                               phase_henyey_greenstein(m->nu, s->cloud.g.z * sc));
        sc *= CLOUD_OCTAVE_C;
    }
    float len = fminf(t1 - t0, CLOUD_TAU_CUT / sigma.y), cut = t0 + len;
    int n = s->cloud.steps, j = 1;
    float dt_cloud = len / (float)n, chord0 = cloud_shell_chord_at(s, m, t0);
    /* each step ends at a cloud or a grid break point: at most n + grid_n + 1 of them */
    quadrature_walk w = quadrature_begin_sized(t0, cut, n + grid_n + 1, jitter);
    while (quadrature_more(&w)) {
        float tc = j < n ? t0 + (float)j * dt_cloud : cut;
        quadrature_step_to(&w, fminf(tc, quadrature_grid_next(w.done, grid_d, grid_n)));
        float chord1 = cloud_shell_chord_at(s, m, w.done);
        cloud_shell_step(s, ATMO_LUT_ARGS, m, phase, w.t, w.dt, chord0, chord1, use_ms, ground,
                         L, T);
        if (w.done >= tc)
            j++;
        chord0 = chord1;
    }
    /* what lies beyond the optical-depth cut */
    *T = v3_mul(*T, v3_exp(v3_scale(v3_add(sigma, atmosphere_extinction(
                                                      &s->atmosphere,
                                                      geometry_altitude_at(m->r, m->mu,
                                                                           0.5f * (cut + t1),
                                                                           s->atmosphere.bottom_radius))),
                                    -(t1 - cut))));
    *shell_t = v3_mul(*shell_t, v3_exp(v3_scale(sigma, -(t1 - t0))));
}

#endif
