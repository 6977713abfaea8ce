// The public headers from C++: they compile with -Wall -Wextra -Werror -pedantic as C++11, their
// functions link with C names (extern "C") from libobscura.so and libobscura-eval.so, and a few of
// them work. eval.h includes scene.h, which includes obscura.h; each is also included on its own
// first, so that each stands alone.
#include <obscura/obscura.h>
#include <obscura/scene.h>
#include <obscura/eval.h>

#include <cmath>
#include <cstdio>
#include <cstring>

static int failures = 0;

static void check(bool ok, const char *what)
{
    if (!ok) {
        std::printf("FAIL: %s\n", what);
        ++failures;
    }
}

int main()
{
    check(std::strcmp(ob_error_name(OB_ERR_UNKNOWN_METHOD), "OB_ERR_UNKNOWN_METHOD") == 0, "ob_error_name");
    check(ob_method_count() > 0 && ob_find_method("ssao") >= 0, "the registry has ssao");
    check(ob_find_filter("geometry") >= 0, "the filter registry has geometry");

    ob_settings s;
    std::memset(&s, 0, sizeof s);
    check(ob_settings_init(&s, "hbao") == OB_OK, "ob_settings_init(hbao)");
    check(ob_settings_set(&s, "radius=0.25") == OB_OK, "ob_settings_set");
    check(std::fabs(ob_settings_get(&s, "radius") - 0.25f) < 1e-6f, "ob_settings_get");
    check(ob_settings_set_filter(&s, "gaussian") == OB_OK, "ob_settings_set_filter");

    const char *msg = nullptr;
    check(ob_settings_init(&s, "no-such-method") == OB_ERR_UNKNOWN_METHOD, "unknown method refused");
    check(ob_get_error(&msg) == OB_ERR_UNKNOWN_METHOD && msg && msg[0], "ob_get_error names it");
    check(ob_get_error(nullptr) == OB_OK, "ob_get_error clears");

    ob_scene_desc desc;
    std::memset(&desc, 0, sizeof desc);
    desc.name = "corner";
    ob_scene *scene = ob_load_scene(&desc); // libobscura-eval, the built-in scene from libobscura
    check(scene && ob_query_scene_stats(scene).triangles > 0, "ob_load_scene(corner)");
    ob_destroy_scene(scene);

    const char *dir = ob_data_dir();
    check(dir != nullptr && dir[0] != '\0', "ob_data_dir");
    std::printf("header_cxx: %d methods, %d filters, data %s: %s\n", ob_method_count(), ob_filter_count(), dir,
                failures ? "FAILED" : "ok");
    return failures;
}
