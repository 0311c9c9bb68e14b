/* test_terrain_occluders — the preview's terrain and objects in the shadows of the other
 * occluders and of the shadowing media (kernels/terrain/terrain_shade.h's terrain_radiance,
 * kernels/render/objects_light.h's objects_light_radiance: visibility_sun_surface and
 * visibility_sun, media/visibility.h).
 * labels: kernel slow
 *
 * Scene: the sun at the zenith, method march, a nearly flat terrain (heights 0..2 m, all
 * land), a sphere of radius 8 m centred 30 m up over the camera's foot; variants with a
 * homogeneous cloud shell 1000..1500 m (LWC 0.01 g/m^3: optical depth tau = 500 m times the
 * extinction per channel, read from the plan, about 0.78) and with a second sphere (radius 20 m, 300 m up) over the
 * first. Probes (on the device, the renderer's own functions): the terrain's radiance along a
 * vertical ray down to the ground at distances rho = 0, 3, 6 m (inside the first sphere's
 * shadow, a disc of radius 8 m under a zenith sun, parallel rays) and 10, 14 m (outside) from
 * its foot, and the sphere's own radiance at its top (normal up).
 * Oracles (closed forms of the Lambertian surfaces' light, L = K + S V with K the sky's part,
 * S the sun's, V the sun's visibility, which the two other parts do not depend on):
 *  1. The shell's shadow: V = e^{-tau / mu_0} = e^{-tau}; with the terrain's light L_N
 *     without shell and object and L_S with the shell, S = (L_N - L_S) / (1 - e^{-tau}), so
 *     the sky's part alone is K = L_N - S.
 *  2. The object's shadow: inside the disc the terrain's light with the sphere, L_O, is K
 *     (relative 1e-4 of L_N: float roundings of the sums); outside it L_O = L_N to 1e-6.
 *  3. The object under the shell: with the second sphere shadowing it, its top's light is its
 *     sky's part K_o, so (L_o - L_o,shell) / (L_o - K_o) = 1 - e^{-tau} (relative 1e-4). */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "atmo/plan.h"
#include "atmo/scene.h"
#include "testcl.h"
#include "testlib.h"
#include "testscene.h"

static const char probe_src[] =
    "__kernel void ground(__global const atmo_gpu_scene *s, ATMO_LUT_PARAMS,\n"
    "                     __global const float4 *p, __global float4 *out, uint n) {\n"
    "  uint i = get_global_id(0); if (i >= n) return;\n"
    "  vec3 o = (vec3)(p[i].x, p[i].y, p[i].z), d = (vec3)(0.0f, -1.0f, 0.0f);\n"
    "  medium_ray m = medium_ray_make(s, o, d);\n"
    "  float t = -1.0f;\n"
    "  if (!terrain_trace(s, heightmap, o, d, 0.0f, 1e4f, s->terrain.steps, &t, 0)) {\n"
    "    out[i] = (float4)(-1.0f); return; }\n"
    "  vec3 L = terrain_radiance(s, ATMO_LUT_ARGS, &m, t);\n"
    "  out[i] = (float4)(L.x, L.y, L.z, t);\n"
    "}\n"
    "#ifdef ATMO_OBJECTS_PREVIEW\n"
    "__kernel void object(__global const atmo_gpu_scene *s, ATMO_LUT_PARAMS,\n"
    "                     __global const float4 *p, __global float4 *out, uint n) {\n"
    "  uint i = get_global_id(0); if (i >= n) return;\n"
    "  vec3 o = (vec3)(p[i].x, p[i].y, p[i].z), d = (vec3)(0.0f, -1.0f, 0.0f);\n"
    "  medium_ray m = medium_ray_make(s, o, d);\n"
    "  vec3 L = objects_light_radiance(s, ATMO_LUT_ARGS, &m, p[i].w);\n"
    "  out[i] = (float4)(L.x, L.y, L.z, 0.0f);\n"
    "}\n"
    "#endif\n";

#define RHOS 5
static const double rhos[RHOS] = {0.0, 3.0, 6.0, 10.0, 14.0};
#define RADIUS 8.0
#define SPHERE "{\"type\": \"sphere\", \"center_m\": [0, 30, 0], \"radius_m\": 8}"
#define BLOCKER "{\"type\": \"sphere\", \"center_m\": [0, 300, 0], \"radius_m\": 20}"

static void scene_of(atmo_scene *s, int shell, const char *objects)
{
    test_scene_preset(s, "sky-noon");
    test_scene_set(s, "sun.zenith_deg=0");
    test_scene_set(s, "atmosphere.method=march");
    test_scene_set(s, "camera.position_m=0,50,0");
    test_scene_set(s, "terrain.enabled=true");
    test_scene_set(s, "terrain.max_height_m=2");
    test_scene_set(s, "terrain.land_fraction=1");
    if (shell) {
        test_scene_set(s, "cloud.enabled=true");
        test_scene_set(s, "cloud.bottom_m=1000");
        test_scene_set(s, "cloud.top_m=1500");
        test_scene_set(s, "cloud.lwc_g_m3=0.01");
    }
    if (objects)
        test_scene_set(s, objects);
}

/* The probe `kernel` at n points of the scene; its plan's shell extinction into ext (may be
 * NULL). */
static void probe(int shell, const char *objects, const char *kernel, const float4 *pts, int n,
                  float4 *out, double ext[3])
{
    atmo_scene s;
    atmo_plan p;
    scene_of(&s, shell, objects);
    test_plan(&s, &p);
    if (ext)
        ext[0] = p.gpu.cloud.extinction.x, ext[1] = p.gpu.cloud.extinction.y,
        ext[2] = p.gpu.cloud.extinction.z;
    test_plan_points(&p, probe_src, kernel, pts, sizeof *pts, out, sizeof *out, n);
    atmo_plan_free(&p);
}

static double channel(float4 v, int c)
{
    return c == 0 ? v.x : c == 1 ? v.y : v.z;
}

int main(void)
{
    test_require_opencl();
    /* ray origins 20 m above the ground (camera-relative: the camera is 50 m up), below the
     * sphere (its bottom 28 m below the camera) */
    float4 pts[RHOS], none[RHOS], shell[RHOS], object[RHOS];
    for (int i = 0; i < RHOS; i++)
        pts[i] = (float4){(float)rhos[i], -30.0f, 0.0f, 0.0f};
    double ext[3];
    probe(0, NULL, "ground", pts, RHOS, none, NULL);
    probe(1, NULL, "ground", pts, RHOS, shell, ext);
    probe(0, "objects=[" SPHERE "]", "ground", pts, RHOS, object, NULL);
    double worst_in = 0.0, worst_out = 0.0, share = 0.0;
    for (int i = 0; i < RHOS; i++)
        for (int c = 0; c < 3; c++) {
            double tau = 500.0 * ext[c], ln = channel(none[i], c);
            double sun = (ln - channel(shell[i], c)) / (1.0 - exp(-tau)), sky = ln - sun;
            double lo = channel(object[i], c);
            CHECK(none[i].w > 0.0f && ln > 0.0);
            if (rhos[i] < RADIUS) {
                worst_in = fmax(worst_in, fabs(lo - sky) / ln);
                share = fmax(share, sky / ln);
                CHECK(fabs(lo - sky) <= 1e-4 * ln);
            } else {
                worst_out = fmax(worst_out, fabs(lo - ln) / ln);
                CHECK(fabs(lo - ln) <= 1e-6 * ln);
            }
        }
    printf("terrain: tau %.3f %.3f %.3f; in the sphere's shadow the light is the sky's part to "
           "%.2g (the sky's share at most %.3f), outside it unchanged to %.2g\n",
           500.0 * ext[0], 500.0 * ext[1], 500.0 * ext[2], worst_in, share, worst_out);
    CHECK(share < 0.5); /* the shadow is dark: the sun dominates at noon */

    /* 3: the sphere's top under the shell */
    float4 top = {0.0f, -11.0f, 0.0f, 1.0f}, lit, shaded, blocked;
    probe(0, "objects=[" SPHERE "]", "object", &top, 1, &lit, NULL);
    probe(1, "objects=[" SPHERE "]", "object", &top, 1, &shaded, NULL);
    probe(0, "objects=[" SPHERE ", " BLOCKER "]", "object", &top, 1, &blocked, NULL);
    double worst_o = 0.0;
    for (int c = 0; c < 3; c++) {
        double tau = 500.0 * ext[c], want = 1.0 - exp(-tau);
        double got = (channel(lit, c) - channel(shaded, c)) / (channel(lit, c) - channel(blocked, c));
        worst_o = fmax(worst_o, fabs(got - want) / want);
        CHECK(fabs(got - want) <= 1e-4 * want);
        CHECK(channel(blocked, c) < 0.5 * channel(lit, c));
    }
    printf("the sphere's top under the shell: its sun's part times e^-tau to %.2g\n", worst_o);
    return test_finish();
}
