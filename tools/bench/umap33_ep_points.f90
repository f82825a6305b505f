!> Two hysteresis table files evaluated at test_plastic_map's five points (turning point,
!> overlap in sigma; test/test_rough_cap_hysteresis.f90): where a gap table (main's,
!> version 4) and a u table (umap33's, version 6) of the same EP-GW psi 1 + cap scene
!> differ, relative to P(m) (doc/benchmarks.md "Stop 66: umap33"). Stop 66, umap33.
!>
!>   for w in A B; do  # A: main's egw-table, B: this branch's
!>     EGW_CACHE_DIR=off $EXE_$w --radius 810569.469138702 --effective-modulus 1 --sigma 1 \
!>       --mu 4 --psi 1 --flow-pressure 0.01 --model EP-GW --delta-min 0 --delta-max 600 \
!>       --tol 1e-3 --formats binary -q -o /tmp/umap33_ep/$w
!>   done
!>   B=$(dirname $(find build -path '*/egw_hysteresis_lengths.mod' | head -1))
!>   gfortran -O2 -fopenmp -I$B tools/bench/umap33_ep_points.f90 \
!>     $(find build -name libegw.a | head -1) -lfftw3_omp -lfftw3 -llapack -lblas \
!>     -o /tmp/umap33_ep_points && /tmp/umap33_ep_points
program umap33_ep_points
   use egw_kinds, only: dp
   use egw_status, only: egw_error
   use egw_hysteresis, only: hysteresis_table, hysteresis_eval
   use egw_hysteresis_format, only: read_hysteresis
   use egw_table, only: table_eval
   implicit none
   type(hysteresis_table) :: a, b
   type(egw_error), allocatable :: err
   real(dp), parameter :: pts(2, 5) = reshape([-3.35_dp, -3.95_dp, -2.92_dp, &
      & -3.52_dp, -4.30_dp, -4.90_dp, 37.5_dp, 0.5_dp, 250.0_dp, 125.0_dp], [2, 5])
   real(dp) :: fa, fb, k, s, fm, km
   integer :: i, st
   call read_hysteresis("/tmp/umap33_ep/A/scene_hysteresis.bin", a, err)
   if (allocated(err)) stop 1
   call read_hysteresis("/tmp/umap33_ep/B/scene_hysteresis.bin", b, err)
   if (allocated(err)) stop 2
   print '(a, 2i4, l2, 2i4, l2)', "grids", size(a%m), size(a%s), a%ratio_on_map, size(b%m), &
      & size(b%s), b%ratio_on_map
   do i = 1, 5
      call table_eval(a%loading, pts(1, i), fm, km)
      s = pts(1, i)
      call hysteresis_eval(a, pts(2, i), s, fa, k, st)
      s = pts(1, i)
      call hysteresis_eval(b, pts(2, i), s, fb, k, st)
      print '(2f8.2, 3es12.4, a, es10.2)', pts(:, i), fm, fa, fb, "  (B-A)/P(m)", (fb - fa)/fm
   end do
end program umap33_ep_points
