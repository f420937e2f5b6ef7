/* adapter.h — the adapters to heavy libraries, loaded on first use.
 *
 * OpenImageIO and the 250 shared libraries it needs cost a process about
 * 0.3 s of CPU time to load and relocate; linked into every program, they
 * made each tool's start-up (and `--version`) cost that much, although most
 * runs read and write no image. So such an adapter is built as a shared
 * object, BUILD/lib/gibake/gibake-NAME.so beside BUILD/bin (installed as
 * PREFIX/lib/gibake/), and loaded when first needed.
 *
 * An adapter exports one entry function; the module that fronts it (e.g.
 * formats/image.c) calls it with a table of the gibake functions the
 * adapter may call, so the adapter links no gibake code and the program's
 * state (the output writer's temporaries) stays one.
 */
#ifndef GB_ADAPTER_H
#define GB_ADAPTER_H

#include <stddef.h>

#include "result.h"

/* The path of adapter NAME: the program's folder, then ../lib/gibake/
 * gibake-NAME.so, into path (size bytes). */
gb_result gb_adapter_path(const char *name, char *path, size_t size, gb_error *error);

/* Loads adapter NAME (once; later calls find it loaded) and returns the
 * address of its function entry, or NULL with error set ("cannot load the
 * openimageio adapter PATH: why"). Thread-safe; never unloaded. */
void *gb_adapter_entry(const char *name, const char *entry, gb_error *error);

#endif
