/* tonemap.h — tone mapping operators and display transfer curves (host C and OpenCL C).
 *
 * The display pipeline of one pixel (atmo_post_pixel in host/image/post.c, and any kernel that
 * previews an image) is
 *     linear value x  ->  x / white balance  ->  x * exposure  ->  tone map  ->  clamp [0, 1]
 *                     ->  transfer curve (sRGB or gamma 2.2)  ->  display value in [0, 1].
 *
 * Per channel, not per luminance. The thesis ("Realistic Rendering of Atmospheric Phenomena",
 * see ../shared/reference/presets.md) applied its operators to the luminance Y and scaled the
 * colour by the ratio; atmo applies each operator to R, G and B separately, as most real-time
 * renderers and film pipelines do: bright skies then desaturate towards white instead of
 * leaving [0, 1] in one channel, and no luminance weights are needed for what are, in
 * radiance mode, three spectral samples rather than sRGB primaries.
 *
 * Operators (x >= 0 is the exposed linear value; each returns a linear display value, and the
 * caller clamps to [0, 1] before the transfer curve):
 *   none            x (clamped by the caller)
 *   exposure        1 - exp(-x)                       (the thesis default; E is the exposure)
 *   reinhard        x / (1 + x)                       (Reinhard et al. 2002, eq. 3)
 *   reinhard-white  x (1 + x / w^2) / (1 + x)         (Reinhard et al. 2002, eq. 4; w maps to 1)
 *   aces            x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14)
 *                                                     (K. Narkowicz 2015, fit of the ACES RRT+ODT)
 *   unreal3         (1.019 x / (x + 0.155))^2.2       (Unreal Engine 3 filmic curve; the curve
 *                   itself is display-encoded with gamma 2.2 built in, so this returns its linear
 *                   equivalent: with the gamma 2.2 transfer the PNG holds the original curve)
 *   uchimura        Uchimura 2017 ("HDR theory and practice", Gran Turismo Sport): a power-law
 *                   toe m (x/m)^c, a linear part m + a (x - m) and an exponential shoulder
 *                   P - (P - S1) exp(-a P / (P - S1) (x - S0)), blended by smoothstep(0, m, x)
 *                   and step(S0, x), with l0 = (P - m) l / a, S0 = m + l0, S1 = m + a l0;
 *                   constants of the thesis: P = 1, a = 1, m = 0.22, l = 0.4, c = 1.33, b = 0
 *   lottes          x^a / (x^(a d) b' + c') (T. Lottes 2016, "Advanced techniques and
 *                   optimization of HDR color pipelines"), with b', c' chosen so that midIn
 *                   maps to midOut and hdrMax maps to 1; a = 1.6, d = 0.977, midIn = 0.18,
 *                   midOut = 0.267. hdrMax is the post white point (post.white_point, the same
 *                   "exposed value that becomes white" as for reinhard-white); the thesis tied it
 *                   to its exposure E instead. The curve needs hdrMax^a midOut > midIn^a, i.e. a white
 *                   point above 0.41; below that it is not monotonic (and may be NaN, which
 *                   tonemap_apply maps to 0).
 *
 * Transfer curves (display value from linear value v in [0, 1]):
 *   sRGB            12.92 v for v <= 0.0031308, else 1.055 v^(1/2.4) - 0.055  (IEC 61966-2-1)
 *   gamma 2.2       v^(1/2.2)
 *
 * All functions take and return float; the values are dimensionless (exposed radiance). */
#ifndef ATMO_TONEMAP_H
#define ATMO_TONEMAP_H
#include "common/compat.h"

#ifndef __OPENCL_VERSION__
#include "atmo/gpu_enums.h"
#endif

ATMO_FN float tonemap_exposure(float x) { return -expm1f(-x); }

ATMO_FN float tonemap_reinhard(float x) { return x / (1.0f + x); }

ATMO_FN float tonemap_reinhard_white(float x, float white)
{
    return x * (1.0f + x / (white * white)) / (1.0f + x);
}

ATMO_FN float tonemap_aces(float x)
{
    return x * (2.51f * x + 0.03f) / (x * (2.43f * x + 0.59f) + 0.14f);
}

ATMO_FN float tonemap_unreal3(float x)
{
    /* Past x ~ 8.2 the curve exceeds 1 (its asymptote is 1.019): clamp before linearising. */
    float encoded = fminf(1.019f * x / (x + 0.155f), 1.0f);
    return powf(encoded, 2.2f);
}

ATMO_FN float tonemap_smoothstep(float e0, float e1, float x)
{
    float t = clamp((x - e0) / (e1 - e0), 0.0f, 1.0f);
    return t * t * (3.0f - 2.0f * t);
}

ATMO_FN float tonemap_uchimura(float x)
{
    const float p = 1.0f;   /* maximum display value */
    const float a = 1.0f;   /* contrast (slope of the linear part) */
    const float m = 0.22f;  /* start of the linear part */
    const float l = 0.4f;   /* length of the linear part */
    const float c = 1.33f;  /* toe exponent ("black tightness") */
    const float b = 0.0f;   /* pedestal */
    float l0 = (p - m) * l / a;
    float s0 = m + l0;
    float s1 = m + a * l0;
    float shoulder_rate = a * p / (p - s1);
    float w0 = 1.0f - tonemap_smoothstep(0.0f, m, x);
    float w2 = x >= s0 ? 1.0f : 0.0f;
    float w1 = 1.0f - w0 - w2;
    float toe = m * powf(x / m, c) + b;
    float linear = m + a * (x - m);
    float shoulder = p - (p - s1) * expf(-shoulder_rate * (x - s0));
    return toe * w0 + linear * w1 + shoulder * w2;
}

ATMO_FN float tonemap_lottes(float x, float hdr_max)
{
    const float a = 1.6f;       /* contrast */
    const float d = 0.977f;     /* shoulder */
    const float mid_in = 0.18f;
    const float mid_out = 0.267f;
    float mid_a = powf(mid_in, a), mid_ad = powf(mid_in, a * d);
    float max_a = powf(hdr_max, a), max_ad = powf(hdr_max, a * d);
    float denom = (max_ad - mid_ad) * mid_out;
    float b = (max_a * mid_out - mid_a) / denom;
    float c = (max_ad * mid_a - max_a * mid_ad * mid_out) / denom;
    return powf(x, a) / (powf(x, a * d) * b + c);
}

/* The operator `op` (ATMO_TONEMAP_*) on one exposed linear value x, clamped to [0, 1].
 * Negative and NaN inputs give 0 (fmaxf returns the number when one argument is NaN). */
ATMO_FN float tonemap_apply(int op, float x, float white_point)
{
    float y;
    x = fmaxf(x, 0.0f);
    switch (op) {
    case ATMO_TONEMAP_EXPOSURE: y = tonemap_exposure(x); break;
    case ATMO_TONEMAP_REINHARD: y = tonemap_reinhard(x); break;
    case ATMO_TONEMAP_REINHARD_WHITE: y = tonemap_reinhard_white(x, white_point); break;
    case ATMO_TONEMAP_ACES: y = tonemap_aces(x); break;
    case ATMO_TONEMAP_UNREAL3: y = tonemap_unreal3(x); break;
    case ATMO_TONEMAP_UCHIMURA: y = tonemap_uchimura(x); break;
    case ATMO_TONEMAP_LOTTES: y = tonemap_lottes(x, white_point); break;
    default: y = x; break;
    }
    /* Written so that a NaN (Lottes with an unusable white point) also becomes 0. */
    return y > 0.0f ? fminf(y, 1.0f) : 0.0f;
}

ATMO_FN float transfer_srgb_encode(float v)
{
    return v <= 0.0031308f ? 12.92f * v : 1.055f * powf(v, 1.0f / 2.4f) - 0.055f;
}

ATMO_FN float transfer_srgb_decode(float e)
{
    return e <= 0.04045f ? e / 12.92f : powf((e + 0.055f) / 1.055f, 2.4f);
}

ATMO_FN float transfer_gamma22_encode(float v) { return powf(v, 1.0f / 2.2f); }

ATMO_FN float transfer_gamma22_decode(float e) { return powf(e, 2.2f); }

/* The transfer curve `transfer` (ATMO_TRANSFER_*) on a linear display value in [0, 1]. */
ATMO_FN float transfer_encode(int transfer, float v)
{
    return transfer == ATMO_TRANSFER_GAMMA22 ? transfer_gamma22_encode(v) : transfer_srgb_encode(v);
}

#endif
