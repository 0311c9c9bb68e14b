/* method_reference.h — atmosphere method "reference": a Monte Carlo volumetric path tracer of
 * the spherical atmosphere, all orders of scattering, unbiased. It is the oracle the other
 * methods are measured against, so it uses nothing precomputed (not even the transmittance LUT).
 *
 * Geometry. Spherical symmetry lets (r, mu, mu_s, nu) fix a 3-D frame: planet centre at the
 * origin, camera at (0, r, 0), view (sqrt(1 - mu^2), mu, 0), sun (s_x, mu_s, s_z) with
 * s_x = (nu - mu mu_s) / sqrt(1 - mu^2). A camera above the atmosphere starts where the ray
 * enters it. Along each path segment the altitude is computed in the (r, mu) form of
 * geometry.h, which keeps metre precision at planet scale.
 *
 * Light transport (radiative transfer equation with a point sun of irradiance E):
 *   L(x, w) = int_0^d T(x, x_t) [sigma_R p_R + sigma_M,s p_M](x_t) * (E T_sun(x_t) + L_ms) dt
 *           + T(x, x_d) L_ground,      L_ground = (rho / pi) (E T_sun mu_s+ + int L cos dw)
 * Each segment is walked with the tentative collisions of a homogeneous Poisson process of
 * rate sigma_bar (a majorant: the extinction bound at the lowest altitude the segment reaches,
 * Rayleigh and Mie at that altitude plus the ozone peak, times 1.001). At every tentative point:
 *   - next-event estimation to the sun with the ratio-tracking weight W = prod (1 - sigma_t/sigma_bar)
 *     of the points before it (Novak et al. 2014): by Campbell's theorem
 *     E[sum W sigma_s/sigma_bar f] = int T sigma_s f dt, so single scattering is sampled along the
 *     whole ray instead of at one collision (much lower variance, order 1 dominates the sky);
 *   - spectral tracking (Kutz et al. 2017, with absorption folded into the weight) picks the
 *     one point where the path continues: Rayleigh scattering, Mie scattering or a null
 *     collision with probabilities proportional to max over channels of w * sigma_R, w * sigma_M,s
 *     and w * (sigma_bar - sigma_t); the vec3 weight w is multiplied by sigma_event /
 *     (sigma_bar P_event), so every channel stays unbiased with one shared path.
 * The sun's transmittance T_sun is ratio tracking too, with its own majorant, towards a point sun
 * (zero where the ray to the sun hits the planet: the planet's shadow). W at the end of a segment
 * weighs the ground's direct light and, on the camera ray, the sun disc (E / Omega_sun, Omega_sun
 * = 2 pi (1 - cos alpha), where nu >= cos alpha and the ray misses the ground). New directions
 * sample the phase function exactly (Rayleigh = Draine with g = 0, alpha = 1; Mie: HG or
 * Cornette-Shanks, phase.h), the Lambertian ground a cosine-weighted hemisphere (weight = albedo).
 * After 4 scattering events Russian roulette keeps a path with probability min(0.95, max w).
 *
 * Orders: order n is light that scattered (in the air or on the ground) n times; order 1 is
 * single scattering plus the directly lit ground. Knobs (plan_reference.c):
 *   s->reference.min_order = reference.min_order (>= 1), s->reference.max_order =
 *   reference.max_order (0 = all);
 * only light of orders min..max is counted.
 * Aerial perspective (sky_segment): the camera ray ends at a black surface at distance d, later
 * segments of the path do not; the weight W at its end estimates T(0, d). On that cut segment
 * the majorant is raised to at least REFERENCE_SEGMENT_POINTS / d (ratio and spectral tracking
 * stay unbiased for any majorant >= sigma_t): with sigma_bar d ~ 0.04 on a 1 km segment most
 * paths would see no tentative point there: over tests/test_aerial.c's 1 km rays the relative
 * standard error of 65536 samples was 1.7-8.9 % (median 4 %), with 4 points 0.2-6 % (median
 * 1.5 %), for about 1.5 times the time (10 s -> 16 s for its 108 rays, all distances).
 * Random numbers: rng_uniform(seed, pixel, sample, d), d counting up from ATMO_RNG_METHOD_DIM.
 * Units: radiance W m^-2 sr^-1 nm^-1, lengths m, coefficients 1/m. */
#ifndef ATMO_METHOD_REFERENCE_H
#define ATMO_METHOD_REFERENCE_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "atmosphere/atmosphere.h"
#include "common/geometry.h"
#include "common/phase.h"
#include "common/rng.h"
#include "atmosphere/sky_method.h"
#include "atmo/gpu_types.h"
#endif

#define REFERENCE_ROULETTE_ORDER 4
#define REFERENCE_SEGMENT_POINTS 4.0f

typedef struct reference_rng {
    uint seed, pixel, sample, dim;
} reference_rng;

ATMO_FN float reference_uniform(reference_rng *g)
{
    return rng_uniform(g->seed, g->pixel, g->sample, g->dim++);
}

/* Exponential step of rate sigma_bar; 1 - u lies in (0, 1], so the log is finite. */
ATMO_FN float reference_step(reference_rng *g, float sigma_bar)
{
    return -logf(1.0f - reference_uniform(g)) / sigma_bar;
}

ATMO_FN float reference_max3(vec3 v) { return fmaxf(v.x, fmaxf(v.y, v.z)); }

/* Lowest altitude along the ray from r along mu up to distance d (the ray's end). */
ATMO_FN float reference_min_altitude(ATMO_GLOBAL const atmo_gpu_atmosphere *a, float r,
                                       float mu, float d)
{
    if (mu >= 0.0f || d <= 0.0f)
        return r - a->bottom_radius;
    if (-r * mu >= d) /* still descending at the end */
        return geometry_altitude_at(r, mu, d, a->bottom_radius);
    float perigee = r * atmo_safe_sqrt(1.0f - mu * mu);
    return fmaxf(perigee - a->bottom_radius, 0.0f);
}

/* A bound on the extinction of every channel above altitude h_min. The 10 m margin covers
 * the float rounding of the altitude (about 0.5 m at 6400 km). */
ATMO_FN float reference_majorant(ATMO_GLOBAL const atmo_gpu_atmosphere *a, float h_min)
{
    float h = fmaxf(h_min - 10.0f, 0.0f);
    float ozone = h < a->ozone_peak ? 1.0f : atmosphere_ozone_tent(a, h);
    vec3 bound = v3_add(v3_add(v3_scale(v3_from4(a->rayleigh_scattering),
                                        expf(-h / a->rayleigh_scale_height)),
                               v3_scale(v3_from4(a->mie_extinction), expf(-h / a->mie_scale_height))),
                        v3_scale(v3_from4(a->ozone_absorption), ozone));
    return fmaxf(reference_max3(bound), 1e-12f) * 1.001f;
}

/* Transmittance along the whole ray from r along mu by ratio tracking (the ray must not hit the
 * ground); unbiased, each factor 1 - sigma_t / sigma_bar in [0, 1]. */
ATMO_FN vec3 reference_transmittance(ATMO_GLOBAL const atmo_gpu_atmosphere *a, float r, float mu,
                                     reference_rng *g)
{
    float d = geometry_distance_to_top(r, mu, a->top_radius);
    float sigma_bar = reference_majorant(a, reference_min_altitude(a, r, mu, d));
    vec3 T = v3(1.0f, 1.0f, 1.0f);
    for (float t = reference_step(g, sigma_bar); t < d; t += reference_step(g, sigma_bar)) {
        vec3 sigma_t = atmosphere_extinction(a, geometry_altitude_at(r, mu, t, a->bottom_radius));
        T = v3_mul(T, v3_sub(v3(1.0f, 1.0f, 1.0f), v3_scale(sigma_t, 1.0f / sigma_bar)));
    }
    return T;
}

/* E T_sun at radius r with sun cosine mu_s (zero in the planet's shadow). */
ATMO_FN vec3 reference_sunlight(ATMO_GLOBAL const atmo_gpu_atmosphere *a, float r, float mu_s,
                                  reference_rng *g)
{
    if (geometry_ray_hits_ground(r, mu_s, a->bottom_radius))
        return v3(0.0f, 0.0f, 0.0f);
    return v3_mul(v3_from4(a->solar_irradiance), reference_transmittance(a, r, mu_s, g));
}

ATMO_FN float reference_mie_phase(ATMO_GLOBAL const atmo_gpu_atmosphere *a, float nu)
{
    return a->mie_phase == ATMO_PHASE_HENYEY_GREENSTEIN ? phase_henyey_greenstein(nu, a->mie_g)
                             : phase_cornette_shanks(nu, a->mie_g);
}

/* A unit vector at cosine c to the unit vector n, with azimuth phi around it. */
ATMO_FN vec3 reference_rotate(vec3 n, float c, float phi)
{
    vec3 helper = fabsf(n.x) < 0.6f ? v3(1.0f, 0.0f, 0.0f) : v3(0.0f, 1.0f, 0.0f);
    vec3 b1 = v3_normalize(v3_cross(n, helper));
    vec3 b2 = v3_cross(n, b1);
    float s = atmo_safe_sqrt(1.0f - c * c);
    return v3_normalize(v3_add(v3_scale(n, c),
                               v3_add(v3_scale(b1, s * cosf(phi)), v3_scale(b2, s * sinf(phi)))));
}

/* One path from the camera along (r, mu, mu_s, nu); the camera ray ends at a black surface at
 * distance t_max (INFINITY: none), later segments of the path do not. view_t gets the ratio-
 * tracking weight at the camera ray's end, an unbiased estimate of T(0, min(t_max, end)). */
ATMO_FN void reference_trace(ATMO_GLOBAL const atmo_gpu_scene *s, float r, float mu, float mu_s,
                               float nu, float t_max, uint pixel, uint sample, vec3 *sky,
                               vec3 *sun, vec3 *view_t)
{
    ATMO_GLOBAL const atmo_gpu_atmosphere *a = &s->atmosphere;
    int min_order = s->reference.min_order, max_order = s->reference.max_order;
    reference_rng g = {s->seed, pixel, sample, ATMO_RNG_METHOD_DIM};
    vec3 beta_r = v3_from4(a->rayleigh_scattering), beta_m = v3_from4(a->mie_scattering);
    vec3 albedo = v3_from4(a->ground_albedo);
    vec3 one = v3(1.0f, 1.0f, 1.0f);
    *sky = v3(0.0f, 0.0f, 0.0f);
    *sun = v3(0.0f, 0.0f, 0.0f);
    *view_t = one;
    int looks_at_sun = nu >= s->sun_direction.w;

    t_max -= atmosphere_entry_distance(a, r, mu);
    if (!atmosphere_enter(a, &r, &mu, &mu_s, nu)) { /* the ray misses the atmosphere */
        if (looks_at_sun)
            *sun = atmosphere_sun_disc_radiance(a, s->sun_direction.w);
        return;
    }
    if (t_max <= 0.0f) /* the surface lies before the atmosphere */
        return;
    float sin_v = atmo_safe_sqrt(1.0f - mu * mu);
    vec3 dir = v3(sin_v, mu, 0.0f);
    float s_x = sin_v > 1e-6f ? (nu - mu * mu_s) / sin_v : atmo_safe_sqrt(1.0f - mu_s * mu_s);
    s_x = clamp(s_x, -1.0f, 1.0f);
    vec3 to_sun = v3_normalize(v3(s_x, mu_s, atmo_safe_sqrt(1.0f - mu_s * mu_s - s_x * s_x)));

    vec3 pos = v3(0.0f, r, 0.0f); /* planet-centred */
    vec3 w = one;                 /* path throughput */
    vec3 L = v3(0.0f, 0.0f, 0.0f);
    for (int order = 0;; order++) {
        /* the segment from pos along dir, with `order` scattering events behind it */
        float r0 = v3_length(pos);
        float mu0 = atmo_clamp_cos(v3_dot(pos, dir) / r0);
        float mus0 = atmo_clamp_cos(v3_dot(pos, to_sun) / r0);
        float nu0 = atmo_clamp_cos(v3_dot(dir, to_sun));
        int ground = geometry_ray_hits_ground(r0, mu0, a->bottom_radius);
        float d = ground ? geometry_distance_to_bottom(r0, mu0, a->bottom_radius)
                         : geometry_distance_to_top(r0, mu0, a->top_radius);
        int blocked = order == 0 && t_max < d; /* by the black surface */
        if (blocked)
            d = t_max, ground = 0;
        float sigma_bar = reference_majorant(a, reference_min_altitude(a, r0, mu0, d));
        if (blocked) /* at least REFERENCE_SEGMENT_POINTS tentative points on a short segment */
            sigma_bar = fmaxf(sigma_bar, REFERENCE_SEGMENT_POINTS / d);
        int count = order + 1 >= min_order; /* light reaching the camera through this segment's
                                               next-event estimates has order + 1 events */
        int more = max_order == 0 || order + 1 < max_order;
        float p_r = phase_rayleigh(nu0), p_m = reference_mie_phase(a, nu0);
        vec3 W = w, ws = w;
        int collided = 0, chose_mie = 0;
        float t_hit = 0.0f;
        for (float t = reference_step(&g, sigma_bar); t < d; t += reference_step(&g, sigma_bar)) {
            float h = geometry_altitude_at(r0, mu0, t, a->bottom_radius);
            vec3 sigma_r = v3_scale(beta_r, expf(-h / a->rayleigh_scale_height));
            vec3 sigma_m = v3_scale(beta_m, expf(-h / a->mie_scale_height));
            vec3 sigma_t = atmosphere_extinction(a, h);
            if (count) {
                float r_t = geometry_radius_at(r0, mu0, t);
                float mu_s_t = atmo_clamp_cos((r0 * mus0 + t * nu0) / r_t);
                vec3 sun_light = reference_sunlight(a, r_t, mu_s_t, &g);
                vec3 scat = v3_add(v3_scale(sigma_r, p_r), v3_scale(sigma_m, p_m));
                L = v3_add(L, v3_mul(v3_mul(W, scat), v3_scale(sun_light, 1.0f / sigma_bar)));
            }
            if (more && !collided) {
                vec3 sigma_n = v3_sub(v3(sigma_bar, sigma_bar, sigma_bar), sigma_t);
                float q_r = reference_max3(v3_mul(ws, sigma_r));
                float q_m = reference_max3(v3_mul(ws, sigma_m));
                float q_n = reference_max3(v3_mul(ws, sigma_n));
                float q = q_r + q_m + q_n; /* q_n > 0 while ws > 0: sigma_bar > sigma_t */
                float u = reference_uniform(&g) * q;
                if (u < q_r) {
                    ws = v3_scale(v3_mul(ws, sigma_r), q / (q_r * sigma_bar));
                    collided = 1, t_hit = t;
                } else if (u < q_r + q_m) {
                    ws = v3_scale(v3_mul(ws, sigma_m), q / (q_m * sigma_bar));
                    collided = 1, chose_mie = 1, t_hit = t;
                } else {
                    ws = v3_scale(v3_mul(ws, sigma_n), q / (q_n * sigma_bar));
                }
            }
            W = v3_mul(W, v3_sub(one, v3_scale(sigma_t, 1.0f / sigma_bar)));
        }
        if (ground && count) { /* the directly lit ground, seen through the segment */
            float mu_s_g = atmo_clamp_cos((r0 * mus0 + d * nu0) / a->bottom_radius);
            vec3 sun_light = reference_sunlight(a, a->bottom_radius, mu_s_g, &g);
            L = v3_add(L, v3_mul(v3_mul(W, albedo),
                                 v3_scale(sun_light, fmaxf(mu_s_g, 0.0f) / ATMO_PI)));
        }
        if (order == 0)
            *view_t = W;
        if (order == 0 && !ground && !blocked && looks_at_sun)
            *sun = v3_mul(W, atmosphere_sun_disc_radiance(a, s->sun_direction.w));
        if (!more || (!collided && !ground))
            break;
        /* the next vertex: a scattering in the air or a reflection on the ground */
        if (collided) {
            pos = v3_add(pos, v3_scale(dir, t_hit));
            float u1 = reference_uniform(&g), phi = 2.0f * ATMO_PI * reference_uniform(&g);
            float c = !chose_mie ? phase_draine_sample(0.0f, 1.0f, u1)
                      : a->mie_phase == ATMO_PHASE_HENYEY_GREENSTEIN
                          ? phase_henyey_greenstein_sample(a->mie_g, u1)
                          : phase_cornette_shanks_sample(a->mie_g, u1);
            dir = reference_rotate(dir, c, phi);
            w = ws;
        } else {
            pos = v3_add(pos, v3_scale(dir, d));
            vec3 n = v3_normalize(pos);
            pos = v3_scale(n, a->bottom_radius);
            float u1 = reference_uniform(&g), phi = 2.0f * ATMO_PI * reference_uniform(&g);
            dir = reference_rotate(n, sqrtf(u1), phi); /* cosine-weighted: pdf cos / pi */
            w = v3_mul(ws, albedo);
            if (reference_max3(w) <= 0.0f) /* a black ground ends the path */
                break;
        }
        if (order + 1 >= REFERENCE_ROULETTE_ORDER) {
            float keep = fminf(0.95f, reference_max3(w));
            if (reference_uniform(&g) >= keep)
                break;
            w = v3_scale(w, 1.0f / keep);
        }
    }
    *sky = L;
}

ATMO_FN void sky_radiance(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS, float r,
                          float mu, float mu_s, float nu, uint pixel, uint sample, vec3 *sky,
                          vec3 *sun)
{
    vec3 view_t;
    (void)transmittance_lut; /* nothing precomputed */
    reference_trace(s, r, mu, mu_s, nu, INFINITY, pixel, sample, sky, sun, &view_t);
}

/* The segment [0, d]: the camera ray stops at a black (absorbing) surface at d; the light that
 * scattered before d arrives with all its orders, whatever paths it took beyond d. */
ATMO_FN void sky_segment(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS, float r, float mu,
                         float mu_s, float nu, float d, uint pixel, uint sample, vec3 *inscatter,
                         vec3 *transmittance)
{
    vec3 sun;
    (void)transmittance_lut; /* nothing precomputed */
    reference_trace(s, r, mu, mu_s, nu, d, pixel, sample, inscatter, &sun, transmittance);
}

#endif
