// The stand-in for OpenImageIO's C++ API (oiio_python/OpenImageIO/imageio.h), carried out by the Python
// binding of PyPI's openimageio wheel, in the Python package's Windows and macOS modules. Each call takes the
// GIL (the module releases it while the core works, so a reading thread of the core may call here too), and
// turns a Python error into the failure OpenImageIO's C++ API would report (false or null, with its message
// for geterror()).
#include <OpenImageIO/imageio.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>

namespace py = pybind11;

namespace OIIO {

namespace {

// The openimageio module, imported on first use and kept for the life of the process (never released: the
// interpreter may be finalising when static objects go).
py::module_& oiio() {
  static py::module_* m = new py::module_(py::module_::import("OpenImageIO"));
  return *m;
}

py::object& held(const PyRef& r) { return *reinterpret_cast<py::object*>(const_cast<PyRef&>(r).get()); }
void* hold(py::object o) { return new py::object(std::move(o)); }

std::string pythonError(py::error_already_set& e) {
  std::string why = e.what();
  e.restore();
  PyErr_Clear();
  return why;
}

// Runs f() with the GIL taken; a Python exception becomes `failed`, its message kept in `error`.
template <class R, class F>
R guarded(std::string& error, R failed, F&& f) {
  py::gil_scoped_acquire gil;
  try {
    return f();
  } catch (py::error_already_set& e) {
    error = pythonError(e);
    return failed;
  }
}

// What a failed call said: ours (a Python exception) before the binding's own geterror().
std::string errorOf(const py::object& object, std::string& ours, bool clear) {
  std::string why = ours, ignored;
  if (clear) ours.clear();
  const std::string theirs =
      guarded(ignored, std::string(), [&] { return object.attr("geterror")(clear).cast<std::string>(); });
  return why.empty() ? theirs : why;
}

const char* typeName(TypeDesc t) {
  switch (t.basetype) {
    case TypeDesc::UINT8:
      return "uint8";
    case TypeDesc::INT8:
      return "int8";
    case TypeDesc::UINT16:
      return "uint16";
    case TypeDesc::INT16:
      return "int16";
    case TypeDesc::UINT32:
      return "uint32";
    case TypeDesc::INT32:
      return "int32";
    case TypeDesc::HALF:
      return "half";
    case TypeDesc::DOUBLE:
      return "double";
    case TypeDesc::FLOAT:
      return "float";
    default:
      return "unknown";
  }
}

TypeDesc typeOf(const py::handle& t) {
  return TypeDesc(static_cast<TypeDesc::BASETYPE>(t.attr("basetype").attr("value").cast<int>()));
}

ImageSpec specOf(const py::object& s) {
  ImageSpec spec;
  for (auto [field, name] : {std::pair{&spec.x, "x"},
                             {&spec.y, "y"},
                             {&spec.z, "z"},
                             {&spec.width, "width"},
                             {&spec.height, "height"},
                             {&spec.depth, "depth"},
                             {&spec.full_x, "full_x"},
                             {&spec.full_y, "full_y"},
                             {&spec.full_z, "full_z"},
                             {&spec.full_width, "full_width"},
                             {&spec.full_height, "full_height"},
                             {&spec.full_depth, "full_depth"},
                             {&spec.tile_width, "tile_width"},
                             {&spec.nchannels, "nchannels"}})
    *field = s.attr(name).cast<int>();
  spec.deep = s.attr("deep").cast<bool>();
  spec.format = typeOf(s.attr("format"));
  for (const py::handle t : s.attr("channelformats")) spec.channelformats.push_back(typeOf(t));
  for (const py::handle n : s.attr("channelnames")) spec.channelnames.push_back(n.cast<std::string>());
  for (const char* name : {"Software", "oiio:ColorSpace"})
    if (std::string v = s.attr("get_string_attribute")(name, "").cast<std::string>(); !v.empty())
      spec.strings[name] = v;
  if (float g = s.attr("get_float_attribute")("oiio:Gamma", 0.0f).cast<float>(); g != 0)
    spec.floats["oiio:Gamma"] = g;
  return spec;
}

py::object pythonSpec(const ImageSpec& spec, TypeDesc format) {
  py::object s = oiio().attr("ImageSpec")(spec.width, spec.height, spec.nchannels, typeName(format));
  for (const auto& [name, value] : spec.strings) s.attr("attribute")(name, value);
  for (const auto& [name, value] : spec.ints) s.attr("attribute")(name, value);
  return s;
}

// An H x W x C float array of the buffer.
py::array_t<float> arrayOf(const float* pixels, int width, int height, int channels) {
  py::array_t<float> a({height, width, channels});
  std::memcpy(a.mutable_data(), pixels, sizeof(float) * static_cast<std::size_t>(width) * height * channels);
  return a;
}

// Copies a float array of `count` values into `data`; false when its size differs.
bool copyOut(const py::object& result, void* data, std::size_t count) {
  if (result.is_none()) return false;
  auto a = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(result);
  if (!a || static_cast<std::size_t>(a.size()) != count) return false;
  std::memcpy(data, a.data(), count * sizeof(float));
  return true;
}

}  // namespace

std::size_t TypeDesc::size() const {
  switch (basetype) {
    case UINT8:
    case INT8:
      return 1;
    case UINT16:
    case INT16:
    case HALF:
      return 2;
    case UINT32:
    case INT32:
    case FLOAT:
      return 4;
    case UINT64:
    case INT64:
    case DOUBLE:
      return 8;
    default:
      return 0;
  }
}

ROI roi_intersection(const ROI& a, const ROI& b) {
  return ROI(std::max(a.xbegin, b.xbegin), std::min(a.xend, b.xend), std::max(a.ybegin, b.ybegin),
             std::min(a.yend, b.yend));
}

ImageSpec::ImageSpec(int w, int h, int channels, TypeDesc fmt)
    : width(w), height(h), full_width(w), full_height(h), full_depth(1), nchannels(channels), format(fmt) {}

std::string ImageSpec::get_string_attribute(std::string_view name, std::string_view otherwise) const {
  auto it = strings.find(std::string(name));
  return it != strings.end() ? it->second : std::string(otherwise);
}

float ImageSpec::get_float_attribute(std::string_view name, float otherwise) const {
  auto it = floats.find(std::string(name));
  return it != floats.end() ? it->second : otherwise;
}

void PyRef::reset(void* object) {
  if (object_) {
    py::gil_scoped_acquire gil;
    delete reinterpret_cast<py::object*>(object_);
  }
  object_ = object;
}

PyRef::~PyRef() { reset(nullptr); }

namespace {
// What the last failed open or create said (OIIO::geterror()), per thread as OpenImageIO keeps it: a library
// bake opens probes on several threads at once.
thread_local std::string lastError;
}  // namespace

ImageInput::unique_ptr ImageInput::open(const std::string& filename, const ImageSpec* config) {
  return guarded(lastError, unique_ptr(), [&]() -> unique_ptr {
    py::object in =
        config ? oiio().attr("ImageInput").attr("open")(filename, pythonSpec(*config, TypeDesc::FLOAT))
               : oiio().attr("ImageInput").attr("open")(filename);
    if (in.is_none()) {
      lastError = oiio().attr("geterror")().cast<std::string>();
      return nullptr;
    }
    unique_ptr input(new ImageInput);
    input->spec_ = specOf(in.attr("spec")());
    input->format_ = in.attr("format_name")().cast<std::string>();
    input->in_.reset(hold(std::move(in)));
    return input;
  });
}

bool ImageInput::read_image(int subimage, int miplevel, int chbegin, int chend, TypeDesc format, void* data) {
  const std::size_t count = static_cast<std::size_t>(spec_.image_pixels()) * (chend - chbegin);
  return format == TypeDesc::FLOAT && guarded(error_, false, [&] {
           return copyOut(held(in_).attr("read_image")(subimage, miplevel, chbegin, chend, "float"), data,
                          count);
         });
}

bool ImageInput::read_scanlines(int subimage, int miplevel, int ybegin, int yend, int z, int chbegin,
                                int chend, TypeDesc format, void* data) {
  const std::size_t count = static_cast<std::size_t>(yend - ybegin) * spec_.width * (chend - chbegin);
  return format == TypeDesc::FLOAT && guarded(error_, false, [&] {
           py::object rows =
               held(in_).attr("read_scanlines")(subimage, miplevel, ybegin, yend, z, chbegin, chend, "float");
           return copyOut(rows, data, count);
         });
}

bool ImageInput::has_error() const {
  std::string ignored;
  return !error_.empty() || guarded(ignored, true, [&] {
    py::object flag = held(in_).attr("has_error");  // a property in OpenImageIO 3's binding
    return (PyCallable_Check(flag.ptr()) ? flag() : flag).cast<bool>();
  });
}

std::string ImageInput::geterror(bool clear) { return errorOf(held(in_), error_, clear); }

ImageOutput::unique_ptr ImageOutput::create(const std::string& filename) {
  return guarded(lastError, unique_ptr(), [&]() -> unique_ptr {
    py::object out = oiio().attr("ImageOutput").attr("create")(filename);
    if (out.is_none()) {
      lastError = oiio().attr("geterror")().cast<std::string>();
      return nullptr;
    }
    unique_ptr output(new ImageOutput);
    output->out_.reset(hold(std::move(out)));
    return output;
  });
}

bool ImageOutput::open(const std::string& filename, const ImageSpec& spec) {
  spec_ = spec;
  return guarded(error_, false, [&] {
    return held(out_).attr("open")(filename, pythonSpec(spec, spec.format)).cast<bool>();
  });
}

bool ImageOutput::write_image(TypeDesc format, const void* data, std::ptrdiff_t xstride,
                              std::ptrdiff_t ystride) {
  if (format != TypeDesc::FLOAT) return error_ = "only float pixels are written", false;
  const int W = spec_.width, H = spec_.height, C = spec_.nchannels;
  std::vector<float> packed(static_cast<std::size_t>(W) * H * C);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x)
      std::memcpy(&packed[(static_cast<std::size_t>(y) * W + x) * C],
                  static_cast<const char*>(data) + y * ystride + x * xstride, sizeof(float) * C);
  return guarded(error_, false, [&] {
    return held(out_).attr("write_image")(arrayOf(packed.data(), W, H, C)).cast<bool>();
  });
}

bool ImageOutput::close() {
  return guarded(error_, false, [&] { return held(out_).attr("close")().cast<bool>(); });
}

std::string ImageOutput::geterror(bool clear) { return errorOf(held(out_), error_, clear); }

ImageBuf::ImageBuf(const ImageSpec& spec)
    : spec_(spec), pixels_(static_cast<std::size_t>(spec.width) * spec.height * spec.nchannels, 0.0f) {}

bool ImageBuf::setpixel(int x, int y, const float* pixel, int n) {
  if (x < 0 || y < 0 || x >= spec_.width || y >= spec_.height) return false;
  std::copy_n(pixel, std::min(n, spec_.nchannels), at(x, y));
  return true;
}

// A Python ImageBuf holding these pixels (and this spec's metadata).
static py::object pythonBuf(ImageBuf& buf) {
  const ImageSpec& spec = buf.spec();
  py::object b = oiio().attr("ImageBuf")(pythonSpec(spec, TypeDesc::FLOAT));
  b.attr("set_pixels")(oiio().attr("ROI").attr("All"),
                       arrayOf(buf.pixels().data(), spec.width, spec.height, spec.nchannels));
  return b;
}

bool ImageBuf::write(const std::string& filename, TypeDesc format) {
  py::gil_scoped_acquire gil;
  try {
    py::object b = pythonBuf(*this);
    if (b.attr("write")(filename, typeName(format)).cast<bool>()) return true;
    error_ = b.attr("geterror")().cast<std::string>();
  } catch (py::error_already_set& e) {
    error_ = pythonError(e);
  }
  return false;
}

namespace ImageBufAlgo {

namespace {
void plot(ImageBuf& dst, int x, int y, cspan<float> color) {
  const ImageSpec& s = dst.spec();
  if (x < 0 || y < 0 || x >= s.width || y >= s.height) return;
  std::copy_n(color.data(), std::min<std::size_t>(color.size(), s.nchannels), dst.at(x, y));
}
}  // namespace

bool fill(ImageBuf& dst, cspan<float> values) {
  for (int y = 0; y < dst.spec().height; ++y)
    for (int x = 0; x < dst.spec().width; ++x) plot(dst, x, y, values);
  return true;
}

// As OpenImageIO's: the corners inclusive; filled, or the outline alone.
bool render_box(ImageBuf& dst, int x1, int y1, int x2, int y2, cspan<float> color, bool filled) {
  if (x2 < x1) std::swap(x1, x2);
  if (y2 < y1) std::swap(y1, y2);
  for (int y = y1; y <= y2; ++y)
    for (int x = x1; x <= x2; ++x)
      if (filled || y == y1 || y == y2 || x == x1 || x == x2) plot(dst, x, y, color);
  return true;
}

// Bresenham's line, both ends drawn (the first skipped on request), as OpenImageIO's.
bool render_line(ImageBuf& dst, int x1, int y1, int x2, int y2, cspan<float> color, bool skip_first) {
  const int dx = std::abs(x2 - x1), dy = -std::abs(y2 - y1), sx = x1 < x2 ? 1 : -1, sy = y1 < y2 ? 1 : -1;
  for (int err = dx + dy, first = 1;; first = 0) {
    if (!(first && skip_first)) plot(dst, x1, y1, color);
    if (x1 == x2 && y1 == y2) break;
    const int e2 = 2 * err;
    if (e2 >= dy) err += dy, x1 += sx;
    if (e2 <= dx) err += dx, y1 += sy;
  }
  return true;
}

bool render_text(ImageBuf& dst, int x, int y, std::string_view text, int fontsize, std::string_view fontname,
                 cspan<float> color) {
  py::gil_scoped_acquire gil;
  try {
    py::object b = pythonBuf(dst);
    py::tuple colour(color.size());
    for (std::size_t i = 0; i < color.size(); ++i) colour[i] = color[i];
    if (!oiio()
             .attr("ImageBufAlgo")
             .attr("render_text")(b, x, y, std::string(text), fontsize, std::string(fontname), colour)
             .cast<bool>()) {
      dst.set_error(b.attr("geterror")().cast<std::string>());
      return false;
    }
    return copyOut(b.attr("get_pixels")("float"), dst.pixels().data(), dst.pixels().size());
  } catch (py::error_already_set& e) {
    dst.set_error(pythonError(e));
    return false;
  }
}

}  // namespace ImageBufAlgo

namespace Strutil {
std::string lower(std::string_view s) {
  std::string r(s);
  for (char& c : r) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return r;
}
std::string upper(std::string_view s) {
  std::string r(s);
  for (char& c : r) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return r;
}
bool icontains(std::string_view a, std::string_view b) {
  return lower(a).find(lower(b)) != std::string::npos;
}
bool istarts_with(std::string_view a, std::string_view b) { return lower(a).rfind(lower(b), 0) == 0; }
}  // namespace Strutil

bool attribute(std::string_view name, int value) {
  py::gil_scoped_acquire gil;
  try {
    return oiio().attr("attribute")(std::string(name), value), true;
  } catch (py::error_already_set& e) {
    pythonError(e);
    return false;
  }
}

std::string geterror(bool clear) {
  std::string why = lastError;
  if (clear) lastError.clear();
  return why;
}

}  // namespace OIIO
