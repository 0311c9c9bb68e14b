/* volume_stage.h — the path tracer's scattering events in its volume media (path.clouds =
 * volume: the fBm cloud layer, a medium that no method sees, whose sky_trace gives the air's
 * light alone, in the layer's shadow; path.air = medium: the air itself, below): the stage
 * functions the loop (path.h) calls for a volume vertex's phase function and continuation
 * (the segment's free flight is path.h's path_flight on media_walk.h's iterator, and the sun's
 * transmittance through the volume media its shadow query). All of them run on the one
 * majorant walk in volume mode (media/media_walk.h) over the plan's composed volume medium
 * (media.h's media_volume_*); without one they are the identity (no event, no attenuation, no
 * random number), so the loop is the same source for every build.
 *
 * The radiative transfer along a segment of the path [0, end] (end: the surface it hits, or
 * infinity), with the air (sigma_a: its method) and the volume medium (sigma_c) both present:
 *     L(0) = int_0^end T_a T_c (sigma_s,a J_a + sigma_s,c J_c) dt + T_a(0, end) T_c(0, end) L_end
 * The free flight through the volume medium alone (media_walk_volume_flight: spectral tracking
 * against its majorant) draws t_c with density T_c(0, t_c) sigma_s,c(t_c) (weight w), or none
 * with probability T_c(0, end). Since P(t_c > t) = T_c(0, t), the estimator
 *     t_c drawn:  int_0^{t_c} T_a sigma_s,a J_a dt + w T_a(0, t_c) J_c(t_c)
 *     none:       int_0^end  T_a sigma_s,a J_a dt + w T_a(0, end) L_end
 * has the expectation L(0): the air's part is sky_trace with t_max = t_c (or end) and the
 * method's transmittance T_a, and J_c(t_c) = int p_c L_in dw is the next vertex: next-event
 * estimation to the sun (phase p_c(nu) times the sunlight, path.h's one shadow function, whose
 * transmittance through the volume medium is the walk's ratio tracking) and a continuation
 * drawn from p_c mixed with p_c's lobe around the sun (the layer's clouds_phase_direction,
 * phase_table.h's sun guiding: the Mie table by its CDF, Henyey-Greenstein, Jendersie-d'Eon;
 * weight p / pdf per wavelength). The sky reaches a volume vertex only by the phase-sampled
 * continuation (no sky sampling there, so no MIS weight: 1). The air's J_a is the method's,
 * with the sun at each of its samples seen through the volume medium: the integrator multiplies
 * the sunlight (and the multiple-scattering source, as the marched layer's does) by the walk's
 * ratio-tracked transmittance toward the sun (media_walk_volume_sun), so the air in the layer's
 * shadow is dark (light shafts, the air under an overcast). The air's light along a segment
 * takes the volume medium's spectral-tracking weight w of the whole segment, exact for a grey
 * medium (w = 1 with albedo 1; clouds.extinction_per_m > 0 gives the same extinction in every
 * channel).
 * With the air a volume medium (path.air = medium, MEDIA_VOLUME_AIR) the same estimator holds
 * with sigma_a moved from the method into the walk: the free flight draws t_c with density
 * T(0, t_c) sigma_s,k(t_c) over the components k (cloud, air Rayleigh, air aerosols; T the
 * transmittance of air and clouds together, absorption folded into the weight w), or none with
 * probability T(0, end), so
 *     t_c drawn:  w J_k(t_c)        none:  w L_end
 * has the expectation L(0) with no method term: J_k is the next vertex with component k's
 * phase (the air's sampled exactly, media_air_direction), and an escaping ray's L_end is the
 * sun's disc alone. The air's J_a = J_sun + J_ms splits: its single scattering of the sun
 * (J_sun = int p_a E T_sun) moves from the vertex to every tentative point of the flight
 * (path.h's path_flight: the collision estimator sum_i w_i sigma_s,a J_sun(x_i) / sigma_bar_i,
 * whose expectation is int_0^t_c-or-end T sigma_s,a J_sun dt, the same as that of w J_sun at
 * the vertex), and the vertex keeps J_ms, its continuation.
 * Units: radiance W m^-2 sr^-1 nm^-1, metres, phase per steradian. */
#ifndef ATMO_RENDER_VOLUME_STAGE_H
#define ATMO_RENDER_VOLUME_STAGE_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "common/rng.h"
#include "media/ray.h"
#include "media/media.h"
#include "media/media_walk.h"
#include "atmo/gpu_types.h"
#endif

/* The volume medium's phase function per steradian between the ray's direction and w,
 * nu = d . w (0 without one). */
ATMO_FN vec3 volume_phase(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS, float nu)
{
    return media_volume_phase(s, ATMO_LUT_ARGS, nu);
}

/* The factor on the throughput of the Russian roulette's survival probability at a volume
 * vertex reached along d: the medium's roulette gain of its phase between d and the sun
 * (phase_table.h's cloud_roulette_gain: the continuation mostly keeps d, the forward peak), so
 * that paths the sun guiding sent toward the sun survive it; 1 without a volume medium. */
ATMO_FN float volume_roulette_gain(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS, vec3 d)
{
    return media_volume_roulette_gain(s, ATMO_LUT_ARGS, v3_dot(d, v3_from4(s->sun_direction)));
}

/* A new direction at a volume vertex of component k (MEDIA_WALK_VOLUME_*) reached along d by a
 * path of throughput beta (u1, u2, and g for Jendersie-d'Eon): the volume medium's phase
 * function's lobe around d mixed with its lobe around the sun's direction
 * (clouds.sun_guiding), or the air's Rayleigh or aerosol phase sampled exactly
 * (media_air_direction: Draine's sampler with g = 0, alpha = 1 for Rayleigh; Henyey-Greenstein
 * or Cornette-Shanks; phase.h); *weight the phase over the density it was drawn with (0
 * without a volume medium). */
ATMO_FN vec3 volume_phase_direction(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS, int k,
                                    vec3 d, vec3 beta, float u1, float u2, rng_stream *g,
                                    vec3 *weight)
{
    if (k == MEDIA_WALK_VOLUME_MEDIUM)
        return media_volume_direction(s, ATMO_LUT_ARGS, d, v3_from4(s->sun_direction), beta, u1,
                                      u2, g, weight);
    return media_air_direction(s, k == MEDIA_WALK_VOLUME_RAYLEIGH ? MEDIA_RAYLEIGH : MEDIA_MIE, d,
                               u1, u2, weight);
}

#endif
