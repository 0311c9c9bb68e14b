/* guides.cl — guide_render: the denoiser's guides (Intel Open Image Denoise's "albedo" and
 * "normal" auxiliary images, docs/guide/denoise.md), free of Monte Carlo noise, in every mode.
 *
 * For each pixel the camera rays of a fixed GUIDES_GRID x GUIDES_GRID pattern of positions in
 * the pixel meet the first surface (render/surfaces.h: the ground sphere, the terrain and its
 * sea, the objects); the guides are the means over the pattern of
 *     albedo: the surface's Lambertian albedo; 1 for a ray that meets no surface (OIDN's
 *             convention for the environment: "1 or the environment's colour clamped to
 *             [0, 1]"; 1 keeps the guide flat where the sky's own gradients are, so the filter
 *             takes them from the colour);
 *     normal: the surface's outward unit normal, world axes; 0 for a ray that meets nothing
 *             (OIDN: a zero normal marks "no surface");
 *     depth:  the distance to the surface (m), GUIDES_NO_HIT_DEPTH_M for a ray that meets
 *             nothing (Blender's background depth); written as an EXR layer only.
 * The positions follow each mode's pixel filter, so a guide's edge is anti-aliased as the
 * converged image's is: the preview's box over the pixel (sky.cl) at the cell centres
 * (i + 1/2) / GUIDES_GRID; the path tracer's truncated Gaussian (path_camera.h) by inverting
 * its radial distribution at the same cell centres taken as (u1, u2) — its samples' own
 * mapping, on a stratified grid instead of the Sobol sequence. The rays are the pinhole's
 * (a thin lens blurs what the guide would keep sharp; the host does not use the guides then).
 * The pattern's rays lie in a cone about the pixel's centre ray (its spread the largest chord
 * between their unit directions and the centre's); the marched surfaces (the terrain) walk the
 * cone once to where it first comes within the tracer's tolerance of them
 * (render/surfaces.h's surfaces_cone_start), and each ray's own march starts there.
 * Nothing random is drawn: the guides of a pixel are the same for any seed, sample count,
 * tile size or launch, and a 4-spp image gets the guides of the converged image. A fisheye's
 * corners outside its circle (no ray) get albedo 0 and normal 0, as their image is black.
 *
 * Volumes (the media's slots `guide_depth` and `guide_block`, composed by the plan into
 * guides_media_ray and guides_media_block: the cloud shell, the fBm cloud layer; in every mode
 * and for path.clouds = march and volume alike): a transmittance-weighted average, not the
 * first scattering. A ray's values are
 *     albedo = (1 - T) w + T a_behind,   normal = T_y n_behind
 * per channel, T = e^{-tau} the view transmittance through the clouds that the image shows (not
 * the method's under the path tracer's uniform sky or before a surface nearer than its
 * PATH_AIR_MIN_M, which the path tracer does not march) in front of the first surface (all of
 * them for a ray that meets none), w the clouds' single-scattering albedo (the media's weighted
 * by their optical depths), a_behind and n_behind the surface's values or the sky's (1 and 0).
 * The shell's optical depth is each ray's chord (closed form); for a homogeneous shell of
 * optical depth tau along the ray the guide is (1 - e^{-tau}) w + e^{-tau} a_behind
 * (tests/test_guides.c). The layer's is a march (cloud_layer.h's clouds_view_density_ends, on
 * GUIDES_CLOUD_STEP_SCALE times the marcher's steps, at their midpoints: no random number
 * either) along the centre ray of each GUIDES_CLOUD_STRIDE x GUIDES_CLOUD_STRIDE block of the
 * pattern, which gives each of the block's rays the density in front of its own surface: the
 * rays of a block differ by a fraction of a pixel across, but their surfaces' distances can
 * differ by kilometres (a peak in front of the valley behind it). Why
 * this: OIDN documents its features as those of the first hit, noise-free and under the
 * colour's pixel filter, and warns that features seen through transparent surfaces do not help;
 * a cloud pixel's light is a blend of the cloud's and what lies behind in the proportions 1 - T
 * and T, and the guide blends the same way, so a cloud edge over terrain is an edge in the
 * guide where it is one in the image, and a thin veil keeps the terrain's texture in the guide.
 * The first significant scattering is a random point (noise in the guide) or, taken as the
 * point of optical depth 1, a hard switch between cloud and ground where the image blends them.
 * The cloud's own normal is 0, OIDN's "no surface": a cloud has no surface and its multiple
 * scattering follows no local normal, so the filter takes a cloud's shading from the colour as
 * it takes the sky's (a normal facing the camera did worse, docs/guide/denoise.md; the
 * density's gradient was not tried).
 *
 * The sun's disc: the share of the pattern's rays that meet no surface and point into the
 * disc (cos of their angle to the sun >= sun_direction.w, the cosine of its angular radius),
 * so the host can keep the disc out of the filter (outputs.c).
 *
 * Output: one work item per pixel `first + id` of the image (row-major, row 0 = top), items
 * past `count` return at once; albedo[pixel] = (albedo, disc share), normal[pixel] = (normal,
 * depth). */

/* The pattern per mode (GUIDES_GRID, composed by the plan from gpu_enums.h): path 8 x 8 rays,
 * since at 4 x 4 the radial-angular grid samples the Gaussian too coarsely and the guided
 * filter lost a tenth of its gain; preview its box at 4 x 4 cell centres. Both march the
 * clouds once per 2 x 2 block (docs/guide/denoise.md: the rays, the blocks and the step,
 * measured). */
#define GUIDES_CLOUD_STRIDE ATMO_GUIDES_BLOCK
#define GUIDES_BLOCK_RAYS ATMO_GUIDES_BLOCK_RAYS
/* the layer's march takes this many times the marcher's steps: the guide needs the
 * transmittance's shape, not the image's accuracy */
#define GUIDES_CLOUD_STEP_SCALE 2.0f
#define GUIDES_NO_HIT_DEPTH_M 1e10f
/* the clouds' view optical depth is integrated to this (e^-9.2 = 1e-4 of the guide behind) */
#define GUIDES_TAU_STOP 9.2f

/* Ray (i, j) of pixel (x, y)'s pattern: the mode's camera ray at the centre of cell (i, j) of
 * GUIDES_GRID x GUIDES_GRID; 0 where there is none (a fisheye's corner). */
float3 guides_pattern_ray(__global const atmo_gpu_scene *scene, int x, int y, int i, int j)
{
    const float cell = 1.0f / (float)GUIDES_GRID;
    return guides_pixel_ray(scene, x, y, ((float)i + 0.5f) * cell, ((float)j + 0.5f) * cell);
}

__kernel void guide_render(__global const atmo_gpu_scene *scene, ATMO_LUT_PARAMS,
                           __global float4 *albedo, __global float4 *normal, uint first,
                           uint count)
{
    uint id = get_global_id(0);
    if (id >= count)
        return;
    uint pixel = first + id;
    int width = scene->camera.width;
    int x = (int)(pixel % (uint)width), y = (int)(pixel / (uint)width);
    float3 a = (float3)(0.0f), n = (float3)(0.0f);
    float depth = 0.0f, disc = 0.0f;
    float4 sun = scene->sun_direction;
    const float cell = 1.0f / (float)GUIDES_GRID;
    /* the pattern's cone (where a surface is marched): its axis the mean of the pattern's
     * rays, its spread the largest chord from the axis to one of them; the marched surfaces
     * start where it first meets them */
    float3 axis = (float3)(0.0f);
    float spread = 0.0f, march_from = 0.0f;
    if (SURFACES_MARCHED > 0)
        for (int k = 0; k < GUIDES_GRID * GUIDES_GRID; k++)
            axis += guides_pattern_ray(scene, x, y, k % GUIDES_GRID, k / GUIDES_GRID);
    if (dot(axis, axis) > 0.0f) {
        axis = normalize(axis);
        for (int k = 0; k < GUIDES_GRID * GUIDES_GRID; k++) {
            float3 d = guides_pattern_ray(scene, x, y, k % GUIDES_GRID, k / GUIDES_GRID);
            if (dot(d, d) > 0.0f)
                spread = fmax(spread, length(d - axis));
        }
        medium_ray cone = medium_ray_from_camera(scene, axis);
        march_from = surfaces_cone_start(scene, ATMO_LUT_ARGS, &cone, spread);
    }
    for (int bj = 0; bj < GUIDES_GRID; bj += GUIDES_CLOUD_STRIDE)
        for (int bi = 0; bi < GUIDES_GRID; bi += GUIDES_CLOUD_STRIDE) {
            /* the block's rays: their surfaces, and where the layer in front of each ends */
            path_hit hit[GUIDES_BLOCK_RAYS];
            float3 dirs[GUIDES_BLOCK_RAYS];
            float ends[GUIDES_BLOCK_RAYS];
            float3 block_tau[GUIDES_BLOCK_RAYS], block_tau_albedo[GUIDES_BLOCK_RAYS];
            int any_ray = 0;
            for (int k = 0; k < GUIDES_BLOCK_RAYS; k++) {
                int i = bi + k % GUIDES_CLOUD_STRIDE, j = bj + k / GUIDES_CLOUD_STRIDE;
                dirs[k] = guides_pattern_ray(scene, x, y, i, j);
                ends[k] = 0.0f;
                if (dot(dirs[k], dirs[k]) == 0.0f)
                    continue;
                medium_ray ray = medium_ray_from_camera(scene, dirs[k]);
                hit[k] = surfaces_hit_from(scene, ATMO_LUT_ARGS, &ray, march_from, INFINITY);
                ends[k] = (guides_media_shown(scene, hit[k].t) | (MEDIA_VOLUME > 0))
                              ? hit[k].t
                              : 0.0f;
                any_ray = 1;
            }
            /* the layer along the block's centre ray (its first ray where the centre sees
             * nothing: a fisheye's rim) */
            float3 centre = guides_pixel_ray(scene, x, y,
                                             ((float)bi + 0.5f * GUIDES_CLOUD_STRIDE) * cell,
                                             ((float)bj + 0.5f * GUIDES_CLOUD_STRIDE) * cell);
            for (int k = 0; k < GUIDES_BLOCK_RAYS && dot(centre, centre) == 0.0f; k++)
                centre = dirs[k];
            medium_ray shared = medium_ray_from_camera(scene, centre);
            for (int k = 0; k < GUIDES_BLOCK_RAYS; k++)
                block_tau[k] = block_tau_albedo[k] = (float3)(0.0f);
            guides_media_block(scene, &shared, any_ray ? GUIDES_BLOCK_RAYS : 0, ends,
                               GUIDES_CLOUD_STEP_SCALE, GUIDES_TAU_STOP, block_tau,
                               block_tau_albedo);
            for (int k = 0; k < GUIDES_BLOCK_RAYS; k++) {
                if (dot(dirs[k], dirs[k]) == 0.0f)
                    continue;
                path_hit h = hit[k];
                medium_ray ray = medium_ray_from_camera(scene, dirs[k]);
                float3 tau = (float3)(0.0f), tau_albedo = (float3)(0.0f);
                if (guides_media_shown(scene, h.t))
                    guides_media_ray(scene, &ray, h.t, &tau, &tau_albedo);
                tau += block_tau[k];
                tau_albedo += block_tau_albedo[k];
                float3 w = select((float3)(0.0f), tau_albedo / tau, tau > (float3)(0.0f));
                float3 T = exp(-tau);
                float3 behind_albedo = (float3)(1.0f), behind_normal = (float3)(0.0f);
                if (h.kind == SURFACES_NONE) {
                    depth += GUIDES_NO_HIT_DEPTH_M;
                    disc += dot(dirs[k], sun.xyz) >= sun.w ? 1.0f : 0.0f;
                } else {
                    behind_albedo = h.albedo;
                    behind_normal = h.normal;
                    depth += h.t;
                }
                a += T * behind_albedo + ((float3)(1.0f) - T) * w;
                n += T.y * behind_normal;
            }
        }
    float inv = 1.0f / (float)(GUIDES_GRID * GUIDES_GRID);
    albedo[pixel] = (float4)(clamp(a * inv, 0.0f, 1.0f), disc * inv);
    normal[pixel] = (float4)(n * inv, depth * inv);
}
