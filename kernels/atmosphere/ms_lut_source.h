/* ms_lut_source.h — the lookups of the multiple-scattering transfer LUT Psi_ms (ms_lut.h
 * describes the LUT, its source J_ms and the passes that fill it): its parametrisation, the
 * source toward a view direction and the sky's irradiance on the ground. They are the
 * multiple-scattering source of methods march and fast in the plan's composition (media.h:
 * medium_ms_source, medium_ms_ground_irradiance), so they come before the media's composition
 * and the medium integrator, and the passes (ms_lut.h, which march with that integrator) after. */
#ifndef ATMO_MS_LUT_SOURCE_H
#define ATMO_MS_LUT_SOURCE_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "atmosphere/atmosphere.h"
#include "common/geometry.h"
#include "common/phase.h"
#include "atmosphere/sky_method.h"
#include "media/ray.h"
#include "media/media.h"
#include "atmo/gpu_types.h"
#endif

/* mu_s -> x in [0, 1]: x = (1 + sign(mu_s) sqrt|mu_s|) / 2, so texels crowd toward the
 * terminator (mu_s = 0), where Psi rises from ~0 within a few degrees of sun elevation. */
ATMO_FN float ms_lut_unit_from_mu_s(float mu_s)
{
    float y = sqrtf(fminf(fabsf(mu_s), 1.0f));
    y = mu_s < 0.0f ? -y : y;
    return clamp(0.5f + 0.5f * y, 0.0f, 1.0f);
}

/* (r, mu_s) -> (u, v) of the Psi LUT of size width x height. */
ATMO_FN void ms_lut_uv(ATMO_GLOBAL const atmo_gpu_atmosphere *a, float r, float mu_s, int width,
                       int height, float *u, float *v)
{
    float x_h = clamp((r - a->bottom_radius) / (a->top_radius - a->bottom_radius), 0.0f, 1.0f);
    *u = atmosphere_texcoord_from_unit(ms_lut_unit_from_mu_s(mu_s), width);
    *v = atmosphere_texcoord_from_unit(x_h, height);
}

/* Texel (i, j) -> (r, mu_s), the inverse at texel centres. */
ATMO_FN void ms_lut_r_mu_s(ATMO_GLOBAL const atmo_gpu_atmosphere *a, int i, int j, int width,
                           int height, float *r, float *mu_s)
{
    float y = 2.0f * (float)i / (float)(width - 1) - 1.0f, x_h = (float)j / (float)(height - 1);
    *mu_s = atmo_clamp_cos(y * fabsf(y));
    /* a hair above the ground so rays along the horizontal do not graze it */
    *r = a->bottom_radius + fmaxf(x_h * (a->top_radius - a->bottom_radius), 1.0f);
}

ATMO_FN vec3 ms_lut_lookup(ATMO_GLOBAL const atmo_gpu_atmosphere *a, ATMO_GLOBAL const float4 *lut,
                           int width, int height, float r, float mu_s)
{
    float u, v;
    ms_lut_uv(a, r, mu_s, width, height, &u, &v);
    return atmosphere_lut_bilinear(lut, width, height, u, v);
}

ATMO_FN float4 ms_float4(vec3 v, float w)
{
    float4 out;
    out.x = v.x;
    out.y = v.y;
    out.z = v.z;
    out.w = w;
    return out;
}

/* The four texels and weights of a bilinear lookup at (u, v), shared by the planes a source
 * reads at one place (the arithmetic of atmosphere_lut_bilinear). */
typedef struct ms_taps {
    int i00, i10, i01, i11;
    float fx, fy;
} ms_taps;

ATMO_FN ms_taps ms_lut_taps(int width, int height, float u, float v)
{
    ms_taps t;
    float x = clamp(u * (float)width - 0.5f, 0.0f, (float)(width - 1));
    float y = clamp(v * (float)height - 0.5f, 0.0f, (float)(height - 1));
    int x0 = (int)x, y0 = (int)y;
    int x1 = x0 + 1 < width ? x0 + 1 : x0;
    int y1 = y0 + 1 < height ? y0 + 1 : y0;
    t.fx = x - (float)x0;
    t.fy = y - (float)y0;
    t.i00 = y0 * width + x0;
    t.i10 = y0 * width + x1;
    t.i01 = y1 * width + x0;
    t.i11 = y1 * width + x1;
    return t;
}

ATMO_FN vec3 ms_lut_fetch(ATMO_GLOBAL const float4 *plane, const ms_taps *t)
{
    vec3 top = v3_add(v3_scale(v3_from4(plane[t->i00]), 1.0f - t->fx),
                      v3_scale(v3_from4(plane[t->i10]), t->fx));
    vec3 bottom = v3_add(v3_scale(v3_from4(plane[t->i01]), 1.0f - t->fx),
                         v3_scale(v3_from4(plane[t->i11]), t->fx));
    return v3_add(v3_scale(top, 1.0f - t->fy), v3_scale(bottom, t->fy));
}

/* The source J = sigma_R (Psi + v^T D v) + sigma_M (Psi + 3 g_1 b.v + 10 g_2 v^T D v) toward
 * the view direction v (radius r, view cosine mu, sun cosine mu_s, view-sun cosine nu: v is the
 * direction a camera looks along, so light arriving from v scatters forward into it) with Psi
 * in the plane `psi_plane` and the anisotropy in the five consecutive planes from `aniso`
 * (D_uu, D_ss, D_us, b_u, b_s; each width x height); v in the frame (up, sun-ward horizontal,
 * across); g_1, g_2 = s->ms.g1, [2]; each part is kept >= 0. */
ATMO_FN vec3 ms_lut_source_planes(ATMO_GLOBAL const atmo_gpu_scene *s,
                                    ATMO_GLOBAL const float4 *psi_plane,
                                    ATMO_GLOBAL const float4 *aniso, int width, int height,
                                    float r, float mu, float mu_s, float nu, vec3 sigma_r,
                                    vec3 sigma_m)
{
    float u, v;
    int n = width * height;
    ms_lut_uv(&s->atmosphere, r, mu_s, width, height, &u, &v);
    ms_taps taps = ms_lut_taps(width, height, u, v);
    vec3 psi = ms_lut_fetch(psi_plane, &taps);
    vec3 d_uu = ms_lut_fetch(aniso, &taps);
    vec3 d_ss = ms_lut_fetch(aniso + n, &taps);
    vec3 d_us = ms_lut_fetch(aniso + 2 * n, &taps);
    vec3 b_u = ms_lut_fetch(aniso + 3 * n, &taps);
    vec3 b_s = ms_lut_fetch(aniso + 4 * n, &taps);
    float sin_s = atmo_safe_sqrt(1.0f - mu_s * mu_s), across = 1.0f - mu * mu;
    /* the sun-ward component is undefined with the sun at the zenith, where D_ss = D_pp and
     * b_s = 0 */
    float v_s = sin_s > 1e-4f ? (nu - mu * mu_s) / sin_s : 0.0f;
    v_s = clamp(v_s, -atmo_safe_sqrt(across), atmo_safe_sqrt(across));
    float v_p2 = fmaxf(across - v_s * v_s, 0.0f);
    vec3 c2 = v3_add(v3_add(v3_scale(d_uu, mu * mu - v_p2), v3_scale(d_ss, v_s * v_s - v_p2)),
                     v3_scale(d_us, 2.0f * mu * v_s));
    vec3 c1 = v3_add(v3_scale(b_u, mu), v3_scale(b_s, v_s));
    vec3 l_r = v3_add(psi, c2);
    vec3 l_m = v3_add(psi, v3_add(v3_scale(c1, 3.0f * s->ms.g1),
                                  v3_scale(c2, 10.0f * s->ms.g2)));
    vec3 j_r = v3_mul(sigma_r, v3(fmaxf(l_r.x, 0.0f), fmaxf(l_r.y, 0.0f), fmaxf(l_r.z, 0.0f)));
    vec3 j_m = v3_mul(sigma_m, v3(fmaxf(l_m.x, 0.0f), fmaxf(l_m.y, 0.0f), fmaxf(l_m.z, 0.0f)));
    return v3_add(j_r, j_m);
}

/* The multiple-scattering source toward the view direction at a point (radius r, view cosine
 * mu, sun cosine mu_s, view-sun cosine nu) with scattering coefficients sigma_r (Rayleigh) and
 * sigma_m (Mie), from planes 0-5 of the LUT (ms_lut_source_planes). */
ATMO_FN vec3 ms_lut_source(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_GLOBAL const float4 *lut,
                           int width, int height, float r, float mu, float mu_s, float nu,
                           vec3 sigma_r, vec3 sigma_m)
{
    return ms_lut_source_planes(s, lut, lut + width * height, width, height, r, mu, mu_s, nu,
                                  sigma_r, sigma_m);
}

/* The sky irradiance of the ground (all orders, W m^-2 nm^-1) where the sun cosine is mu_s:
 * plane 12 of the LUT at the bottom radius. */
ATMO_FN vec3 ms_lut_sky_irradiance(ATMO_GLOBAL const atmo_gpu_atmosphere *a,
                                   ATMO_GLOBAL const float4 *lut, int width, int height,
                                   float mu_s)
{
    return ms_lut_lookup(a, lut + 12 * width * height, width, height, a->bottom_radius, mu_s);
}

/* The source as the plan's composition calls it (medium_ms_source): at the point q with the
 * media's coefficients m, from the LUT in buffer ms_lut. */
ATMO_FN vec3 ms_lut_ms_source(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                              const medium_point *q, float nu, const media_sample *m, int ground)
{
    return ms_lut_source(s, ms_lut, s->ms.width, s->ms.height, q->r, q->mu, q->mu_s, nu,
                         m->scattering[MEDIA_RAYLEIGH], m->scattering[MEDIA_MIE]);
}

ATMO_FN vec3 ms_lut_ms_ground_irradiance(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                         float mu_s)
{
    return ms_lut_sky_irradiance(&s->atmosphere, ms_lut, s->ms.width, s->ms.height, mu_s);
}

#endif
