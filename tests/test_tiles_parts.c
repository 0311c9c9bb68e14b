/* test_tiles_parts — the split of an image into parts (atmo/tiles.h) and the merge's checks
 * (atmo/part.h), on the host.
 * labels: unit
 *
 * Oracle: the definition of the split. For every image size, tile size and part count tried,
 * the tiles of parts 1..N together cover each pixel exactly once; each tile lies inside the
 * image, is at most `size` wide and tall, and lies in one band (ATMO_PART_BAND_ROWS rows) of
 * its own part (band b in part b mod N + 1); every tile is `size` wide except at the right
 * edge; parts = 0 is the whole image in the classic square tiles. The scheduler's per-pixel
 * sample count is the sample count of the tile that holds the pixel, 0 outside the part. The
 * counts are exact: no tolerance. Then atmo_part_merge on synthetic parts (each holding only
 * its rows): complete parts merge into each pixel's own part's values, and their row counts add
 * up to the image's; a missing, a duplicated, a foreign and an incomplete
 * part are refused as usage errors. */
#include <stdlib.h>
#include <string.h>
#include "atmo/part.h"
#include "atmo/tiles.h"
#include "testlib.h"

static void check_split(int width, int height, int size, int parts)
{
    int *cover = calloc((size_t)width * height, sizeof *cover);
    for (int part = parts ? 1 : 0; part <= parts; part++) {
        atmo_tiles t;
        atmo_err e = {{0}};
        CHECK(atmo_tiles_init_part(&t, width, height, size, part, parts, &e) == ATMO_OK);
        for (int i = 0; i < t.count; i++) {
            atmo_tile tile;
            atmo_tiles_get(&t, i, &tile);
            CHECK(tile.x >= 0 && tile.y >= 0 && tile.w >= 1 && tile.h >= 1);
            CHECK(tile.x + tile.w <= width && tile.y + tile.h <= height);
            CHECK(tile.w <= size && tile.h <= size);
            CHECK(tile.w == size || tile.x + tile.w == width);
            if (parts) {
                int band = tile.y / ATMO_PART_BAND_ROWS;
                CHECK((tile.y + tile.h - 1) / ATMO_PART_BAND_ROWS == band);
                CHECK(atmo_part_of_row(tile.y, parts) == part);
                CHECK(band % parts + 1 == part);
            } else {
                CHECK(tile.y % size == 0);
            }
            t.samples[i] = i + 1; /* mark the tile, then read it back per pixel */
            for (int y = tile.y; y < tile.y + tile.h; y++)
                for (int x = tile.x; x < tile.x + tile.w; x++) {
                    cover[(size_t)y * width + x]++;
                    CHECK(atmo_tiles_pixel_samples(&t, x, y) == i + 1);
                }
        }
        for (int y = 0; y < height; y++)
            if (parts && atmo_part_of_row(y, parts) != part)
                CHECK(atmo_tiles_pixel_samples(&t, 0, y) == 0);
        atmo_tiles_free(&t);
    }
    int once = 1;
    for (size_t i = 0; i < (size_t)width * height; i++)
        once = once && cover[i] == 1;
    CHECK(once);
    if (!once)
        fprintf(stderr, "  %dx%d, tiles of %d, %d parts: a pixel not covered exactly once\n",
                width, height, size, parts);
    free(cover);
}

/* A synthetic part i of n of a w x h image: `samples` in each pixel, values i + c and i c. */
static void make_part(atmo_part *p, int w, int h, int i, int n, int samples, const char *scene)
{
    atmo_err e = {{0}};
    CHECK(atmo_part_alloc(p, w, h, i, n, scene, &e) == ATMO_OK);
    CHECK(p->rows == atmo_part_row_count(h, i, n));
    for (size_t k = 0; k < (size_t)w * p->rows; k++) {
        p->samples[k] = samples;
        for (int c = 0; c < 3; c++) {
            p->s1[3 * k + c] = (float)(i + c);
            p->s2[3 * k + c] = (float)(i * c);
        }
    }
}

static void check_merge(void)
{
    enum { W = 5, H = 50, N = 3, S = 4 };
    atmo_part parts[N + 1], merged;
    const char *paths[N + 1] = {"a.exr", "b.exr", "c.exr", "d.exr"};
    atmo_err e = {{0}};
    for (int i = 0; i < N; i++)
        make_part(&parts[i], W, H, i + 1, N, S, "{\"scene\": 1}");
    CHECK(parts[0].rows + parts[1].rows + parts[2].rows == H);
    CHECK(atmo_part_merge(parts, paths, N, S, &merged, &e) == ATMO_OK);
    CHECK(merged.rows == H);
    int right = 1;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            size_t k = (size_t)y * W + x;
            int owner = atmo_part_of_row(y, N);
            right = right && merged.samples[k] == S && merged.s1[3 * k + 2] == (float)(owner + 2) &&
                    merged.s2[3 * k + 1] == (float)owner;
        }
    CHECK(right);
    atmo_part_free(&merged);
    /* missing: parts 1 and 3 only */
    atmo_part two[2] = {parts[0], parts[2]};
    CHECK(atmo_part_merge(two, paths, 2, S, &merged, &e) == ATMO_ERR_USAGE);
    CHECK(strstr(e.msg, "part 2/3 is missing") != NULL);
    /* duplicated: part 2 twice */
    atmo_part dup[4] = {parts[0], parts[1], parts[2], parts[1]};
    CHECK(atmo_part_merge(dup, paths, 4, S, &merged, &e) == ATMO_ERR_USAGE);
    CHECK(strstr(e.msg, "'d.exr' is part 2/3 again") != NULL);
    /* incomplete: the requested samples differ from the parts' */
    CHECK(atmo_part_merge(parts, paths, N, S + 1, &merged, &e) == ATMO_ERR_USAGE);
    CHECK(strstr(e.msg, "incomplete") != NULL);
    /* foreign: another scene's part 2 */
    make_part(&parts[N], W, H, 2, N, S, "{\"scene\": 2}");
    atmo_part mixed[3] = {parts[0], parts[N], parts[2]};
    CHECK(atmo_part_merge(mixed, paths, 3, S, &merged, &e) == ATMO_ERR_USAGE);
    CHECK(strstr(e.msg, "'b.exr' is a part of another scene") != NULL);
    for (int i = 0; i <= N; i++)
        atmo_part_free(&parts[i]);
}

int main(void)
{
    static const int widths[] = {1, 17, 64, 100}, heights[] = {1, 15, 16, 17, 40, 100};
    static const int sizes[] = {8, 13, 16, 64};
    for (int a = 0; a < 4; a++)
        for (int b = 0; b < 6; b++)
            for (int c = 0; c < 4; c++) {
                int bands = (heights[b] + ATMO_PART_BAND_ROWS - 1) / ATMO_PART_BAND_ROWS;
                for (int n = 0; n <= bands && n <= 7; n++)
                    check_split(widths[a], heights[b], sizes[c], n);
            }
    atmo_tiles t;
    atmo_err e = {{0}};
    CHECK(atmo_tiles_init_part(&t, 64, 40, 16, 1, 6, &e) == ATMO_ERR_USAGE); /* 5 bands */
    CHECK(atmo_tiles_init_part(&t, 64, 40, 16, 0, 2, &e) == ATMO_ERR_USAGE);
    CHECK(atmo_tiles_init_part(&t, 64, 40, 16, 3, 2, &e) == ATMO_ERR_USAGE);
    check_merge();
    return test_finish();
}
