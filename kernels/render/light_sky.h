/* light_sky.h — sampling the sky at a surface point from the atmosphere's radiance, for
 * next-event estimation combined with the BSDF's sampling by multiple importance sampling.
 *
 * The sky's radiance table (buffer sky_env, LIGHT_SKY_W x LIGHT_SKY_H texels over the sphere,
 * rows of equal zenith angle theta from the camera's local up, columns of equal azimuth phi
 * around it in the frame (e1, e2) below): the pass path_sky_env (render/path.cl) fills each
 * texel with the scene method's radiance of the ray from the camera through its centre (the sky
 * without the sun's disc, which light_sun.h samples) and the weight w = (L_R + L_G + L_B)
 * Omega_texel, Omega_texel = dphi (cos theta_0 - cos theta_1); the pass path_sky_cdf then turns
 * the weights into each row's conditional CDF (in w) and the marginal CDF of the rows (texels
 * LIGHT_SKY_W LIGHT_SKY_H + j: x the row's weight, y its CDF, z the total). The sky seen from the
 * camera stands for the sky around every shading point (their positions differ by metres to
 * kilometres; the sky's brightness pattern by little): it is a sampling density only, so the
 * estimator stays unbiased wherever it is used. u1 picks the row by the marginal CDF, its
 * remainder within the row's interval the column by the row's CDF, that remainder the azimuth
 * within the texel, and u2 its cosine.
 * Density: a mixture of the table, share LIGHT_SKY_TABLE, and the uniform sphere (every
 * direction possible, the ground's light too):
 *     p(w) = c p_table(texel) / Omega_texel + (1 - c) / (4 pi),
 * a texel drawn by the two CDFs (binary search), its direction uniform in solid angle in it
 * (cos theta uniform in [cos theta_1, cos theta_0], phi uniform). With no light in the table (the
 * sun far below the horizon) or the uniform test sky, p(w) = 1 / (4 pi). A sample takes three
 * numbers: u0 picks the component, (u1, u2) the direction.
 * The estimators are combined by the power heuristic with beta = 2 (Veach 1997, sec. 9.2.4):
 * for n_l light samples of density p_l and n_b BSDF samples of density p_b at the same vertex,
 *     w_l = (n_l p_l)^2 / ((n_l p_l)^2 + (n_b p_b)^2),  w_b = (n_b p_b)^2 / (same),
 * which sum to 1 for every direction, so the sum of the weighted estimators is unbiased. */
#ifndef ATMO_RENDER_LIGHT_SKY_H
#define ATMO_RENDER_LIGHT_SKY_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "render/bsdf.h"
#include "atmo/gpu_types.h"
#endif

#define LIGHT_SKY_W ATMO_PATH_SKY_COLUMNS
#define LIGHT_SKY_H ATMO_PATH_SKY_ROWS
#define LIGHT_SKY_TEXELS (LIGHT_SKY_W * LIGHT_SKY_H)
#define LIGHT_SKY_TABLE 0.75f

/* The table's frame: up (the camera's local vertical) and two horizontal axes. */
ATMO_FN void light_sky_frame(vec3 up, vec3 *e1, vec3 *e2) { frame_basis(up, e1, e2); }

/* Solid angle of a texel of row j. */
ATMO_FN float light_sky_texel_omega(int j)
{
    float t0 = ATMO_PI * (float)j / (float)LIGHT_SKY_H, t1 = ATMO_PI * (float)(j + 1) / LIGHT_SKY_H;
    return 2.0f * ATMO_PI / (float)LIGHT_SKY_W * (cosf(t0) - cosf(t1));
}

/* The direction through texel (i, j) at fractions (a, b) of its azimuth and cosine ranges. */
ATMO_FN vec3 light_sky_direction(vec3 up, int i, int j, float a, float b)
{
    vec3 e1, e2;
    light_sky_frame(up, &e1, &e2);
    float c0 = cosf(ATMO_PI * (float)j / LIGHT_SKY_H), c1 = cosf(ATMO_PI * (float)(j + 1) / LIGHT_SKY_H);
    float c = c0 + b * (c1 - c0), sn = sqrtf(fmaxf(1.0f - c * c, 0.0f));
    float phi = 2.0f * ATMO_PI * ((float)i + a) / (float)LIGHT_SKY_W;
    return v3_add(v3_add(v3_scale(e1, sn * cosf(phi)), v3_scale(e2, sn * sinf(phi))),
                  v3_scale(up, c));
}

/* The texel holding direction w. */
ATMO_FN int light_sky_texel(vec3 up, vec3 w)
{
    vec3 e1, e2;
    light_sky_frame(up, &e1, &e2);
    float c = clamp(v3_dot(w, up), -1.0f, 1.0f);
    int j = (int)(acosf(c) / ATMO_PI * (float)LIGHT_SKY_H);
    float phi = atan2f(v3_dot(w, e2), v3_dot(w, e1));
    if (phi < 0.0f)
        phi += 2.0f * ATMO_PI;
    int i = (int)(phi / (2.0f * ATMO_PI) * (float)LIGHT_SKY_W);
    j = j < 0 ? 0 : (j >= LIGHT_SKY_H ? LIGHT_SKY_H - 1 : j);
    i = i < 0 ? 0 : (i >= LIGHT_SKY_W ? LIGHT_SKY_W - 1 : i);
    return j * LIGHT_SKY_W + i;
}

/* The CDFs from the weights in env[k].w (path_sky_cdf; see the top of the file). */
ATMO_FN void light_sky_build(ATMO_GLOBAL float4 *env)
{
    float total = 0.0f;
    for (int j = 0; j < LIGHT_SKY_H; j++) {
        float row = 0.0f;
        for (int i = 0; i < LIGHT_SKY_W; i++)
            row += env[j * LIGHT_SKY_W + i].w;
        float run = 0.0f;
        for (int i = 0; i < LIGHT_SKY_W; i++) {
            run += env[j * LIGHT_SKY_W + i].w;
            env[j * LIGHT_SKY_W + i].w = row > 0.0f ? run / row : (float)(i + 1) / LIGHT_SKY_W;
        }
        env[LIGHT_SKY_TEXELS + j].x = row;
        total += row;
    }
    float run = 0.0f;
    for (int j = 0; j < LIGHT_SKY_H; j++) {
        run += env[LIGHT_SKY_TEXELS + j].x;
        env[LIGHT_SKY_TEXELS + j].y = total > 0.0f ? run / total : 0.0f;
        env[LIGHT_SKY_TEXELS + j].z = total;
    }
}

/* The table's probability of texel k (0 when the table is empty). */
ATMO_FN float light_sky_texel_p(ATMO_GLOBAL const float4 *env, int k)
{
    int j = k / LIGHT_SKY_W, i = k % LIGHT_SKY_W;
    float total = env[LIGHT_SKY_TEXELS].z;
    if (!(total > 0.0f))
        return 0.0f;
    float row = env[LIGHT_SKY_TEXELS + j].x / total;
    float c_hi = env[k].w, c_lo = i > 0 ? env[k - 1].w : 0.0f;
    return row * (c_hi - c_lo);
}

ATMO_FN float light_sky_share(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_GLOBAL const float4 *env)
{
    return s->path.sky == ATMO_PATH_SKY_UNIFORM || !(env[LIGHT_SKY_TEXELS].z > 0.0f)
               ? 0.0f
               : LIGHT_SKY_TABLE;
}

ATMO_FN vec3 light_sky_sample(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_GLOBAL const float4 *env,
                              float u0, float u1, float u2)
{
    vec3 up = v3_from4(s->camera.local_up);
    if (u0 < light_sky_share(s, env)) {
        int j = 0;
        while (j < LIGHT_SKY_H - 1 && env[LIGHT_SKY_TEXELS + j].y <= u1)
            j++;
        float lo = j > 0 ? env[LIGHT_SKY_TEXELS + j - 1].y : 0.0f, hi = env[LIGHT_SKY_TEXELS + j].y;
        float v = hi > lo ? clamp((u1 - lo) / (hi - lo), 0.0f, 1.0f) : 0.5f;
        int i = 0;
        while (i < LIGHT_SKY_W - 1 && env[j * LIGHT_SKY_W + i].w <= v)
            i++;
        float c_lo = i > 0 ? env[j * LIGHT_SKY_W + i - 1].w : 0.0f, c_hi = env[j * LIGHT_SKY_W + i].w;
        float a = c_hi > c_lo ? clamp((v - c_lo) / (c_hi - c_lo), 0.0f, 1.0f) : 0.5f;
        return light_sky_direction(up, i, j, a, u2);
    }
    float z = 1.0f - 2.0f * u1, rr = sqrtf(fmaxf(1.0f - z * z, 0.0f));
    float phi = 2.0f * ATMO_PI * u2;
    return v3(rr * cosf(phi), z, rr * sinf(phi));
}

ATMO_FN float light_sky_pdf(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_GLOBAL const float4 *env,
                            vec3 w)
{
    float c = light_sky_share(s, env), table = 0.0f;
    if (c > 0.0f) {
        int k = light_sky_texel(v3_from4(s->camera.local_up), w);
        table = light_sky_texel_p(env, k) / light_sky_texel_omega(k / LIGHT_SKY_W);
    }
    return c * table + (1.0f - c) * (1.0f / (4.0f * ATMO_PI));
}

/* The power heuristic's weight of a strategy with n_a samples of density p_a against one with
 * n_b of density p_b. */
ATMO_FN float light_sky_power(float n_a, float p_a, float n_b, float p_b)
{
    float a = n_a * p_a, b = n_b * p_b;
    return a * a / (a * a + b * b);
}

#endif
