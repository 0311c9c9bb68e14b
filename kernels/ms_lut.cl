/* ms_lut.cl — fills the multiple-scattering transfer LUT Psi_ms (ms_lut.h) into LUT buffer a.
 *
 * Size s->lut_dims[0][0] (mu_s) x s->lut_dims[0][1] (altitude); quadrature knobs from
 * s->method_int: [0] cosine bands, [1] azimuths over [0, pi], [2] segments per direction;
 * s->method_float[0]: share of the anisotropy given to orders >= 3 (ms_lut.h). Four planes of
 * w x h texels: Psi and f_ms, then the Rayleigh anisotropy D_uu, D_ss, D_us.
 * Needs the transmittance LUT, so its pass runs after transmittance_lut. */

__kernel void ms_lut(__global const atmo_gpu_scene *scene, ATMO_LUT_OUT_PARAMS, int arg)
{
    int i = get_global_id(0), j = get_global_id(1);
    int w = scene->lut_dims[0][0], h = scene->lut_dims[0][1];
    if (i >= w || j >= h)
        return;
    float r, mu_s;
    ms_lut_r_mu_s(&scene->atmosphere, i, j, w, h, &r, &mu_s);
    float4 dev[3];
    int n = w * h, idx = j * w + i;
    lut_a[idx] = ms_lut_texel(scene, lut_transmittance, r, mu_s, scene->method_int[0],
                              scene->method_int[1], scene->method_int[2],
                              scene->method_float[0], dev);
    for (int k = 0; k < 3; k++)
        lut_a[(k + 1) * n + idx] = dev[k];
}
