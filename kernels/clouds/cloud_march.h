/* cloud_march.h — the fBm cloud layer's own stepping along a view ray (the fast integrator of
 * the clouds): the media_interval of cloud_layer.h's medium, called by the medium integrator
 * (medium.h) for the part of a ray inside the layer's shell, where it integrates everything:
 * the clouds and the air between and around them.
 *
 * Steps. A step starts with the coverage test at its start (cloud_layer.h: a coverage field of
 * 0 means no cloud there at any altitude; the field's features are hundreds of km, so a clear
 * step rarely cuts into a cloud): in clear air the step is CLOUDS_CLEAR_STRIDE times longer, in cloud it is
 *     dt = step_m + CLOUDS_STEP_GROWTH t_c
 * (t_c the distance from the camera, so the step follows the pixel's footprint), the first one
 * shortened by the sample's jitter so successive samples cover the ray. The steps are the
 * pieces of a sized quadrature walk (quadrature_walk.h) over the part; each is sampled at the
 * fraction `jitter` of it and integrated exactly for constant coefficients (Hillaire 2015;
 * media.h's medium_piece_weight),
 *     L += T (1 - e^{-sigma_t dt}) / sigma_t S,   T *= e^{-sigma_t dt}
 * which conserves energy for any step length. Beyond the far plane max_distance_m, after
 * `steps` steps or once T < CLOUDS_T_MIN, the rest of the part is air only: one long step
 * (clouds there are not seen; below T_MIN nothing is). The air's light is integrated in every
 * step, so aerial perspective lies between the cloud segments, not only in front of the first.
 *
 * Source S at a point with the sun's light E T_air V (the atmosphere's transmittance toward the
 * sun, the occluders: planet, observer) and the density integral D toward the sun (tau_sun =
 * extinction D) of the sun shadow map or the light march: at a sample in cloud the march cut at
 * light_distance_m (clouds_octave_light_density below, with which the octaves were fitted), at
 * a sample in clear air the whole chord in as many steps (cloud_layer_medium.h's
 * clouds_chord_density: the clouds that shade the air under a low sun lie far along it):
 *   air:    (sigma_R p_R + sigma_M p_M) E T_air V e^{-tau_sun}  (+ J_ms e^{-tau_sun}, use_ms)
 *   clouds: sigma_s E T_air V [p_0(nu) T_0 + B (sum_{1<=i<N} b^i p_i(nu) (T_i - T_0)
 *                                                + d R(s) e^{-k_d tau_sun} / (4 pi))]
 * the octaves of Wrenninge, Kulla & Lundqvist 2013 ("Oz: the great and volumetric") and the
 * diffuse orders beyond them, with the build-up B (below). Octave 0 is single scattering with
 * the true phase and T_0 = e^{-tau_sun}; octave i >= 1 is Henyey-Greenstein with the table's g
 * times c^i and T_i = e^{-a^i tau_sun} (with the deep decay below).
 * N = ms_octaves, a, b, c, d = ms_a, ms_b, ms_c, ms_d, by default 2, 0.2, 0.99, 0.7, 6.81,
 * fitted to the reference (its own seed) by `atmo bench clouds --fit`, 1.5 % RMS over the
 * bench's six views (docs/bench/README.md). The sixth, a sunset looking toward the sun
 * (scattering angles of 8-20 degrees), bounds c: Henyey-Greenstein with g near the droplets'
 * has several times the Mie phase at 10 degrees, whose diffraction peak keeps that light
 * within a few degrees.
 *
 * Build-up. The octaves beyond the first and the diffuse orders are light that has scattered
 * in the cloud before it reaches the point, and where the cloud around the point is thin
 * there is little of it. Two factors take it out there:
 * - an octave's beam carries only its scattered part, T_i - T_0 (T_0 is the unscattered beam,
 *   octave 0's), which vanishes where the sun's path crosses no cloud;
 * - both terms are weighted by the build-up
 *       B = [(1 - e^{-tau_front}) + (1 - e^{-tau_back}) + (1 - e^{-tau_sun})] / 3,
 *   the mean over three directions of the light that a uniform cloud of optical depth tau
 *   sends to the point from that direction, per unit of its source: from the camera's side
 *   (tau_front, the clouds' optical depth from the ray's origin to the step), from behind
 *   (tau_back, from the step to where the march ends: the end of the layer's part, the far
 *   plane or T_MIN) and from the sun's side.
 * The march knows tau_back only at its end. With t_c(t) the clouds' transmittance from the
 * origin, 1 - e^{-tau_back} = 1 - t_c(end) / t_c(t), so the light weighted by it is
 * sum Tw S - t_c(end) sum Tw S / t_c(t): two sums in one pass. B sees three directions of the
 * cloud around the point, not the sphere: it is a weight the fit scales, 1 deep in a cloud,
 * 1/3 to 2/3 at a thick cloud's face toward the camera (as its sun's side is clear or not) and
 * 0 in a wisp. The bench's held-out near cloud (a cumulus' face turned away from a low sun,
 * seen from inside the layer) measures what the two factors do (docs/bench/README.md, "The
 * build-up").
 *
 * Deep decay. In an absorbing cloud (albedo w < 1) diffuse light decays with depth at least as
 * e^{-k_d tau}, the diffusion exponent
 *     k_d = sqrt(3 (1 - w)(1 - w g))
 * (the diffusion approximation's eigenvalue; 0.16 for the thesis' w 0.9512 and g 0.86). An
 * octave i >= 1 whose a^i is below k_d keeps e^{-a^i tau_sun} within a diffusion length 1 / k_d
 * of the lit side and decays at the rate k_d beyond it,
 *     T_i = e^{-a^i tau_sun - (k_d - a^i) max(tau_sun - 1 / k_d, 0)},
 * and the light march that feeds the octaves and the diffuse orders stops only where the slowest
 * of them is opaque, so no deck passes the sun's light that does not cross it.
 *
 * Diffuse orders. Light that leaves a thick deck away from the sun has scattered many times (a
 * turn from forward alone takes about 1 / (1 - g), 7 scatterings at g 0.86): its radiance is
 * nearly isotropic. The octaves' phases stay forward (g c^i) and their weights b^i fall fast,
 * so they miss it; the orders beyond them are one isotropic term, the diffusion
 * approximation's fluence under the sun decaying into the cloud as e^{-k_d tau_sun}, weighted by
 * d R(s), R the plane albedo of a semi-infinite cloud from similarity theory (van de Hulst's
 * fit),
 *     R = (1 - s)(1 - 0.139 s) / (1 + 1.17 s),   s = sqrt((1 - w) / (1 - w g))
 * (0.28 for the thesis' optics; 1 without absorption, 0 for w = 0), and d fitted. It stands for
 * the light a deck sends back out; in thin cloud the build-up takes it out. With w = 1
 * (k_d = 0) the deep decay is off: the octaves and the diffuse orders are the fit's alone.
 *
 * The sky. With use_ms (method march) the sky's light is
 * added isotropically,
 *   sigma_s E_sky(mu_s) / (4 pi) (1 + (h - bottom) / (top - bottom)) / 2
 * (E_sky the sky's irradiance on a horizontal surface from the ms LUT, halved at the layer's
 * bottom, where the cloud above shades it), times the same deep decay at a = 0 over the
 * vertical optical depth mu_s tau_sun (plane-parallel: the sky's light comes down through the
 * deck too). The thesis look (clouds.look = thesis) replaces the
 * octaves and the sky by the thesis' model: single scattering times the powder factor
 * 1 - e^{-2 tau_sun}, plus a constant ambient CLOUDS_THESIS_AMBIENT sigma_s E / (4 pi), and
 * passes the clouds' light through the thesis' soft clamp.
 *
 * The soft clamp. The thesis works in units where the sun's irradiance is 1 and its cloud phase
 * function p' lacks the 1/(4 pi) (p' = 4 pi p, so that its ambient CLOUDS_THESIS_AMBIENT sigma_s
 * is the one above): the cloud light L' it computes is 4 pi / E_sun times the light L of the same
 * model here, E_sun the sun's irradiance at the top of the atmosphere in the channel. It clamps
 * L' softly at CLOUDS_THESIS_CLAMP = 3, which hides its 4 pi too bright forward peak; here that
 * level is
 *     L_clamp = CLOUDS_THESIS_CLAMP E_sun / (4 pi)   (per channel, W m^-2 sr^-1 nm^-1).
 * Only the level 3 is the thesis'; the curve is atmo's choice, smooth and monotone with slope 1
 * at 0 and the asymptote L_clamp:
 *     f(L) = L_clamp (1 - e^{-L / L_clamp}) = L - L^2 / (2 L_clamp) + O(L^3)
 * (relative deficit below L / (2 L_clamp); 1 - e^{-x} by expm1, accurate for small x). It acts on
 * the clouds' light (the in-scattering by sigma_s of the clouds, times the view transmittance T
 * from the ray's origin) summed over one part of the ray inside the layer, before it is added to
 * the light of the air; a ray that crosses the layer twice (under its bottom between the parts)
 * clamps each part alone. The physical look sums the two lights step by step, unclamped.
 * Units: radiance W m^-2 sr^-1 nm^-1, metres. */
#ifndef ATMO_CLOUDS_CLOUD_MARCH_H
#define ATMO_CLOUDS_CLOUD_MARCH_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "atmosphere/atmosphere.h"
#include "common/phase.h"
#include "media/ray.h"
#include "media/media.h"
#include "media/quadrature_walk.h"
#include "media/visibility.h"
#include "clouds/cloud_layer_medium.h"
#include "media/tracking.h"
#include "clouds/cloud_layer.h"
#include "atmo/gpu_types.h"
#endif

#define CLOUDS_T_MIN 1e-4f
#define CLOUDS_THESIS_AMBIENT 0.1f
#define CLOUDS_THESIS_CLAMP 3.0f

/* The diffusion exponent k_d = sqrt(3 (1 - w)(1 - w g)) per channel (w the albedo, g the
 * asymmetry): the rate, per unit optical depth, at which diffuse light decays deep in an
 * absorbing medium (the header). */
ATMO_FN vec3 clouds_diffusion_exponent(ATMO_GLOBAL const atmo_gpu_clouds *c)
{
    return v3(sqrtf(3.0f * (1.0f - c->albedo.x) * fmaxf(1.0f - c->albedo.x * c->g.x, 0.0f)),
              sqrtf(3.0f * (1.0f - c->albedo.y) * fmaxf(1.0f - c->albedo.y * c->g.y, 0.0f)),
              sqrtf(3.0f * (1.0f - c->albedo.z) * fmaxf(1.0f - c->albedo.z * c->g.z, 0.0f)));
}

/* The plane albedo of a semi-infinite cloud per channel from similarity theory,
 *     R = (1 - s)(1 - 0.139 s) / (1 + 1.17 s),   s = sqrt((1 - w) / (1 - w g))
 * (van de Hulst's fit, the header): the weight the diffuse orders carry. */
ATMO_FN float clouds_similarity_channel(float w, float g)
{
    float s = sqrtf((1.0f - w) / fmaxf(1.0f - w * g, 1e-6f));
    return (1.0f - s) * (1.0f - 0.139f * s) / (1.0f + 1.17f * s);
}

ATMO_FN vec3 clouds_similarity_albedo(ATMO_GLOBAL const atmo_gpu_clouds *c)
{
    return v3(clouds_similarity_channel(c->albedo.x, c->g.x),
              clouds_similarity_channel(c->albedo.y, c->g.y),
              clouds_similarity_channel(c->albedo.z, c->g.z));
}

/* One octave's transmittance toward the sun (the header): e^{-a tau} within a diffusion length
 * 1 / k_d of the lit side, and from there on decaying at least as fast as diffuse light does,
 *     e^{-a tau - max(k_d - a, 0) max(tau - 1 / k_d, 0)}   per channel. */
ATMO_FN float clouds_octave_channel(float tau, float a, float k_d)
{
    float deep = k_d > a ? (k_d - a) * fmaxf(tau - 1.0f / k_d, 0.0f) : 0.0f;
    return expf(-a * tau - deep);
}

ATMO_FN vec3 clouds_octave_transmittance(vec3 tau, float a, vec3 k_d)
{
    return v3(clouds_octave_channel(tau.x, a, k_d.x), clouds_octave_channel(tau.y, a, k_d.y),
              clouds_octave_channel(tau.z, a, k_d.z));
}

/* The scattered part of an octave's beam (the header): its transmittance t_i less the
 * unscattered beam's t_0 = e^{-tau_sun}, per channel, never below 0. */
ATMO_FN vec3 clouds_octave_scattered(vec3 t_i, vec3 t_0)
{
    return v3(fmaxf(t_i.x - t_0.x, 0.0f), fmaxf(t_i.y - t_0.y, 0.0f), fmaxf(t_i.z - t_0.z, 0.0f));
}

/* The build-up's weight, the part known at a step (the header): the mean over the three
 * directions of 1 - e^{-tau} with the camera's and the sun's known and the back's e^{-tau}
 * deferred, (3 - t_front - t_sun) / 3 per channel; t_front the clouds' transmittance from the
 * camera to the step, t_sun = e^{-tau_sun}. */
ATMO_FN vec3 clouds_buildup_known(vec3 t_front, vec3 t_sun)
{
    return v3_scale(v3_sub(v3_sub(v3(3.0f, 3.0f, 3.0f), t_front), t_sun), 1.0f / 3.0f);
}

/* The build-up's deferred part of a step's scattered light `source` (the header): the march
 * subtracts t_end times the sum of Tw source / (3 t_front) over its steps, Tw the step's
 * weight (medium_piece_weight), t_front as above and t_end the clouds' transmittance at the
 * march's end. Tw is 0 wherever t_front is (the view transmittance includes the clouds'). */
ATMO_FN vec3 clouds_buildup_deferred(vec3 Tw, vec3 t_front, vec3 source)
{
    return v3(t_front.x > 0.0f ? Tw.x * source.x / (3.0f * t_front.x) : 0.0f,
              t_front.y > 0.0f ? Tw.y * source.y / (3.0f * t_front.y) : 0.0f,
              t_front.z > 0.0f ? Tw.z * source.z / (3.0f * t_front.z) : 0.0f);
}

/* The density integral D toward the sun for the octaves and the diffuse orders: the light
 * march stops only once the slowest of them is opaque, a_N tau_sun past CLOUDS_TAU_OPAQUE
 * (a_N = k_d, the smallest channel's, with the diffuse orders, else max(a^(N-1), k_d)), not once
 * tau_sun does, which would cap the deep terms' tau at CLOUDS_TAU_OPAQUE and let them see the
 * sun through any deck; the shadow map's integral has no stop. */
ATMO_FN float clouds_octave_light_density(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                          const medium_point *q, vec3 k_d)
{
#ifdef ATMO_CLOUDS_SHADOW_MAP
    (void)k_d;
    return clouds_chord_density(s, ATMO_LUT_ARGS, q, s->clouds.light_steps);
#else
    ATMO_GLOBAL const atmo_gpu_clouds *c = &s->clouds;
    float a_n = 1.0f;
    if (c->look != ATMO_CLOUDS_LOOK_THESIS) {
        float k_min = fminf(k_d.x, fminf(k_d.y, k_d.z));
        a_n = c->ms_d > 0.0f ? k_min : fmaxf(powf(c->ms_a, (float)(c->ms_octaves - 1)), k_min);
    }
    return clouds_sun_density_steps(s, q, clouds_point_jitter(q->p, c->seed), c->light_steps,
                                    c->light_distance_m,
                                    (CLOUDS_TAU_OPAQUE + 1.0f) / fmaxf(a_n, 1e-30f));
#endif
}

/* The physical look's cloud light at a point per unit scattering coefficient and of the sun's
 * irradiance sun_e there (the header): octave 0 (single scattering, phase p0, transmittance
 * t_0 = e^{-tau_sun}) and the sky's light to *direct; the octaves beyond it, each the
 * scattered part of its beam, and the diffuse orders to *scattered, which the caller weights
 * by the build-up. */
ATMO_FN void clouds_physical_source(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                    const medium_ray *m, const medium_point *q, vec3 sun_e,
                                    vec3 tau_sun, vec3 t_0, vec3 p0, int use_ms, vec3 k_d,
                                    vec3 diffuse_albedo, vec3 *direct, vec3 *scattered)
{
    ATMO_GLOBAL const atmo_gpu_clouds *c = &s->clouds;
    *direct = v3_mul(v3_mul(p0, sun_e), t_0);
    *scattered = v3_scale(v3_mul(v3_mul(sun_e, diffuse_albedo),
                                 v3_exp(v3_scale(v3_mul(k_d, tau_sun), -1.0f))),
                          c->ms_d / (4.0f * ATMO_PI));
    float ka = c->ms_a, kb = c->ms_b, kc = c->ms_c;
    for (int i = 1; i < c->ms_octaves; i++) {
        vec3 p = v3(phase_henyey_greenstein(m->nu, c->g.x * kc),
                    phase_henyey_greenstein(m->nu, c->g.y * kc),
                    phase_henyey_greenstein(m->nu, c->g.z * kc));
        vec3 t_i = clouds_octave_scattered(clouds_octave_transmittance(tau_sun, ka, k_d), t_0);
        *scattered = v3_add(*scattered, v3_scale(v3_mul(v3_mul(p, sun_e), t_i), kb));
        ka *= c->ms_a;
        kb *= c->ms_b;
        kc *= c->ms_c;
    }
    if (use_ms) {
        float rise = clamp((q->h - c->bottom_m) / (c->top_m - c->bottom_m), 0.0f, 1.0f);
        vec3 sky = v3_mul(medium_ms_ground_irradiance(s, ATMO_LUT_ARGS, q->mu_s),
                          clouds_octave_transmittance(v3_scale(tau_sun, fmaxf(q->mu_s, 0.0f)),
                                                      0.0f, k_d));
        *direct = v3_add(*direct, v3_scale(sky, 0.5f * (1.0f + rise) / (4.0f * ATMO_PI)));
    }
}

/* The light of one step of length dt sampled at distance t (coefficients constant over it),
 * added to *L, the clouds' part of it to *L_cloud instead with the thesis look; *T and *medium_t
 * advance over the step, and *deferred gathers the build-up's deferred part
 * (clouds_buildup_deferred). `cloudy`: the layer is asked there; k_d and diffuse_albedo: the
 * scene's clouds_diffusion_exponent and clouds_similarity_albedo, computed once per march. */
ATMO_FN void clouds_step(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS, const medium_ray *m,
                         float t, float dt, int cloudy, int use_ms, int ground, vec3 k_d,
                         vec3 diffuse_albedo, vec3 *L, vec3 *L_cloud, vec3 *T, vec3 *medium_t,
                         vec3 *deferred)
{
    ATMO_GLOBAL const atmo_gpu_atmosphere *a = &s->atmosphere;
    ATMO_GLOBAL const atmo_gpu_clouds *c = &s->clouds;
    medium_point q = medium_ray_at(m, t, a->bottom_radius);
    media_sample ms;
    if (cloudy) {
        ms = media_at(s, ATMO_LUT_ARGS, &q);
    } else { /* the air alone: the coverage test found no cloud */
        ms.scattering[MEDIA_RAYLEIGH] = v3_scale(v3_from4(a->rayleigh_scattering),
                                                 expf(-q.h / a->rayleigh_scale_height));
        ms.scattering[MEDIA_MIE] =
            v3_scale(v3_from4(a->mie_scattering), expf(-q.h / a->mie_scale_height));
        for (int k = MEDIA_MIE + 1; k < MEDIA_COMPONENTS; k++)
            ms.scattering[k] = v3(0.0f, 0.0f, 0.0f);
        ms.extinction = atmosphere_extinction(a, q.h);
    }
    vec3 Tw = medium_piece_weight(ms.extinction, dt, T);
    float occluded = visibility_sun_occluders(s, ATMO_LUT_ARGS, &q);
    vec3 sigma_c = ms.scattering[MEDIA_CLOUDS];
    int in_cloud = cloudy && sigma_c.y > 0.0f;
    float D = occluded <= 0.0f ? 0.0f
              : in_cloud       ? clouds_octave_light_density(s, ATMO_LUT_ARGS, &q, k_d)
                               : clouds_chord_density(s, ATMO_LUT_ARGS, &q, c->light_steps);
    vec3 tau_sun = v3_scale(v3_from4(c->extinction), D), cloud_t = v3_exp(v3_scale(tau_sun, -1.0f));
    vec3 sun_e = v3(0.0f, 0.0f, 0.0f);
    if (occluded > 0.0f)
        sun_e = v3_scale(v3_mul(v3_from4(a->solar_irradiance),
                                atmosphere_transmittance_to_top(a, transmittance_lut,
                                                                s->transmittance_width,
                                                                s->transmittance_height, q.r,
                                                                q.mu_s)),
                         occluded);
    vec3 air = v3_add(v3_mul(ms.scattering[MEDIA_RAYLEIGH],
                             media_phase(s, ATMO_LUT_ARGS, MEDIA_RAYLEIGH, m->nu)),
                      v3_mul(ms.scattering[MEDIA_MIE],
                             media_phase(s, ATMO_LUT_ARGS, MEDIA_MIE, m->nu)));
    vec3 S = v3_mul(v3_mul(air, sun_e), cloud_t);
    if (use_ms)
        S = v3_add(S, v3_mul(medium_ms_source(s, ATMO_LUT_ARGS, &q, m->nu, &ms, ground), cloud_t));
    if (in_cloud) {
        vec3 cloud = v3(0.0f, 0.0f, 0.0f);
        vec3 p0 = media_phase(s, ATMO_LUT_ARGS, MEDIA_CLOUDS, m->nu);
        if (c->look == ATMO_CLOUDS_LOOK_THESIS) {
            vec3 powder = v3_sub(v3(1.0f, 1.0f, 1.0f), v3_exp(v3_scale(tau_sun, -2.0f)));
            cloud = v3_add(v3_mul(v3_mul(v3_mul(p0, sun_e), cloud_t), powder),
                           v3_scale(v3_from4(a->solar_irradiance),
                                    CLOUDS_THESIS_AMBIENT / (4.0f * ATMO_PI)));
        } else {
            vec3 scattered;
            clouds_physical_source(s, ATMO_LUT_ARGS, m, &q, sun_e, tau_sun, cloud_t, p0, use_ms,
                                   k_d, diffuse_albedo, &cloud, &scattered);
            scattered = v3_mul(sigma_c, scattered);
            S = v3_add(S, v3_mul(scattered, clouds_buildup_known(*medium_t, cloud_t)));
            *deferred = v3_add(*deferred, clouds_buildup_deferred(Tw, *medium_t, scattered));
        }
        if (c->look == ATMO_CLOUDS_LOOK_THESIS)
            *L_cloud = v3_add(*L_cloud, v3_mul(Tw, v3_mul(sigma_c, cloud)));
        else
            S = v3_add(S, v3_mul(sigma_c, cloud));
        *medium_t = v3_mul(*medium_t, v3_exp(v3_scale(v3_sub(ms.extinction,
                                                             atmosphere_extinction(a, q.h)),
                                                      -dt)));
    }
    *L = v3_add(*L, v3_mul(Tw, S));
}

/* The thesis' soft clamp f(L) per channel at the level L_clamp (the header): 0 where
 * L_clamp is 0 (a channel without sunlight has no cloud light either). */
ATMO_FN vec3 clouds_thesis_clamp(vec3 L, vec3 L_clamp)
{
    return v3(L_clamp.x > 0.0f ? -L_clamp.x * expm1f(-L.x / L_clamp.x) : 0.0f,
              L_clamp.y > 0.0f ? -L_clamp.y * expm1f(-L.y / L_clamp.y) : 0.0f,
              L_clamp.z > 0.0f ? -L_clamp.z * expm1f(-L.z / L_clamp.z) : 0.0f);
}

/* The steps over [t0, t1] (a part of the ray inside the layer): the light to *L, with the thesis
 * look the clouds' light unclamped to *L_cloud. */
ATMO_FN void clouds_march(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                          const medium_ray *m, float t0, float t1, float jitter, int use_ms,
                          int ground, vec3 *L, vec3 *L_cloud, vec3 *T, vec3 *medium_t)
{
    ATMO_GLOBAL const atmo_gpu_clouds *c = &s->clouds;
    float start = v3_length(m->origin); /* the camera's distance to the ray's origin */
    float far = c->max_distance_m - start;
    /* the scene's constants of every step: the diffusion exponent and the diffuse orders' albedo */
    vec3 k_d = clouds_diffusion_exponent(c), diffuse_albedo = clouds_similarity_albedo(c);
    vec3 deferred = v3(0.0f, 0.0f, 0.0f);
    quadrature_walk w = quadrature_begin_sized(t0, t1, c->steps, jitter);
    while (quadrature_more(&w) && w.done < far && tracking_max3(*T) >= CLOUDS_T_MIN) {
        medium_point q = medium_ray_at(m, w.done, s->atmosphere.bottom_radius);
        int cloudy = clouds_coverage(c, q.p) > 0.0f;
        float dt = clouds_march_step(c, start + w.done, cloudy);
        if (w.i == 0) /* a shorter first step: the samples' steps interleave */
            dt *= fmaxf(jitter, 1e-3f);
        quadrature_step(&w, dt);
        clouds_step(s, ATMO_LUT_ARGS, m, w.t, w.dt, cloudy, use_ms, ground, k_d, diffuse_albedo,
                    L, L_cloud, T, medium_t, &deferred);
    }
    if (w.done < t1 && tracking_max3(*T) >= CLOUDS_T_MIN) { /* the rest: air only */
        quadrature_step_to(&w, t1);
        clouds_step(s, ATMO_LUT_ARGS, m, w.t, w.dt, 0, use_ms, ground, k_d, diffuse_albedo, L,
                    L_cloud, T, medium_t, &deferred);
    }
    /* the build-up's deferred part: the clouds' optical depth behind each step is now known */
    *L = v3_sub(*L, v3_mul(*medium_t, deferred));
}

/* media_interval's part [t0, t1] of the layer: the steps, then with the thesis look the
 * clouds' light clamped and added to *L. */
ATMO_FN void clouds_interval(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                             const medium_ray *m, float t0, float t1, float jitter, int use_ms,
                             int ground, vec3 *L, vec3 *T, vec3 *medium_t)
{
    vec3 cloud = v3(0.0f, 0.0f, 0.0f);
    clouds_march(s, ATMO_LUT_ARGS, m, t0, t1, jitter, use_ms, ground, L, &cloud, T, medium_t);
    if (s->clouds.look == ATMO_CLOUDS_LOOK_THESIS) {
        vec3 level = v3_scale(v3_from4(s->atmosphere.solar_irradiance),
                              CLOUDS_THESIS_CLAMP / (4.0f * ATMO_PI));
        *L = v3_add(*L, clouds_thesis_clamp(cloud, level));
    }
}

/* The layer's media_interval in the plan's composition (media.h): clouds_interval, whose own
 * steps follow the pixel's footprint, not the air grid (grid_d, grid_n unused). */
ATMO_FN void clouds_media_interval(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                   const medium_ray *m, float t0, float t1, float jitter,
                                   int use_ms, int ground, float grid_d, int grid_n, vec3 *L,
                                   vec3 *T, vec3 *medium_t)
{
    clouds_interval(s, ATMO_LUT_ARGS, m, t0, t1, jitter, use_ms, ground, L, T, medium_t);
}

#endif
