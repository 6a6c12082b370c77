// OpenImageIO's C++ API as far as probelights uses it (native/src/image.cpp, preview.cpp, native/cli/),
// carried out by PyPI's `openimageio` wheel through its Python binding (oiio_python.cpp). It stands in for
// OpenImageIO's own headers in the Python package's Windows and macOS modules: their C++ library is built
// with MSVC (Windows) or Apple's libc++ ABI (macOS), which zig's clang + libc++ cannot link, while its Python
// binding is a C API away (docs/decisions.md). One copy of OpenImageIO still: the wheel's, which pip keeps up
// to date. Only what is declared here exists; every call takes the GIL itself, so callers may hold it or not.
#pragma once

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace OIIO {

struct TypeDesc {
  enum BASETYPE : unsigned char {
    UNKNOWN,
    NONE,
    UINT8,
    INT8,
    UINT16,
    INT16,
    UINT32,
    INT32,
    UINT64,
    INT64,
    HALF,
    FLOAT,
    DOUBLE
  };
  unsigned char basetype = UNKNOWN;
  constexpr TypeDesc(BASETYPE b = UNKNOWN) : basetype(b) {}
  std::size_t size() const;  // bytes of one value
  friend bool operator==(TypeDesc a, TypeDesc b) { return a.basetype == b.basetype; }
  friend bool operator!=(TypeDesc a, TypeDesc b) { return a.basetype != b.basetype; }
};

template <class T>
struct cspan {
  const T* data_ = nullptr;
  std::size_t size_ = 0;
  cspan(const T* p, std::size_t n) : data_(p), size_(n) {}
  template <std::size_t N>
  cspan(const T (&a)[N]) : data_(a), size_(N) {}
  cspan(std::initializer_list<T> l) : data_(l.begin()), size_(l.size()) {}
  const T* data() const { return data_; }
  std::size_t size() const { return size_; }
  const T& operator[](std::size_t i) const { return data_[i]; }
};

struct ROI {
  int xbegin = 0, xend = 0, ybegin = 0, yend = 0;
  ROI() = default;
  ROI(int x0, int x1, int y0, int y1) : xbegin(x0), xend(x1), ybegin(y0), yend(y1) {}
  bool defined() const { return xbegin != xend || ybegin != yend; }
  std::int64_t npixels() const {
    return xend > xbegin && yend > ybegin ? std::int64_t{xend - xbegin} * (yend - ybegin) : 0;
  }
};
ROI roi_intersection(const ROI& a, const ROI& b);

struct ImageSpec {
  int x = 0, y = 0, z = 0, width = 0, height = 0, depth = 1;
  int full_x = 0, full_y = 0, full_z = 0, full_width = 0, full_height = 0, full_depth = 0;
  int tile_width = 0, nchannels = 0;
  bool deep = false;
  TypeDesc format;
  std::vector<TypeDesc> channelformats;
  std::vector<std::string> channelnames;
  // The string and float metadata probelights reads (Software, oiio:ColorSpace, oiio:Gamma), copied from the
  // file's, and what it sets for a write.
  std::map<std::string, std::string> strings;
  std::map<std::string, float> floats;
  std::map<std::string, int> ints;  // set for an open (a config)

  ImageSpec() = default;
  ImageSpec(int w, int h, int channels, TypeDesc fmt);
  std::string get_string_attribute(std::string_view name, std::string_view otherwise = {}) const;
  float get_float_attribute(std::string_view name, float otherwise = 0) const;
  void attribute(std::string_view name, std::string_view value) { strings[std::string(name)] = value; }
  void attribute(std::string_view name, int value) { ints[std::string(name)] = value; }
  std::int64_t image_pixels() const { return std::int64_t{width} * height * (depth > 0 ? depth : 1); }
};

namespace Filesystem {
struct IOProxy {
  virtual ~IOProxy() = default;
};
// Reads from memory are OpenImageIO's C++ API alone: ImageInput::create gives nothing here, so image.cpp
// reads files by name.
struct IOMemReader : IOProxy {
  IOMemReader(const void*, std::size_t) {}
};
}  // namespace Filesystem

// A Python object (PyObject*) held with the GIL taken for its release.
class PyRef {
 public:
  PyRef() = default;
  explicit PyRef(void* object) : object_(object) {}
  PyRef(const PyRef&) = delete;
  PyRef& operator=(const PyRef&) = delete;
  ~PyRef();
  void* get() const { return object_; }
  void reset(void* object);  // the one held before is released

 private:
  void* object_ = nullptr;
};

class ImageInput {
 public:
  using unique_ptr = std::unique_ptr<ImageInput>;
  static unique_ptr open(const std::string& filename, const ImageSpec* config = nullptr);
  static unique_ptr create(const std::string&, bool = false) { return nullptr; }
  const ImageSpec& spec() const { return spec_; }
  const char* format_name() const { return format_.c_str(); }
  bool read_image(int subimage, int miplevel, int chbegin, int chend, TypeDesc format, void* data);
  bool read_scanlines(int subimage, int miplevel, int ybegin, int yend, int z, int chbegin, int chend,
                      TypeDesc format, void* data);
  bool read_native_scanlines(int subimage, int miplevel, int ybegin, int yend, int z, int chbegin, int chend,
                             void* data) {
    return read_scanlines(subimage, miplevel, ybegin, yend, z, chbegin, chend, TypeDesc::FLOAT, data);
  }
  bool has_error() const;
  std::string geterror(bool clear = true);
  bool supports(std::string_view) const { return false; }
  bool set_ioproxy(Filesystem::IOProxy*) { return false; }
  bool open(const std::string&, ImageSpec&, const ImageSpec&) { return false; }

 private:
  ImageInput() = default;
  PyRef in_;
  ImageSpec spec_;
  std::string format_, error_;
};

class ImageOutput {
 public:
  using unique_ptr = std::unique_ptr<ImageOutput>;
  static unique_ptr create(const std::string& filename);
  bool open(const std::string& filename, const ImageSpec& spec);
  bool write_image(TypeDesc format, const void* data, std::ptrdiff_t xstride, std::ptrdiff_t ystride);
  bool close();
  std::string geterror(bool clear = true);

 private:
  ImageOutput() = default;
  PyRef out_;
  ImageSpec spec_;
  std::string error_;
};

// An image in memory: float pixels kept here, drawn on here (fill, boxes, lines), handed to Python for text
// and for writing.
class ImageBuf {
 public:
  explicit ImageBuf(const ImageSpec& spec);
  const ImageSpec& spec() const { return spec_; }
  bool setpixel(int x, int y, const float* pixel, int n);
  bool write(const std::string& filename, TypeDesc format = TypeDesc::UNKNOWN);
  std::string geterror(bool = true) const { return error_; }
  float* at(int x, int y) {
    return &pixels_[(static_cast<std::size_t>(y) * spec_.width + x) * spec_.nchannels];
  }
  std::vector<float>& pixels() { return pixels_; }
  void set_error(std::string e) { error_ = std::move(e); }

 private:
  ImageSpec spec_;
  std::vector<float> pixels_;
  std::string error_;
};

namespace ImageBufAlgo {
bool fill(ImageBuf& dst, cspan<float> values);
bool render_box(ImageBuf& dst, int x1, int y1, int x2, int y2, cspan<float> color, bool fill = false);
bool render_line(ImageBuf& dst, int x1, int y1, int x2, int y2, cspan<float> color, bool skip_first = false);
bool render_text(ImageBuf& dst, int x, int y, std::string_view text, int fontsize, std::string_view fontname,
                 cspan<float> color);
}  // namespace ImageBufAlgo

namespace Strutil {
std::string lower(std::string_view s);
std::string upper(std::string_view s);
bool icontains(std::string_view a, std::string_view b);
bool istarts_with(std::string_view a, std::string_view b);
}  // namespace Strutil

bool attribute(std::string_view name, int value);
std::string geterror(bool clear = true);

}  // namespace OIIO
