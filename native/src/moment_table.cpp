#include "probelights/moment_table.h"

#include <OpenImageIO/parallel.h>

#include <algorithm>
#include <charconv>

#include "probelights/error.h"

namespace probelights {

int WorkingResolution::cellSize(int probeWidth) const {
  constexpr int kAutoWidth = 2048;
  switch (mode) {
    case Mode::Full: return 1;
    case Mode::Auto: {
      int size = 1;
      while (probeWidth / size > kAutoWidth) size *= 2;
      return size;
    }
    case Mode::Width: return std::max(1, (probeWidth + width - 1) / std::max(1, width));
  }
  return 1;
}

std::optional<WorkingResolution> WorkingResolution::parse(const std::string& text) {
  if (text == "full") return WorkingResolution{Mode::Full, 0};
  if (text == "auto") return WorkingResolution{Mode::Auto, 0};
  int w = 0;
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), w);
  if (ec != std::errc() || end != text.data() + text.size() || w < 1) return std::nullopt;
  return WorkingResolution{Mode::Width, w};
}

std::string WorkingResolution::toString() const {
  switch (mode) {
    case Mode::Full: return "full";
    case Mode::Auto: return "auto";
    case Mode::Width: return std::to_string(width);
  }
  return "?";
}

MomentTable::MomentTable(const Probe& probe, int cellSize)
    : cellSize_(cellSize), pixelWidth_(probe.width()), pixelHeight_(probe.height()) {
  if (cellSize < 1) throw Error("working-grid cell size must be at least 1 pixel");
  const int W = probe.width(), H = probe.height();
  const int cellsX = (W + cellSize - 1) / cellSize, cellsY = (H + cellSize - 1) / cellSize;
  using Values = SummedAreaTable<5>::Values;

  // Cell rows are computed in parallel batches; the table consumes them in order. Each cell row is summed by one
  // thread in a fixed order, so the table is bit-identical whatever the thread count.
  const int batch = std::max(1, 64 / cellSize);
  std::vector<Values> cells(static_cast<std::size_t>(batch) * cellsX);
  std::vector<Rgb> rowIntegral(cellsY);
  std::vector<long long> rowLit(cellsY);
  int batchStart = -batch;

  auto computeCellRow = [&](int cy, std::span<Values> out) {
    std::vector<Vec3> dirs(W);
    std::vector<double> omega(W);
    std::fill(out.begin(), out.end(), Values{});
    Rgb integral{};
    for (int y = cy * cellSize; y < std::min(H, (cy + 1) * cellSize); ++y) {
      probe.projection().rowGeometry(y, 0, W, dirs, omega);
      for (int x = 0; x < W; ++x) {
        Rgb L = probe.radiance(x, y);
        double w = luminance(L) * omega[x];
        for (int k = 0; k < 3; ++k) integral[k] += L[k] * omega[x];
        Values& c = out[x / cellSize];
        c[0] += w;
        c[1] += w * dirs[x].x;
        c[2] += w * dirs[x].y;
        c[3] += w * dirs[x].z;
      }
    }
    rowIntegral[cy] = integral;
    long long lit = 0;
    for (Values& c : out) {
      c[4] = c[0] > 0 ? 1.0 : 0.0;
      lit += c[0] > 0;
    }
    rowLit[cy] = lit;
  };

  sat_ = SummedAreaTable<5>(cellsX, cellsY, [&](int cy, std::span<Values> row) {
    if (cy >= batchStart + batch) {
      batchStart = cy;
      int n = std::min(batch, cellsY - cy);
      OIIO::parallel_for(0, n, [&](int64_t i) {
        computeCellRow(cy + static_cast<int>(i),
                       std::span<Values>(cells.data() + i * cellsX, static_cast<std::size_t>(cellsX)));
      });
    }
    std::copy_n(cells.data() + static_cast<std::size_t>(cy - batchStart) * cellsX, cellsX, row.begin());
  });

  for (int cy = 0; cy < cellsY; ++cy) {
    for (int k = 0; k < 3; ++k) integral_[k] += rowIntegral[cy][k];
    litCells_ += rowLit[cy];
  }
  totalEnergy_ = sat_.sum(wholeGrid())[0];
}

Rect MomentTable::toPixels(const Rect& c) const {
  return {c.x0 * cellSize_, c.y0 * cellSize_, std::min(pixelWidth_, c.x1 * cellSize_),
          std::min(pixelHeight_, c.y1 * cellSize_)};
}

}  // namespace probelights
