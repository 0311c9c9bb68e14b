/* flare.c — a procedural lens flare in screen space (atmo/flare.h).
 *
 * A real lens scatters and reflects a small part of the light that reaches it from the sun
 * back onto the sensor: glare around the sun (scattering in the glass), ghosts (reflections
 * between the lens surfaces, on the line from the sun's image through the image centre) and a
 * halo. Here each part is a fixed shape on the image plane whose total irradiance is a fixed
 * fraction of the sun's, so the flare is as bright as the light that actually gets through:
 *   - the sun's light is measured from the image itself, P = sum of L(q) omega(q) over the
 *     pixels q within the sun's disc (its radius plus 1.5 pixels, for the pixel filter), with
 *     omega the pixel's solid angle (2 tan(fov/2) / H)^2 cos^3(theta) of a perspective image
 *     plane. Whatever covers the sun in the render (the ground, an object, terrain, a cloud)
 *     has taken its pixels' light away, so it removes the flare in proportion: no separate
 *     visibility test can disagree with the image;
 *   - glare: radiance P g(d) with g(d) proportional to (1 + (d / d0)^2)^-2, d the distance from
 *     the sun's centre on the image plane (d0 = 0.01 of the frame height), carrying
 *     FLARE_GLARE of P, plus six spokes (cos^2(3 phi))^16 on a wider (1 + d/d1)^-3 falloff
 *     carrying FLARE_STAR;
 *   - ghosts: discs with soft edges (smoothstep over their outer 30 %) at s + t (c - s), for
 *     the t, radius and tint of the table below (a tint per wavelength channel, R G B), each
 *     carrying its fraction of P;
 *   - halo: a ring of radius 0.3 H around the sun, Gaussian in radius (width 0.015 H).
 * Each shape is normalised on the image plane (its integral times the solid angle of a pixel
 * next to the sun, below), so the fractions hold wherever the sun is; the part of a shape outside the frame is lost,
 * as in a camera. Perspective cameras only: the caller leaves panoramas and fisheyes alone.
 * The sun's image position is the projection of its direction, x = W/2 (1 + (s.r)/(s.f)
 * / (tan(fov/2) W/H)), y = H/2 (1 - (s.u)/(s.f) / tan(fov/2)); a sun behind the camera
 * (s.f <= 0) makes no flare. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/flare.h"

#define FLARE_GLARE 2e-3
#define FLARE_STAR 4e-4
#define FLARE_HALO 3e-4

typedef struct ghost {
    double t, radius_h, fraction, tint[3];
} ghost;

static const ghost ghosts[] = {
    {0.35, 0.030, 6e-5, {0.6, 0.9, 1.0}}, {0.65, 0.060, 8e-5, {1.0, 0.8, 0.5}},
    {1.20, 0.020, 5e-5, {0.5, 1.0, 0.6}}, {1.45, 0.100, 1.2e-4, {0.7, 0.6, 1.0}},
    {1.85, 0.045, 7e-5, {1.0, 0.6, 0.5}},
};

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static double smooth_edge(double r, double radius)
{
    double x = (radius - r) / (0.3 * radius); /* 0 at the edge, 1 at 70 % of the radius */
    if (x <= 0.0)
        return 0.0;
    if (x >= 1.0)
        return 1.0;
    return x * x * (3.0 - 2.0 * x);
}

/* The unnormalised profiles at (dx, dy) pixels from the sun / from a ghost's centre. */
static double glare(double dx, double dy, double d0)
{
    double q = 1.0 + (dx * dx + dy * dy) / (d0 * d0);
    return 1.0 / (q * q);
}
static double star(double dx, double dy, double d1)
{
    double d = sqrt(dx * dx + dy * dy), phi = atan2(dy, dx), c = cos(3.0 * phi);
    return pow(c * c, 16.0) / pow(1.0 + d / d1, 3.0);
}
static double halo(double dx, double dy, double radius, double width)
{
    double d = sqrt(dx * dx + dy * dy) - radius;
    return exp(-0.5 * d * d / (width * width));
}

/* The profiles' integrals over the unclipped plane, in pixels^2 (d in pixels):
 *   glare: int (1 + d^2/d0^2)^-2 dA = pi d0^2,
 *   star: int (cos^2 3phi)^16 (1 + d/d1)^-3 dA = 2 pi m d1^2 / 2 with m = C(32, 16) / 2^32
 *         the mean of cos^32 over a turn,
 *   halo: int exp(-(d - R)^2 / (2 w^2)) dA = 2 pi R w sqrt(2 pi) (R >> w),
 *   ghost: int smooth_edge(d, r) dA, by the midpoint rule over 4096 rings. */
static double ghost_area(double r)
{
    double sum = 0.0, dr = r / 4096.0;
    for (int i = 0; i < 4096; i++) {
        double x = (i + 0.5) * dr;
        sum += smooth_edge(x, r) * 2.0 * M_PI * x * dr;
    }
    return sum;
}

void atmo_flare_apply(float *rgb, const atmo_flare_camera *c, double strength,
                      atmo_flare_info *info)
{
    atmo_flare_info local;
    atmo_flare_info *out = info ? info : &local;
    memset(out, 0, sizeof *out);
    int W = c->width, H = c->height;
    double f = dot3(c->sun, c->forward);
    if (f <= 0.0 || strength <= 0.0)
        return;
    double th = c->tan_half_fov, pix = 2.0 * th / H; /* image-plane size of a pixel at 1 */
    double sx = 0.5 * W * (1.0 + dot3(c->sun, c->right) / f / (th * W / H));
    double sy = 0.5 * H * (1.0 - dot3(c->sun, c->up) / f / th);
    out->sun_x = sx;
    out->sun_y = sy;
    /* the sun's light as the image holds it */
    double reach = tan(c->sun_radius_rad) / pix + 1.5;
    double P[3] = {0.0, 0.0, 0.0};
    for (int y = (int)floor(sy - reach); y <= (int)ceil(sy + reach); y++)
        for (int x = (int)floor(sx - reach); x <= (int)ceil(sx + reach); x++) {
            if (x < 0 || y < 0 || x >= W || y >= H)
                continue;
            double dx = x + 0.5 - sx, dy = y + 0.5 - sy;
            if (dx * dx + dy * dy > reach * reach)
                continue;
            double u = (2.0 * (x + 0.5) / W - 1.0) * th * W / H, v = (1.0 - 2.0 * (y + 0.5) / H) * th;
            double cos_t = 1.0 / sqrt(1.0 + u * u + v * v);
            double omega = pix * pix * cos_t * cos_t * cos_t;
            for (int k = 0; k < 3; k++)
                P[k] += (double)rgb[3 * ((size_t)y * W + x) + k] * omega;
        }
    memcpy(out->irradiance, P, sizeof P);
    if (P[0] <= 0.0 && P[1] <= 0.0 && P[2] <= 0.0)
        return;
    double cos_s = f, omega_s = pix * pix * cos_s * cos_s * cos_s; /* per pixel near the sun */
    double d0 = 0.01 * H, d1 = 0.05 * H, hr = 0.3 * H, hw = 0.015 * H;
    double mean_cos32 = 601080390.0 / 4294967296.0;
    double n_glare = M_PI * d0 * d0 * omega_s;
    double n_star = M_PI * mean_cos32 * d1 * d1 * omega_s;
    double n_halo = 2.0 * M_PI * hr * hw * sqrt(2.0 * M_PI) * omega_s;
    double cx = 0.5 * W, cy = 0.5 * H;
    int n_ghosts = (int)(sizeof ghosts / sizeof ghosts[0]);
    double n_ghost[8];
    for (int g = 0; g < n_ghosts; g++)
        n_ghost[g] = ghost_area(ghosts[g].radius_h * H) * omega_s;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            double px = x + 0.5, py = y + 0.5, dx = px - sx, dy = py - sy;
            double u = (2.0 * px / W - 1.0) * th * W / H, v = (1.0 - 2.0 * py / H) * th;
            double cos_t = 1.0 / sqrt(1.0 + u * u + v * v);
            double omega = pix * pix * cos_t * cos_t * cos_t;
            double white = FLARE_GLARE * glare(dx, dy, d0) / n_glare +
                           FLARE_STAR * star(dx, dy, d1) / n_star +
                           FLARE_HALO * halo(dx, dy, hr, hw) / n_halo;
            for (int k = 0; k < 3; k++) {
                double L = white;
                for (int g = 0; g < n_ghosts; g++) {
                    double gx = sx + ghosts[g].t * (cx - sx), gy = sy + ghosts[g].t * (cy - sy);
                    double r = sqrt((px - gx) * (px - gx) + (py - gy) * (py - gy));
                    L += ghosts[g].fraction * ghosts[g].tint[k] *
                         smooth_edge(r, ghosts[g].radius_h * H) / n_ghost[g];
                }
                double add = strength * P[k] * L;
                rgb[3 * ((size_t)y * W + x) + k] += (float)add;
                out->added[k] += add * omega;
            }
        }
}
