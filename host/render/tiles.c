/* tiles.c — the tile scheduler (atmo/tiles.h).
 *
 * A launch is a rectangle of whole tiles that all hold the same number of samples: a run of
 * consecutive tiles within one tile row, or, from a row's first tile, whole tile rows. Its size
 * follows one adapted quantity, the work per launch in tile-samples (tiles x samples, where an
 * edge tile counts by its share of a full tile's pixels): after a launch that did u tile-samples
 * in m ms, the work that fills the budget is u * budget / m. Under the budget the work grows to
 * that (at most doubled per launch, since one launch's timing is noisy and the first carries
 * the driver's one-time compile); over it, it shrinks to that. The work goes to tiles first (up
 * to every tile, or max_tiles), then to samples per launch (up to max_batch): a launch then
 * covers as much of the image as the budget allows before any pixel gets a second sample, and
 * a fast scene needs a few launches per sample pass instead of one per tile. */
#include <stdlib.h>
#include <string.h>
#include "atmo/tiles.h"

int atmo_tiles_init(atmo_tiles *t, int width, int height, int size, atmo_err *e)
{
    memset(t, 0, sizeof *t);
    if (width < 1 || height < 1 || size < 1)
        return atmo_fail(e, ATMO_ERR_USAGE, "tiles of %d px for a %dx%d image: sizes must be > 0",
                         size, width, height);
    t->width = width;
    t->height = height;
    t->size = size;
    t->columns = (width + size - 1) / size;
    t->count = t->columns * ((height + size - 1) / size);
    t->batch = 1;
    t->group = 1;
    t->samples = calloc((size_t)t->count, sizeof *t->samples);
    if (!t->samples)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory for %d tiles", t->count);
    return ATMO_OK;
}

void atmo_tiles_free(atmo_tiles *t)
{
    free(t->samples);
    memset(t, 0, sizeof *t);
}

void atmo_tiles_reset(atmo_tiles *t)
{
    memset(t->samples, 0, sizeof *t->samples * (size_t)t->count);
    t->cursor = 0;
}

/* 1 when every tile of tile row `row` holds n samples. */
static int row_holds(const atmo_tiles *t, int row, int n)
{
    for (int c = 0; c < t->columns; c++)
        if (t->samples[row * t->columns + c] != n)
            return 0;
    return 1;
}

int atmo_tiles_next(atmo_tiles *t, int target, atmo_tile *launch)
{
    int rows = t->count / t->columns;
    for (int k = 0; k < t->count; k++) {
        int i = (t->cursor + k) % t->count;
        int n = t->samples[i], remaining = target - n;
        if (remaining <= 0)
            continue;
        int column = i % t->columns, row = i / t->columns, across = 1, down = 1;
        if (column == 0 && t->group >= t->columns) {
            int want = t->group / t->columns;
            down = 0;
            while (down < want && row + down < rows && row_holds(t, row + down, n))
                down++;
            across = down > 0 ? t->columns : 1;
            down = down > 0 ? down : 1;
        }
        if (across == 1)
            while (across < t->group && column + across < t->columns &&
                   t->samples[i + across] == n)
                across++;
        launch->index = i;
        launch->tiles_across = across;
        launch->tiles_down = down;
        launch->x = column * t->size;
        launch->y = row * t->size;
        launch->w = t->width - launch->x < across * t->size ? t->width - launch->x
                                                              : across * t->size;
        launch->h = t->height - launch->y < down * t->size ? t->height - launch->y
                                                             : down * t->size;
        launch->sample_begin = n;
        launch->sample_count = t->batch < remaining ? t->batch : remaining;
        launch->samples = n + launch->sample_count;
        return 1;
    }
    return 0;
}

void atmo_tiles_done(atmo_tiles *t, atmo_tile *launch, double ms, double budget_ms, int max_batch,
                     int max_tiles)
{
    int first = launch->index;
    for (int r = 0; r < launch->tiles_down; r++)
        for (int c = 0; c < launch->tiles_across; c++)
            t->samples[first + r * t->columns + c] = launch->samples;
    int last = first + (launch->tiles_down - 1) * t->columns + launch->tiles_across - 1;
    t->cursor = (last + 1) % t->count;

    double work = (double)t->group * t->batch;
    double done = (double)launch->w * launch->h * launch->sample_count /
                  ((double)t->size * t->size);
    double fill = done * budget_ms / (ms > 1e-3 ? ms : 1e-3);
    double next = ms > budget_ms ? fill : fill > 2.0 * work ? 2.0 * work : fill > work ? fill : work;
    int tiles = max_tiles > 0 && max_tiles < t->count ? max_tiles : t->count;
    if (next <= tiles) {
        t->group = next < 1.0 ? 1 : (int)next;
        t->batch = 1;
    } else {
        t->group = tiles;
        t->batch = (int)(next / tiles);
    }
    if (max_batch > 0 && t->batch > max_batch)
        t->batch = max_batch;
}

int atmo_tiles_pixel_samples(const atmo_tiles *t, int x, int y)
{
    return t->samples[(y / t->size) * t->columns + x / t->size];
}

void atmo_tiles_range(const atmo_tiles *t, int *min, int *max)
{
    *min = t->samples[0];
    *max = t->samples[0];
    for (int i = 1; i < t->count; i++) {
        *min = t->samples[i] < *min ? t->samples[i] : *min;
        *max = t->samples[i] > *max ? t->samples[i] : *max;
    }
}
