/* terrain.h — the terrain on the planet: where a camera-relative point lies over the height
 * field, the surface's height and normal there (from the heightmap or the fBm directly), the
 * first hit of a ray (sphere tracing), and the terrain's shadow on the sun.
 *
 * Placement. The height field h(u, v) (noise.h) is a function of the planar coordinates of a
 * point's foot on the ground sphere of radius R, u = R x / r, v = R z / r (x, z world
 * coordinates relative to the planet's axis through the origin, r the distance to the planet
 * centre): exact metres near the origin, continuous over the whole sphere (the far hemisphere
 * mirrors the near one). The surface lies at altitude S = max(h, sea level) above the sphere.
 * Kernels keep metre precision at 6360 km by never forming a world position: for a
 * camera-relative point p, with the camera's unit vertical n_c, distance r_c and altitude h_c
 * (computed in double by the host),
 *     alt(p) = h_c + (2 r_c n_c.p + p.p) / (r_c + r_p),   r_p = sqrt(r_c^2 + 2 r_c n_c.p + p.p),
 *     u = (x_c + p_x) R / r_p,  v = (z_c + p_z) R / r_p,
 * and the clearance g(p) = alt(p) - S(u, v) is > 0 above the surface.
 *
 * Normal. With the point's vertical n and the gradient (h_u, h_v), the surface's normal is
 * N = normalize(n - P_t (h_u, 0, h_v)), P_t the projection onto the tangent plane at n: the
 * tangent frame of the sphere, not of world +Y (the relative error of dropping the curvature
 * terms is h / R < 1e-3).
 *
 * Heightmap. heightmap_size = N > 0: the pass of heightmap.cl sampled h at the centres of an
 * N x N grid over the square [-E/2, E/2]^2 (E = heightmap_extent_m); lookups inside it are
 * bilinear (the height alone, gradient by central differences one texel apart, as a float or a
 * half float; or the height and its derivatives, each interpolated), plus the fBm's detail below a DEM's cells where the
 * field has one (terrain_detail.h: value and exact gradient); outside it the fBm is evaluated
 * directly. N = 0: always direct.
 *
 * Sphere tracing (Hart 1996; over-relaxation after Keinert et al. 2014). Along a ray of local
 * cosine mu to the vertical, the clearance falls at most at the rate L sqrt(1 - mu^2) - mu with
 * L = slope_bound, so a step of dt = omega g / max(L sqrt(1 - mu^2) - mu, 0.05) with omega = 1
 * cannot pass the surface while L bounds |grad h|; omega = optimism > 1 takes longer steps.
 * Under the domain warp L is the worst case of its stretch (7.6 times the unwarped field's for
 * the default warp), far above the slopes most points have; over the direct fBm each step
 * instead starts from the local bound L_0 = stretch_slope ||J|| at its start (the warp's
 * stretch there, noise.h) and lets it grow by slope_growth_per_m per metre (G, host/plan/
 * plan_terrain.c), capped at L: the clearance then falls at most as
 * a + G sqrt(1 - mu^2) s after s metres, a = max(L_0 sqrt(1 - mu^2) - mu, 0.05), and the safe
 * step is the root of g = a s + G sqrt(1 - mu^2) s^2 / 2 (terrain_step_clearance). A
 * step that lands below the surface steps back to the last point above it and goes on with
 * omega = 1 (back-stepping); below it again, the bracket is bisected (24 halvings or to 1e-6 of
 * t). A point within the distance-dependent tolerance eps(t) = 0.01 m + tolerance t above the
 * surface (a pixel's footprint at t) is a hit. Between the ends the steps size themselves by
 * a lower bound on g where it clears eps(t) (terrain_clearance_bounded: far above the surface
 * the height's upper bound from the coarse octaves, noise.h), which keeps every decision the
 * exact clearance would make except to shorten a step, and costs a few octaves instead of
 * fifteen. Tracing is confined to the shell between sea level and the highest terrain
 * (max_height_m plus the detail's bound); the ray's end at sea level is a hit by construction.
 * A ray that has used `steps` steps is resolved by TERRAIN_FALLBACK_STEPS = 304 more steps,
 * each at least a minimum that starts at the safe step there, (g + eps(t)) / the rate above,
 * and grows by a factor 1.5 per step up to U = 1/256 of the rest of the shell (at most 48
 * steps to reach U from 1 cm for any U below 1e6 m, then 256 of U), with the same back-stepping and bisection, so it ends as a hit
 * or leaves the shell: never as sky by exhaustion.
 *
 * Shadows, from a point toward the sun (unit vector s, angular radius alpha, within
 * shadow_far_m): ATMO_TERRAIN_SHADOW_EXACT traces shadow_rays rays toward points of the sun
 * disc on a Vogel spiral (equal areas, deterministic) and returns the fraction that escapes
 * (soft by construction); ATMO_TERRAIN_SHADOW_ESTIMATE marches one ray toward the sun's centre
 * through the terrain, keeps x = min over the march of g cos(e) / (t alpha) (e the sun's
 * elevation: g cos(e) is the perpendicular clearance; Quilez, "Soft shadows in raymarched
 * SDFs", 2010) and returns the visible fraction of a disc cut by a straight edge at x disc
 * radii from its centre,
 *     F(x) = 1/2 + (x sqrt(1 - x^2) + asin x) / pi,   x in [-1, 1].
 *
 * Parameters: gpu_terrain.h. */
#ifndef ATMO_TERRAIN_TERRAIN_H
#define ATMO_TERRAIN_TERRAIN_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "common/geometry.h"
#include "terrain/noise.h"
#include "terrain/terrain_detail.h"
#include "terrain/terrain_half.h"
#include "atmo/gpu_types.h"
#endif

#define TERRAIN_FALLBACK_STEPS 304
#define TERRAIN_FALLBACK_GROWTH 1.5f
#define TERRAIN_BISECTIONS 24
#define TERRAIN_EPS_M 0.01f
#define TERRAIN_GOLDEN_ANGLE 2.39996323f

/* A camera-relative point over the height field. */
typedef struct terrain_site {
    float u, v;   /* planar coordinates of its foot, m */
    float alt;    /* altitude above the ground sphere, m */
} terrain_site;

ATMO_FN terrain_site terrain_locate(ATMO_GLOBAL const atmo_gpu_scene *s, vec3 p)
{
    vec3 up = v3_from4(s->camera.local_up);
    float r_c = s->camera.local_up.w;
    float rise = 2.0f * r_c * v3_dot(up, p) + v3_dot(p, p);
    float r_p = atmo_safe_sqrt(r_c * r_c + rise);
    terrain_site q;
    q.alt = s->terrain.camera.w + rise / (r_p + r_c);
    float k = s->atmosphere.bottom_radius / r_p;
    q.u = (s->terrain.camera.x + p.x) * k;
    q.v = (s->terrain.camera.z + p.z) * k;
    return q;
}

/* The unit vertical at a camera-relative point. */
ATMO_FN vec3 terrain_vertical(ATMO_GLOBAL const atmo_gpu_scene *s, vec3 p)
{
    return v3_normalize(v3_add(v3_scale(v3_from4(s->camera.local_up), s->camera.local_up.w), p));
}

/* Texel (i, j) of the heightmap (clamped to the grid). */
ATMO_FN float terrain_texel(ATMO_GLOBAL const atmo_gpu_terrain_field *f,
                            ATMO_GLOBAL const float *hm, int i, int j, int k)
{
    int n = f->heightmap_size;
    i = i < 0 ? 0 : (i >= n ? n - 1 : i);
    j = j < 0 ? 0 : (j >= n ? n - 1 : j);
    if (f->heightmap_format == ATMO_TERRAIN_FORMAT_HALF)
        return TERRAIN_LOAD_HALF(hm, j * n + i);
    int stride = f->heightmap_format == ATMO_TERRAIN_FORMAT_DERIVATIVES ? 3 : 1;
    return hm[(j * n + i) * stride + k];
}

/* Bilinear lookup of component k at grid coordinates (gx, gy) (texel centres at integers). */
ATMO_FN float terrain_bilinear(ATMO_GLOBAL const atmo_gpu_terrain_field *f,
                               ATMO_GLOBAL const float *hm, float gx, float gy, int k)
{
    float x0 = floorf(gx), y0 = floorf(gy), fx = gx - x0, fy = gy - y0;
    int i = (int)x0, j = (int)y0;
    float a = terrain_texel(f, hm, i, j, k), b = terrain_texel(f, hm, i + 1, j, k);
    float c = terrain_texel(f, hm, i, j + 1, k), d = terrain_texel(f, hm, i + 1, j + 1, k);
    return mix(mix(a, b, fx), mix(c, d, fx), fy);
}

/* Whether (u, v) lies inside the heightmap's square of texel centres, and its grid coordinates
 * (*gx, *gy) there. */
ATMO_FN int terrain_in_heightmap(ATMO_GLOBAL const atmo_gpu_terrain_field *f, float u, float v,
                                 float *gx, float *gy)
{
    int n = f->heightmap_size;
    if (n <= 1)
        return 0;
    float texel = f->heightmap_extent_m / (float)n;
    *gx = (u + 0.5f * f->heightmap_extent_m) / texel - 0.5f;
    *gy = (v + 0.5f * f->heightmap_extent_m) / texel - 0.5f;
    return *gx >= 0.0f && *gy >= 0.0f && *gx <= (float)(n - 1) && *gy <= (float)(n - 1);
}

/* The height field at (u, v): the heightmap inside its square, else the fBm. */
ATMO_FN terrain_height terrain_height_at(ATMO_GLOBAL const atmo_gpu_terrain_field *f,
                                         ATMO_GLOBAL const float *hm, float u, float v)
{
    float gx, gy;
    if (terrain_in_heightmap(f, u, v, &gx, &gy)) {
        float texel = f->heightmap_extent_m / (float)f->heightmap_size;
        terrain_height r;
        r.h = terrain_bilinear(f, hm, gx, gy, 0);
        if (f->heightmap_format == ATMO_TERRAIN_FORMAT_DERIVATIVES) {
            r.du = terrain_bilinear(f, hm, gx, gy, 1);
            r.dv = terrain_bilinear(f, hm, gx, gy, 2);
        } else {
            r.du = (terrain_bilinear(f, hm, gx + 1.0f, gy, 0) -
                    terrain_bilinear(f, hm, gx - 1.0f, gy, 0)) / (2.0f * texel);
            r.dv = (terrain_bilinear(f, hm, gx, gy + 1.0f, 0) -
                    terrain_bilinear(f, hm, gx, gy - 1.0f, 0)) / (2.0f * texel);
        }
        if (f->detail_octaves > 0) {
            terrain_height d = terrain_detail_height(f, u, v);
            r.h += d.h, r.du += d.du, r.dv += d.dv;
        }
        return r;
    }
    return terrain_height_direct(f, u, v);
}

/* The height alone at (u, v): terrain_height_at without the gradient (the tracer's clearance;
 * the heightmap's one bilinear lookup instead of five, the fBm without its derivatives). */
ATMO_FN float terrain_height_value(ATMO_GLOBAL const atmo_gpu_terrain_field *f,
                                   ATMO_GLOBAL const float *hm, float u, float v)
{
    float gx, gy;
    if (terrain_in_heightmap(f, u, v, &gx, &gy))
        return terrain_bilinear(f, hm, gx, gy, 0) +
               (f->detail_octaves > 0 ? terrain_detail_value(f, u, v) : 0.0f);
    return terrain_height_direct_value(f, u, v);
}

/* The surface's altitude S = max(h, sea level) over a site. */
ATMO_FN float terrain_surface(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_GLOBAL const float *hm,
                              terrain_site q)
{
    return fmaxf(terrain_height_value(&s->terrain.field, hm, q.u, q.v), s->terrain.sea_level_m);
}

/* A lower bound on the clearance at a camera-relative point, exact wherever the bound would be
 * below floor_m (the tracer's hit tolerance there; INFINITY: always exact) or the point lies
 * over the heightmap: above the procedural fBm, the clearance over
 * terrain_height_direct_capped's upper bound on the height, which skips the coverage and the
 * fine octaves far above the surface. *slope: a bound on |grad h| at the point's foot, under the
 * domain warp over the direct fBm stretch_slope times the warp's stretch there, else
 * slope_bound. */
ATMO_FN float terrain_clearance_bounded(ATMO_GLOBAL const atmo_gpu_scene *s,
                                        ATMO_GLOBAL const float *hm, vec3 p, float floor_m,
                                        float *slope)
{
    ATMO_GLOBAL const atmo_gpu_terrain *tr = &s->terrain;
    ATMO_GLOBAL const atmo_gpu_terrain_field *f = &tr->field;
    terrain_site q = terrain_locate(s, p);
    float gx, gy, stretch;
    *slope = tr->slope_bound;
    if (terrain_in_heightmap(f, q.u, q.v, &gx, &gy))
        return q.alt - terrain_surface(s, hm, q);
    int bound, warped = tr->slope_growth_per_m > 0.0f;
    float h = terrain_height_direct_capped(f, q.u, q.v, q.alt - floor_m, &bound,
                                           warped ? &stretch : 0);
    if (warped)
        *slope = fminf(tr->stretch_slope * stretch, tr->slope_bound);
    return q.alt - fmaxf(h, tr->sea_level_m);
}

/* The clearance g above the surface at a camera-relative point. */
ATMO_FN float terrain_clearance(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_GLOBAL const float *hm,
                                vec3 p)
{
    terrain_site q = terrain_locate(s, p);
    return q.alt - terrain_surface(s, hm, q);
}

/* The surface's unit normal at a camera-relative point on it (see the top of the file). */
ATMO_FN vec3 terrain_normal(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_GLOBAL const float *hm,
                            vec3 p)
{
    terrain_site q = terrain_locate(s, p);
    vec3 n = terrain_vertical(s, p);
    terrain_height h = terrain_height_at(&s->terrain.field, hm, q.u, q.v);
    if (h.h <= s->terrain.sea_level_m)
        return n;
    vec3 g = v3(h.du, 0.0f, h.dv);
    vec3 g_t = v3_sub(g, v3_scale(n, v3_dot(g, n)));
    return v3_normalize(v3_sub(n, g_t));
}

/* Distances [t_in, t_out] along the ray where it lies in the terrain's shell (between sea level
 * and the highest terrain); *ends_low: t_out is where the ray reaches sea level. 0 if the ray
 * misses the shell. */
ATMO_FN int terrain_shell(ATMO_GLOBAL const atmo_gpu_scene *s, vec3 o, vec3 d, float *t_in,
                          float *t_out, int *ends_low)
{
    float R = s->atmosphere.bottom_radius, alt = terrain_locate(s, o).alt;
    float top = fmaxf(s->terrain.field.max_height_m + terrain_detail_bound_m(&s->terrain.field),
                      s->terrain.sea_level_m) + 1.0f;
    float low = s->terrain.sea_level_m;
    float r = R + alt, mu = v3_dot(terrain_vertical(s, o), d), t0, t1, b0, b1;
    if (!geometry_sphere_roots(r * mu, (alt - top) * (2.0f * R + alt + top), &t0, &t1) ||
        t1 <= 0.0f)
        return 0;
    *t_in = fmaxf(t0, 0.0f);
    *t_out = t1;
    *ends_low = 0;
    if (geometry_sphere_roots(r * mu, (alt - low) * (2.0f * R + alt + low), &b0, &b1) &&
        b0 >= 0.0f && b0 < t1) {
        *t_out = b0;
        *ends_low = 1;
    }
    return 1;
}

/* The cosine of the ray to the local vertical at distance t (origin radius r, cosine mu). */
ATMO_FN float terrain_ray_cosine(float r, float mu, float t)
{
    return atmo_clamp_cos((r * mu + t) / geometry_radius_at(r, mu, t));
}

/* Bisection of [a, b] (clearance > 0 at a, <= 0 at b) to the surface. */
ATMO_FN float terrain_bisect(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_GLOBAL const float *hm,
                             vec3 o, vec3 d, float a, float b)
{
    for (int i = 0; i < TERRAIN_BISECTIONS && b - a > 1e-6f * b; i++) {
        float m = 0.5f * (a + b);
        if (terrain_clearance(s, hm, v3_add(o, v3_scale(d, m))) > 0.0f)
            a = m;
        else
            b = m;
    }
    return 0.5f * (a + b);
}

/* The clearance the step from a point of clearance g may count on, in units of the global
 * rate: the tracer steps omega times it over `rate`, the clearance's fastest fall under
 * slope_bound (a ray of cosine mu to the vertical, sin_t its sine). Without the warp's local
 * bound that is g; with it (the top of the file: `slope` the bound at the point, growing by
 * slope_growth_per_m per metre) the safe step is the root s of g = a s + b s^2 / 2,
 * a = max(slope sin_t - mu, 0.05), b = slope_growth_per_m sin_t, taken as
 * 2 g / (a + sqrt(a^2 + 2 b g)) (no cancellation), times rate, and never below g. */
ATMO_FN float terrain_step_clearance(ATMO_GLOBAL const atmo_gpu_terrain *tr, float g, float slope,
                                     float sin_t, float mu, float rate)
{
    if (tr->slope_growth_per_m <= 0.0f)
        return g;
    float a = fmaxf(slope * sin_t - mu, 0.05f), b = tr->slope_growth_per_m * sin_t;
    return fmaxf(rate * (2.0f * g / (a + sqrtf(a * a + 2.0f * b * g))), g);
}

/* The first hit of the ray o + t d (camera-relative, d unit) with t0 <= t <= t1: 1 and *t_hit,
 * or 0. steps: the sphere-tracing budget; *used (may be NULL) gets the steps taken, fallback
 * included. */
ATMO_FN int terrain_trace(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_GLOBAL const float *hm,
                          vec3 o, vec3 d, float t0, float t1, int steps, float *t_hit, int *used)
{
    ATMO_GLOBAL const atmo_gpu_terrain *tr = &s->terrain;
    float t_in, t_out;
    int ends_low, n = 0;
    if (used)
        *used = 0;
    if (!terrain_shell(s, o, d, &t_in, &t_out, &ends_low))
        return 0;
    float t = fmaxf(t_in, t0), t_end = fminf(t_out, t1);
    ends_low = ends_low && t_out <= t1;
    if (t > t_end)
        return 0;
    float R = s->atmosphere.bottom_radius, slope, slope_prev;
    float r_o = R + terrain_locate(s, o).alt, mu_o = v3_dot(terrain_vertical(s, o), d);
    float g = terrain_clearance_bounded(s, hm, v3_add(o, v3_scale(d, t)), INFINITY, &slope);
    if (g <= 0.0f) { /* starts inside the terrain */
        *t_hit = t;
        return 1;
    }
    float omega = tr->optimism, t_prev = t, g_prev = g, min_step = 0.0f, uniform = 0.0f;
    int total = steps + TERRAIN_FALLBACK_STEPS, hit = 0;
    for (n = 0; n < total; n++) {
        float mu = terrain_ray_cosine(r_o, mu_o, t), sin_t = atmo_safe_sqrt(1.0f - mu * mu);
        float rate = fmaxf(tr->slope_bound * sin_t - mu, 0.05f);
        if (n == steps) { /* the fallback: from the safe step up to a 256th of the rest */
            min_step = (g + TERRAIN_EPS_M + tr->tolerance * t) / rate;
            uniform = (t_end - t) / 256.0f;
        } else if (n > steps) {
            min_step = fminf(min_step * TERRAIN_FALLBACK_GROWTH, uniform);
        }
        if (g < TERRAIN_EPS_M + tr->tolerance * t) {
            hit = 1;
            break;
        }
        float reach = terrain_step_clearance(tr, g, slope, sin_t, mu, rate);
        float dt = fmaxf(omega * reach / rate, min_step);
        t_prev = t, g_prev = g, slope_prev = slope;
        t = fminf(t + dt, t_end);
        /* a lower bound suffices while it clears the hit tolerance at t: no hit, no overshoot,
         * and a step no longer than the exact clearance allows */
        g = terrain_clearance_bounded(s, hm, v3_add(o, v3_scale(d, t)),
                                      TERRAIN_EPS_M + tr->tolerance * t, &slope);
        if (g <= 0.0f) {
            if (omega > 1.0f) { /* back-step, then go on within the bound */
                omega = 1.0f;
                t = t_prev, g = g_prev, slope = slope_prev;
                continue;
            }
            t = terrain_bisect(s, hm, o, d, t_prev, t);
            hit = 1;
            break;
        }
        if (t >= t_end) {
            if (ends_low) { /* sea level is below every surface: the hit is before it */
                t = terrain_bisect(s, hm, o, d, t_prev, t_end);
                hit = 1;
            }
            break;
        }
    }
    if (used)
        *used = n + 1;
    if (hit)
        *t_hit = t;
    return hit;
}

/* Where a cone of rays from o first comes near the terrain: a distance t_s such that every ray
 * o + t d' with unit d', |d' - d| <= spread (a chord), keeps its clearance above the tracer's
 * hit tolerance eps(t) = TERRAIN_EPS_M + tolerance t for all t in [0, t_s], so that tracing
 * such a ray from t_s (terrain_trace's t0) finds the hit it finds from 0, up to where a
 * grazing ray's steps land within eps of a ridge. Math: at equal t the ray's point lies within
 * t |d' - d| <= t spread of the axis's, and the clearance g = alt - S is Lipschitz in space
 * with constant 1 + L (the altitude's gradient is the unit vertical; the surface's height
 * changes at most L = slope_bound per metre of its foot, which moves at most as far as the
 * point), so
 *     g(o + t d') >= G(t) + eps(t),   G(t) = g(o + t d) - w t - TERRAIN_EPS_M,
 *     w = (1 + L) spread + tolerance.
 * G falls along the axis at most at the tracer's rate plus w, so the march takes the safe
 * steps G / (rate + w) from 0 (g from terrain_clearance_bounded's lower bound) while the
 * axis's clearance is at least 2 (TERRAIN_EPS_M + w t) (nearer, the steps shrink toward the
 * cone's surface and cost more than they save the rays), for at most `steps` steps; every
 * step ends where G >= 0 still holds. 0 where the axis misses the terrain's shell (the cone's
 * rays trace from 0). */
ATMO_FN float terrain_cone_start(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_GLOBAL const float *hm,
                                 vec3 o, vec3 d, float spread, int steps)
{
    ATMO_GLOBAL const atmo_gpu_terrain *tr = &s->terrain;
    float t_in, t_out, slope;
    int ends_low;
    if (!terrain_shell(s, o, d, &t_in, &t_out, &ends_low))
        return 0.0f;
    float r_o = s->atmosphere.bottom_radius + terrain_locate(s, o).alt;
    float mu_o = v3_dot(terrain_vertical(s, o), d);
    float w = (1.0f + tr->slope_bound) * spread + tr->tolerance, t = 0.0f;
    for (int n = 0; n < steps && t < t_out; n++) {
        float margin = TERRAIN_EPS_M + w * t;
        float G = terrain_clearance_bounded(s, hm, v3_add(o, v3_scale(d, t)), 2.0f * margin,
                                            &slope) - margin;
        if (G < margin)
            break;
        float mu = terrain_ray_cosine(r_o, mu_o, t), sin_t = atmo_safe_sqrt(1.0f - mu * mu);
        t += G / (fmaxf(tr->slope_bound * sin_t - mu, 0.05f) + w);
    }
    return t;
}

/* The visible fraction of a disc cut by a straight edge x disc radii from its centre. */
ATMO_FN float terrain_disc_fraction(float x)
{
    x = clamp(x, -1.0f, 1.0f);
    return 0.5f + (x * atmo_safe_sqrt(1.0f - x * x) + asinf(x)) / ATMO_PI;
}

/* Point k of n on the sun disc as offsets (a, b) in units of its angular radius (a Vogel
 * spiral: radius sqrt((k + 1/2) / n), angle k times the golden angle). */
ATMO_FN void terrain_disc_point(int k, int n, float *a, float *b)
{
    float rho = sqrtf(((float)k + 0.5f) / (float)n), phi = (float)k * TERRAIN_GOLDEN_ANGLE;
    *a = rho * cosf(phi);
    *b = rho * sinf(phi);
}

/* Quilez's estimate from one march toward the sun's centre (see the top of the file). */
ATMO_FN float terrain_shadow_estimate(ATMO_GLOBAL const atmo_gpu_scene *s,
                                      ATMO_GLOBAL const float *hm, vec3 p, vec3 sun, float start)
{
    ATMO_GLOBAL const atmo_gpu_terrain *tr = &s->terrain;
    float t_in, t_out;
    int ends_low;
    if (!terrain_shell(s, p, sun, &t_in, &t_out, &ends_low))
        return 1.0f;
    float alpha = s->atmosphere.sun_angular_radius;
    float cos_e = atmo_safe_sqrt(1.0f - atmo_sq(v3_dot(terrain_vertical(s, p), sun)));
    float t = fmaxf(t_in, start), t_end = fminf(t_out, tr->shadow_far_m), x = 1.0f;
    float min_step = (t_end - t) / (float)tr->shadow_steps;
    for (int i = 0; i < tr->shadow_steps && t < t_end && x > -1.0f; i++) {
        float g = terrain_clearance(s, hm, v3_add(p, v3_scale(sun, t)));
        x = fminf(x, g * cos_e / (t * alpha));
        t += fmaxf(fabsf(g) / (tr->slope_bound + 1.0f), min_step);
    }
    return terrain_disc_fraction(x);
}

/* The fraction of the sun disc the terrain leaves visible from the camera-relative point p
 * (a point on or above the surface; start: the distance along each shadow ray where the march
 * begins, clear of the point's own surface). */
ATMO_FN float terrain_sun_visible(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_GLOBAL const float *hm,
                                  vec3 p, float start)
{
    ATMO_GLOBAL const atmo_gpu_terrain *tr = &s->terrain;
    vec3 sun = v3_from4(s->sun_direction);
    if (tr->shadow == ATMO_TERRAIN_SHADOW_NONE)
        return 1.0f;
    if (tr->shadow == ATMO_TERRAIN_SHADOW_ESTIMATE)
        return terrain_shadow_estimate(s, hm, p, sun, start);
    float alpha = s->atmosphere.sun_angular_radius, t;
    vec3 e1 = v3_normalize(v3_cross(sun, fabsf(sun.y) < 0.9f ? v3(0.0f, 1.0f, 0.0f)
                                                             : v3(1.0f, 0.0f, 0.0f)));
    vec3 e2 = v3_cross(sun, e1);
    int lit = 0;
    for (int k = 0; k < tr->shadow_rays; k++) {
        float a, b;
        terrain_disc_point(k, tr->shadow_rays, &a, &b);
        vec3 d = v3_normalize(v3_add(sun, v3_add(v3_scale(e1, a * alpha), v3_scale(e2, b * alpha))));
        lit += !terrain_trace(s, hm, p, d, start, tr->shadow_far_m, tr->shadow_steps, &t, 0);
    }
    return (float)lit / (float)tr->shadow_rays;
}

/* For the path tracer's surfaces: the first terrain hit along the camera-relative ray o + t d
 * with t0 <= t <= t_max, its distance and the surface's unit normal there. */
ATMO_FN int terrain_intersect(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_GLOBAL const float *hm,
                              vec3 o, vec3 d, float t0, float t_max, float *t, vec3 *normal)
{
    if (!terrain_trace(s, hm, o, d, t0, t_max, s->terrain.steps, t, 0))
        return 0;
    *normal = terrain_normal(s, hm, v3_add(o, v3_scale(d, *t)));
    return 1;
}

#endif
