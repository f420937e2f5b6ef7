// image_openimageio.cpp — the OpenImageIO adapter: gb_image (image.h) read
// from and written to EXR, PNG, JPEG and the other files OpenImageIO knows.
// The only file that includes OpenImageIO. Built as the shared object
// gibake-openimageio.so, loaded by formats/image.c on first use; it calls
// gibake only through the host table it is given (image_adapter.h).

#include "image_adapter.h"

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include <sys/mman.h>
#include <unistd.h>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

namespace {

const gb_image_host *host;

float srgb_to_linear(float c)
{
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

float linear_to_srgb(float c)
{
    c = c < 0 ? 0 : c > 1 ? 1 : c;
    return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1 / 2.4f) - 0.055f;
}

// Integer pixels (PNG, JPEG, ...) hold sRGB values unless the file says
// they are linear; float pixels (EXR, HDR) are linear.
bool holds_srgb(const OIIO::ImageSpec &spec)
{
    OIIO::TypeDesc::BASETYPE type = static_cast<OIIO::TypeDesc::BASETYPE>(spec.format.basetype);
    if (type == OIIO::TypeDesc::FLOAT || type == OIIO::TypeDesc::HALF
        || type == OIIO::TypeDesc::DOUBLE)
        return false;
    std::string space = spec.get_string_attribute("oiio:ColorSpace");
    return space != "Linear" && space != "linear";
}

std::string last_error(const std::string &own)
{
    std::string message = own.empty() ? OIIO::geterror() : own;
    std::size_t newline = message.find('\n');
    if (newline != std::string::npos)
        message.resize(newline);
    return message.empty() ? std::string("unknown OpenImageIO error") : message;
}

void convert_to_linear(gb_image *image, int alpha_channel)
{
    std::size_t pixels = static_cast<std::size_t>(image->width) * image->height;
    for (std::size_t i = 0; i < pixels; ++i)
        for (int c = 0; c < image->channels; ++c)
            if (c != alpha_channel) {
                float &value = image->pixels[i * image->channels + c];
                value = srgb_to_linear(value);
            }
}

// OpenImageIO's PNG reader keeps libpng's default error handler, which
// prints "libpng error: ..." on stderr. While a PNG file is read, file
// descriptor 2 points at a memory file instead, so that nothing is printed
// (library code never prints) and what was printed can go in the message.
// It is the process's descriptor: PNG reads must not run in parallel with
// each other or with output on stderr (a sanitizer's report too goes there).
class StderrCapture {
public:
    explicit StderrCapture(bool active)
    {
        if (!active)
            return;
        std::fflush(stderr);
        capture_ = memfd_create("gibake-stderr", MFD_CLOEXEC);
        saved_ = capture_ >= 0 ? dup(2) : -1;
        if (saved_ < 0 || dup2(capture_, 2) < 0)
            restore();
    }
    ~StderrCapture() { restore(); }

    // The first line printed, or "".
    std::string first_line()
    {
        restore();
        char text[512] = {0};
        ssize_t got = capture_ >= 0 ? pread(capture_, text, sizeof text - 1, 0) : 0;
        std::string line(text, got > 0 ? static_cast<std::size_t>(got) : 0);
        return line.substr(0, line.find('\n'));
    }

private:
    void restore()
    {
        if (saved_ >= 0) {
            std::fflush(stderr);
            dup2(saved_, 2);
            close(saved_);
            saved_ = -1;
        }
    }

    int capture_ = -1, saved_ = -1;
};

// OpenImageIO's message, else what its libraries printed.
std::string read_error(const std::string &own, StderrCapture &capture)
{
    std::string printed = capture.first_line();
    std::string message = own.empty() ? OIIO::geterror() : own;
    if (message.empty() && !printed.empty())
        return printed;
    return last_error(message);
}

// The file is opened with the one reader of the format its bytes show
// (image_check.h), after its size is checked against the file's.
gb_result read_image(const char *path, gb_image *image, gb_error *error)
{
    gb_image_file file;
    gb_result result = host->check_file(path, &file, error);
    if (result != GB_OK)
        return result;
    // Colours stay as stored (PNG alpha is unassociated); OpenImageIO would
    // otherwise multiply them by alpha.
    OIIO::ImageSpec config, spec;
    config.attribute("oiio:UnassociatedAlpha", 1);
    StderrCapture capture(std::strcmp(file.format, "png") == 0);
    auto input = OIIO::ImageInput::create(file.format);
    if (!input || !input->open(path, spec, config))
        return host->fail(error, GB_ERROR_FORMAT, "%s: %s", path,
                       read_error(input ? input->geterror() : "", capture).c_str());
    result = host->check_size(path, &file, spec.width, spec.height, spec.depth,
                                 spec.nchannels, error);
    if (result == GB_OK)
        result = host->allocate(image, spec.width, spec.height, spec.nchannels, error);
    if (result != GB_OK)
        return result;
    if (!input->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, image->pixels)) {
        std::string message = read_error(input->geterror(), capture);
        host->free(image);
        return host->fail(error, GB_ERROR_FORMAT, "%s: %s", path, message.c_str());
    }
    input->close();
    if (holds_srgb(spec))
        convert_to_linear(image, spec.alpha_channel);
    return GB_OK;
}

// Float formats keep the values; the others get 8-bit sRGB.
bool writes_float(const std::string &format)
{
    return format == "openexr" || format == "hdr" || format == "tiff";
}

std::vector<std::uint8_t> to_srgb8(const gb_image *image)
{
    std::size_t values = static_cast<std::size_t>(image->width) * image->height * image->channels;
    std::vector<std::uint8_t> bytes(values);
    int alpha = image->channels == 4 || image->channels == 2 ? image->channels - 1 : -1;
    for (std::size_t i = 0; i < values; ++i) {
        float v = image->pixels[i];
        bool is_alpha = static_cast<int>(i % image->channels) == alpha;
        v = is_alpha ? (v < 0 ? 0 : v > 1 ? 1 : v) : linear_to_srgb(v);
        bytes[i] = static_cast<std::uint8_t>(std::lround(v * 255.0f));
    }
    return bytes;
}

// The OpenImageIO writer that path's extension names.
gb_result create_output(const char *path, std::unique_ptr<OIIO::ImageOutput> *output,
                        gb_error *error)
{
    *output = OIIO::ImageOutput::create(path);
    if (!*output) {
        OIIO::geterror();  // taken: the message below says it
        return host->fail(error, GB_ERROR_UNSUPPORTED,
                       "%s: unknown image format (the extension names it: .exr, .png, "
                       ".jpg, .tif, .hdr, ...)",
                       path);
    }
    return GB_OK;
}

// Encodes image with output into name (the output file, or the IO proxy's
// memory when one is set).
gb_result encode(OIIO::ImageOutput *output, const char *name, const char *path,
                 const gb_image *image, gb_error *error)
{
    bool as_float = writes_float(output->format_name());
    OIIO::ImageSpec spec(image->width, image->height, image->channels,
                         as_float ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8);
    if (image->channels == 4 || image->channels == 2) {
        spec.alpha_channel = image->channels - 1;
        spec.attribute("oiio:UnassociatedAlpha", 1);   // colours not multiplied by alpha
    }
    spec.attribute("oiio:ColorSpace", as_float ? "Linear" : "sRGB");
    spec.attribute("DateTime", "1970:01:01 00:00:00");  // same pixels, same bytes
    bool written = output->open(name, spec);
    if (written && as_float)
        written = output->write_image(OIIO::TypeDesc::FLOAT, image->pixels);
    else if (written)
        written = output->write_image(OIIO::TypeDesc::UINT8, to_srgb8(image).data());
    written = output->close() && written;
    if (!written)
        return host->fail(error, GB_ERROR_IO, "%s: %s", path,
                       last_error(output->geterror()).c_str());
    return GB_OK;
}

// Through the one output writer (output_file.h), opened before encoding so
// that a bad path fails first. Formats with IO-proxy support (EXR, PNG, ...)
// are encoded into memory and their bytes written by the output writer
// (straight through to a device or FIFO); the others are written by
// OpenImageIO into the output writer's temporary.
gb_result write_image(const char *path, const gb_image *image, gb_error *error)
{
    if (!image->pixels || image->width <= 0 || image->height <= 0 || image->channels <= 0)
        return host->fail(error, GB_ERROR_ARGUMENT, "%s: no pixels to write", path);
    std::unique_ptr<OIIO::ImageOutput> output;
    gb_result result = create_output(path, &output, error);
    if (result != GB_OK)
        return result;
    OIIO::Filesystem::IOVecOutput memory;
    bool in_memory = output->supports("ioproxy") && output->set_ioproxy(&memory);
    gb_output_file *out = nullptr;
    result = host->output->open(path, in_memory ? GB_OUTPUT_FILE_STREAM : GB_OUTPUT_FILE_BY_NAME,
                                 &out, error);
    if (result != GB_OK)
        return result;
    try {
        result = encode(output.get(), in_memory ? path : host->output->name(out), path, image,
                        error);
        if (result == GB_OK && in_memory)
            result = host->output->write(out, memory.buffer().data(), memory.buffer().size(),
                                          error);
    } catch (const std::exception &e) {
        result = host->fail(error, GB_ERROR_IO, "%s: %s", path, e.what());
    }
    if (result != GB_OK) {
        host->output->abort(out);
        return result;
    }
    return host->output->commit(out, error);
}

gb_result read(const char *path, gb_image *image, gb_error *error)
{
    try {
        return read_image(path, image, error);
    } catch (const std::exception &e) {
        host->free(image);
        return host->fail(error, GB_ERROR_IO, "%s: %s", path, e.what());
    }
}

gb_result write(const char *path, const gb_image *image, gb_error *error)
{
    try {
        return write_image(path, image, error);
    } catch (const std::exception &e) {
        return host->fail(error, GB_ERROR_IO, "%s: %s", path, e.what());
    }
}

gb_result check_output(const char *path, gb_error *error)
{
    try {
        std::unique_ptr<OIIO::ImageOutput> output;
        gb_result result = create_output(path, &output, error);
        return result == GB_OK ? host->output->check(path, error) : result;
    } catch (const std::exception &e) {
        return host->fail(error, GB_ERROR_IO, "%s: %s", path, e.what());
    }
}

const gb_image_adapter adapter = {read, write, check_output};

} // namespace

// The entry (adapter.h): host is a gb_image_host, the result a gb_image_adapter.
extern "C" __attribute__((visibility("default"))) const void *
gb_openimageio_adapter(const void *given)
{
    host = static_cast<const gb_image_host *>(given);
    return &adapter;
}
