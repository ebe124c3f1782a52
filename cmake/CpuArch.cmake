# SIMD for the CPU solvers. The CRM CPU backend sums neighbours with `omp simd`; AVX2 and FMA
# make that loop 8 floats wide. They are enabled only when the compiler accepts
# -march=x86-64-v3 and the machine that builds also runs them (CI builds where it tests), so a
# build never emits instructions its own CPU lacks. TERRACAL_CPU_ARCH=OFF turns it off, e.g. to
# build binaries for an older CPU.
option(TERRACAL_CPU_ARCH "Build the CPU solvers for x86-64-v3 (AVX2, FMA) when this CPU has it" ON)
set(TERRACAL_CPU_SIMD_FLAGS -fno-math-errno -fno-trapping-math)
if(TERRACAL_CPU_ARCH AND CMAKE_SYSTEM_PROCESSOR MATCHES "x86_64|AMD64")
  include(CheckCXXSourceRuns)
  set(CMAKE_REQUIRED_FLAGS "-march=x86-64-v3")
  check_cxx_source_runs("
    int main() {
      __builtin_cpu_init();
      return (__builtin_cpu_supports(\"avx2\") && __builtin_cpu_supports(\"fma\")) ? 0 : 1;
    }" TERRACAL_HOST_HAS_X86_64_V3)
  unset(CMAKE_REQUIRED_FLAGS)
  if(TERRACAL_HOST_HAS_X86_64_V3)
    list(APPEND TERRACAL_CPU_SIMD_FLAGS -march=x86-64-v3)
  endif()
endif()
message(STATUS "terracal: CPU solver flags ${TERRACAL_CPU_SIMD_FLAGS}")
