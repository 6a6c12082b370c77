// The evaluator's truths (evaluator_truth.h): sums over the probe's samples, exact up to rounding.
#include "evaluator_truth.h"

#include <algorithm>
#include <cmath>

#include "parallel.h"
#include "probelights/cone.h"
#include "probelights/pixel_sums.h"

namespace probelights::truth {

namespace {

// A sample stands at one direction, so a ground point sees it hidden whole or not at all. Where a small
// bright source (a low sun: its light in a few samples) meets the edge of the sphere's shadow, that moves the
// shadow truth by whole percent. Cycles sees a pixel as a square of constant radiance (it samples the world
// within it), so the truth does too where it matters: the samples that each carry at least kSplitShare of the
// probe's light are taken as their pixels (brightest first, up to kSplitPixels pixels), and a pixel with a
// share s >= kSplitShare as n x n points, n = ceil(sqrt(s / kSplitShare)) up to kSubPixels (n^2 <= 4 s /
// kSplitShare: at most 40000 points in all). Only on split pixels does the estimate agree with Cycles'
// render where a low sun meets the shadow's edge (docs/decisions.md; tests/blender/test_estimate.py holds it
// to the render). Diffuse light is smooth in direction and keeps the samples.
constexpr double kSplitShare = 1e-4;
constexpr std::size_t kSplitPixels = std::size_t{1} << 16;
constexpr int kSubPixels = 8;

}  // namespace

Samples splitBrightest(const Probe& probe, int cell, const Samples& samples,
                       const std::vector<std::array<int, 2>>& at) {
  double total = 0;
  for (const Rgb& r : samples.radiance) total += std::abs(luminance(r));
  std::vector<std::size_t> bright;
  for (std::size_t i = 0; i < samples.radiance.size(); ++i)
    if (std::abs(luminance(samples.radiance[i])) >= kSplitShare * total && total > 0) bright.push_back(i);
  std::sort(bright.begin(), bright.end(), [&](std::size_t a, std::size_t b) {
    const double la = std::abs(luminance(samples.radiance[a])), lb = std::abs(luminance(samples.radiance[b]));
    return la != lb ? la > lb : a < b;
  });
  bright.resize(std::min(bright.size(), kSplitPixels / static_cast<std::size_t>(cell * cell)));
  if (bright.empty()) return {};
  std::vector<std::vector<PixelSums>> pixels(bright.size());
  parallelFor(static_cast<std::int64_t>(bright.size()), [&](std::int64_t i) {
    const auto [x, y] = at[bright[i]];
    const int x0 = x * cell, x1 = std::min(probe.width(), x0 + cell);
    const int y0 = y * cell, y1 = std::min(probe.height(), y0 + cell);
    pixels[i].resize(static_cast<std::size_t>((x1 - x0) * (y1 - y0)));
    for (int row = y0; row < y1; ++row)
      accumulateRows(probe, row, row + 1, x0, x1, 1,
                     std::span<PixelSums>(&pixels[i][static_cast<std::size_t>((row - y0) * (x1 - x0))],
                                          static_cast<std::size_t>(x1 - x0)),
                     false);
  });
  std::vector<char> split(samples.radiance.size(), 0);
  for (std::size_t i : bright) split[i] = 1;
  Samples out;
  for (std::size_t i = 0; i < split.size(); ++i)
    if (!split[i])
      out.directions.push_back(samples.directions[i]), out.radiance.push_back(samples.radiance[i]);
  for (std::size_t i = 0; i < bright.size(); ++i) {
    const auto [x, y] = at[bright[i]];
    const int x0 = x * cell, y0 = y * cell, w = std::min(probe.width(), x0 + cell) - x0;
    for (std::size_t p = 0; p < pixels[i].size(); ++p) {
      const int px = x0 + static_cast<int>(p) % w, py = y0 + static_cast<int>(p) / w;
      const Rgb& rgb = pixels[i][p].rgb;
      const double share = std::abs(luminance(rgb)) / total;
      const int n =
          share < kSplitShare ? 1 : std::min(kSubPixels, int(std::ceil(std::sqrt(share / kSplitShare))));
      if (n == 1) {
        out.add(probe.projection(), rgb, pixels[i][p].moment, (px + 0.5) / probe.width(),
                (py + 0.5) / probe.height());
        continue;
      }
      const std::size_t first = out.directions.size();
      for (int sy = 0; sy < n; ++sy)
        for (int sx = 0; sx < n; ++sx)
          if (auto d = probe.projection().direction((px + (sx + 0.5) / n) / probe.width(),
                                                    (py + (sy + 0.5) / n) / probe.height()))
            out.directions.push_back(*d);
      const double part = 1.0 / static_cast<double>(out.directions.size() - first);
      out.radiance.resize(out.directions.size(), Rgb{rgb[0] * part, rgb[1] * part, rgb[2] * part});
    }
  }
  return out;
}

namespace {

// The samples binned by (z, azimuth) (equal-area bins) for the truths' sums, and the bins grouped 2 x 2 level
// by level up to a top level of kTopBands x 2 kTopBands: every node keeps the cone that bounds its samples'
// directions and their per-channel moments sum(L w). A sum over the samples with a kernel that is linear in w
// on a whole node (n . w above a normal's horizon, w.z inside the sphere's cap) takes the node's moments; a
// node the kernel is zero on is skipped; a node a boundary crosses is opened, down to the leaf bins, whose
// samples are visited one by one. A boundary crosses O(sqrt(nodes)) nodes a level, so a sum costs
// ~ sqrt(samples) operations instead of the samples' count. The sums are exact up to rounding.
struct SampleTree {
  static constexpr int kTopBands = 4, kMaxLevels = 12;
  double zMin;                  // the bins cover z in [zMin, 1]; samples below are left out
  int levels, bandsZ, binsPhi;  // the leaves: bandsZ x binsPhi bins, levels - 1 groupings above them
  std::vector<int> start;       // leaf b's samples are [start[b], start[b + 1])
  std::vector<Vec3> dir;
  std::vector<Rgb> rad;
  struct Node {
    Vec3 axis, sum;              // the bounding cone's axis; the sum of the directions
    double cosR = -1, sinR = 1;  // the bounding cone's radius (cosR <= 0: too wide to bound, always opened)
    std::array<Vec3, 3> moment;  // per channel: sum of L w
    int count = 0;
  };
  std::vector<std::vector<Node>> nodes;  // nodes[l]: (kTopBands << l) x (2 kTopBands << l), z-band major

  // Leaves of perLeaf to 4 perLeaf samples on average (at least the top level).
  SampleTree(const std::vector<Vec3>& directions, const std::vector<Rgb>& radiance, double zMin_, int perLeaf)
      : zMin(zMin_), levels(1) {
    while (levels < kMaxLevels &&
           static_cast<double>(kTopBands << (levels - 1)) * (2 * kTopBands << (levels - 1)) * perLeaf * 4 <=
               static_cast<double>(directions.size()))
      ++levels;
    bandsZ = kTopBands << (levels - 1), binsPhi = 2 * bandsZ;
    start.assign(static_cast<std::size_t>(bandsZ) * binsPhi + 1, 0);
    std::vector<int> bin(directions.size(), -1);
    for (std::size_t k = 0; k < directions.size(); ++k)
      if (directions[k].z > zMin || zMin <= -1) ++start[(bin[k] = binOf(directions[k])) + 1];
    for (std::size_t b = 1; b < start.size(); ++b) start[b] += start[b - 1];
    dir.resize(start.back()), rad.resize(start.back());
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (std::size_t k = 0; k < directions.size(); ++k)
      if (bin[k] >= 0) {
        const int at = fill[bin[k]]++;
        dir[at] = directions[k], rad[at] = radiance[k];
      }
    // Sums and counts: the leaves' from their samples, each level's from the four nodes below it.
    nodes.resize(levels);
    std::vector<Node>& leaves = nodes[levels - 1];
    leaves.resize(start.size() - 1);
    parallelFor(static_cast<std::int64_t>(leaves.size()), [&](std::int64_t b) {
      Node& out = leaves[b];
      for (int k = start[b]; k < start[b + 1]; ++k) {
        out.sum += dir[k];
        for (int c = 0; c < 3; ++c) out.moment[c] += rad[k][c] * dir[k];
      }
      out.count = start[b + 1] - start[b];
    });
    for (int l = levels - 2; l >= 0; --l) {
      const int phi = 2 * kTopBands << l;
      nodes[l].resize(nodes[l + 1].size() / 4);
      for (std::size_t i = 0; i < nodes[l].size(); ++i) {
        Node& out = nodes[l][i];
        const int z = static_cast<int>(i) / phi, p = static_cast<int>(i) % phi;
        for (int c = 0; c < 4; ++c) {
          const Node& child =
              nodes[l + 1][static_cast<std::size_t>((2 * z + c / 2) * 2 * phi + 2 * p + c % 2)];
          out.sum += child.sum, out.count += child.count;
          for (int ch = 0; ch < 3; ++ch) out.moment[ch] += child.moment[ch];
        }
      }
    }
    // Every node's bounding cone: about its mean direction, out to its widest sample (those of the leaves
    // below it), a little wider so rounding never takes a crossed node whole.
    for (int l = 0; l < levels; ++l) {
      const int phi = 2 * kTopBands << l, f = 1 << (levels - 1 - l);
      parallelFor(static_cast<std::int64_t>(nodes[l].size()), [&](std::int64_t i) {
        Node& out = nodes[l][static_cast<std::size_t>(i)];
        const double len = out.sum.length();
        if (!(len > 0)) return;
        out.axis = (1 / len) * out.sum;
        const int z = static_cast<int>(i) / phi, p = static_cast<int>(i) % phi;
        double cosR = 1;
        for (int lz = z * f; lz < (z + 1) * f; ++lz)
          for (int k = start[static_cast<std::size_t>(lz) * binsPhi + p * f];
               k < start[static_cast<std::size_t>(lz) * binsPhi + (p + 1) * f]; ++k)
            cosR = std::min(cosR, dot(dir[k], out.axis));
        if (cosR > 0) out.cosR = cosR - 1e-9, out.sinR = std::min(1.0, std::sqrt(1 - cosR * cosR) + 1e-9);
      });
    }
  }
  int binOf(const Vec3& d) const {
    const int z = std::clamp(static_cast<int>((d.z - zMin) / (1 - zMin) * bandsZ), 0, bandsZ - 1);
    const double u = (std::atan2(d.y, d.x) + kPi) / (2 * kPi);
    return z * binsPhi + std::clamp(static_cast<int>(u * binsPhi), 0, binsPhi - 1);
  }
  // Visits the tree: whole(node) for a node taken whole, samples(first, last) for a leaf's crossed samples;
  // classify(node) says Whole, Skip or Open.
  enum class Take { Whole, Skip, Open };
  template <class Classify, class WholeNode, class Samples>
  void visit(Classify&& classify, WholeNode&& whole, Samples&& samples) const {
    // Depth first: the top level's nodes and at most three siblings a level wait on the stack.
    std::array<std::pair<int, int>, 2 * kTopBands * kTopBands + 3 * kMaxLevels + 4> stack;
    int top = 0;
    for (int i = static_cast<int>(nodes[0].size()) - 1; i >= 0; --i) stack[top++] = {0, i};
    while (top > 0) {
      const auto [l, i] = stack[--top];
      const Node& node = nodes[l][static_cast<std::size_t>(i)];
      if (node.count == 0) continue;
      const Take take = node.cosR > 0 ? classify(node) : Take::Open;
      if (take == Take::Whole) {
        whole(node);
      } else if (take == Take::Open) {
        if (l + 1 == levels) {
          samples(start[i], start[i + 1]);
        } else {
          const int phi = 2 * kTopBands << l, z = i / phi, p = i % phi;
          for (int c = 3; c >= 0; --c) stack[top++] = {l + 1, (2 * z + c / 2) * 2 * phi + 2 * p + c % 2};
        }
      }
    }
  }
};

}  // namespace

// A node wholly above the normal's horizon gives n . its moments, one wholly below nothing.
std::vector<Rgb> irradianceTruthAt(const std::vector<Vec3>& directions, const std::vector<Rgb>& radiance,
                                   const std::vector<Vec3>& normals) {
  const SampleTree tree(directions, radiance, -1, 32);
  std::vector<Rgb> out(normals.size());
  using Take = SampleTree::Take;
  parallelFor(static_cast<std::int64_t>(normals.size()), [&](std::int64_t i) {
    const Vec3& n = normals[i];
    Rgb e{};
    tree.visit(
        [&](const SampleTree::Node& node) {
          const double s = dot(n, node.axis);
          return s >= node.sinR ? Take::Whole : s <= -node.sinR ? Take::Skip : Take::Open;
        },
        [&](const SampleTree::Node& node) {
          for (int c = 0; c < 3; ++c) e[c] += dot(n, node.moment[c]);
        },
        [&](int first, int last) {
          for (int k = first; k < last; ++k) {
            const double w = dot(n, tree.dir[k]);
            if (w > 0)
              for (int c = 0; c < 3; ++c) e[c] += tree.rad[k][c] * w;
          }
        });
    out[i] = e;
  });
  return out;
}

// A ground point's truth is the upper hemisphere's irradiance less what the sphere hides: the samples inside
// the sphere's cap seen from the point. A node wholly inside the cap is hidden by its moments' z, one wholly
// outside skipped.
std::vector<Rgb> shadowTruthAt(const std::vector<Vec3>& directions, const std::vector<Rgb>& radiance,
                               const std::vector<Vec3>& points) {
  const SampleTree tree(directions, radiance, 0, 32);
  Rgb upper{};
  for (const SampleTree::Node& node : tree.nodes[0])
    for (int c = 0; c < 3; ++c) upper[c] += node.moment[c].z;
  std::vector<Rgb> out(points.size());
  using Take = SampleTree::Take;
  parallelFor(static_cast<std::int64_t>(points.size()), [&](std::int64_t i) {
    const Cap cap = sphereCap(points[i], {0, 0, 1}, 1.0);
    const double cosG = std::cos(cap.radius), sinG = std::sin(cap.radius);
    Rgb hidden{};
    tree.visit(
        [&](const SampleTree::Node& node) {
          const double c = dot(node.axis, cap.axis);
          if (cosG <= node.cosR && c >= cosG * node.cosR + sinG * node.sinR) return Take::Whole;
          if (c < cosG * node.cosR - sinG * node.sinR) return Take::Skip;
          return Take::Open;
        },
        [&](const SampleTree::Node& node) {
          for (int ch = 0; ch < 3; ++ch) hidden[ch] += node.moment[ch].z;
        },
        [&](int first, int last) {
          for (int k = first; k < last; ++k)
            if (dot(tree.dir[k], cap.axis) > cosG)
              for (int ch = 0; ch < 3; ++ch) hidden[ch] += tree.rad[k][ch] * tree.dir[k].z;
        });
    for (int c = 0; c < 3; ++c) out[i][c] = upper[c] - hidden[c];
  });
  return out;
}

}  // namespace probelights::truth
