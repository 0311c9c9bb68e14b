/* ray.h — the rays and points of the medium integrator (medium.h): a camera-relative 3-D ray
 * that also carries its exact spherical description.
 *
 * A ray is (origin, direction) in metres relative to the camera, in the world's axes, with the
 * frame it lives in: `up`, the unit vector from the planet centre to the camera, r_c the
 * camera's distance to the centre, and the unit vector toward the sun. Because the ray is a
 * straight line and the planet a sphere, four numbers at its origin determine everything the
 * atmosphere needs along it (Bruneton 2017, sec. 2): the radius r, the view cosine mu to the
 * local vertical, the sun cosine mu_s and the view-sun cosine nu; at distance t
 *     r_t = sqrt(t^2 + 2 r mu t + r^2),  mu_t = (r mu + t) / r_t,  mu_s,t = (r mu_s + t nu) / r_t
 * (geometry.h; its altitude formula keeps metre precision at 6360 km, where r_t - R would lose
 * 0.5 m to float rounding). The 3-D point origin + t direction goes with them to the visibility
 * sources (an observer, terrain, clouds), which need a position, not a radius.
 *
 * The origin's radius is found without forming |r_c up + o| in float: with q = r_c up + o,
 *     r - r_c = (2 r_c (up . o) + o . o) / (r + r_c)
 * loses nothing when o is small, so a ray from the camera itself has r = r_c exactly.
 *
 * A ray built from cosines alone (the probes, the LUT precomputes: medium_ray_from_cosines)
 * gets a 3-D direction in the frame (e_s, up, e_p): e_s the horizontal unit vector toward the
 * scene sun's azimuth, e_p = up x e_s, with the view (v_s, mu, +sqrt(1 - mu^2 - v_s^2)),
 * v_s = (nu - mu mu_s) / sqrt(1 - mu_s^2), and the sun (sqrt(1 - mu_s^2), mu_s, 0). For a probe
 * from the camera's own radius and sun that is the camera's frame, up to the mirror image in
 * the sun's vertical plane, which (r, mu, mu_s, nu) cannot tell apart. */
#ifndef ATMO_MEDIA_RAY_H
#define ATMO_MEDIA_RAY_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "common/geometry.h"
#include "atmo/gpu_types.h"
#endif

typedef struct medium_ray {
    vec3 origin;           /* camera-relative, m */
    vec3 dir;              /* unit */
    vec3 up;               /* unit, planet centre -> camera */
    vec3 sun;              /* unit, toward the sun */
    float r_c;             /* the camera's distance to the planet centre, m */
    float r, mu, mu_s, nu; /* at the origin */
} medium_ray;

/* A point of a ray: where the media and the visibility sources are asked. */
typedef struct medium_point {
    vec3 p;            /* camera-relative position, m */
    float r, h;        /* distance to the planet centre and altitude above the ground sphere, m */
    float mu, mu_s;    /* cosines of the ray and of the sun to the local vertical */
} medium_point;

/* The ray from the camera along the unit vector dir (sky.cl's pixels). */
ATMO_FN medium_ray medium_ray_from_camera(ATMO_GLOBAL const atmo_gpu_scene *s, vec3 dir)
{
    medium_ray m;
    m.origin = v3(0.0f, 0.0f, 0.0f);
    m.dir = dir;
    m.up = v3_from4(s->camera.local_up);
    m.sun = v3_from4(s->sun_direction);
    m.r_c = s->camera.local_up.w;
    m.r = m.r_c;
    m.mu = v3_dot(m.up, dir);
    m.mu_s = v3_dot(m.up, m.sun);
    m.nu = v3_dot(dir, m.sun);
    return m;
}

/* The ray from a camera-relative origin along the unit vector dir, in the camera's frame. */
ATMO_FN medium_ray medium_ray_make(ATMO_GLOBAL const atmo_gpu_scene *s, vec3 origin, vec3 dir)
{
    medium_ray m = medium_ray_from_camera(s, dir);
    float r_c = m.r_c, rise = 2.0f * r_c * v3_dot(m.up, origin) + v3_dot(origin, origin);
    float r_approx = atmo_safe_sqrt(r_c * r_c + rise);
    m.origin = origin;
    m.r = r_c + rise / (r_approx + r_c);
    m.mu = atmo_clamp_cos((r_c * m.mu + v3_dot(origin, dir)) / m.r);
    m.mu_s = atmo_clamp_cos((r_c * m.mu_s + v3_dot(origin, m.sun)) / m.r);
    return m;
}

/* A ray from the camera given by its cosines (see the top of the file), radius r. */
ATMO_FN medium_ray medium_ray_from_cosines(ATMO_GLOBAL const atmo_gpu_scene *s, float r, float mu,
                                           float mu_s, float nu)
{
    medium_ray m;
    vec3 up = v3_from4(s->camera.local_up), sun = v3_from4(s->sun_direction);
    vec3 level = v3_sub(sun, v3_scale(up, v3_dot(up, sun)));
    if (v3_dot(level, level) < 1e-12f) /* the sun at the zenith: any horizontal axis */
        level = v3_cross(up, fabsf(up.x) < 0.6f ? v3(1.0f, 0.0f, 0.0f) : v3(0.0f, 0.0f, 1.0f));
    vec3 e_s = v3_normalize(level), e_p = v3_cross(up, e_s);
    float sin_s = atmo_safe_sqrt(1.0f - mu_s * mu_s), horizontal = atmo_safe_sqrt(1.0f - mu * mu);
    float v_s = sin_s > 1e-4f ? clamp((nu - mu * mu_s) / sin_s, -horizontal, horizontal)
                              : horizontal;
    float v_p = atmo_safe_sqrt(1.0f - mu * mu - v_s * v_s);
    m.origin = v3(0.0f, 0.0f, 0.0f);
    m.up = up;
    m.dir = v3_add(v3_add(v3_scale(e_s, v_s), v3_scale(up, mu)), v3_scale(e_p, v_p));
    m.sun = v3_add(v3_scale(e_s, sin_s), v3_scale(up, mu_s));
    m.r_c = r;
    m.r = r, m.mu = mu, m.mu_s = mu_s, m.nu = nu;
    return m;
}

/* The point at distance t along the ray. */
ATMO_FN medium_point medium_ray_at(const medium_ray *m, float t, float bottom_radius)
{
    medium_point q;
    q.p = v3_add(m->origin, v3_scale(m->dir, t));
    q.r = geometry_radius_at(m->r, m->mu, t);
    q.h = geometry_altitude_at(m->r, m->mu, t, bottom_radius);
    q.mu = (m->r * m->mu + t) / q.r;
    q.mu_s = atmo_clamp_cos((m->r * m->mu_s + t * m->nu) / q.r);
    return q;
}

/* The same ray started at distance t along it. */
ATMO_FN medium_ray medium_ray_advance(const medium_ray *m, float t)
{
    medium_ray a = *m;
    float r_t = geometry_radius_at(m->r, m->mu, t);
    a.origin = v3_add(m->origin, v3_scale(m->dir, t));
    a.mu = atmo_clamp_cos((m->r * m->mu + t) / r_t);
    a.mu_s = atmo_clamp_cos((m->r * m->mu_s + t * m->nu) / r_t);
    a.r = r_t;
    return a;
}

#endif
