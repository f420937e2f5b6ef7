/* tile_merge.c — gb_reference_merge_tiles (reference.h): the renders of
 * --tile 0/N .. N-1/N made one image, each pixel from the render its tile
 * belongs to (tile t of the rows of GB_REFERENCE_TILE_SIZE tiles belongs to
 * t % N), so that the bytes are those of one whole render. A part with
 * light outside its own tiles is refused: a part of another split, or the
 * parts out of order. */
#include <string.h>

#include "reference.h"

/* A part leaves the tiles of the others black. */
static int is_black(const float *pixel, size_t channels)
{
    for (size_t c = 0; c < channels; ++c)
        if (pixel[c] != 0.0f)
            return 0;
    return 1;
}

static gb_result check_sizes(const gb_image *tiles, const char *const *names, uint32_t count,
                             gb_error *error)
{
    if (count < 2)
        return gb_fail(error, GB_ERROR_ARGUMENT, "reference --merge: give the N images of "
                       "--tile 0/N .. N-1/N, N at least 2 (got %u)", count);
    for (uint32_t i = 1; i < count; ++i)
        if (tiles[i].width != tiles[0].width || tiles[i].height != tiles[0].height ||
            tiles[i].channels != tiles[0].channels)
            return gb_fail(error, GB_ERROR_ARGUMENT, "%s: %dx%d, %d channels, but %s is "
                           "%dx%d, %d channels: not tiles of one render", names[i],
                           tiles[i].width, tiles[i].height, tiles[i].channels, names[0],
                           tiles[0].width, tiles[0].height, tiles[0].channels);
    return GB_OK;
}

gb_result gb_reference_merge_tiles(const gb_image *tiles, const char *const *names,
                                   uint32_t count, gb_image *merged, gb_error *error)
{
    *merged = (gb_image){0};
    gb_result result = check_sizes(tiles, names, count, error);
    if (result == GB_OK)
        result = gb_image_allocate(merged, tiles[0].width, tiles[0].height, tiles[0].channels,
                                   error);
    if (result != GB_OK)
        return result;
    int size = GB_REFERENCE_TILE_SIZE, tiles_x = (merged->width + size - 1) / size;
    size_t channels = (size_t)merged->channels;
    for (int y = 0; y < merged->height; ++y)
        for (int x = 0; x < merged->width; ++x) {
            uint32_t tile = (uint32_t)((y / size) * tiles_x + x / size);
            size_t at = ((size_t)y * (size_t)merged->width + (size_t)x) * channels;
            memcpy(&merged->pixels[at], &tiles[tile % count].pixels[at],
                   channels * sizeof(float));
            for (uint32_t i = 0; i < count; ++i)
                if (i != tile % count && !is_black(&tiles[i].pixels[at], channels)) {
                    gb_image_free(merged);
                    return gb_fail(error, GB_ERROR_ARGUMENT, "%s: a pixel (%d, %d) outside "
                                   "its tiles: not part %u of %u of one render (give the "
                                   "parts in order, all of them)", names[i], x, y, i, count);
                }
        }
    return GB_OK;
}
