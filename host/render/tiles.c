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
 * a fast scene needs a few launches per sample pass instead of one per tile. Whole tile rows go
 * into one launch only where they touch (a part's bands are apart: atmo/tiles.h).
 *
 * The first pass over the image (a tile's first sample) takes its launches from the tile rows
 * in turn, in the bit-reversed order of their indices (top, bottom, middle, the quarters, ...),
 * each launch within one row from its first tile without a sample, so the tiles timed first
 * sample the whole image from top to bottom: a sky row costs a fraction of a terrain row, and
 * the session's estimate of the time left (session.c) prices the tiles not yet timed from the
 * nearest rows timed. Later passes go in image order. The order of launches changes no pixel:
 * each pixel's samples still arrive in sample order. */
#include <stdlib.h>
#include <string.h>
#include "atmo/tiles.h"

int atmo_part_of_row(int y, int parts) { return y / ATMO_PART_BAND_ROWS % parts + 1; }

/* The tile rows of the part's bands (of the whole image for parts = 0), in image order. */
static int tile_rows(atmo_tiles *t, atmo_err *e)
{
    int band = t->parts ? ATMO_PART_BAND_ROWS : t->height;
    t->row_y = malloc(sizeof *t->row_y * (size_t)t->height);
    t->row_h = malloc(sizeof *t->row_h * (size_t)t->height);
    t->row_of_y = malloc(sizeof *t->row_of_y * (size_t)t->height);
    if (!t->row_y || !t->row_h || !t->row_of_y)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory for the tiles of %d rows", t->height);
    for (int b0 = 0; b0 < t->height; b0 += band) {
        int b1 = b0 + band < t->height ? b0 + band : t->height;
        int mine = !t->parts || atmo_part_of_row(b0, t->parts) == t->part;
        for (int y = b0; y < b1; y += t->size) {
            int h = b1 - y < t->size ? b1 - y : t->size;
            if (mine) {
                t->row_y[t->rows] = y;
                t->row_h[t->rows] = h;
            }
            for (int k = y; k < y + h; k++)
                t->row_of_y[k] = mine ? t->rows : -1;
            t->rows += mine;
        }
    }
    return ATMO_OK;
}

int atmo_tiles_init_part(atmo_tiles *t, int width, int height, int size, int part, int parts,
                         atmo_err *e)
{
    memset(t, 0, sizeof *t);
    if (width < 1 || height < 1 || size < 1)
        return atmo_fail(e, ATMO_ERR_USAGE, "tiles of %d px for a %dx%d image: sizes must be > 0",
                         size, width, height);
    int bands = (height + ATMO_PART_BAND_ROWS - 1) / ATMO_PART_BAND_ROWS;
    if (parts < 0 || (parts > 0 && (part < 1 || part > parts)))
        return atmo_fail(e, ATMO_ERR_USAGE, "part %d of %d: a part is I/N with 1 <= I <= N",
                         part, parts);
    if (parts > bands)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "%d parts of a %d-row image: it has only %d bands of %d rows, one per "
                         "part at least; use at most %d parts",
                         parts, height, bands, ATMO_PART_BAND_ROWS, bands);
    t->width = width;
    t->height = height;
    t->size = size;
    t->part = part;
    t->parts = parts;
    int rc = tile_rows(t, e);
    if (rc) {
        atmo_tiles_free(t);
        return rc;
    }
    t->columns = (width + size - 1) / size;
    t->count = t->columns * t->rows;
    t->batch = 1;
    t->group = 1;
    t->samples = calloc((size_t)t->count, sizeof *t->samples);
    t->converged = calloc((size_t)t->count, 1);
    if (!t->samples || !t->converged) {
        atmo_tiles_free(t);
        return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory for %d tiles", t->count);
    }
    return ATMO_OK;
}

int atmo_tiles_init(atmo_tiles *t, int width, int height, int size, atmo_err *e)
{
    return atmo_tiles_init_part(t, width, height, size, 0, 0, e);
}

void atmo_tiles_get(const atmo_tiles *t, int index, atmo_tile *tile)
{
    int row = index / t->columns;
    tile->index = index;
    tile->tiles_across = tile->tiles_down = 1;
    tile->x = index % t->columns * t->size;
    tile->y = t->row_y[row];
    tile->w = t->width - tile->x < t->size ? t->width - tile->x : t->size;
    tile->h = t->row_h[row];
    tile->sample_begin = t->samples[index];
    tile->sample_count = 0;
    tile->samples = t->samples[index];
}

void atmo_tiles_free(atmo_tiles *t)
{
    free(t->samples);
    free(t->row_of_y);
    free(t->row_h);
    free(t->row_y);
    free(t->converged);
    memset(t, 0, sizeof *t);
}

void atmo_tiles_reset(atmo_tiles *t)
{
    memset(t->samples, 0, sizeof *t->samples * (size_t)t->count);
    memset(t->converged, 0, (size_t)t->count);
    t->cursor = 0;
    t->spread = 0;
}

int atmo_tiles_is_checkpoint(int n)
{
    return n >= ATMO_TILES_FIRST_CHECKPOINT && (n & (n - 1)) == 0;
}

void atmo_tiles_converge(atmo_tiles *t, int index) { t->converged[index] = 1; }

/* The first checkpoint after n samples. */
static int next_checkpoint(int n)
{
    int c = ATMO_TILES_FIRST_CHECKPOINT;
    while (c <= n && c < (1 << 30))
        c *= 2;
    return c;
}

/* 1 when every tile of tile row `row` holds n samples and none has converged. */
static int row_holds(const atmo_tiles *t, int row, int n)
{
    for (int c = 0; c < t->columns; c++)
        if (t->samples[row * t->columns + c] != n || t->converged[row * t->columns + c])
            return 0;
    return 1;
}

/* The first pass's next tile: the first tile without a sample in the row at or after position
 * t->spread of the rows' bit-reversed order (cyclic), which then moves past that row; -1 when
 * every tile has a sample (or has converged). */
static int first_pass_tile(atmo_tiles *t)
{
    int bits = 0;
    while ((1 << bits) < t->rows)
        bits++;
    for (int k = 0; k < (1 << bits); k++) {
        int j = (t->spread + k) % (1 << bits), row = 0;
        for (int b = 0; b < bits; b++) /* j's bits reversed */
            row |= (j >> b & 1) << (bits - 1 - b);
        if (row >= t->rows)
            continue;
        for (int c = 0; c < t->columns; c++)
            if (t->samples[row * t->columns + c] == 0 && !t->converged[row * t->columns + c]) {
                t->spread = (j + 1) % (1 << bits);
                return row * t->columns + c;
            }
    }
    return -1;
}

int atmo_tiles_next(atmo_tiles *t, int target, atmo_tile *launch)
{
    int first = target > 0 ? first_pass_tile(t) : -1;
    for (int k = 0; k < t->count; k++) {
        int i = first >= 0 ? first : (t->cursor + k) % t->count;
        int n = t->samples[i], remaining = target - n;
        if (remaining <= 0 || t->converged[i])
            continue;
        if (t->checkpoints && next_checkpoint(n) - n < remaining)
            remaining = next_checkpoint(n) - n;
        int column = i % t->columns, row = i / t->columns, across = 1, down = 1;
        int h = t->row_h[row];
        if (column == 0 && n > 0 && t->group >= t->columns && row_holds(t, row, n)) {
            int want = t->group / t->columns;
            while (down < want && row + down < t->rows &&
                   t->row_y[row + down] == t->row_y[row] + h && row_holds(t, row + down, n))
                h += t->row_h[row + down++];
            across = t->columns;
        }
        if (across == 1)
            while (across < t->group && column + across < t->columns &&
                   t->samples[i + across] == n && !t->converged[i + across])
                across++;
        launch->index = i;
        launch->tiles_across = across;
        launch->tiles_down = down;
        launch->x = column * t->size;
        launch->y = t->row_y[row];
        launch->w = t->width - launch->x < across * t->size ? t->width - launch->x
                                                              : across * t->size;
        launch->h = h;
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
    int row = t->row_of_y[y];
    return row < 0 ? 0 : t->samples[row * t->columns + x / t->size];
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
