/* test_clouds_render — the fBm cloud layer in rendered images: no NaN, Inf or negative value
 * over a sweep of its parameters and views, the same bits for any tile size and launch budget,
 * and the wind's motion with clouds.time_s.
 * labels: render kernel slow
 *
 * Oracles: the closed set of valid values (every pixel mean finite and >= 0, and the render's
 * own count of non-finite samples 0); the renderer's determinism contract (DESIGN.md, "Random
 * numbers": memcmp of renders with tile sizes 8 and 64 and launch budgets 1 ms and 100 ms);
 * the wind's motion: the noise's origin at time t with wind v seen from x is that at time 0
 * seen from x - v t (both exactly x - v t in float), and a render at another time differs.
 * The sweep (16 x 12 pixels, 2 samples): coverage 0 and 1, density 0 and 1e5, the sun below
 * the horizon, the camera inside a cloud, above the layer and from space (thesis-4), methods
 * single and march; coverage 0 and density 0 (both cloudless) must agree within 1 %. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/render.h"
#include "testlib.h"
#include "testscene.h"

#define W 16
#define H 12

static float *render(const atmo_plan *plan, int tile, double budget_ms)
{
    atmo_render_settings rs;
    atmo_render_result r;
    atmo_err e;
    atmo_render_settings_default(&rs);
    rs.tile_size = tile;
    rs.launch_budget_ms = budget_ms;
    if (atmo_render(plan, &rs, &r, &e)) {
        fprintf(stderr, "render failed: %s\n", e.msg);
        exit(1);
    }
    CHECK(r.nonfinite == 0);
    return r.rgb;
}

static void scene_for(atmo_scene *s, const char *preset, const char *const *sets)
{
    test_scene_preset(s, preset);
    test_scene_set(s, "clouds.enabled=true");
    test_scene_set(s, "atmosphere.method=march");
    test_scene_set(s, "image.width=16");
    test_scene_set(s, "image.height=12");
    test_scene_set(s, "image.samples=2");
    test_scene_set(s, "clouds.steps=64");
    for (int i = 0; sets && sets[i]; i++)
        test_scene_set(s, sets[i]);
}

/* Renders the scene; checks every value; returns the mean of channel y. */
static double check_valid(const char *what, const char *preset, const char *const *sets)
{
    atmo_scene s;
    atmo_plan p;
    scene_for(&s, preset, sets);
    test_plan(&s, &p);
    float *rgb = render(&p, 64, 100.0);
    int bad = 0;
    double mean = 0.0;
    for (int i = 0; i < 3 * W * H; i++) {
        bad += !(isfinite(rgb[i]) && rgb[i] >= 0.0f);
        if (i % 3 == 1)
            mean += rgb[i] / (W * H);
    }
    printf("%-28s mean radiance (550 nm) %.6g, %d bad values\n", what, mean, bad);
    CHECK(bad == 0);
    free(rgb);
    atmo_plan_free(&p);
    return mean;
}

static void check_determinism(void)
{
    atmo_scene s;
    atmo_plan p;
    scene_for(&s, "thesis-6", NULL);
    test_plan(&s, &p);
    size_t bytes = sizeof(float) * 3 * W * H;
    float *a = render(&p, 64, 100.0), *b = render(&p, 8, 1.0);
    CHECK(memcmp(a, b, bytes) == 0);
    free(b);
    atmo_plan_free(&p);

    /* wind 20 m/s toward +X for 100 s: the noise's origin is the camera's position minus
     * 2000 m along X, i.e. that of a still layer seen from 2000 m further back */
    static const char *const moved[] = {"clouds.wind_m_s=20", "clouds.wind_azimuth_deg=90",
                                        "clouds.time_s=100", NULL};
    static const char *const still[] = {"clouds.wind_m_s=20", "clouds.wind_azimuth_deg=90",
                                        "clouds.time_s=0", NULL};
    atmo_plan p_moved, p_back;
    scene_for(&s, "thesis-6", moved);
    test_plan(&s, &p_moved);
    scene_for(&s, "thesis-6", still);
    s.camera.position_m[0] -= 2000.0;
    test_plan(&s, &p_back);
    CHECK(memcmp(&p_moved.gpu.clouds.origin, &p_back.gpu.clouds.origin, sizeof(float4)) == 0);
    CHECK_ABS(p_moved.gpu.clouds.origin.x, 23796.0 - 2000.0, 1e-3);
    float *moved_rgb = render(&p_moved, 64, 100.0);
    CHECK(memcmp(moved_rgb, a, bytes) != 0); /* the clouds have moved in the image */
    free(moved_rgb);
    free(a);
    atmo_plan_free(&p_moved);
    atmo_plan_free(&p_back);
}

int main(void)
{
    test_require_opencl();
    static const char *const cov0[] = {"clouds.coverage=0", NULL};
    static const char *const cov1[] = {"clouds.coverage=1", NULL};
    static const char *const dens0[] = {"clouds.density=0", NULL};
    static const char *const dens_huge[] = {"clouds.density=1e5", "clouds.coverage=1", NULL};
    static const char *const night[] = {"sun.zenith_deg=100", NULL};
    static const char *const inside[] = {"camera.position_m=0,5000,0", "clouds.coverage=1",
                                         "clouds.density=20", NULL};
    static const char *const above[] = {"camera.position_m=0,12000,0", "camera.pitch_deg=-40",
                                        "clouds.coverage=0.6", NULL};
    static const char *const single[] = {"atmosphere.method=single", NULL};
    double clear = check_valid("coverage 0", "thesis-6", cov0);
    check_valid("coverage 1", "thesis-6", cov1);
    double none = check_valid("density 0", "thesis-6", dens0);
    check_valid("density 1e5", "thesis-6", dens_huge);
    check_valid("sun below the horizon", "thesis-6", night);
    check_valid("camera inside a cloud", "thesis-6", inside);
    check_valid("camera above the layer", "thesis-6", above);
    check_valid("from space (thesis-4)", "thesis-4", NULL);
    check_valid("method single", "thesis-6", single);
    /* no cloud anywhere: coverage 0 and density 0 are the same clear sky; the marcher steps
     * the air 4 times longer where the coverage test finds none (coverage 0) than where it
     * finds some (density 0), and the air's steps are energy conserving, so the two agree to
     * the air's discretisation error, far below 1 % */
    printf("coverage 0 vs density 0: relative difference %.2e\n", fabs(clear / none - 1.0));
    CHECK_REL(clear, none, 1e-2);
    check_determinism();
    return test_finish();
}
