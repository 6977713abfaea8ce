/* libFuzzer target: the tuned settings files of --settings FILE (app/settings_file.c), loaded as
 * cli_common_finish loads them and applied to fresh settings of their method as every command
 * applies them. Seeds: tests/fuzz/corpus_settings (make fuzz, make test-fuzz). */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

#include "cli.h"
#include "settings_file.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char path[] = "/tmp/ob_fuzz_settings_XXXXXX";
    int fd = mkstemp(path);
    if (fd < 0) return 0;
    if (write(fd, data, size) == (ssize_t)size) {
        static cli_tuned tuned[CLI_MAX_TUNED_FILES]; /* 32 x 4.5 KB: not on the stack */
        int count = 0;
        if (cli_tuned_load(path, tuned, CLI_MAX_TUNED_FILES, &count) == EXIT_OK) {
            for (int i = 0; i < count; ++i) {
                /* What load accepted must apply: it was checked against the same table. */
                ob_settings s;
                if (ob_settings_init(&s, ob_method_at(tuned[i].method)->name) != OB_OK ||
                    cli_tuned_apply(&tuned[i], &s) != EXIT_OK)
                    __builtin_trap();
            }
        }
        ob_clear_error();
    }
    close(fd);
    unlink(path);
    return 0;
}
