/* suggest.c — "did you mean" hints (atmo/suggest.h).
 *
 * The distance is the optimal string alignment distance (Levenshtein's three edits plus the
 * swap of two neighbouring characters, the commonest typing slip), computed case-insensitively
 * with three rolling rows. A hint is only worth giving when the word is plausibly a typo of
 * it, so a candidate must lie within a limit that grows with the word's length (about one edit
 * in three characters), or begin with the word (a name typed in part), or, for dotted keys,
 * be near the word after its group (a key given without its group). */
#include <ctype.h>
#include <string.h>
#include "atmo/suggest.h"

static size_t min3(size_t a, size_t b, size_t c)
{
    size_t m = a < b ? a : b;
    return m < c ? m : c;
}

size_t atmo_edit_distance(const char *a, const char *b)
{
    size_t la = strlen(a), lb = strlen(b);
    if (la > ATMO_SUGGEST_MAX_CHARS)
        la = ATMO_SUGGEST_MAX_CHARS;
    if (lb > ATMO_SUGGEST_MAX_CHARS)
        lb = ATMO_SUGGEST_MAX_CHARS;
    size_t rows[3][ATMO_SUGGEST_MAX_CHARS + 1];
    size_t *before = rows[0], *prev = rows[1], *cur = rows[2];
    for (size_t j = 0; j <= lb; j++)
        prev[j] = j;
    for (size_t i = 1; i <= la; i++) {
        cur[0] = i;
        int ca = tolower((unsigned char)a[i - 1]);
        for (size_t j = 1; j <= lb; j++) {
            int cb = tolower((unsigned char)b[j - 1]);
            cur[j] = min3(prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (ca != cb));
            if (i > 1 && j > 1 && ca == tolower((unsigned char)b[j - 2]) &&
                tolower((unsigned char)a[i - 2]) == cb && before[j - 2] + 1 < cur[j])
                cur[j] = before[j - 2] + 1;
        }
        size_t *t = before;
        before = prev;
        prev = cur;
        cur = t;
    }
    return prev[lb];
}

size_t atmo_suggest_limit(const char *word)
{
    size_t n = strlen(word);
    return n <= 4 ? 1 : n / 3 > 1 ? n / 3 : 1;
}

void atmo_suggest_begin(atmo_suggest *s, const char *word)
{
    s->word = word;
    s->best = NULL;
    s->best_distance = (size_t)-1;
}

static int starts_with(const char *text, const char *prefix)
{
    size_t n = strlen(prefix);
    for (size_t i = 0; i < n; i++)
        if (tolower((unsigned char)text[i]) != tolower((unsigned char)prefix[i]))
            return 0;
    return 1;
}

void atmo_suggest_offer(atmo_suggest *s, const char *candidate)
{
    size_t d = atmo_edit_distance(s->word, candidate);
    size_t limit = atmo_suggest_limit(s->word);
    const char *leaf = strchr(candidate, '.');
    if (leaf && !strchr(s->word, '.')) {
        size_t dl = atmo_edit_distance(s->word, leaf + 1) + 1;
        if (dl < d)
            d = dl;
        limit++;
    }
    if (d > limit && strlen(s->word) >= 3 && starts_with(candidate, s->word))
        d = limit;
    if (d <= limit && d < s->best_distance) {
        s->best = candidate;
        s->best_distance = d;
    }
}

const char *atmo_suggest_result(const atmo_suggest *s) { return s->best; }

const char *atmo_suggest_among(const char *word, const char *const *candidates)
{
    atmo_suggest s;
    atmo_suggest_begin(&s, word);
    for (const char *const *c = candidates; *c; c++)
        atmo_suggest_offer(&s, *c);
    return atmo_suggest_result(&s);
}
