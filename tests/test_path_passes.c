/* test_path_passes — the path tracer's render passes (kernels/render/path.cl, path.passes).
 * labels: render kernel
 *
 * Oracles:
 *   - The light passes are a partition of each sample's radiance (kernels/render/path.h), so
 *     their means sum to the beauty image's: per pixel and channel within 1e-5 relative plus
 *     1e-7 absolute (float rounding of sums over 16 samples of six terms).
 *   - Depth and normal against the closed form of a ray and a sphere: for the sphere of centre
 *     c and radius R, t(d) = -b - sqrt(b^2 - |f|^2 + R^2) with f = -c, b = f . d, and
 *     n = (t d - c) / R. With the pixel filter shrunk to sigma 0.1 px truncated at 0.5 px, a
 *     pixel's samples lie in the disc of radius 0.5 px around its centre, so the mean depth
 *     (and each component of the mean normal) lies within the range the closed form takes over
 *     that disc (evaluated on a 21 x 21 grid of offsets; plus 1e-4 of float rounding). Checked
 *     on every pixel whose whole disc sees the sphere; the others see the sky, whose depth is
 *     1e10 (to float rounding of its sum, 1e-6) and normal 0 where no sample of the pixel hits.
 *   - The albedo pass is the sphere's albedo on those pixels (exactly: every sample hits it).
 * World: the uniform test world (no air), a sphere of albedo (0.6, 0.4, 0.2) 6 m ahead and
 * 0.5 m right of the camera, sun at zenith 30 degrees, sky (0.1, 0.2, 0.3); 20 x 16 pixels.
 * The partition again with scattering events in the cloud layer (path.clouds = volume: the
 * camera in a cloud layer of the same world, the sphere beside it), where the Clouds pass must
 * hold light (positive in every channel of the image's sum). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/render.h"
#include "atmo/session.h"
#include "testlib.h"
#include "testscene.h"

#define W 20
#define H 16
#define PATH_PASS_CLOUDS_PLANE 5 /* kernels/render/path.h's PATH_PASS_CLOUDS */

static double sphere_t(const double d[3], const double c[3], double R)
{
    double b = -(d[0] * c[0] + d[1] * c[1] + d[2] * c[2]);
    double f2 = c[0] * c[0] + c[1] * c[1] + c[2] * c[2], disc = b * b - f2 + R * R;
    return disc < 0.0 ? -1.0 : -b - sqrt(disc);
}

/* The light passes of the render r against its beauty image: the pixels whose sum differs by
 * more than float rounding; *worst the largest relative difference. */
static int pass_sum_bad(const atmo_render_result *r, size_t pixels, double *worst)
{
    int bad = 0;
    *worst = 0.0;
    for (size_t i = 0; i < pixels; i++)
        for (int c = 0; c < 3; c++) {
            double total = 0.0;
            for (int k = 0; k < ATMO_PATH_LIGHT_PASSES; k++)
                total += r->passes[4 * (pixels * k + i) + c];
            double beauty = r->rgb[3 * i + c], diff = fabs(total - beauty);
            *worst = fmax(*worst, diff / fmax(beauty, 1e-30));
            bad += diff > 1e-5 * fabs(beauty) + 1e-7;
        }
    return bad;
}

static void test_cloud_passes(void)
{
    atmo_scene s;
    test_scene_preset(&s, "sky-noon");
    test_scene_set(&s, "render.mode=path");
    test_scene_set(&s, "path.passes=true");
    test_scene_set(&s, "path.sky=uniform");
    test_scene_set(&s, "path.uniform_sky=0.1,0.2,0.3");
    test_scene_set(&s, "path.ground=false");
    test_scene_set(&s, "sun.zenith_deg=30");
    test_scene_set(&s, "clouds.enabled=true");
    test_scene_set(&s, "path.clouds=volume");
    test_scene_set(&s, "clouds.bottom_m=1000");
    test_scene_set(&s, "clouds.top_m=2000");
    test_scene_set(&s, "clouds.fade_m=300");
    test_scene_set(&s, "clouds.coverage=0.7");
    test_scene_set(&s, "clouds.extinction_per_m=0.005");
    test_scene_set(&s, "camera.position_m=0,1500,0");
    test_scene_set(&s, "image.width=8");
    test_scene_set(&s, "image.height=8");
    test_scene_set(&s, "image.samples=8");
    test_scene_set(&s, "objects=[{\"type\": \"sphere\", \"center_m\": [0.5, 1500, 6], "
                       "\"radius_m\": 1.5, \"albedo\": [0.6, 0.4, 0.2]}]");
    atmo_plan p;
    test_plan(&s, &p);
    atmo_render_settings rs;
    atmo_render_settings_default(&rs);
    atmo_render_result r;
    atmo_err e;
    if (atmo_render(&p, &rs, &r, &e)) {
        fprintf(stderr, "render failed: %s\n", e.msg);
        exit(1);
    }
    size_t pixels = 64;
    double worst, clouds[3] = {0.0, 0.0, 0.0};
    int bad = pass_sum_bad(&r, pixels, &worst);
    for (size_t i = 0; i < pixels; i++)
        for (int c = 0; c < 3; c++)
            clouds[c] += r.passes[4 * (pixels * PATH_PASS_CLOUDS_PLANE + i) + c];
    printf("clouds (volume): light passes vs beauty worst relative difference %.2g; Clouds pass "
           "sum %.3g %.3g %.3g\n",
           worst, clouds[0], clouds[1], clouds[2]);
    CHECK(r.nonfinite == 0 && bad == 0);
    CHECK(clouds[0] > 0.0 && clouds[1] > 0.0 && clouds[2] > 0.0);
    atmo_render_result_free(&r);
    atmo_plan_free(&p);
}

int main(void)
{
    test_require_opencl();
    atmo_scene s;
    test_scene_preset(&s, "sky-noon");
    test_scene_set(&s, "render.mode=path");
    test_scene_set(&s, "path.passes=true");
    test_scene_set(&s, "path.sky=uniform");
    test_scene_set(&s, "path.uniform_sky=0.1,0.2,0.3");
    test_scene_set(&s, "path.ground=false");
    test_scene_set(&s, "path.filter_sigma_px=0.1");
    test_scene_set(&s, "path.filter_radius_px=0.5");
    test_scene_set(&s, "sun.zenith_deg=30");
    test_scene_set(&s, "camera.position_m=0,100,0");
    test_scene_set(&s, "camera.pitch_deg=0");
    test_scene_set(&s, "camera.yaw_deg=0");
    test_scene_set(&s, "image.width=20");
    test_scene_set(&s, "image.height=16");
    test_scene_set(&s, "image.samples=16");
    test_scene_set(&s, "objects=[{\"type\": \"sphere\", \"center_m\": [0.5, 100, 6], "
                       "\"radius_m\": 1.5, \"albedo\": [0.6, 0.4, 0.2]}]");
    atmo_plan p;
    test_plan(&s, &p);
    CHECK(p.pass_planes == ATMO_PATH_PASS_PLANES);
    atmo_render_settings rs;
    atmo_render_settings_default(&rs);
    atmo_render_result r;
    atmo_err e;
    if (atmo_render(&p, &rs, &r, &e)) {
        fprintf(stderr, "render failed: %s\n", e.msg);
        return 1;
    }
    CHECK(r.pass_planes == ATMO_PATH_PASS_PLANES && r.nonfinite == 0);
    size_t pixels = (size_t)W * H;
    double worst_sum;
    int sum_bad = pass_sum_bad(&r, pixels, &worst_sum);
    printf("light passes vs beauty: worst relative difference %.2g\n", worst_sum);
    CHECK(sum_bad == 0);

    double forward[3], right[3], up[3], c[3] = {0.5, 0.0, 6.0}, R = 1.5;
    atmo_camera_basis(0.0, 0.0, forward, right, up);
    double th = tan(22.5 * M_PI / 180.0);
    const float *np = r.passes + 4 * pixels * ATMO_PATH_LIGHT_PASSES;
    const float *ap = r.passes + 4 * pixels * (ATMO_PATH_LIGHT_PASSES + 1);
    int inside = 0, depth_bad = 0, normal_bad = 0, albedo_bad = 0, sky_bad = 0;
    double worst_depth = 0.0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            double t_lo = INFINITY, t_hi = -INFINITY, n_lo[3], n_hi[3];
            int all = 1, any = 0;
            for (int k = 0; k < 3; k++)
                n_lo[k] = INFINITY, n_hi[k] = -INFINITY;
            for (int a = -10; a <= 10; a++)
                for (int b = -10; b <= 10; b++) {
                    double ox = 0.05 * a, oy = 0.05 * b;
                    if (ox * ox + oy * oy > 0.25)
                        continue;
                    double sx = (2.0 * (x + 0.5 + ox) / W - 1.0) * th * W / H;
                    double sy = (1.0 - 2.0 * (y + 0.5 + oy) / H) * th, d[3];
                    for (int k = 0; k < 3; k++)
                        d[k] = forward[k] + sx * right[k] + sy * up[k];
                    double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
                    for (int k = 0; k < 3; k++)
                        d[k] /= len;
                    double t = sphere_t(d, c, R);
                    if (t < 0.0) {
                        all = 0;
                        continue;
                    }
                    any = 1;
                    t_lo = fmin(t_lo, t), t_hi = fmax(t_hi, t);
                    for (int k = 0; k < 3; k++) {
                        double n = (t * d[k] - c[k]) / R;
                        n_lo[k] = fmin(n_lo[k], n), n_hi[k] = fmax(n_hi[k], n);
                    }
                }
            size_t i = (size_t)y * W + x;
            double depth = np[4 * i + 3];
            if (!any) { /* every sample sees the sky */
                sky_bad += fabs(depth / 1e10 - 1.0) > 1e-6 || np[4 * i] != 0.0f || ap[4 * i] != 0.0f;
                continue;
            }
            if (!all)
                continue;
            inside++;
            worst_depth = fmax(worst_depth, fmax(t_lo - depth, depth - t_hi));
            depth_bad += depth < t_lo - 1e-4 || depth > t_hi + 1e-4;
            for (int k = 0; k < 3; k++)
                normal_bad += np[4 * i + k] < n_lo[k] - 1e-4 || np[4 * i + k] > n_hi[k] + 1e-4;
            albedo_bad += fabsf(ap[4 * i] - 0.6f) > 1e-6f || fabsf(ap[4 * i + 1] - 0.4f) > 1e-6f ||
                          fabsf(ap[4 * i + 2] - 0.2f) > 1e-6f;
        }
    printf("%d pixels on the sphere: depth outside its closed-form range by at most %.2g m; "
           "%d depth, %d normal, %d albedo, %d sky pixels wrong\n",
           inside, worst_depth, depth_bad, normal_bad, albedo_bad, sky_bad);
    CHECK(inside > 40);
    CHECK(depth_bad == 0 && normal_bad == 0 && albedo_bad == 0 && sky_bad == 0);
    atmo_render_result_free(&r);
    atmo_plan_free(&p);
    test_cloud_passes();
    return test_finish();
}
