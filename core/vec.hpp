#pragma once
// Small fixed-size vector and tensor types usable in host and device code (C++17: nvcc compiles
// the CUDA sources at that standard). Vec4 is 16-byte aligned for float so that a particle field
// is fetched by one 128-bit load on the GPU.
#include <cmath>

#include "core/host_device.hpp"

namespace terracal {

template <typename T>
struct Vec3 {
  T x{}, y{}, z{};
  TERRACAL_HD T& operator[](int k) { return k == 0 ? x : (k == 1 ? y : z); }
  TERRACAL_HD T operator[](int k) const { return k == 0 ? x : (k == 1 ? y : z); }
  template <typename U>
  TERRACAL_HD explicit operator Vec3<U>() const {
    return {U(x), U(y), U(z)};
  }
};

template <typename T>
TERRACAL_HD inline Vec3<T> operator+(Vec3<T> a, Vec3<T> b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
template <typename T>
TERRACAL_HD inline Vec3<T> operator-(Vec3<T> a, Vec3<T> b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
template <typename T>
TERRACAL_HD inline Vec3<T> operator-(Vec3<T> a) {
  return {-a.x, -a.y, -a.z};
}
template <typename T>
TERRACAL_HD inline Vec3<T> operator*(T s, Vec3<T> a) {
  return {s * a.x, s * a.y, s * a.z};
}
template <typename T>
TERRACAL_HD inline Vec3<T> operator*(Vec3<T> a, T s) {
  return {s * a.x, s * a.y, s * a.z};
}
template <typename T>
TERRACAL_HD inline Vec3<T>& operator+=(Vec3<T>& a, Vec3<T> b) {
  a.x += b.x;
  a.y += b.y;
  a.z += b.z;
  return a;
}
template <typename T>
TERRACAL_HD inline Vec3<T>& operator-=(Vec3<T>& a, Vec3<T> b) {
  a.x -= b.x;
  a.y -= b.y;
  a.z -= b.z;
  return a;
}
template <typename T>
TERRACAL_HD inline T dot(Vec3<T> a, Vec3<T> b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <typename T>
TERRACAL_HD inline Vec3<T> cross(Vec3<T> a, Vec3<T> b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <typename T>
TERRACAL_HD inline T norm(Vec3<T> a) {
  return std::sqrt(dot(a, a));
}

template <typename T>
struct alignas(4 * sizeof(T)) Vec4 {
  T x{}, y{}, z{}, w{};
  TERRACAL_HD Vec3<T> xyz() const { return {x, y, z}; }
};
template <typename T>
TERRACAL_HD inline Vec4<T> make_vec4(Vec3<T> v, T w) {
  return {v.x, v.y, v.z, w};
}

// Symmetric 3x3 tensor (stress, strain rate): xx, yy, zz, xy, xz, yz.
template <typename T>
struct Sym3 {
  T xx{}, yy{}, zz{}, xy{}, xz{}, yz{};
  TERRACAL_HD T trace() const { return xx + yy + zz; }
  TERRACAL_HD Vec3<T> operator*(Vec3<T> v) const {
    return {xx * v.x + xy * v.y + xz * v.z, xy * v.x + yy * v.y + yz * v.z, xz * v.x + yz * v.y + zz * v.z};
  }
};
template <typename T>
TERRACAL_HD inline Sym3<T> operator+(Sym3<T> a, Sym3<T> b) {
  return {a.xx + b.xx, a.yy + b.yy, a.zz + b.zz, a.xy + b.xy, a.xz + b.xz, a.yz + b.yz};
}
template <typename T>
TERRACAL_HD inline Sym3<T> operator*(T s, Sym3<T> a) {
  return {s * a.xx, s * a.yy, s * a.zz, s * a.xy, s * a.xz, s * a.yz};
}
// s:s for a symmetric tensor.
template <typename T>
TERRACAL_HD inline T double_dot(Sym3<T> a) {
  return a.xx * a.xx + a.yy * a.yy + a.zz * a.zz + T(2) * (a.xy * a.xy + a.xz * a.xz + a.yz * a.yz);
}

// General 3x3 matrix, row-major: m[r][c]. Used for the velocity gradient L = grad v.
template <typename T>
struct Mat3 {
  T m[3][3]{};
};
// m v
template <typename T>
TERRACAL_HD inline Vec3<T> operator*(const Mat3<T>& a, Vec3<T> v) {
  return {a.m[0][0] * v.x + a.m[0][1] * v.y + a.m[0][2] * v.z, a.m[1][0] * v.x + a.m[1][1] * v.y + a.m[1][2] * v.z,
          a.m[2][0] * v.x + a.m[2][1] * v.y + a.m[2][2] * v.z};
}
// a (outer) b
template <typename T>
TERRACAL_HD inline Mat3<T> outer(Vec3<T> a, Vec3<T> b) {
  return {{{a.x * b.x, a.x * b.y, a.x * b.z}, {a.y * b.x, a.y * b.y, a.y * b.z}, {a.z * b.x, a.z * b.y, a.z * b.z}}};
}
// m += a (outer) b
template <typename T>
TERRACAL_HD inline void add_outer(Mat3<T>& m, Vec3<T> a, Vec3<T> b) {
  m.m[0][0] += a.x * b.x;
  m.m[0][1] += a.x * b.y;
  m.m[0][2] += a.x * b.z;
  m.m[1][0] += a.y * b.x;
  m.m[1][1] += a.y * b.y;
  m.m[1][2] += a.y * b.z;
  m.m[2][0] += a.z * b.x;
  m.m[2][1] += a.z * b.y;
  m.m[2][2] += a.z * b.z;
}

}  // namespace terracal
