/* "Did you mean …?" (suggest.h): the optimal string alignment distance (Damerau 1964's four
 * operations, each substring edited once), which counts "vboa" for "vbao" as one slip. */
#include "suggest.h"

#include <ctype.h>
#include <stdbool.h>
#include <stdio.h>
#include <string.h>

enum { SUGGEST_MAX = 64 }; /* longer words are no slip of the keyboard: no suggestion */

static size_t distance(const char *a, size_t la, const char *b, size_t lb)
{
    /* Three rows of the dynamic programme: i - 2, i - 1 and i. */
    size_t rows[3][SUGGEST_MAX + 1];
    for (size_t j = 0; j <= lb; ++j) rows[1][j] = j;
    for (size_t i = 1; i <= la; ++i) {
        size_t *cur = rows[(i + 1) % 3], *prev = rows[i % 3], *prev2 = rows[(i + 2) % 3];
        cur[0] = i;
        for (size_t j = 1; j <= lb; ++j) {
            const int ca = tolower((unsigned char)a[i - 1]), cb = tolower((unsigned char)b[j - 1]);
            size_t best = prev[j - 1] + (ca != cb);
            if (prev[j] + 1 < best) best = prev[j] + 1;
            if (cur[j - 1] + 1 < best) best = cur[j - 1] + 1;
            if (i > 1 && j > 1 && ca == tolower((unsigned char)b[j - 2]) && tolower((unsigned char)a[i - 2]) == cb &&
                prev2[j - 2] + 1 < best)
                best = prev2[j - 2] + 1;
            cur[j] = best;
        }
    }
    return rows[(la + 1) % 3][lb];
}

const char *ob_suggest(const char *word, size_t len, const char *const *names, int count)
{
    if (!word || !names || len == 0 || len > SUGGEST_MAX) return NULL;
    const size_t most = len / 3 > 1 ? len / 3 : 1;
    const char *best = NULL;
    size_t best_d = most + 1;
    bool tie = false;
    for (int i = 0; i < count; ++i) {
        if (!names[i]) continue;
        const size_t ln = strlen(names[i]);
        if (ln > SUGGEST_MAX || (ln > len ? ln - len : len - ln) > most) continue;
        const size_t d = distance(word, len, names[i], ln);
        if (d < best_d) {
            best = names[i];
            best_d = d;
            tie = false;
        } else if (d == best_d && best && strcmp(best, names[i]) != 0) {
            tie = true;
        }
    }
    return best && !tie && best_d > 0 ? best : NULL;
}

const char *ob_suggest_text(const char *word, size_t len, const char *const *names, int count, char *out, size_t n)
{
    const char *s = ob_suggest(word, len, names, count);
    if (n) out[0] = '\0';
    if (s && n) snprintf(out, n, "; did you mean '%s'?", s);
    return out;
}
