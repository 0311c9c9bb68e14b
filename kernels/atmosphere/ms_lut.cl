/* ms_lut.cl — fills the multiple-scattering transfer LUT Psi_ms (ms_lut.h) into the buffer
 * ms_lut.
 *
 * Size s->ms.width (mu_s) x s->ms.height (altitude); quadrature knobs (atmo_gpu_ms_lut):
 * directions_mu cosine bands, directions_phi azimuths over [0, pi] (half in the gathering
 * passes), steps segments per direction; higher_anisotropy: share of the order-3 anisotropy
 * given to orders >= 4; g1, g2: the aerosol phase function's Legendre coefficients (ms_lut.h).
 * Fourteen planes of w x h texels (ms_lut.h): 0 Psi and f_ms, 1-5 the anisotropy D_uu, D_ss, D_us,
 * b_u, b_s (final after the third pass), 6 the source of the third pass and 7-11 its anisotropy, 12
 * the sky irradiance of the ground, 13 scratch (1 - f_ms, then E_1 + E_2 / (1 - f)). Each pass writes
 * only planes that no texel of the same pass reads from another texel. Needs the transmittance LUT,
 * so its passes run after transmittance_lut. */

#define MS_PLANE(k) (ms_lut + (k) * scene->ms.width * scene->ms.height)

/* Azimuths of the gathering passes: half of pass 1's. The gathered light has no aureole, and
 * the n-point midpoint rule over [0, pi] integrates its azimuthal harmonics exactly up to
 * cos((2n - 1) phi), so half the azimuths change the sky by a few 1e-5 for a third less
 * precompute time (measured: docs/notes/ms_lut.md). */
#define MS_GATHER_PHI (scene->ms.directions_phi > 1 ? scene->ms.directions_phi / 2 : 1)

/* The texel of this work item: its (r, mu_s) and index in a plane, or -1 outside the LUT
 * (the global size is padded). */
int ms_this_texel(__global const atmo_gpu_scene *scene, float *r, float *mu_s)
{
    int i = get_global_id(0), j = get_global_id(1);
    int w = scene->ms.width, h = scene->ms.height;
    if (i >= w || j >= h)
        return -1;
    ms_lut_r_mu_s(&scene->atmosphere, i, j, w, h, r, mu_s);
    return j * w + i;
}

/* Pass 1: order 2 from the first-order light at x (ms_lut_texel): plane 0 = (L_2, f_y),
 * 1-5 = its anisotropy, 13 = 1 - f_ms per channel, 12 = E_1 (the ground's first-order sky light). */
__kernel void ms_lut(__global const atmo_gpu_scene *scene, ATMO_LUT_OUT_PARAMS, int arg)
{
    float r, mu_s;
    int idx = ms_this_texel(scene, &r, &mu_s);
    if (idx < 0)
        return;
    float4 dev[7];
    MS_PLANE(0)[idx] = ms_lut_texel(scene, transmittance_lut, r, mu_s, scene->ms.directions_mu,
                                    scene->ms.directions_phi, scene->ms.steps, dev);
    for (int k = 0; k < 5; k++)
        MS_PLANE(k + 1)[idx] = dev[k];
    MS_PLANE(13)[idx] = dev[5];
    MS_PLANE(12)[idx] = dev[6];
}

/* Pass 2: order 3 gathered from order 2's source (planes 0-5) and the ground lit by E_1
 * (plane 12): S_3, its anisotropy A_3 and the sky irradiance E_2 it gives. Writes the third
 * pass's source, the series over the gathered order 3: plane 6 = L_2 + S_3 / (1 - f), 7-11 =
 * A_2 + A_3 (1 + k f / (1 - f)), and plane 13 = E_1 + E_2 / (1 - f) (moved to plane 12 by the
 * third pass). */
__kernel void ms_lut_order3(__global const atmo_gpu_scene *scene, ATMO_LUT_OUT_PARAMS, int arg)
{
    float r, mu_s;
    int idx = ms_this_texel(scene, &r, &mu_s);
    if (idx < 0)
        return;
    int w = scene->ms.width, h = scene->ms.height;
    float4 dev[6];
    float3 s3 = ms_lut_gather(scene, MS_PLANE(0), MS_PLANE(1), MS_PLANE(12), w, h, r, mu_s,
                              scene->ms.directions_mu, MS_GATHER_PHI, scene->ms.steps, dev);
    float3 escape = MS_PLANE(13)[idx].xyz, series = 1.0f / escape;
    float3 gain = 1.0f + scene->ms.higher_anisotropy * (1.0f - escape) * series;
    MS_PLANE(6)[idx] = (float4)(MS_PLANE(0)[idx].xyz + s3 * series, 0.0f);
    for (int k = 0; k < 5; k++)
        MS_PLANE(k + 7)[idx] = (float4)(MS_PLANE(k + 1)[idx].xyz + dev[k].xyz * gain, 0.0f);
    MS_PLANE(13)[idx] = (float4)(MS_PLANE(12)[idx].xyz + dev[5].xyz * series, 0.0f);
}

/* Pass 3: orders >= 3 gathered from the series source (planes 6-11) and the ground lit by the
 * sky of all orders (plane 13): Psi = L_2 + <G>, anisotropy A_2 + A_G; plane 12 = the ground's
 * sky irradiance for the march. */
__kernel void ms_lut_second(__global const atmo_gpu_scene *scene, ATMO_LUT_OUT_PARAMS, int arg)
{
    float r, mu_s;
    int idx = ms_this_texel(scene, &r, &mu_s);
    if (idx < 0)
        return;
    int w = scene->ms.width, h = scene->ms.height;
    float4 dev[6];
    float3 higher = ms_lut_gather(scene, MS_PLANE(6), MS_PLANE(7), MS_PLANE(13), w, h, r, mu_s,
                                  scene->ms.directions_mu, MS_GATHER_PHI, scene->ms.steps, dev);
    MS_PLANE(0)[idx] = (float4)(MS_PLANE(0)[idx].xyz + higher, MS_PLANE(0)[idx].w);
    for (int k = 0; k < 5; k++)
        MS_PLANE(k + 1)[idx] += (float4)(dev[k].xyz, 0.0f);
    MS_PLANE(12)[idx] = MS_PLANE(13)[idx];
}
