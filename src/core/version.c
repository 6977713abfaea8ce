/* ob_version (obscura.h, "version"): the numbers this library was built with. */
#include "obscura/scene.h"

const char *ob_version(int *major, int *minor, int *patch)
{
    if (major) *major = OB_VERSION_MAJOR;
    if (minor) *minor = OB_VERSION_MINOR;
    if (patch) *patch = OB_VERSION_PATCH;
    return OB_VERSION_STRING;
}
