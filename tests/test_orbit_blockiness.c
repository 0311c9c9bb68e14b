/* test_orbit_blockiness — the planet seen from orbit carries no pattern of a square grid laid
 * along the world's axes (blocks, tiles or straight cuts from a lattice, a heightmap's texels or
 * a brick grid) in the image as rendered: the blockiness statistic of issue #28 for `space`.
 * labels: render slow
 *
 * View: the `space` preset (the terrain from 2000 km, land and sea, no clouds) at 1280 x 720, 2
 * samples per pixel, seeds 1 and 2, turned to camera.yaw_deg = 45: the preset looks along the
 * world's z axis, which lays the image's pixel grid along the world's axes on the ground, and
 * the pixels' own structure (their noise through the bilinear resampling below) then reads as
 * a grid along the world's axes (measured at yaw 0: the noise alone, seed 1 minus seed 2, at
 * +1.2 standard deviations of the spectral statistic and +3.6 of a gradient-orientation one).
 * Every grid the terrain's pipeline has lies along the world's x and z axes (the value noise's
 * first octave and the coverage's, kernels/terrain/noise.h; a heightmap's texels, terrain.h).
 *
 * Statistic: the spectrum of the image resampled on the ground. The image's luminance (the
 * channels' mean) is sampled bilinearly at the points of the ground sphere (radius R; the
 * terrain's height left out: 4 km against 2700 km to the camera) on N x N = 128 x 128 square
 * grids of spacing DELTA_M = 3 km in the planar coordinates (u, v) of terrain.h, 2 x 2 grids
 * side by side around the point the image's centre sees, each turned by theta about its
 * centre, windowed by a radial Hann window (round, so the window prefers no direction) and
 * Fourier transformed. In each shell of radius r = R1..R2 = 12..40 cycles per grid (wave
 * lengths 32 km, about the first octave's cell of 33 km, down to 9.6 km, 3.7 pixels at the
 * grid's centre), the power of the cells within one cell of the grid's two axes is divided by
 * what those cells would hold at the mean power of the shell's cells 3 or more cells away from
 * the axes; Q(theta) is that ratio averaged over the shells and the 4 grids. Edges along the
 * grid's axes (blocks: a piecewise constant field on square cells, whose spectrum is a cross)
 * give Q >> 1; a field without a preferred direction gives Q near 1. theta = 0 puts the grids'
 * axes on the world's; the turns theta_i = 0, 5, .. 85 degrees at least 15 degrees (modulo 90)
 * from the turn tested are the null, their spread what Q does with no grid there (the field's
 * own structure, its noise, the foreshortening that blurs along the view's ground direction):
 *     z(theta_k) = (Q(theta_k) - mean Q(null)) / sd Q(null).
 * Oracles (Z_MAX = 4):
 *   - the render: z(0) < Z_MAX at both seeds;
 *   - power against the failure the issue saw (grid-aligned patches from orbit): the same view
 *     with terrain.warp = 0, whose first octave's square lattice shows in the snow and grass
 *     lines along the world's axes (tests/test_terrain_isotropy.c), gives z(0) > Z_MAX;
 *   - power against blocks: the render plus a (b_ij - 1/2) times its mean luminance, b_ij a
 *     hash in [0, 1) of the cell floor((u, v) / 33 km) of each pixel's ground point (averaged
 *     over 4 x 4 points in the pixel, as the camera's jitter does), gives z(0) > Z_MAX at
 *     a = BLOCK_CONTRAST = 2 (blocks as bright as the white patches and teal lakes the issue
 *     saw; at a = 1 z is 3.95, at 0.5 0.4: this view's coastlines and relief carry far more
 *     power in the band than faint blocks do);
 *   - alignment, not presence: the same blocks on cells turned by 30 degrees give z(30) >
 *     Z_MAX and z(0) < Z_MAX;
 *   - the noise alone (seed 1 minus seed 2, plus the mean) gives |z(0)| < Z_MAX.
 * Measured: z(0) -0.89 and -0.18 (seeds 1 and 2); warp 0 +8.62; blocks +7.42; turned blocks
 * z(30) +13.95, z(0) -0.88; noise -0.62. Other views: thesis-4 and thesis-5 see the cloud
 * layer, whose noise lattices are turned off every world axis (kernels/clouds/cloud_noise.h), so
 * no grid of theirs lies along the axes this statistic tests; their footprint filter is tested
 * against the view at twice the size (tests/test_clouds_lod.c). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/render.h"
#include "testlib.h"
#include "testscene.h"

#define IMG_W 1280
#define IMG_H 720
#define SAMPLES 2
#define N 128
#define DELTA_M 3000.0
#define R1 12
#define R2 40
#define TURNS 18 /* theta = 0, 5, .. 85 degrees */
#define NULL_FROM_DEG 15.0 /* the null: the turns at least this far from the one tested */
#define TURNED_DEG 30
#define REGIONS 2
#define Z_MAX 4.0
#define CELL_M 33333.0
#define BLOCK_CONTRAST 2.0
#define BLOCK_SUB 4

typedef struct view {
    double cam[3];  /* the camera's position from the planet's centre, m */
    double fwd[3], right[3], up[3];
    double tan_half_fov, radius;
} view;

static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static view view_of(const atmo_scene *s, const atmo_plan *p)
{
    view v;
    v.radius = p->gpu.atmosphere.bottom_radius;
    v.cam[0] = s->camera.position_m[0];
    v.cam[1] = s->camera.position_m[1] + v.radius;
    v.cam[2] = s->camera.position_m[2];
    atmo_camera_basis(s->camera.pitch_deg, s->camera.yaw_deg, v.fwd, v.right, v.up);
    v.tan_half_fov = tan(0.5 * s->camera.fov_deg * M_PI / 180.0);
    return v;
}

/* The planar coordinates (u, v) of the ground point the ray through image point (x, y) meets
 * (terrain.h: u = R x / r, v = R z / r from the planet's centre; on the sphere r = R); 0 when
 * the ray misses the sphere. */
static int pixel_ground(const view *v, double x, double y, double *u, double *w)
{
    double sx = (2.0 * x / IMG_W - 1.0) * IMG_W / IMG_H * v->tan_half_fov;
    double sy = (1.0 - 2.0 * y / IMG_H) * v->tan_half_fov;
    double d[3];
    for (int k = 0; k < 3; k++)
        d[k] = v->fwd[k] + sx * v->right[k] + sy * v->up[k];
    double n = sqrt(dot3(d, d));
    for (int k = 0; k < 3; k++)
        d[k] /= n;
    double b = dot3(v->cam, d), c = dot3(v->cam, v->cam) - v->radius * v->radius;
    double disc = b * b - c;
    if (disc < 0.0)
        return 0;
    double t = -b - sqrt(disc);
    *u = v->cam[0] + t * d[0];
    *w = v->cam[2] + t * d[2];
    return 1;
}

/* The image point (x, y) of the ground point at planar coordinates (u, w); 0 when it faces
 * away from the camera or lies outside the image. */
static int ground_pixel(const view *v, double u, double w, double *x, double *y)
{
    double g[3] = {u, sqrt(v->radius * v->radius - u * u - w * w), w};
    double d[3] = {g[0] - v->cam[0], g[1] - v->cam[1], g[2] - v->cam[2]};
    if (dot3(d, g) >= 0.0)
        return 0;
    double f = dot3(d, v->fwd);
    if (f <= 0.0)
        return 0;
    double sx = dot3(d, v->right) / (f * v->tan_half_fov * IMG_W / IMG_H);
    double sy = dot3(d, v->up) / (f * v->tan_half_fov);
    *x = 0.5 * IMG_W * (1.0 + sx);
    *y = 0.5 * IMG_H * (1.0 - sy);
    return *x >= 1.0 && *y >= 1.0 && *x <= IMG_W - 1.0 && *y <= IMG_H - 1.0;
}

/* Bilinear lookup of a W x H image (pixel centres at index + 1/2). */
static double bilinear(const double *img, double x, double y)
{
    double fx = x - 0.5, fy = y - 0.5;
    int i = (int)floor(fx), j = (int)floor(fy);
    double a = fx - i, b = fy - j;
    const double *r0 = img + (size_t)j * IMG_W, *r1 = r0 + IMG_W;
    return (1 - b) * ((1 - a) * r0[i] + a * r0[i + 1]) + b * ((1 - a) * r1[i] + a * r1[i + 1]);
}

/* Q(theta) of the image (see the top of the file); exits when the grid leaves the image. */
static double axis_ratio(const view *v, const double *img, double u0, double w0, double theta)
{
    static double re[N][N], tre[N][N], tim[N][N];
    double c = cos(theta), s = sin(theta), sum = 0.0, wsum = 0.0;
    static double win[N][N];
    for (int b = 0; b < N; b++)
        for (int a = 0; a < N; a++) {
            double p = (a - N / 2 + 0.5), q = (b - N / 2 + 0.5), rho = hypot(p, q) / (N / 2);
            double u = u0 + DELTA_M * (c * p - s * q), w = w0 + DELTA_M * (s * p + c * q);
            double x, y;
            if (!ground_pixel(v, u, w, &x, &y)) {
                fprintf(stderr, "the resampling grid leaves the image at (%d, %d)\n", a, b);
                exit(1);
            }
            win[b][a] = rho < 1.0 ? 0.5 * (1.0 + cos(M_PI * rho)) : 0.0;
            re[b][a] = bilinear(img, x, y);
            sum += win[b][a] * re[b][a], wsum += win[b][a];
        }
    for (int b = 0; b < N; b++)
        for (int a = 0; a < N; a++)
            re[b][a] = win[b][a] * (re[b][a] - sum / wsum);
    /* the 2-D DFT, rows then columns (direct sums: N^3), e^{-2 pi i m / N} tabulated */
    static double cs[N], sn[N];
    for (int m = 0; m < N; m++)
        cs[m] = cos(2.0 * M_PI * m / N), sn[m] = -sin(2.0 * M_PI * m / N);
    for (int b = 0; b < N; b++)
        for (int k = 0; k < N; k++) {
            double sr = 0.0, si = 0.0;
            for (int a = 0; a < N; a++) {
                int m = (k * a) % N;
                sr += re[b][a] * cs[m], si += re[b][a] * sn[m];
            }
            tre[b][k] = sr, tim[b][k] = si;
        }
    for (int k = 0; k < N; k++)
        for (int l = 0; l < N; l++) {
            double sr = 0.0, si = 0.0;
            for (int b = 0; b < N; b++) {
                int m = (l * b) % N;
                sr += tre[b][k] * cs[m] - tim[b][k] * sn[m];
                si += tre[b][k] * sn[m] + tim[b][k] * cs[m];
            }
            re[l][k] = sr * sr + si * si; /* the power at (k, l) */
        }
    /* per shell: the axis cells' power against the shell's mean away from the axes */
    double axis = 0.0;
    int shells = 0;
    for (int r = R1; r <= R2; r++) {
        double off = 0.0, on = 0.0;
        int n_off = 0, n_on = 0;
        for (int l = -R2 - 1; l <= R2 + 1; l++)
            for (int k = -R2 - 1; k <= R2 + 1; k++) {
                if ((int)lround(hypot(k, l)) != r)
                    continue;
                double pw = re[(l + N) % N][(k + N) % N];
                int m = abs(k) < abs(l) ? abs(k) : abs(l);
                if (m <= 1)
                    on += pw, n_on++;
                else if (m >= 3)
                    off += pw, n_off++;
            }
        axis += on / (n_on * off / n_off);
        shells++;
    }
    return axis / shells;
}

/* Q(theta) averaged over REGIONS x REGIONS grids side by side around (u0, w0). */
static double axis_ratio_mean(const view *v, const double *img, double u0, double w0,
                              double theta)
{
    double q = 0.0, side = N * DELTA_M;
    for (int j = 0; j < REGIONS; j++)
        for (int i = 0; i < REGIONS; i++)
            q += axis_ratio(v, img, u0 + side * (i - 0.5 * (REGIONS - 1)),
                            w0 + side * (j - 0.5 * (REGIONS - 1)), theta);
    return q / (REGIONS * REGIONS);
}

/* Q at the TURNS turns theta_i = i 90 / TURNS degrees. */
static void axis_ratios(const view *v, const double *img, double u0, double w0, double *q)
{
    for (int i = 0; i < TURNS; i++)
        q[i] = axis_ratio_mean(v, img, u0, w0, i * (0.5 * M_PI / TURNS));
}

/* z of the grid turned by theta_k against the turns at least NULL_FROM_DEG from it (modulo 90
 * degrees: the same grid), see the top of the file. */
static double axis_z(const double *q, int k)
{
    double m = 0.0, sd = 0.0, lo = INFINITY, hi = -INFINITY;
    int n = 0, use[TURNS];
    for (int i = 0; i < TURNS; i++) {
        int apart = abs(i - k) < TURNS - abs(i - k) ? abs(i - k) : TURNS - abs(i - k);
        use[i] = apart * 90.0 / TURNS >= NULL_FROM_DEG;
        if (use[i])
            m += q[i], n++, lo = fmin(lo, q[i]), hi = fmax(hi, q[i]);
    }
    m /= n;
    for (int i = 0; i < TURNS; i++)
        if (use[i])
            sd += (q[i] - m) * (q[i] - m);
    sd = sqrt(sd / (n - 1));
    double z = (q[k] - m) / sd;
    printf("    Q(%.0f deg) %.3f; %d turns apart: mean %.3f, sd %.3f, range %.3f..%.3f: z %.2f\n",
           k * 90.0 / TURNS, q[k], n, m, sd, lo, hi, z);
    return z;
}

static float *render_space(const atmo_scene *s, int seed, const char *assignment)
{
    atmo_scene t = *s;
    t.image.seed = seed;
    if (assignment)
        test_scene_set(&t, assignment);
    atmo_plan p;
    test_plan(&t, &p);
    p.cache_luts = 2;
    atmo_render_result r;
    test_render_whole(&p, NULL, &r);
    float *rgb = r.rgb;
    r.rgb = NULL;
    atmo_render_result_free(&r);
    atmo_plan_free(&p);
    return rgb;
}

static unsigned hash2(int i, int j)
{
    unsigned h = (unsigned)i * 0x8da6b343u ^ (unsigned)j * 0xd8163841u;
    h ^= h >> 15, h *= 0x2c1b3c6du, h ^= h >> 12, h *= 0x297a2d39u, h ^= h >> 15;
    return h;
}

/* img times (1 + a (b - 1/2)), b the hash of the CELL_M cell, on axes turned by turn, of the
 * ground point each pixel centre sees. */
static void add_blocks(const view *v, const double *img, double a, double turn, double *out)
{
    double c = cos(turn), s = sin(turn), mean = 0.0;
    for (int i = 0; i < IMG_W * IMG_H; i++)
        mean += img[i] / (IMG_W * IMG_H);
    for (int y = 0; y < IMG_H; y++)
        for (int x = 0; x < IMG_W; x++) {
            double f = 0.0; /* the factor's mean over the pixel, BLOCK_SUB^2 points */
            for (int j = 0; j < BLOCK_SUB; j++)
                for (int i = 0; i < BLOCK_SUB; i++) {
                    double u, w, b = 0.5;
                    if (pixel_ground(v, x + (i + 0.5) / BLOCK_SUB, y + (j + 0.5) / BLOCK_SUB, &u,
                                     &w)) {
                        double p = c * u + s * w, q = -s * u + c * w;
                        b = (hash2((int)floor(p / CELL_M), (int)floor(q / CELL_M)) >> 8) /
                            16777216.0;
                    }
                    f += a * (b - 0.5) / (BLOCK_SUB * BLOCK_SUB);
                }
            out[y * IMG_W + x] = img[y * IMG_W + x] + mean * f;
        }
}

int main(void)
{
    test_require_opencl();
    atmo_scene s;
    test_scene_preset(&s, "space");
    test_scene_image(&s, IMG_W, IMG_H, SAMPLES, 1);
    test_scene_set(&s, "camera.yaw_deg=45");
    atmo_plan p;
    test_plan(&s, &p);
    view v = view_of(&s, &p);
    atmo_plan_free(&p);
    double u0, w0;
    if (!pixel_ground(&v, 0.5 * IMG_W, 0.5 * IMG_H, &u0, &w0)) {
        fprintf(stderr, "the image's centre misses the planet\n");
        return 1;
    }
    printf("ground grid %d x %d at %.0f m, centred at (u, v) = (%.0f, %.0f) km\n", N, N, DELTA_M,
           u0 / 1e3, w0 / 1e3);

    const int n = IMG_W * IMG_H;
    double *img[2], *work = malloc(sizeof(double) * n);
    for (int k = 0; k < 2; k++) {
        float *rgb = render_space(&s, k + 1, NULL);
        img[k] = malloc(sizeof(double) * n);
        for (int i = 0; i < n; i++)
            img[k][i] = ((double)rgb[3 * i] + rgb[3 * i + 1] + rgb[3 * i + 2]) / 3.0;
        free(rgb);
    }

    double q[TURNS];
    for (int k = 0; k < 2; k++) {
        printf("space, seed %d:\n", k + 1);
        axis_ratios(&v, img[k], u0, w0, q);
        CHECK(axis_z(q, 0) < Z_MAX);
    }

    printf("control, blocks of %.0f km along the world's axes, contrast %.0f %% of the mean:\n",
           CELL_M / 1e3, 100.0 * BLOCK_CONTRAST);
    add_blocks(&v, img[0], BLOCK_CONTRAST, 0.0, work);
    axis_ratios(&v, work, u0, w0, q);
    CHECK(axis_z(q, 0) > Z_MAX);

    printf("control, the same blocks turned by %d degrees (their axes, then the world's):\n",
           TURNED_DEG);
    add_blocks(&v, img[0], BLOCK_CONTRAST, TURNED_DEG * M_PI / 180.0, work);
    axis_ratios(&v, work, u0, w0, q);
    CHECK(axis_z(q, TURNED_DEG * TURNS / 90) > Z_MAX);
    CHECK(axis_z(q, 0) < Z_MAX);

    printf("control, the noise alone (seed 1 - seed 2):\n");
    double mean = 0.0;
    for (int i = 0; i < n; i++)
        mean += img[0][i] / n;
    for (int i = 0; i < n; i++)
        work[i] = mean + img[0][i] - img[1][i];
    axis_ratios(&v, work, u0, w0, q);
    CHECK(fabs(axis_z(q, 0)) < Z_MAX);

    printf("control, the field without its domain warp (terrain.warp=0):\n");
    float *rgb = render_space(&s, 1, "terrain.warp=0");
    for (int i = 0; i < n; i++)
        work[i] = ((double)rgb[3 * i] + rgb[3 * i + 1] + rgb[3 * i + 2]) / 3.0;
    free(rgb);
    axis_ratios(&v, work, u0, w0, q);
    CHECK(axis_z(q, 0) > Z_MAX);

    free(img[0]), free(img[1]), free(work);
    return test_finish();
}
