! asm21 (stop 55): influence_row's near and far elements timed apart on one graded mesh (the
! focus, layer width, outer radius and step of a first unloading level of README's E-GW + cap
! build: 22 elements, 45 nodes, 254 of the 990 (node, element) pairs near).
! Build against a release build's modules and library, e.g.
!   B=build/gfortran_<hash>; gfortran -O3 -fopenmp -I$B tools/bench/influence_row_microbench.f90 \
!     build/gfortran_<hash>/egw/libegw.a -llapack -lfftw3_omp -lfftw3 -lmvec -lm -o irm
!   ./irm 2000            (CPU seconds), or valgrind --tool=cachegrind --cache-sim=no ./irm 100
! "all": every row of the mesh nrep times; "near only": the same rows with their far elements
! marked known (skipped), so that near = near only, far = all - near only.
program influence_row_microbench
   use egw_kinds, only: dp
   use egw_halfspace, only: radial_mesh, build_mesh, graded_edges, influence_row
   implicit none
   type(radial_mesh) :: mesh
   real(dp), allocatable :: row(:)
   logical, allocatable :: far(:)
   character(len=32) :: arg
   integer :: i, e, rep, nrep, n_near
   real(dp) :: t0, t1, t2, r, dist, check
   nrep = 2000
   if (command_argument_count() >= 1) then
      call get_command_argument(1, arg)
      read (arg, *) nrep
   end if
   call build_mesh(graded_edges(6.5_dp, 0.3_dp, 12.0_dp, 0.35_dp), 2, 6, mesh)
   allocate (row(mesh%n_elem*mesh%n_gauss), far(mesh%n_elem))
   check = 0.0_dp
   call cpu_time(t0)
   do rep = 1, nrep
      do i = 1, size(mesh%node)
         call influence_row(mesh, mesh%node(i), row)
         check = check + sum(row)
      end do
   end do
   call cpu_time(t1)
   n_near = 0
   do rep = 1, nrep
      do i = 1, size(mesh%node)
         r = mesh%node(i)
         do e = 1, mesh%n_elem
            dist = max(0.0_dp, mesh%edge(e - 1) - r, r - mesh%edge(e))
            far(e) = r <= 0.0_dp .or. dist >= 2.0_dp*(mesh%edge(e) - mesh%edge(e - 1))
         end do
         if (rep == 1) n_near = n_near + count(.not. far)
         call influence_row(mesh, r, row, far)
      end do
   end do
   call cpu_time(t2)
   print '(a,i0,a,i0,a,i0,a,i0)', 'elements ', mesh%n_elem, ', nodes ', size(mesh%node), &
      & ', near pairs ', n_near, ' of ', size(mesh%node)*mesh%n_elem
   print '(a,f8.4,a,f8.4,a)', 'all ', t1 - t0, ' s, near only ', t2 - t1, ' s'
   print '(a,es24.16)', 'sum of the rows (the same on both paths to rounding) ', check/nrep
end program influence_row_microbench
