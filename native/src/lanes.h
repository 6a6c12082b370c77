// Four doubles at a time for the per-pixel loops (pixel_sums.cpp, moment_rows.cpp): one vector of four
// doubles in an AVX2 clone of a loop, two SSE2 pairs in its portable build (GCC splits a four-double vector
// without AVX through the stack: the CLI's 8K grid took 2.4x as long as with two pairs). A loop is written
// once as a template on the lane type V (D4 or Pairs) with the operators and Lanes<V> below; the same
// operations lane by lane and no FMA (no contraction), so both builds give the same bits. Vectors go in and
// out of functions by reference: by value a four-double vector would change the ABI between the two builds.
#pragma once

#if defined(__x86_64__)
#include <cpuid.h>
#endif

namespace probelights::lanes {

using D2 = double __attribute__((vector_size(16)));
using I2 = long long __attribute__((vector_size(16)));
using D4 = double __attribute__((vector_size(32)));
using I4 = long long __attribute__((vector_size(32)));
using F4 = float __attribute__((vector_size(16)));
constexpr double kMax = 3.4028234663852886e38;  // FLT_MAX: Probe::finite's bounds

// Four lanes as two pairs, with the operations the loops use.
struct Pairs {
  D2 lo, hi;
};
struct PairMasks {
  I2 lo, hi;
};
#define PROBELIGHTS_LANEWISE(R, op, A, B) \
  [[gnu::always_inline]] inline R operator op(const A& a, const B& b) { return {a.lo op b.lo, a.hi op b.hi}; }
PROBELIGHTS_LANEWISE(Pairs, +, Pairs, Pairs)
PROBELIGHTS_LANEWISE(Pairs, *, Pairs, Pairs)
PROBELIGHTS_LANEWISE(PairMasks, >, Pairs, Pairs)
PROBELIGHTS_LANEWISE(PairMasks, >=, Pairs, Pairs)
PROBELIGHTS_LANEWISE(PairMasks, <=, Pairs, Pairs)
PROBELIGHTS_LANEWISE(PairMasks, &, PairMasks, PairMasks)
PROBELIGHTS_LANEWISE(PairMasks, |, PairMasks, PairMasks)
PROBELIGHTS_LANEWISE(PairMasks, -, PairMasks, PairMasks)
#undef PROBELIGHTS_LANEWISE
[[gnu::always_inline]] inline PairMasks operator~(const PairMasks& m) { return {~m.lo, ~m.hi}; }
[[gnu::always_inline]] inline Pairs operator*(const Pairs& a, double s) { return {a.lo * s, a.hi * s}; }

// What the loops need of a lane type beyond its operators: V is D4 (AVX2) or Pairs (portable).
template <class V>
struct Lanes;
template <>
struct Lanes<D4> {  // values out by reference: by value a four-double vector changes the ABI without AVX
  using Mask = I4;
  static void splat(double x, D4& out) { out = D4{x, x, x, x}; }
  static void load(float a, float b, float c, float d, D4& out) {
    out = __builtin_convertvector((F4{a, b, c, d}), D4);
  }
  static void keep(const D4& v, const I4& m, D4& out) {
    out = reinterpret_cast<D4>(reinterpret_cast<I4>(v) & m);
  }
  static double get(const D4& v, int k) { return v[k]; }
  static void set(D4& v, int k, double x) { v[k] = x; }
  static long long get(const I4& m, int k) { return m[k]; }
  static void make(double a, double b, double c, double d, D4& out) { out = D4{a, b, c, d}; }
  static void loadu(const double* p, D4& out) { __builtin_memcpy(&out, p, sizeof out); }
  static void storeu(double* p, const D4& v) { __builtin_memcpy(p, &v, sizeof v); }
  // Rows a, b, c, d of a 4 x 4 matrix in, its columns out in place.
  static void transpose(D4& a, D4& b, D4& c, D4& d) {
    const D4 t0 = __builtin_shufflevector(a, b, 0, 4, 2, 6), t1 = __builtin_shufflevector(a, b, 1, 5, 3, 7);
    const D4 t2 = __builtin_shufflevector(c, d, 0, 4, 2, 6), t3 = __builtin_shufflevector(c, d, 1, 5, 3, 7);
    a = __builtin_shufflevector(t0, t2, 0, 1, 4, 5), b = __builtin_shufflevector(t1, t3, 0, 1, 4, 5);
    c = __builtin_shufflevector(t0, t2, 2, 3, 6, 7), d = __builtin_shufflevector(t1, t3, 2, 3, 6, 7);
  }
};
template <>
struct Lanes<Pairs> {
  using Mask = PairMasks;
  static void splat(double x, Pairs& out) { out = {D2{x, x}, D2{x, x}}; }
  static void load(float a, float b, float c, float d, Pairs& out) { out = {D2{a, b}, D2{c, d}}; }
  static void keep(const Pairs& v, const PairMasks& m, Pairs& out) {
    out = {reinterpret_cast<D2>(reinterpret_cast<I2>(v.lo) & m.lo),
           reinterpret_cast<D2>(reinterpret_cast<I2>(v.hi) & m.hi)};
  }
  static double get(const Pairs& v, int k) { return k < 2 ? v.lo[k] : v.hi[k - 2]; }
  static void set(Pairs& v, int k, double x) {  // clang: a vector element is no lvalue through ?:
    if (k < 2)
      v.lo[k] = x;
    else
      v.hi[k - 2] = x;
  }
  static long long get(const PairMasks& m, int k) { return k < 2 ? m.lo[k] : m.hi[k - 2]; }
  static void make(double a, double b, double c, double d, Pairs& out) { out = {D2{a, b}, D2{c, d}}; }
  static void loadu(const double* p, Pairs& out) {
    __builtin_memcpy(&out.lo, p, sizeof out.lo), __builtin_memcpy(&out.hi, p + 2, sizeof out.hi);
  }
  static void storeu(double* p, const Pairs& v) {
    __builtin_memcpy(p, &v.lo, sizeof v.lo), __builtin_memcpy(p + 2, &v.hi, sizeof v.hi);
  }
  static void transpose(Pairs& a, Pairs& b, Pairs& c, Pairs& d) {
    const Pairs a0 = a, b0 = b, c0 = c, d0 = d;
    a = {__builtin_shufflevector(a0.lo, b0.lo, 0, 2), __builtin_shufflevector(c0.lo, d0.lo, 0, 2)};
    b = {__builtin_shufflevector(a0.lo, b0.lo, 1, 3), __builtin_shufflevector(c0.lo, d0.lo, 1, 3)};
    c = {__builtin_shufflevector(a0.hi, b0.hi, 0, 2), __builtin_shufflevector(c0.hi, d0.hi, 0, 2)};
    d = {__builtin_shufflevector(a0.hi, b0.hi, 1, 3), __builtin_shufflevector(c0.hi, d0.hi, 1, 3)};
  }
};

// The lanes added as ((l0 + l1) + (l2 + l3)).
template <class V>
[[gnu::always_inline]] inline double hsum(const V& v) {
  using L = Lanes<V>;
  return (L::get(v, 0) + L::get(v, 1)) + (L::get(v, 2) + L::get(v, 3));
}

// Set by tests to run the portable builds on a processor that has AVX2 (both must give the same bits).
inline bool& portableOnly() {
  static bool portable = false;
  return portable;
}

// Whether the AVX2 clones run: the processor has AVX2 and the system saves its registers (checked
// once), and the tests have not said otherwise. Asked of CPUID and XGETBV directly, as libgcc's
// __builtin_cpu_supports("avx2") does, because the zig/clang runtime of the Windows and macOS builds has
// no __cpu_model: leaf 1 ECX bits 27 (OSXSAVE) and 28 (AVX), XCR0 bits 1 and 2 (the system saves XMM and
// YMM state), leaf 7 EBX bit 5 (AVX2).
inline bool hasAvx2() {
#if defined(__x86_64__)
  static const bool avx2 = [] {
    unsigned a = 0, b = 0, c = 0, d = 0;
    if (!__get_cpuid(1, &a, &b, &c, &d) || !(c & bit_OSXSAVE) || !(c & bit_AVX)) return false;
    unsigned low = 0, high = 0;
    __asm__("xgetbv" : "=a"(low), "=d"(high) : "c"(0));
    if ((low & 6u) != 6u) return false;
    return __get_cpuid_count(7, 0, &a, &b, &c, &d) && (b & bit_AVX2);
  }();
  return avx2 && !portableOnly();
#else
  return false;  // arm64: the portable build's pairs are NEON vectors
#endif
}

}  // namespace probelights::lanes
