/* test_path_bounces — path.bounces counts reflections off surfaces (kernels/render/path.h):
 * 0 is the camera ray's light alone, 1 adds single scattering off surfaces, each more one order.
 * labels: reliability render kernel
 *
 * Oracle: closed forms in scenes where every sample of every pixel is the same number (zero
 * variance), so each pixel must equal the closed form to float rounding (1e-6 relative):
 * 1. The lit enclosure: the camera at the centre of a sphere of radius 2 m with emission
 *    L_e = (1, 2, 3) and albedo a = 0.5 under a black sky, no roulette. Every ray hits the
 *    sphere; a path of N_b reflections sees L_e at its N_b + 1 hits, weighted a^k:
 *        L = L_e sum_{k=0}^{N_b} a^k:  N_b = 0: L_e,  1: 1.5 L_e,  2: 1.75 L_e.
 *    N_b = 1 differs from N_b = 0 by a L_e, the single-scattering term.
 * 2. A convex sphere (radius 5 m, 10 m in front of a 20-degree camera, so it fills the frame,
 *    pixel filter included), albedo 0.5, emission e = (0.1, 0.2, 0.3), under the uniform sky
 *    L_u = (1, 0.5, 0.25) and the uniform world's sun, with sun and sky next-event estimation:
 *    with N_b = 0 no light reaches it but its own, L = e in every pixel (the first hit's
 *    next-event estimation is a reflection).
 * 3. The same sphere without the sun and with BSDF sampling alone (path.sky_nee = false),
 *    N_b = 1: every reflection's continuation escapes to the sky (a convex object never sees
 *    itself) with weight a, so L = e + a L_u in every pixel. */
#include <math.h>
#include <stdio.h>
#include "testlib.h"
#include "testscene.h"

/* the largest |pixel / want - 1| over the image, channel by channel */
static double image_spread(const test_image *im, const double want[3])
{
    double spread = 0.0;
    for (int i = 0; i < im->w * im->h; i++)
        for (int c = 0; c < 3; c++)
            spread = fmax(spread, fabs(im->mean[3 * i + c] / want[c] - 1.0));
    return spread;
}

static void base_scene(atmo_scene *s, int bounces)
{
    char buf[64];
    test_scene_preset(s, "sky-noon");
    test_scene_set(s, "render.mode=path");
    test_scene_set(s, "path.sky=uniform");
    test_scene_set(s, "path.ground=false");
    test_scene_set(s, "path.rr_bounce=64");
    test_scene_set(s, "camera.position_m=0,100,0");
    test_scene_set(s, "camera.pitch_deg=0");
    test_scene_set(s, "camera.fov_deg=20");
    test_scene_set(s, "image.width=10");
    test_scene_set(s, "image.height=10");
    test_scene_set(s, "image.samples=2");
    snprintf(buf, sizeof buf, "path.bounces=%d", bounces);
    test_scene_set(s, buf);
}

static void check(const char *what, int bounces, const atmo_scene *s, const double want[3])
{
    test_image im = test_render(s, 64, 0);
    double spread = image_spread(&im, want);
    printf("%s, N_b = %d: want (%.4f, %.4f, %.4f), pixel (%.6f, %.6f, %.6f), spread %.2g\n", what,
           bounces, want[0], want[1], want[2], im.mean[0], im.mean[1], im.mean[2], spread);
    CHECK(spread < 1e-6);
    test_image_free(&im);
}

static void test_enclosure(void)
{
    static const double Le[3] = {1.0, 2.0, 3.0};
    for (int n_b = 0; n_b <= 2; n_b++) {
        atmo_scene s;
        base_scene(&s, n_b);
        test_scene_set(&s, "sun.irradiance_scale=0");
        test_scene_set(&s, "path.uniform_sky=0,0,0");
        test_scene_set(&s, "objects=[{\"type\": \"sphere\", \"center_m\": [0, 100, 0], "
                           "\"radius_m\": 2, \"albedo\": [0.5, 0.5, 0.5], "
                           "\"emission\": [1, 2, 3]}]");
        double series = 0.0, want[3];
        for (int k = 0; k <= n_b; k++)
            series += pow(0.5, k);
        for (int c = 0; c < 3; c++)
            want[c] = Le[c] * series;
        check("enclosure", n_b, &s, want);
    }
}

#define CONVEX_SPHERE                                                                           \
    "objects=[{\"type\": \"sphere\", \"center_m\": [0, 100, 10], \"radius_m\": 5, "           \
    "\"albedo\": [0.5, 0.5, 0.5], \"emission\": [0.1, 0.2, 0.3]}]"

static void test_convex(void)
{
    static const double e[3] = {0.1, 0.2, 0.3}, Lu[3] = {1.0, 0.5, 0.25};
    atmo_scene s;
    base_scene(&s, 0);
    test_scene_set(&s, "path.uniform_sky=1,0.5,0.25");
    test_scene_set(&s, CONVEX_SPHERE);
    check("convex sphere in sun and sky, both sampled", 0, &s, e);

    double want[3];
    for (int c = 0; c < 3; c++)
        want[c] = e[c] + 0.5 * Lu[c];
    base_scene(&s, 1);
    test_scene_set(&s, "sun.irradiance_scale=0");
    test_scene_set(&s, "path.sky_nee=false");
    test_scene_set(&s, "path.uniform_sky=1,0.5,0.25");
    test_scene_set(&s, CONVEX_SPHERE);
    check("convex sphere in the sky, BSDF sampling", 1, &s, want);
}

int main(void)
{
    test_require_opencl();
    test_enclosure();
    test_convex();
    return test_finish();
}
