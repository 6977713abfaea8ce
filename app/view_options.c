/* obscura view's options: the option table, its checks and the help text (what `obscura view
 * --help` prints is the whole user-facing contract: options, keys and script events). Parsing
 * happens before any window or scene exists, so a usage error costs nothing. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "view.h"

static void view_usage(FILE *f)
{
    fputs("usage: obscura view [options]\n"
          "\n"
          "An interactive window: fly the camera, switch methods, tune every parameter live and\n"
          "watch the GPU time of each pass. Needs a display (on a server: xvfb-run -a obscura view).\n"
          "\n"
          "  --scene NAME|PATH     as for render (default fzk-haus)\n"
          "  --sidecar FILE        scene sidecar JSON; --up y|z the model's up axis\n"
          "  --camera NAME|INDEX   the preset to start from (default: the first)\n"
          "  --method NAME         the method to start with (default ssao)\n"
          "  --filter NAME         the filter to start with (default geometry)\n"
          "  --quality Q           low|medium|high|ultra, applied to each method picked\n"
          "  --set M.P=V           a parameter, validated (repeatable)\n"
          "  --ao-scale S          1, 0.5 or 0.25; --adaptive on|off\n"
          "  --shadow none|hard|pcf|vsm   --shadow-size N   --hdr on|off   --env FILE.hdr\n"
          "  --size WxH            the window's size (default 1280x720)\n"
          "  --vsync on|off        (default on; test mode turns it off)\n"
          "  --gui on|off          show the panel at start (default on)\n"
          "  --shots DIR           where screenshots go (default screenshots/; test mode: beside --log)\n"
          "  --script FILE         replay timed input events (see below), then keep running\n"
          "  --test-mode           cycle every camera preset x every method, then exit:\n"
          "    --seconds S         time per camera x method (default 5)\n"
          "    --cycles N          times through the whole set (default 3)\n"
          "    --methods A,B,..    the methods to cycle (default all, none included)\n"
          "    --log FILE.csv      one row per camera x method: average FPS and ms per pass\n"
          "                        (required), and a screenshot each in FILE's directory\n"
          "\n"
          "keys: W A S D move, Q E down/up, Shift 4x faster, right mouse button held: look,\n"
          "      scroll: zoom (field of view), 1-9 camera presets, Tab next preset, L lock the\n"
          "      camera, M / Shift+M next / previous method, V / Shift+V next / previous view,\n"
          "      F1 or H panel on/off, F3 vsync, P or F12 screenshot, R reload shaders (development\n"
          "      builds), Esc quit\n"
          "\n"
          "script lines: TIME EVENT ARGS, TIME in seconds on a clock that advances 1/30 s per frame\n"
          "  key NAME down|up|press       NAME: A-Z, 0-9, TAB, ESCAPE, SPACE, LEFT_SHIFT, F1-F12\n"
          "  mouse left|right down|up     move X Y (cursor, pixels)    scroll DY\n"
          "  method NAME   filter NAME   set M.P=V   camera NAME|INDEX   view NAME\n"
          "  resize W H   screenshot FILE.png   quit (as Esc)   close (as the window's close button)\n",
          f);
}


int parse_view_opts(int argc, char **argv, view_opts *o)
{
    *o = (view_opts){.scene = "fzk-haus", .method = "ssao", .filter = "geometry", .ao_scale = 1.0f, .vsync = true,
                     .gui = true, .shadow_method = -1, .shadow_size = -1, .width = 1280, .height = 720,
                     .cycles = 3, .seconds = 5.0f};
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i];
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            view_usage(stdout);
            return -1;
        }
        if (!strcmp(a, "--test-mode")) {
            o->test_mode = true;
            continue;
        }
        static const char *const with_value[] = {"--scene", "--sidecar", "--camera", "--method", "--filter", "--env",
                                                 "--shots", "--script", "--log", "--methods", "--set", "--up",
                                                 "--quality", "--ao-scale", "--adaptive", "--vsync", "--gui", "--hdr",
                                                 "--shadow", "--shadow-size", "--size", "--seconds", "--cycles"};
        bool known = false;
        for (size_t k = 0; k < sizeof with_value / sizeof with_value[0]; ++k) known = known || !strcmp(a, with_value[k]);
        if (!known) return cli_fail(EXIT_USAGE, "unknown option '%s' (see obscura view --help)", a);
        if (i + 1 >= argc) return cli_fail(EXIT_USAGE, "%s: missing value (see obscura view --help)", a);
        const char *v = argv[++i];
        if (!strcmp(a, "--scene")) o->scene = v;
        else if (!strcmp(a, "--sidecar")) o->sidecar = v;
        else if (!strcmp(a, "--camera")) o->camera = v;
        else if (!strcmp(a, "--method")) o->method = v;
        else if (!strcmp(a, "--filter")) o->filter = v;
        else if (!strcmp(a, "--env")) o->env = v;
        else if (!strcmp(a, "--shots")) o->shots = v;
        else if (!strcmp(a, "--script")) o->script = v;
        else if (!strcmp(a, "--log")) o->log = v;
        else if (!strcmp(a, "--methods")) o->methods = v;
        else if (!strcmp(a, "--set")) {
            if (o->set_count >= 64) return cli_fail(EXIT_USAGE, "--set: too many");
            o->sets[o->set_count++] = v;
        } else if (!strcmp(a, "--up")) {
            if (!cli_parse_up(v, &o->up)) return cli_fail(EXIT_USAGE, "--up: expected y or z, got '%s'", v);
        } else if (!strcmp(a, "--quality")) {
            o->quality_samples = ob_quality_samples(v);
            if (o->quality_samples < 0) return cli_fail(EXIT_USAGE, "--quality: expected low, medium, high or ultra, got '%s'", v);
        } else if (!strcmp(a, "--ao-scale")) {
            if (!cli_parse_ao_scale(v, &o->ao_scale))
                return cli_fail(EXIT_USAGE, "--ao-scale: expected 1, 0.5 or 0.25, got '%s'", v);
        } else if (!strcmp(a, "--adaptive")) {
            if (!cli_parse_on_off(v, &o->adaptive)) return cli_fail(EXIT_USAGE, "--adaptive: expected on or off, got '%s'", v);
        } else if (!strcmp(a, "--vsync")) {
            if (!cli_parse_on_off(v, &o->vsync)) return cli_fail(EXIT_USAGE, "--vsync: expected on or off, got '%s'", v);
        } else if (!strcmp(a, "--gui")) {
            if (!cli_parse_on_off(v, &o->gui)) return cli_fail(EXIT_USAGE, "--gui: expected on or off, got '%s'", v);
        } else if (!strcmp(a, "--hdr")) {
            bool on = true;
            if (!cli_parse_on_off(v, &on)) return cli_fail(EXIT_USAGE, "--hdr: expected on or off, got '%s'", v);
            o->hdr_off = !on;
        } else if (!strcmp(a, "--shadow")) {
            ob_shadow_method m = OB_SHADOW_NONE;
            if (!cli_parse_shadow(v, &m)) return cli_fail(EXIT_USAGE, "--shadow: expected none, hard, pcf or vsm, got '%s'", v);
            o->shadow_method = (int)m;
        } else if (!strcmp(a, "--shadow-size")) {
            char *end = NULL;
            long n = strtol(v, &end, 10);
            if (end == v || *end || n < 16 || n > 16384) return cli_fail(EXIT_USAGE, "--shadow-size: expected 16..16384, got '%s'", v);
            o->shadow_size = (int)n;
        } else if (!strcmp(a, "--size")) {
            if (!cli_parse_size(v, &o->width, &o->height) || o->width < 16 || o->height < 16 || o->width > 16384 ||
                o->height > 16384)
                return cli_fail(EXIT_USAGE, "--size: expected WIDTHxHEIGHT, each 16..16384, got '%s'", v);
        } else if (!strcmp(a, "--seconds")) {
            if (!cli_parse_float(v, &o->seconds) || !(o->seconds >= 0.0f) || o->seconds > 3600.0f)
                return cli_fail(EXIT_USAGE, "--seconds: expected 0..3600, got '%s'", v);
        } else if (!strcmp(a, "--cycles")) {
            char *end = NULL;
            long n = strtol(v, &end, 10);
            if (end == v || *end || n < 1 || n > MAX_CYCLES) return cli_fail(EXIT_USAGE, "--cycles: expected 1..%d, got '%s'", MAX_CYCLES, v);
            o->cycles = (int)n;
        } else {
            return cli_fail(EXIT_USAGE, "unknown option '%s' (see obscura view --help)", a);
        }
    }
    if (o->test_mode && !o->log) return cli_fail(EXIT_USAGE, "--test-mode needs --log FILE.csv");
    if (!o->test_mode && (o->log || o->methods))
        return cli_fail(EXIT_USAGE, "--log and --methods belong to --test-mode");
    if (o->test_mode && o->script) return cli_fail(EXIT_USAGE, "--test-mode and --script exclude each other");
    if (o->log && !cli_output_writable(o->log))
        return cli_fail(EXIT_OUTPUT, "cannot write %s: its directory does not exist or is not writable", o->log);
    return 0;
}
