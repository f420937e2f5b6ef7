/* screenshot_path.h — where the window's next screenshot goes: BASE with a
 * number before its extension (gbview.png: gbview-000.png, gbview-001.png
 * ...), the first number not yet taken, so that a screenshot never
 * overwrites one, this session's or an earlier one's.
 */
#ifndef GB_SCREENSHOT_PATH_H
#define GB_SCREENSHOT_PATH_H

#include <stddef.h>

#include "result.h"

enum { GB_SCREENSHOT_MAX_NUMBER = 99999 };

/* The first base-NNN.ext (at least three digits) from number *next up whose
 * file does not exist, into path; *next past it. GB_ERROR_IO when every
 * number up to GB_SCREENSHOT_MAX_NUMBER is taken, GB_ERROR_ARGUMENT when
 * path is too small. */
gb_result gb_screenshot_path(const char *base, unsigned *next, char *path, size_t size,
                             gb_error *error);

#endif
