!> The SIMD path in use (simd_path.c; issue 32): 1 where the CPU has AVX2 and FMA, the
!> path of the 4-lane C kernels of solver/ (egw_simd) and kernels/ (egw_unloading), 0 the
!> baseline x86-64 code. Decided once when the library loads; EGW_SIMD=sse2 in the
!> environment keeps the baseline. One switch for every layer, so that a table's bits
!> depend on one path (egw_cache keys on it).
module egw_simd_path
   use, intrinsic :: iso_c_binding, only: c_int
   implicit none
   private

   public :: simd_level, simd_set

   interface
      !> The path in use: 1 AVX2 + FMA, 0 the baseline (set once when the library loads).
      pure integer(c_int) function simd_level() bind(C, name="egw_simd_level")
         import :: c_int
      end function simd_level
      !> Ask for a path (1 AVX2 + FMA, only where the CPU has it; 0 the baseline); returns
      !> the path now in use. Tests and benchmarks only, never while threads solve.
      integer(c_int) function simd_set(level) bind(C, name="egw_simd_set")
         import :: c_int
         integer(c_int), value :: level
      end function simd_set
   end interface
end module egw_simd_path
