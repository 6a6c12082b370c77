#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <OpenImageIO/strutil.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <future>
#include <memory>

#include "probelights/error.h"
#include "probelights/image_file.h"
#include "probelights/probe.h"

namespace probelights {

namespace {

std::string oneLine(std::string why) {
  // OpenImageIO's messages can span lines; the user gets one.
  for (char& c : why)
    if (c == '\n') c = ' ';
  return why;
}

// How an integer image's values become linear light. A float image (EXR, .hdr, PFM, float TIFF) is linear
// already. An 8- or 16-bit one (PNG, JPEG, TIFF) holds display values: decoded with the sRGB curve unless
// the file says it is linear or names a gamma, as Blender reads such an image (its default colour space for
// them is sRGB).
struct Transfer {
  enum Kind { Linear, Srgb, Gamma } kind = Linear;
  float gamma = 1;
};

// An open image file: OpenImageIO's reader, and the file's bytes when it reads them from memory.
struct OpenImage {
  std::vector<unsigned char> bytes;
  std::vector<Note> notes;  // how it is read, for the probe's report (Image::notes)
  Transfer transfer;
  std::unique_ptr<OIIO::Filesystem::IOMemReader> memory;
  std::unique_ptr<OIIO::ImageInput> in;  // destroyed first (members go in reverse order)
};

// A file of at most this many bytes is read whole with one read and decoded from memory by OpenImageIO (an
// IOProxy), where its reader for the format takes one: its own reads go through stdio a few bytes at a
// time, a large part of a small file's read (docs/decisions.md). Larger files keep OpenImageIO's reads, so
// a big probe's bytes are never held beside its pixels.
constexpr std::uintmax_t kReadWholeBytes = 32u << 20;

// Refuses what is not a regular file before a byte is read: a FIFO would block the read forever, a device
// might never end; a symbolic link loop or a folder that cannot be searched says so rather than "no such
// file".
void checkRegularFile(const std::string& path) {
  namespace fs = std::filesystem;
  if (path.find('\0') != std::string::npos) throw Error("cannot read probe: its path holds a NUL character");
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (ec && ec != std::errc::no_such_file_or_directory)
    throw Error("cannot read probe '" + path + "': " + ec.message());
  switch (status.type()) {
    case fs::file_type::not_found:
      throw Error("cannot read probe '" + path + "': no such file");
    case fs::file_type::regular:
      return;
    case fs::file_type::directory:
      throw Error("cannot read probe '" + path + "': it is a directory");
    case fs::file_type::fifo:
      throw Error("cannot read probe '" + path + "': it is a FIFO (named pipe), not a file");
    case fs::file_type::socket:
      throw Error("cannot read probe '" + path + "': it is a socket, not a file");
    case fs::file_type::block:
    case fs::file_type::character:
      throw Error("cannot read probe '" + path + "': it is a device, not a file");
    default:
      throw Error("cannot read probe '" + path + "': not a regular file");
  }
}

// The most pixels a file may claim: a 32768 x 32768 image (12 GB as float RGB), beyond any probe published.
constexpr std::uint64_t kMaxPixels = std::uint64_t{1} << 30;
// The most pixels per byte of file any encoding reaches, with a wide margin over the densest encoding of a
// constant image (DWAB EXR; docs/decisions.md).
constexpr std::uint64_t kMaxPixelsPerByte = 20000;

// Refuses a header that claims more pixels than its file could hold, before memory is taken for them (a
// 255-byte .hdr claiming 600000 x 300000 pixels took 7.2 GB before failing).
void checkClaims(const std::string& path, const OIIO::ImageSpec& spec, std::uintmax_t fileBytes) {
  const std::uint64_t w = static_cast<std::uint64_t>(std::max(spec.full_width, spec.width));
  const std::uint64_t h = static_cast<std::uint64_t>(std::max(spec.full_height, spec.height));
  const std::string size = std::to_string(w) + "x" + std::to_string(h);
  if (w * h > kMaxPixels)
    throw Error("cannot read probe '" + path + "': " + size + " pixels, more than the 1-gigapixel limit");
  if (fileBytes > 0 && w * h > fileBytes * kMaxPixelsPerByte)
    throw Error("cannot read probe '" + path + "': its header claims " + size + " pixels, more than its " +
                std::to_string(fileBytes) + " bytes can hold (a damaged or hostile file)");
}

std::string channelName(const OIIO::ImageSpec& spec, int c) {
  std::string name = c < static_cast<int>(spec.channelnames.size()) ? spec.channelnames[c] : "";
  if (const auto dot = name.rfind('.'); dot != std::string::npos) name = name.substr(dot + 1);  // layer.R
  return OIIO::Strutil::upper(name);
}

std::string channelList(const OIIO::ImageSpec& spec) {
  std::string names;
  for (int c = 0; c < spec.nchannels; ++c)
    names += (c ? ", " : "") + (c < static_cast<int>(spec.channelnames.size()) ? spec.channelnames[c] : "?");
  return names;
}

// The channels a probe is read from (image.h's ImageView: 1 or 2 grey, 3+ RGB first), checked by name: an
// image whose first three channels are not R, G, B, or whose two are not grey + alpha, is refused rather
// than read as if it were colour.
void checkChannels(const std::string& path, const OIIO::ImageSpec& spec, std::vector<Note>& notes) {
  if (spec.nchannels == 1) return;
  if (spec.nchannels == 2) {
    if (channelName(spec, 1) == "A") {
      notes.push_back({NoteKind::Reading, "channels " + channelList(spec) + ": read as grey, alpha ignored"});
      return;
    }
    throw Error("cannot read probe '" + path + "': its 2 channels (" + channelList(spec) +
                ") are not grey and alpha; probelights reads grey, grey + alpha, or R, G, B (+ more)");
  }
  if (channelName(spec, 0) == "R" && channelName(spec, 1) == "G" && channelName(spec, 2) == "B") {
    if (spec.nchannels > 4 || (spec.nchannels == 4 && channelName(spec, 3) != "A"))
      notes.push_back(
          {NoteKind::Reading, "channels " + channelList(spec) + ": R, G, B read, the others ignored"});
    return;
  }
  throw Error("cannot read probe '" + path + "': its channels (" + channelList(spec) +
              ") do not begin with R, G, B; probelights reads grey, grey + alpha, or R, G, B (+ more)");
}

Transfer transferOf(const OIIO::ImageSpec& spec, const std::string& format, std::vector<Note>& notes) {
  const OIIO::TypeDesc::BASETYPE base = static_cast<OIIO::TypeDesc::BASETYPE>(spec.format.basetype);
  if (base == OIIO::TypeDesc::FLOAT || base == OIIO::TypeDesc::HALF || base == OIIO::TypeDesc::DOUBLE)
    return {};
  const std::string space = spec.get_string_attribute("oiio:ColorSpace");
  const std::string what = std::to_string(spec.format.size() * 8) + "-bit " + format;
  if (OIIO::Strutil::icontains(space, "linear") || OIIO::Strutil::istarts_with(space, "lin_")) {
    notes.push_back({NoteKind::Reading, what + ": read as linear light", "the file says " + space});
    return {};
  }
  const float gamma = spec.get_float_attribute("oiio:Gamma", 0.0f);
  if (OIIO::Strutil::istarts_with(space, "gamma") && gamma > 0.1f && gamma < 10.0f) {
    notes.push_back(
        {NoteKind::Reading,
         what + ": values decoded with gamma " + std::to_string(gamma).substr(0, 4) + " to linear light",
         "the file's"});
    return {Transfer::Gamma, gamma};
  }
  notes.push_back(
      {NoteKind::Reading, what + ": sRGB values decoded to linear light, as Blender reads them; an HDR "
                                 "probe (EXR, .hdr) keeps the light brighter than white"});
  return {Transfer::Srgb};
}

// Applies `t` to the colour channels (not alpha or others) of `count` pixels of `channels` floats.
void decode(const Transfer& t, float* pixels, std::size_t count, int channels) {
  if (t.kind == Transfer::Linear) return;
  const int colour = channels < 3 ? 1 : 3;
  for (std::size_t i = 0; i < count; ++i)
    for (int c = 0; c < colour; ++c) {
      float& v = pixels[i * channels + c];
      if (t.kind == Transfer::Gamma)
        v = v > 0 ? std::pow(v, t.gamma) : 0.0f;
      else  // IEC 61966-2-1
        v = v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
    }
}

bool windowsDiffer(const OIIO::ImageSpec& spec) {
  return spec.full_width > 0 && spec.full_height > 0 &&
         (spec.x != spec.full_x || spec.y != spec.full_y || spec.width != spec.full_width ||
          spec.height != spec.full_height);
}

// How every file is opened: a PFM's rows are stored bottom to top, and OpenImageIO 3.2 flips them to top to
// bottom when it reads from memory but not when it opens a file by name unless asked (pnm:pfmflip): asked
// always, so a PFM reads the same way whatever its size (kReadWholeBytes) and whichever OpenImageIO build
// reads it.
OIIO::ImageSpec openConfig() {
  OIIO::ImageSpec config;
  config.attribute("pnm:pfmflip", 1);
  return config;
}

// Opens `path` and checks it is a 2D image with pixels that a probe can be read from (checkRegularFile,
// checkClaims, checkChannels); its spec is in->spec(). fromMemory: read a small file whole first
// (kReadWholeBytes).
OpenImage openImage(const std::string& path, bool fromMemory = false) {
  // OpenImageIO 3's own limit on a header's claimed size follows the machine's physical memory, so one file
  // would be refused on one machine and read on another; checkClaims' limits are the same everywhere.
  static const bool sameLimitsEverywhere = OIIO::attribute("limits:imagesize_MB", 0);
  (void)sameLimitsEverywhere;
  checkRegularFile(path);
  std::error_code ec;
  OpenImage o;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (fromMemory && !ec && size > 0 && size <= kReadWholeBytes) {
    auto in = OIIO::ImageInput::create(path, false);
    std::ifstream file(path, std::ios::binary);
    o.bytes.resize(static_cast<std::size_t>(size));
    if (in && in->supports("ioproxy") && file.read(reinterpret_cast<char*>(o.bytes.data()), size)) {
      o.memory = std::make_unique<OIIO::Filesystem::IOMemReader>(o.bytes.data(), o.bytes.size());
      OIIO::ImageSpec spec, config = openConfig();
      if (in->set_ioproxy(o.memory.get()) && in->open(path, spec, config)) o.in = std::move(in);
    }
    if (!o.in) o = OpenImage{};  // not this way: opened as usual below, with its usual errors
  }
  if (!o.in) {
    const OIIO::ImageSpec config = openConfig();
    o.in = OIIO::ImageInput::open(path, &config);
  }
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
  checkClaims(path, spec, ec ? 0 : size);
  checkChannels(path, spec, o.notes);
  o.transfer = transferOf(spec, o.in->format_name(), o.notes);
  if (windowsDiffer(spec)) {
    const OIIO::ROI data(spec.x, spec.x + spec.width, spec.y, spec.y + spec.height);
    const OIIO::ROI full(spec.full_x, spec.full_x + spec.full_width, spec.full_y,
                         spec.full_y + spec.full_height);
    if (!OIIO::roi_intersection(data, full).defined() || OIIO::roi_intersection(data, full).npixels() == 0)
      throw Error("cannot read probe '" + path + "': its data window lies outside its display window");
    o.notes.push_back({NoteKind::Reading,
                       "data window " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                           " at (" + std::to_string(spec.x - spec.full_x) + ", " +
                           std::to_string(spec.y - spec.full_y) + ") of the " +
                           std::to_string(spec.full_width) + "x" + std::to_string(spec.full_height) +
                           " display window: the sphere is the display window, the rest of it read as 0"});
  }
  return o;
}

// The image as a probe sees it: the display window's size.
Image description(const OpenImage& o) {
  const OIIO::ImageSpec& spec = o.in->spec();
  Image image;
  image.width = windowsDiffer(spec) ? spec.full_width : spec.width;
  image.height = windowsDiffer(spec) ? spec.full_height : spec.height;
  image.channels = spec.nchannels;
  image.format = o.in->format_name();
  image.notes = o.notes;
  return image;
}

Error readFailure(const std::string& path, OIIO::ImageInput& in) {
  std::string why = oneLine(in.geterror());
  return Error("cannot read probe '" + path + "': " + (why.empty() ? "read failed" : why));
}

// A read counts only when the decoder reported nothing: some report missing data (a cut TIFF) as an error
// message beside a read that "succeeded".
bool readClean(bool read, OIIO::ImageInput& in) { return read && !in.has_error(); }

// A scanline file whose samples are float already (.hdr, float EXR) is read straight into the caller's
// buffer: read_image and read_scanlines would decode it into a buffer of their own and copy that (a fresh
// buffer as large as the image, then the copy: most of an 8K read's time and of a library's page faults;
// docs/decisions.md). Anything else is converted to float by OpenImageIO.
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
  Image image = description(file);
  const std::size_t C = static_cast<std::size_t>(spec.nchannels);
  image.pixels = keptArray<float>(static_cast<std::size_t>(image.width) * image.height * C);
  // Subimage 0, MIP level 0 (the finest), every channel, as float (every sample written).
  if (!windowsDiffer(spec)) {
    const bool read = nativeFloat(spec) ? readFloatRows(*in, 0, spec.height, image.pixels.get())
                                        : in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT,
                                                         image.pixels.get());
    if (!readClean(read, *in)) throw readFailure(path, *in);
  } else {  // the data window read, then placed in the display window (zeros elsewhere)
    std::vector<float> data(static_cast<std::size_t>(spec.width) * spec.height * C);
    if (!readClean(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, data.data()), *in))
      throw readFailure(path, *in);
    std::fill_n(image.pixels.get(), static_cast<std::size_t>(image.width) * image.height * C, 0.0f);
    for (int y = std::max(spec.y, spec.full_y);
         y < std::min(spec.y + spec.height, spec.full_y + image.height); ++y)
      for (int x = std::max(spec.x, spec.full_x);
           x < std::min(spec.x + spec.width, spec.full_x + image.width); ++x)
        std::copy_n(
            &data[(static_cast<std::size_t>(y - spec.y) * spec.width + (x - spec.x)) * C], C,
            &image.pixels
                 .get()[(static_cast<std::size_t>(y - spec.full_y) * image.width + (x - spec.full_x)) * C]);
  }
  decode(file.transfer, image.pixels.get(), static_cast<std::size_t>(image.width) * image.height,
         spec.nchannels);
  return image;
}

Image describeImage(const std::string& path, bool* canReadInBands) {
  const OpenImage file = openImage(path);
  const OIIO::ImageSpec& spec = file.in->spec();
  if (canReadInBands) *canReadInBands = spec.tile_width == 0 && !spec.deep && !windowsDiffer(spec);
  return description(file);
}

Image readImageBands(const std::string& path, int bandRows,
                     const std::function<void(const ImageView&)>& consume) {
  OpenImage file = openImage(path, true);
  auto& in = file.in;
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.tile_width != 0 || spec.deep || windowsDiffer(spec))
    throw Error("cannot read probe '" + path +
                "' band by band: it is tiled, deep or cropped to a data window (read it whole)");
  Image info = description(file);
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
    if (!readClean(read, *in)) throw readFailure(path, *in);
    decode(file.transfer, buffers[b % 2].data(), static_cast<std::size_t>(y1 - y0) * W, channels);
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

void writeImage(const ImageView& image, const std::string& path) {
  std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(path);
  if (!out) throw Error("cannot write image '" + path + "': " + oneLine(OIIO::geterror()));
  OIIO::ImageSpec spec(image.width, image.height, image.channels, OIIO::TypeDesc::FLOAT);
  const bool ok = out->open(path, spec) &&
                  out->write_image(OIIO::TypeDesc::FLOAT, image.pixels, image.pixelStep() * sizeof(float),
                                   image.rowStep() * sizeof(float)) &&
                  out->close();
  if (!ok) throw Error("cannot write image '" + path + "': " + oneLine(out->geterror()));
}

Probe loadProbe(const std::string& path, const ProbeOptions& options) {
  return Probe(readImage(path), options.projection, options.nonFinite, path);
}

Probe loadProbeUnchecked(const std::string& path, const ProbeOptions& options) {
  return Probe(readImage(path), options.projection, path);
}

}  // namespace probelights
