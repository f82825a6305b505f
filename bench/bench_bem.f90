!> egw-bench --bem: the periodic BEM flat law (bem_flat_curve) on the benchmark's maps,
!> timed (issue 31: the whole law on 512^2 against ContactMechanics' ten loads, and a 576^2
!> law within 30 s on 2 threads). The maps come from tools/bench/bem_contactmechanics_time.py
!> (out/bench/bem_map_<n>.txt: "nx ny pixel", then one line of heights per x index),
!> which also times ContactMechanics and takes the ratio in the same run.
module bench_bem
   use, intrinsic :: iso_fortran_env, only: output_unit
   !$ use omp_lib, only: omp_get_max_threads
   use egw_all, only: dp, egw_error, bem_options, bem_flat_curve
   use bench_common, only: wall
   implicit none
   private
   public :: run_bem

contains

   !> Time bem_flat_curve (p/E* 1e-6 ... 1e-2, 5 loads a decade, E* = 1) on each map found.
   subroutine run_bem()
      integer, parameter :: sizes(2) = [512, 576]
      real(dp), allocatable :: h(:, :), u(:), p(:), area(:), k(:)
      real(dp) :: pixel, t0, seconds
      type(bem_options) :: opt
      type(egw_error), allocatable :: err
      integer :: s, i, threads
      character(len=64) :: path
      logical :: ok
      threads = 1
      !$ threads = omp_get_max_threads()
      write (output_unit, '(a,i0,a)') "egw-bench --bem: bem_flat_curve, p/E* 1e-6..1e-2, " &
         & //"5 loads a decade, tolerance 1e-10 rms, ", threads, " threads"
      do s = 1, size(sizes)
         write (path, '(a,i0,a)') "out/bench/bem_map_", sizes(s), ".txt"
         call read_map(trim(path), h, pixel, ok)
         if (.not. ok) then
            write (output_unit, '(a)') "  "//trim(path)//" missing: run tools/bench/" &
               & //"bem_contactmechanics_time.py first"
            cycle
         end if
         t0 = wall()
         call bem_flat_curve(h, pixel, 1.0_dp, 1.0e-6_dp, 1.0e-2_dp, 5, opt, u, p, area, k, err)
         seconds = wall() - t0
         if (allocated(err)) then
            write (output_unit, '(a)') "  error: "//err%message
            cycle
         end if
         write (output_unit, '(a,i0,a,i0,a,i0,a,f9.3,a)') "  bem_flat_curve ", sizes(s), &
            & "^2 (", size(u), " loads, ", threads, " threads): ", seconds, " s"
         do i = 1, size(u), 5
            write (output_unit, '(4x,a,es10.3,a,es13.6,a,es10.3,a,es10.3)') "p/E* = ", p(i), &
               & "  u = ", u(i), "  area = ", area(i), "  stiffness = ", k(i)
         end do
      end do
   end subroutine run_bem

   subroutine read_map(path, h, pixel, ok)
      character(len=*), intent(in) :: path
      real(dp), allocatable, intent(out) :: h(:, :)
      real(dp), intent(out) :: pixel
      logical, intent(out) :: ok
      integer :: unit, stat, nx, ny, i
      ok = .false.
      open (newunit=unit, file=path, status="old", action="read", iostat=stat)
      if (stat /= 0) return
      read (unit, *, iostat=stat) nx, ny, pixel
      if (stat /= 0) return
      allocate (h(nx, ny))
      do i = 1, nx
         read (unit, *, iostat=stat) h(i, :)
         if (stat /= 0) return
      end do
      close (unit)
      ok = .true.
   end subroutine read_map

end module bench_bem
