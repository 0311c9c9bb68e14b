/* test_path_terrain — the terrain as a surface of the path tracer (kernels/render/surfaces.h):
 * its light on a flat patch, and its shadow on the sun behind a ridge.
 * labels: render kernel stat slow
 *
 * Oracles:
 *  1. A flat patch (terrain.max_height_m 1 mm, all land: grass, normal = vertical; the same
 *     patch as test_terrain_shading's) in the uniform test world (path.sky = uniform: sky
 *     radiance L_u in every direction, no air, the sun's irradiance E unattenuated), seen from
 *     100 m under a sun 60 degrees from the zenith. A Lambertian plane of albedo a under a sun
 *     of cosine mu_s and a uniform upper hemisphere returns, in closed form,
 *         L = a / pi (E mu_s + pi L_u)
 *     (the sun's disc: mean cosine mu_s (1 + cos alpha) / 2, 6e-6 below mu_s; the hit points'
 *     verticals differ from the camera's by < 2e-5 rad): the path tracer's estimate of every
 *     pixel (8 x 8, 64 samples, N_b = 2, sun and sky next-event estimation with MIS) must lie
 *     within 5 standard errors of it (per pixel and channel, the standard error from the
 *     pixel's second moment), the image mean within 4 of the mean's, plus 1e-5 relative of
 *     float rounding.
 *  2. A shadow behind a ridge: the thesis terrain (seed 46, unwarped: terrain.warp=0, the
 *     field this view was set up on; with the default warp the relief moves and the host
 *     reference classifies none of the 256 pixels, neither dark nor lit) seen straight down
 *     from 1 km over
 *     the world's origin (fov 10 degrees, 16 x 16), the sun placed behind the highest summit
 *     within 60 km (aimed from the origin at the point 300 m below the summit's top, about 1
 *     degree high), in the uniform world with a black sky and one reflection (N_b = 1), so a
 *     pixel's radiance is the sunlight its terrain reflects directly; the pixel filter shrunk
 *     to sigma 0.1 px truncated at 0.5 px (a pixel's samples lie within 0.5 px of its centre).
 *     The host's double-precision terrain (host/terrain/terrain_ref.c) classifies pixels: for
 *     the primary rays through 3 x 3 positions spanning that support, from each hit point
 *     raised 0.5 m, and raised as high as the path tracer's shadow rays may start (the hit's
 *     tolerance plus its lift: surfaces.h), five rays toward the sun's centre and four points
 *     of its rim are marched to terrain.shadow_far_m (the first 10 m in 0.25 m steps, then
 *     terrain_ref_hit); "dark" where every ray hits terrain and lies 0.5 m deep in it (50 m
 *     beyond the hit, or within the first 10 m), "lit" where every ray misses by more than
 *     2 m, both only where the surface faces the sun (N . s > 0.05). Dark pixels must be
 *     exactly 0 (every sample's shadow ray blocked), lit ones (if any) > 0, and with
 *     terrain.shadow = none the same dark pixels must be > 0 (so the darkness is the
 *     terrain's shadow). At least 3 dark pixels must be found. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/terrain_ref.h"
#include "terrain/terrain_material.h"
#include "testlib.h"
#include "testscene.h"

/* Render the scene's image: mean and standard error per pixel, 3 floats each. */
static int render(atmo_scene *s, float *mean, float *se)
{
    atmo_plan p;
    test_plan(s, &p);
    int rc = test_render_plan(&p, 0, 0, mean, se, NULL);
    atmo_plan_free(&p);
    return rc;
}

#define FW 8
#define FH 8

static int flat_patch(void)
{
    atmo_scene s;
    test_scene_preset(&s, "sky-noon");
    static const char *const keys[] = {
        "terrain.enabled=true", "terrain.max_height_m=0.001", "terrain.land_fraction=1",
        "camera.position_m=0,100,0", "camera.pitch_deg=-60", "sun.zenith_deg=60",
        "sun.azimuth_deg=30", "render.mode=path", "path.sky=uniform",
        "path.uniform_sky=0.05,0.08,0.12", "path.bounces=2", "image.width=8", "image.height=8",
        "image.samples=64", NULL};
    for (int i = 0; keys[i]; i++)
        test_scene_set(&s, keys[i]);
    atmo_plan p;
    test_plan(&s, &p);
    double E[3] = {p.gpu.atmosphere.solar_irradiance.x, p.gpu.atmosphere.solar_irradiance.y,
                   p.gpu.atmosphere.solar_irradiance.z};
    atmo_plan_free(&p);
    static float mean[FW * FH * 3], se[FW * FH * 3];
    if (render(&s, mean, se))
        return 1;
    vec3 albedo = terrain_material_albedo(TERRAIN_GRASS);
    double a[3] = {albedo.x, albedo.y, albedo.z}, Lu[3] = {0.05, 0.08, 0.12};
    double mu_s = cos(60.0 * M_PI / 180.0), worst_z = 0;
    for (int c = 0; c < 3; c++) {
        double want = a[c] / M_PI * (E[c] * mu_s + M_PI * Lu[c]), sum = 0, var = 0;
        for (int i = 0; i < FW * FH; i++) {
            double got = mean[3 * i + c], e = se[3 * i + c];
            double z = (got - want) / sqrt(e * e + 1e-10 * want * want);
            worst_z = fmax(worst_z, fabs(z));
            CHECK(fabs(got - want) <= 5.0 * e + 1e-5 * want);
            sum += got;
            var += e * e;
        }
        double m = sum / (FW * FH), m_se = sqrt(var) / (FW * FH);
        printf("flat patch channel %d: path traced %.6f +- %.6f, closed form %.6f, rel diff "
               "%+.5f, z %+.2f\n",
               c, m, m_se, want, m / want - 1.0, (m - want) / m_se);
        CHECK(fabs(m - want) <= 4.0 * m_se + 1e-5 * want);
    }
    printf("flat patch: worst pixel |z| %.2f over %d pixels x 3 channels\n", worst_z, FW * FH);
    return 0;
}

#define SW 16
#define SH 16
#define SITE_X 23796.0
#define SITE_Z 16636.0
#define SHADOW_FAR_M 20000.0

typedef struct site {
    const atmo_gpu_terrain_field *f;
    double R, cam[3], fwd[3], right[3], up[3], tan_half, sun[3], e1[3], e2[3], alpha, tol;
} site;

static void unit3(double v[3])
{
    double l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int k = 0; k < 3; k++)
        v[k] /= l;
}

static void cross3(const double a[3], const double b[3], double out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

/* The world point of the surface at planar (u, v) raised by `above` metres along the vertical. */
static void surface_point(const site *g, double u, double v, double above, double out[3])
{
    double h = fmax(terrain_ref_height(g->f, u, v, NULL, NULL), 0.0);
    double n[3] = {u / g->R, sqrt(1.0 - (u * u + v * v) / (g->R * g->R)), v / g->R};
    for (int k = 0; k < 3; k++)
        out[k] = n[k] * (g->R + h + above) - (k == 1 ? g->R : 0.0);
}

/* Whether the five shadow rays from q (toward the sun's centre and four points of its rim) all
 * hit terrain deeply (1), all miss it by more than 2 m (0), or neither (-1). */
static int sun_rays(const site *g, const double q[3])
{
    static const double rim[5][2] = {{0, 0}, {1, 0}, {-1, 0}, {0, 1}, {0, -1}};
    int hits = 0, clear = 0;
    for (int r = 0; r < 5; r++) {
        double w[3];
        for (int k = 0; k < 3; k++)
            w[k] = g->sun[k] + g->alpha * (rim[r][0] * g->e1[k] + rim[r][1] * g->e2[k]);
        unit3(w);
        /* the first 10 m in 0.25 m steps (the ray leaves the point's own surface), then the
         * reference march from there */
        double near = INFINITY, o10[3], ts, m = INFINITY;
        for (int j = 1; j <= 40; j++) {
            double qj[3];
            for (int k = 0; k < 3; k++)
                qj[k] = q[k] + 0.25 * j * w[k];
            near = fmin(near, terrain_ref_clearance(g->f, g->R, 0.0, qj));
        }
        if (near < -0.5) { /* deep in the terrain within 10 m */
            hits++;
            continue;
        }
        if (near < 0.1)
            return -1;
        for (int k = 0; k < 3; k++)
            o10[k] = q[k] + 10.0 * w[k];
        if (terrain_ref_hit(g->f, g->R, 0.0, o10, w, SHADOW_FAR_M - 10.0, 2.0, &ts, &m)) {
            double deep[3];
            for (int k = 0; k < 3; k++)
                deep[k] = o10[k] + (ts + 50.0) * w[k];
            hits += terrain_ref_clearance(g->f, g->R, 0.0, deep) < -0.5;
        } else {
            clear += m > 2.0;
        }
    }
    return hits == 5 ? 1 : clear == 5 ? 0 : -1;
}

/* 0 lit, 1 dark, -1 neither, for the primary ray through image position (px, py): the shadow
 * rays from 0.5 m above its hit and from as high as the path tracer's shadow rays may start
 * (the hit's tolerance eps(t) = 0.01 m + tau t above the surface plus the lift 0.1 m +
 * 2 tau t: surfaces.h) must agree, where the surface faces the sun (N . s > 0.05). */
static int classify(const site *g, double px, double py)
{
    double sx = (2.0 * px / SW - 1.0) * g->tan_half * SW / SH;
    double sy = (1.0 - 2.0 * py / SH) * g->tan_half, d[3], t, mc;
    for (int k = 0; k < 3; k++)
        d[k] = g->fwd[k] + sx * g->right[k] + sy * g->up[k];
    unit3(d);
    if (!terrain_ref_hit(g->f, g->R, 0.0, g->cam, d, 1e5, 2.0, &t, &mc))
        return -1;
    double q[3], grad[2];
    for (int k = 0; k < 3; k++)
        q[k] = g->cam[k] + t * d[k];
    /* the vertical at the hit and the surface's normal in its tangent frame (terrain.h) */
    double n[3] = {q[0], q[1] + g->R, q[2]};
    unit3(n);
    terrain_ref_height(g->f, g->R * n[0], g->R * n[2], grad, NULL);
    double gn = grad[0] * n[0] + grad[1] * n[2];
    double N[3] = {n[0] - (grad[0] - gn * n[0]), n[1] + gn * n[1], n[2] - (grad[1] - gn * n[2])};
    unit3(N);
    if (!(N[0] * g->sun[0] + N[1] * g->sun[1] + N[2] * g->sun[2] > 0.05))
        return -1;
    double lo[3], hi[3], top = 0.11 + 3.0 * g->tol * t;
    for (int k = 0; k < 3; k++) {
        lo[k] = q[k] + 0.5 * n[k];
        hi[k] = q[k] + (0.5 + top) * n[k];
    }
    int a = sun_rays(g, lo);
    return a == sun_rays(g, hi) ? a : -1;
}

static int ridge_shadow(void)
{
    atmo_scene s;
    test_scene_preset(&s, "sky-noon");
    static const char *const keys[] = {
        "terrain.enabled=true", "terrain.seed=46", "terrain.warp=0", "camera.pitch_deg=-90",
        "camera.yaw_deg=0",
        "camera.fov_deg=10", "terrain.shadow=exact", "terrain.shadow_far_m=20000",
        "render.mode=path", "path.sky=uniform", "path.uniform_sky=0,0,0", "path.bounces=1",
        "path.filter_radius_px=0.5", "path.filter_sigma_px=0.1", "image.width=16",
        "image.height=16", "image.samples=16", NULL};
    for (int i = 0; keys[i]; i++)
        test_scene_set(&s, keys[i]);
    atmo_plan p;
    test_plan(&s, &p);
    site g;
    g.f = &p.gpu.terrain.field;
    g.R = p.atmosphere.bottom_radius_m;
    /* the highest point of a 400 m grid within 60 km of the thesis site (a summit 36 km from
     * the world's origin); the site the origin; the sun behind the summit, aimed from the site
     * at the point 300 m below its top along its vertical, so the site's shadow ray runs deep
     * through the mountain */
    double best_h = -1, peak_u = 0, peak_v = 0, site_u = 0, site_v = 0, site_h;
    for (double du = -60000; du <= 60000; du += 400)
        for (double dv = -60000; dv <= 60000; dv += 400) {
            double h = terrain_ref_height(g.f, SITE_X + du, SITE_Z + dv, NULL, NULL);
            if (h > best_h)
                best_h = h, peak_u = SITE_X + du, peak_v = SITE_Z + dv;
        }
    double aim[3], site_p[3];
    surface_point(&g, peak_u, peak_v, -300.0, aim);
    site_h = fmax(terrain_ref_height(g.f, site_u, site_v, NULL, NULL), 0.0);
    surface_point(&g, site_u, site_v, 0.5, site_p);
    for (int k = 0; k < 3; k++)
        g.sun[k] = aim[k] - site_p[k];
    unit3(g.sun);
    double zen = acos(g.sun[1]) * 180.0 / M_PI, az = atan2(g.sun[0], g.sun[2]) * 180.0 / M_PI;
    char buf[96];
    snprintf(buf, sizeof buf, "sun.zenith_deg=%.9f", zen);
    test_scene_set(&s, buf);
    snprintf(buf, sizeof buf, "sun.azimuth_deg=%.9f", az);
    test_scene_set(&s, buf);
    surface_point(&g, site_u, site_v, 1000.0, g.cam);
    snprintf(buf, sizeof buf, "camera.position_m=%.17g,%.17g,%.17g", g.cam[0], g.cam[1], g.cam[2]);
    test_scene_set(&s, buf);
    atmo_plan_free(&p);
    test_plan(&s, &p);
    g.f = &p.gpu.terrain.field;
    g.tol = p.gpu.terrain.tolerance;
    const atmo_gpu_camera *c = &p.gpu.camera;
    double basis[3][3] = {{c->forward.x, c->forward.y, c->forward.z},
                          {c->right.x, c->right.y, c->right.z},
                          {c->up.x, c->up.y, c->up.z}};
    memcpy(g.fwd, basis[0], sizeof g.fwd);
    memcpy(g.right, basis[1], sizeof g.right);
    memcpy(g.up, basis[2], sizeof g.up);
    g.tan_half = tan(0.5 * s.camera.fov_deg * M_PI / 180.0);
    /* the plan's sun (float) is the one the kernels sample around */
    g.sun[0] = p.gpu.sun_direction.x, g.sun[1] = p.gpu.sun_direction.y;
    g.sun[2] = p.gpu.sun_direction.z;
    unit3(g.sun);
    double helper[3] = {0, 1, 0};
    cross3(g.sun, helper, g.e1);
    unit3(g.e1);
    cross3(g.sun, g.e1, g.e2);
    g.alpha = s.sun.angular_radius_deg * M_PI / 180.0;
    printf("ridge shadow: summit %.0f m at (%.0f, %.0f), site %.0f m at (%.0f, %.0f), the sun "
           "%.2f degrees high at azimuth %.2f\n",
           best_h, peak_u, peak_v, site_h, site_u, site_v, 90.0 - zen, az);

    int kind[SW * SH], dark = 0, lit = 0;
    for (int y = 0; y < SH; y++)
        for (int x = 0; x < SW; x++) {
            int k = classify(&g, x + 0.5, y + 0.5);
            for (int j = 0; k >= 0 && j < 9; j++)
                if (j != 4 && classify(&g, x + 0.5 + 0.5 * (j % 3 - 1),
                                       y + 0.5 + 0.5 * (j / 3 - 1)) != k)
                    k = -1;
            kind[y * SW + x] = k;
            dark += k == 1, lit += k == 0;
        }
    atmo_plan_free(&p);
    printf("ridge shadow: %d dark and %d lit pixels of %d classified by the host reference\n",
           dark, lit, SW * SH);
    CHECK(90.0 - zen > 0.5);
    CHECK(dark >= 3);

    static float mean[SW * SH * 3], se[SW * SH * 3], open[SW * SH * 3];
    if (render(&s, mean, se))
        return 1;
    test_scene_set(&s, "terrain.shadow=none");
    if (render(&s, open, se))
        return 1;
    double dark_max = 0, dark_open_min = INFINITY, lit_min = INFINITY;
    for (int i = 0; i < SW * SH; i++)
        for (int ch = 0; ch < 3; ch++) {
            if (kind[i] == 1) {
                dark_max = fmax(dark_max, mean[3 * i + ch]);
                dark_open_min = fmin(dark_open_min, open[3 * i + ch]);
            } else if (kind[i] == 0) {
                lit_min = fmin(lit_min, mean[3 * i + ch]);
            }
        }
    printf("ridge shadow: dark pixels at most %.3g (shadowless render: at least %.3g), lit "
           "pixels at least %.3g\n",
           dark_max, dark_open_min, lit_min);
    CHECK(dark_max == 0.0);
    CHECK(dark_open_min > 0.0);
    CHECK(lit == 0 || lit_min > 0.0);
    return 0;
}

int main(void)
{
    test_require_opencl();
    test_fresh_cache_dir();
    if (flat_patch() || ridge_shadow())
        return 1;
    return test_finish();
}
