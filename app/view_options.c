/* obscura view's options: the option table, its checks and the help text (what `obscura view
 * --help` prints is the whole user-facing contract: options, keys and script events). Parsing
 * happens before any window or scene exists, so a usage error costs nothing. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "view.h"

static void view_usage(FILE *f, const cli_common *c)
{
    fputs("usage: obscura view [options]\n"
          "\n"
          "An interactive window: fly the camera, switch methods, tune every parameter live and\n"
          "watch the GPU and CPU time of each pass. Needs a display (on a server: xvfb-run -a obscura\n"
          "view). --size is the window's size: the panel takes a column at its right edge (drag its\n"
          "left edge to resize it) and the picture the rest, with the window's shape; --camera the\n"
          "preset to start from; --quality applies to each method picked; a --set for any method\n"
          "goes to that method's values.\n"
          "\n"
          "  --vsync on|off        (default on; test mode turns it off)\n"
          "  --gui on|off          show the panel and the overlay at start (default on; off: the\n"
          "                        picture takes the whole window)\n"
          "  --shots DIR           where screenshots go (default screenshots/; test mode: beside --log)\n"
          "  --script FILE         replay timed input events (see below), then keep running\n"
          "  --stereo MODE         both eyes of a headset (Belonogov 2018 §5.2), each its own renderer:\n"
          "                        mirror (side by side, each eye half the picture) or single (the\n"
          "                        left eye in the whole picture); the profiler shows both eyes'\n"
          "                        GPU time against the 11.1 ms (90 Hz) budget\n"
          "  --ipd D               --stereo: eye separation in world units (default 0.064)\n"
          "  --test-mode           cycle every camera preset x every method, then exit; a row per\n"
          "                        camera as it finishes (defaults: under a minute on 2 cores); no\n"
          "                        panel, the picture is the whole window:\n"
          "    --seconds S         time per camera x method (default 0.5; Puri 2024: 5)\n"
          "    --cycles N          times through the whole set (default 1; Puri 2024: 3)\n"
          "                        --size defaults to 640x360 in test mode\n"
          "    --methods A,B,..    the methods to cycle (default all, none included)\n"
          "    --log FILE.csv      one row per camera x method: average FPS, GPU ms per pass\n"
          "                        (PASS_ms), the stereo columns, then CPU ms per pass\n"
          "                        (PASS_cpu_ms) (required), and a screenshot each in FILE's\n"
          "                        directory\n",
          f);
    cli_common_usage(f, c);
    fputs("\n"
          "keys: W A S D move, Q E down/up, Shift 4x faster, right mouse button held: look and\n"
          "      scroll: zoom (field of view), both pressed or turned on the picture, 1-9 camera\n"
          "      presets, Tab next preset, L lock the camera, M / Shift+M next / previous method,\n"
          "      V / Shift+V next / previous view, F1 or H panel on/off, F3 vsync, P or F12 screenshot, R reload shaders (development\n"
          "      builds), T temporal accumulation on/off, Space play/pause --path/--orbit (starts\n"
          "      playing), G reference view (the Embree AO_R of this camera beside the method's AO\n"
          "      and the signed error, with the RMSE; cached), X albedo textures on/off, Esc quit\n"
          "\n"
          "script lines: TIME EVENT ARGS, TIME in seconds on a clock that advances 1/30 s per frame\n"
          "  key NAME down|up|press       NAME: A-Z, 0-9, TAB, ESCAPE, SPACE, LEFT_SHIFT, F1-F12\n"
          "  mouse left|right down|up     move X Y (cursor, pixels)    scroll DY\n"
          "                               (the panel gets them first, as a person's mouse; the\n"
          "                               camera only on the picture)\n"
          "  method NAME   filter NAME   set M.P=V   camera NAME|INDEX   view NAME\n"
          "  stereo mono|mirror|single\n"
          "  resize W H   quit (as Esc)   close (as the window's close button)\n"
          "  screenshot FILE.png      the picture alone, at its size (no panel, bars, overlay or\n"
          "                           messages)\n"
          "  screenshot_ui FILE.png   the window as it shows, panel and overlay included\n"
          "  The clock stands still while the reference view traces, so what follows sees it done.\n",
          f);
}


int parse_view_opts(int argc, char **argv, view_opts *o)
{
    /* Test mode's defaults finish FZK-Haus's 4 cameras x 11 methods in under a minute on 2 cores
     * with llvmpipe (issue 20: 5 s x 3 cycles at 1280x720 ran 7 minutes with no output); the
     * Puri 2024's 5 s x 3 cycles are an option away. */
    *o = (view_opts){.vsync = true, .gui = true, .cycles = 1, .seconds = 0.5f, .ipd = 0.064f};
    bool has_ipd = false;
    cli_common *c = &o->common;
    cli_common_init(c, "view", CLI_TAKES_SCENE | CLI_TAKES_CAMERA | CLI_TAKES_PATH);
    c->scene = "cornell"; /* every command's default: built in, always there */
    c->width = 1280;
    c->height = 720;
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i];
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            view_usage(stdout, c);
            return -1;
        }
        if (!strcmp(a, "--test-mode")) {
            o->test_mode = true;
            continue;
        }
        int taken = cli_common_option(c, argc, argv, &i);
        if (taken == CLI_TAKEN) continue;
        if (taken != CLI_NOT_MINE) return taken;
        static const char *const with_value[] = {"--shots", "--script", "--log", "--methods", "--vsync",
                                                 "--gui",   "--seconds", "--cycles", "--stereo", "--ipd"};
        bool known = false;
        for (size_t k = 0; k < sizeof with_value / sizeof with_value[0]; ++k) known = known || !strcmp(a, with_value[k]);
        if (!known) return cli_unknown_option("view", a, view_usage, c);
        if (i + 1 >= argc) return cli_fail(EXIT_USAGE, "%s: missing value (see obscura view --help)", a);
        const char *v = argv[++i];
        if (!strcmp(a, "--shots")) o->shots = v;
        else if (!strcmp(a, "--script")) o->script = v;
        else if (!strcmp(a, "--log")) o->log = v;
        else if (!strcmp(a, "--methods")) o->methods = v;
        else if (!strcmp(a, "--stereo")) {
            if (!strcmp(v, "mirror")) o->stereo = VIEW_MIRROR;
            else if (!strcmp(v, "single")) o->stereo = VIEW_SINGLE;
            else return cli_fail(EXIT_USAGE, "--stereo: expected mirror or single, got '%s'", v);
        } else if (!strcmp(a, "--ipd")) {
            if (!cli_parse_float(v, &o->ipd) || !(o->ipd > 0.0f) || !isfinite(o->ipd))
                return cli_fail(EXIT_USAGE, "--ipd: expected a positive number, got '%s'", v);
            has_ipd = true;
        } else if (!strcmp(a, "--vsync")) {
            if (!cli_parse_on_off(v, &o->vsync)) return cli_fail(EXIT_USAGE, "--vsync: expected on or off, got '%s'", v);
        } else if (!strcmp(a, "--gui")) {
            if (!cli_parse_on_off(v, &o->gui)) return cli_fail(EXIT_USAGE, "--gui: expected on or off, got '%s'", v);
        } else if (!strcmp(a, "--seconds")) {
            if (!cli_parse_float(v, &o->seconds) || !(o->seconds >= 0.0f) || o->seconds > 3600.0f)
                return cli_fail(EXIT_USAGE, "--seconds: expected 0..3600, got '%s'", v);
        } else {
            char *end = NULL;
            long n = strtol(v, &end, 10);
            if (end == v || *end || n < 1 || n > MAX_CYCLES) return cli_fail(EXIT_USAGE, "--cycles: expected 1..%d, got '%s'", MAX_CYCLES, v);
            o->cycles = (int)n;
        }
    }
    int code = cli_common_finish(c);
    if (code != 0) return code;
    if (c->width < 16 || c->height < 16 || c->width > 16384 || c->height > 16384)
        return cli_fail(EXIT_USAGE, "--size: expected a window of 16..16384 each way, got %dx%d", c->width, c->height);
    if (has_ipd && o->stereo == VIEW_MONO) return cli_fail(EXIT_USAGE, "--ipd needs --stereo mirror|single");
    if (o->test_mode && !o->log) return cli_fail(EXIT_USAGE, "--test-mode needs --log FILE.csv");
    if (o->test_mode && !c->has_size) {
        c->width = 640;
        c->height = 360;
    }
    if (!o->test_mode && (o->log || o->methods))
        return cli_fail(EXIT_USAGE, "--log and --methods belong to --test-mode");
    if (o->test_mode && o->script) return cli_fail(EXIT_USAGE, "--test-mode and --script exclude each other");
    if (o->log && !cli_output_writable(o->log))
        return cli_fail(EXIT_OUTPUT, "cannot write %s: its directory does not exist or is not writable", o->log);
    return 0;
}
