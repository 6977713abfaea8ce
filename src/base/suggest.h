/* "Did you mean …?": the known name closest to a mistyped one. */
#ifndef OB_BASE_SUGGEST_H
#define OB_BASE_SUGGEST_H

#include <stddef.h>

/* Of names[0..count) (NULL entries skipped), the one nearest to word[0..len) in edit distance
 * (insertions, deletions, substitutions and transpositions of neighbours, case ignored), when it is
 * within max(1, len / 3) edits and nearer than every other: a slip of the keyboard, not another
 * word. NULL when none is that close. Never fails. */
const char *ob_suggest(const char *word, size_t len, const char *const *names, int count);

/* The same as text to append to a message, "; did you mean 'NAME'?" or "", into out (n bytes). */
const char *ob_suggest_text(const char *word, size_t len, const char *const *names, int count, char *out, size_t n);

#endif
