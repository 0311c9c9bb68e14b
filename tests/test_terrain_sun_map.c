/* test_terrain_sun_map — the terrain's sun-height map (kernels/terrain/terrain_sun.h, its bake
 * terrain_sun_map.h / .cl): the device's map, read back, looked up on the host (the same
 * header) against the exact march toward the sun.
 * labels: kernel
 *
 * Scenes: thesis-1's mountains (seed 7, sun 2.5 degrees high) and thesis-3's site (seed 34,
 * sun 3.9 degrees), each with a map of 512 texels over 10 km (texels of 19.5 m) and a lead of
 * terrain.shadow_far_m = 10 km.
 *
 * Oracle: the exact march (terrain.h's terrain_trace, host build) from the point toward the
 * sun's centre, with hit tolerance 0 (1 cm), no over-relaxation and 4096 steps, up to the
 * bake's sunward end (the distance at which the ray's gnomonic x reaches the last texel of the
 * lead): the map holds exactly the terrain between the point and that end.
 *
 * Band. The map's verdict (lit iff z >= S, z the point's altitude) may differ from the march's
 * only where z lies within delta of the true S:
 *     delta = L t (sqrt 2 + 1/2) + w / 2 + 1 m,
 * L the slope bound (terrain.h's, plan_terrain.c), t the texel, w the soft edge: the bake
 * samples the height field every t along a row, so a peak between samples rises at most L t / 2
 * above them; the true S is L-Lipschitz across the rows and along them (max(L, tan e) = L),
 * so the bilinear lookup of the four texels around the point (each within sqrt 2 t of it)
 * errs by at most sqrt 2 L t more; 1 m covers the float rounding of the points and of the
 * recurrence (about a millimetre per texel). A disagreement is checked by one more march from
 * the point moved delta along its vertical (down where the march says lit, up where it says
 * shadowed): the march must then agree with the map. POINTS random points per scene, uniform
 * over the map and 0 to 1000 m above the surface; the share of disagreements (inside the
 * band) and the largest |z - S| among them are printed.
 *
 * Power: the same judge on maps broken on purpose must report violations:
 *   - mirrored: each row reversed (the sun from the opposite azimuth);
 *   - no recurrence: S = the ground height (every point above the terrain lit);
 *   - double drop: the recurrence with twice the per-texel drop (too high a sun).
 * Each reports hundreds of violations at these scenes (printed); the test fails unless each
 * reports at least one.
 * Cache: the map's key (atmo_product_key) changes with the sun's azimuth and the camera's
 * position and not with the image's height; with the disk cache on, a second precompute
 * loads the stored map bit for bit, and a damaged file (a payload byte flipped) is reported,
 * recomputed to the same bits and rewritten.
 * Also: a point beyond the square gets -1 (the caller marches); the sun below the camera's
 * horizon or at its zenith (the rows' vanishing point inside the bake) plans an empty map; terrain.sun_visibility = exact and path mode plan none. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "common/compat.h"
#include "common/rng.h"
#include "terrain/terrain.h"
#include "terrain/terrain_sun.h"
#include "terrain/terrain_sun_map.h"
#include "atmo/cl_runtime.h"
#include "atmo/embedded.h"
#include "atmo/features.h"
#include "atmo/plan_terrain.h"
#include "atmo/render.h"
#include "testlib.h"
#include "testscene.h"

#define POINTS 2000
#define HEIGHT_RANGE_M 1000.0
#define ORACLE_STEPS 4096
#define FLOAT_MARGIN_M 1.0

typedef struct sun_case {
    atmo_plan plan;
    atmo_gpu_scene oracle; /* the plan's struct with the exact march's tolerance at 0 */
    float *map;
    int n;
} sun_case;

static void open_case(sun_case *c, const char *preset, atmo_cl *cl)
{
    atmo_scene sc;
    test_scene_preset(&sc, preset);
    test_scene_set(&sc, "clouds.enabled=false"); /* the terrain's map alone; fast has no clouds */
    test_scene_set(&sc, "atmosphere.method=fast");
    test_scene_set(&sc, "image.width=8");
    test_scene_set(&sc, "image.height=8");
    test_scene_set(&sc, "terrain.sun_map_size=512");
    test_scene_set(&sc, "terrain.sun_map_extent_m=10000");
    test_scene_set(&sc, "terrain.shadow_far_m=10000");
    test_plan(&sc, &c->plan);
    c->n = c->plan.gpu.terrain.sun_map_size;
    CHECK(c->n == 512);
    c->oracle = c->plan.gpu;
    c->oracle.terrain.tolerance = 0.0f;
    c->oracle.terrain.optimism = 1.0f;
    cl_program prog = test_plan_program(cl, &c->plan, "");
    cl_mem scene = test_cl_buffer(cl, sizeof c->plan.gpu, &c->plan.gpu);
    cl_mem luts[ATMO_PLAN_MAX_BUFFERS] = {0};
    size_t texels = (size_t)c->n * (size_t)c->n;
    c->map = malloc(sizeof(float) * texels);
    if (!c->map) {
        fprintf(stderr, "out of memory\n");
        exit(1);
    }
    test_precompute(cl, prog, scene, &c->plan, luts);
    test_cl_read(cl, test_plan_buffer(&c->plan, luts, "terrain_sun_map"), sizeof(float) * texels,
                 c->map);
    test_release_luts(luts);
    clReleaseMemObject(scene);
    clReleaseProgram(prog);
}

/* The exact march from p (camera-relative) toward the sun up to the bake's sunward end: 1 lit. */
static int march_lit(const sun_case *c, vec3 p)
{
    const atmo_gpu_scene *s = &c->oracle;
    vec3 n, a, b, sun = v3_from4(s->sun_direction);
    terrain_sun_frame(s, &n, &a, &b);
    double R = s->atmosphere.bottom_radius, texel = terrain_sun_texel_m(s);
    double X = (c->n - 1 + s->terrain.sun_map_lead + 0.5) * texel - 0.5 * s->terrain.sun_map_extent_m;
    double D = s->camera.local_up.w + v3_dot(n, p), ap = v3_dot(a, p);
    double t_end = (X * D - R * ap) / (R * v3_dot(a, sun) - X * v3_dot(n, sun));
    float t;
    return !terrain_trace(s, NULL, p, sun, 0.0f, (float)t_end, ORACLE_STEPS, &t, 0);
}

/* The camera-relative point at grid coordinates (gx, gy) of the map, z metres above the
 * ground sphere (formed in double, then rounded). */
static vec3 grid_point(const sun_case *c, double gx, double gy, double z)
{
    const atmo_gpu_scene *s = &c->plan.gpu;
    vec3 n, a, b;
    terrain_sun_frame(s, &n, &a, &b);
    double R = s->atmosphere.bottom_radius, texel = terrain_sun_texel_m(s);
    double half_e = 0.5 * s->terrain.sun_map_extent_m;
    double x = (gx + 0.5) * texel - half_e;
    double y = ((gy + 0.5) * texel - half_e) * (1.0 - x * s->terrain.sun_map_axis.w / R);
    double w[3], len = 0.0, out[3];
    double nn[3] = {n.x, n.y, n.z}, aa[3] = {a.x, a.y, a.z}, bb[3] = {b.x, b.y, b.z};
    for (int i = 0; i < 3; i++)
        w[i] = R * nn[i] + x * aa[i] + y * bb[i], len += w[i] * w[i];
    len = sqrt(len);
    for (int i = 0; i < 3; i++)
        out[i] = (R + z) * w[i] / len - R * nn[i] - s->terrain.camera.w * nn[i];
    /* (R + z) w / |w| - r_c n: the radius cancels in double, the rounding is the float's */
    return v3((float)out[0], (float)out[1], (float)out[2]);
}

typedef struct tally {
    int disagree, violations;
    double widest; /* largest |z - S_map| among the disagreements */
} tally;

/* Judges `map` (n x n, the case's frame) at POINTS random points against the march. */
static tally judge(const sun_case *c, const float *map, double delta)
{
    const atmo_gpu_scene *s = &c->plan.gpu;
    tally r = {0, 0, 0.0};
    for (uint i = 0; i < POINTS; i++) {
        double gx = rng_uniform(11u, i, 0u, 0u) * (c->n - 1);
        double gy = rng_uniform(11u, i, 0u, 1u) * (c->n - 1);
        vec3 ground = grid_point(c, gx, gy, 0.0);
        double h = terrain_surface(s, NULL, terrain_locate(s, ground));
        vec3 p = grid_point(c, gx, gy, h + HEIGHT_RANGE_M * rng_uniform(11u, i, 0u, 2u));
        float v = terrain_sun_map_visibility(s, map, p);
        CHECK(v >= 0.0f);
        int map_lit = v >= 0.5f, lit = march_lit(c, p);
        if (map_lit == lit)
            continue;
        r.disagree++;
        float g_x = 0.0f, g_y = 0.0f;
        terrain_sun_grid(s, p, &g_x, &g_y);
        double S = terrain_sun_height(s, map, g_x, g_y), z = terrain_locate(s, p).alt;
        r.widest = fmax(r.widest, fabs(z - S));
        vec3 up = terrain_vertical(s, p);
        vec3 moved = v3_add(p, v3_scale(up, (float)(lit ? -delta : delta)));
        if (march_lit(c, moved) != map_lit)
            r.violations++;
    }
    return r;
}

static void run_case(const char *preset, atmo_cl *cl)
{
    sun_case c;
    open_case(&c, preset, cl);
    const atmo_gpu_scene *s = &c.plan.gpu;
    int n = c.n;
    double texel = terrain_sun_texel_m(s), L = s->terrain.slope_bound;
    double delta = L * texel * (sqrt(2.0) + 0.5) + 0.5 * s->terrain.sun_map_soft_m + FLOAT_MARGIN_M;
    tally t = judge(&c, c.map, delta);
    printf("%s: texel %.1f m, L %.2f, delta %.0f m: %d of %d points disagree with the march "
           "(%.2f %%), all within |z - S| <= %.1f m; %d outside the band\n",
           preset, texel, L, delta, t.disagree, POINTS, 100.0 * t.disagree / POINTS, t.widest,
           t.violations);
    CHECK(t.violations == 0);

    size_t texels = (size_t)n * (size_t)n;
    float *broken = calloc(texels, sizeof(float));
    if (!broken) {
        CHECK(broken != NULL);
        return;
    }
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++)
            broken[j * n + i] = c.map[j * n + (n - 1 - i)];
    tally mirrored = judge(&c, broken, delta);
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++)
            broken[j * n + i] = terrain_sun_map_ground(s, NULL, i, j);
    tally flat = judge(&c, broken, delta);
    for (int j = 0; j < n; j++) { /* the recurrence with the drop doubled */
        float S = 0.0f, sin_prev = 0.0f, cos_prev = 1.0f, R = s->atmosphere.bottom_radius;
        vec3 up;
        for (int k = n - 1 + s->terrain.sun_map_lead; k >= 0; k--) {
            float sin_e = terrain_sun_map_line(s, k, j, &up);
            float cos_e = sqrtf(1.0f - sin_e * sin_e), h = terrain_sun_map_ground(s, NULL, k, j);
            float dc = (sin_e - sin_prev) * (sin_e + sin_prev) / (cos_e + cos_prev);
            S = k == n - 1 + s->terrain.sun_map_lead ? h : fmaxf(h, S + 2.0f * (R + S) * dc / cos_e);
            sin_prev = sin_e, cos_prev = cos_e;
            if (k < n)
                broken[j * n + k] = S;
        }
    }
    tally doubled = judge(&c, broken, delta);
    printf("%s, broken maps: mirrored %d, no recurrence %d, double drop %d violations (of %d "
           "points)\n",
           preset, mirrored.violations, flat.violations, doubled.violations, POINTS);
    CHECK(mirrored.violations > 0);
    CHECK(flat.violations > 0);
    CHECK(doubled.violations > 0);
    free(broken);

    vec3 beyond = grid_point(&c, -2.0, 0.5 * n, 100.0);
    CHECK(terrain_sun_map_visibility(s, c.map, beyond) == -1.0f);
    free(c.map);
    atmo_plan_free(&c.plan);
}

static int planned(const char *const *sets)
{
    atmo_scene sc;
    atmo_plan p;
    test_scene_preset(&sc, "thesis-1");
    test_scene_set(&sc, "image.width=8");
    test_scene_set(&sc, "image.height=8");
    for (int i = 0; sets[i]; i++)
        test_scene_set(&sc, sets[i]);
    test_plan(&sc, &p);
    int size = atmo_plan_buffer_find(&p, "terrain_sun_map") ? p.gpu.terrain.sun_map_size : -1;
    atmo_plan_free(&p);
    return size;
}

static void small_plan(atmo_plan *p, const char *set)
{
    atmo_scene sc;
    test_scene_preset(&sc, "thesis-1");
    test_scene_set(&sc, "image.width=8");
    test_scene_set(&sc, "image.height=8");
    test_scene_set(&sc, "terrain.sun_map_size=64");
    if (set)
        test_scene_set(&sc, set);
    test_plan(&sc, p);
}

static unsigned long long map_key(const char *set, const atmo_device_identity *dev)
{
    atmo_plan p;
    small_plan(&p, set);
    int f = -1;
    for (int i = 0; i < p.feature_count; i++)
        if (strcmp(p.features[i]->name, "terrain_sun_map") == 0)
            f = i;
    CHECK(f >= 0);
    unsigned long long k = f >= 0 ? atmo_product_key(&p, f, dev, atmo_kernel_sources) : 0;
    atmo_plan_free(&p);
    return k;
}

/* The map of plan p through atmo_precompute (its disk cache as p says) into out (64 x 64). */
static atmo_precompute_info cached_map(atmo_cl *cl, cl_program prog, const atmo_plan *p,
                                       float *out)
{
    cl_mem scene = test_cl_buffer(cl, sizeof p->gpu, &p->gpu);
    cl_mem luts[ATMO_PLAN_MAX_BUFFERS] = {0};
    atmo_precompute_info info;
    atmo_err e;
    CHECK(atmo_precompute(cl, prog, p, scene, luts, &info, &e) == ATMO_OK);
    test_cl_read(cl, test_plan_buffer(p, luts, "terrain_sun_map"), sizeof(float) * 64 * 64, out);
    test_release_luts(luts);
    clReleaseMemObject(scene);
    return info;
}

static void test_cache(atmo_cl *cl)
{
    atmo_device_identity dev = {cl->device_name, cl->device_vendor, cl->driver_version};
    unsigned long long k = map_key(NULL, &dev);
    CHECK(map_key("sun.azimuth_deg=-150", &dev) != k);
    CHECK(map_key("camera.position_m=23796,2266,16700", &dev) != k);
    CHECK(map_key("image.height=16", &dev) == k);

    test_fresh_cache_dir();
    char dir[1024], path[1200];
    CHECK(atmo_cache_dir(dir, sizeof dir) == 0);
    atmo_plan p;
    small_plan(&p, NULL);
    p.cache_luts = 2;
    cl_program prog = test_plan_program(cl, &p, "");
    static float first[64 * 64], again[64 * 64], healed[64 * 64];
    atmo_precompute_info a = cached_map(cl, prog, &p, first);
    atmo_precompute_info b = cached_map(cl, prog, &p, again);
    CHECK(a.loaded == 0 && b.loaded > a.loaded);
    CHECK(memcmp(first, again, sizeof first) == 0);
    snprintf(path, sizeof path, "%s/terrain_sun_map-%016llx.bin", dir, k);
    FILE *f = fopen(path, "r+b");
    CHECK(f != NULL);
    if (f) {
        long at = 4096; /* inside the payload: the map's floats */
        int c;
        CHECK(fseek(f, at, SEEK_SET) == 0 && (c = fgetc(f)) != EOF);
        CHECK(fseek(f, at, SEEK_SET) == 0 && fputc(c ^ 0x5a, f) != EOF);
        fclose(f);
    }
    atmo_precompute_info d = cached_map(cl, prog, &p, healed);
    CHECK(d.damaged == 1);
    CHECK(memcmp(first, healed, sizeof first) == 0);
    atmo_precompute_info e2 = cached_map(cl, prog, &p, healed);
    CHECK(e2.damaged == 0 && e2.loaded == b.loaded);
    clReleaseProgram(prog);
    atmo_plan_free(&p);
}

int main(void)
{
    test_require_opencl();
    atmo_cl cl;
    test_cl_open(&cl);
    run_case("thesis-1", &cl);
    run_case("thesis-3", &cl);
    test_cache(&cl);
    atmo_cl_close(&cl);
    const char *const below[] = {"sun.zenith_deg=90.5", NULL};
    const char *const noon[] = {"sun.zenith_deg=0", NULL};
    const char *const exact[] = {"terrain.sun_visibility=exact", NULL};
    const char *const path[] = {"render.mode=path", NULL};
    const char *const none[] = {NULL};
    CHECK(planned(none) == 1024);
    CHECK(planned(below) == 0);
    CHECK(planned(noon) == 0);
    CHECK(planned(exact) == -1);
    CHECK(planned(path) == -1);
    return test_finish();
}
