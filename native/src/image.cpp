#include "probelights/image.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <future>
#include <memory>

#include "probelights/error.h"
#include "probelights/probe.h"

namespace probelights {

namespace {

std::string oneLine(std::string why) {
  // OpenImageIO's messages can span lines; the user gets one.
  for (char& c : why)
    if (c == '\n') c = ' ';
  return why;
}

// An open image file: OpenImageIO's reader, and the file's bytes when it reads them from memory.
struct OpenImage {
  std::vector<unsigned char> bytes;
  std::unique_ptr<OIIO::Filesystem::IOMemReader> memory;
  std::unique_ptr<OIIO::ImageInput> in;  // destroyed first (members go in reverse order)
};

// A file of at most this many bytes is read whole with one read and decoded from memory by OpenImageIO (an
// IOProxy), where its reader for the format takes one: its own reads go through stdio a few bytes at a
// time, which for a 1K .hdr was a third of its read (100 1K probes: 5.9 -> 4.2 ms a file). Larger files
// keep OpenImageIO's reads, so a big probe's bytes are never held beside its pixels.
constexpr std::uintmax_t kReadWholeBytes = 32u << 20;

// Opens `path` and checks it is a 2D image with pixels; its spec is in->spec(). fromMemory: read a small
// file whole first (kReadWholeBytes).
OpenImage openImage(const std::string& path, bool fromMemory = false) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw Error("cannot read probe '" + path + "': no such file");
  if (std::filesystem::is_directory(path, ec))
    throw Error("cannot read probe '" + path + "': it is a directory");

  OpenImage o;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (fromMemory && !ec && size > 0 && size <= kReadWholeBytes) {
    auto in = OIIO::ImageInput::create(path, false);
    std::ifstream file(path, std::ios::binary);
    o.bytes.resize(static_cast<std::size_t>(size));
    if (in && in->supports("ioproxy") && file.read(reinterpret_cast<char*>(o.bytes.data()), size)) {
      o.memory = std::make_unique<OIIO::Filesystem::IOMemReader>(o.bytes.data(), o.bytes.size());
      OIIO::ImageSpec spec, config;
      if (in->set_ioproxy(o.memory.get()) && in->open(path, spec, config)) o.in = std::move(in);
    }
    if (!o.in) o = OpenImage{};  // not this way: opened as usual below, with its usual errors
  }
  if (!o.in) o.in = OIIO::ImageInput::open(path);
  if (!o.in) {
    std::string why = oneLine(OIIO::geterror());
    if (why.empty()) why = "not an image OpenImageIO can read";
    throw Error("cannot read probe '" + path + "': " + why);
  }
  const OIIO::ImageSpec& spec = o.in->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0)
    throw Error("cannot read probe '" + path + "': the image is empty (" + std::to_string(spec.width) + "x" +
                std::to_string(spec.height) + ")");
  if (spec.depth > 1) throw Error("cannot read probe '" + path + "': volume images are not probes");
  return o;
}

Image description(const OIIO::ImageInput& in) {
  Image image;
  image.width = in.spec().width;
  image.height = in.spec().height;
  image.channels = in.spec().nchannels;
  image.format = in.format_name();
  return image;
}

Error readFailure(const std::string& path, OIIO::ImageInput& in) {
  std::string why = oneLine(in.geterror());
  return Error("cannot read probe '" + path + "': " + (why.empty() ? "read failed" : why));
}

// A scanline file whose samples are float already (.hdr, float EXR) is read straight into the caller's
// buffer: read_image and read_scanlines would decode it into a buffer of their own and copy that, which at 8K
// .hdr was 659 ms against 281 ms straight (a fresh 402 MB buffer, then the copy), and in a library of 1K .hdr
// two thirds of all page faults. Anything else is converted to float by OpenImageIO.
bool nativeFloat(const OIIO::ImageSpec& spec) {
  return spec.format == OIIO::TypeDesc::FLOAT && spec.channelformats.empty() && spec.tile_width == 0 &&
         !spec.deep;
}

// Rows [y0, y1) counted from the top of the data window, every channel.
bool readFloatRows(OIIO::ImageInput& in, int y0, int y1, float* out) {
  const OIIO::ImageSpec& spec = in.spec();
  return in.read_native_scanlines(0, 0, spec.y + y0, spec.y + y1, spec.z, 0, spec.nchannels, out);
}

}  // namespace

Image readImage(const std::string& path) {
  OpenImage file = openImage(path, true);
  auto& in = file.in;
  const OIIO::ImageSpec& spec = in->spec();
  Image image = description(*in);
  image.pixels = keptArray<float>(static_cast<std::size_t>(spec.width) * spec.height * spec.nchannels);
  // Subimage 0, MIP level 0 (the finest), every channel, as float (every sample written).
  const bool read = nativeFloat(spec)
                        ? readFloatRows(*in, 0, spec.height, image.pixels.get())
                        : in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, image.pixels.get());
  if (!read) throw readFailure(path, *in);
  return image;
}

Image describeImage(const std::string& path, bool* canReadInBands) {
  auto in = openImage(path).in;
  if (canReadInBands) *canReadInBands = in->spec().tile_width == 0 && !in->spec().deep;
  return description(*in);
}

Image readImageBands(const std::string& path, int bandRows,
                     const std::function<void(const ImageView&)>& consume) {
  OpenImage file = openImage(path, true);
  auto& in = file.in;
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.tile_width != 0 || spec.deep)
    throw Error("cannot read probe '" + path + "' band by band: it is tiled or deep (read it whole)");
  Image info = description(*in);
  const int W = info.width, H = info.height, channels = info.channels;
  const int rows = std::clamp(bandRows, 1, H), bands = (H + rows - 1) / rows;
  const bool native = nativeFloat(spec);
  std::vector<float> buffers[2];
  for (auto& b : buffers) b.resize(static_cast<std::size_t>(rows) * W * channels);
  // Band b goes to buffers[b % 2]: the reader fills one while consume() reads the other.
  auto read = [&](int b) {
    const int y0 = b * rows, y1 = std::min(H, y0 + rows);
    // Rows are counted from the top of the data window (spec.y), as read_image counts them.
    const bool read = native ? readFloatRows(*in, y0, y1, buffers[b % 2].data())
                             : in->read_scanlines(0, 0, spec.y + y0, spec.y + y1, 0, 0, channels,
                                                  OIIO::TypeDesc::FLOAT, buffers[b % 2].data());
    if (!read) throw readFailure(path, *in);
  };
  std::future<void> next = std::async(std::launch::async, read, 0);
  for (int b = 0; b < bands; ++b) {
    next.get();
    if (b + 1 < bands) next = std::async(std::launch::async, read, b + 1);
    ImageView view{buffers[b % 2].data(), W, std::min(H, (b + 1) * rows) - b * rows, channels};
    view.firstRow = b * rows;
    consume(view);  // if it throws, `next` (declared after the buffers) waits for its read on the way out
  }
  return info;
}

Probe Probe::load(const std::string& path, const ProbeOptions& options) {
  return Probe(readImage(path), options.projection, options.nonFinite, path);
}

Probe Probe::loadUnchecked(const std::string& path, const ProbeOptions& options) {
  return Probe(readImage(path), options.projection, path);
}

}  // namespace probelights
