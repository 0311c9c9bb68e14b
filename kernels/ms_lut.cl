/* ms_lut.cl — fills the multiple-scattering transfer LUT Psi_ms (ms_lut.h) into LUT buffer a.
 *
 * Size s->lut_dims[0][0] (mu_s) x s->lut_dims[0][1] (altitude); quadrature knobs from
 * s->method_int: [0] cosine bands, [1] azimuths over [0, pi], [2] segments per direction;
 * s->method_float[0]: share of the order-3 anisotropy given to orders >= 4 (ms_lut.h). Ten
 * planes of w x h texels (ms_lut.h): 0 Psi and f_ms, 1-3 the Rayleigh anisotropy D_uu, D_ss,
 * D_us (final after the third pass), 4 the source of the third pass, 5 the sky irradiance of
 * the ground, 6-8 the anisotropy of the third pass's source, 9 scratch (f_ms, E_1). Each pass
 * writes only planes that no texel of the same pass reads from another texel. Needs the
 * transmittance LUT, so its passes run after transmittance_lut. */

#define MS_PLANE(k) (lut_a + (k) * scene->lut_dims[0][0] * scene->lut_dims[0][1])

/* Pass 1: order 2 from the first-order light at x (ms_lut_texel): plane 0 = (L_2, f_y),
 * 1-3 = D_2, 9 = f_ms per channel; E_1 (the ground's first-order sky light) in plane 5. */
__kernel void ms_lut(__global const atmo_gpu_scene *scene, ATMO_LUT_OUT_PARAMS, int arg)
{
    int i = get_global_id(0), j = get_global_id(1);
    int w = scene->lut_dims[0][0], h = scene->lut_dims[0][1];
    if (i >= w || j >= h)
        return;
    float r, mu_s;
    ms_lut_r_mu_s(&scene->atmosphere, i, j, w, h, &r, &mu_s);
    float4 dev[5];
    int idx = j * w + i;
    MS_PLANE(0)[idx] = ms_lut_texel(scene, lut_transmittance, r, mu_s, scene->method_int[0],
                                    scene->method_int[1], scene->method_int[2], dev);
    for (int k = 0; k < 3; k++)
        MS_PLANE(k + 1)[idx] = dev[k];
    MS_PLANE(9)[idx] = dev[3];
    MS_PLANE(5)[idx] = dev[4];
}

/* Pass 2: order 3 gathered from order 2's source (planes 0-3) and the ground lit by E_1
 * (plane 5): S_3, D_3 and the sky irradiance E_2 it gives. Writes the third pass's source, the
 * series over the gathered order 3: plane 4 = L_2 + S_3 / (1 - f), 6-8 = D_2 + D_3 (1 + k f /
 * (1 - f)), and plane 9 = E_1 + E_2 / (1 - f) (moved to plane 5 by the third pass). */
__kernel void ms_lut_order3(__global const atmo_gpu_scene *scene, ATMO_LUT_OUT_PARAMS, int arg)
{
    int i = get_global_id(0), j = get_global_id(1);
    int w = scene->lut_dims[0][0], h = scene->lut_dims[0][1];
    if (i >= w || j >= h)
        return;
    float r, mu_s;
    ms_lut_r_mu_s(&scene->atmosphere, i, j, w, h, &r, &mu_s);
    int idx = j * w + i;
    float4 dev[4];
    float3 s3 = ms_lut_gather(scene, MS_PLANE(0), MS_PLANE(1), MS_PLANE(5), w, h, r, mu_s,
                              scene->method_int[0], scene->method_int[1], scene->method_int[2],
                              dev);
    float3 f = MS_PLANE(9)[idx].xyz, series = 1.0f / (1.0f - f);
    float3 gain = 1.0f + scene->method_float[0] * f * series;
    MS_PLANE(4)[idx] = (float4)(MS_PLANE(0)[idx].xyz + s3 * series, 0.0f);
    for (int k = 0; k < 3; k++)
        MS_PLANE(k + 6)[idx] = (float4)(MS_PLANE(k + 1)[idx].xyz + dev[k].xyz * gain, 0.0f);
    MS_PLANE(9)[idx] = (float4)(MS_PLANE(5)[idx].xyz + dev[3].xyz * series, 0.0f);
}

/* Pass 3: orders >= 3 gathered from the series source (planes 4, 6-8) and the ground lit by
 * the sky of all orders (plane 9): Psi = L_2 + <G>, D = D_2 + D_G; plane 5 = the ground's sky
 * irradiance for the march. */
__kernel void ms_lut_second(__global const atmo_gpu_scene *scene, ATMO_LUT_OUT_PARAMS, int arg)
{
    int i = get_global_id(0), j = get_global_id(1);
    int w = scene->lut_dims[0][0], h = scene->lut_dims[0][1];
    if (i >= w || j >= h)
        return;
    float r, mu_s;
    ms_lut_r_mu_s(&scene->atmosphere, i, j, w, h, &r, &mu_s);
    int idx = j * w + i;
    float4 dev[4];
    float3 higher = ms_lut_gather(scene, MS_PLANE(4), MS_PLANE(6), MS_PLANE(9), w, h, r, mu_s,
                                  scene->method_int[0], scene->method_int[1],
                                  scene->method_int[2], dev);
    MS_PLANE(0)[idx] = (float4)(MS_PLANE(0)[idx].xyz + higher, MS_PLANE(0)[idx].w);
    for (int k = 0; k < 3; k++)
        MS_PLANE(k + 1)[idx] += (float4)(dev[k].xyz, 0.0f);
    MS_PLANE(5)[idx] = MS_PLANE(9)[idx];
}
