#pragma once
// Small vector helpers for the kernels, written over the number type T.
#include "shadetlm/numeric/ops.hpp"

namespace shadetlm::modules {

template <class T>
T dot3(const T a[3], const T b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

// Exact normalization: v · 1/sqrt(v·v).
template <class T>
void normalize3(T v[3]) {
  const T s = T(1.0f) / sqrt_op(dot3(v, v));
  v[0] = v[0] * s;
  v[1] = v[1] * s;
  v[2] = v[2] * s;
}
constexpr Ops kOpsNormalize3{/*add*/ 2, /*mul*/ 6, /*div*/ 1, /*sqrt*/ 1};

}  // namespace shadetlm::modules
