/* test_path_sampling — the path tracer's sampling routines and the cameras, in a host build of
 * the shared kernel headers (kernels/render/bsdf.h, light_sun.h, light_sky.h, path_camera.h,
 * kernels/common/camera.h; float, as the kernels run them).
 * labels: unit stat
 *
 * Oracles:
 *   - Chi-square goodness of fit of every sampler against its closed-form density, with
 *     independent uniforms from a fixed xorshift stream, N samples in B bins whose expected
 *     probabilities are exact (bins chosen equal in the sampler's own CDF, or integrated in
 *     closed form): the statistic must stay below the chi-square quantile at p = 1e-4
 *     (test_chi2_critical_1e4, B - 1 degrees of freedom). Cosine hemisphere around a tilted
 *     normal: bins of sin^2(theta) x phi (each 1/B); sun cone (half-angle 5 degrees, wide
 *     enough that float spacing of cos near 1 does not quantise the bins): bins of
 *     (1 - cos)/(1 - cos alpha) x phi; the sky table's sampling (a synthetic sky: a bright
 *     patch, a gradient, black below the horizon) over its own texels, each expected with the
 *     mixture's probability c p_texel + (1 - c) Omega_texel / (4 pi) (which must sum to 1,
 *     1e-5), every direction the table's CDFs chose lying in a texel they can choose; pixel
 *     filter: bins of the truncated Gaussian's radial CDF x phi.
 *   - Pdf round trips: for samples w ~ p, E[g(w) / p(w)] = int g dw (importance-sampling
 *     identity), with g = cos^2 for the cosine sampler (2 pi / 3), g = 1 for the sun cone
 *     (its solid angle; 1/p is constant, so exact to float rounding) and the sky table's
 *     mixture (4 pi; with the uniform sky or an empty table 1/p = 4 pi exactly); the mean must lie within 5 standard errors of the integral (the estimator's own
 *     sample variance). Every sample is a unit vector inside its support.
 *   - Stratification: the first 2^k samples of a pixel's scrambled Sobol points form a
 *     (0, k, 2)-net: every elementary interval [a 2^-j, (a+1) 2^-j) x [b 2^-(k-j), (b+1)
 *     2^-(k-j)) holds exactly one point, for k = 0..10, every j, and 8 pixels (exact, no
 *     tolerance). Decorrelation between pixels: sample 0 of 40000 pixels is uniform over a
 *     20 x 20 grid (chi-square as above).
 *   - Cameras, closed forms at known pixels: the perspective's centre looks along forward and
 *     its right edge along normalize(forward + tan(fov/2) W/H right); the panorama follows
 *     Blender's equirectangular mapping (u = 1/2 - atan2(y_b, x_b) / 2 pi, v = 1/2 + asin(z_b) /
 *     pi with (x, y, z)_b = (x, z, y)_atmo, yaw -90): atmo +X at the centre, atmo +Z at u = 1/4,
 *     the zenith on the top row, thesis view 1's sun at the pixel the mapping gives it, and the
 *     ray of any pixel back to that pixel; the fisheye: the centre along forward, the top
 *     edge's middle at fov/2 from it, a point as many pixels to the side at the same angle (round
 *     whatever the aspect), the angle at radius rho 2 asin(rho sin(fov/4)) (equal-area), and
 *     the zero vector outside the circle. Tolerance 2e-6 on unit vectors (float rounding).
 *   - The thin lens (path.aperture_m > 0): closed form, see test_thin_lens. */
#include <math.h>
#include <stdint.h>
#include <string.h>
#include "atmo/plan.h"
#include "common/compat.h"
#include "render/path_camera.h"
#include "render/bsdf.h"
#include "render/light_sun.h"
#include "render/light_sky.h"
#include "testlib.h"

#define N 200000

static uint64_t state = 0x2545F4914F6CDD1Dull;
static float uniform(void)
{
    state ^= state >> 12;
    state ^= state << 25;
    state ^= state >> 27;
    return (float)((state * 0x2545F4914F6CDD1Dull) >> 40) * (1.0f / 16777216.0f);
}

static double chi2(const double *count, const double *p, int bins, double n)
{
    double x = 0.0;
    for (int i = 0; i < bins; i++) {
        double e = p[i] * n;
        x += (count[i] - e) * (count[i] - e) / e;
    }
    return x;
}

static int phi_bin(double phi, int n)
{
    double f = (phi + M_PI) / (2.0 * M_PI);
    int b = (int)(f * n);
    return b < 0 ? 0 : (b >= n ? n - 1 : b);
}

static int clampi(int b, int n) { return b < 0 ? 0 : (b >= n ? n - 1 : b); }

/* local coordinates of w in the frame of n */
static void local(vec3 n, vec3 w, double *z, double *phi)
{
    vec3 t, b;
    frame_basis(n, &t, &b);
    *z = v3_dot(w, n);
    *phi = atan2(v3_dot(w, b), v3_dot(w, t));
}

static void test_cosine(void)
{
    enum { BZ = 10, BP = 16 };
    static double count[BZ * BP], p[BZ * BP];
    vec3 n = v3_normalize(v3(0.3f, -0.5f, 0.8f));
    double sum = 0.0, sum2 = 0.0, worst_len = 0.0, min_z = 1.0;
    for (int i = 0; i < BZ * BP; i++)
        p[i] = 1.0 / (BZ * BP);
    for (int i = 0; i < N; i++) {
        vec3 w = bsdf_sample_cosine(n, uniform(), uniform());
        double z, phi;
        local(n, w, &z, &phi);
        worst_len = fmax(worst_len, fabs(v3_length(w) - 1.0));
        min_z = fmin(min_z, z);
        count[clampi((int)((1.0 - z * z) * BZ), BZ) * BP + phi_bin(phi, BP)] += 1.0;
        double g = z * z / bsdf_pdf_cosine(n, w);
        sum += g;
        sum2 += g * g;
    }
    double x = chi2(count, p, BZ * BP, N);
    printf("cosine hemisphere: chi2 %.1f (critical %.1f)\n", x, test_chi2_critical_1e4(BZ * BP - 1));
    CHECK(x < test_chi2_critical_1e4(BZ * BP - 1));
    CHECK(worst_len < 2e-6 && min_z >= 0.0);
    double mean = sum / N, se = sqrt((sum2 / N - mean * mean) / N);
    CHECK_ABS(mean, 2.0 * M_PI / 3.0, 5.0 * se);
}

static void test_sun_cone(void)
{
    enum { BZ = 10, BP = 16 };
    static double count[BZ * BP], p[BZ * BP];
    vec3 s = v3_normalize(v3(-0.484568f, 0.044021f, -0.873645f));
    float cos_a = cosf(5.0f * (float)M_PI / 180.0f);
    double omega = 2.0 * M_PI * (1.0 - (double)cos_a), worst = 0.0;
    int outside = 0;
    for (int i = 0; i < BZ * BP; i++)
        p[i] = 1.0 / (BZ * BP);
    for (int i = 0; i < N; i++) {
        vec3 w = light_sun_sample(s, cos_a, uniform(), uniform());
        double z, phi;
        local(s, w, &z, &phi);
        count[clampi((int)((1.0 - z) / (1.0 - cos_a) * BZ), BZ) * BP + phi_bin(phi, BP)] += 1.0;
        float pdf = light_sun_pdf(s, cos_a, w);
        outside += pdf <= 0.0f && z < cos_a - 1e-6;
        if (pdf > 0.0f)
            worst = fmax(worst, fabs(1.0 / pdf / omega - 1.0));
    }
    double x = chi2(count, p, BZ * BP, N);
    printf("sun cone: chi2 %.1f (critical %.1f), 1/pdf vs Omega %.2g\n", x,
           test_chi2_critical_1e4(BZ * BP - 1), worst);
    CHECK(x < test_chi2_critical_1e4(BZ * BP - 1));
    CHECK(outside == 0);
    CHECK(worst < 1e-5);
    /* the real sun (0.26786 degrees): every sample inside its disc */
    float cos_sun = cosf(0.26786f * (float)M_PI / 180.0f);
    int miss = 0;
    for (int i = 0; i < 10000; i++)
        miss += light_sun_pdf(s, cos_sun, light_sun_sample(s, cos_sun, uniform(), uniform())) <= 0.0f;
    CHECK(miss == 0);
}

static void test_sky(void)
{
    enum { B = LIGHT_SKY_TEXELS };
    static double count[B], p[B];
    static float4 env[LIGHT_SKY_TEXELS + LIGHT_SKY_H];
    atmo_gpu_scene g;
    memset(&g, 0, sizeof g);
    vec3 up = v3_normalize(v3(0.1f, 0.98f, -0.05f));
    g.camera.local_up = (float4){up.x, up.y, up.z, 6.36e6f};
    g.path.sky = ATMO_PATH_SKY_ATMOSPHERE;
    /* a sky bright in a patch near the zenith, dim elsewhere, black below the horizon */
    for (int j = 0; j < LIGHT_SKY_H; j++)
        for (int i = 0; i < LIGHT_SKY_W; i++) {
            double L = j >= LIGHT_SKY_H / 2 ? 0.0 : (j < 4 && i >= 8 && i < 12) ? 20.0 : 1.0 + j;
            env[j * LIGHT_SKY_W + i].w = (float)(L * light_sky_texel_omega(j));
        }
    light_sky_build(env);
    double c = LIGHT_SKY_TABLE;
    for (int k = 0; k < B; k++)
        p[k] = c * light_sky_texel_p(env, k) +
               (1.0 - c) * light_sky_texel_omega(k / LIGHT_SKY_W) / (4.0 * M_PI);
    double sum = 0.0, sum2 = 0.0, psum = 0.0;
    for (int k = 0; k < B; k++)
        psum += p[k];
    int own = 0, table_draws = 0;
    for (int i = 0; i < N; i++) {
        float u0 = uniform(), u1 = uniform(), u2 = uniform();
        vec3 w = light_sky_sample(&g, env, u0, u1, u2);
        int k = light_sky_texel(up, w);
        count[k] += 1.0;
        double q = 1.0 / light_sky_pdf(&g, env, w);
        sum += q;
        sum2 += q * q;
        if (u0 < c) { /* the texel the CDFs picked must be the texel the direction lies in */
            table_draws++;
            own += light_sky_texel_p(env, k) > 0.0f;
        }
    }
    double x = chi2(count, p, B, N);
    printf("sky table: chi2 %.1f (critical %.1f), probabilities sum to %.7f\n", x,
           test_chi2_critical_1e4(B - 1), psum);
    CHECK(x < test_chi2_critical_1e4(B - 1));
    CHECK_ABS(psum, 1.0, 1e-5);
    CHECK(own == table_draws);
    double mean = sum / N, se = sqrt((sum2 / N - mean * mean) / N);
    CHECK_ABS(mean, 4.0 * M_PI, 5.0 * se);
    /* the uniform test sky, or an empty table: the plain sphere, 1/p = 4 pi exactly */
    g.path.sky = ATMO_PATH_SKY_UNIFORM;
    CHECK_REL(1.0 / light_sky_pdf(&g, env, v3(0.0f, 1.0f, 0.0f)), 4.0 * M_PI, 1e-6);
    g.path.sky = ATMO_PATH_SKY_ATMOSPHERE;
    memset(env, 0, sizeof env);
    light_sky_build(env);
    CHECK_REL(1.0 / light_sky_pdf(&g, env, v3(0.0f, 1.0f, 0.0f)), 4.0 * M_PI, 1e-6);
}

static void test_filter(void)
{
    enum { BR = 20, BP = 8 };
    static double count[BR * BP], p[BR * BP];
    double sigma = 0.5, R = 1.5, tail = 1.0 - exp(-R * R / (2.0 * sigma * sigma));
    double r_max = 0.0;
    for (int i = 0; i < BR * BP; i++)
        p[i] = 1.0 / (BR * BP);
    for (int i = 0; i < N; i++) {
        float dx, dy;
        path_filter_offset((float)sigma, (float)R, uniform(), uniform(), &dx, &dy);
        double r = sqrt((double)dx * dx + (double)dy * dy);
        r_max = fmax(r_max, r);
        double F = (1.0 - exp(-r * r / (2.0 * sigma * sigma))) / tail;
        count[clampi((int)(F * BR), BR) * BP + phi_bin(atan2(dy, dx), BP)] += 1.0;
    }
    double x = chi2(count, p, BR * BP, N);
    printf("pixel filter: chi2 %.1f (critical %.1f), largest radius %.4f px\n", x,
           test_chi2_critical_1e4(BR * BP - 1), r_max);
    CHECK(x < test_chi2_critical_1e4(BR * BP - 1));
    CHECK(r_max <= R * (1.0 + 1e-6));
}

static void test_sobol(void)
{
    int failures = 0;
    for (uint pixel = 0; pixel < 8; pixel++)
        for (int k = 0; k <= 10; k++) {
            int n = 1 << k;
            static float u[1024], v[1024];
            for (int i = 0; i < n; i++)
                path_sobol_2d(7u, pixel * 977u, (uint)i, &u[i], &v[i]);
            for (int j = 0; j <= k; j++) {
                int cols = 1 << j, rows = 1 << (k - j);
                static unsigned char cell[1024];
                memset(cell, 0, (size_t)n);
                for (int i = 0; i < n; i++)
                    cell[(int)(v[i] * rows) * cols + (int)(u[i] * cols)]++;
                for (int c = 0; c < n; c++)
                    failures += cell[c] != 1;
            }
        }
    printf("sobol: %d elementary intervals without exactly one point\n", failures);
    CHECK(failures == 0);
    enum { B = 20, PIXELS = 40000 };
    static double count[B * B], p[B * B];
    for (int i = 0; i < B * B; i++)
        p[i] = 1.0 / (B * B);
    for (uint pixel = 0; pixel < PIXELS; pixel++) {
        float a, b;
        path_sobol_2d(3u, pixel, 0u, &a, &b);
        count[(int)(b * B) * B + (int)(a * B)] += 1.0;
    }
    double x = chi2(count, p, B * B, PIXELS);
    printf("sobol sample 0 over pixels: chi2 %.1f (critical %.1f)\n", x,
           test_chi2_critical_1e4(B * B - 1));
    CHECK(x < test_chi2_critical_1e4(B * B - 1));
}

static atmo_gpu_camera camera(int kind, double pitch, double yaw, double fov_deg, int w, int h)
{
    atmo_gpu_camera c;
    double f[3], r[3], u[3];
    memset(&c, 0, sizeof c);
    atmo_camera_basis(kind == ATMO_CAMERA_PANORAMA ? 0.0 : pitch, yaw, f, r, u);
    c.forward = (float4){(float)f[0], (float)f[1], (float)f[2], 0.0f};
    c.right = (float4){(float)r[0], (float)r[1], (float)r[2], 0.0f};
    c.up = (float4){(float)u[0], (float)u[1], (float)u[2], 0.0f};
    c.kind = kind;
    c.width = w;
    c.height = h;
    double a = fov_deg * M_PI / 180.0;
    c.tan_half_fov = (float)(kind == ATMO_CAMERA_FISHEYE ? sin(a / 4.0) : tan(a / 2.0));
    return c;
}

/* the angle between two vectors, as atan2(|a x b|, a . b) in double (acos of the dot product
 * would turn float rounding of 6e-8 into 3e-4 rad near 0) */
static double angle(vec3 a, vec3 b)
{
    double ax = a.x, ay = a.y, az = a.z, bx = b.x, by = b.y, bz = b.z;
    double cx = ay * bz - az * by, cy = az * bx - ax * bz, cz = ax * by - ay * bx;
    return atan2(sqrt(cx * cx + cy * cy + cz * cz), ax * bx + ay * by + az * bz);
}

/* Blender's equirectangular (u, v) of an atmo direction */
static void blender_uv(vec3 d, double *u, double *v)
{
    double xb = d.x, yb = d.z, zb = d.y;
    *u = 0.5 - atan2(yb, xb) / (2.0 * M_PI);
    *v = 0.5 + asin(fmax(-1.0, fmin(1.0, zb))) / M_PI;
}

static void test_cameras(void)
{
    /* perspective */
    atmo_gpu_camera c = camera(ATMO_CAMERA_PERSPECTIVE, -20.0, 30.0, 45.0, 64, 36);
    vec3 f = v3_from4(c.forward), r = v3_from4(c.right);
    CHECK_ABS(angle(camera_ray(&c, 32.0f, 18.0f), f), 0.0, 2e-6);
    vec3 edge = v3_normalize(v3_add(f, v3_scale(r, c.tan_half_fov * 64.0f / 36.0f)));
    CHECK_ABS(angle(camera_ray(&c, 64.0f, 18.0f), edge), 0.0, 2e-6);
    /* panorama, yaw -90: Blender's environment texture */
    int W = 360, H = 180;
    c = camera(ATMO_CAMERA_PANORAMA, 0.0, -90.0, 45.0, W, H);
    CHECK_ABS(angle(camera_ray(&c, W * 0.5f, H * 0.5f), v3(1.0f, 0.0f, 0.0f)), 0.0, 2e-6);
    CHECK_ABS(angle(camera_ray(&c, W * 0.25f, H * 0.5f), v3(0.0f, 0.0f, 1.0f)), 0.0, 2e-6);
    CHECK_ABS(angle(camera_ray(&c, W * 0.5f, 0.0f), v3(0.0f, 1.0f, 0.0f)), 0.0, 2e-6);
    vec3 sun = v3_normalize(v3(-0.484568f, 0.044021f, -0.873645f));
    double u, v;
    blender_uv(sun, &u, &v);
    vec3 at = camera_ray(&c, (float)(u * W), (float)((1.0 - v) * H));
    printf("panorama: thesis-1 sun at pixel (%.2f, %.2f), off by %.2g rad\n", u * W,
           (1.0 - v) * H, angle(at, sun));
    CHECK_ABS(angle(at, sun), 0.0, 4e-6);
    double worst = 0.0;
    for (int y = 1; y < H; y += 7)
        for (int x = 0; x < W; x += 11) {
            blender_uv(camera_ray(&c, x + 0.5f, y + 0.5f), &u, &v);
            double du = fabs(u * W - (x + 0.5)), dv = fabs((1.0 - v) * H - (y + 0.5));
            du = fmin(du, W - du); /* the seam */
            worst = fmax(worst, fmax(du, dv));
        }
    printf("panorama: pixel -> ray -> Blender (u, v) worst %.2g px\n", worst);
    CHECK(worst < 1e-3);
    /* fisheye, 160 degrees, wide frame */
    double fov = 160.0;
    c = camera(ATMO_CAMERA_FISHEYE, 10.0, 40.0, fov, 96, 48);
    f = v3_from4(c.forward);
    CHECK_ABS(angle(camera_ray(&c, 48.0f, 24.0f), f), 0.0, 2e-6);
    CHECK_ABS(angle(camera_ray(&c, 48.0f, 0.0f), f), fov / 2.0 * M_PI / 180.0, 2e-6);
    CHECK_ABS(angle(camera_ray(&c, 48.0f + 24.0f, 24.0f), f), fov / 2.0 * M_PI / 180.0, 2e-6);
    for (double rho = 0.1; rho < 1.0; rho += 0.2) {
        double want = 2.0 * asin(rho * sin(fov / 4.0 * M_PI / 180.0));
        CHECK_ABS(angle(camera_ray(&c, 48.0f, (float)(24.0 - 24.0 * rho)), f), want, 4e-6);
    }
    vec3 corner = camera_ray(&c, 0.5f, 0.5f);
    CHECK(corner.x == 0.0f && corner.y == 0.0f && corner.z == 0.0f);
}

/* The thin lens: every ray of a pixel, whatever its point on the aperture, passes through the
 * pinhole ray's point on the plane in focus (closed form of the thin lens), starts within the
 * aperture disc in the camera's right/up plane, and the aperture's points fill the disc
 * (their mean radius^2 is R^2 / 2 for a uniform disc, within 5 standard errors). */
static void test_thin_lens(void)
{
    atmo_gpu_scene g;
    memset(&g, 0, sizeof g);
    g.camera = camera(ATMO_CAMERA_PERSPECTIVE, -10.0, 25.0, 45.0, 64, 36);
    g.path.sampler = ATMO_SAMPLER_SOBOL;
    g.path.filter_sigma = 0.5f;
    g.path.filter_radius = 1.5f;
    g.path.aperture_m = 0.05f;
    g.path.focus_m = 7.0f;
    vec3 f = v3_from4(g.camera.forward), r = v3_from4(g.camera.right), u = v3_from4(g.camera.up);
    double worst = 0.0, worst_plane = 0.0, sum = 0.0, sum2 = 0.0;
    int outside = 0, n = 4096;
    for (int i = 0; i < n; i++) {
        rng_stream st = rng_stream_stage(1u, 77u, (uint)i, 0u);
        vec3 o, d = path_camera_sample(&g, 20, 11, 77u, (uint)i, &st, &o);
        /* the pinhole ray of the same sample: same pixel position, aperture 0 */
        g.path.aperture_m = 0.0f;
        rng_stream st0 = rng_stream_stage(1u, 77u, (uint)i, 0u);
        vec3 o0, d0 = path_camera_sample(&g, 20, 11, 77u, (uint)i, &st0, &o0);
        g.path.aperture_m = 0.05f;
        vec3 want = v3_scale(d0, 7.0f / v3_dot(d0, f));
        float t = (7.0f - v3_dot(o, f)) / v3_dot(d, f);
        vec3 got = v3_add(o, v3_scale(d, t));
        worst = fmax(worst, v3_length(v3_sub(got, want)));
        worst_plane = fmax(worst_plane, fabs(v3_dot(o, f)));
        double rr = (double)v3_dot(o, r) * v3_dot(o, r) + (double)v3_dot(o, u) * v3_dot(o, u);
        outside += rr > 0.05 * 0.05 * (1.0 + 1e-5);
        sum += rr;
        sum2 += rr * rr;
    }
    double mean = sum / n, se = sqrt((sum2 / n - mean * mean) / n);
    printf("thin lens: focus points within %.2g m, origins %.2g m off the lens plane, mean r^2 "
           "%.4g (want %.4g)\n",
           worst, worst_plane, mean, 0.05 * 0.05 / 2.0);
    CHECK(worst < 2e-5 && worst_plane < 1e-7 && outside == 0);
    CHECK_ABS(mean, 0.05 * 0.05 / 2.0, 5.0 * se);
}

int main(void)
{
    test_cosine();
    test_sun_cone();
    test_sky();
    test_filter();
    test_sobol();
    test_cameras();
    test_thin_lens();
    return test_finish();
}
