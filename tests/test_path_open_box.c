/* test_path_open_box — energy: the path tracer renders thesis view 7's open box lit from above
 * as a double-precision host path tracer of the same configuration does, within their
 * statistical errors.
 * labels: render kernel stat
 *
 * Configuration: thesis-7's camera and objects (the open box of four boxes, no ceiling and no
 * front, and its three small spheres; presets.md), in the uniform test world (path.sky =
 * uniform: sky radiance L_u = (0.05, 0.08, 0.12) in every direction, no air, no ground) under
 * the sun at zenith 40 degrees, azimuth -135 (from the front left and above, so it shines into
 * the box through its open top and front) with the solar irradiance E of the render
 * wavelengths unattenuated; N_b = 3 reflections, Russian roulette from event 2, N_s = 2, sky
 * sampling with MIS; 16 x 12 pixels, 128 samples.
 * Oracle: a host path tracer written here in double (its own ray-box and ray-sphere tests,
 * camera, rejection-sampled truncated Gaussian pixel filter, its own cosine sampling, sun NEE
 * over the disc, the sky by BSDF sampling only, no roulette, one secondary ray): a different
 * estimator of the same expectation. For the whole image and its left and right halves (the
 * red and the green wall) and each channel, the host estimates the region's mean radiance
 * from 150000 paths through uniformly chosen pixels; the GPU's region mean is the mean of its
 * pixels, its standard error from the per-pixel second moments (pixels independent). The
 * difference must be within 4.4 combined standard errors (two-sided p ~ 1e-5 each, 9 checks).
 * The relative differences are printed (the measured agreement). */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/render.h"
#include "atmo/session.h"
#include "testlib.h"
#include "testscene.h"

#define W 16
#define H 12
#define BOUNCES 3

typedef struct { double x, y, z; } d3;
static d3 mk(double x, double y, double z) { d3 r = {x, y, z}; return r; }
static d3 add(d3 a, d3 b) { return mk(a.x + b.x, a.y + b.y, a.z + b.z); }
static d3 sub(d3 a, d3 b) { return mk(a.x - b.x, a.y - b.y, a.z - b.z); }
static d3 scl(d3 a, double s) { return mk(a.x * s, a.y * s, a.z * s); }
static d3 mul(d3 a, d3 b) { return mk(a.x * b.x, a.y * b.y, a.z * b.z); }
static double dot(d3 a, d3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static d3 cross(d3 a, d3 b)
{
    return mk(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
static d3 unit(d3 a) { return scl(a, 1.0 / sqrt(dot(a, a))); }

static uint64_t state = 0x853C49E6748FEA9Bull;
static double rnd(void)
{
    state ^= state >> 12;
    state ^= state << 25;
    state ^= state >> 27;
    return (double)((state * 0x2545F4914F6CDD1Dull) >> 11) * (1.0 / 9007199254740992.0);
}

typedef struct obj {
    int sphere;
    d3 a, b; /* sphere: centre, (radius, 0, 0); box: min, max */
    d3 albedo;
} obj;

static const d3 cam = {26631.5, 1336.5, 10747.5};
static obj objs[7];

static void setup(void)
{
    struct { double min[3], size[3], albedo[3]; } boxes[4] = {
        {{26630, 1336, 10749}, {1, 1, 1}, {0.9, 0.1, 0.1}},
        {{26632, 1336, 10749}, {1, 1, 1}, {0.1, 0.9, 0.1}},
        {{26630, 1335, 10749}, {3, 1, 1}, {0.7, 0.7, 0.7}},
        {{26630, 1336, 10750}, {3, 1, 1}, {0.7, 0.7, 0.7}}};
    struct { double c[3], r, albedo[3]; } spheres[3] = {
        {{26631.33, 1336.12, 10749.66}, 0.12, {38.0 / 255, 25.0 / 255, 17.0 / 255}},
        {{26631.66, 1336.12, 10749.66}, 0.12, {1, 0.5, 0.15}},
        {{26631.5, 1336.12, 10749.33}, 0.12, {1, 1, 1}}};
    for (int i = 0; i < 4; i++) {
        d3 lo = sub(mk(boxes[i].min[0], boxes[i].min[1], boxes[i].min[2]), cam);
        objs[i].sphere = 0;
        objs[i].a = lo;
        objs[i].b = add(lo, mk(boxes[i].size[0], boxes[i].size[1], boxes[i].size[2]));
        objs[i].albedo = mk(boxes[i].albedo[0], boxes[i].albedo[1], boxes[i].albedo[2]);
    }
    for (int i = 0; i < 3; i++) {
        objs[4 + i].sphere = 1;
        objs[4 + i].a = sub(mk(spheres[i].c[0], spheres[i].c[1], spheres[i].c[2]), cam);
        objs[4 + i].b = mk(spheres[i].r, 0, 0);
        objs[4 + i].albedo = mk(spheres[i].albedo[0], spheres[i].albedo[1], spheres[i].albedo[2]);
    }
}

/* nearest hit beyond 1e-9 m: object index, distance, outward normal */
static int trace(d3 o, d3 d, double *t_out, d3 *n_out)
{
    int best = -1;
    double tb = INFINITY;
    for (int i = 0; i < 7; i++) {
        const obj *ob = &objs[i];
        if (ob->sphere) {
            d3 f = sub(o, ob->a);
            double b = dot(f, d), c = dot(f, f) - ob->b.x * ob->b.x, disc = b * b - c;
            if (disc < 0)
                continue;
            double q = sqrt(disc);
            double t = -b - q > 1e-9 ? -b - q : -b + q;
            if (t > 1e-9 && t < tb) {
                tb = t;
                best = i;
                *n_out = unit(sub(add(o, scl(d, t)), ob->a));
            }
        } else {
            double lo[3] = {ob->a.x, ob->a.y, ob->a.z}, hi[3] = {ob->b.x, ob->b.y, ob->b.z};
            double oo[3] = {o.x, o.y, o.z}, dd[3] = {d.x, d.y, d.z};
            double tn = -INFINITY, tf = INFINITY;
            int an = 0, af = 0;
            for (int k = 0; k < 3; k++) {
                double t0 = (lo[k] - oo[k]) / dd[k], t1 = (hi[k] - oo[k]) / dd[k];
                if (t0 > t1) {
                    double tmp = t0;
                    t0 = t1;
                    t1 = tmp;
                }
                if (t0 > tn)
                    tn = t0, an = k;
                if (t1 < tf)
                    tf = t1, af = k;
            }
            if (tn > tf)
                continue;
            double t = tn > 1e-9 ? tn : tf;
            int axis = tn > 1e-9 ? an : af;
            if (t > 1e-9 && t < tb) {
                tb = t;
                best = i;
                double nn[3] = {0, 0, 0};
                nn[axis] = (tn > 1e-9 ? -1.0 : 1.0) * (dd[axis] > 0 ? 1.0 : -1.0);
                *n_out = mk(nn[0], nn[1], nn[2]);
            }
        }
    }
    *t_out = tb;
    return best;
}

static d3 around(d3 n, double x, double y, double z)
{
    d3 helper = fabs(n.x) < 0.5 ? mk(1, 0, 0) : mk(0, 1, 0);
    d3 t = unit(cross(helper, n)), b = cross(n, t);
    return add(add(scl(t, x), scl(b, y)), scl(n, z));
}

static d3 sky_l, sun_e, sun_dir;
static double cos_alpha;

/* one path through pixel position (px, py) */
static d3 radiance(double px, double py)
{
    double th = tan(22.5 * M_PI / 180.0);
    double sx = (2.0 * px / W - 1.0) * th * W / H, sy = (1.0 - 2.0 * py / H) * th;
    d3 o = mk(0, 0, 0), d = unit(mk(sx, sy, 1.0)), beta = mk(1, 1, 1), L = mk(0, 0, 0);
    double t;
    d3 n;
    int k = trace(o, d, &t, &n);
    if (k < 0)
        return sky_l;
    for (int depth = 0;; depth++) {
        d3 p = add(o, scl(d, t));
        if (dot(n, d) > 0)
            n = scl(n, -1.0);
        d3 alb = objs[k].albedo;
        double c = 1.0 - rnd() * (1.0 - cos_alpha), phi = 2.0 * M_PI * rnd();
        d3 w = around(sun_dir, sqrt(1 - c * c) * cos(phi), sqrt(1 - c * c) * sin(phi), c);
        double cs = dot(n, w), ts;
        d3 ns;
        if (cs > 0 && trace(add(p, scl(n, 1e-7)), w, &ts, &ns) < 0)
            L = add(L, mul(beta, scl(mul(alb, sun_e), cs / M_PI)));
        double u1 = rnd(), u2 = 2.0 * M_PI * rnd();
        d3 wi = around(n, sqrt(u1) * cos(u2), sqrt(u1) * sin(u2), sqrt(1.0 - u1));
        beta = mul(beta, alb);
        o = add(p, scl(n, 1e-7));
        d = wi;
        k = trace(o, d, &t, &n);
        if (k < 0)
            return add(L, mul(beta, sky_l));
        if (depth + 2 > BOUNCES) /* the hit would be reflection depth + 2 */
            return L;
    }
}

static void pixel_offset(double *dx, double *dy)
{
    for (;;) { /* Gaussian sigma 0.5 by Box-Muller, rejected beyond radius 1.5 */
        double r = 0.5 * sqrt(-2.0 * log(1.0 - rnd())), a = 2.0 * M_PI * rnd();
        if (r <= 1.5) {
            *dx = r * cos(a);
            *dy = r * sin(a);
            return;
        }
    }
}

int main(void)
{
    test_require_opencl();
    setup();
    atmo_scene s;
    test_scene_preset(&s, "thesis-7");
    test_scene_set(&s, "path.sky=uniform");
    test_scene_set(&s, "path.uniform_sky=0.05,0.08,0.12");
    test_scene_set(&s, "path.ground=false");
    test_scene_set(&s, "sun.zenith_deg=40");
    test_scene_set(&s, "sun.azimuth_deg=-135");
    test_scene_set(&s, "path.bounces=3");
    test_scene_set(&s, "path.rr_bounce=2");
    test_scene_set(&s, "path.secondary=2");
    test_scene_set(&s, "image.width=16");
    test_scene_set(&s, "image.height=12");
    test_scene_set(&s, "image.samples=128");
    atmo_plan p;
    test_plan(&s, &p);
    sun_e = mk(p.gpu.atmosphere.solar_irradiance.x, p.gpu.atmosphere.solar_irradiance.y,
               p.gpu.atmosphere.solar_irradiance.z);
    double sd[3];
    atmo_sun_direction(40.0, -135.0, sd);
    sun_dir = mk(sd[0], sd[1], sd[2]);
    cos_alpha = cos(s.sun.angular_radius_deg * M_PI / 180.0);
    sky_l = mk(0.05, 0.08, 0.12);

    atmo_render_settings rs;
    atmo_render_settings_default(&rs);
    atmo_session *session = NULL;
    atmo_err e;
    atmo_step step = {0};
    atmo_step_status st;
    static float mean[W * H * 3], se[W * H * 3];
    if (atmo_session_open(&session, &p, &rs, &e) || atmo_session_step(session, &step, &st, &e) ||
        atmo_session_read(session, mean, se, NULL, &e)) {
        fprintf(stderr, "render failed: %s\n", e.msg);
        return 1;
    }
    CHECK(atmo_session_get_info(session)->nonfinite == 0);
    atmo_session_close(session);
    atmo_plan_free(&p);

    const char *names[3] = {"image", "left half", "right half"};
    int x0[3] = {0, 0, W / 2}, x1[3] = {W, W / 2, W};
    for (int r = 0; r < 3; r++) {
        double gs[3] = {0, 0, 0}, gv[3] = {0, 0, 0};
        int np = (x1[r] - x0[r]) * H;
        for (int y = 0; y < H; y++)
            for (int x = x0[r]; x < x1[r]; x++)
                for (int c = 0; c < 3; c++) {
                    gs[c] += mean[3 * (y * W + x) + c];
                    gv[c] += (double)se[3 * (y * W + x) + c] * se[3 * (y * W + x) + c];
                }
        double hs[3] = {0, 0, 0}, hq[3] = {0, 0, 0};
        const int n = 150000;
        for (int i = 0; i < n; i++) {
            double px = x0[r] + (x1[r] - x0[r]) * rnd(), py = H * rnd(), dx, dy;
            pixel_offset(&dx, &dy);
            /* the pixel's centre plus the filter offset, as the kernel places a sample */
            d3 l = radiance(floor(px) + 0.5 + dx, floor(py) + 0.5 + dy);
            double v[3] = {l.x, l.y, l.z};
            for (int c = 0; c < 3; c++) {
                hs[c] += v[c];
                hq[c] += v[c] * v[c];
            }
        }
        for (int c = 0; c < 3; c++) {
            double g = gs[c] / np, g_se = sqrt(gv[c]) / np;
            double h = hs[c] / n, h_se = sqrt((hq[c] / n - h * h) / (n - 1));
            double z = (g - h) / sqrt(g_se * g_se + h_se * h_se);
            printf("%-10s channel %d: path_render %.6f +- %.6f, host %.6f +- %.6f, rel diff "
                   "%+.4f, z %+.2f\n",
                   names[r], c, g, g_se, h, h_se, g / h - 1.0, z);
            CHECK(fabs(z) < 4.4);
        }
    }
    return test_finish();
}
