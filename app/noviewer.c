/* `obscura view` in a build without the viewer (cmake -DOB_VIEWER=OFF: no GLFW, no Dear ImGui).
 * Takes the place of app/view*.c, which CMake leaves out of such a build. */
#include "cli.h"

int cmd_view(int argc, char **argv)
{
    (void)argc;
    (void)argv;
    return cli_fail(EXIT_USAGE, "view: this build has no viewer (configured with -DOB_VIEWER=OFF; "
                                "rebuild with -DOB_VIEWER=ON, which needs GLFW 3 and Dear ImGui)");
}
