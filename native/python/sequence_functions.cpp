// The module's SequenceBaker: the frames of an animated world given one by one as pixels (a rendered sky, an
// image sequence the caller reads), baked into the same N lights each frame with their ids kept
// (sequence.h); its keywords the sequence table's options (sequence_request.h), the GIL released while a
// frame bakes.
#include <pybind11/stl.h>

#include <memory>
#include <optional>

#include "probelights/sequence_request.h"
#include "shell.h"

namespace probelights::shell {
namespace {

class PySequenceBaker {
 public:
  explicit PySequenceBaker(const py::kwargs& options)
      : request_(fromKeywords(sequenceOptions(), options)), baker_(makeSequenceBaker(request_)) {}

  py::dict add(Pixels pixels, const std::string& projection, int frameNumber) {
    const ImageView view = viewOf(pixels);
    const ProjectionKind kind = parseProjection(projection);
    std::optional<Probe> probe;
    std::optional<SequenceFrame> frame;
    std::optional<FrameResponse> judged;
    {
      py::gil_scoped_release release;
      probe.emplace(view, kind, request_.judging.probe.nonFinite);
      frame.emplace(baker_.add(*probe));
      if (request_.judging.accuracy.evaluate)
        judged = judgeFrame(*probe, frame->lights, request_.judging.accuracy.evaluatorWidth);
    }
    py::dict out;
    DictWriter writer(out);
    writeSequenceFrame(writer, {frameNumber, "", *probe, *frame, judged ? &*judged : nullptr, 0});
    return out;
  }
  int frames() const { return baker_.frames(); }

 private:
  SequenceRequest request_;
  SequenceBaker baker_;
};

}  // namespace

void defineSequence(py::module_& m) {
  static const std::string doc =
      "SequenceBaker(**options): bakes the frames of an animated world, given one by one with add(), into "
      "the "
      "same N lights each frame, each keeping its id (a light's row in every frame's table is the same "
      "light)."
      " add(pixels, *, projection='latlong', frame=0) takes a float32 H x W x C array like bake() (every "
      "frame "
      "of one size) and returns the frame's layout: frame, source, recut, motion, spread, fresh_spread, "
      "lights "
      "(a dict of numpy arrays with id), total_rgb, timings_ms, notes, evaluation (diffuse, shadow when "
      "evaluate)." +
      optionsDoc(sequenceOptions());
  py::class_<PySequenceBaker>(m, "SequenceBaker", doc.c_str())
      .def(py::init<const py::kwargs&>())
      .def("add", &PySequenceBaker::add, py::arg("pixels"), py::kw_only(), py::arg("projection") = "latlong",
           py::arg("frame") = 0, "Bake the next frame: its lights, ids kept from the frames before.")
      .def_property_readonly("frames", &PySequenceBaker::frames, "How many frames were added.");
}

}  // namespace probelights::shell
