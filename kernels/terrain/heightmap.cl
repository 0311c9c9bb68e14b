/* heightmap.cl — the terrain's precompute pass: the height field sampled on a grid.
 *
 * terrain_heightmap: work item (i, j) of an N x N grid (N = heightmap_size) evaluates the fBm
 * height (noise.h) at the texel centre
 *     u = -E/2 + (i + 1/2) E/N,  v = -E/2 + (j + 1/2) E/N   (E = heightmap_extent_m)
 * and writes texel j N + i: the height (ATMO_TERRAIN_FORMAT_FLOAT, 4 bytes) or the height and
 * its analytic derivatives dh/du, dh/dv (ATMO_TERRAIN_FORMAT_DERIVATIVES, 12 bytes). It reads
 * only the scene's terrain.field, so the heightmap is cached under the key of those inputs and
 * stays when the camera moves. Items outside the grid (padding) return at once. */

__kernel void terrain_heightmap(__global const atmo_gpu_scene *s, ATMO_LUT_OUT_PARAMS, int arg)
{
    __global const atmo_gpu_terrain_field *f = &s->terrain.field;
    int i = get_global_id(0), j = get_global_id(1), n = f->heightmap_size;
    if (i >= n || j >= n)
        return;
    float texel = f->heightmap_extent_m / (float)n;
    float u = -0.5f * f->heightmap_extent_m + ((float)i + 0.5f) * texel;
    float v = -0.5f * f->heightmap_extent_m + ((float)j + 0.5f) * texel;
    terrain_height h = terrain_height_direct(f, u, v);
    if (f->heightmap_format == ATMO_TERRAIN_FORMAT_DERIVATIVES) {
        heightmap[3 * (j * n + i)] = h.h;
        heightmap[3 * (j * n + i) + 1] = h.du;
        heightmap[3 * (j * n + i) + 2] = h.dv;
    } else {
        heightmap[j * n + i] = h.h;
    }
}
