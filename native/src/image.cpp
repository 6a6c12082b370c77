#include "probelights/image.h"

#include <OpenImageIO/imageio.h>

#include <filesystem>

#include "probelights/error.h"
#include "probelights/probe.h"

namespace probelights {

Image readImage(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw Error("cannot read probe '" + path + "': no such file");
  if (std::filesystem::is_directory(path, ec))
    throw Error("cannot read probe '" + path + "': it is a directory");

  auto in = OIIO::ImageInput::open(path);
  if (!in) {
    std::string why = OIIO::geterror();
    if (why.empty()) why = "not an image OpenImageIO can read";
    // OpenImageIO's messages can span lines; the user gets one.
    for (char& c : why)
      if (c == '\n') c = ' ';
    throw Error("cannot read probe '" + path + "': " + why);
  }
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0)
    throw Error("cannot read probe '" + path + "': the image is empty (" + std::to_string(spec.width) + "x" +
                std::to_string(spec.height) + ")");
  if (spec.depth > 1) throw Error("cannot read probe '" + path + "': volume images are not probes");

  Image image;
  image.width = spec.width;
  image.height = spec.height;
  image.channels = spec.nchannels;
  image.format = in->format_name();
  image.pixels.resize(static_cast<std::size_t>(spec.width) * spec.height * spec.nchannels);
  // Subimage 0, MIP level 0 (the finest), every channel, converted to float.
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, image.pixels.data())) {
    std::string why = in->geterror();
    for (char& c : why)
      if (c == '\n') c = ' ';
    throw Error("cannot read probe '" + path + "': " + (why.empty() ? "read failed" : why));
  }
  return image;
}

Probe Probe::load(const std::string& path, const ProbeOptions& options) {
  return Probe(readImage(path), options.projection, options.nonFinite, path);
}

}  // namespace probelights
