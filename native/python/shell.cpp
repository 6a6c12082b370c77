// What the module's parts share (shell.h): Python's view of the core's text, paths, pixels and results.
#include "shell.h"

#include <memory>

#include "probelights/names.h"
#include "probelights/placement.h"

namespace probelights::shell {

std::string spelled(const Remedy& remedy) {
  std::vector<std::string> values;
  for (const std::string& v : remedy.values) values.push_back("'" + v + "'");
  return remedy.option + "=" + listOf(values);
}

py::str fsText(const std::string& s) {
  PyObject* o = PyUnicode_DecodeFSDefaultAndSize(s.data(), static_cast<Py_ssize_t>(s.size()));
  if (!o) throw py::error_already_set();
  return py::reinterpret_steal<py::str>(o);
}

std::string fsPath(const py::handle& p) {
  const std::string s = py::module_::import("os").attr("fsencode")(p).cast<std::string>();
  if (s.find('\0') != std::string::npos) throw Error("a path holds a NUL character");
  return s;
}

void DictWriter::begin(const char* key) {
  py::dict d;
  stack_.back()[key] = d;
  stack_.push_back(d);
}

void DictWriter::notes(const char* key, const std::vector<Note>& v) {
  py::list list;
  for (const Note& n : v)
    list.append(py::dict(py::arg("kind") = toString(n.kind), py::arg("text") = fsText(n.text),
                         py::arg("detail") = fsText(n.detail)));
  stack_.back()[key] = list;
}

void DictWriter::numbers(const char* key, std::span<const double> v) {
  stack_.back()[key] = py::array_t<double>(static_cast<py::ssize_t>(v.size()), v.data());
}

void DictWriter::table(const char* key, std::size_t rows, const std::vector<ResultColumn>& columns) {
  py::dict t;
  double values[16];
  for (const ResultColumn& c : columns) {
    if (c.kind == ResultColumn::Kind::Text) {
      py::list words;
      for (std::size_t i = 0; i < rows; ++i) words.append(c.text(i));
      t[c.key] = words;
      continue;
    }
    std::vector<py::ssize_t> shape{static_cast<py::ssize_t>(rows)};
    if (c.width > 1) shape.push_back(c.width);
    auto fill = [&](auto array) {
      auto* data = array.mutable_data();
      for (std::size_t i = 0; i < rows; ++i) {
        c.fill(i, values);
        for (int k = 0; k < c.width; ++k)
          data[i * c.width + k] = static_cast<std::remove_reference_t<decltype(data[0])>>(values[k]);
      }
      t[c.key] = array;
    };
    if (c.kind == ResultColumn::Kind::Integer)
      fill(py::array_t<long long>(shape));
    else if (c.kind == ResultColumn::Kind::Boolean)
      fill(py::array_t<bool>(shape));
    else
      fill(py::array_t<double>(shape));
  }
  stack_.back()[key] = t;
}

py::dict toDict(const std::string& path, const Probe& probe, const BakeOptions& options,
                const EvaluatedBake& bake, double loadMs) {
  py::dict d;
  DictWriter writer(d);
  writeBake(writer, {path, probe, options, bake, loadMs});
  if (bake.sources) {
    // The residual image itself (H x W x 3 float32, read-only), sharing the bake's memory.
    const auto image = bake.sources->residual;
    auto* keep = new std::shared_ptr<const Image>(image);
    py::capsule owner(keep, [](void* p) { delete static_cast<std::shared_ptr<const Image>*>(p); });
    const auto f = static_cast<py::ssize_t>(sizeof(float));
    py::array_t<float> residual(
        {static_cast<py::ssize_t>(image->height), static_cast<py::ssize_t>(image->width), py::ssize_t{3}},
        {image->width * 3 * f, 3 * f, f}, image->pixels.get(), owner);
    residual.attr("flags").attr("writeable") = false;
    d["sources"].cast<py::dict>()["residual"] = residual;
  }
  return d;
}

ImageView viewOf(Pixels& pixels) {
  if (pixels.ndim() != 2 && pixels.ndim() != 3)
    throw Error("pixels must be a H x W or H x W x C array, got " + std::to_string(pixels.ndim()) +
                " dimensions");
  const int channels = pixels.ndim() == 3 ? static_cast<int>(pixels.shape(2)) : 1;
  if (pixels.ndim() == 3 && pixels.shape(2) > 1 &&
      pixels.strides(2) != static_cast<py::ssize_t>(sizeof(float)))
    pixels = py::array_t<float, py::array::forcecast | py::array::c_style>::ensure(pixels);
  // A stride that is not a whole number of floats, or 0 (a broadcast view repeats one row or pixel; the
  // view's 0 means "contiguous" and would read past the array): copied into a C-contiguous array first.
  for (int k = 0; k < 2; ++k)
    if (pixels.strides(k) % static_cast<py::ssize_t>(sizeof(float)) != 0 || pixels.strides(k) == 0)
      pixels = py::array_t<float, py::array::forcecast | py::array::c_style>::ensure(pixels);
  return ImageView{pixels.data(),
                   static_cast<int>(pixels.shape(1)),
                   static_cast<int>(pixels.shape(0)),
                   channels,
                   pixels.strides(0) / static_cast<py::ssize_t>(sizeof(float)),
                   pixels.strides(1) / static_cast<py::ssize_t>(sizeof(float))};
}

std::vector<Light> exportedLights(const py::dict& lights) {
  auto column = [&](const char* key, py::ssize_t width, bool required) {
    if (!lights.contains(key)) {
      if (required)
        throw Error(std::string("lights has no '") + key + "' (pass the 'lights' of a bake's result)");
      return py::array_t<double, py::array::c_style | py::array::forcecast>();
    }
    auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(lights[key]);
    if (!a || (width == 1 ? a.ndim() != 1 : (a.ndim() != 2 || a.shape(1) != width)))
      throw Error(std::string("lights['") + key + "'] must be an array of shape (N" +
                  (width == 1 ? "" : ", " + std::to_string(width)) + ")");
    return a;
  };
  const auto direction = column("direction", 3, true), rgb = column("rgb", 3, true);
  const auto angle = column("angle", 1, false), solidAngle = column("solid_angle", 1, false);
  const py::ssize_t n = direction.shape(0);
  if (rgb.shape(0) != n || (angle.size() && angle.shape(0) != n) ||
      (solidAngle.size() && solidAngle.shape(0) != n))
    throw Error("lights' columns differ in length");
  std::vector<Light> out(static_cast<std::size_t>(n));
  for (py::ssize_t i = 0; i < n; ++i) {
    Light& l = out[static_cast<std::size_t>(i)];
    l.direction = {direction.at(i, 0), direction.at(i, 1), direction.at(i, 2)};
    l.rgb = {rgb.at(i, 0), rgb.at(i, 1), rgb.at(i, 2)};
    if (angle.size()) l.angle = angle.at(i);
    if (solidAngle.size()) l.solidAngle = solidAngle.at(i);
  }
  return out;
}

std::string optionText(const std::string& name, const std::string& takes, const py::handle& value) {
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>() ? "true" : "false";
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  // A sequence (a list, a tuple, a range, a numpy array) of numbers or words: joined by commas.
  const auto isSequence = [](const py::handle v) {
    return PySequence_Check(v.ptr()) && !py::isinstance<py::str>(v) && !py::isinstance<py::bytes>(v);
  };
  const py::ssize_t n = isSequence(value) ? PySequence_Size(value.ptr()) : -1;
  if (n < 0) PyErr_Clear();  // not a sequence, or one without a length (a 0-d numpy array): a number below
  if (n >= 0) {
    std::string text;
    const py::sequence items = py::reinterpret_borrow<py::sequence>(value);
    for (py::ssize_t i = 0; i < n; ++i) {
      const py::object item = items[static_cast<std::size_t>(i)];
      if (isSequence(item)) throw Error(name + " takes " + takes + ", got a list in a list");
      text += (text.empty() ? "" : ",") + optionText(name, takes, item);
    }
    if (text.empty()) throw Error(name + " takes " + takes + ", got an empty list");
    return text;
  }
  if (py::hasattr(value, "__index__")) return py::str(py::int_(py::reinterpret_borrow<py::object>(value)));
  if (py::isinstance<py::float_>(value) || py::hasattr(value, "__float__"))
    return py::repr(py::float_(value.cast<double>()));  // a plain float's repr (numpy's reads np.float64(x))
  throw Error(name + " takes " + takes + ", got a " +
              py::str(py::type::handle_of(value).attr("__name__")).cast<std::string>());
}

std::string optionDoc(const std::string& name, const std::string& values, const std::string& help,
                      const std::string& value, bool isSwitch) {
  // A switch, or an on|off option, is a bool here; a list of words or a word in quotes; a number as it is.
  const bool onOff = isSwitch || values == "on|off";
  const bool list = values.find(",...") != std::string::npos;
  const bool word =
      !onOff && (values.find('|') != std::string::npos || values.find(',') != std::string::npos);
  std::string shown = onOff ? (value == "on" || value == "true" ? "True" : "False") : "'" + value + "'";
  if (list) {
    shown.clear();
    for (std::size_t at = 0; at <= value.size();) {
      const std::size_t comma = std::min(value.find(',', at), value.size());
      const std::string item = value.substr(at, comma - at);
      const bool number = !item.empty() && item.find_first_not_of("0123456789") == std::string::npos;
      shown += (shown.empty() ? "" : ", ") + (number ? item : "'" + item + "'");
      at = comma + 1;
    }
    shown = "[" + shown + "]";
  } else if (!onOff && !word) {
    shown = value;
  }
  return "\n  " + name + "=" + shown + ": " + help + (onOff || values.size() < 2 ? "" : " (" + values + ")");
}

std::vector<std::string> methodNames() {
  std::vector<std::string> names;
  for (const PlacementMethod& m : placementMethods()) names.push_back(m.name);
  return names;
}

}  // namespace probelights::shell
