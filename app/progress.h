/* The CLI's progress reports: the library's own helper (src/core/progress.h), so that compare,
 * tune, bench, test mode and the reference renderer they call all report the same way. */
#ifndef OB_APP_PROGRESS_H
#define OB_APP_PROGRESS_H
#include "../src/core/progress.h"
#endif
