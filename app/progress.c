/* The CLI's copy of the library's progress helper: one source for both. The library is built with
 * hidden visibility, so its copy is not exported and this one cannot clash with it. */
#include "../src/core/progress.c"
