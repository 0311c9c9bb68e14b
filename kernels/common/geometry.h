/* geometry.h — rays against the planet's spheres, in the (r, mu) form of Bruneton 2017.
 *
 * A point is described by r, its distance to the planet centre, and a ray by mu, the cosine of
 * its angle to the local vertical. The distance along the ray to a sphere of radius R is
 *     d = -r mu +- sqrt(r^2 (mu^2 - 1) + R^2)           (Bruneton 2017, sec. "Distance to ...")
 * The discriminant is evaluated as (R - r)(R + r) + (r mu)^2, which keeps its precision at planet
 * scale where r^2 ~ 4e13 would swallow the difference of the two radii in float. Points along a
 * ray: r_t = sqrt(t^2 + 2 r mu t + r^2), and cosines at t are (r mu + t) / r_t for the ray itself
 * and (r mu_s + t nu) / r_t for the sun, nu being the cosine between ray and sun. */
#ifndef ATMO_GEOMETRY_H
#define ATMO_GEOMETRY_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#endif

ATMO_FN float geometry_discriminant(float r, float mu, float radius)
{
    return (radius - r) * (radius + r) + atmo_sq(r * mu);
}

/* Distance to the outer intersection with a sphere the point is inside of (r <= radius). */
ATMO_FN float geometry_distance_to_top(float r, float mu, float top_radius)
{
    float d = -r * mu + atmo_safe_sqrt(geometry_discriminant(r, mu, top_radius));
    return fmaxf(d, 0.0f);
}

/* Distance to the near intersection with the ground sphere (r >= radius). */
ATMO_FN float geometry_distance_to_bottom(float r, float mu, float bottom_radius)
{
    float d = -r * mu - atmo_safe_sqrt(geometry_discriminant(r, mu, bottom_radius));
    return fmaxf(d, 0.0f);
}

ATMO_FN int geometry_ray_hits_ground(float r, float mu, float bottom_radius)
{
    return mu < 0.0f && geometry_discriminant(r, mu, bottom_radius) >= 0.0f;
}

/* Radius at distance t along the ray. */
ATMO_FN float geometry_radius_at(float r, float mu, float t)
{
    return atmo_safe_sqrt(t * t + 2.0f * r * mu * t + r * r);
}

/* Altitude above a sphere of radius R at distance t along the ray, written as
 * (r_t^2 - R^2) / (r_t + R) so it keeps metre precision instead of losing the ~0.5 m that
 * r_t - R loses to float rounding of r_t ~ 6.4e6 m. */
ATMO_FN float geometry_altitude_at(float r, float mu, float t, float radius)
{
    float r_t = geometry_radius_at(r, mu, t);
    return (t * (t + 2.0f * r * mu) + (r - radius) * (r + radius)) / (r_t + radius);
}

/* Roots t0 <= t1 of t^2 + 2 b t + c = 0 (a ray from a point at radius r with cosine mu against
 * a sphere of radius R: b = r mu, c = r^2 - R^2, which the caller forms from an accurate
 * altitude difference), without cancellation. 0 when the ray misses. */
ATMO_FN int geometry_sphere_roots(float b, float c, float *t0, float *t1)
{
    float disc = b * b - c;
    if (disc < 0.0f)
        return 0;
    float q = -(b + (b >= 0.0f ? sqrtf(disc) : -sqrtf(disc)));
    float ta = q, tb = q != 0.0f ? c / q : 0.0f;
    *t0 = fminf(ta, tb);
    *t1 = fmaxf(ta, tb);
    return 1;
}

/* The parts of [t_start, t_end] of the ray from radius r with cosine mu (R the ground's radius)
 * inside the spherical shell between the altitudes base and top, in order: their count (0..2),
 * their ends in lo[], hi[]. The ray is in the shell between the roots of the top sphere and
 * outside those of the base sphere (geometry_sphere_roots, c = (h - z)(r + R + z) for the
 * sphere at altitude z, h = r - R: the altitude difference formed first, so c keeps its
 * precision at planet scale). The media shaped as shells (the cloud shell, the fBm layer's
 * slab) take their parts from here, for the quadrature's parts and the majorant walk's
 * segments alike. Units: metres. */
ATMO_FN int geometry_shell_parts(float R, float base, float top, float r, float mu,
                                 float t_start, float t_end, float *lo, float *hi)
{
    float h = r - R, b = r * mu, o0, o1, i0, i1;
    int n = 0;
    if (!geometry_sphere_roots(b, (h - top) * (r + R + top), &o0, &o1))
        return 0;
    float part_lo[2] = {o0, 0.0f}, part_hi[2] = {o1, 0.0f};
    int parts = 1;
    if (geometry_sphere_roots(b, (h - base) * (r + R + base), &i0, &i1)) {
        part_hi[0] = i0, part_lo[1] = i1, part_hi[1] = o1;
        parts = 2;
    }
    for (int k = 0; k < parts; k++) {
        float l = fmaxf(part_lo[k], t_start), u = fminf(part_hi[k], t_end);
        if (u > l)
            lo[n] = l, hi[n] = u, n++;
    }
    return n;
}

#endif
