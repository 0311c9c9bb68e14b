/* test_flare — the procedural lens flare (host/image/flare.c) and its occlusion by what covers
 * the sun in the render.
 * labels: unit render kernel
 *
 * Oracles:
 *   - Energy (closed form): with the sun at the image centre every ghost, the halo and nearly
 *     all of the glare fall inside the frame, so the irradiance the flare adds is the sun's
 *     measured irradiance P times the sum of the parts' fractions, minus what the frame clips
 *     of the spokes and the glare's tails: within [0.75, 1] of the sum for each channel (the
 *     frame can only lose light; the spokes' tails beyond the frame's half height carry at
 *     most 17 % of theirs, 2 % of the total), and P equals the sum of L omega of the disc
 *     pixels the test painted (pixel solid angles (2 tan(fov/2) / H)^2 cos^3 theta), 1e-9.
 *   - Linearity: twice the sun's radiance adds twice the flare (1e-6 relative).
 *   - Occlusion, synthetic: the disc's pixels dark (something in front of the sun) add nothing
 *     (the image is unchanged, memcmp); a sun behind the camera adds nothing.
 *   - Occlusion, rendered (the visibility of the sun's pixel): a preview render (method fast,
 *     64 x 36, 32 samples) with the sun 10 degrees up in the middle of the frame, its disc
 *     enlarged to 2 degrees in radius so that its coverage of the pixels is well sampled,
 *     gives the flare the sun's irradiance E T (T the transmittance toward the sun from the
 *     host's double-precision optical depth, atmosphere_ref.c) within 10 % (the disc edge's
 *     coverage estimated from 32 samples per pixel, and the sky in the ring around the disc
 *     the flare also collects); the same view with a sphere between the camera and the sun,
 *     wider than the flare's reach, leaves below 1 % of it (the sphere's dim shadowed side). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/atmosphere_ref.h"
#include "atmo/flare.h"
#include "atmo/plan.h"
#include "atmo/render.h"
#include "testlib.h"
#include "testscene.h"

#define W 256
#define H 144

static const double fractions_white = 2e-3 + 4e-4 + 3e-4;
static const double ghost_fraction[5] = {6e-5, 8e-5, 5e-5, 1.2e-4, 7e-5};
static const double ghost_tint[5][3] = {{0.6, 0.9, 1.0}, {1.0, 0.8, 0.5}, {0.5, 1.0, 0.6},
                                        {0.7, 0.6, 1.0}, {1.0, 0.6, 0.5}};

static atmo_flare_camera camera(double pitch, double yaw, const double sun[3])
{
    atmo_flare_camera c = {.width = W, .height = H, .tan_half_fov = tan(22.5 * M_PI / 180.0),
                           .sun_radius_rad = 0.26786 * M_PI / 180.0};
    atmo_camera_basis(pitch, yaw, c.forward, c.right, c.up);
    memcpy(c.sun, sun, sizeof c.sun);
    return c;
}

/* paint the pixels within 1 px of the centre with radiance L; return sum L omega */
static double paint_sun(float *rgb, double L)
{
    double th = tan(22.5 * M_PI / 180.0), pix = 2.0 * th / H, sum = 0.0;
    for (int y = H / 2 - 1; y <= H / 2; y++)
        for (int x = W / 2 - 1; x <= W / 2; x++) {
            double u = (2.0 * (x + 0.5) / W - 1.0) * th * W / H, v = (1.0 - 2.0 * (y + 0.5) / H) * th;
            double c = 1.0 / sqrt(1.0 + u * u + v * v);
            for (int k = 0; k < 3; k++)
                rgb[3 * (y * W + x) + k] = (float)L;
            sum += L * pix * pix * c * c * c;
        }
    return sum;
}

static void test_synthetic(void)
{
    static float img[W * H * 3], twice[W * H * 3], dark[W * H * 3], before[W * H * 3];
    double forward[3], right[3], up[3];
    atmo_camera_basis(10.0, 30.0, forward, right, up);
    atmo_flare_camera c = camera(10.0, 30.0, forward); /* the sun straight ahead */
    memset(img, 0, sizeof img);
    double P = paint_sun(img, 1000.0);
    memcpy(twice, img, sizeof img);
    for (int i = 0; i < W * H * 3; i++)
        twice[i] *= 2.0f;
    atmo_flare_info a, b;
    atmo_flare_apply(img, &c, 1.0, &a);
    atmo_flare_apply(twice, &c, 1.0, &b);
    for (int k = 0; k < 3; k++) {
        double want = fractions_white;
        for (int g = 0; g < 5; g++)
            want += ghost_fraction[g] * ghost_tint[g][k];
        double ratio = a.added[k] / (a.irradiance[k] * want);
        printf("channel %d: sun irradiance %.6g (painted %.6g), flare added %.4g of the %.4g "
               "the parts carry\n",
               k, a.irradiance[k], P, a.added[k] / a.irradiance[k], want);
        CHECK_REL(a.irradiance[k], P, 1e-9);
        CHECK(ratio >= 0.75 && ratio <= 1.0);
        CHECK_REL(b.added[k], 2.0 * a.added[k], 1e-6);
    }
    CHECK_ABS(a.sun_x, W / 2.0, 1e-6);
    CHECK_ABS(a.sun_y, H / 2.0, 1e-6);
    memset(dark, 0, sizeof dark);
    dark[0] = 5.0f; /* light elsewhere in the frame, none at the sun */
    memcpy(before, dark, sizeof dark);
    atmo_flare_apply(dark, &c, 1.0, &a);
    CHECK(memcmp(dark, before, sizeof dark) == 0 && a.added[0] == 0.0);
    double behind[3] = {-forward[0], -forward[1], -forward[2]};
    atmo_flare_camera cb = camera(10.0, 30.0, behind);
    memset(img, 0, sizeof img);
    paint_sun(img, 1000.0);
    memcpy(before, img, sizeof img);
    atmo_flare_apply(img, &cb, 1.0, &a);
    CHECK(memcmp(img, before, sizeof img) == 0);
}

static double rendered_sun(int covered, double *expect)
{
    atmo_scene s;
    test_scene_preset(&s, "sky-sunset"); /* sun 2 degrees up, straight ahead */
    test_scene_set(&s, "image.width=64");
    test_scene_set(&s, "image.height=36");
    test_scene_set(&s, "image.samples=32");
    test_scene_set(&s, "sun.zenith_deg=80");
    test_scene_set(&s, "sun.angular_radius_deg=2");
    test_scene_set(&s, "camera.pitch_deg=10");
    if (covered) /* 20 m away along the sun's direction, 3 m in radius: 8.6 degrees */
        test_scene_set(&s, "objects=[{\"type\": \"sphere\", \"center_m\": [0, 5.1729, 19.696], "
                           "\"radius_m\": 3}]");
    atmo_plan p;
    test_plan(&s, &p);
    p.cache_luts = 2;
    atmo_render_settings rs;
    atmo_render_settings_default(&rs);
    atmo_render_result r;
    atmo_err e;
    if (atmo_render(&p, &rs, &r, &e)) {
        fprintf(stderr, "render: %s\n", e.msg);
        exit(1);
    }
    double sun[3];
    atmo_sun_direction(80.0, 0.0, sun);
    atmo_flare_camera c = {.width = 64, .height = 36, .tan_half_fov = tan(22.5 * M_PI / 180.0),
                           .sun_radius_rad = 2.0 * M_PI / 180.0};
    atmo_camera_basis(10.0, 0.0, c.forward, c.right, c.up);
    memcpy(c.sun, sun, sizeof sun);
    atmo_flare_info info;
    atmo_flare_apply(r.rgb, &c, 1.0, &info);
    /* the sun's irradiance through the air: E T with T from the camera toward the sun,
     * as the disc's radiance E T / Omega over its solid angle Omega */
    double tau[3], r0 = p.atmosphere.bottom_radius_m + 1.7;
    atmo_ref_optical_depth(&p.atmosphere, r0, cos(80.0 * M_PI / 180.0), tau);
    *expect = p.gpu.atmosphere.solar_irradiance.y * exp(-tau[1]);
    atmo_render_result_free(&r);
    atmo_plan_free(&p);
    return info.irradiance[1];
}

int main(void)
{
    test_synthetic();
    test_require_opencl();
    test_fresh_cache_dir();
    double E, E2;
    double open = rendered_sun(0, &E), covered = rendered_sun(1, &E2);
    printf("rendered sun: irradiance from its pixels %.4g (E T %.4g), with a sphere in front "
           "%.3g\n",
           open, E, covered);
    CHECK_REL(open, E, 0.10);
    CHECK(covered < 0.01 * open);
    return test_finish();
}
