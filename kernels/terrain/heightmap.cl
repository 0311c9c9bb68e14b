/* heightmap.cl — the terrain's precompute pass: the height field sampled on a grid.
 *
 * terrain_heightmap: work item (i, j) of an N x N grid (N = heightmap_size) evaluates the fBm
 * height (noise.h) at the texel centre
 *     u = -E/2 + (i + 1/2) E/N,  v = -E/2 + (j + 1/2) E/N   (E = heightmap_extent_m)
 * and writes texel j N + i: the height (ATMO_TERRAIN_FORMAT_FLOAT, 4 bytes), the height and
 * its analytic derivatives dh/du, dh/dv (ATMO_TERRAIN_FORMAT_DERIVATIVES, 12 bytes), or the
 * height rounded to a half float (ATMO_TERRAIN_FORMAT_HALF, 2 bytes: vstore_half, round to
 * nearest even; terrain_half.h). With a
 * host-supplied height grid (buffer terrain_base, base_nx x base_nz samples from (x0, z0) at
 * spacing (dx, dz): base_rect) the texel is the grid's bilinear interpolation (clamped at its
 * edges; derivatives from the interpolating patch) plus base_detail times the fBm. It reads
 * only the scene's terrain.field and the grid, so the heightmap is cached under the key of those inputs and
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
    if (f->base_nx > 0 && f->base_nz > 0) {
        float gx = clamp((u - f->base_rect.x) / f->base_rect.z, 0.0f, (float)(f->base_nx - 1));
        float gz = clamp((v - f->base_rect.y) / f->base_rect.w, 0.0f, (float)(f->base_nz - 1));
        int i0 = min((int)gx, max(f->base_nx - 2, 0)), j0 = min((int)gz, max(f->base_nz - 2, 0));
        int i1 = min(i0 + 1, f->base_nx - 1), j1 = min(j0 + 1, f->base_nz - 1);
        float fx = gx - (float)i0, fz = gz - (float)j0;
        float a = terrain_base[j0 * f->base_nx + i0], b = terrain_base[j0 * f->base_nx + i1];
        float c = terrain_base[j1 * f->base_nx + i0], d = terrain_base[j1 * f->base_nx + i1];
        float k = f->base_detail;
        h.h = mix(mix(a, b, fx), mix(c, d, fx), fz) + k * h.h;
        h.du = ((b - a) * (1.0f - fz) + (d - c) * fz) / f->base_rect.z + k * h.du;
        h.dv = ((c - a) * (1.0f - fx) + (d - b) * fx) / f->base_rect.w + k * h.dv;
    }
    if (f->heightmap_format == ATMO_TERRAIN_FORMAT_HALF) {
        vstore_half(h.h, (size_t)(j * n + i), (__global half *)heightmap);
    } else if (f->heightmap_format == ATMO_TERRAIN_FORMAT_DERIVATIVES) {
        heightmap[3 * (j * n + i)] = h.h;
        heightmap[3 * (j * n + i) + 1] = h.du;
        heightmap[3 * (j * n + i) + 2] = h.dv;
    } else {
        heightmap[j * n + i] = h.h;
    }
}
