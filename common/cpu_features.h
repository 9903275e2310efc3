#pragma once
// What this CPU's vector units can do, asked once per process: the kernels that have AVX2 or
// AVX-512 versions (compiled with target attributes, the rest of the program for the baseline)
// pick them at run time from these. False on other architectures and compilers.
namespace allanlab {

#if defined(__x86_64__) && defined(__GNUC__)
// __builtin_cpu_supports needs a string literal, hence one function per feature; each runs
// __builtin_cpu_init first, which may be called any number of times.
inline bool CpuHasAvx2() {
  static const bool has = (__builtin_cpu_init(), __builtin_cpu_supports("avx2") != 0);
  return has;
}
inline bool CpuHasFma() {
  static const bool has = (__builtin_cpu_init(), __builtin_cpu_supports("fma") != 0);
  return has;
}
inline bool CpuHasAvx512f() {
  static const bool has = (__builtin_cpu_init(), __builtin_cpu_supports("avx512f") != 0);
  return has;
}
#else
inline bool CpuHasAvx2() { return false; }
inline bool CpuHasFma() { return false; }
inline bool CpuHasAvx512f() { return false; }
#endif

}  // namespace allanlab
