#pragma once
// The CPU's neighbour filter and staging (see stage_neighbours below). The filter appends to `list` the indices j in
// [first, last) of one row of cells, j != self, whose particle lies within the support of x. With AVX2 it tests 8
// candidates at a time and compacts the hits with a lookup table, so that a row costs a few instructions per candidate
// and no branch per candidate. Not used on the GPU, where a thread walks its rows.
//
// Contract: `list` has room for n + (last - first) + 8 entries (the vector path stores 8 at a
// time), and `pos` may be read up to 7 records past `last` (the CPU backend pads its arrays).
#include <cstdint>

#include "core/vec.hpp"

#if defined(__AVX2__)
#include <immintrin.h>
#endif

namespace terracal {

template <typename T>
inline int filter_row_scalar(const Vec4<T>* pos, int first, int last, long self, const Vec3<T>& x, T support2,
                             int* list, int n) {
  for (int j = first; j < last; ++j) {
    const Vec3<T> r = x - pos[j].xyz();
    list[n] = j;
    n += int(dot(r, r) < support2) & int(j != self);
  }
  return n;
}

#if defined(__AVX2__)
namespace detail {
// For each 8-bit mask, the positions of its set bits packed into bytes (lowest first).
struct CompactTable {
  std::uint64_t entry[256];
  constexpr CompactTable() : entry() {
    for (int m = 0; m < 256; ++m) {
      std::uint64_t e = 0;
      int k = 0;
      for (int b = 0; b < 8; ++b)
        if (m & (1 << b)) e |= std::uint64_t(b) << (8 * k++);
      entry[m] = e;
    }
  }
};
inline constexpr CompactTable kCompactTable{};
}  // namespace detail

inline int filter_row(const Vec4<float>* pos, int first, int last, long self, const Vec3<float>& x, float support2,
                      int* list, int n) {
  const __m256 cx = _mm256_set1_ps(x.x), cy = _mm256_set1_ps(x.y), cz = _mm256_set1_ps(x.z);
  const __m256 s2 = _mm256_set1_ps(support2);
  // The 4x4 transposes below leave the 8 candidates in lane order 0, 2, 4, 6, 1, 3, 5, 7.
  const __m256i lane = _mm256_setr_epi32(0, 2, 4, 6, 1, 3, 5, 7);
  const __m256i vlast = _mm256_set1_epi32(last), vself = _mm256_set1_epi32(int(self));
  for (int j = first; j < last; j += 8) {
    const float* p = reinterpret_cast<const float*>(pos + j);
    const __m256 a0 = _mm256_loadu_ps(p), a1 = _mm256_loadu_ps(p + 8), a2 = _mm256_loadu_ps(p + 16),
                 a3 = _mm256_loadu_ps(p + 24);
    const __m256 t0 = _mm256_unpacklo_ps(a0, a1), t1 = _mm256_unpackhi_ps(a0, a1);
    const __m256 t2 = _mm256_unpacklo_ps(a2, a3), t3 = _mm256_unpackhi_ps(a2, a3);
    const __m256 dx = _mm256_sub_ps(cx, _mm256_shuffle_ps(t0, t2, 0x44));
    const __m256 dy = _mm256_sub_ps(cy, _mm256_shuffle_ps(t0, t2, 0xEE));
    const __m256 dz = _mm256_sub_ps(cz, _mm256_shuffle_ps(t1, t3, 0x44));
    const __m256 r2 = _mm256_fmadd_ps(dz, dz, _mm256_fmadd_ps(dy, dy, _mm256_mul_ps(dx, dx)));
    const __m256i idx = _mm256_add_epi32(_mm256_set1_epi32(j), lane);
    const __m256i valid = _mm256_andnot_si256(_mm256_cmpeq_epi32(idx, vself), _mm256_cmpgt_epi32(vlast, idx));
    const __m256 hit = _mm256_and_ps(_mm256_cmp_ps(r2, s2, _CMP_LT_OQ), _mm256_castsi256_ps(valid));
    const int mask = _mm256_movemask_ps(hit);
    const __m256i perm =
        _mm256_cvtepu8_epi32(_mm_cvtsi64_si128(static_cast<long long>(detail::kCompactTable.entry[mask])));
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(list + n), _mm256_permutevar8x32_epi32(idx, perm));
    n += __builtin_popcount(unsigned(mask));
  }
  return n;
}
#endif

// Copies the records pos/vel/s0/s1[list[q]], q < n, into structure-of-arrays form for the SIMD
// neighbour sum: out[f][q] is field f (x, y, z, rho, vx, vy, vz, sxx, syy, szz, sxy, sxz, syz).
// With AVX2, 8 records of each array are loaded and transposed at a time, in list order (so that
// the first n staged entries are exactly the listed neighbours). `list` must have room for n + 8
// entries; each out[f] for n + 8 values.
constexpr int kStagedFields = 13;
template <typename T>
inline void stage_neighbours_scalar(const Vec4<T>* pos, const Vec4<T>* vel, const Vec4<T>* s0, const Vec4<T>* s1,
                                    const int* list, int n, T* const* out) {
  for (int q = 0; q < n; ++q) {
    const int j = list[q];
    const Vec4<T> p = pos[j], v = vel[j], a = s0[j], b = s1[j];
    const T f[kStagedFields] = {p.x, p.y, p.z, p.w, v.x, v.y, v.z, a.x, a.y, a.z, a.w, b.x, b.y};
    for (int c = 0; c < kStagedFields; ++c) out[c][q] = f[c];
  }
}

#if defined(__AVX2__)
namespace detail {
// Transposes the records src[idx[0..7]] into four vectors of x, y, z and w, in the order of idx
// (records k and k + 4 share a load, which puts them in lanes k and k + 4 after the shuffles).
inline void transpose8(const Vec4<float>* src, const int* idx, __m256& x, __m256& y, __m256& z, __m256& w) {
  auto rec = [&](int k) { return _mm_load_ps(&src[idx[k]].x); };
  const __m256 a0 = _mm256_set_m128(rec(4), rec(0)), a1 = _mm256_set_m128(rec(5), rec(1));
  const __m256 a2 = _mm256_set_m128(rec(6), rec(2)), a3 = _mm256_set_m128(rec(7), rec(3));
  const __m256 t0 = _mm256_unpacklo_ps(a0, a1), t1 = _mm256_unpackhi_ps(a0, a1);
  const __m256 t2 = _mm256_unpacklo_ps(a2, a3), t3 = _mm256_unpackhi_ps(a2, a3);
  x = _mm256_shuffle_ps(t0, t2, 0x44);
  y = _mm256_shuffle_ps(t0, t2, 0xEE);
  z = _mm256_shuffle_ps(t1, t3, 0x44);
  w = _mm256_shuffle_ps(t1, t3, 0xEE);
}
}  // namespace detail

inline void stage_neighbours(const Vec4<float>* pos, const Vec4<float>* vel, const Vec4<float>* s0,
                             const Vec4<float>* s1, int* list, int n, float* const* out) {
  if (n <= 0) return;
  for (int q = n; q < n + 8; ++q) list[q] = list[0];  // pad the last group with a valid record
  for (int q = 0; q < n; q += 8) {
    __m256 x, y, z, w;
    detail::transpose8(pos, list + q, x, y, z, w);
    _mm256_storeu_ps(out[0] + q, x);
    _mm256_storeu_ps(out[1] + q, y);
    _mm256_storeu_ps(out[2] + q, z);
    _mm256_storeu_ps(out[3] + q, w);
    detail::transpose8(vel, list + q, x, y, z, w);
    _mm256_storeu_ps(out[4] + q, x);
    _mm256_storeu_ps(out[5] + q, y);
    _mm256_storeu_ps(out[6] + q, z);
    detail::transpose8(s0, list + q, x, y, z, w);
    _mm256_storeu_ps(out[7] + q, x);
    _mm256_storeu_ps(out[8] + q, y);
    _mm256_storeu_ps(out[9] + q, z);
    _mm256_storeu_ps(out[10] + q, w);
    detail::transpose8(s1, list + q, x, y, z, w);
    _mm256_storeu_ps(out[11] + q, x);
    _mm256_storeu_ps(out[12] + q, y);
  }
}
#endif

template <typename T>
inline void stage_neighbours(const Vec4<T>* pos, const Vec4<T>* vel, const Vec4<T>* s0, const Vec4<T>* s1, int* list,
                             int n, T* const* out) {
  stage_neighbours_scalar(pos, vel, s0, s1, list, n, out);
}

template <typename T>
inline int filter_row(const Vec4<T>* pos, int first, int last, long self, const Vec3<T>& x, T support2, int* list,
                      int n) {
  return filter_row_scalar(pos, first, last, self, x, support2, list, n);
}

}  // namespace terracal
