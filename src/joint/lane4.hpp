// Four doubles side by side, one per joint of a batch (joint_forces.cpp's lean batch): the
// same IEEE operations as the scalar code, lane by lane, so every lane's result is the scalar
// result to the bit. There is no fused multiply-add here on purpose (it rounds once where the
// scalar code rounds twice). One AVX register where the translation unit is compiled for AVX,
// two SSE2 registers otherwise (the x86-64 baseline).
#pragma once
#include <immintrin.h>

#include <cstddef>

namespace dspdem::joint::lane {

#ifdef __AVX__
struct V4 {
  __m256d v;
  static V4 load(const double* p) { return {_mm256_loadu_pd(p)}; }
  static V4 set1(double a) { return {_mm256_set1_pd(a)}; }
  void store(double* p) const { _mm256_storeu_pd(p, v); }
  /// Lane i from p[i]: loaded straight into the register (lanes written to memory one by one
  /// and read back as a vector would stall on store forwarding).
  static V4 gather(const double* p0, const double* p1, const double* p2, const double* p3) {
    const __m128d lo = _mm_loadh_pd(_mm_load_sd(p0), p1), hi = _mm_loadh_pd(_mm_load_sd(p2), p3);
    return {_mm256_insertf128_pd(_mm256_castpd128_pd256(lo), hi, 1)};
  }
  /// Lane i to p[i s].
  void scatter(double* p, std::size_t s) const {
    const __m128d lo = _mm256_castpd256_pd128(v), hi = _mm256_extractf128_pd(v, 1);
    _mm_storel_pd(p, lo), _mm_storeh_pd(p + s, lo), _mm_storel_pd(p + 2 * s, hi), _mm_storeh_pd(p + 3 * s, hi);
  }
};
inline V4 operator+(V4 a, V4 b) { return {_mm256_add_pd(a.v, b.v)}; }
inline V4 operator-(V4 a, V4 b) { return {_mm256_sub_pd(a.v, b.v)}; }
inline V4 operator*(V4 a, V4 b) { return {_mm256_mul_pd(a.v, b.v)}; }
inline V4 operator/(V4 a, V4 b) { return {_mm256_div_pd(a.v, b.v)}; }
inline V4 sqrt(V4 a) { return {_mm256_sqrt_pd(a.v)}; }
/// -a, as the scalar unary minus: the sign bit flipped (also of 0 and NaN).
inline V4 neg(V4 a) { return {_mm256_xor_pd(a.v, _mm256_set1_pd(-0.0))}; }
inline V4 lt(V4 a, V4 b) { return {_mm256_cmp_pd(a.v, b.v, _CMP_LT_OQ)}; }
inline V4 gt(V4 a, V4 b) { return {_mm256_cmp_pd(a.v, b.v, _CMP_GT_OQ)}; }
/// Lanes where mask is set take a, the others b.
inline V4 select(V4 mask, V4 a, V4 b) { return {_mm256_blendv_pd(b.v, a.v, mask.v)}; }
inline V4 operator&(V4 a, V4 b) { return {_mm256_and_pd(a.v, b.v)}; }
inline V4 operator|(V4 a, V4 b) { return {_mm256_or_pd(a.v, b.v)}; }
/// True if every lane of the mask is set.
inline bool all(V4 mask) { return _mm256_movemask_pd(mask.v) == 0xF; }
#else
struct V4 {
  __m128d lo, hi;
  static V4 load(const double* p) { return {_mm_loadu_pd(p), _mm_loadu_pd(p + 2)}; }
  static V4 set1(double a) { return {_mm_set1_pd(a), _mm_set1_pd(a)}; }
  void store(double* p) const { _mm_storeu_pd(p, lo), _mm_storeu_pd(p + 2, hi); }
  /// Lane i from p[i]: loaded straight into the register (lanes written to memory one by one
  /// and read back as a vector would stall on store forwarding).
  static V4 gather(const double* p0, const double* p1, const double* p2, const double* p3) {
    return {_mm_loadh_pd(_mm_load_sd(p0), p1), _mm_loadh_pd(_mm_load_sd(p2), p3)};
  }
  /// Lane i to p[i s].
  void scatter(double* p, std::size_t s) const {
    _mm_storel_pd(p, lo), _mm_storeh_pd(p + s, lo), _mm_storel_pd(p + 2 * s, hi), _mm_storeh_pd(p + 3 * s, hi);
  }
};
inline V4 operator+(V4 a, V4 b) { return {_mm_add_pd(a.lo, b.lo), _mm_add_pd(a.hi, b.hi)}; }
inline V4 operator-(V4 a, V4 b) { return {_mm_sub_pd(a.lo, b.lo), _mm_sub_pd(a.hi, b.hi)}; }
inline V4 operator*(V4 a, V4 b) { return {_mm_mul_pd(a.lo, b.lo), _mm_mul_pd(a.hi, b.hi)}; }
inline V4 operator/(V4 a, V4 b) { return {_mm_div_pd(a.lo, b.lo), _mm_div_pd(a.hi, b.hi)}; }
inline V4 sqrt(V4 a) { return {_mm_sqrt_pd(a.lo), _mm_sqrt_pd(a.hi)}; }
inline V4 neg(V4 a) {
  const __m128d s = _mm_set1_pd(-0.0);
  return {_mm_xor_pd(a.lo, s), _mm_xor_pd(a.hi, s)};
}
inline V4 lt(V4 a, V4 b) { return {_mm_cmplt_pd(a.lo, b.lo), _mm_cmplt_pd(a.hi, b.hi)}; }
inline V4 gt(V4 a, V4 b) { return {_mm_cmpgt_pd(a.lo, b.lo), _mm_cmpgt_pd(a.hi, b.hi)}; }
inline V4 operator&(V4 a, V4 b) { return {_mm_and_pd(a.lo, b.lo), _mm_and_pd(a.hi, b.hi)}; }
inline V4 operator|(V4 a, V4 b) { return {_mm_or_pd(a.lo, b.lo), _mm_or_pd(a.hi, b.hi)}; }
inline V4 select(V4 mask, V4 a, V4 b) {
  return {_mm_or_pd(_mm_and_pd(mask.lo, a.lo), _mm_andnot_pd(mask.lo, b.lo)),
          _mm_or_pd(_mm_and_pd(mask.hi, a.hi), _mm_andnot_pd(mask.hi, b.hi))};
}
inline bool all(V4 mask) { return (_mm_movemask_pd(mask.lo) & _mm_movemask_pd(mask.hi)) == 0x3; }
#endif

/// std::max(a, b) lane by lane: (a < b) ? b : a, which keeps a when they compare equal
/// (+0 and -0) and is what max_pd(b, a) computes.
inline V4 max(V4 a, V4 b) { return select(lt(a, b), b, a); }
/// std::min(a, b): (b < a) ? b : a.
inline V4 min(V4 a, V4 b) { return select(lt(b, a), b, a); }

}  // namespace dspdem::joint::lane
