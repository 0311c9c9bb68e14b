/* path.h — the path tracer's loop: one sample of a pixel's radiance, through the stages of
 * kernels/render/ (path_camera.h, surfaces.h, bsdf.h, bsdf_water.h, light_sun.h, light_sky.h) and
 * the scene's atmosphere method (sky_trace, atmosphere/sky_method.h) for the air along every
 * segment, or (path.air = medium) the air as a volume medium of the paths (below).
 *
 * The estimator of the rendering equation with participating media reduced to the
 * single-scattering form the methods integrate (the air's in-scattered light along each
 * segment comes from the method; the path's bounces are off surfaces: Lambertian, and the sea's
 * mirror and body, render/bsdf_water.h):
 *   primary ray from the camera (path_camera_sample): the first surface h along it
 *   (surfaces_hit); the segment's light S = sky_trace(t_max = t_h) (the air in front, view
 *   transmittance T) or, where the ray leaves the scene, sky_trace(INFINITY) (the sky, and the
 *   sun's disc seen directly); L = S + T (L_e + L_surface);
 *   at a surface vertex with throughput beta and albedo a:
 *     sun: beta a/pi E T_sun V max(0, n . w_sun)      (light_sun.h: the disc sampled; V the
 *          planet and the shadowing media at the point, times the objects and the terrain
 *          along w_sun: surfaces_occluded)
 *     sky: beta a/pi S(w_l) cos / p_l * w_l           (light_sky.h, MIS weight w_l)
 *     continuation: w_b ~ cos / pi (bsdf.h), beta *= a; its segment's light S(w_b) counts with
 *     the MIS weight w_b, then the next vertex (emission counted there with weight 1).
 *   at a sea vertex (SURFACES_WATER, the terrain's; bsdf_water.h): the sun term is
 *     beta E T_sun V (glint + (1 - F) a_w / pi max(0, n . w_sun)); the sky's sample weighs the
 *     body (1 - F) a_w / pi against its density (1 - P_m) cos / pi; the continuation is the
 *     mirror with probability P_m (beta *= F / P_m, its segment with MIS weight 1, the sun's
 *     disc only without the sun's NEE: the glint has it) or the body's cosine lobe
 *     (beta *= (1 - F) a_w / (1 - P_m)).
 *   S of a direction is the air up to the first surface along it plus, where the ray escapes,
 *   the sky behind: both strategies estimate the same integral of S, so their weights sum to 1
 *   and the sum is unbiased (Veach 1997). The sun's disc is left to next-event estimation: a
 *   continuation ray that finds it adds nothing there (path.sun_nee = 0: it adds the disc).
 * Clouds (path.clouds = volume): the fBm cloud layer is no medium of the method then but the
 * path tracer's volume medium; each segment's free flight through it (volume_stage.h, the one
 * majorant walk in volume mode) may end in a scattering
 * at t_c before the surface: S is the air's light up to t_c and the scattering is the next
 * vertex, lit by the sun (beta p(nu) E T_sun V T_clouds: the same shadow function as a
 * surface's, path_shadow, the layer's transmittance ratio-tracked) and continued by a direction
 * drawn from the phase function (beta *= p / pdf); the sky reaches it by that continuation
 * alone (weight 1). A surface's sun is ratio-tracked through the layer the same way. A path
 * scatters at most path.volume_bounces times in the clouds; roulette counts every event.
 * (path.clouds = march: the method marches the layer along each segment, octave multiple
 * scattering, cloud_march.h; no vertex is ever in a cloud.)
 * The air (path.air = medium, MEDIA_VOLUME_AIR): the air is a volume medium of the same free
 * flight (path_flight), no method is asked, and S is the air's single scattering of the sun
 * estimated at every tentative point of the flight (the collision estimator, path_flight; the
 * same shadow function with the air's phases) plus the sun's disc through the flight's weight
 * on an escaping ray (with_sun; path_sun_disc). A scattering by the air's Rayleigh or aerosols
 * is a vertex like a cloud's (path_vertex.component says which) but without a sun of its own
 * (its flight's points estimated it): the continuation drawn exactly from its phase, gain 1
 * in the roulette; air and cloud scatterings count together against
 * path.volume_bounces. The sky is the air's scattering, so the plan turns the sky sampling off
 * (its table is the method's sky) and surfaces meet the sky by their continuations.
 * N_s = path.secondary continuation rays leave the primary hit, each with beta / N_s (the
 * primary's direct light once, its sky MIS weighed against N_s BSDF samples); a path reflects
 * off surfaces at most N_b = path.bounces times, as pbrt's maxdepth counts: a reflection is
 * the vertex's next-event estimation and its continuation (whose segment and the emission it
 * finds count), so N_b = 0 is the camera ray's light alone (the sky, the sun's disc, the air
 * in front, the emission of the surface it hits), N_b = 1 adds the direct light of the first
 * hit, and each further bounce one order of indirect light (cloud scatterings are counted
 * apart, by path.volume_bounces); from event path.rr_bounce on (the surface reflections and
 * the cloud scatterings so far, depth + scatters), Russian roulette keeps it with probability
 *     q = min(q_max, gain x max beta),  q_max = 1 before TRACKING_ROULETTE_LONG (256) events,
 *     0.95 from there on,
 * and divides beta by q (unbiased: E[beta'] = q beta / q = beta); gain is 1 at a surface and
 * the clouds' cloud_roulette_gain at a cloud vertex (volume_stage.h). A path with gain x beta
 * >= 1 goes on with beta unchanged: a cap q_max < 1 at every event would multiply the weight
 * of such paths by 1 / q_max per vertex, a heavy tail over the tens of vertices of thick cloud
 * (tracking_survival, tracking.h: the rule the reference's walk shares; the cap from 256
 * events on bounds paths through cloud of albedo ~1, whose weights do not fall).
 * Units: spectral radiance, W m^-2 sr^-1 nm^-1 (the objects' emission too), times the
 * scene's sky_factor (the disc seen directly: sun_factor), as sky_render does.
 * The uniform test world (path.sky = uniform) has S = L_u on escaping rays and no air; its
 * sun is the solar irradiance E (times sun.irradiance_scale; 0 for the furnace tests) with no
 * atmosphere and no planet in the way, only the objects' shadows: the world of the furnace and
 * open-box tests, which a host reference can trace exactly.
 * Passes: every contribution goes to one light pass (PATH_PASS_*: the sky seen directly, the
 * objects' emission, the air in front of surfaces and cloud vertices, reflected sunlight,
 * reflected skylight, the light of cloud vertices: their sun and the sky behind them), and
 * the sample's radiance is their sum, so the passes add up to the beauty image; the primary
 * hit's distance, normal and albedo come with them (render/path.cl stores them when the scene
 * asks for passes; a primary ray that scatters in a cloud has none of them, as if it escaped).
 * Random numbers: stage 0 of the sample (rng.h) has the lens, the primary segment and the
 * primary hit's direct light; secondary ray j and all its bounces draw from stage 1 + j, in
 * order. The pixel position comes from path_camera.h's sequence. */
#ifndef ATMO_RENDER_PATH_H
#define ATMO_RENDER_PATH_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "common/rng.h"
#include "atmosphere/sky_method.h"
#include "media/medium.h"
#include "media/media_walk.h"
#include "media/tracking.h"
#include "render/path_camera.h"
#include "render/surfaces.h"
#include "render/bsdf.h"
#include "render/light_sun.h"
#include "render/light_sky.h"
#include "render/volume_stage.h"
#include "render/bsdf_water.h"
#endif

/* The light passes (render passes, path.passes): a partition of a sample's radiance by where the
 * light was last scattered toward the camera, so they sum to it. */
enum {
    PATH_PASS_ENV = 0, /* the sky and the sun's disc seen directly (primary rays that escape;
                          path.air = medium: the air's scatterings on them) */
    PATH_PASS_EMIT,    /* emission of the objects, at any bounce */
    PATH_PASS_VOLUME,  /* the air's in-scattered light in front of surfaces, every segment
                          (path.air = medium: the light of air vertices past the camera ray) */
    PATH_PASS_SUN,     /* sunlight reflected by surfaces (next-event estimation), every bounce */
    PATH_PASS_SKY,     /* skylight reflected by surfaces (sky sampling and escaping bounces) */
    PATH_PASS_CLOUDS,  /* light scattered by the cloud layer's volume (path.clouds = volume):
                          the sun at its vertices, the sky their continuations reach */
    PATH_LIGHT_PASSES
};

/* A sample's parts: the light passes and, at the primary hit, the distance, the normal on the
 * ray's side and the albedo (PATH_NO_HIT_DEPTH, zero and zero where the ray escapes). */
typedef struct path_parts {
    vec3 light[PATH_LIGHT_PASSES];
    float depth;
    vec3 normal, albedo;
} path_parts;

/* The depth of rays that hit nothing: Blender's value for the background in its Z pass. */
#define PATH_NO_HIT_DEPTH 1e10f

ATMO_FN void path_add(path_parts *parts, int pass, vec3 L)
{
    parts->light[pass] = v3_add(parts->light[pass], L);
}

/* A segment that ends at a surface stops the air this fraction of its length short of it, so
 * the method never counts the surface itself (its own ground or surface term): 1e-5 of the
 * distance is far below any change in the air. */
#define PATH_SEGMENT_SHORTEN 0.99999f

/* A segment between surfaces shorter than this has no air: over d = 10 m the sea-level air
 * scatters and absorbs sigma_t d ~ (1.2e-5 + 4.4e-6) / m x 10 m < 2e-4 of the light through it
 * (Rayleigh at 680-440 nm and the aerosols: atmosphere.* defaults), below the noise of any
 * path-traced pixel, while the method's march over it costs as much as over a long one: the
 * bounces inside an open box are all this short. */
#define PATH_AIR_MIN_M 10.0f

/* Whether the image shows the method's media in front of a surface at t_end (the denoiser's
 * guides: the slot `media_shown`): not in the uniform test world (path.sky = uniform), where
 * only a volume medium scatters, nor on a segment shorter than PATH_AIR_MIN_M. */
ATMO_FN int path_media_shown(ATMO_GLOBAL const atmo_gpu_scene *s, float t_end)
{
    return s->path.sky != ATMO_PATH_SKY_UNIFORM && t_end >= PATH_AIR_MIN_M;
}

/* The sun's disc seen along m where it leaves the atmosphere without meeting the ground:
 * its radiance outside the atmosphere (atmosphere.h) inside the disc, zero elsewhere. */
ATMO_FN vec3 path_sun_disc(ATMO_GLOBAL const atmo_gpu_scene *s, const medium_ray *m)
{
    ATMO_GLOBAL const atmo_gpu_atmosphere *a = &s->atmosphere;
    if (m->nu < s->sun_direction.w || geometry_ray_hits_ground(m->r, m->mu, a->bottom_radius))
        return v3(0.0f, 0.0f, 0.0f);
    return atmosphere_sun_disc_radiance(a, s->sun_direction.w);
}

/* The sunlight E T_sun V arriving at a surface point q: V from visibility_sun_surface (the
 * planet, the shadowing media), the opaque surfaces left to the shadow ray along the direction
 * sampled on the disc (surfaces_occluded). */
ATMO_FN vec3 path_sunlight(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                           const medium_point *q)
{
    ATMO_GLOBAL const atmo_gpu_atmosphere *a = &s->atmosphere;
    vec3 vis = visibility_sun_surface(s, ATMO_LUT_ARGS, q);
    if (vis.x <= 0.0f && vis.y <= 0.0f && vis.z <= 0.0f)
        return v3(0.0f, 0.0f, 0.0f);
    vec3 to_sun = atmosphere_transmittance_to_top(a, transmittance_lut, s->transmittance_width,
                                                  s->transmittance_height, q->r, q->mu_s);
    return v3_mul(v3_from4(a->solar_irradiance), v3_mul(to_sun, vis));
}

/* The one shadow function of surface and cloud vertices: the sunlight arriving at q along the
 * direction w sampled on the disc, for rays leaving from p: E T_sun V (path_sunlight; in the
 * uniform world E), zero where a surface blocks w (surfaces_occluded), times the volume
 * medium's transmittance toward the sun by ratio tracking (media_walk.h's shadow query in
 * volume mode; 1 without a volume medium). */
ATMO_FN vec3 path_shadow(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                         const medium_point *q, vec3 p, vec3 w, rng_stream *g)
{
    vec3 e = s->path.sky == ATMO_PATH_SKY_UNIFORM ? v3_from4(s->atmosphere.solar_irradiance)
                                                   : path_sunlight(s, ATMO_LUT_ARGS, q);
    if ((e.x <= 0.0f && e.y <= 0.0f && e.z <= 0.0f) || surfaces_occluded(s, ATMO_LUT_ARGS, p, w))
        return v3(0.0f, 0.0f, 0.0f);
    return v3_mul(e, media_walk_sun_transmittance(s, ATMO_LUT_ARGS, q, MEDIA_WALK_VOLUME, g));
}

/* The sunlight the air scatters toward the ray's origin per unit length at x, along a ray of
 * direction dir, with the air's Rayleigh and aerosol scattering coefficients sigma[] there
 * (media_walk.h's MEDIA_WALK_VOLUME_*): sum_k sigma_s,k p_k(nu) E T_sun V T_clouds, the sun's
 * direction w sampled on its disc (u1, u2) and its light through the one shadow function
 * (path_shadow: the air's transmittance from the LUT, the planet, the surfaces along w, the
 * volume medium's ratio tracking), times sky_factor. */
ATMO_FN vec3 path_air_sun(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                          const medium_point *x, vec3 dir, const vec3 *sigma, rng_stream *g)
{
    float u1 = rng_next(g), u2 = rng_next(g);
    vec3 w = light_sun_sample(v3_from4(s->sun_direction), s->sun_direction.w, u1, u2);
    float nu = v3_dot(dir, w);
    vec3 f = v3_add(
        v3_mul(sigma[MEDIA_WALK_VOLUME_RAYLEIGH], media_air_phase(s, MEDIA_RAYLEIGH, nu)),
        v3_mul(sigma[MEDIA_WALK_VOLUME_MIE], media_air_phase(s, MEDIA_MIE, nu)));
    vec3 e = path_shadow(s, ATMO_LUT_ARGS, x, x->p, w, g);
    return v3_mul(v3_mul(f, e), v3_from4(s->sky_factor));
}

/* The free flight of segment m through the volume media up to `end` (media_walk.h's spectral
 * tracking): the distance of the first scattering, or -1 where the ray passes; *component the
 * medium that scatters there (MEDIA_WALK_VOLUME_*), *w the tracking weight (1 without volume
 * media). With the air a volume medium and air_sun set, *air_light is the air's single
 * scattering of the sun along the flight, estimated at every tentative point x_i the walk
 * reaches (null and real, the last one included) with the weight w_i it reaches it with:
 *     air_light = sum_i w_i sum_k sigma_s,k(x_i) p_k E T_sun(x_i) / sigma_bar_i
 * By Campbell's theorem (majorant_walk.h: the points are a Poisson process of rate sigma_bar,
 * and E[w_i | the point is reached] is the ratio-tracking estimate of T(0, x_i)),
 * E[air_light] = int_0^end T(0, t) sum_k sigma_s,k p_k E T_sun dt, the same expectation as the
 * sun's next-event estimate at the flight's real air scattering (E[w'] = w sigma_s,k /
 * sigma_bar for the pick of k), which therefore adds no sun of its own (path_direct_sun). The
 * walk's rate is at least path.air_collisions over the flight's length, so a flight through
 * thin air still has that many estimates. Where the volume medium raises the rate above the
 * air's part a = max(the air's bound, that floor) (inside a cloud, whose points are dense and
 * whose shadow queries ratio-track the cloud), a point estimates with probability
 * P = a / sigma_bar and its estimate is divided by P (Russian roulette: E[1{u < P} / P] = 1),
 * so the air's estimates keep the air's rate. Otherwise *air_light is zero. */
ATMO_FN float path_flight(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                          const medium_ray *m, float end, int air_sun, rng_stream *g, vec3 *w,
                          int *component, vec3 *air_light)
{
    media_walk mw;
    medium_point x;
    vec3 sigma[3], sigma_t;
    int estimate = MEDIA_VOLUME_AIR && air_sun;
    *w = v3(1.0f, 1.0f, 1.0f);
    *component = WALK_NULL;
    *air_light = v3(0.0f, 0.0f, 0.0f);
    if (!media_walk_volume_flight_begin(s, ATMO_LUT_ARGS, m, end,
                                        MEDIA_VOLUME_AIR ? s->path.air_collisions : 0, &mw))
        return -1.0f;
    float air_rate = fmaxf(mw.air, mw.w.least); /* 1/m */
    while (media_walk_volume_point(s, ATMO_LUT_ARGS, &mw, m, g, &x, sigma, &sigma_t)) {
        float p = fminf(air_rate / mw.w.sigma_bar, 1.0f);
        if (estimate &&
            tracking_max3(v3_add(sigma[MEDIA_WALK_VOLUME_RAYLEIGH],
                                 sigma[MEDIA_WALK_VOLUME_MIE])) > 0.0f &&
            (p >= 1.0f || rng_next(g) < p))
            *air_light = v3_add(*air_light,
                                v3_mul(*w, v3_scale(path_air_sun(s, ATMO_LUT_ARGS, &x, m->dir,
                                                                 sigma, g),
                                                    1.0f / (mw.w.sigma_bar * p))));
        *component = walk_pick(&mw.w, g, w, sigma, media_walk_volume_components(), sigma_t);
        if (*component != WALK_NULL)
            return mw.w.t;
    }
    return -1.0f;
}

/* The light S that segment m brings to its origin, up to the first of the hit h and a
 * scattering in the volume media (path_flight: its distance in *t_event, else -1; the medium
 * that scatters in *component), or out of the scene (the sun disc only with_sun), and its view
 * transmittance (the air's, times the volume media's tracking weight).
 * With the air a volume medium (MEDIA_VOLUME_AIR) the free flight crosses the air too: S is
 * the air's single scattering of the sun along the flight (path_flight's estimate at its
 * tentative points, where air_sun is set) plus, on an escaping ray, the sun's disc through the
 * flight's weight w (the tracking estimate of the transmittance); the air's higher orders are
 * the scatterings' continuations. */
ATMO_FN vec3 path_segment(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                          const medium_ray *m, const path_hit *h, int with_sun, int air_sun,
                          rng_stream *g, vec3 *view_t, float *t_event, int *component)
{
    vec3 w, air;
    float t_c = path_flight(s, ATMO_LUT_ARGS, m, h->kind == SURFACES_NONE ? INFINITY : h->t,
                            air_sun, g, &w, component, &air);
    int escapes = h->kind == SURFACES_NONE && t_c < 0.0f;
    *t_event = t_c;
    *view_t = w;
    if (MEDIA_VOLUME_AIR)
        return escapes && with_sun
                   ? v3_add(air, v3_mul(w, v3_mul(path_sun_disc(s, m), v3_from4(s->sun_factor))))
                   : air;
    if (s->path.sky == ATMO_PATH_SKY_UNIFORM) /* the sun's disc is left to the NEE here */
        return escapes ? v3_mul(w, v3_from4(s->path.uniform_sky)) : v3(0.0f, 0.0f, 0.0f);
    if (!escapes && (t_c >= 0.0f ? t_c : h->t) < PATH_AIR_MIN_M)
        return v3(0.0f, 0.0f, 0.0f);
    vec3 sky, sun, air_t;
    float t_max = t_c >= 0.0f ? t_c : escapes ? INFINITY : h->t * PATH_SEGMENT_SHORTEN;
    sky_trace(s, ATMO_LUT_ARGS, m, t_max, g, &sky, &sun, &air_t);
    *view_t = v3_mul(air_t, w);
    vec3 L = v3_mul(sky, v3_from4(s->sky_factor));
    if (with_sun)
        L = v3_add(L, v3_mul(sun, v3_from4(s->sun_factor)));
    return v3_mul(L, w);
}

/* A vertex: the hit of ray m, its facing normal and the offset origin of rays leaving it; or a
 * scattering in the volume media (volume: no normal, no albedo; dir the ray that reached it;
 * component the medium that scattered, MEDIA_WALK_VOLUME_*: the cloud layer or the air's
 * Rayleigh or aerosols). */
typedef struct path_vertex {
    medium_point q; /* the hit point (for the visibility sources) */
    vec3 p;         /* origin for new rays, off the surface */
    vec3 n;         /* unit normal on the ray's side */
    vec3 albedo;
    vec3 dir;       /* the direction of the ray m */
    int volume;     /* 1: a scattering in the volume media */
    int component;  /* the medium that scattered (MEDIA_WALK_VOLUME_*); volume vertices only */
    float fresnel;  /* the sea's F(n . -dir); 0 elsewhere */
    int water;      /* 1 on the sea (bsdf_water.h) */
} path_vertex;

ATMO_FN path_vertex path_vertex_at(ATMO_GLOBAL const atmo_gpu_scene *s, const medium_ray *m,
                                   const path_hit *h)
{
    path_vertex v;
    v.q = medium_ray_at(m, h->t, s->atmosphere.bottom_radius);
    v.n = v3_dot(h->normal, m->dir) > 0.0f ? v3_scale(h->normal, -1.0f) : h->normal;
    v.p = v3_add(v.q.p, v3_scale(v.n, h->lift));
    v.albedo = h->albedo;
    v.dir = m->dir;
    v.volume = 0;
    v.component = MEDIA_WALK_VOLUME_MEDIUM;
    v.water = h->kind == SURFACES_WATER;
    v.fresnel = 0.0f;
    if (v.water)
        v.fresnel = water_fresnel(-v3_dot(v.n, v.dir), WATER_INDEX);
    return v;
}

/* The vertex of a scattering by component k at distance t along m in the volume media. */
ATMO_FN path_vertex path_vertex_volume(ATMO_GLOBAL const atmo_gpu_scene *s, const medium_ray *m,
                                       float t, int k)
{
    path_vertex v;
    v.q = medium_ray_at(m, t, s->atmosphere.bottom_radius);
    v.p = v.q.p;
    v.n = v3(0.0f, 0.0f, 0.0f);
    v.albedo = v3(0.0f, 0.0f, 0.0f);
    v.dir = m->dir;
    v.volume = 1;
    v.component = k;
    v.water = 0;
    v.fresnel = 0.0f;
    return v;
}

/* The pass of light scattered toward the ray at volume vertex v: the cloud layer's, or
 * air_pass for a scattering in the air (path.air = medium); `air_pass` also for a surface
 * vertex (v->volume = 0). */
ATMO_FN int path_volume_pass(const path_vertex *v, int air_pass)
{
    return v->volume && v->component == MEDIA_WALK_VOLUME_MEDIUM ? PATH_PASS_CLOUDS : air_pass;
}

/* The probability that v's continuation takes its cosine lobe (the sea's body; 1 elsewhere). */
ATMO_FN float path_cosine_probability(const path_vertex *v)
{
    if (v->water)
        return 1.0f - bsdf_water_mirror_probability(v->fresnel, v->albedo);
    return 1.0f;
}

/* The cosine lobe's albedo at v: a, or the sea body's (1 - F) a_w. */
ATMO_FN vec3 path_cosine_albedo(const path_vertex *v)
{
    return v3_scale(v->albedo, 1.0f - v->fresnel);
}

/* Sunlight scattered at v toward the ray (without the throughput): a surface's albedo/pi cos, a
 * cloud vertex's phase function; none at a scattering in the air, whose sun is the flight's
 * estimate at every tentative point up to it (path_flight; no random number drawn here). */
ATMO_FN vec3 path_direct_sun(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                             const path_vertex *v, rng_stream *g)
{
    if (v->volume && v->component != MEDIA_WALK_VOLUME_MEDIUM)
        return v3(0.0f, 0.0f, 0.0f);
    float u1 = rng_next(g), u2 = rng_next(g);
    if (!s->path.sun_nee)
        return v3(0.0f, 0.0f, 0.0f);
    vec3 w = light_sun_sample(v3_from4(s->sun_direction), s->sun_direction.w, u1, u2);
    if (v->volume) {
        vec3 f = volume_phase(s, ATMO_LUT_ARGS, v3_dot(v->dir, w));
        vec3 e = path_shadow(s, ATMO_LUT_ARGS, &v->q, v->p, w, g);
        return v3_mul(v3_mul(f, e), v3_from4(s->sky_factor));
    }
    float c = v3_dot(v->n, w);
    if (c <= 0.0f)
        return v3(0.0f, 0.0f, 0.0f);
    vec3 e = path_shadow(s, ATMO_LUT_ARGS, &v->q, v->p, w, g);
    if (v->water)
        return v3_mul(v3_mul(bsdf_water_sun(v->n, v3_scale(v->dir, -1.0f), w, v->fresnel,
                                            v->albedo),
                             e),
                      v3_from4(s->sky_factor));
    return v3_mul(v3_scale(v3_mul(v->albedo, e), c / ATMO_PI), v3_from4(s->sky_factor));
}

/* Skylight reflected at v by the sky's sampling, weighed against n_bsdf BSDF samples. */
ATMO_FN vec3 path_direct_sky(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                             const path_vertex *v, float n_bsdf, rng_stream *g)
{
    float u0 = rng_next(g), u1 = rng_next(g), u2 = rng_next(g);
    if (!s->path.sky_nee)
        return v3(0.0f, 0.0f, 0.0f);
    vec3 w = light_sky_sample(s, sky_env, u0, u1, u2);
    float c = v3_dot(v->n, w);
    if (c <= 0.0f)
        return v3(0.0f, 0.0f, 0.0f);
    float p_c = path_cosine_probability(v);
    if (p_c <= 0.0f)
        return v3(0.0f, 0.0f, 0.0f);
    float p_l = light_sky_pdf(s, sky_env, w), p_b = p_c * c / ATMO_PI;
    medium_ray r = medium_ray_make(s, v->p, w);
    path_hit h = surfaces_hit(s, ATMO_LUT_ARGS, &r, INFINITY);
    vec3 view_t;
    float t_event; /* a scattering in the volume media ends S there (its light is the
                      continuation's) */
    int k;
    vec3 S = path_segment(s, ATMO_LUT_ARGS, &r, &h, 0, s->path.sun_nee, g, &view_t, &t_event,
                          &k);
    float weight = light_sky_power(1.0f, p_l, n_bsdf, p_b);
    return v3_scale(v3_mul(path_cosine_albedo(v), S), c / ATMO_PI * weight / p_l);
}

/* The light of a path that leaves vertex v (depth: its reflections off surfaces so far, v's
 * included; scatters: its scattering events in the volume media so far) with throughput beta, its first
 * continuation from a surface weighed against n_bsdf BSDF samples. A cloud vertex continues by
 * its phase function, with weight 1 for the light its segment finds (no sky sampling there). */
ATMO_FN void path_continue(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS, path_vertex v,
                           vec3 beta, int depth, int scatters, float n_bsdf, rng_stream *g,
                           path_parts *parts)
{
    for (;;) {
        float u_rr = rng_next(g), u1 = rng_next(g), u2 = rng_next(g);
        if (depth + scatters >= s->path.rr_bounce) {
            float gain = v.volume && v.component == MEDIA_WALK_VOLUME_MEDIUM
                             ? volume_roulette_gain(s, ATMO_LUT_ARGS, v.dir)
                             : 1.0f;
            float q = tracking_survival(beta, gain, depth + scatters);
            if (u_rr >= q)
                break;
            beta = v3_scale(beta, 1.0f / q);
        }
        vec3 w, phase_weight;
        /* a surface's lobe from u1: the mirror below 1 - p_c, else the cosine lobe with u1
         * rescaled */
        float p_c = path_cosine_probability(&v);
        int mirror = !v.volume && u1 < 1.0f - p_c;
        if (v.volume) {
            w = volume_phase_direction(s, ATMO_LUT_ARGS, v.component, v.dir, beta, u1, u2, g,
                                       &phase_weight);
            beta = v3_mul(beta, phase_weight); /* p / pdf */
        } else if (mirror) {
            w = v3_sub(v.dir, v3_scale(v.n, 2.0f * v3_dot(v.dir, v.n))); /* d - 2 (n . d) n */
            beta = v3_scale(beta, v.fresnel / (1.0f - p_c));            /* F / P_m */
        } else {
            w = bsdf_sample_cosine(v.n, fminf((u1 - (1.0f - p_c)) / p_c, 1.0f), u2);
            beta = v3_mul(beta, v3_scale(path_cosine_albedo(&v), 1.0f / p_c)); /* f cos / p */
        }
        medium_ray r = medium_ray_make(s, v.p, w);
        path_hit h = surfaces_hit(s, ATMO_LUT_ARGS, &r, INFINITY);
        vec3 view_t;
        float t_event;
        int k;
        /* the air's sun along the segment stands for the sun of the scattering it may end in,
         * which path.volume_bounces allows while scatters < path.volume_bounces */
        vec3 S = path_segment(s, ATMO_LUT_ARGS, &r, &h, !s->path.sun_nee,
                              s->path.sun_nee && scatters < s->path.volume_bounces, g, &view_t,
                              &t_event, &k);
        float weight = s->path.sky_nee && !v.volume && !mirror
                           ? light_sky_power(n_bsdf, p_c * bsdf_pdf_cosine(v.n, w), 1.0f,
                                             light_sky_pdf(s, sky_env, w))
                           : 1.0f;
        int escapes = h.kind == SURFACES_NONE && t_event < 0.0f;
        path_add(parts,
                 !escapes ? PATH_PASS_VOLUME
                 : v.volume ? path_volume_pass(&v, PATH_PASS_VOLUME) : PATH_PASS_SKY,
                 v3_mul(beta, v3_scale(S, weight)));
        if (escapes)
            break;
        beta = v3_mul(beta, view_t);
        if (t_event >= 0.0f) { /* a scattering in the volume media: the next vertex */
            if (++scatters > s->path.volume_bounces)
                break;
            v = path_vertex_volume(s, &r, t_event, k);
            path_add(parts, path_volume_pass(&v, PATH_PASS_VOLUME),
                     v3_mul(beta, path_direct_sun(s, ATMO_LUT_ARGS, &v, g)));
            continue;
        }
        path_add(parts, PATH_PASS_EMIT, v3_mul(beta, v3_mul(h.emission, v3_from4(s->sky_factor))));
        if (++depth > s->path.bounces)
            break;
        v = path_vertex_at(s, &r, &h);
        path_add(parts, PATH_PASS_SUN, v3_mul(beta, path_direct_sun(s, ATMO_LUT_ARGS, &v, g)));
        path_add(parts, PATH_PASS_SKY,
                 v3_mul(beta, path_direct_sky(s, ATMO_LUT_ARGS, &v, 1.0f, g)));
        n_bsdf = 1.0f;
    }
}

/* The parts of one sample of pixel (x, y) (path_parts above). */
ATMO_FN void path_sample(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS, int x, int y,
                         uint pixel, uint sample, path_parts *parts)
{
    for (int k = 0; k < PATH_LIGHT_PASSES; k++)
        parts->light[k] = v3(0.0f, 0.0f, 0.0f);
    parts->depth = PATH_NO_HIT_DEPTH;
    parts->normal = v3(0.0f, 0.0f, 0.0f);
    parts->albedo = v3(0.0f, 0.0f, 0.0f);
    rng_stream g = rng_stream_stage(s->seed, pixel, sample, 0u);
    vec3 origin;
    vec3 d = path_camera_sample(s, x, y, pixel, sample, &g, &origin);
    if (v3_dot(d, d) == 0.0f)
        return;
    medium_ray ray = s->path.aperture_m > 0.0f ? medium_ray_make(s, origin, d)
                                               : medium_ray_from_camera(s, d);
    path_hit h = surfaces_hit(s, ATMO_LUT_ARGS, &ray, INFINITY);
    vec3 view_t;
    float t_event;
    int k;
    vec3 S = path_segment(s, ATMO_LUT_ARGS, &ray, &h, 1, s->path.sun_nee, &g, &view_t, &t_event,
                          &k);
    int escapes = h.kind == SURFACES_NONE && t_event < 0.0f;
    /* the air's light on a camera ray that meets no surface is the sky seen directly */
    path_add(parts,
             h.kind == SURFACES_NONE && (escapes || MEDIA_VOLUME_AIR) ? PATH_PASS_ENV
                                                                     : PATH_PASS_VOLUME,
             S);
    if (escapes)
        return;
    int n_s = s->path.secondary;
    path_vertex v;
    if (t_event >= 0.0f) { /* the primary vertex is a scattering in the volume media */
        v = path_vertex_volume(s, &ray, t_event, k);
        path_add(parts, path_volume_pass(&v, PATH_PASS_VOLUME),
                 v3_mul(view_t, path_direct_sun(s, ATMO_LUT_ARGS, &v, &g)));
    } else {
        path_add(parts, PATH_PASS_EMIT,
                 v3_mul(view_t, v3_mul(h.emission, v3_from4(s->sky_factor))));
        v = path_vertex_at(s, &ray, &h);
        parts->depth = h.t;
        parts->normal = v.n;
        parts->albedo = v.albedo;
        if (s->path.bounces == 0) /* no reflection: the surface shows its emission alone */
            return;
        path_add(parts, PATH_PASS_SUN, v3_mul(view_t, path_direct_sun(s, ATMO_LUT_ARGS, &v, &g)));
        path_add(parts, PATH_PASS_SKY,
                 v3_mul(view_t, path_direct_sky(s, ATMO_LUT_ARGS, &v, (float)n_s, &g)));
    }
    vec3 beta = v3_scale(view_t, 1.0f / (float)n_s);
    for (int j = 0; j < n_s; j++) {
        rng_stream gj = rng_stream_stage(s->seed, pixel, sample, 1u + (uint)j);
        path_continue(s, ATMO_LUT_ARGS, v, beta, !v.volume, v.volume, (float)n_s, &gj, parts);
    }
}

/* A sample's radiance: the sum of its light passes, in pass order. */
ATMO_FN vec3 path_total(const path_parts *parts)
{
    vec3 L = parts->light[0];
    for (int k = 1; k < PATH_LIGHT_PASSES; k++)
        L = v3_add(L, parts->light[k]);
    return L;
}

#endif
