/* test_clouds_photometeors — the fog bow in a rendered image of a flat deck of the fBm cloud
 * layer seen from above lies where the droplets' Mie table has it.
 * labels: render kernel
 *
 * Oracle: the phase table the plan uploads (clouds_phase_table, 550 nm), interpolated as the
 * kernel does: single scattering dominates a thick deck's light near the antisolar point, so
 * the radiance's maximum over scattering angles 130..160 deg must sit at the table's maximum
 * there within 2 deg (1-degree bins of the image's pixels by their scattering angle, pixels
 * 1.9 deg wide; the deck's geometry, L ~ mu_s / (mu_s + mu_v), tilts the profile by less than
 * that over the bow's width).
 * Scene: the glory preset's camera and sun (3 km up, looking at the antisolar point, fov 90
 * deg), the shell replaced by the layer made flat: frequencies 1e-8 1/m and coverage features
 * of 1e8 m (the noise is constant over the view), 1-m fades, one octave, no warp, the density
 * scaled so the 1000-2000 m deck has sigma = 0.02 1/m (optical depth 20); method single with
 * one octave and no diffuse orders, so the image is single scattering (its multiple scattering is the marcher's
 * approximation, not what is tested). 48 x 48 pixels, 2 samples. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "common/compat.h"
#include "common/camera.h"
#include "clouds/cloud_layer.h"
#include "atmo/render.h"
#include "testlib.h"
#include "testscene.h"

#define N 48
#define DEG (M_PI / 180.0)

static void flat_deck(atmo_scene *s, double density)
{
    char buf[64];
    test_scene_preset(s, "glory");
    test_scene_set(s, "cloud.enabled=false");
    test_scene_set(s, "clouds.enabled=true");
    test_scene_set(s, "atmosphere.method=single");
    test_scene_set(s, "clouds.frequency_per_m=1e-8,1e-8,1e-8");
    test_scene_set(s, "clouds.coverage_scale_m=1e8");
    test_scene_set(s, "clouds.coverage=1");
    test_scene_set(s, "clouds.octaves=1");
    test_scene_set(s, "clouds.warp_m=0");
    test_scene_set(s, "clouds.sharpness=1");
    test_scene_set(s, "clouds.bottom_m=1000");
    test_scene_set(s, "clouds.top_m=2000");
    test_scene_set(s, "clouds.fade_m=1");
    test_scene_set(s, "clouds.ms_octaves=1");
    test_scene_set(s, "clouds.ms_d=0");
    test_scene_set(s, "image.width=48");
    test_scene_set(s, "image.height=48");
    test_scene_set(s, "image.samples=2");
    snprintf(buf, sizeof buf, "clouds.density=%.9g", density);
    test_scene_set(s, buf);
}

int main(void)
{
    test_require_opencl();
    atmo_scene s;
    atmo_plan p;
    /* the deck's density at unit scale, from the kernel's own function on the host */
    flat_deck(&s, 1.0);
    test_plan(&s, &p);
    float d1 = clouds_density(&p.gpu.clouds, v3(0.0f, -1500.0f, -1000.0f), 1500.0f);
    float d2 = clouds_density(&p.gpu.clouds, v3(3000.0f, -1500.0f, -4000.0f), 1500.0f);
    printf("deck density at unit scale: %.6f and %.6f 3 km away\n", d1, d2);
    CHECK(d1 > 0.05f);
    CHECK_ABS(d2, d1, 1e-3 * d1); /* flat */
    float sigma_unit = p.gpu.clouds.extinction.y;
    atmo_plan_free(&p);
    flat_deck(&s, 0.02 / (d1 * sigma_unit));
    test_plan(&s, &p);

    atmo_render_result r;
    test_render_whole(&p, NULL, &r);

    /* the radiance (550 nm) in 1-degree bins of the scattering angle */
    enum { BINS = 181 };
    double sum[BINS] = {0}, count[BINS] = {0};
    vec3 sun = v3_from4(p.gpu.sun_direction);
    for (int j = 0; j < N; j++)
        for (int i = 0; i < N; i++) {
            vec3 d = camera_ray(&p.gpu.camera, (float)i + 0.5f, (float)j + 0.5f);
            double theta = acos(fmax(-1.0, fmin(1.0, (double)v3_dot(d, sun)))) / DEG;
            int b = (int)floor(theta + 0.5);
            sum[b] += r.rgb[3 * (j * N + i) + 1];
            count[b] += 1.0;
        }
    const float4 *rows = atmo_plan_buffer_find(&p, "clouds_phase_table")->host_data;
    double best_render = -1.0, best_table = -1.0, max_render = -1.0, max_table = -1.0;
    for (int b = 130; b <= 160; b++) {
        if (count[b] > 0 && sum[b] / count[b] > max_render)
            max_render = sum[b] / count[b], best_render = b;
        vec3 pt = phase_rows_eval(rows, p.gpu.clouds.table_size, (float)cos(b * DEG));
        if (pt.y > max_table)
            max_table = pt.y, best_table = b;
    }
    printf("fog bow: render %.0f deg, table %.0f deg (scattering angle)\n", best_render,
           best_table);
    CHECK(best_table > 131 && best_table < 159); /* a maximum inside the window */
    CHECK_ABS(best_render, best_table, 2.0);
    free(r.rgb);
    atmo_plan_free(&p);
    return test_finish();
}
