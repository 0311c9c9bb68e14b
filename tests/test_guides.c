/* test_guides — the denoiser's guides (host/render/guides.c, kernels/render/guides.cl) in both
 * modes: right against closed forms, and free of noise.
 * labels: render slow
 *
 * Oracle 1, a closed form: a heightfield that is a tilted plane, h(x, z) = H0 + A x + B z over
 * the DEM's frame (world X east, Z north: row 0 is the DEM's north edge, dem.h; a one-channel
 * float EXR through terrain.heightmap_file), whose bilinear interpolation and central differences are the plane
 * itself. Its normal is N = normalize(-A, 1, -B) in the tangent frame of the ground sphere at
 * the point (terrain.h), with H0 = 1000 m high enough that the view (camera at 2500 m, 60 deg
 * down) sees no sea; the frame turns away from the origin's by at most d / R for a point
 * d metres from it (R = 6360 km), so every pixel whose guide rays all meet the terrain must
 * have a normal of unit length (1e-5: the float rounding of a mean of up to 64 equal unit
 * vectors, the path tracer's 8 x 8 pattern)
 * within d_max / R + 0.01 degrees of N (the 0.01: float rounding of the heights, 2^-24 of
 * 1000 m over a texel of 62.5 m). Oracle 2, the material: a sphere of albedo (0.7, 0.5, 0.3)
 * in front of the camera: its pixels' albedo is the material's to 2e-6 (a float sum of up to 64
 * equal values below 1, each addition rounded by at most half an ulp of 64, 3.8e-6 / 2, over
 * 64: 63 of those, 1.9e-6), and their normals match the sphere's closed form at the pixel's centre
 * within the angle the pixel spans on the sphere (the guide averages over the pixel); a sky
 * pixel has albedo 1, normal 0 (OIDN's conventions); the ground sphere's pixels below the
 * camera have the ground's albedo and the vertical (0, 1, 0) to 1e-4 (they lie within 20 m of
 * the camera's foot: 3e-6 rad of the sphere's curvature). Oracle 3, exact: the guides carry no
 * noise: two renders with other seeds and sample counts give the same guides, bit for bit.
 * Preview (fast method) and path mode alike, 32 x 24 pixels.
 * Oracle 4, a closed form for a volume: a homogeneous cloud shell (cloud.enabled, extinction
 * sigma_c and single-scattering albedo w_c per channel from the plan) between 1000 and 2000 m,
 * seen in the preview from 3000 m looking down at the ground sphere (albedo 0.25) and from
 * 500 m looking up at the sky. Each guide ray's values are (guides.cl)
 *     albedo_c = (1 - e^{-tau_c}) w_c + e^{-tau_c} a_behind,
 *     normal = e^{-tau_y} n_behind,   tau_c = sigma_c L,
 * L the ray's own chord through the shell (double precision: the lengths of the ray inside the
 * two spheres before the ground), for each ray of the preview's pattern (its box at the cell
 * centres of ATMO_GUIDES_PREVIEW_GRID x ATMO_GUIDES_PREVIEW_GRID, gpu_enums.h), a_behind,
 * n_behind the ground's (0.25, its sphere's normal at the hit) or the sky's (1, 0); the pixel's
 * guide is the mean over the pattern. The liquid water content puts tau near 1 along the
 * vertical (0.5 to 3 over the views), where the guide depends most on tau. Tolerance 5e-6: the
 * float mean of at most 64 values below 1 (2e-6, as above) and the float chord's rounding
 * (the roots are formed without cancellation: a few 1e-7 of 3 km, 1e-3 m, times sigma_c of
 * about 1e-3 / m: 1e-6 in tau). */
#include <math.h>
#include <openexr.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/gpu_enums.h"
#include "atmo/guides.h"
#include "atmo/render.h"
#include "testlib.h"
#include "testscene.h"

#define W 32
#define H 24
#define DEM_N 129
#define DEM_EXTENT_M 8000.0
#define PLANE_H0 1000.0
#define PLANE_A 0.2
#define PLANE_B -0.1
#define GROUND_RADIUS_M 6360e3
#define GRID ATMO_GUIDES_PREVIEW_GRID /* the preview's pattern: GRID x GRID rays a pixel */

/* A one-channel ("Y") float scanline EXR of the plane sampled at the cells' centres. */
static int write_plane_exr(const char *path)
{
    float *h = malloc(sizeof(float) * DEM_N * DEM_N);
    double cell = DEM_EXTENT_M / DEM_N;
    for (int row = 0; row < DEM_N; row++)
        for (int col = 0; col < DEM_N; col++) {
            double x = (col + 0.5) * cell - DEM_EXTENT_M / 2;
            double z = DEM_EXTENT_M / 2 - (row + 0.5) * cell;
            h[row * DEM_N + col] = (float)(PLANE_H0 + PLANE_A * x + PLANE_B * z);
        }
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    exr_context_t ctxt = NULL;
    int part = -1, rows = 1, started = 0;
    exr_encode_pipeline_t enc = EXR_ENCODE_PIPELINE_INITIALIZER;
    exr_result_t r = exr_start_write(&ctxt, path, EXR_WRITE_FILE_DIRECTLY, &init);
    if (r == EXR_ERR_SUCCESS)
        r = exr_add_part(ctxt, NULL, EXR_STORAGE_SCANLINE, &part);
    if (r == EXR_ERR_SUCCESS)
        r = exr_initialize_required_attr_simple(ctxt, part, DEM_N, DEM_N, EXR_COMPRESSION_NONE);
    if (r == EXR_ERR_SUCCESS)
        r = exr_add_channel(ctxt, part, "Y", EXR_PIXEL_FLOAT, EXR_PERCEPTUALLY_LINEAR, 1, 1);
    if (r == EXR_ERR_SUCCESS)
        r = exr_write_header(ctxt);
    if (r == EXR_ERR_SUCCESS)
        r = exr_get_scanlines_per_chunk(ctxt, part, &rows);
    for (int y = 0; r == EXR_ERR_SUCCESS && y < DEM_N; y += rows) {
        exr_chunk_info_t ci;
        r = exr_write_scanline_chunk_info(ctxt, part, y, &ci);
        if (r == EXR_ERR_SUCCESS)
            r = started ? exr_encoding_update(ctxt, part, &ci, &enc)
                        : exr_encoding_initialize(ctxt, part, &ci, &enc);
        if (r != EXR_ERR_SUCCESS)
            break;
        enc.channels[0].encode_from_ptr = (const uint8_t *)(h + (size_t)y * DEM_N);
        enc.channels[0].user_pixel_stride = sizeof(float);
        enc.channels[0].user_line_stride = DEM_N * (int32_t)sizeof(float);
        enc.channels[0].user_bytes_per_element = sizeof(float);
        enc.channels[0].user_data_type = EXR_PIXEL_FLOAT;
        if (!started)
            r = exr_encoding_choose_default_routines(ctxt, part, &enc);
        started = 1;
        if (r == EXR_ERR_SUCCESS)
            r = exr_encoding_run(ctxt, part, &enc);
    }
    if (started)
        exr_encoding_destroy(ctxt, &enc);
    exr_result_t fin = ctxt ? exr_finish(&ctxt) : EXR_ERR_SUCCESS;
    free(h);
    return r == EXR_ERR_SUCCESS && fin == EXR_ERR_SUCCESS;
}

/* The guides of the scene of keys in `mode`, at spp samples with seed (block of
 * ATMO_GUIDES_FLOATS planes, malloc'd). */
static float *render_guides(const char *const *keys, const char *mode, int spp, int seed)
{
    atmo_scene s;
    char buf[64];
    test_scene_preset(&s, "sky-noon");
    for (int i = 0; keys[i]; i++)
        test_scene_set(&s, keys[i]);
    snprintf(buf, sizeof buf, "render.mode=%s", mode);
    test_scene_set(&s, buf);
    snprintf(buf, sizeof buf, "image.width=%d", W);
    test_scene_set(&s, buf);
    snprintf(buf, sizeof buf, "image.height=%d", H);
    test_scene_set(&s, buf);
    snprintf(buf, sizeof buf, "image.samples=%d", spp);
    test_scene_set(&s, buf);
    snprintf(buf, sizeof buf, "image.seed=%d", seed);
    test_scene_set(&s, buf);
    atmo_plan p;
    test_plan(&s, &p);
    atmo_render_settings rs;
    atmo_render_settings_default(&rs);
    rs.guides = 1;
    atmo_render_result r;
    atmo_err e;
    if (atmo_render(&p, &rs, &r, &e)) {
        fprintf(stderr, "render failed: %s\n", e.msg);
        exit(1);
    }
    atmo_plan_free(&p);
    float *g = r.guides;
    r.guides = NULL;
    atmo_render_result_free(&r);
    CHECK(g != NULL);
    if (!g)
        exit(1);
    return g;
}

/* The unit direction of the ray through pixel (x, y)'s centre (pinhole, fov 45 deg vertical,
 * the camera's pitch and yaw 0). */
static void centre_ray(int x, int y, double pitch_deg, double d[3])
{
    double forward[3], right[3], up[3], th = tan(22.5 * M_PI / 180.0), n = 0.0;
    atmo_camera_basis(pitch_deg, 0.0, forward, right, up);
    double sx = (2.0 * (x + 0.5) / W - 1.0) * th * W / H, sy = (1.0 - 2.0 * (y + 0.5) / H) * th;
    for (int k = 0; k < 3; k++)
        d[k] = forward[k] + sx * right[k] + sy * up[k], n += d[k] * d[k];
    for (int k = 0; k < 3; k++)
        d[k] /= sqrt(n);
}

static double angle_deg(const float *n, const double *m)
{
    double dot = 0.0, ln = 0.0, lm = 0.0;
    for (int k = 0; k < 3; k++)
        dot += n[k] * m[k], ln += (double)n[k] * n[k], lm += m[k] * m[k];
    return acos(fmin(dot / sqrt(ln * lm), 1.0)) * 180.0 / M_PI;
}

static void check_plane(const char *mode, const char *dem_path)
{
    char file[400];
    snprintf(file, sizeof file, "terrain.heightmap_file=%s", dem_path);
    const char *keys[] = {file, "terrain.heightmap_file_extent_m=8000",
                          "camera.position_m=0,2500,0", "camera.pitch_deg=-60",
                          "sun.zenith_deg=40", NULL};
    float *g = render_guides(keys, mode, 1, 1);
    size_t pixels = (size_t)W * H;
    double want[3] = {-PLANE_A, 1.0, -PLANE_B}, worst = 0.0, worst_len = 0.0, d_max = 0.0;
    int on_plane = 0;
    for (size_t i = 0; i < pixels; i++) {
        const float *n = g + 3 * pixels + 3 * i;
        float depth = g[6 * pixels + i];
        if (depth >= 1e9f)
            continue;
        double len = sqrt((double)n[0] * n[0] + (double)n[1] * n[1] + (double)n[2] * n[2]);
        worst_len = fmax(worst_len, fabs(len - 1.0));
        worst = fmax(worst, angle_deg(n, want));
        d_max = fmax(d_max, depth);
        on_plane++;
    }
    double tol = d_max / GROUND_RADIUS_M * 180.0 / M_PI + 0.01;
    printf("%s, plane: %d pixels, | |n| - 1 | <= %.2g, worst angle to the closed form %.4f deg "
           "(bound %.4f)\n", mode, on_plane, worst_len, worst, tol);
    CHECK(on_plane == (int)pixels);
    CHECK(worst_len <= 1e-5 && worst <= tol);
    free(g);
}

static void check_sphere(const char *mode)
{
    static const char *const keys[] = {
        "sun.zenith_deg=50", "camera.position_m=0,1.5,0", "camera.pitch_deg=-10",
        "atmosphere.ground_albedo=0.25", "objects=[{\"type\": \"sphere\", \"center_m\": [0.8, 1, 6], \"radius_m\": 1, "
        "\"albedo\": [0.7, 0.5, 0.3]}]",
        NULL};
    float *g = render_guides(keys, mode, 1, 1);
    float *g2 = render_guides(keys, mode, 3, 7);
    size_t pixels = (size_t)W * H;
    double c[3] = {0.8, -0.5, 6.0}, worst = 0.0;
    int sphere = 0, sky = 0, ground = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            size_t i = (size_t)y * W + x;
            const float *a = g + 3 * i, *n = g + 3 * pixels + 3 * i;
            float depth = g[6 * pixels + i];
            if (depth >= 1e10f) {
                CHECK(a[0] == 1.0f && a[1] == 1.0f && a[2] == 1.0f);
                CHECK(n[0] == 0.0f && n[1] == 0.0f && n[2] == 0.0f);
                sky++;
            }
            if (y == H - 1 && (x < 4 || x >= W - 4)) { /* the ground sphere, below the camera */
                CHECK(fabs(n[0]) < 1e-4 && fabs(n[1] - 1.0) < 1e-4 && fabs(n[2]) < 1e-4);
                CHECK(fabsf(a[0] - 0.25f) < 2e-6f && fabsf(a[2] - 0.25f) < 2e-6f);
                ground++;
            }
            if (depth > 8.0f) /* not wholly on the sphere (its far side is 7.2 m away) */
                continue;
            double d[3], b = 0.0, f2 = 0.0, m[3];
            centre_ray(x, y, -10.0, d);
            for (int k = 0; k < 3; k++)
                b -= d[k] * c[k], f2 += c[k] * c[k];
            if (b * b - f2 + 1.0 < 0.0) /* the centre's ray misses the sphere */
                continue;
            int on = fabsf(a[0] - 0.7f) < 2e-6f && fabsf(a[1] - 0.5f) < 2e-6f &&
                     fabsf(a[2] - 0.3f) < 2e-6f;
            if (!on)
                continue;
            double t = -b - sqrt(b * b - f2 + 1.0);
            for (int k = 0; k < 3; k++)
                m[k] = t * d[k] - c[k];
            /* the pixel spans 45 / H degrees at 6 m, i.e. t * that on a unit sphere */
            double tol = t * 45.0 / H * 1.5;
            double ang = angle_deg(n, m);
            worst = fmax(worst, ang / tol);
            CHECK(ang <= tol);
            sphere++;
        }
    int same = memcmp(g, g2, sizeof(float) * ATMO_GUIDES_FLOATS * pixels) == 0;
    printf("%s, sphere: %d pixels of the material's albedo (worst normal angle %.2f of its "
           "bound), %d sky pixels, %d ground pixels, guides bitwise equal for another seed and sample count: "
           "%s\n", mode, sphere, worst, sky, ground, same ? "yes" : "no");
    CHECK(sphere >= 20 && sky >= 20 && ground == 8 && same);
    free(g2);
    free(g);
}

/* The length of the ray from (0, r, 0) along d, over [0, t_end], inside the sphere of radius a
 * about the origin. */
static double inside_sphere(double r, const double *d, double t_end, double a)
{
    double b = r * d[1], disc = b * b - (r - a) * (r + a);
    if (disc < 0.0)
        return 0.0;
    double t0 = -b - sqrt(disc), t1 = -b + sqrt(disc);
    return fmax(fmin(t1, t_end) - fmax(t0, 0.0), 0.0);
}

/* The unit direction of the preview's ray at the sub-pixel position (px, py) (pinhole, fov 45
 * deg vertical, yaw 0). */
static void pixel_ray(double px, double py, double pitch_deg, double d[3])
{
    double forward[3], right[3], up[3], th = tan(22.5 * M_PI / 180.0), n = 0.0;
    atmo_camera_basis(pitch_deg, 0.0, forward, right, up);
    double sx = (2.0 * px / W - 1.0) * th * W / H, sy = (1.0 - 2.0 * py / H) * th;
    for (int k = 0; k < 3; k++)
        d[k] = forward[k] + sx * right[k] + sy * up[k], n += d[k] * d[k];
    for (int k = 0; k < 3; k++)
        d[k] /= sqrt(n);
}

/* One guide ray's closed form (oracle 4) at camera radius r along the direction d: albedo
 * into a[], normal into n[]. */
static void shell_ray(double r, const double *d, const float *sigma, const float *w, double *a,
                      double *n)
{
    double R = GROUND_RADIUS_M, T[3];
    double b = r * d[1], disc = b * b - (r - R) * (r + R);
    double t_ground = disc >= 0.0 && -b - sqrt(disc) > 0.0 ? -b - sqrt(disc) : INFINITY;
    double L = inside_sphere(r, d, t_ground, R + 2000.0) - inside_sphere(r, d, t_ground, R + 1000.0);
    for (int c = 0; c < 3; c++)
        T[c] = exp(-sigma[c] * L);
    double nb[3] = {0.0, 0.0, 0.0}, ab = 1.0;
    if (isfinite(t_ground)) {
        double p[3] = {t_ground * d[0], r + t_ground * d[1], t_ground * d[2]};
        double len = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
        for (int k = 0; k < 3; k++)
            nb[k] = p[k] / len;
        ab = 0.25;
    }
    for (int c = 0; c < 3; c++) {
        a[c] += (1.0 - T[c]) * w[c] + T[c] * ab;
        n[c] += T[1] * nb[c];
    }
}

/* Oracle 4 on one view: camera at altitude_m, pitch pitch_deg. */
static void check_cloud_shell(double altitude_m, double pitch_deg)
{
    char pos[64], pitch[64];
    snprintf(pos, sizeof pos, "camera.position_m=0,%g,0", altitude_m);
    snprintf(pitch, sizeof pitch, "camera.pitch_deg=%g", pitch_deg);
    const char *const keys[] = {"atmosphere.ground_albedo=0.25", "cloud.enabled=true",
                                "cloud.bottom_m=1000", "cloud.top_m=2000",
                                "cloud.lwc_g_m3=0.006", pos, pitch, NULL};
    atmo_scene s;
    test_scene_preset(&s, "sky-noon");
    for (int i = 0; keys[i]; i++)
        test_scene_set(&s, keys[i]);
    atmo_plan p;
    test_plan(&s, &p);
    float sigma[3] = {p.gpu.cloud.extinction.x, p.gpu.cloud.extinction.y,
                      p.gpu.cloud.extinction.z};
    float w[3] = {p.gpu.cloud.albedo.x, p.gpu.cloud.albedo.y, p.gpu.cloud.albedo.z};
    atmo_plan_free(&p);
    float *g = render_guides(keys, "preview", 1, 1);
    size_t pixels = (size_t)W * H;
    double r = GROUND_RADIUS_M + altitude_m, worst_a = 0.0, worst_n = 0.0, tau_lo = INFINITY,
           tau_hi = 0.0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            double a[3] = {0, 0, 0}, n[3] = {0, 0, 0}, d[3];
            for (int j = 0; j < GRID; j++)
                for (int i = 0; i < GRID; i++) {
                    pixel_ray(x + (i + 0.5) / GRID, y + (j + 0.5) / GRID, pitch_deg, d);
                    shell_ray(r, d, sigma, w, a, n);
                }
            pixel_ray(x + 0.5, y + 0.5, pitch_deg, d);
            double L = inside_sphere(r, d, INFINITY, GROUND_RADIUS_M + 2000.0) -
                       inside_sphere(r, d, INFINITY, GROUND_RADIUS_M + 1000.0);
            if (altitude_m > 2000.0) /* down through both spheres: the near part only */
                L = 0.5 * L;
            tau_lo = fmin(tau_lo, sigma[1] * L), tau_hi = fmax(tau_hi, sigma[1] * L);
            size_t px = (size_t)y * W + x;
            for (int c = 0; c < 3; c++) {
                worst_a = fmax(worst_a, fabs(g[3 * px + c] - a[c] / (GRID * GRID)));
                worst_n = fmax(worst_n, fabs(g[3 * pixels + 3 * px + c] - n[c] / (GRID * GRID)));
            }
        }
    printf("preview, cloud shell from %g m, pitch %g deg: tau %.2f to %.2f, worst albedo error "
           "%.2g, worst normal error %.2g (bound 5e-6)\n", altitude_m, pitch_deg, tau_lo, tau_hi,
           worst_a, worst_n);
    CHECK(tau_lo >= 0.3 && tau_hi <= 4.0);
    CHECK(worst_a <= 5e-6 && worst_n <= 5e-6);
    free(g);
}

int main(void)
{
    test_require_opencl();
    const char *dem_path = "test_guides_plane.exr";
    CHECK(write_plane_exr(dem_path));
    check_plane("preview", dem_path);
    check_plane("path", dem_path);
    check_sphere("preview");
    check_sphere("path");
    check_cloud_shell(3000.0, -60.0);
    check_cloud_shell(500.0, 60.0);
    remove(dem_path);
    return test_finish();
}
