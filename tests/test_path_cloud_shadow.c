/* test_path_cloud_shadow — cloud shadows in the path tracer: the direct sunlight a ground point
 * receives (kernels/render/path.h's path_sunlight: visibility_sun_surface, the layer's
 * clouds_media_sun_surface, cloud_layer_medium.h) is cut by the cloud layer's transmittance toward the
 * sun.
 * labels: render kernel slow
 *
 * Scene: the fBm cloud layer made thin and scattered (1-3 km, fades of 500 m, coverage 0.1,
 * density 0.5: optical depths toward the sun of 0-3, where the default layer's are > 20 under
 * every cloud; method march), the sun 30 degrees from the zenith, the ground sphere seen
 * straight down from 900 m (below the layer; fov 90 degrees, 8 x 8 pixels over 1.8 km, the
 * pixel filter shrunk to sigma 0.1 px within 0.5 px, 16 samples, one reflection: the Sun pass is
 * the primary hit's sunlight alone), the light march given 1000 steps over the whole layer
 * (clouds.light_steps, clouds.light_distance_m). The camera's x is the first on the x axis, in
 * 250 m steps, whose patch's edges (x -+ 800 m) have T < 0.6 on one side and T > 0.9 on the
 * other (a 300-step host rule: only a choice of place), so the patch straddles a shadow's edge.
 * Oracle: the layer's optical depth toward the sun integrated on the host in double (midpoint
 * rule, 2^14 steps from the ground point to the layer's top, of clouds.extinction_per_m x
 * clouds_density, the layer's density function in its host build) gives T(p) at each pixel
 * centre's ground point. The same scene with clouds.density = 0 (the same program, the same
 * random numbers; T = 1) is the open ground: the ratio of the Sun passes, pixel by pixel, must
 * equal T(p) within 3 times the host rule's own error at 1000 steps (|T_1000 - T_16384|: the
 * kernel's march has 1000) plus 0.005 (the pixel's footprint within the filter, the disc's
 * samples); and the patch must hold a shadowed pixel (T < 0.6) whose direct sun is under 0.7
 * of an open one's (T > 0.9).
 *
 * Part 2, the air in the layer's shadow with path.clouds = volume (the layer no medium of the
 * method; media/media_walk.h's media_walk_volume_sun ratio-tracks it toward the sun at every
 * air sample of the integrator). The same camera and layer, method single (the
 * single-scattering form the oracle integrates), the ground black (albedo 0: every surface
 * term and every continuation is zero, so the image is the air's in-scatter between the
 * camera and the ground), 64 view steps, 64 samples. The view rays stay below the layer, so
 * they meet no cloud and draw the same numbers with and without it: the open image
 * (clouds.density = 0) is what the renderer gave before the air saw the layer's shadow,
 * whatever the density.
 * Oracle: per pixel, the ratio rho = L_clouds / L_open of the host's single-scattering integral
 *     L = int_0^d T_air(0, t) [sigma_R(t) p_R(nu) + sigma_M,s(t) p_M(nu)] E T_sun(t) T_c(t) dt
 * (atmosphere_ref.h's optical depths and phases in double; T_c = 1 for L_open), a midpoint
 * rule of 256 points along the view ray, T_c(t) = exp(-tau) of the layer's optical depth along
 * the sun from the point through the layer's shell by a midpoint rule of 256 steps (9 m; the
 * finest octave's wavelength is ~200 m). The
 * ratio cancels the method's own error (transmittance LUT, float), common to both renders.
 * Test: D = mean_clouds - rho mean_open against its standard error
 * se = sqrt(se_clouds^2 + rho^2 se_open^2) (the two renders' per-pixel standard errors, taken
 * as independent: they share random numbers, are positively correlated, so this
 * overstates se): |D| < 4.4 se + b per pixel (64 tests, family-wise p ~ 1e-3), b the oracle's
 * own error times the open mean: 3 times the rule's change from half its points and steps, plus
 * the pixel's footprint (the filter's sigma 0.1 px: sigma^2/2 times the Laplacian of rho, the
 * half rule's five-point estimate from points 0.1 px off the centre); the image's sum of D within 4.4 of its standard error;
 * and the test's power: the open image (the renderer before the fix) lies more than 10 standard
 * errors from the oracle over the image, with a pixel of rho < 0.75. Then the determinism of
 * volume mode with the air's ratio tracking: tiles of 8 with one launch per sample and of 64
 * with no bound give the same image bitwise, every pixel finite. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "common/compat.h"
#include "clouds/cloud_layer.h"
#include "atmo/atmosphere_ref.h"
#include "atmo/render.h"
#include "testlib.h"
#include "testscene.h"

#define W 8
#define H 8
#define CAM_Y 900.0
#define SUN_PASS 3 /* PATH_PASS_SUN of kernels/render/path.h: the EXR layer Sun */

typedef struct world {
    const atmo_gpu_clouds *c;
    double R, cam[3], sun[3], ext, bottom, top;
} world;

/* The distance from world point g (inside the sphere) along the sun to the sphere of altitude
 * h. */
static double sun_exit(const world *w, const double g[3], double h)
{
    double c[3] = {g[0], g[1] + w->R, g[2]}, b = 0.0, cc = 0.0;
    for (int k = 0; k < 3; k++)
        b += c[k] * w->sun[k], cc += c[k] * c[k];
    double rt = w->R + h;
    return -b + sqrt(b * b - cc + rt * rt);
}

/* The layer's optical depth (green channel) along the sun from world point g between the
 * distances t0 and t1, n midpoint steps. */
static double sun_tau_between(const world *w, const double g[3], double t0, double t1, int n)
{
    double c[3] = {g[0], g[1] + w->R, g[2]}, len = t1 - t0, D = 0.0;
    for (int i = 0; i < n; i++) {
        double t = t0 + (i + 0.5) * len / n, q[3], x[3], r2 = 0.0;
        for (int k = 0; k < 3; k++) {
            x[k] = c[k] + t * w->sun[k];
            r2 += x[k] * x[k];
            q[k] = g[k] + t * w->sun[k] - w->cam[k];
        }
        vec3 p = {(float)q[0], (float)q[1], (float)q[2]};
        D += clouds_density(w->c, p, (float)(sqrt(r2) - w->R)) * len / n;
    }
    return w->ext * D;
}

/* The layer's optical depth toward the sun from world ground point g, n midpoint steps up to
 * the layer's top. */
static double sun_tau(const world *w, const double g[3], int n)
{
    return sun_tau_between(w, g, 0.0, sun_exit(w, g, w->top), n);
}

/* The unit direction d through the image point (px, py) (pixels from the top left corner)
 * from the camera; returns the distance to the ground along it. */
static double view_ray(const world *w, double px, double py, double d[3])
{
    double t = tan(M_PI / 4.0), sx = (2.0 * px / W - 1.0) * t;
    double sy = (1.0 - 2.0 * py / H) * t;
    double l = sqrt(sx * sx + 1.0 + sy * sy);
    double o[3] = {w->cam[0], w->cam[1] + w->R, w->cam[2]}, b = 0.0, oo = 0.0;
    d[0] = sx, d[1] = -1.0, d[2] = sy;
    for (int k = 0; k < 3; k++)
        d[k] /= l, b += o[k] * d[k], oo += o[k] * o[k];
    return -b - sqrt(b * b - oo + w->R * w->R);
}

/* The ground point (world) seen through the centre of pixel (x, y) from the camera. */
static void ground_point(const world *w, int x, int y, double g[3])
{
    double d[3], s = view_ray(w, x + 0.5, y + 0.5, d);
    for (int k = 0; k < 3; k++)
        g[k] = w->cam[k] + s * d[k];
}

/* The scene of part 1 (volume 0: the layer marched, its shadow on the ground) or of part 2
 * (volume 1: the path tracer's volume, the air's in-scatter over a black ground). */
static void scene_at(atmo_scene *s, double x, double density, int volume)
{
    char buf[96];
    test_scene_preset(s, "sky-noon");
    static const char *const keys[] = {
        "render.mode=path", "path.passes=true", "atmosphere.method=march", "clouds.enabled=true",
        "clouds.light_steps=1000", "clouds.light_distance_m=100000", "sun.zenith_deg=30",
        "sun.azimuth_deg=0", "camera.pitch_deg=-90", "camera.yaw_deg=0", "camera.fov_deg=90",
        "path.bounces=1", "path.sky_nee=false", "path.filter_sigma_px=0.1",
        "clouds.bottom_m=1000", "clouds.top_m=3000", "clouds.fade_m=500", "clouds.coverage=0.1", "path.filter_radius_px=0.5", "image.width=8", "image.height=8", "image.samples=16", NULL};
    for (int i = 0; keys[i]; i++)
        test_scene_set(s, keys[i]);
    snprintf(buf, sizeof buf, "camera.position_m=%.1f,%.1f,0", x, CAM_Y);
    test_scene_set(s, buf);
    snprintf(buf, sizeof buf, "clouds.density=%g", density);
    test_scene_set(s, buf);
    static const char *const volume_keys[] = {
        "path.clouds=volume", "clouds.look=physical", "atmosphere.method=single",
        "atmosphere.ground_albedo=0", "render.view_steps=64", "image.samples=64", NULL};
    for (int i = 0; volume && volume_keys[i]; i++)
        test_scene_set(s, volume_keys[i]);
}

/* The world of scene s's plan p with the camera at x. */
static void world_of(world *w, const atmo_scene *s, const atmo_plan *p, double x)
{
    w->c = &p->gpu.clouds;
    w->R = s->atmosphere.bottom_radius_m;
    w->cam[0] = x, w->cam[1] = CAM_Y, w->cam[2] = 0.0;
    for (int k = 0; k < 3; k++)
        w->sun[k] = (&p->gpu.sun_direction.x)[k];
    w->ext = p->gpu.clouds.extinction.y;
    w->bottom = s->clouds.bottom_m;
    w->top = s->clouds.top_m;
}

/* The oracle's ratio rho = L_clouds / L_open (green) through the image point (px, py): a
 * midpoint rule of nv points along the view ray, the layer's optical depth toward the sun from
 * each by nt steps through the shell (see the top of the file); *open gets L_open. */
static double air_ratio(const world *w, const atmo_atmosphere *a, double px, double py, int nv,
                        int nt, double *open)
{
    double d[3], len = view_ray(w, px + 0.5, py + 0.5, d) * 0.99999; /* path.h's shortening */
    double o[3] = {w->cam[0], w->cam[1] + w->R, w->cam[2]}, r0 = 0.0, mu = 0.0, nu = 0.0;
    for (int k = 0; k < 3; k++)
        r0 += o[k] * o[k], mu += o[k] * d[k], nu += d[k] * w->sun[k];
    r0 = sqrt(r0), mu /= r0;
    double p_r = atmo_ref_phase_rayleigh(nu), p_m = atmo_ref_phase_mie(a, nu);
    double lit = 0.0, all = 0.0;
    for (int i = 0; i < nv; i++) {
        double t = (i + 0.5) * len / nv, x[3], c[3], r2 = 0.0, mu_s = 0.0;
        for (int k = 0; k < 3; k++)
            x[k] = w->cam[k] + t * d[k], c[k] = x[k] + (k == 1 ? w->R : 0.0), r2 += c[k] * c[k];
        double r = sqrt(r2), h = r - w->R, tau[3], t_sun[3];
        for (int k = 0; k < 3; k++)
            mu_s += c[k] * w->sun[k] / r;
        atmo_ref_optical_depth_to(a, r0, mu, t, tau);
        atmo_ref_sun_transmittance(a, r, mu_s, t_sun);
        double f = exp(-tau[1]) * t_sun[1] * a->solar_irradiance[1] *
                   (a->rayleigh_scattering_per_m[1] * exp(-h / a->rayleigh_scale_height_m) * p_r +
                    a->mie_scattering_per_m[1] * exp(-h / a->mie_scale_height_m) * p_m);
        double t_c = exp(-sun_tau_between(w, x, sun_exit(w, x, w->bottom), sun_exit(w, x, w->top),
                                          nt));
        all += f * len / nv;
        lit += f * t_c * len / nv;
    }
    *open = all;
    return lit / all;
}

/* The Sun pass (green) of the scene's render. */
static int sun_pass(atmo_scene *s, float *out)
{
    atmo_plan p;
    test_plan(s, &p);
    atmo_render_settings rs;
    atmo_render_settings_default(&rs);
    atmo_render_result r;
    atmo_err e;
    if (atmo_render(&p, &rs, &r, &e)) {
        fprintf(stderr, "render failed: %s\n", e.msg);
        atmo_plan_free(&p);
        return 1;
    }
    CHECK(r.nonfinite == 0);
    for (int i = 0; i < W * H; i++)
        out[i] = r.passes[4 * ((size_t)W * H * SUN_PASS + (size_t)i) + 1];
    atmo_render_result_free(&r);
    atmo_plan_free(&p);
    return 0;
}

/* Part 1; returns the patch's camera x (negative where none was found). */
static double test_ground_shadow(void)
{
    atmo_scene s;
    atmo_plan p;
    world w;
    /* the patch: the first camera x (250 m steps) whose patch's edges at x -+ 800 m have
     * T < 0.6 on one side and T > 0.9 on the other (300-step rule: only a choice) */
    double x_cam = -1.0;
    for (double x = 0.0; x < 100000.0 && x_cam < 0.0; x += 250.0) {
        scene_at(&s, x, 0.5, 0);
        test_plan(&s, &p);
        world_of(&w, &s, &p, x);
        double a[3] = {x - 800.0, 0.0, 0.0}, b[3] = {x + 800.0, 0.0, 0.0};
        double ta = exp(-sun_tau(&w, a, 300)), tb = exp(-sun_tau(&w, b, 300));
        if ((ta < 0.6 && tb > 0.9) || (tb < 0.6 && ta > 0.9))
            x_cam = x;
        atmo_plan_free(&p);
    }
    printf("patch: camera x %.0f m\n", x_cam);
    CHECK(x_cam >= 0.0);
    if (x_cam < 0.0)
        return x_cam;

    scene_at(&s, x_cam, 0.5, 0);
    test_plan(&s, &p);
    world_of(&w, &s, &p, x_cam);
    static float cloudy[W * H], open[W * H];
    if (sun_pass(&s, cloudy) || (scene_at(&s, x_cam, 0.0, 0), sun_pass(&s, open))) {
        CHECK(!"the renders of part 1 failed");
        atmo_plan_free(&p);
        return x_cam;
    }
    double worst = 0.0, shade_T = 2.0, open_T = -1.0;
    float shade_sun = 0.0f, open_sun = 0.0f;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            int i = y * W + x;
            double g[3];
            ground_point(&w, x, y, g);
            double T = exp(-sun_tau(&w, g, 16384)), T1 = exp(-sun_tau(&w, g, 1000));
            double ratio = open[i] > 0.0f ? cloudy[i] / open[i] : -1.0;
            double tol = 3.0 * fabs(T1 - T) + 0.005;
            worst = fmax(worst, fabs(ratio - T));
            CHECK(fabs(ratio - T) <= tol);
            if (T < shade_T)
                shade_T = T, shade_sun = cloudy[i];
            if (T > open_T)
                open_T = T, open_sun = cloudy[i];
        }
    printf("cloud shadow: %dx%d ground pixels, Sun pass ratio (clouds / none) against the host's "
           "transmittance: worst |difference| %.4f; darkest T %.3f (sun %.4g), lightest T %.3f "
           "(sun %.4g)\n",
           W, H, worst, shade_T, shade_sun, open_T, open_sun);
    CHECK(shade_T < 0.6 && open_T > 0.9 && shade_sun < 0.7f * open_sun);
    atmo_plan_free(&p);
    return x_cam;
}

/* Part 2 with the camera at x_cam. */
static void test_air_shadow(double x_cam)
{
    atmo_scene s;
    atmo_plan p;
    atmo_atmosphere a;
    atmo_err e;
    world w;
    scene_at(&s, x_cam, 0.5, 1);
    test_plan(&s, &p);
    world_of(&w, &s, &p, x_cam);
    CHECK(atmo_atmosphere_from_scene(&s, &a, &e) == 0);
    test_image cloudy = test_render(&s, 0, 0);
    scene_at(&s, x_cam, 0.0, 1);
    test_image open = test_render(&s, 0, 0);
    const double sigma = 0.1; /* path.filter_sigma_px */
    double sum_d = 0.0, var_d = 0.0, sum_old = 0.0, rho_min = 2.0, z_max = 0.0, b_max = 0.0;
    int bad = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            int i = 3 * (y * W + x) + 1; /* green */
            double l_open, l_half, rho = air_ratio(&w, &a, x, y, 256, 256, &l_open);
            double rho_half = air_ratio(&w, &a, x, y, 128, 128, &l_half), lap = -4.0 * rho_half;
            for (int k = 0; k < 4; k++) {
                double dx = k == 0 ? sigma : k == 1 ? -sigma : 0.0;
                double dy = k == 2 ? sigma : k == 3 ? -sigma : 0.0;
                lap += air_ratio(&w, &a, x + dx, y + dy, 128, 128, &l_half);
            }
            /* sigma^2 / 2 times the Laplacian, whose five-point estimate is lap / sigma^2 */
            double b = (3.0 * fabs(rho - rho_half) + fabs(0.5 * lap)) * open.mean[i];
            double dv = cloudy.mean[i] - rho * open.mean[i];
            double se = sqrt((double)cloudy.se[i] * cloudy.se[i] +
                             rho * rho * (double)open.se[i] * open.se[i]);
            bad += !(fabs(dv) < 4.4 * se + b);
            z_max = fmax(z_max, fabs(dv) / se);
            b_max = fmax(b_max, b / (se > 0.0 ? se : 1.0));
            sum_d += dv, var_d += se * se;
            sum_old += open.mean[i] - rho * open.mean[i];
            rho_min = fmin(rho_min, rho);
        }
    double z = sum_d / sqrt(var_d), z_old = sum_old / sqrt(var_d);
    printf("air shadow: %dx%d pixels, in-scatter (clouds) against rho x (open): %d outside "
           "4.4 se + b, largest |z| %.2f (b at most %.2f se); image z = %+.2f; smallest rho "
           "%.3f; the open image (no air shadow) is z = %+.1f from the oracle\n",
           W, H, bad, z_max, b_max, z, rho_min, z_old);
    CHECK(bad == 0);
    CHECK(fabs(z) < 4.4);
    CHECK(rho_min < 0.75 && z_old > 10.0);
    test_image_free(&cloudy);
    test_image_free(&open);

    scene_at(&s, x_cam, 0.5, 1);
    test_scene_set(&s, "image.samples=4");
    test_image t8 = test_render(&s, 8, 1), t64 = test_render(&s, 64, 0);
    size_t bytes = sizeof(float) * 3 * W * H;
    int finite = 1;
    for (int i = 0; i < 3 * W * H; i++)
        finite &= isfinite(t8.mean[i]) && t8.mean[i] >= 0.0f;
    printf("air shadow determinism: tiles 8/64, batches 1/any %s; finite and non-negative: %s\n",
           memcmp(t8.mean, t64.mean, bytes) == 0 ? "bitwise equal" : "DIFFER",
           finite ? "yes" : "NO");
    CHECK(memcmp(t8.mean, t64.mean, bytes) == 0);
    CHECK(finite);
    test_image_free(&t8);
    test_image_free(&t64);
    atmo_plan_free(&p);
}

int main(void)
{
    test_require_opencl();
    double x_cam = test_ground_shadow();
    if (x_cam >= 0.0)
        test_air_shadow(x_cam);
    return test_finish();
}
