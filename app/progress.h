/* The CLI's progress reports: the library's own helper (src/base/progress.h), so that compare,
 * tune, bench, test mode and the reference renderer they call all report the same way. The CLI
 * compiles src/base/progress.c itself (CMakeLists.txt): the library's copy is hidden. */
#ifndef OB_APP_PROGRESS_H
#define OB_APP_PROGRESS_H
#include "../src/base/progress.h"
#endif
