/* transmittance.cl — fills the transmittance LUT (atmosphere.h has its parametrisation).
 *
 * Each texel (i, j) is placed at its centre u = (i + 0.5)/W, v = (j + 0.5)/H, mapped back to
 * (r, mu), and holds the optical depth tau to the top of the atmosphere by the midpoint rule
 * with TRANSMITTANCE_STEPS segments (error ~ 1/n^2). At 200 the LUT's worst error (8.8e-4
 * relative where T > 1e-2, tests/test_transmittance.c against the published table and the
 * double quadrature) is the interpolation's, not the quadrature's, so more steps would cost
 * without helping (measured choices: docs/notes/transmittance.md). */
#define TRANSMITTANCE_STEPS 200

__kernel void transmittance_lut(__global const atmo_gpu_scene *scene, ATMO_LUT_OUT_PARAMS,
                                int arg)
{
    int i = get_global_id(0), j = get_global_id(1);
    int w = scene->transmittance_width, h = scene->transmittance_height;
    if (i >= w || j >= h)
        return;
    float r, mu;
    atmosphere_transmittance_r_mu(&scene->atmosphere, ((float)i + 0.5f) / (float)w,
                                  ((float)j + 0.5f) / (float)h, w, h, &r, &mu);
    vec3 tau = atmosphere_optical_depth_to_top(&scene->atmosphere, r, mu, TRANSMITTANCE_STEPS);
    transmittance_lut[j * w + i] = (float4)(tau, 0.0f);
}
