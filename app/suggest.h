/* "Did you mean …?" for the CLI: the library's own helper (src/base/suggest.h), compiled into the
 * CLI from the same file (CMakeLists.txt), as progress.h is. */
#ifndef OB_APP_SUGGEST_H
#define OB_APP_SUGGEST_H
#include "../src/base/suggest.h"
#endif
