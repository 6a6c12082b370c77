// What reading a probe costs against each format's own decoder (issue 10, "loading near the decoder's
// limit"): OpenImageIO's whole-image read and its band reads (what grid_load.h uses) next to OpenEXR's own
// readPixels with the same threads, a plain RGBE decoder written here for .hdr, and reading the file's bytes
// (the floor: the file is in the page cache after the first run).
//
//   build/bin/probelights_decode_bench                         the bundled probe resized to 8192 x 4096
//   build/bin/probelights_decode_bench --benchmark_filter=hdr  one format
//   PROBELIGHTS_LIBRARY=DIR build/bin/probelights_decode_bench --benchmark_filter=Library
//                                          every image file of DIR read one after another (what `probelights
//                                          bake DIR --out-dir` is measured against: bench/bench_library.sh)
// The files are made once in $TMPDIR/probelights_decode/ (Radiance .hdr, OpenEXR half and float with ZIP).
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfThreading.h>
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "probelights/batch.h"
#include "probelights/image_file.h"

namespace {

namespace fs = std::filesystem;
using namespace probelights;

enum Format { kHdr, kExrHalf, kExrFloat };
const char* kNames[] = {"hdr", "exr_half_zip", "exr_float_zip"};

std::string file(Format f) {
  static const fs::path dir = fs::temp_directory_path() / "probelights_decode";
  static const char* kFiles[] = {"8k.hdr", "8k_half.exr", "8k_float.exr"};
  const fs::path path = dir / kFiles[f];
  if (!fs::exists(path)) {
    fs::create_directories(dir);
    OIIO::ImageBuf src(PROBELIGHTS_BUNDLED_PROBE);
    OIIO::ImageBuf big = OIIO::ImageBufAlgo::resize(src, OIIO::ImageBufAlgo::KWArgs(),
                                                    OIIO::ROI(0, 8192, 0, 4096, 0, 1, 0, 3));
    if (f != kHdr) big.specmod().attribute("compression", "zip");
    const OIIO::TypeDesc type = f == kExrHalf ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT;
    const fs::path part = path.string() + ".part";
    if (!big.write(part.string(), type, f == kHdr ? "hdr" : "openexr"))
      throw std::runtime_error("cannot write " + part.string() + ": " + big.geterror());
    fs::rename(part, path);
  }
  return path.string();
}

void setThreads(int n) {
  OIIO::attribute("threads", n);
  OIIO::attribute("exr_threads", n);
  Imf::setGlobalThreadCount(n);
}

void report(benchmark::State& state, Format f) {
  state.SetLabel(kNames[f]);
  state.counters["MB_float_out"] = 8192.0 * 4096 * 3 * 4 / 1e6;
}

void BM_FileBytes(benchmark::State& state) {
  const Format f = static_cast<Format>(state.range(0));
  const std::string path = file(f);
  std::vector<char> bytes(fs::file_size(path));
  for (auto _ : state) {
    std::ifstream in(path, std::ios::binary);
    in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    benchmark::DoNotOptimize(bytes.data());
  }
  report(state, f);
  state.counters["MB_file"] = bytes.size() / 1e6;
}

void BM_OIIO_WholeImage(benchmark::State& state) {
  const Format f = static_cast<Format>(state.range(0));
  const std::string path = file(f);
  setThreads(static_cast<int>(state.range(1)));
  for (auto _ : state) benchmark::DoNotOptimize(readImage(path).pixels.get());
  report(state, f);
}

void BM_OIIO_Bands(benchmark::State& state) {
  const Format f = static_cast<Format>(state.range(0));
  const std::string path = file(f);
  setThreads(static_cast<int>(state.range(1)));
  for (auto _ : state) {
    double sum = 0;
    readImageBands(path, 256, [&](const ImageView& band) { sum += band.pixels[0]; });
    benchmark::DoNotOptimize(sum);
  }
  report(state, f);
}

// OpenEXR's own API: RGB as float slices of one buffer, all rows in one readPixels (its threads decode the
// chunks in parallel).
void BM_OpenEXR_ReadPixels(benchmark::State& state) {
  const Format f = static_cast<Format>(state.range(0));
  const std::string path = file(f);
  setThreads(static_cast<int>(state.range(1)));
  for (auto _ : state) {
    Imf::InputFile in(path.c_str());
    const Imath::Box2i dw = in.header().dataWindow();
    const int W = dw.max.x - dw.min.x + 1, H = dw.max.y - dw.min.y + 1;
    std::vector<float> pixels(static_cast<std::size_t>(W) * H * 3);
    Imf::FrameBuffer fb;
    const char* channels[] = {"R", "G", "B"};
    for (int c = 0; c < 3; ++c) {
      char* base = reinterpret_cast<char*>(pixels.data() + c) -
                   (static_cast<std::ptrdiff_t>(dw.min.y) * W + dw.min.x) * 3 * sizeof(float);
      fb.insert(channels[c], Imf::Slice(Imf::FLOAT, base, 3 * sizeof(float), 3 * sizeof(float) * W));
    }
    in.setFrameBuffer(fb);
    in.readPixels(dw.min.y, dw.max.y);
    benchmark::DoNotOptimize(pixels.data());
  }
  report(state, f);
}

// A plain Radiance RGBE decoder: header, then per scanline the new-style run-length encoding (four channels
// one after the other) or flat RGBE; mantissas scaled by 2^(e - 136), as OpenImageIO's reader does.
std::vector<float> decodeRgbe(const std::vector<unsigned char>& b) {
  std::size_t i = 0;
  auto line = [&] {
    std::string s;
    while (i < b.size() && b[i] != '\n') s += static_cast<char>(b[i++]);
    ++i;
    return s;
  };
  while (!line().empty()) {
  }
  int W = 0, H = 0;
  if (std::sscanf(line().c_str(), "-Y %d +X %d", &H, &W) != 2) throw std::runtime_error("unsupported layout");
  std::vector<float> out(static_cast<std::size_t>(W) * H * 3);
  std::vector<unsigned char> row(static_cast<std::size_t>(W) * 4);
  float scale[256];
  for (int e = 0; e < 256; ++e) scale[e] = e ? std::ldexp(1.0f, e - 136) : 0.0f;
  for (int y = 0; y < H; ++y) {
    if (b[i] == 2 && b[i + 1] == 2 && ((b[i + 2] << 8) | b[i + 3]) == W) {
      i += 4;
      for (int c = 0; c < 4; ++c)
        for (int x = 0; x < W;) {
          int n = b[i++];
          if (n > 128) {
            n -= 128;
            std::memset(&row[c * W + x], b[i++], n);
          } else {
            std::memcpy(&row[c * W + x], &b[i], n);
            i += n;
          }
          x += n;
        }
      float* o = &out[static_cast<std::size_t>(y) * W * 3];
      for (int x = 0; x < W; ++x) {
        const float s = scale[row[3 * W + x]];
        o[3 * x] = row[x] * s, o[3 * x + 1] = row[W + x] * s, o[3 * x + 2] = row[2 * W + x] * s;
      }
    } else {
      float* o = &out[static_cast<std::size_t>(y) * W * 3];
      for (int x = 0; x < W; ++x, i += 4) {
        const float s = scale[b[i + 3]];
        o[3 * x] = b[i] * s, o[3 * x + 1] = b[i + 1] * s, o[3 * x + 2] = b[i + 2] * s;
      }
    }
  }
  return out;
}

void BM_PlainRgbe(benchmark::State& state) {
  const std::string path = file(kHdr);
  for (auto _ : state) {
    std::ifstream in(path, std::ios::binary);
    std::vector<unsigned char> bytes(fs::file_size(path));
    in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    benchmark::DoNotOptimize(decodeRgbe(bytes).data());
  }
  report(state, kHdr);
}

// A library's reads alone: every file of $PROBELIGHTS_LIBRARY read whole, one after another, in this process.
void BM_LibraryReads(benchmark::State& state) {
  const char* dir = std::getenv("PROBELIGHTS_LIBRARY");
  if (!dir) {
    state.SkipWithError("set PROBELIGHTS_LIBRARY to a folder of probes");
    return;
  }
  const std::vector<std::string> paths = expandProbePaths({dir});
  for (auto _ : state)
    for (const std::string& path : paths) benchmark::DoNotOptimize(readImage(path).pixels.get());
  state.counters["files"] = static_cast<double>(paths.size());
}

void formatsAndThreads(benchmark::internal::Benchmark* b) {
  for (int f : {kHdr, kExrHalf, kExrFloat})
    for (int threads : {1, 2}) b->Args({f, threads});
}

BENCHMARK(BM_FileBytes)
    ->Arg(kHdr)
    ->Arg(kExrHalf)
    ->Arg(kExrFloat)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_OIIO_WholeImage)->Apply(formatsAndThreads)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_OIIO_Bands)->Apply(formatsAndThreads)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_OpenEXR_ReadPixels)
    ->Args({kExrHalf, 1})
    ->Args({kExrHalf, 2})
    ->Args({kExrFloat, 1})
    ->Args({kExrFloat, 2})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_PlainRgbe)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_LibraryReads)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1)->Repetitions(6);

}  // namespace

BENCHMARK_MAIN();
