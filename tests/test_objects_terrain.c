/* test_objects_terrain — objects placed on the terrain ("on_terrain", plan_objects.c)
 * and the checks of the keys (host/scene/scene_objects.c).
 * labels: kernel slow
 *
 * Oracles:
 *  1. Placement against the device's own terrain: a sphere with on_terrain and centre y = r
 *     rests on the surface, so the point of it r below its centre along the world's Y lies on
 *     the terrain; a box with y = 0 has the centre of its base on it. The device's float
 *     clearance (kernels/terrain/terrain.h: terrain_clearance, the same field the renderer
 *     traces) at those camera-relative points must be 0 within its float error, 0.2 m: the
 *     float height against double is within 0.17 m out to 3000 km (test_terrain_trace), here
 *     tens of km, plus the point's rounding (|p| ulp ~ 1e-3 m). The difference between the
 *     anchor's world Y and the surface's along the vertical rather than the Y axis is
 *     r (1 - cos(theta)), theta = |x| / R < 5e-3 rad: below 1e-5 m for r = 1 m. Four places over
 *     slopes of the thesis terrain and one with terrain_at_m (a box raised 2 m above the
 *     surface under another point: its base's clearance there must be 2 m; the same bound).
 *  2. The objects of a scene without on_terrain are where the scene puts them (the plan's rows
 *     equal the positions minus the camera, in float).
 *  3. Bad input: on_terrain without terrain.enabled, terrain_at_m without on_terrain, a
 *     non-boolean on_terrain, terrain_at_m of the wrong length: each one usage error naming
 *     objects[i] and the member; --save-scene's JSON of on_terrain objects reads back to the
 *     same list.
 *  4. The camera on the terrain (camera.on_terrain, host/plan/plan.c), the same oracle and
 *     bound: with `below` and y = 10 the device's clearance at the camera is 10 m; with `at`
 *     and y = 5 the point 5 m below the camera along Y over camera.terrain_at_m has clearance
 *     0; objects on that terrain are placed relative to the absolute camera.
 *  5. Objects on a DEM (terrain.heightmap_file: the shipped GeoTIFF, tests/data, with GDAL):
 *     a sphere, a box and a raised box with terrain_at_m at places over the file's 236-1076 m
 *     relief; the device's clearance (the resampled heightmap the renderer traces) at their
 *     anchors as in 1, the same bound. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/plan.h"
#include "atmo/scene.h"
#include "testlib.h"
#include "testscene.h"

static const char probe_src[] =
    "__kernel void clearance(__global const atmo_gpu_scene *s, ATMO_LUT_PARAMS,\n"
    "                        __global const float4 *p, __global float *out, uint n) {\n"
    "  uint i = get_global_id(0); if (i >= n) return;\n"
    "  out[i] = terrain_clearance(s, heightmap, p[i].xyz);\n"
    "}\n";

#define SPOTS 4
static const double spots[SPOTS][2] = {
    {22832, 13326}, {26631.5, 10749.5}, {23796, 16636}, {-3404, -35764}};

static void expect_error(const char *json, const char *needle)
{
    atmo_scene s;
    atmo_err e;
    test_scene_preset(&s, "sky-noon");
    int rc = atmo_scene_set_objects(&s, json, "the test", &e);
    if (rc == 0)
        rc = atmo_scene_validate(&s, &e);
    CHECK(rc == ATMO_ERR_USAGE);
    CHECK(rc != 0 && strstr(e.msg, needle) != NULL && strchr(e.msg, '\n') == NULL);
    printf("refused: %s\n", rc ? e.msg : "(accepted)");
}

/* The device's terrain_clearance at n camera-relative points of plan p. */
static void device_clearance(const atmo_plan *p, const float4 *pts, int count, float *out)
{
    test_plan_points(p, probe_src, "clearance", pts, sizeof *pts, out, sizeof *out, count);
}

/* The anchors of the plan's objects (a sphere's lowest point, a box's base centre). */
static void anchors(const atmo_plan *p, int n, float4 *pts)
{
    const atmo_gpu_object *rows = atmo_plan_buffer_find((atmo_plan *)p, "objects")->host_data;
    for (int i = 0; i < n; i++) {
        const atmo_gpu_object *o = &rows[i];
        if (o->kind == ATMO_OBJECT_SPHERE) {
            pts[i] = o->a;
            pts[i].y -= o->a.w;
        } else {
            pts[i].x = 0.5f * (o->a.x + o->b.x);
            pts[i].y = o->a.y;
            pts[i].z = 0.5f * (o->a.z + o->b.z);
        }
        pts[i].w = 0.0f;
    }
}

static void camera_on_terrain(void)
{
    atmo_scene s;
    atmo_plan p;
    float4 pts[2];
    float out[2];
    test_scene_preset(&s, "thesis-1");
    test_scene_set(&s, "camera.position_m=23796,10,16636");
    test_scene_set(&s, "camera.on_terrain=below");
    test_plan(&s, &p);
    pts[0] = (float4){0.0f, 0.0f, 0.0f, 0.0f};
    device_clearance(&p, pts, 1, out);
    printf("camera.on_terrain=below, y = 10: device clearance at the camera %.4f m\n", out[0]);
    CHECK_ABS(out[0], 10.0, 0.2);
    atmo_plan_free(&p);

    test_scene_set(&s, "camera.position_m=23000,5,13000");
    test_scene_set(&s, "camera.on_terrain=at");
    test_scene_set(&s, "camera.terrain_at_m=22832,13326");
    test_scene_set(&s, "objects=[{\"type\": \"sphere\", \"center_m\": [22832, 1, 13326], "
                       "\"radius_m\": 1, \"on_terrain\": true}]");
    test_plan(&s, &p);
    pts[0] = (float4){22832.0f - 23000.0f, -5.0f, 13326.0f - 13000.0f, 0.0f};
    anchors(&p, 1, &pts[1]);
    device_clearance(&p, pts, 2, out);
    printf("camera.on_terrain=at, y = 5: device clearance 5 m below it over the anchor %.4f m; "
           "the sphere on the terrain there %.4f m\n",
           out[0], out[1]);
    CHECK_ABS(out[0], 0.0, 0.2);
    CHECK_ABS(out[1], 0.0, 0.2);
    CHECK(fabs(pts[0].x - pts[1].x) < 1e-3f && fabs(pts[0].z - pts[1].z) < 1e-3f);
    atmo_plan_free(&p);
}

static void objects_on_dem(void)
{
#ifdef ATMO_HAVE_GDAL
    const char *src = getenv("ATMO_SOURCE_DIR");
    char set[640];
    snprintf(set, sizeof set, "terrain.heightmap_file=%s/tests/data/jacksboro_fault_dem.tif",
             src ? src : "..");
    atmo_scene s;
    atmo_plan p;
    test_scene_preset(&s, "sky-noon");
    test_scene_set(&s, set);
    test_scene_set(&s, "camera.position_m=0,3000,0");
    test_scene_set(&s, "objects=[{\"type\": \"sphere\", \"center_m\": [1000, 1.5, -2000], "
                       "\"radius_m\": 1.5, \"on_terrain\": true}, {\"type\": \"box\", \"min_m\": "
                       "[-5000, 0, 4000], \"size_m\": [2, 1, 4], \"on_terrain\": true}, "
                       "{\"type\": \"box\", \"min_m\": [9000, 2, -11000], \"size_m\": [1, 1, 1], "
                       "\"on_terrain\": true, \"terrain_at_m\": [9000.5, -10999.5]}]");
    test_plan(&s, &p);
    float4 pts[3];
    float out[3];
    anchors(&p, 3, pts);
    pts[2].y -= 2.0f; /* the raised box's base, 2 m above its anchor's surface */
    device_clearance(&p, pts, 3, out);
    double worst = 0;
    for (int i = 0; i < 3; i++) {
        worst = fmax(worst, fabs(out[i]));
        CHECK_ABS(out[i], 0.0, 0.2);
    }
    printf("on_terrain on a DEM: 3 anchors, device clearance within %.3g m of the placement\n",
           worst);
    atmo_plan_free(&p);
#else
    printf("on_terrain on a DEM: not run (built without GDAL: the shipped DEM is a GeoTIFF)\n");
#endif
}

int main(void)
{
    expect_error("[{\"type\": \"sphere\", \"center_m\": [0, 1, 5], \"radius_m\": 1, "
                 "\"on_terrain\": true}]",
                 "objects[0].on_terrain needs the terrain");
    expect_error("[{\"type\": \"sphere\", \"center_m\": [0, 1, 5], \"radius_m\": 1, "
                 "\"terrain_at_m\": [0, 5]}]",
                 "objects[0].terrain_at_m");
    expect_error("[{\"type\": \"box\", \"min_m\": [0, 1, 5], \"size_m\": [1, 1, 1], "
                 "\"on_terrain\": 1}]",
                 "objects[0].on_terrain");
    expect_error("[{\"type\": \"box\", \"min_m\": [0, 1, 5], \"size_m\": [1, 1, 1], "
                 "\"on_terrain\": true, \"terrain_at_m\": [1, 2, 3]}]",
                 "objects[0].terrain_at_m");

    /* the objects: a sphere and a box at each spot, and a raised box measured at another point */
    char json[4096];
    size_t n = 0;
    n += (size_t)snprintf(json + n, sizeof json - n, "[");
    for (int k = 0; k < SPOTS; k++)
        n += (size_t)snprintf(json + n, sizeof json - n,
                              "%s{\"type\": \"sphere\", \"center_m\": [%.1f, 1.5, %.1f], "
                              "\"radius_m\": 1.5, \"on_terrain\": true}, {\"type\": \"box\", "
                              "\"min_m\": [%.1f, 0, %.1f], \"size_m\": [2, 1, 4], "
                              "\"on_terrain\": true}",
                              k ? ", " : "", spots[k][0] + 40.0, spots[k][1], spots[k][0] - 1.0,
                              spots[k][1] - 2.0);
    n += (size_t)snprintf(json + n, sizeof json - n,
                          ", {\"type\": \"box\", \"min_m\": [100, 2, 200], \"size_m\": [1, 1, 1], "
                          "\"on_terrain\": true, \"terrain_at_m\": [23796, 16636]}]");
    atmo_scene s;
    atmo_err e;
    test_scene_preset(&s, "thesis-1");
    CHECK(atmo_scene_set_objects(&s, json, "the test", &e) == 0);
    char *saved = atmo_scene_objects_json(&s);
    atmo_scene back = s;
    CHECK(saved && atmo_scene_set_objects(&back, saved, "the saved scene", &e) == 0);
    CHECK(memcmp(&back.objects, &s.objects, sizeof s.objects) == 0);
    free(saved);
    atmo_plan p;
    test_plan(&s, &p);
    const atmo_plan_buffer *b = atmo_plan_buffer_find(&p, "objects");
    CHECK(b != NULL && b->host_data != NULL);
    const atmo_gpu_object *rows = b->host_data;
    int count = 2 * SPOTS + 1;
    float4 pts[2 * SPOTS + 2];
    double want[2 * SPOTS + 2];
    for (int i = 0; i < 2 * SPOTS; i++) {
        const atmo_gpu_object *o = &rows[i];
        if (o->kind == ATMO_OBJECT_SPHERE) {
            pts[i] = o->a;
            pts[i].y -= o->a.w; /* the lowest point of the sphere */
        } else {
            pts[i].x = 0.5f * (o->a.x + o->b.x);
            pts[i].y = o->a.y;
            pts[i].z = 0.5f * (o->a.z + o->b.z);
        }
        pts[i].w = 0.0f;
        want[i] = 0.0;
    }
    /* the raised box: 2 m above the surface under (23796, 16636), which lies at the same world
     * x, z relative to the camera as the box's anchor point */
    const double *cam = s.camera.position_m;
    pts[2 * SPOTS].x = (float)(23796.0 - cam[0]);
    pts[2 * SPOTS].y = rows[2 * SPOTS].a.y;
    pts[2 * SPOTS].z = (float)(16636.0 - cam[2]);
    pts[2 * SPOTS].w = 0.0f;
    want[2 * SPOTS] = 2.0;
    test_require_opencl();
    test_fresh_cache_dir();
    float out[2 * SPOTS + 2];
    device_clearance(&p, pts, count, out);
    double worst = 0;
    for (int i = 0; i < count; i++) {
        worst = fmax(worst, fabs(out[i] - want[i]));
        CHECK_ABS(out[i], want[i], 0.2);
    }
    printf("on_terrain: %d anchors, device clearance within %.3g m of the placement\n", count,
           worst);

    /* without on_terrain the rows are the positions minus the camera */
    test_scene_set(&s, "objects=[{\"type\": \"sphere\", \"center_m\": [23800, 2000, 16640], "
                       "\"radius_m\": 2}]");
    atmo_plan q;
    test_plan(&s, &q);
    const atmo_gpu_object *r = atmo_plan_buffer_find(&q, "objects")->host_data;
    CHECK(r[0].a.x == (float)(23800 - cam[0]) && r[0].a.y == (float)(2000 - cam[1]) &&
          r[0].a.z == (float)(16640 - cam[2]) && r[0].a.w == 2.0f);
    atmo_plan_free(&q);

    atmo_plan_free(&p);
    camera_on_terrain();
    objects_on_dem();
    return test_finish();
}
