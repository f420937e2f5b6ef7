/* depfile.h — a make rule naming the files a run read, the compilers' -MD
 * habit (every tool's --depfile FILE):
 *
 *   bake/cornell.vdb: scenes/cornell/cornell.scene scenes/cornell/cornell.obj \
 *    scenes/cornell/cornell.mtl
 *   scenes/cornell/cornell.scene:
 *   ...
 *
 * then an empty rule for each input (the -MP habit), so that make does not
 * stop when an input is deleted or renamed: it reruns the step, which then
 * fails with the real reason. Spaces, '#' and '\' in a path are escaped with
 * a backslash and '$' doubled, as make reads them; a path with a newline
 * cannot be written in a make rule and is refused. The file is written
 * through gb_output_file (output_file.h): whole or not at all.
 *
 * The caller owns target and inputs; nothing is kept.
 */
#ifndef GB_DEPFILE_H
#define GB_DEPFILE_H

#include <stdint.h>

#include "result.h"
#include "scene.h"

/* Writes the rule "target: inputs..." and one empty rule per input to path.
 * An input named twice is listed once. */
gb_result gb_depfile_write(const char *path, const char *target, const char *const *inputs,
                           uint32_t input_count, gb_error *error);

/* The rule of a run that read scene (every file of scene->inputs) and, when
 * not NULL, the file other (cluster's photon map). */
gb_result gb_depfile_write_scene(const char *path, const char *target, const gb_scene *scene,
                                 const char *other, gb_error *error);

#endif
