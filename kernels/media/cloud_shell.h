/* cloud_shell.h — a homogeneous cloud or fog layer between two altitudes (a spherical shell, so
 * the atmosphere stays spherically symmetric), an observer sphere that shadows it (Brocken
 * spectre), and the view-ray integrator of methods "single" and "march" when a scene has them
 * (feature "cloud" of the plan's registry: assembled, with -DATMO_CLOUD for the methods, only
 * when the scene has a cloud or an observer).
 *
 * Medium: extinction sigma (1/m, per wavelength) = (sigma_ext / LWC) x LWC of a droplet size
 * distribution, albedo omega and a phase function p (per steradian): the 4pi-normalised Mie table
 * P(theta) / 4pi of the distribution (host/plan/plan_cloud.c builds it with mie_table_get into
 * the buffer cloud_phase_table, rows float4 (P_680, P_550, P_440, theta) ascending in theta,
 * interpolated linearly here), or
 * Henyey-Greenstein with the table's g, or Jendersie & d'Eon 2023 for the effective diameter.
 *
 * View ray (cloud_integrate): the ray is cut at the shell's spheres (at most two cloud segments)
 * and at the observer sphere. Between them the atmosphere is marched as in sky_single.h /
 * ms_lut.h (n segments shared in proportion to length, each integrated exactly for constant
 * coefficients), with the sun's light also attenuated by the cloud on its way down (the shell's
 * chord toward the sun, analytic: exp(-sigma l_sun)) and by the observer's shadow. The multiple
 * scattering term sigma_s Psi_ms of method march (ms_lut.h) is multiplied by the same cloud
 * transmittance: a documented approximation that darkens the haze under a thick deck. Each
 * cloud segment is integrated with `s->cloud.steps` steps equal in optical depth, up to
 * CLOUD_TAU_CUT (beyond it the view transmittance is below 1e-5), so a cloud of optical
 * thickness 10-1000 is resolved where it is seen. Within a step the sun's path length in the
 * shell is taken as linear in t, from l_0 to l_1, so with x(s) = a sigma l(s) + sigma_v s the
 * step integrates exactly
 *     int_0^dt S_0 e^{-x(s)} ds = S_0 dt (e^{-x(0)} - e^{-x(dt)}) / (x(dt) - x(0))
 * (exact for a plane-parallel slab, where the single-scattering radiance has the closed form
 * omega p(theta) E mu_s / (mu_s + mu_v) (1 - e^{-tau (1/mu_s + 1/mu_v)}) used by the tests).
 *
 * Multiple scattering inside the cloud: the octaves of Wrenninge, Kulla & Lundqvist 2013
 * ("Oz: the great and volumetric", SIGGRAPH talk): octave i adds the single-scattering source
 * with the sun's extinction scaled by a^i, the contribution by b^i and the phase anisotropy by
 * c^i (octave 0 is exact single scattering with the true phase; octaves i >= 1 use
 * Henyey-Greenstein with g c^i). a, b, c and the octave count are below; they are chosen by eye
 * so a thick deck (tau >= 30) under a 54-degree sun reflects roughly a third of the light (real
 * decks reflect 0.6-0.8) while the glory and fog bow of octave 0 keep their contrast; the
 * approximation is not energy conserving and has no diffuse light under the deck.
 *
 * Observer: a sphere whose centre (s->cloud.observer.xyz) is given in the camera's sun frame
 * (y = local up at the camera, x = horizontal toward the sun's azimuth, z = y cross x...
 * any sign: the centre has z = 0). sky_radiance knows a view direction only up to its mirror
 * image in the vertical plane through the sun, which contains the sphere, so the direction
 * (vx, mu, +vz) with vx = (nu - mu mu_s) / sin_s is as good as its mirror. The sphere blocks
 * the sun at every sample it shadows and ends a view ray it meets, showing a Lambertian
 * surface of albedo CLOUD_OBSERVER_ALBEDO lit by the sun only (a dark silhouette). A sphere
 * around the camera is the photographer: it casts the shadow but is not seen.
 *
 * Units: metres, 1/m, radians; radiance in W m^-2 sr^-1 nm^-1 like sky_single.h. */
#ifndef ATMO_CLOUD_SHELL_H
#define ATMO_CLOUD_SHELL_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "atmosphere/atmosphere.h"
#include "common/geometry.h"
#include "common/phase.h"
#include "atmosphere/sky_single.h"
#include "atmo/gpu_types.h"
#endif

#ifndef ATMO_CLOUD_OCTAVES
#define ATMO_CLOUD_OCTAVES 5
#endif
#define CLOUD_OCTAVE_A 0.25f /* extinction of the sun's path, per octave */
#define CLOUD_OCTAVE_B 0.7f  /* contribution, per octave */
#define CLOUD_OCTAVE_C 0.5f  /* phase anisotropy, per octave */
#define CLOUD_TAU_CUT 11.5f  /* view optical depth integrated per segment (e^-11.5 = 1e-5) */
#define CLOUD_OBSERVER_ALBEDO 0.1f

/* Roots t0 <= t1 of t^2 + 2 b t + c = 0 (a ray from a point at radius r with cosine mu
 * against a sphere of radius R: b = r mu, c = r^2 - R^2, which the caller forms from an
 * accurate altitude difference), without cancellation. 0 when the ray misses. */
ATMO_FN int cloud_sphere_roots(float b, float c, float *t0, float *t1)
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

/* Length of the half-line t >= 0 inside a sphere, for roots as above. */
ATMO_FN float cloud_length_inside(float b, float c)
{
    float t0, t1;
    if (!cloud_sphere_roots(b, c, &t0, &t1))
        return 0.0f;
    return fmaxf(t1, 0.0f) - fmaxf(t0, 0.0f);
}

/* Path length through the shell [R + base, R + top] of the half-line from a point at altitude
 * h (above the ground sphere R) and radius r_t, with cosine m to the local vertical. */
ATMO_FN float cloud_shell_chord(float R, float base, float top, float h, float r_t, float m)
{
    float b = r_t * m;
    float c_top = (h - top) * (r_t + R + top), c_base = (h - base) * (r_t + R + base);
    return fmaxf(cloud_length_inside(b, c_top) - cloud_length_inside(b, c_base), 0.0f);
}

/* The cloud's phase function per steradian at view-sun cosine nu, one value per wavelength. */
ATMO_FN vec3 cloud_phase(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_GLOBAL const float4 *table,
                         float nu)
{
    if (s->cloud.phase == ATMO_CLOUD_PHASE_HG)
        return v3(phase_henyey_greenstein(nu, s->cloud.g.x),
                  phase_henyey_greenstein(nu, s->cloud.g.y),
                  phase_henyey_greenstein(nu, s->cloud.g.z));
    if (s->cloud.phase == ATMO_CLOUD_PHASE_JENDERSIE_DEON) {
        float p = phase_jendersie_deon(nu, phase_jendersie_deon_params(s->cloud.diameter_um));
        return v3(p, p, p);
    }
    /* the light turns from -sun to -view: the scattering angle's cosine is nu */
    ATMO_GLOBAL const float4 *rows = table;
    int n = s->cloud.table_size;
    float theta = acosf(atmo_clamp_cos(nu));
    int lo = 0, hi = n - 1; /* rows[lo].w <= theta <= rows[hi].w */
    while (hi - lo > 1) {
        int mid = (lo + hi) / 2;
        if (rows[mid].w <= theta)
            lo = mid;
        else
            hi = mid;
    }
    float4 a = rows[lo], b = rows[hi];
    float f = b.w > a.w ? clamp((theta - a.w) / (b.w - a.w), 0.0f, 1.0f) : 0.0f;
    float k = 1.0f / (4.0f * ATMO_PI);
    return v3(mix(a.x, b.x, f) * k, mix(a.y, b.y, f) * k, mix(a.z, b.z, f) * k);
}

/* The view direction in the camera's sun frame (see the top of the file). */
ATMO_FN vec3 cloud_view_direction(float mu, float mu_s, float nu)
{
    float sin_s = atmo_safe_sqrt(1.0f - mu_s * mu_s);
    float horizontal = atmo_safe_sqrt(1.0f - mu * mu);
    float vx = sin_s > 1e-4f ? clamp((nu - mu * mu_s) / sin_s, -horizontal, horizontal)
                             : horizontal;
    return v3(vx, mu, atmo_safe_sqrt(1.0f - mu * mu - vx * vx));
}

/* 1 when the half-line from p along d meets the observer sphere (centre o.xyz, radius o.w). */
ATMO_FN int cloud_observer_blocks(float4 o, vec3 p, vec3 d)
{
    if (o.w <= 0.0f)
        return 0;
    vec3 oc = v3_sub(p, v3(o.x, o.y, o.z));
    float b = v3_dot(oc, d), c = v3_dot(oc, oc) - o.w * o.w;
    return c <= 0.0f || (b < 0.0f && b * b - c >= 0.0f);
}

/* Distance along d from the camera (origin) to the observer sphere, or -1; also -1 when the
 * camera is inside it (the observer is the photographer: it shadows but is not seen). */
ATMO_FN float cloud_observer_hit(float4 o, vec3 d)
{
    float t0, t1;
    if (o.w <= 0.0f)
        return -1.0f;
    vec3 oc = v3_scale(v3(o.x, o.y, o.z), -1.0f);
    if (!cloud_sphere_roots(v3_dot(oc, d), v3_dot(oc, oc) - o.w * o.w, &t0, &t1) || t0 <= 0.0f)
        return -1.0f;
    return t0;
}

/* (1 - e^{-x}) / sigma with x = sigma dt for any sign of sigma (a decaying or growing source). */
ATMO_FN float cloud_weight(float sigma, float dt)
{
    float x = sigma * dt;
    return fabsf(x) > 1e-4f ? -expm1f(-x) / sigma : dt * (1.0f - 0.5f * x);
}

ATMO_FN vec3 cloud_weight3(vec3 sigma, float dt)
{
    return v3(cloud_weight(sigma.x, dt), cloud_weight(sigma.y, dt),
              cloud_weight(sigma.z, dt));
}

/* int_0^dt e^{-x(s)} ds for an exponent linear from x0 to x1 (both >= 0):
 * dt (e^{-x0} - e^{-x1}) / (x1 - x0). Written with the end values so it stays finite when the
 * exponent falls steeply (the sun's path shortening fast along a ray going up). */
ATMO_FN float cloud_exp_mean(float x0, float x1, float dt)
{
    float d = x1 - x0;
    return fabsf(d) > 1e-4f ? dt * (expf(-x0) - expf(-x1)) / d : dt * expf(-x0) * (1.0f - 0.5f * d);
}

ATMO_FN vec3 cloud_exp_mean3(vec3 x0, vec3 x1, float dt)
{
    return v3(cloud_exp_mean(x0.x, x1.x, dt), cloud_exp_mean(x0.y, x1.y, dt),
              cloud_exp_mean(x0.z, x1.z, dt));
}

/* A view ray: the camera's radius, the ray's cosines and its direction and the sun's in the
 * camera's sun frame. */
typedef struct cloud_ray {
    float r, mu, mu_s, nu; /* the camera and the ray */
    vec3 dir, sun_dir;     /* camera sun frame */
} cloud_ray;

/* The sun's transmittance through the atmosphere to the point at distance t along the ray, and
 * (in *chord) its path length through the cloud shell. */
ATMO_FN vec3 cloud_sun_transmittance(ATMO_GLOBAL const atmo_gpu_scene *s,
                                     ATMO_GLOBAL const float4 *lut0, cloud_ray ray, float t,
                                     float *chord)
{
    ATMO_GLOBAL const atmo_gpu_atmosphere *a = &s->atmosphere;
    float R = a->bottom_radius;
    float r_t = geometry_radius_at(ray.r, ray.mu, t);
    float h = geometry_altitude_at(ray.r, ray.mu, t, R);
    float mu_s_t = atmo_clamp_cos((ray.r * ray.mu_s + t * ray.nu) / r_t);
    *chord = cloud_shell_chord(R, s->cloud.base_m, s->cloud.top_m, h, r_t, mu_s_t);
    return atmosphere_sun_transmittance(a, lut0, s->transmittance_width,
                                        s->transmittance_height, r_t, mu_s_t);
}

/* The atmosphere between t0 and t1 in n segments (sample offset jitter), added to *L with the
 * running view transmittance *T. */
ATMO_FN void cloud_atmosphere_segment(ATMO_GLOBAL const atmo_gpu_scene *s,
                                        ATMO_GLOBAL const float4 *lut0,
                                        ATMO_GLOBAL const float4 *ms, int ms_w, int ms_h,
                                        int use_ms, cloud_ray ray, float t0, float t1, int n,
                                        float jitter, vec3 *L, vec3 *T)
{
    ATMO_GLOBAL const atmo_gpu_atmosphere *a = &s->atmosphere;
    vec3 E = v3_from4(a->solar_irradiance), sigma_c = v3_from4(s->cloud.extinction);
    vec3 beta_r = v3_from4(a->rayleigh_scattering), beta_m = v3_from4(a->mie_scattering);
    float p_r = phase_rayleigh(ray.nu), p_m = sky_mie_phase(a, ray.nu);
    float dt = (t1 - t0) / (float)n;
    for (int i = 0; i < n; i++) {
        float t = t0 + ((float)i + jitter) * dt, chord;
        float h = geometry_altitude_at(ray.r, ray.mu, t, a->bottom_radius);
        float rho_r = expf(-h / a->rayleigh_scale_height), rho_m = expf(-h / a->mie_scale_height);
        vec3 sun_t = cloud_sun_transmittance(s, lut0, ray, t, &chord);
        if (cloud_observer_blocks(s->cloud.observer, v3_scale(ray.dir, t), ray.sun_dir))
            sun_t = v3(0.0f, 0.0f, 0.0f);
        vec3 cloud_t = v3_exp(v3_scale(sigma_c, -chord));
        vec3 sigma_t = atmosphere_extinction(a, h);
        vec3 scattering = v3_add(v3_scale(beta_r, rho_r * p_r), v3_scale(beta_m, rho_m * p_m));
        vec3 source = v3_mul(v3_mul(v3_mul(scattering, E), sun_t), cloud_t);
#ifdef ATMO_MS_LUT_H
        if (use_ms) {
            float r_t = geometry_radius_at(ray.r, ray.mu, t);
            float mu_s_t = atmo_clamp_cos((ray.r * ray.mu_s + t * ray.nu) / r_t);
            vec3 sigma_s = v3_add(v3_scale(beta_r, rho_r), v3_scale(beta_m, rho_m));
            vec3 psi = ms_lut_lookup(a, ms, ms_w, ms_h, r_t, mu_s_t);
            source = v3_add(source, v3_mul(v3_mul(sigma_s, psi), cloud_t));
        }
#endif
        *L = v3_add(*L, v3_mul(v3_mul(*T, source), cloud_weight3(sigma_t, dt)));
        *T = v3_mul(*T, v3_exp(v3_scale(sigma_t, -dt)));
    }
}

/* One cloud segment [t0, t1]: steps equal in optical depth (channel y), octaves of multiple
 * scattering, the atmosphere's extinction (taken at the segment's middle) on top. */
ATMO_FN void cloud_segment(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_GLOBAL const float4 *lut0,
                           ATMO_GLOBAL const float4 *table,
                             cloud_ray ray, float t0, float t1, float jitter, vec3 *L, vec3 *T)
{
    ATMO_GLOBAL const atmo_gpu_atmosphere *a = &s->atmosphere;
    vec3 E = v3_from4(a->solar_irradiance);
    vec3 sigma = v3_from4(s->cloud.extinction), albedo = v3_from4(s->cloud.albedo);
    vec3 sigma_v = v3_add(sigma, atmosphere_extinction(
                                     a, geometry_altitude_at(ray.r, ray.mu, 0.5f * (t0 + t1),
                                                             a->bottom_radius)));
    float len = fminf(t1 - t0, CLOUD_TAU_CUT / sigma.y);
    int n = s->cloud.steps;
    float dt = len / (float)n;
    vec3 p0 = cloud_phase(s, table, ray.nu);
    vec3 k_src = v3_mul(v3_mul(sigma, albedo), E);
    float chord0, chord1;
    vec3 sun0 = cloud_sun_transmittance(s, lut0, ray, t0, &chord0);
    for (int j = 0; j < n; j++) {
        float ta = t0 + (float)j * dt;
        vec3 sun1 = cloud_sun_transmittance(s, lut0, ray, ta + dt, &chord1);
        /* the observer's shadow is sharp: test it at a jittered point of the step */
        vec3 sun_t = cloud_observer_blocks(s->cloud.observer, v3_scale(ray.dir, ta + jitter * dt),
                                           ray.sun_dir)
                         ? v3(0.0f, 0.0f, 0.0f)
                         : sun0;
        float sa = 1.0f, sb = 1.0f, sc = 1.0f;
        for (int i = 0; i < ATMO_CLOUD_OCTAVES; i++) {
            vec3 p = i == 0 ? p0
                            : v3(phase_henyey_greenstein(ray.nu, s->cloud.g.x * sc),
                                 phase_henyey_greenstein(ray.nu, s->cloud.g.y * sc),
                                 phase_henyey_greenstein(ray.nu, s->cloud.g.z * sc));
            vec3 sig_sun = v3_scale(sigma, sa);
            vec3 source = v3_scale(v3_mul(v3_mul(k_src, p), sun_t), sb);
            vec3 x0 = v3_scale(sig_sun, chord0);
            vec3 w = cloud_exp_mean3(x0, v3_add(v3_scale(sig_sun, chord1), v3_scale(sigma_v, dt)),
                                       dt);
            *L = v3_add(*L, v3_mul(v3_mul(*T, source), w));
            sa *= CLOUD_OCTAVE_A;
            sb *= CLOUD_OCTAVE_B;
            sc *= CLOUD_OCTAVE_C;
        }
        *T = v3_mul(*T, v3_exp(v3_scale(sigma_v, -dt)));
        chord0 = chord1;
        sun0 = sun1;
    }
    /* what lies beyond the optical-depth cut */
    *T = v3_mul(*T, v3_exp(v3_scale(sigma_v, -(t1 - t0 - len))));
}

/* Sky radiance along (r, mu, mu_s, nu) through the atmosphere, the cloud shell and past the
 * observer, up to a black surface at distance t_max (INFINITY: none), as sky_integrate
 * (sky_single.h) with the same outputs; lut0 is the transmittance LUT, table the droplets'
 * phase table (cloud_phase_table), ms (ms_w x ms_h) the Psi_ms LUT of method march, used when
 * use_ms (and when ms_lut.h is compiled in). */
ATMO_FN void cloud_integrate(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_GLOBAL const float4 *lut0,
                             ATMO_GLOBAL const float4 *table,
                             ATMO_GLOBAL const float4 *ms, int ms_w, int ms_h, int use_ms, float r,
                             float mu, float mu_s, float nu, float t_max, int n, float jitter,
                             vec3 *sky, vec3 *sun, vec3 *view_t)
{
    ATMO_GLOBAL const atmo_gpu_atmosphere *a = &s->atmosphere;
    int tw = s->transmittance_width, th = s->transmittance_height;
    vec3 E = v3_from4(a->solar_irradiance);
    float R = a->bottom_radius, h_cam = r - R;
    vec3 sun_disc = atmosphere_sun_disc_radiance(a, s->sun_direction.w);
    int looks_at_sun = nu >= s->sun_direction.w;
    *sky = v3(0.0f, 0.0f, 0.0f);
    *sun = v3(0.0f, 0.0f, 0.0f);
    *view_t = v3(1.0f, 1.0f, 1.0f);

    cloud_ray ray;
    ray.r = r, ray.mu = mu, ray.mu_s = mu_s, ray.nu = nu;
    ray.dir = cloud_view_direction(mu, mu_s, nu);
    ray.sun_dir = v3(atmo_safe_sqrt(1.0f - mu_s * mu_s), mu_s, 0.0f);

    /* the atmosphere's extent along the ray */
    float top_h = a->top_radius - R, t_start = 0.0f, t_end, ta0, ta1;
    if (!cloud_sphere_roots(r * mu, (h_cam - top_h) * (r + a->top_radius), &ta0, &ta1) ||
        ta1 <= 0.0f) {
        if (looks_at_sun)
            *sun = sun_disc;
        return;
    }
    t_start = fmaxf(ta0, 0.0f);
    t_end = ta1;
    float tg0, tg1;
    int hits_ground = mu < 0.0f && cloud_sphere_roots(r * mu, h_cam * (r + R), &tg0, &tg1) &&
                      tg0 > 0.0f;
    if (hits_ground)
        t_end = tg0;
    float t_obs = cloud_observer_hit(s->cloud.observer, ray.dir);
    int hits_observer = t_obs >= 0.0f && t_obs < t_end;
    if (hits_observer)
        t_end = t_obs, hits_ground = 0;
    int blocked = t_max < t_end; /* by the black surface at t_max */
    if (blocked)
        t_end = t_max, hits_ground = hits_observer = 0;
    if (t_end <= t_start)
        return;

    /* the cloud segments: inside the top sphere and outside the base sphere */
    float base = s->cloud.base_m, top = s->cloud.top_m;
    float c_lo[2], c_hi[2], o0, o1, i0, i1;
    int nc = 0;
    if (cloud_sphere_roots(r * mu, (h_cam - top) * (r + R + top), &o0, &o1)) {
        float lo[2] = {o0, 0.0f}, hi[2] = {o1, 0.0f};
        int parts = 1;
        if (cloud_sphere_roots(r * mu, (h_cam - base) * (r + R + base), &i0, &i1)) {
            hi[0] = i0, lo[1] = i1, hi[1] = o1;
            parts = 2;
        }
        for (int k = 0; k < parts; k++) {
            float l = fmaxf(lo[k], t_start), u = fminf(hi[k], t_end);
            if (u > l)
                c_lo[nc] = l, c_hi[nc] = u, nc++;
        }
    }
    float atm_len = t_end - t_start;
    for (int k = 0; k < nc; k++)
        atm_len -= c_hi[k] - c_lo[k];

    vec3 L = v3(0.0f, 0.0f, 0.0f), T = v3(1.0f, 1.0f, 1.0f);
    float prev = t_start;
    for (int k = 0; k <= nc; k++) {
        float next = k < nc ? c_lo[k] : t_end;
        if (next > prev && atm_len > 0.0f) {
            int steps = (int)ceilf((float)n * (next - prev) / atm_len);
            cloud_atmosphere_segment(s, lut0, ms, ms_w, ms_h, use_ms, ray, prev, next,
                                       steps < 1 ? 1 : steps, jitter, &L, &T);
        }
        if (k < nc) {
            cloud_segment(s, lut0, table, ray, c_lo[k], c_hi[k], jitter, &L, &T);
            prev = c_hi[k];
        }
    }

    if (hits_observer) {
        vec3 p = v3_scale(ray.dir, t_end);
        vec3 normal = v3_normalize(
            v3_sub(p, v3(s->cloud.observer.x, s->cloud.observer.y, s->cloud.observer.z)));
        /* lit like the camera's surroundings (the sphere is small); its own shadow test
         * would block it, so the cloud's chord is taken at the camera */
        float chord = cloud_shell_chord(R, base, top, h_cam, r, mu_s);
        vec3 sun_t = v3_mul(atmosphere_sun_transmittance(a, lut0, tw, th, r, mu_s),
                            v3_exp(v3_scale(v3_from4(s->cloud.extinction), -chord)));
        float cos_i = fmaxf(v3_dot(normal, ray.sun_dir), 0.0f);
        L = v3_add(L, v3_mul(T, v3_scale(v3_mul(E, sun_t), CLOUD_OBSERVER_ALBEDO * cos_i /
                                                               ATMO_PI)));
    } else if (hits_ground) {
        float mu_s_g = atmo_clamp_cos((r * mu_s + t_end * nu) / R);
        vec3 sun_t = v3_mul(atmosphere_sun_transmittance(a, lut0, tw, th, R, mu_s_g),
                            v3_exp(v3_scale(v3_from4(s->cloud.extinction),
                                            -cloud_shell_chord(R, base, top, 0.0f, R, mu_s_g))));
        vec3 irradiance = v3_scale(v3_mul(E, sun_t), fmaxf(mu_s_g, 0.0f));
        L = v3_add(L, v3_mul(T, v3_scale(v3_mul(v3_from4(a->ground_albedo), irradiance),
                                         1.0f / ATMO_PI)));
    } else if (looks_at_sun && !blocked) {
        /* the sun through the atmosphere and the cloud: T_atm from where the ray enters it */
        float r0 = geometry_radius_at(r, mu, t_start);
        float mu0 = atmo_clamp_cos((r * mu + t_start) / r0);
        vec3 to_space = atmosphere_transmittance_to_top(a, lut0, tw, th, r0, mu0);
        vec3 cloud_t = v3(1.0f, 1.0f, 1.0f);
        for (int k = 0; k < nc; k++)
            cloud_t = v3_mul(cloud_t, v3_exp(v3_scale(v3_from4(s->cloud.extinction),
                                                      -(c_hi[k] - c_lo[k]))));
        *sun = v3_mul(v3_mul(sun_disc, to_space), cloud_t);
    }
    *sky = L;
    *view_t = T;
}

#endif
