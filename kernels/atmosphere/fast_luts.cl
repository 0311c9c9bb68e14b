/* fast_luts.cl — the per-frame LUTs of method "fast" (method_fast.h): the sky-view LUT around
 * the camera, into the buffer sky_view_lut, in three planes of w x h texels: single scattering
 * without its phase functions, Rayleigh (0) and Mie (1), and the rest (2: multiple scattering and
 * the ground): the parts of the medium integrator's result over the air alone, no opaque surface
 * (medium_integrate_air, kernels/media/medium.h; why: method_fast.h). Needs the
 * transmittance and Psi_ms LUTs (passes before it). */

__kernel void sky_view_lut(__global const atmo_gpu_scene *scene, ATMO_LUT_OUT_PARAMS, int arg)
{
    int i = get_global_id(0), j = get_global_id(1);
    int w = scene->sky_view.width, h = scene->sky_view.height;
    if (i >= w || j >= h)
        return;
    float mu, cos_phi;
    fast_sky_view_ray(scene, i, j, w, h, &mu, &cos_phi);
    float mu_s = fast_camera_mu_s(scene);
    float nu = atmo_clamp_cos(mu * mu_s + atmo_safe_sqrt((1.0f - mu * mu) * (1.0f - mu_s * mu_s)) *
                                              cos_phi);
    medium_ray m = medium_ray_from_cosines(scene, scene->camera.local_up.w, mu, mu_s, nu);
    medium_result res;
    medium_integrate_air(scene, ATMO_LUT_ARGS, &m, 0.0f, INFINITY, scene->sky_view.steps, 0.5f,
                         1, &res);
    int idx = j * w + i, n = w * h;
    sky_view_lut[idx] = (float4)(res.single[MEDIA_RAYLEIGH], 0.0f);
    sky_view_lut[n + idx] = (float4)(res.single[MEDIA_MIE], 0.0f);
    sky_view_lut[2 * n + idx] = (float4)(res.rest, 0.0f);
}
