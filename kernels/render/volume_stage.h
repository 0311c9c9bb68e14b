/* volume_stage.h — the path tracer's scattering events in the fBm cloud layer (path.clouds =
 * volume, built with -DATMO_CLOUDS_VOLUME: the layer is then no medium of the methods, whose
 * sky_trace gives the air's light alone, in the layer's shadow): the stage functions the loop (path.h) calls for a
 * segment's free flight, the sun's transmittance through the layer, and a cloud vertex's phase
 * function and continuation. Without the layer's volume they are the identity (no event, no
 * attenuation), so the loop is the same source for every build.
 *
 * The radiative transfer along a segment of the path [0, end] (end: the surface it hits, or
 * infinity), with the air (sigma_a: its method) and the layer (sigma_c) both present:
 *     L(0) = int_0^end T_a T_c (sigma_s,a J_a + sigma_s,c J_c) dt + T_a(0, end) T_c(0, end) L_end
 * The free flight through the layer alone (cloud_walk.h: clouds_free_flight, spectral tracking
 * against the layer's majorant) draws t_c with density T_c(0, t_c) sigma_s,c(t_c) (weight w),
 * or none with probability T_c(0, end). Since P(t_c > t) = T_c(0, t), the estimator
 *     t_c drawn:  int_0^{t_c} T_a sigma_s,a J_a dt + w T_a(0, t_c) J_c(t_c)
 *     none:       int_0^end  T_a sigma_s,a J_a dt + w T_a(0, end) L_end
 * has the expectation L(0): the air's part is sky_trace with t_max = t_c (or end) and the
 * method's transmittance T_a, and J_c(t_c) = int p_c L_in dw is the next vertex: next-event
 * estimation to the sun (phase p_c(nu) times the sunlight, path.h's one shadow function) and a
 * continuation drawn from p_c mixed with p_c's lobe around the sun (clouds_phase_direction,
 * phase_table.h's sun guiding: the Mie table by its CDF, Henyey-Greenstein, Jendersie-d'Eon;
 * weight p / pdf per wavelength). The sky reaches a cloud vertex only by the
 * phase-sampled continuation (no sky sampling there, so no MIS weight: 1). The air's J_a is the
 * method's, with the sun at each of its samples seen through the layer: the integrator
 * multiplies the sunlight (and the multiple-scattering source, as the marched layer's does) by
 * the layer's ratio-tracked transmittance toward the sun (media/visibility.h,
 * visibility_air_volume), so the air in the layer's shadow is dark (light shafts, the air under
 * an overcast). The air's light along a segment takes the layer's spectral-tracking weight w of
 * the whole segment, exact for a grey layer (w = 1 with albedo 1; clouds.extinction_per_m > 0
 * gives the same extinction in every channel).
 * Units: radiance W m^-2 sr^-1 nm^-1, metres, phase per steradian. */
#ifndef ATMO_RENDER_VOLUME_STAGE_H
#define ATMO_RENDER_VOLUME_STAGE_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "common/rng.h"
#include "media/ray.h"
#ifdef ATMO_CLOUDS_VOLUME
#include "media/cloud_layer.h"
#include "media/cloud_walk.h"
#endif
#include "atmo/gpu_types.h"
#endif

/* The distance of the first scattering in the layer along m before `end`, or -1 where the ray
 * passes; *w the tracking weight (1 without the layer). */
ATMO_FN float volume_flight(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                            const medium_ray *m, float end, rng_stream *g, vec3 *w)
{
#ifdef ATMO_CLOUDS_VOLUME
    float t;
    return clouds_free_flight(s, ATMO_LUT_ARGS, m, end, g, &t, w) ? t : -1.0f;
#else
    (void)s, (void)m, (void)end, (void)g;
    *w = v3(1.0f, 1.0f, 1.0f);
    return -1.0f;
#endif
}

/* The layer's transmittance toward the sun from q, by ratio tracking (1 without the layer). */
ATMO_FN vec3 volume_sun_transmittance(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                      const medium_point *q, rng_stream *g)
{
#ifdef ATMO_CLOUDS_VOLUME
    return clouds_sun_ratio(s, ATMO_LUT_ARGS, q, g);
#else
    (void)s, (void)q, (void)g;
    return v3(1.0f, 1.0f, 1.0f);
#endif
}

/* The layer's phase function per steradian between the ray's direction and w, nu = d . w. */
ATMO_FN vec3 volume_phase(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS, float nu)
{
#ifdef ATMO_CLOUDS_VOLUME
    return clouds_phase(s, clouds_phase_table, nu);
#else
    (void)s, (void)nu;
    return v3(0.0f, 0.0f, 0.0f);
#endif
}

/* The factor on the throughput of the Russian roulette's survival probability at a cloud
 * vertex reached along d: phase_table.h's cloud_roulette_gain of the layer's phase between d
 * and the sun (the continuation mostly keeps d: the forward peak), so that paths the sun
 * guiding sent toward the sun survive it; 1 without the layer's volume. */
ATMO_FN float volume_roulette_gain(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS, vec3 d)
{
#ifdef ATMO_CLOUDS_VOLUME
    return cloud_roulette_gain(clouds_phase(s, clouds_phase_table,
                                            v3_dot(d, v3_from4(s->sun_direction))));
#else
    (void)s, (void)d;
    return 1.0f;
#endif
}

/* A new direction at a cloud vertex reached along d by a path of throughput beta (u1, u2, and g
 * for Jendersie-d'Eon):
 * cloud_layer.h's clouds_phase_direction, the phase function's lobe around d mixed with its
 * lobe around the sun's direction (clouds.sun_guiding); *weight the phase over the density it
 * was drawn with. */
ATMO_FN vec3 volume_phase_direction(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS, vec3 d,
                                    vec3 beta, float u1, float u2, rng_stream *g, vec3 *weight)
{
#ifdef ATMO_CLOUDS_VOLUME
    return clouds_phase_direction(s, clouds_phase_table, clouds_phase_cdf, d,
                                  v3_from4(s->sun_direction), beta, u1, u2, g, weight);
#else
    (void)s, (void)beta, (void)u1, (void)u2, (void)g;
    *weight = v3(0.0f, 0.0f, 0.0f);
    return d;
#endif
}

#endif
