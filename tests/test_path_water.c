/* test_path_water — the sea in the path tracer (kernels/render/bsdf_water.h, path.h's sea
 * vertex; the optics of kernels/terrain/water.h).
 * labels: render kernel stat
 *
 * Oracles:
 *  1. Energy (numerical integration against the closed form). The glint's directional albedo
 *     A(c_v) = integral over the upper hemisphere of water_glint(n, v, s) d omega_s (the kernel's
 *     float function; midpoint rule, 600 x 1200 cells) plus the body's (1 - F(c_v)) max(a_w) must
 *     stay <= 1 for view cosines 1 ... 0.01 (so must F + (1 - F) a_w, the rest of the light's);
 *     at normal incidence every facet sees the view at cos beta and G = 1 to 1e-30, so A(1) is
 *     the slope average of F(cos beta), which differs from F(1) by 0.1 % (sigma^2 = 0.0286): A(1)
 *     within 1 % of F(1).
 *  2. A uniform sky over a flat sea (terrain.land_fraction = 0, the uniform test world: sky
 *     radiance L_u everywhere, no air, the sun's irradiance E unattenuated), seen from 100 m
 *     30 degrees down (fov 10 degrees, 8 x 8, the pixel filter shrunk to sigma 0.1 px within
 *     0.5 px). Closed form per pixel, the view v of the pixel's centre ray at cosine c_v to the
 *     vertical (the hit points' verticals lie within 4e-5 rad of the camera's):
 *         L = F(c_v) L_u + (1 - F(c_v)) a_w (L_u + E <mu_s> / pi) + E <glint(v, s)>,
 *     F from Snell's angles in double (Born and Wolf 1.5.2), <> the average over the sun's disc
 *     (a 16 x 32 quadrature uniform in solid angle) of the Cox-Munk glint with Smith's
 *     masking written here in double. (a) sun off (sun.irradiance_scale = 0): the mirror's and
 *     the body's sky alone; (b) the sun 30 degrees high straight ahead, whose mirror image lies
 *     at the frame's centre. Every pixel within 5 standard errors (the pixel's second moment)
 *     plus 1e-4 relative (float rounding and the filter's curvature over the 0.1 px kernel),
 *     the image mean within 4 standard errors of the mean's; and the Lambertian sea of before,
 *     a_w (L_u + E <mu_s> / pi), must lie more than 10 standard errors away (the test can tell).
 *  3. The glint's place (measured from the image). A column of 9 x 64 pixels over 32 degrees,
 *     from 10 m 45 degrees down, the sun 45 degrees high ahead, black sky, 64 samples: the
 *     radiance-weighted centroid (row, column) of the image must match the closed form's of 2
 *     within 4 of its standard errors (propagated from the pixels') plus 0.02 px, the column
 *     the centre. The lobe is flat at its top (sigma = 0.17 rad), so the centroid, not the
 *     brightest pixel, is what the image can measure. The glint is not centred on the mirror
 *     angle's row: at view angle theta_v it goes as exp(-tan^2 beta / sigma^2) / cos theta_v,
 *     beta ~ delta / 2 for a view delta off the mirror angle, which moves the peak toward the
 *     horizon (delta ~ 2 sigma^2 tan theta_v = 3.3 degrees from these two factors alone; with
 *     F and cos^4 beta the closed form peaks 8.5 degrees up): the closed form's peak and the
 *     image's centroid must lie above the mirror row. The closed form here is the glint plus
 *     the body's sunlight (1 - F) a_w E <mu_s> / pi of 2 (the sky is black). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "terrain/terrain_material.h"
#include "terrain/water.h"
#include "testlib.h"
#include "testscene.h"

static double fresnel_d(double c)
{
    double eta = 1.333, st = sqrt(fmax(1.0 - c * c, 0.0)) / eta, ct = sqrt(1.0 - st * st);
    double rs = (c - eta * ct) / (c + eta * ct), rp = (eta * c - ct) / (eta * c + ct);
    return 0.5 * (rs * rs + rp * rp);
}

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void unit3(double v[3])
{
    double l = sqrt(dot3(v, v));
    for (int k = 0; k < 3; k++)
        v[k] /= l;
}

#define SIGMA2 (0.003 + 0.00512 * 5.0) /* Cox and Munk, wind 5 m/s */

static double lambda_d(double c)
{
    double a = c / sqrt(SIGMA2 * (1.0 - c * c));
    return 0.5 * (erf(a) - 1.0) + exp(-a * a) / (2.0 * a * sqrt(M_PI));
}

/* L / E of the glint for the vertical +Y, view v and sun s (double, Cox-Munk with Smith's G). */
static double glint_d(const double v[3], const double s[3])
{
    double cv = v[1], cs = s[1], h[3] = {v[0] + s[0], v[1] + s[1], v[2] + s[2]};
    if (cv <= 0.0 || cs <= 0.0)
        return 0.0;
    unit3(h);
    double cb = h[1], tan2 = (1.0 - cb * cb) / (cb * cb);
    double p = exp(-tan2 / SIGMA2) / (M_PI * SIGMA2);
    double g = 1.0 / (1.0 + lambda_d(cv) + lambda_d(cs));
    return fresnel_d(dot3(h, s)) * p * g / (4.0 * cv * pow(cb, 4));
}

/* The disc averages of the glint and of mu_s for view v, the sun's centre s, cone cos_alpha. */
static void disc_average(const double v[3], const double s[3], double cos_alpha, double *glint,
                         double *mu)
{
    double e1[3] = {s[1], -s[0], 0.0}, e2[3];
    unit3(e1);
    e2[0] = s[1] * e1[2] - s[2] * e1[1];
    e2[1] = s[2] * e1[0] - s[0] * e1[2];
    e2[2] = s[0] * e1[1] - s[1] * e1[0];
    double sg = 0.0, sm = 0.0;
    int n = 0;
    for (int i = 0; i < 16; i++)
        for (int j = 0; j < 32; j++, n++) {
            double c = 1.0 - (i + 0.5) / 16.0 * (1.0 - cos_alpha), sn = sqrt(1.0 - c * c);
            double phi = 2.0 * M_PI * (j + 0.5) / 32.0, w[3];
            for (int k = 0; k < 3; k++)
                w[k] = c * s[k] + sn * (cos(phi) * e1[k] + sin(phi) * e2[k]);
            sg += glint_d(v, w);
            sm += fmax(w[1], 0.0);
        }
    *glint = sg / n;
    *mu = sm / n;
}

static void energy(void)
{
    static const double cvs[] = {1.0, 0.8, 0.5, 0.3, 0.2, 0.1, 0.05, 0.02, 0.01};
    vec3 aw = terrain_material_albedo(TERRAIN_WATER);
    double a_max = fmax(aw.x, fmax(aw.y, aw.z));
    enum { NT = 600, NP = 1200 };
    for (size_t k = 0; k < sizeof cvs / sizeof cvs[0]; k++) {
        double cv = cvs[k], sum = 0.0;
        vec3 n = {0.0f, 1.0f, 0.0f}, v = {(float)sqrt(1.0 - cv * cv), (float)cv, 0.0f};
        for (int i = 0; i < NT; i++) {
            double th = (i + 0.5) * (0.5 * M_PI / NT), row = 0.0;
            for (int j = 0; j < NP; j++) {
                double ph = (j + 0.5) * (2.0 * M_PI / NP);
                vec3 s = {(float)(sin(th) * cos(ph)), (float)cos(th), (float)(sin(th) * sin(ph))};
                row += water_glint(n, v, s);
            }
            sum += row * sin(th) * (0.5 * M_PI / NT) * (2.0 * M_PI / NP);
        }
        double f = fresnel_d(cv), body = (1.0 - f) * a_max;
        printf("energy: cos theta_v %.2f: glint albedo %.5f (F %.5f), + body %.5f = %.5f; "
               "mirror + body %.5f\n",
               cv, sum, f, body, sum + body, f + body);
        CHECK(sum + body <= 1.0);
        CHECK(f + body <= 1.0);
        if (cv == 1.0)
            CHECK(fabs(sum / f - 1.0) < 0.01);
    }
}

typedef struct view {
    int w, h;
    double fov_deg, pitch_deg;
} view;

/* The unit direction of the centre ray of pixel (x, y) (kernels/common/camera.h, yaw 0). */
static void pixel_dir(const view *c, int x, int y, double d[3])
{
    double p = c->pitch_deg * M_PI / 180.0, t = tan(0.5 * c->fov_deg * M_PI / 180.0);
    double sx = (2.0 * (x + 0.5) / c->w - 1.0) * t * c->w / c->h;
    double sy = (1.0 - 2.0 * (y + 0.5) / c->h) * t;
    double fwd[3] = {0.0, sin(p), cos(p)}, up[3] = {0.0, cos(p), -sin(p)}, right[3] = {1, 0, 0};
    for (int k = 0; k < 3; k++)
        d[k] = fwd[k] + sx * right[k] + sy * up[k];
    unit3(d);
}

/* Render: mean and standard error per pixel; E, the sun's centre and cone from the plan. */
static int render(atmo_scene *s, float *mean, float *se, double E[3], double sun[3],
                  double *cos_alpha)
{
    atmo_plan p;
    test_plan(s, &p);
    E[0] = p.gpu.atmosphere.solar_irradiance.x;
    E[1] = p.gpu.atmosphere.solar_irradiance.y;
    E[2] = p.gpu.atmosphere.solar_irradiance.z;
    sun[0] = p.gpu.sun_direction.x;
    sun[1] = p.gpu.sun_direction.y;
    sun[2] = p.gpu.sun_direction.z;
    *cos_alpha = p.gpu.sun_direction.w;
    int rc = test_render_plan(&p, 0, 0, mean, se, NULL);
    atmo_plan_free(&p);
    return rc;
}

static void sea_scene(atmo_scene *s, const view *c, double height_m, double sun_elev_deg,
                      const char *sky, int samples)
{
    char buf[128];
    test_scene_preset(s, "sky-noon");
    static const char *const keys[] = {
        "terrain.enabled=true", "terrain.land_fraction=0", "render.mode=path", "path.sky=uniform",
        "path.bounces=2", "path.filter_radius_px=0.5", "path.filter_sigma_px=0.1",
        "camera.yaw_deg=0", "sun.azimuth_deg=0", NULL};
    for (int i = 0; keys[i]; i++)
        test_scene_set(s, keys[i]);
    snprintf(buf, sizeof buf, "camera.position_m=0,%g,0", height_m);
    test_scene_set(s, buf);
    snprintf(buf, sizeof buf, "camera.pitch_deg=%g", c->pitch_deg);
    test_scene_set(s, buf);
    snprintf(buf, sizeof buf, "camera.fov_deg=%g", c->fov_deg);
    test_scene_set(s, buf);
    snprintf(buf, sizeof buf, "sun.zenith_deg=%g", 90.0 - sun_elev_deg);
    test_scene_set(s, buf);
    snprintf(buf, sizeof buf, "path.uniform_sky=%s", sky);
    test_scene_set(s, buf);
    snprintf(buf, sizeof buf, "image.width=%d", c->w);
    test_scene_set(s, buf);
    snprintf(buf, sizeof buf, "image.height=%d", c->h);
    test_scene_set(s, buf);
    snprintf(buf, sizeof buf, "image.samples=%d", samples);
    test_scene_set(s, buf);
}

#define UW 8
#define UH 8

static int uniform_sky(int with_sun)
{
    static const double Lu[3] = {0.05, 0.08, 0.12};
    view c = {UW, UH, 10.0, -30.0};
    atmo_scene s;
    sea_scene(&s, &c, 100.0, 30.0, "0.05,0.08,0.12", 64);
    if (!with_sun)
        test_scene_set(&s, "sun.irradiance_scale=0");
    static float mean[UW * UH * 3], se[UW * UH * 3];
    double E[3], sun[3], cos_alpha;
    if (render(&s, mean, se, E, sun, &cos_alpha))
        return 1;
    if (!with_sun)
        E[0] = E[1] = E[2] = 0.0;
    vec3 aw3 = terrain_material_albedo(TERRAIN_WATER);
    double aw[3] = {aw3.x, aw3.y, aw3.z}, worst_z = 0.0;
    static double want[UW * UH * 3], lamb[UW * UH * 3];
    for (int y = 0; y < UH; y++)
        for (int x = 0; x < UW; x++) {
            double d[3], v[3], g, mu;
            pixel_dir(&c, x, y, d);
            for (int k = 0; k < 3; k++)
                v[k] = -d[k];
            double f = fresnel_d(v[1]);
            disc_average(v, sun, cos_alpha, &g, &mu);
            for (int ch = 0; ch < 3; ch++) {
                int i = 3 * (y * UW + x) + ch;
                double body = aw[ch] * (Lu[ch] + E[ch] * mu / M_PI);
                want[i] = f * Lu[ch] + (1.0 - f) * body + E[ch] * g;
                lamb[i] = body;
            }
        }
    for (int ch = 0; ch < 3; ch++) {
        double sum = 0.0, var = 0.0, sw = 0.0, sl = 0.0;
        for (int p = 0; p < UW * UH; p++) {
            int i = 3 * p + ch;
            double z = (mean[i] - want[i]) / fmax(se[i], 1e-30);
            worst_z = fmax(worst_z, fabs(z));
            CHECK(fabs(mean[i] - want[i]) <= 5.0 * se[i] + 1e-4 * want[i]);
            sum += mean[i];
            var += (double)se[i] * se[i];
            sw += want[i];
            sl += lamb[i];
        }
        double n = UW * UH, m = sum / n, m_se = sqrt(var) / n;
        printf("uniform sky%s channel %d: path traced %.6f +- %.6f, closed form %.6f (z %+.2f), "
               "Lambertian sea %.6f (%.0f standard errors away)\n",
               with_sun ? " + sun" : "", ch, m, m_se, sw / n, (m - sw / n) / m_se, sl / n,
               fabs(sl / n - m) / m_se);
        CHECK(fabs(m - sw / n) <= 4.0 * m_se + 1e-4 * sw / n);
        CHECK(fabs(sl / n - m) > 10.0 * m_se);
    }
    printf("uniform sky%s: worst pixel |z| %.2f over %d pixels x 3 channels\n",
           with_sun ? " + sun" : "", worst_z, UW * UH);
    return 0;
}

#define GW 9
#define GH 64

static int glint_place(void)
{
    view c = {GW, GH, 32.0, -45.0};
    atmo_scene s;
    sea_scene(&s, &c, 10.0, 45.0, "0,0,0", 64);
    static float mean[GW * GH * 3], se[GW * GH * 3];
    double E[3], sun[3], cos_alpha;
    if (render(&s, mean, se, E, sun, &cos_alpha))
        return 1;
    /* the centroids (row, column) of the image's and of the closed form's green radiance */
    double sum = 0.0, sy = 0.0, sx = 0.0, msum = 0.0, my = 0.0, mx = 0.0, peak = -1.0;
    int peak_row = 0, mirror_row = 0;
    double mirror_err = INFINITY;
    static double model[GW * GH];
    vec3 aw = terrain_material_albedo(TERRAIN_WATER);
    for (int y = 0; y < GH; y++)
        for (int x = 0; x < GW; x++) {
            double d[3], v[3], g, mu;
            pixel_dir(&c, x, y, d);
            for (int k = 0; k < 3; k++)
                v[k] = -d[k];
            disc_average(v, sun, cos_alpha, &g, &mu);
            double L = mean[3 * (y * GW + x) + 1];
            model[y * GW + x] = E[1] * (g + (1.0 - fresnel_d(v[1])) * aw.y * mu / M_PI);
            sum += L;
            sy += L * y;
            sx += L * x;
            msum += model[y * GW + x];
            my += model[y * GW + x] * y;
            mx += model[y * GW + x] * x;
            if (x == GW / 2 && model[y * GW + x] > peak) {
                peak = model[y * GW + x];
                peak_row = y;
            }
            double err = fabs(asin(v[1]) - asin(sun[1])); /* depression - the sun's elevation */
            if (x == GW / 2 && err < mirror_err) {
                mirror_err = err;
                mirror_row = y;
            }
        }
    double cy = sy / sum, cx = sx / sum, var_y = 0.0, var_x = 0.0;
    for (int y = 0; y < GH; y++) /* the centroids' standard errors, pixels independent */
        for (int x = 0; x < GW; x++) {
            double e = se[3 * (y * GW + x) + 1] / sum;
            var_y += (y - cy) * (y - cy) * e * e;
            var_x += (x - cx) * (x - cx) * e * e;
        }
    printf("glint: image centroid row %.3f +- %.3f, column %.3f +- %.3f; closed form row %.3f "
           "column %.3f; closed form's peak row %d, mirror angle row %d\n",
           cy, sqrt(var_y), cx, sqrt(var_x), my / msum, mx / msum, peak_row, mirror_row);
    CHECK(fabs(cy - my / msum) <= 4.0 * sqrt(var_y) + 0.02);
    CHECK(fabs(cx - mx / msum) <= 4.0 * sqrt(var_x) + 0.02);
    CHECK(fabs(mx / msum - 0.5 * (GW - 1)) < 1e-6);
    CHECK(peak_row < mirror_row);
    CHECK(cy < mirror_row);
    return 0;
}

int main(void)
{
    energy();
    test_require_opencl();
    test_fresh_cache_dir();
    if (uniform_sky(0) || uniform_sky(1) || glint_place())
        return 1;
    return test_finish();
}
