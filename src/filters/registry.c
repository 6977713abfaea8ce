/* The table of denoising filters. One line per filter. */
#include <string.h>

#include "filters/filter.h"

extern const ob_filter_impl ob_filter_none;
extern const ob_filter_impl ob_filter_box4;
extern const ob_filter_impl ob_filter_gaussian;
extern const ob_filter_impl ob_filter_bilateral;
extern const ob_filter_impl ob_filter_bilateral_sep;
extern const ob_filter_impl ob_filter_geometry;
extern const ob_filter_impl ob_filter_crease;

static const ob_filter_impl *const filters[] = {
    &ob_filter_none,
    &ob_filter_box4,
    &ob_filter_gaussian,
    &ob_filter_bilateral,
    &ob_filter_bilateral_sep,
    &ob_filter_geometry,
    &ob_filter_crease,
};

int ob_filter_count(void) { return (int)(sizeof filters / sizeof filters[0]); }

const ob_filter_impl *ob_filter_impl_at(int index)
{
    return index >= 0 && index < ob_filter_count() ? filters[index] : NULL;
}

const ob_filter_info *ob_filter_at(int index)
{
    const ob_filter_impl *f = ob_filter_impl_at(index);
    return f ? &f->info : NULL;
}

int ob_find_filter(const char *name)
{
    if (!name) return -1;
    for (int i = 0; i < ob_filter_count(); ++i)
        if (strcmp(filters[i]->info.name, name) == 0) return i;
    return -1;
}
