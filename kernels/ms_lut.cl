/* ms_lut.cl — fills the multiple-scattering transfer LUT Psi_ms (ms_lut.h) into LUT buffer a.
 *
 * Size s->lut_dims[0][0] (mu_s) x s->lut_dims[0][1] (altitude); quadrature knobs from
 * s->method_int: [0] cosine bands, [1] azimuths over [0, pi], [2] segments per direction;
 * s->method_float[0]: share of the anisotropy given to orders >= 3 (ms_lut.h). Six planes of
 * w x h texels (ms_lut.h): Psi and f_ms, the Rayleigh anisotropy D_uu, D_ss, D_us, then Psi_1
 * and the sky irradiance for the second pass (ms_lut_second), which completes plane 0.
 * Needs the transmittance LUT, so its passes run after transmittance_lut. */

__kernel void ms_lut(__global const atmo_gpu_scene *scene, ATMO_LUT_OUT_PARAMS, int arg)
{
    int i = get_global_id(0), j = get_global_id(1);
    int w = scene->lut_dims[0][0], h = scene->lut_dims[0][1];
    if (i >= w || j >= h)
        return;
    float r, mu_s;
    ms_lut_r_mu_s(&scene->atmosphere, i, j, w, h, &r, &mu_s);
    float4 dev[5];
    int n = w * h, idx = j * w + i;
    /* Psi_1 = L_2 / (1 - f) in plane 4; L_2 and f in plane 0 until the second pass */
    lut_a[4 * n + idx] = ms_lut_texel(scene, lut_transmittance, r, mu_s, scene->method_int[0],
                                      scene->method_int[1], scene->method_int[2],
                                      scene->method_float[0], dev);
    for (int k = 0; k < 3; k++)
        lut_a[(k + 1) * n + idx] = dev[k];
    lut_a[idx] = dev[3];
    lut_a[5 * n + idx] = dev[4];
}

/* Second pass: Psi = L_2 + the orders >= 3 gathered from Psi_1 (ms_lut_gather); each texel
 * reads its own plane 0 and anyone's plane 4, so no texel reads what another writes. */
__kernel void ms_lut_second(__global const atmo_gpu_scene *scene, ATMO_LUT_OUT_PARAMS, int arg)
{
    int i = get_global_id(0), j = get_global_id(1);
    int w = scene->lut_dims[0][0], h = scene->lut_dims[0][1];
    if (i >= w || j >= h)
        return;
    float r, mu_s;
    ms_lut_r_mu_s(&scene->atmosphere, i, j, w, h, &r, &mu_s);
    int idx = j * w + i;
    vec3 higher = ms_lut_gather(scene, lut_a + 4 * w * h, lut_a + 5 * w * h, w, h, r, mu_s,
                                scene->method_int[0], scene->method_int[1],
                                scene->method_int[2]);
    lut_a[idx] = (float4)(lut_a[idx].xyz + higher, lut_a[idx].w);
}
