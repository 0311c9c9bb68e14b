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
 * Each segment is walked by the one majorant walk through the composed media (media_walk.h over
 * majorant_walk.h): tentative collisions of a Poisson process of rate sigma_bar, the air's
 * bound on the segment (its extinction at the lowest altitude the segment reaches plus the
 * ozone peak, times 1.001) plus the media's own piecewise-constant majorants (a cloud shell's
 * parts, a cloud layer's majorant grid: the features' slots). At every tentative point:
 *   - next-event estimation to the sun with the ratio-tracking weight W = prod (1 - sigma_t/sigma_bar)
 *     of the points before it (Novak et al. 2014): by Campbell's theorem
 *     E[sum W sigma_s/sigma_bar f] = int T sigma_s f dt, so single scattering is sampled along the
 *     whole ray instead of at one collision (much lower variance, order 1 dominates the sky);
 *   - spectral tracking (Kutz et al. 2017, with absorption folded into the weight) picks the
 *     one point where the path continues: Rayleigh scattering, Mie scattering or a null
 *     collision with probabilities proportional to max over channels of w * sigma_R, w * sigma_M,s
 *     and w * (sigma_bar - sigma_t); the vec3 weight w is multiplied by sigma_event /
 *     (sigma_bar P_event), so every channel stays unbiased with one shared path.
 * The sun's transmittance T_sun is the walk's shadow query (media_walk_sun_transmittance: ratio
 * tracking toward a point sun, the media of exact sun transmittance in closed form), zero
 * where an occluder hides the sun (the planet's shadow). W at the end of a segment
 * weighs the ground's direct light and, on the camera ray, the sun disc (E / Omega_sun, Omega_sun
 * = 2 pi (1 - cos alpha), where nu >= cos alpha and the ray misses the ground). New directions
 * come from the composed media_phase_direction: the air's phase functions exactly (Rayleigh =
 * Draine with g = 0, alpha = 1; Mie: HG or Cornette-Shanks, phase.h), a medium's its own
 * sampling (the clouds: their phase mixed with its lobe around the sun, below); the Lambertian
 * ground a cosine-weighted hemisphere (weight = albedo).
 * After 4 scattering events Russian roulette keeps a path with probability
 *     P = min(P_max, gain x the largest channel of w),
 *     P_max = 1 before TRACKING_ROULETTE_LONG (256) events, 0.95 after,
 * and divides w by P (unbiased; gain: the composed media_roulette_gain, 1 in clear air; the rule and
 * why a path with w gain >= 1 keeps its weight unchanged: tracking_survival, tracking.h,
 * shared with the path tracer).
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
 * paths would see no tentative point there, and the few that do would carry the whole
 * estimate; 4 points per segment cut its standard error about 2.7 times for about 1.5 times
 * the time (measured on tests/test_aerial.c's rays: docs/notes/reference_segments.md).
 * Clouds. A cloud medium (the fBm layer, cloud_track.h; the homogeneous shell,
 * cloud_shell_walk.h; they exclude each other) is one more component of media_at and adds its
 * majorant to the walk's: the layer the density bound of each grid cell the segment crosses
 * (cloud_majorant.h's DDA) times its largest extinction, its global bound beyond the grid,
 * zero outside its shell; the shell its largest extinction over the parts of the segment
 * between its spheres. So delta, spectral and ratio tracking stay unbiased through them while
 * clear air and thin cloud cost few points. The sun's transmittance is ratio-tracked through
 * the layer (visibility_sun's marched light march is not used: only the opaque occluders) and
 * exact through the shell (exp(-sigma l) for the sun's chord l, the slot's sun_exact). A
 * scattering by a cloud draws its new direction from its phase function (the Mie table by its
 * CDF, Henyey-Greenstein, Jendersie-d'Eon) mixed with the same lobe centred on the sun with
 * probability sun_guiding, weight p_c / q per wavelength (phase_table.h's
 * cloud_phase_direction: the forward peak's next-event estimates then come with small
 * weights; unbiased for any guiding in [0, 1)). Where such a medium is present
 * (MEDIA_TRACKED > 0), most tentative points under its bound are null collisions, so the sun's
 * next-event estimate is made only with probability keep = min(1, REFERENCE_NEE_FLOOR +
 * max sigma_s / sigma_bar) and divided by it (Russian roulette: unbiased), which spares most
 * of the shadow rays; and inside opaque cloud, where the weights fall fast, a shadow ray's
 * weight below MEDIA_WALK_ROULETTE_T and the view segment's W below REFERENCE_ROULETTE_T times
 * its weight at the segment's start once the segment's collision is chosen go through Russian
 * roulette (tracking_roulette: every estimate is linear in the weight, so it stays unbiased),
 * which ends such walks after a few optical depths instead of kilometres of cloud. The
 * observer sphere is not a source of this method (plan_cloud.c refuses it: its silhouette is
 * lit through the transmittance LUT).
 * Interfaces: the coefficients come from media_at (media.h), the occluders from
 * visibility_sun_occluders (visibility.h) at each point, the walk from media_walk.h. The path
 * lives in its own planet-centred frame (the start of the path at (0, r, 0)); reference_frame
 * maps its points and directions to the world's camera-relative coordinates, so the 3-D media
 * (the cloud layer) and visibility sources see the positions the other methods see.
 * Random numbers: the caller's rng stream (rng.h), one number per draw in order.
 * Units: radiance W m^-2 sr^-1 nm^-1, lengths m, coefficients 1/m. */
#ifndef ATMO_METHOD_REFERENCE_H
#define ATMO_METHOD_REFERENCE_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "atmosphere/atmosphere.h"
#include "common/frame.h"
#include "common/geometry.h"
#include "common/phase.h"
#include "common/rng.h"
#include "atmosphere/sky_method.h"
#include "media/media.h"
#include "media/ray.h"
#include "media/tracking.h"
#include "media/majorant_walk.h"
#include "media/media_walk.h"
#include "media/visibility.h"
#include "atmo/gpu_types.h"
#endif

#define REFERENCE_ROULETTE_ORDER 4
#define REFERENCE_SEGMENT_POINTS 4.0f
#define REFERENCE_NEE_FLOOR 0.05f /* with clouds: least probability of a next-event estimate */
#define REFERENCE_ROULETTE_T 0.1f /* with clouds: weights below this go through roulette */

/* The path's frame (see the top of the file) in the world's axes: a path point X (planet-
 * centred in the path's frame) is at the camera-relative world position
 *     o + e_x X.x + e_y (X.y - r_e) + e_z X.z
 * with o the camera-relative position of the point the path's frame puts at (0, r_e, 0). */
typedef struct reference_frame {
    vec3 o, e_x, e_y, e_z;
    float r_e;
} reference_frame;

ATMO_FN vec3 reference_world_dir(const reference_frame *f, vec3 d)
{
    return v3_add(v3_add(v3_scale(f->e_x, d.x), v3_scale(f->e_y, d.y)), v3_scale(f->e_z, d.z));
}

ATMO_FN vec3 reference_world_point(const reference_frame *f, vec3 x)
{
    return v3_add(f->o, reference_world_dir(f, v3(x.x, x.y - f->r_e, x.z)));
}

/* The frame of a path whose first segment starts t_entry along the ray m, at radius r_e. */
ATMO_FN reference_frame reference_frame_make(const medium_ray *m, float t_entry, float r_e)
{
    reference_frame f;
    f.o = v3_add(m->origin, v3_scale(m->dir, t_entry));
    f.e_y = v3_normalize(v3_add(v3_scale(m->up, m->r_c), f.o));
    f.r_e = r_e;
    vec3 level = v3_sub(m->dir, v3_scale(f.e_y, v3_dot(m->dir, f.e_y)));
    if (v3_dot(level, level) < 1e-12f) /* a vertical ray: the path's x axis follows the sun */
        level = v3_sub(m->sun, v3_scale(f.e_y, v3_dot(m->sun, f.e_y)));
    if (v3_dot(level, level) < 1e-12f)
        level = v3_cross(f.e_y, fabsf(f.e_y.x) < 0.6f ? v3(1.0f, 0.0f, 0.0f) : v3(0.0f, 0.0f, 1.0f));
    f.e_x = v3_normalize(level);
    f.e_z = v3_cross(f.e_x, f.e_y);
    if (v3_dot(m->sun, f.e_z) < 0.0f) /* the path's sun has z >= 0 */
        f.e_z = v3_scale(f.e_z, -1.0f);
    return f;
}

/* A point at distance t along the ray from the point pos (planet-centred in the path's frame,
 * radius r) along dir, with the ray's cosines mu, mu_s, nu there, its 3-D position in the
 * world's camera-relative coordinates. */
ATMO_FN medium_point reference_point(ATMO_GLOBAL const atmo_gpu_atmosphere *a,
                                     const reference_frame *f, vec3 pos, vec3 dir, float r,
                                     float mu, float mu_s, float nu, float t)
{
    medium_ray m;
    m.origin = reference_world_point(f, pos);
    m.dir = reference_world_dir(f, dir);
    m.r = r, m.mu = mu, m.mu_s = mu_s, m.nu = nu;
    return medium_ray_at(&m, t, a->bottom_radius);
}

/* E T_sun at the point q: zero where an opaque source hides the sun (the planet), else the
 * media's transmittance by ratio tracking (every medium is tracked, none taken from
 * visibility_sun's marched estimates). */
ATMO_FN vec3 reference_sunlight(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                const medium_point *q, rng_stream *g)
{
    float vis = visibility_sun_occluders(s, ATMO_LUT_ARGS, q);
    if (vis <= 0.0f)
        return v3(0.0f, 0.0f, 0.0f);
    vec3 t = v3_mul(media_walk_sun_transmittance(s, ATMO_LUT_ARGS, q, MEDIA_WALK_SHADOW, g),
                    media_walk_volume_sun(s, ATMO_LUT_ARGS, q));
    return v3_scale(v3_mul(v3_from4(s->atmosphere.solar_irradiance), t), vis);
}

/* One path from the camera along the ray m (its cosines; the path's frame is its own); the
 * camera ray ends at a black surface at distance t_max (INFINITY: none), later segments of the
 * path do not. view_t gets the ratio-tracking weight at the camera ray's end, an unbiased
 * estimate of T(0, min(t_max, end)). */
ATMO_FN void reference_trace(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                             const medium_ray *m, float t_max, rng_stream *g, vec3 *sky,
                             vec3 *sun, vec3 *view_t)
{
    ATMO_GLOBAL const atmo_gpu_atmosphere *a = &s->atmosphere;
    int min_order = s->reference.min_order, max_order = s->reference.max_order;
    float r = m->r, mu = m->mu, mu_s = m->mu_s, nu = m->nu;
    vec3 albedo = v3_from4(a->ground_albedo);
    vec3 one = v3(1.0f, 1.0f, 1.0f);
    *sky = v3(0.0f, 0.0f, 0.0f);
    *sun = v3(0.0f, 0.0f, 0.0f);
    *view_t = one;
    int looks_at_sun = nu >= s->sun_direction.w;

    float t_entry = atmosphere_entry_distance(a, r, mu);
    t_max -= t_entry;
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

    reference_frame frame = reference_frame_make(m, t_entry, r);
    vec3 pos = v3(0.0f, r, 0.0f);         /* planet-centred, in the path's frame */
    vec3 w = one;                        /* path throughput */
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
        /* on a cut segment, at least REFERENCE_SEGMENT_POINTS tentative points */
        media_walk rw = media_walk_begin(s, ATMO_LUT_ARGS, reference_world_point(&frame, pos),
                                         reference_world_dir(&frame, dir), r0, mu0, d,
                                         blocked ? REFERENCE_SEGMENT_POINTS / d : 0.0f,
                                         MEDIA_WALK_MEDIA);
        int count = order + 1 >= min_order; /* light reaching the camera through this segment's
                                               next-event estimates has order + 1 events */
        int more = max_order == 0 || order + 1 < max_order;
        vec3 phase[MEDIA_COMPONENTS];
        for (int k = 0; k < MEDIA_COMPONENTS; k++)
            phase[k] = media_phase(s, ATMO_LUT_ARGS, k, nu0);
        vec3 W = w, ws = w;
        int collided = 0, chosen = 0;
        float t_hit = 0.0f;
        float w_roulette = REFERENCE_ROULETTE_T * tracking_max3(w);
        while (media_walk_next(s, ATMO_LUT_ARGS, &rw, g)) {
            float t = rw.w.t, sigma_bar = rw.w.sigma_bar;
            medium_point q = reference_point(a, &frame, pos, dir, r0, mu0, mus0, nu0, t);
            media_sample ms = media_at(s, ATMO_LUT_ARGS, &q);
            if (count && tracking_max3(W) > 0.0f) {
                float keep = 1.0f;
                if (MEDIA_TRACKED > 0) {
                    /* under the clouds' majorant most points are null: the estimate is made
                     * with probability keep (>= REFERENCE_NEE_FLOOR, more where it scatters)
                     * and divided by it, which keeps it unbiased and spares most shadow rays */
                    vec3 sigma_s = ms.scattering[0];
                    for (int k = 1; k < MEDIA_COMPONENTS; k++)
                        sigma_s = v3_add(sigma_s, ms.scattering[k]);
                    keep = fminf(1.0f, REFERENCE_NEE_FLOOR + tracking_max3(sigma_s) / sigma_bar);
                    if (keep < 1.0f && rng_next(g) >= keep)
                        keep = 0.0f;
                }
                if (keep > 0.0f) {
                    vec3 sun_light = reference_sunlight(s, ATMO_LUT_ARGS, &q, g);
                    vec3 scat = v3_mul(ms.scattering[0], phase[0]);
                    for (int k = 1; k < MEDIA_COMPONENTS; k++)
                        scat = v3_add(scat, v3_mul(ms.scattering[k], phase[k]));
                    L = v3_add(L, v3_mul(v3_mul(W, scat),
                                         v3_scale(sun_light, 1.0f / (sigma_bar * keep))));
                }
            }
            if (more && !collided) {
                int k = walk_pick(&rw.w, g, &ws, ms.scattering, MEDIA_COMPONENTS,
                                               ms.extinction);
                if (k >= 0)
                    collided = 1, chosen = k, t_hit = t;
            }
            W = walk_ratio(&rw.w, W, ms.extinction);
            /* once the segment's collision is chosen, only W-weighted estimates are left */
            if (MEDIA_TRACKED > 0 && (collided || !more)) {
                W = tracking_roulette(W, w_roulette, g);
                if (tracking_max3(W) <= 0.0f)
                    break;
            }
        }
        if (ground && count) { /* the directly lit ground, seen through the segment */
            medium_point q = reference_point(a, &frame, pos, dir, r0, mu0, mus0, nu0, d);
            q.r = a->bottom_radius;
            q.h = 0.0f;
            q.mu_s = atmo_clamp_cos((r0 * mus0 + d * nu0) / a->bottom_radius);
            vec3 sun_light = reference_sunlight(s, ATMO_LUT_ARGS, &q, g);
            L = v3_add(L, v3_mul(v3_mul(W, albedo),
                                 v3_scale(sun_light, fmaxf(q.mu_s, 0.0f) / ATMO_PI)));
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
            float u1 = rng_next(g), u2 = rng_next(g);
            vec3 phase_weight;
            dir = media_phase_direction(s, ATMO_LUT_ARGS, chosen, dir, to_sun, ws, u1, u2, g,
                                        &phase_weight);
            w = v3_mul(ws, phase_weight);
        } else {
            pos = v3_add(pos, v3_scale(dir, d));
            vec3 n = v3_normalize(pos);
            pos = v3_scale(n, a->bottom_radius);
            float u1 = rng_next(g), phi = 2.0f * ATMO_PI * rng_next(g);
            dir = frame_direction(n, sqrtf(u1), phi); /* cosine-weighted: pdf cos / pi */
            w = v3_mul(ws, albedo);
            if (tracking_max3(w) <= 0.0f) /* a black ground ends the path */
                break;
        }
        if (order + 1 >= REFERENCE_ROULETTE_ORDER) {
            float gain = media_roulette_gain(s, ATMO_LUT_ARGS, v3_dot(dir, to_sun));
            float keep = tracking_survival(w, gain, order + 1);
            if (rng_next(g) >= keep)
                break;
            w = v3_scale(w, 1.0f / keep);
        }
    }
    *sky = L;
}

/* The method's ray (sky_method.h): nothing precomputed. */
ATMO_FN void sky_trace(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS, const medium_ray *m,
                       float t_max, rng_stream *g, vec3 *sky, vec3 *sun, vec3 *view_t)
{
    reference_trace(s, ATMO_LUT_ARGS, m, t_max, g, sky, sun, view_t);
}

#endif
