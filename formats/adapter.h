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

#include <pthread.h>
#include <stddef.h>

#include "result.h"

/* The entry of an adapter: given the host's table, returns its own. */
typedef const void *gb_adapter_entry(const void *host);

/* What a front (image.c, voxel_grid.c) knows of its adapter. */
typedef struct gb_adapter {
    const char *name;           /* "openimageio": gibake-openimageio.so */
    const char *entry_name;     /* its entry function's name */
    const void *host;           /* the gibake functions it may call */
    gb_adapter_entry *linked_in; /* the entry when the program links the adapter
                                   in (the fuzz targets, so that libFuzzer counts
                                   its coverage: it does not see a shared object
                                   loaded after start); NULL: load it */
    pthread_mutex_t lock;       /* PTHREAD_MUTEX_INITIALIZER */
    const void *functions;      /* the adapter's table, once loaded */
} gb_adapter;

/* A front's adapter: NAME ("openvdb"), HOST (its table of gibake
 * functions), ENTRY the entry function's name, declared weak by the front. */
#define GB_ADAPTER_INITIALIZER(NAME, HOST, ENTRY)                                      \
    {.name = NAME, .entry_name = #ENTRY, .host = HOST, .linked_in = ENTRY,              \
     .lock = PTHREAD_MUTEX_INITIALIZER}

/* The adapter's table of functions: PROGRAM_FOLDER/../lib/gibake/
 * gibake-NAME.so loaded and entered by the first call
 * (later calls find it), or NULL with error set ("cannot load the
 * openimageio adapter PATH: why"). Thread-safe; never unloaded. */
const void *gb_adapter_functions(gb_adapter *adapter, gb_error *error);

#endif
