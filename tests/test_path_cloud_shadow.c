/* test_path_cloud_shadow — cloud shadows in the path tracer: the direct sunlight a ground point
 * receives (kernels/render/path.h's path_sunlight: visibility_sun_surface, the layer's
 * visibility_clouds_transmittance) is cut by the cloud layer's transmittance toward the sun.
 * labels: render kernel slow
 *
 * Scene: the fBm cloud layer made thin and scattered (1-3 km, fades of 500 m, coverage 0.1,
 * density 0.5: optical depths toward the sun of 0-3, where the default layer's are > 20 under
 * every cloud; method march), the sun 30 degrees from the zenith, the ground sphere seen
 * straight down from 900 m (below the layer; fov 90 degrees, 8 x 8 pixels over 1.8 km, the
 * pixel filter shrunk to sigma 0.1 px within 0.5 px, 16 samples, no bounces: the Sun pass is
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
 * of an open one's (T > 0.9). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "common/compat.h"
#include "media/cloud_layer.h"
#include "atmo/render.h"
#include "testlib.h"
#include "testscene.h"

#define W 8
#define H 8
#define CAM_Y 900.0
#define SUN_PASS 3 /* PATH_PASS_SUN of kernels/render/path.h: the EXR layer Sun */

typedef struct world {
    const atmo_gpu_clouds *c;
    double R, cam[3], sun[3], ext, top;
} world;

/* The layer's optical depth (green channel) toward the sun from world ground point g,
 * n midpoint steps up to the layer's top. */
static double sun_tau(const world *w, const double g[3], int n)
{
    /* distance to the top sphere from g along the sun */
    double c[3] = {g[0], g[1] + w->R, g[2]}, b = 0.0, cc = 0.0;
    for (int k = 0; k < 3; k++)
        b += c[k] * w->sun[k], cc += c[k] * c[k];
    double rt = w->R + w->top, len = -b + sqrt(b * b - cc + rt * rt), D = 0.0;
    for (int i = 0; i < n; i++) {
        double t = (i + 0.5) * len / n, q[3], x[3], r2 = 0.0;
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

/* The ground point (world) seen through the centre of pixel (x, y) from the camera. */
static void ground_point(const world *w, int x, int y, double g[3])
{
    double t = tan(M_PI / 4.0), sx = (2.0 * (x + 0.5) / W - 1.0) * t;
    double sy = (1.0 - 2.0 * (y + 0.5) / H) * t;
    double d[3] = {sx, -1.0, sy}, l = sqrt(sx * sx + 1.0 + sy * sy);
    double o[3] = {w->cam[0], w->cam[1] + w->R, w->cam[2]}, b = 0.0, oo = 0.0;
    for (int k = 0; k < 3; k++)
        d[k] /= l, b += o[k] * d[k], oo += o[k] * o[k];
    double s = -b - sqrt(b * b - oo + w->R * w->R);
    for (int k = 0; k < 3; k++)
        g[k] = w->cam[k] + s * d[k];
}

static void scene_at(atmo_scene *s, double x, double density)
{
    char buf[96];
    test_scene_preset(s, "sky-noon");
    static const char *const keys[] = {
        "render.mode=path", "path.passes=true", "atmosphere.method=march", "clouds.enabled=true",
        "clouds.light_steps=1000", "clouds.light_distance_m=100000", "sun.zenith_deg=30",
        "sun.azimuth_deg=0", "camera.pitch_deg=-90", "camera.yaw_deg=0", "camera.fov_deg=90",
        "path.bounces=0", "path.sky_nee=false", "path.filter_sigma_px=0.1",
        "clouds.bottom_m=1000", "clouds.top_m=3000", "clouds.fade_m=500", "clouds.coverage=0.1", "path.filter_radius_px=0.5", "image.width=8", "image.height=8", "image.samples=16", NULL};
    for (int i = 0; keys[i]; i++)
        test_scene_set(s, keys[i]);
    snprintf(buf, sizeof buf, "camera.position_m=%.1f,%.1f,0", x, CAM_Y);
    test_scene_set(s, buf);
    snprintf(buf, sizeof buf, "clouds.density=%g", density);
    test_scene_set(s, buf);
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

int main(void)
{
    atmo_scene s;
    atmo_plan p;
    world w;
    /* the patch: the first camera x (250 m steps) whose patch's edges at x -+ 400 m have
     * T < 0.5 on one side and T > 0.95 on the other (300-step rule: only a choice) */
    double x_cam = -1.0;
    for (double x = 0.0; x < 100000.0 && x_cam < 0.0; x += 250.0) {
        scene_at(&s, x, 0.5);
        test_plan(&s, &p);
        w.c = &p.gpu.clouds;
        w.R = s.atmosphere.bottom_radius_m;
        w.cam[0] = x, w.cam[1] = CAM_Y, w.cam[2] = 0.0;
        for (int k = 0; k < 3; k++)
            w.sun[k] = (&p.gpu.sun_direction.x)[k];
        w.ext = p.gpu.clouds.extinction.y;
        w.top = s.clouds.top_m;
        double a[3] = {x - 800.0, 0.0, 0.0}, b[3] = {x + 800.0, 0.0, 0.0};
        double ta = exp(-sun_tau(&w, a, 300)), tb = exp(-sun_tau(&w, b, 300));
        if ((ta < 0.6 && tb > 0.9) || (tb < 0.6 && ta > 0.9))
            x_cam = x;
        atmo_plan_free(&p);
    }
    printf("patch: camera x %.0f m\n", x_cam);
    CHECK(x_cam >= 0.0);
    if (x_cam < 0.0)
        return test_finish();

    scene_at(&s, x_cam, 0.5);
    test_plan(&s, &p);
    w.c = &p.gpu.clouds;
    w.cam[0] = x_cam;
    static float cloudy[W * H], open[W * H];
    if (sun_pass(&s, cloudy))
        return 1;
    scene_at(&s, x_cam, 0.0);
    if (sun_pass(&s, open))
        return 1;
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
    return test_finish();
}
