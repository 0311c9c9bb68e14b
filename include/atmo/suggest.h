/* suggest.h — "did you mean" hints (host/base/suggest.c): the candidate nearest to a mistyped
 * word by edit distance, or none when nothing is near enough to be a plausible typo. */
#ifndef ATMO_SUGGEST_H
#define ATMO_SUGGEST_H
#include <stddef.h>

/* Optimal-string-alignment distance (Damerau-Levenshtein without repeated edits of one
 * substring): insertions, deletions, substitutions and swaps of two neighbours, ignoring case.
 * Words are compared on their first ATMO_SUGGEST_MAX_CHARS characters. */
#define ATMO_SUGGEST_MAX_CHARS 63
size_t atmo_edit_distance(const char *a, const char *b);

/* Offer candidates one at a time; the result is the nearest accepted one (the first of equals).
 * A candidate is accepted when its distance to the word is at most atmo_suggest_limit(word), or
 * when it begins with the word (at least 3 characters: a name typed in part), or, for a dotted
 * key "group.leaf", when the word is near its leaf (the group left out: one edit more). */
typedef struct atmo_suggest {
    const char *word;
    const char *best;
    size_t best_distance;
} atmo_suggest;

/* The most edits a word of this length may be off by: 1 up to 4 characters, then a third of
 * the length (2 from 6 characters, 3 from 9, ...). */
size_t atmo_suggest_limit(const char *word);
void atmo_suggest_begin(atmo_suggest *s, const char *word);
void atmo_suggest_offer(atmo_suggest *s, const char *candidate);
/* The nearest accepted candidate, or NULL. */
const char *atmo_suggest_result(const atmo_suggest *s);
/* The nearest of a NULL-terminated list, or NULL. */
const char *atmo_suggest_among(const char *word, const char *const *candidates);

#endif
